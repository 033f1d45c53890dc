/* avx2.h: helpers of the hand-written AVX2 paths (dispatch.h's RG_AVX2_PATHS): an 8x8
 * transpose, for records of eight floats in and out of eight lanes; pairs (x, y) at eight
 * addresses in and out of lanes; the fat-box test of eight bodies.  Include only
 * where RG_AVX2_PATHS is 1; every function is for callers built with target("avx2"). */
#ifndef RG_AVX2_H
#define RG_AVX2_H

#include <immintrin.h>

#include "state.h"

#define AVX2_FN __attribute__((target("avx2")))
#define AVX2_INLINE __attribute__((target("avx2"), always_inline)) static inline

/* The 8x8 transpose of rows r[0..8): afterwards r[j] holds what was element j of each row, in
 * lanes 0..7 (it is its own inverse). */
AVX2_INLINE void avx2_transpose8(__m256 *r)
{
    __m256 t0 = _mm256_unpacklo_ps(r[0], r[1]), t1 = _mm256_unpackhi_ps(r[0], r[1]);
    __m256 t2 = _mm256_unpacklo_ps(r[2], r[3]), t3 = _mm256_unpackhi_ps(r[2], r[3]);
    __m256 t4 = _mm256_unpacklo_ps(r[4], r[5]), t5 = _mm256_unpackhi_ps(r[4], r[5]);
    __m256 t6 = _mm256_unpacklo_ps(r[6], r[7]), t7 = _mm256_unpackhi_ps(r[6], r[7]);
    __m256 u0 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(1, 0, 1, 0)),
           u1 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2));
    __m256 u2 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0)),
           u3 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(3, 2, 3, 2));
    __m256 u4 = _mm256_shuffle_ps(t4, t6, _MM_SHUFFLE(1, 0, 1, 0)),
           u5 = _mm256_shuffle_ps(t4, t6, _MM_SHUFFLE(3, 2, 3, 2));
    __m256 u6 = _mm256_shuffle_ps(t5, t7, _MM_SHUFFLE(1, 0, 1, 0)),
           u7 = _mm256_shuffle_ps(t5, t7, _MM_SHUFFLE(3, 2, 3, 2));
    r[0] = _mm256_permute2f128_ps(u0, u4, 0x20);
    r[1] = _mm256_permute2f128_ps(u1, u5, 0x20);
    r[2] = _mm256_permute2f128_ps(u2, u6, 0x20);
    r[3] = _mm256_permute2f128_ps(u3, u7, 0x20);
    r[4] = _mm256_permute2f128_ps(u0, u4, 0x31);
    r[5] = _mm256_permute2f128_ps(u1, u5, 0x31);
    r[6] = _mm256_permute2f128_ps(u2, u6, 0x31);
    r[7] = _mm256_permute2f128_ps(u3, u7, 0x31);
}

/* Whether each of eight boxes (lanes of lx, ly, ux, uy) left its broadphase entry e[slot[l]]'s
 * fat box or the entry is marked moved: bit l set where !pairs_inside (pairs.h), the same
 * comparisons. */
AVX2_INLINE uint32_t avx2_outside8(const bp_entry *e, const int32_t *slot, __m256 lx, __m256 ly, __m256 ux, __m256 uy)
{
    __m256 f[8];
    uint32_t moved = 0;
    for (int l = 0; l < 8; l++) {
        const bp_entry *el = &e[slot[l]];
        f[l] = _mm256_castps128_ps256(_mm_loadu_ps(&el->lx)); /* lx, ly, ux, uy */
        moved |= (uint32_t)(el->moved != 0) << l;
    }
    avx2_transpose8(f);
    __m256 inside =
        _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(lx, f[0], _CMP_GE_OQ), _mm256_cmp_ps(ly, f[1], _CMP_GE_OQ)),
                      _mm256_and_ps(_mm256_cmp_ps(ux, f[2], _CMP_LE_OQ), _mm256_cmp_ps(uy, f[3], _CMP_LE_OQ)));
    return (~(uint32_t)_mm256_movemask_ps(inside) & 0xFFu) | moved;
}

/* The pairs (x, y) at p[l], l = 0..7, as eight x and eight y. */
AVX2_INLINE void avx2_pairs_at(const float *const *p, __m256 *x, __m256 *y)
{
    __m128 p01 = _mm_loadl_pi(_mm_setzero_ps(), (const __m64 *)(const void *)p[0]);
    p01 = _mm_loadh_pi(p01, (const __m64 *)(const void *)p[1]);
    __m128 p23 = _mm_loadl_pi(_mm_setzero_ps(), (const __m64 *)(const void *)p[2]);
    p23 = _mm_loadh_pi(p23, (const __m64 *)(const void *)p[3]);
    __m128 p45 = _mm_loadl_pi(_mm_setzero_ps(), (const __m64 *)(const void *)p[4]);
    p45 = _mm_loadh_pi(p45, (const __m64 *)(const void *)p[5]);
    __m128 p67 = _mm_loadl_pi(_mm_setzero_ps(), (const __m64 *)(const void *)p[6]);
    p67 = _mm_loadh_pi(p67, (const __m64 *)(const void *)p[7]);
    /* (x0 y0 x1 y1 | x4 y4 x5 y5) and (x2 y2 x3 y3 | x6 y6 x7 y7) */
    __m256 lo = _mm256_insertf128_ps(_mm256_castps128_ps256(p01), p45, 1);
    __m256 hi = _mm256_insertf128_ps(_mm256_castps128_ps256(p23), p67, 1);
    *x = _mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(2, 0, 2, 0));
    *y = _mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(3, 1, 3, 1));
}

/* And back: eight x and eight y stored as the pairs at p[l], lane 0 first (callers compute
 * every address before the stores, which may alias what they were computed from). */
AVX2_INLINE void avx2_pairs_put(float *const *p, __m256 x, __m256 y)
{
    __m256 lo = _mm256_unpacklo_ps(x, y), hi = _mm256_unpackhi_ps(x, y);
    __m128 p01 = _mm256_castps256_ps128(lo), p45 = _mm256_extractf128_ps(lo, 1);
    __m128 p23 = _mm256_castps256_ps128(hi), p67 = _mm256_extractf128_ps(hi, 1);
    _mm_storel_pi((__m64 *)(void *)p[0], p01);
    _mm_storeh_pi((__m64 *)(void *)p[1], p01);
    _mm_storel_pi((__m64 *)(void *)p[2], p23);
    _mm_storeh_pi((__m64 *)(void *)p[3], p23);
    _mm_storel_pi((__m64 *)(void *)p[4], p45);
    _mm_storeh_pi((__m64 *)(void *)p[5], p45);
    _mm_storel_pi((__m64 *)(void *)p[6], p67);
    _mm_storeh_pi((__m64 *)(void *)p[7], p67);
}

/* Bits 0..7 of m as bytes 0 or 1 at out[0..8). */
static inline void avx2_bytes8(uint8_t *out, uint32_t m)
{
    for (int l = 0; l < 8; l++) out[l] = (uint8_t)((m >> l) & 1u);
}

#endif
