/* keyed.c: the keyed hash of keyed.h: NH over chunks, a polynomial over their sums. */
#include <string.h>

#include "keyed.h"

/* splitmix64 (Steele, Lea, Flood 2014): 64 bits a call from a counter. */
static uint64_t keyed_next(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

void keyed_key_init(keyed_key *k, uint64_t seed)
{
    uint64_t s = seed;
    for (int t = 0; t < 2; t++) {
        for (int i = 0; i < 2 * KEYED_WORDS; i += 2) {
            uint64_t z = keyed_next(&s);
            k->nh[t][i] = (uint32_t)z;
            k->nh[t][i + 1] = (uint32_t)(z >> 32);
        }
        do k->r[t] = keyed_next(&s) >> 3; /* 61 bits */
        while (k->r[t] < 2 || k->r[t] >= KEYED_P);
    }
}

uint64_t keyed_mulmod(uint64_t a, uint64_t b)
{
    /* a = a1 2^32 + a0, b likewise (a1, b1 < 2^29): with 2^61 = 1, 2^64 = 8 modulo p, and the
     * middle product m = mh 2^29 + ml (ml < 2^29) giving m 2^32 = mh + ml 2^32 */
    uint64_t a0 = a & 0xFFFFFFFFu, a1 = a >> 32, b0 = b & 0xFFFFFFFFu, b1 = b >> 32;
    uint64_t hi = a1 * b1, mid = a1 * b0 + a0 * b1, lo = a0 * b0;
    uint64_t s = (hi << 3) + (mid >> 29) + ((mid & ((1u << 29) - 1)) << 32) + (lo & KEYED_P) + (lo >> 61);
    s = (s & KEYED_P) + (s >> 61); /* the five terms sum below 2^63; folded, below 2^61 + 4 */
    return s >= KEYED_P ? s - KEYED_P : s;
}

static void keyed_absorb(uint64_t *poly, uint64_t r, uint64_t e)
{
    uint64_t x = keyed_mulmod(*poly, r) + e; /* e < 2^32 */
    *poly = x >= KEYED_P ? x - KEYED_P : x;
}

void keyed_nh_scalar(uint64_t nh[2], const uint8_t *p, size_t words, const uint32_t *k0, const uint32_t *k1)
{
    uint64_t a = nh[0], b = nh[1];
    for (size_t i = 0; i < words; i++) {
        uint64_t w;
        memcpy(&w, p + 8 * i, 8);
        uint32_t lo = (uint32_t)w, hi = (uint32_t)(w >> 32);
        a += (uint64_t)(uint32_t)(lo + k0[2 * i]) * (uint32_t)(hi + k0[2 * i + 1]);
        b += (uint64_t)(uint32_t)(lo + k1[2 * i]) * (uint32_t)(hi + k1[2 * i + 1]);
    }
    nh[0] = a;
    nh[1] = b;
}

/* On x86-64 (little-endian: a word's low half is its first four bytes, as the scalar loop
 * reads it) the sums also run four or eight words to a register, picked per call. */
#if KEYED_VECTOR
#include <immintrin.h>

__attribute__((target("avx2"))) void keyed_nh_avx2(uint64_t nh[2], const uint8_t *p, size_t words,
                                                          const uint32_t *k0, const uint32_t *k1)
{
    __m256i a = _mm256_setzero_si256(), b = _mm256_setzero_si256();
    size_t i = 0;
    for (; i + 4 <= words; i += 4) {
        __m256i m = _mm256_loadu_si256((const __m256i *)(const void *)(p + 8 * i));
        __m256i t = _mm256_add_epi32(m, _mm256_loadu_si256((const __m256i *)(const void *)(k0 + 2 * i)));
        __m256i u = _mm256_add_epi32(m, _mm256_loadu_si256((const __m256i *)(const void *)(k1 + 2 * i)));
        a = _mm256_add_epi64(a, _mm256_mul_epu32(t, _mm256_srli_epi64(t, 32)));
        b = _mm256_add_epi64(b, _mm256_mul_epu32(u, _mm256_srli_epi64(u, 32)));
    }
    uint64_t la[4], lb[4];
    _mm256_storeu_si256((__m256i *)(void *)la, a);
    _mm256_storeu_si256((__m256i *)(void *)lb, b);
    nh[0] += la[0] + la[1] + la[2] + la[3];
    nh[1] += lb[0] + lb[1] + lb[2] + lb[3];
    keyed_nh_scalar(nh, p + 8 * i, words - i, k0 + 2 * i, k1 + 2 * i);
}

__attribute__((target("avx512f"))) void keyed_nh_avx512(uint64_t nh[2], const uint8_t *p, size_t words,
                                                              const uint32_t *k0, const uint32_t *k1)
{
    /* two registers a tag, sixteen words a turn: the loads of one half overlap the other's */
    __m512i a = _mm512_setzero_si512(), b = _mm512_setzero_si512();
    __m512i c = _mm512_setzero_si512(), d = _mm512_setzero_si512();
    size_t i = 0;
#define KEYED_NH8(acc0, acc1, at)                                                                                 \
    {                                                                                                             \
        __m512i m = _mm512_loadu_si512((const void *)(p + 8 * (at)));                                             \
        __m512i t = _mm512_add_epi32(m, _mm512_loadu_si512((const void *)(k0 + 2 * (at))));                       \
        __m512i u = _mm512_add_epi32(m, _mm512_loadu_si512((const void *)(k1 + 2 * (at))));                       \
        acc0 = _mm512_add_epi64(acc0, _mm512_mul_epu32(t, _mm512_srli_epi64(t, 32)));                             \
        acc1 = _mm512_add_epi64(acc1, _mm512_mul_epu32(u, _mm512_srli_epi64(u, 32)));                             \
    }
    for (; i + 16 <= words; i += 16) {
        KEYED_NH8(a, b, i)
        KEYED_NH8(c, d, i + 8)
    }
    if (i + 8 <= words) {
        KEYED_NH8(a, b, i)
        i += 8;
    }
#undef KEYED_NH8
    uint64_t la[8], lb[8];
    _mm512_storeu_si512((void *)la, _mm512_add_epi64(a, c));
    _mm512_storeu_si512((void *)lb, _mm512_add_epi64(b, d));
    for (int k = 0; k < 8; k++) {
        nh[0] += la[k];
        nh[1] += lb[k];
    }
    keyed_nh_scalar(nh, p + 8 * i, words - i, k0 + 2 * i, k1 + 2 * i);
}
#endif

static void keyed_nh(uint64_t nh[2], const uint8_t *p, size_t words, const uint32_t *k0, const uint32_t *k1)
{
#if KEYED_VECTOR
    if (words >= 8 && __builtin_cpu_supports("avx512f")) {
        keyed_nh_avx512(nh, p, words, k0, k1);
        return;
    }
    if (words >= 4 && __builtin_cpu_supports("avx2")) {
        keyed_nh_avx2(nh, p, words, k0, k1);
        return;
    }
#endif
    keyed_nh_scalar(nh, p, words, k0, k1);
}

void keyed_init(keyed_hasher *h, const keyed_key *k)
{
    memset(h, 0, sizeof *h);
    h->key = k;
}

/* The chunk's sums into the polynomials, each as its two halves. */
static void keyed_chunk_end(keyed_hasher *h)
{
    for (int t = 0; t < 2; t++) {
        keyed_absorb(&h->poly[t], h->key->r[t], h->nh[t] & 0xFFFFFFFFu);
        keyed_absorb(&h->poly[t], h->key->r[t], h->nh[t] >> 32);
        h->nh[t] = 0;
    }
    h->word = 0;
}

static void keyed_words(keyed_hasher *h, const uint8_t *p, size_t words)
{
    while (words > 0) {
        size_t take = KEYED_WORDS - h->word < words ? KEYED_WORDS - h->word : words;
        keyed_nh(h->nh, p, take, h->key->nh[0] + 2 * (size_t)h->word, h->key->nh[1] + 2 * (size_t)h->word);
        h->word += (uint32_t)take;
        p += 8 * take;
        words -= take;
        if (h->word == KEYED_WORDS) keyed_chunk_end(h);
    }
}

void keyed_bytes(keyed_hasher *h, const void *data, size_t n)
{
    const uint8_t *p = data;
    h->length += n;
    if (h->npending > 0) {
        size_t take = 8 - h->npending < n ? 8 - h->npending : n;
        memcpy(h->pending + h->npending, p, take);
        h->npending += (uint32_t)take;
        p += take;
        n -= take;
        if (h->npending < 8) return;
        keyed_words(h, h->pending, 1);
        h->npending = 0;
    }
    keyed_words(h, p, n / 8);
    memcpy(h->pending, p + n - n % 8, n % 8);
    h->npending = (uint32_t)(n % 8);
}

void keyed_final(keyed_hasher *h, uint64_t tag[2])
{
    if (h->npending > 0) { /* the last word zero-padded: strings of one length pad alike */
        memset(h->pending + h->npending, 0, 8 - h->npending);
        keyed_words(h, h->pending, 1);
        h->npending = 0;
    }
    if (h->word > 0) keyed_chunk_end(h);
    for (int t = 0; t < 2; t++) {
        keyed_absorb(&h->poly[t], h->key->r[t], h->length & 0xFFFFFFFFu);
        keyed_absorb(&h->poly[t], h->key->r[t], h->length >> 32);
        tag[t] = h->poly[t];
    }
}
