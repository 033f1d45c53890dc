/* snap_hash.c: the snapshot format's hash function (see snap_hash.h). */
#include <string.h>

#include "snap_hash.h"
#include "snap_le.h"

#define SNAP_HASH_K1 0x9E3779B97F4A7C15ull
#define SNAP_HASH_K2 0xC2B2AE3D27D4EB4Full

void snap_hash_init(snap_hasher *h)
{
    for (int k = 0; k < SNAP_LANES; k++) h->lane[k] = 0x243F6A8885A308D3ull + (uint64_t)k * SNAP_HASH_K2;
    h->npending = 0;
    h->length = 0;
}

static inline uint64_t snap_hash_lane(uint64_t lane, uint64_t w)
{
    lane = (lane ^ w) * SNAP_HASH_K1;
    return lane ^ (lane >> 29);
}

#define SNAP_HASH_BLOCK (8 * SNAP_LANES)
typedef char snap_hash_lanes_in_eights[SNAP_LANES % 8 == 0 ? 1 : -1]; /* snap_hash_blocks takes eight at a time */

/* On x86-64 with GCC or clang the blocks also run with the lanes eight to an AVX-512
 * register (one multiply, VPMULLQ, for eight), picked per call from the CPU: the same
 * operations on each lane, so the same hash.  RG_NO_DISPATCH builds the scalar loop alone. */
#if defined(__GNUC__) && defined(__x86_64__) && !defined(RG_NO_DISPATCH)
#define SNAP_HASH_AVX512 1
#include <immintrin.h>
#else
#define SNAP_HASH_AVX512 0
#endif

#if SNAP_HASH_AVX512
typedef char snap_hash_four_registers[SNAP_LANES == 32 ? 1 : -1];
__attribute__((target("avx512f,avx512dq"))) static void snap_hash_blocks_avx512(snap_hasher *h, const uint8_t *p, size_t n)
{
    /* four registers, four chains that do not wait on each other: register r holds lanes
     * 8r .. 8r + 7, the block's words 8r .. 8r + 7 */
    __m512i l0 = _mm512_loadu_si512((const void *)h->lane), l1 = _mm512_loadu_si512((const void *)(h->lane + 8));
    __m512i l2 = _mm512_loadu_si512((const void *)(h->lane + 16)), l3 = _mm512_loadu_si512((const void *)(h->lane + 24));
    const __m512i k1 = _mm512_set1_epi64((long long)SNAP_HASH_K1);
#define SNAP_HASH_LANE8(l, at)                                                                          \
    l = _mm512_mullo_epi64(_mm512_xor_si512(l, _mm512_loadu_si512((const void *)(p + (at)))), k1); \
    l = _mm512_xor_si512(l, _mm512_srli_epi64(l, 29));
    for (; n >= SNAP_HASH_BLOCK; p += SNAP_HASH_BLOCK, n -= SNAP_HASH_BLOCK) {
        SNAP_HASH_LANE8(l0, 0)
        SNAP_HASH_LANE8(l1, 64)
        SNAP_HASH_LANE8(l2, 128)
        SNAP_HASH_LANE8(l3, 192)
    }
#undef SNAP_HASH_LANE8
    _mm512_storeu_si512((void *)h->lane, l0);
    _mm512_storeu_si512((void *)(h->lane + 8), l1);
    _mm512_storeu_si512((void *)(h->lane + 16), l2);
    _mm512_storeu_si512((void *)(h->lane + 24), l3);
}
#endif

/* Whole blocks: one word into each lane.  Eight lanes in eight scalars (one 64-bit
 * multiply a word; GCC vectorised a loop over the lanes into SSE2's 32-bit multiplies,
 * three a word), in a pass over a run of blocks (a cache line of each): four passes over
 * each run of SNAP_HASH_RUN blocks, small enough to stay in the first-level cache between them. */
#define SNAP_HASH_RUN 32 /* blocks: 8 KB */
static void snap_hash_lanes8(uint64_t *lane, const uint8_t *p, size_t blocks)
{
    uint64_t l0 = lane[0], l1 = lane[1], l2 = lane[2], l3 = lane[3];
    uint64_t l4 = lane[4], l5 = lane[5], l6 = lane[6], l7 = lane[7];
    for (; blocks > 0; blocks--, p += SNAP_HASH_BLOCK) {
        l0 = snap_hash_lane(l0, snap_get64(p));
        l1 = snap_hash_lane(l1, snap_get64(p + 8));
        l2 = snap_hash_lane(l2, snap_get64(p + 16));
        l3 = snap_hash_lane(l3, snap_get64(p + 24));
        l4 = snap_hash_lane(l4, snap_get64(p + 32));
        l5 = snap_hash_lane(l5, snap_get64(p + 40));
        l6 = snap_hash_lane(l6, snap_get64(p + 48));
        l7 = snap_hash_lane(l7, snap_get64(p + 56));
    }
    lane[0] = l0, lane[1] = l1, lane[2] = l2, lane[3] = l3;
    lane[4] = l4, lane[5] = l5, lane[6] = l6, lane[7] = l7;
}

static void snap_hash_blocks(snap_hasher *h, const uint8_t *p, size_t n)
{
#if SNAP_HASH_AVX512
    if (n >= SNAP_HASH_BLOCK && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq")) {
        snap_hash_blocks_avx512(h, p, n);
        return;
    }
#endif
    for (size_t blocks = n / SNAP_HASH_BLOCK, run; blocks > 0; blocks -= run, p += run * SNAP_HASH_BLOCK) {
        run = blocks < SNAP_HASH_RUN ? blocks : SNAP_HASH_RUN;
        for (int g = 0; g < SNAP_LANES; g += 8) snap_hash_lanes8(h->lane + g, p + 8 * g, run);
    }
}

void snap_hash_bytes(snap_hasher *h, const void *data, size_t n)
{
    const uint8_t *p = data;
    h->length += n;
    if (h->npending > 0) {
        size_t take = SNAP_HASH_BLOCK - h->npending < n ? SNAP_HASH_BLOCK - h->npending : n;
        memcpy(h->pending + h->npending, p, take);
        h->npending += take;
        p += take;
        n -= take;
        if (h->npending < SNAP_HASH_BLOCK) return;
        snap_hash_blocks(h, h->pending, SNAP_HASH_BLOCK);
        h->npending = 0;
    }
    size_t whole = n - n % SNAP_HASH_BLOCK;
    snap_hash_blocks(h, p, whole);
    memcpy(h->pending, p + whole, n - whole);
    h->npending = n - whole;
}

static inline uint64_t snap_hash_mix(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

uint64_t snap_hash_final(snap_hasher *h)
{
    if (h->npending > 0) {
        memset(h->pending + h->npending, 0, SNAP_HASH_BLOCK - h->npending);
        snap_hash_blocks(h, h->pending, SNAP_HASH_BLOCK);
        h->npending = 0;
    }
    uint64_t r = snap_hash_mix(h->length * SNAP_HASH_K2);
    for (int k = 0; k < SNAP_LANES; k++) r = snap_hash_mix(r ^ snap_hash_mix(h->lane[k] + (uint64_t)k * SNAP_HASH_K1));
    return r;
}

uint64_t snap_hash(const void *p, size_t n)
{
    snap_hasher h;
    snap_hash_init(&h);
    snap_hash_bytes(&h, p, n);
    return snap_hash_final(&h);
}
