/* avx2.h: helpers of the hand-written AVX2 paths (dispatch.h's RG_AVX2_PATHS): an 8x8
 * transpose, for records of eight floats in and out of eight lanes, and the fat-box test of
 * eight bodies.  Include only where RG_AVX2_PATHS is 1; every function is for callers built
 * with target("avx2"). */
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
    __m256 u0 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(1, 0, 1, 0)), u1 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2));
    __m256 u2 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0)), u3 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(3, 2, 3, 2));
    __m256 u4 = _mm256_shuffle_ps(t4, t6, _MM_SHUFFLE(1, 0, 1, 0)), u5 = _mm256_shuffle_ps(t4, t6, _MM_SHUFFLE(3, 2, 3, 2));
    __m256 u6 = _mm256_shuffle_ps(t5, t7, _MM_SHUFFLE(1, 0, 1, 0)), u7 = _mm256_shuffle_ps(t5, t7, _MM_SHUFFLE(3, 2, 3, 2));
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
    __m256 inside = _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(lx, f[0], _CMP_GE_OQ), _mm256_cmp_ps(ly, f[1], _CMP_GE_OQ)),
                                  _mm256_and_ps(_mm256_cmp_ps(ux, f[2], _CMP_LE_OQ), _mm256_cmp_ps(uy, f[3], _CMP_LE_OQ)));
    return (~(uint32_t)_mm256_movemask_ps(inside) & 0xFFu) | moved;
}

/* Bits 0..7 of m as bytes 0 or 1 at out[0..8). */
static inline void avx2_bytes8(uint8_t *out, uint32_t m)
{
    for (int l = 0; l < 8; l++) out[l] = (uint8_t)((m >> l) & 1u);
}

#endif
