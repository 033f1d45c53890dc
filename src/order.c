/* order.c: the solving order (see order.h). */
#include <string.h>

#include "dispatch.h"
#include "order.h"
#include "vec2.h"
#if RG_AVX2_PATHS
#include "avx2.h"
#endif

/* LSD radix sort of n (key, value) pairs by 16-bit key, two passes of 8 bits; stable. */
static void order_radix_sort16(uint16_t *key, int32_t *val, uint16_t *tkey, int32_t *tval, int32_t n)
{
    for (int shift = 0; shift < 16; shift += 8) {
        int32_t count[257];
        memset(count, 0, sizeof count);
        for (int32_t i = 0; i < n; i++) count[((key[i] >> shift) & 255) + 1]++;
        for (int d = 0; d < 256; d++) count[d + 1] += count[d];
        for (int32_t i = 0; i < n; i++) {
            int32_t at = count[(key[i] >> shift) & 255]++;
            tkey[at] = key[i];
            tval[at] = val[i];
        }
        uint16_t *kt = key;
        key = tkey;
        tkey = kt;
        int32_t *vt = val;
        val = tval;
        tval = vt;
    }
}

/* (order.h) */
int order_resort(const uint16_t *key, int32_t *ord, int32_t n)
{
    int64_t budget = 4 * (int64_t)n + 64;
    uint32_t mk = 0; /* the prefix's last row (its largest) and its key */
    int32_t mv = -1;
    for (int32_t i = 0; i < n; i++) {
        int32_t v = ord[i];
        if (v < 0 || v >= n) return 0;
        uint32_t kv = key[v];
        if (mk < kv || (mk == kv && mv < v)) { /* in place: the common case */
            mk = kv;
            mv = v;
            continue;
        }
        if (mk == kv && mv == v) return 0; /* a row met twice */
        int32_t j = i;
        while (j > 0 && (key[ord[j - 1]] > kv || (key[ord[j - 1]] == kv && ord[j - 1] > v))) {
            ord[j] = ord[j - 1];
            j--;
            if (--budget < 0) return 0;
        }
        /* the prefix is strictly increasing in (key, row): a row met twice sits at j - 1 */
        if (j > 0 && ord[j - 1] == v) return 0;
        ord[j] = v;
    }
    return 1;
}

/* Folds of ORDER_FOLDS heights side by side: the one fold of rg_min over all rows is a
 * chain of dependent compares. */
#define ORDER_FOLDS 8

/* The least and the greatest of h[0..n), folded ORDER_FOLDS side by side from RG_HUGE and
 * -RG_HUGE with rg_min and rg_max: the one-by-one fold's two numbers, since the heights are
 * finite (contact points of bodies within RG_MAX_COORD) and the folds are exact, but for a
 * zero's sign, which the keys below do not see ((+-0 - hmin) and (hmax - hmin) are the same
 * numbers, or zeros that quantize to key 0). */
static void order_span(const rg_real *h, int32_t n, rg_real *out_min, rg_real *out_max)
{
    rg_real lo[ORDER_FOLDS], hi[ORDER_FOLDS];
    for (int u = 0; u < ORDER_FOLDS; u++) {
        lo[u] = RG_HUGE;
        hi[u] = -RG_HUGE;
    }
    int32_t k = 0;
    for (; n - k >= ORDER_FOLDS; k += ORDER_FOLDS)
        for (int u = 0; u < ORDER_FOLDS; u++) {
            lo[u] = rg_min(lo[u], h[k + u]);
            hi[u] = rg_max(hi[u], h[k + u]);
        }
    for (; k < n; k++) {
        lo[0] = rg_min(lo[0], h[k]);
        hi[0] = rg_max(hi[0], h[k]);
    }
    for (int u = 1; u < ORDER_FOLDS; u++) {
        lo[0] = rg_min(lo[0], lo[u]);
        hi[0] = rg_max(hi[0], hi[u]);
    }
    *out_min = lo[0];
    *out_max = hi[0];
}

/* The rows' sort keys: each height's place in [hmin, hmax], scaled by `scale` to 16 bits (0
 * where that is not a number in [0, 65535]); eight at a time where the CPU has AVX2, with the
 * same float operations (a truncation of a number in range), so the same keys. */
#if RG_AVX2_PATHS
AVX2_FN static int32_t order_keys8(const float *h, int32_t n, float hmin, float scale, uint16_t *key)
{
    const __m256 lo = _mm256_set1_ps(hmin), s = _mm256_set1_ps(scale);
    const __m256 zero = _mm256_setzero_ps(), top = _mm256_set1_ps(65535.0f);
    int32_t k = 0;
    for (; n - k >= 8; k += 8) {
        __m256 q = _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(h + k), lo), s);
        __m256 in = _mm256_and_ps(_mm256_cmp_ps(q, zero, _CMP_GE_OQ), _mm256_cmp_ps(q, top, _CMP_LE_OQ));
        __m256i v = _mm256_and_si256(_mm256_cvttps_epi32(q), _mm256_castps_si256(in));
        __m128i p = _mm_packus_epi32(_mm256_castsi256_si128(v), _mm256_extracti128_si256(v, 1));
        _mm_storeu_si128((__m128i *)(void *)(key + k), p);
    }
    return k;
}
#endif

static void order_keys(const rg_real *h, int32_t n, rg_real hmin, rg_real scale, uint16_t *key)
{
    int32_t k = 0;
#if RG_AVX2_PATHS
    if (__builtin_cpu_supports("avx2")) k = order_keys8(h, n, hmin, scale, key);
#endif
    for (; k < n; k++) {
        rg_real q = (h[k] - hmin) * scale;
        key[k] = (uint16_t)(q >= 0 && q <= RG_R(65535) ? q : 0);
    }
}

/* (order.h) */
void order_rows(solver_rows *rows, int32_t nc, int down)
{
    if (down) {
        const rg_real *h = rows->hgt;
        rg_real hmin, hmax;
        order_span(h, nc, &hmin, &hmax);
        rg_real scale = hmax > hmin ? RG_R(65535) / (hmax - hmin) : 0;
        if (!rg_finite(scale)) scale = 0;
        order_keys(h, nc, hmin, scale, rows->key);
        /* the last step's order, repaired, when it held as many rows (a pile at rest keeps
         * its rows and nearly their order); else sorted afresh */
        if (!(rows->nord == nc && order_resort(rows->key, rows->ord, nc))) {
            for (int32_t k = 0; k < nc; k++) rows->ord[k] = k;
            order_radix_sort16(rows->key, rows->ord, rows->tkey, rows->tord, nc);
        }
        rows->nord = nc;
    } else {
        for (int32_t k = 0; k < nc; k++) rows->ord[k] = k;
        rows->nord = 0;
    }
}
