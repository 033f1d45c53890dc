/* broadphase.c: the hierarchical hashed grid (see broadphase.h). */
#include <math.h>
#include <string.h>

#include "broadphase.h"
#include "dispatch.h"
#include "vec2.h"

/* Cell coordinates are clamped to [-LIM, LIM): the clamp is monotone, so two boxes in
 * neighbouring cells stay in neighbouring (or the same) cells, only more crowded. */
#define BP_LIM 268435456 /* 2^28 */
#define BP_MIN_BUCKET_BITS 6

/* Cell sides 2^L m, their inverses, and the sides less 1/256 (a box fits a level when its
 * extent is at most that), L = BP_LEVEL_MIN .. BP_LEVEL_MAX: all exact in float (a power of
 * two times 255/256 has 8 significant bits), so the tables hold the very values the
 * arithmetic on them would give; the tables must list BP_LEVELS entries. */
#define BP_FIT(c) ((c) * 0.99609375)
static const rg_real level_cells[BP_LEVELS] = {
    0x1p-10, 0x1p-9, 0x1p-8, 0x1p-7, 0x1p-6, 0x1p-5, 0x1p-4, 0x1p-3,
    0x1p-2, 0x1p-1, 0x1p0, 0x1p1, 0x1p2, 0x1p3, 0x1p4, 0x1p5,
    0x1p6, 0x1p7, 0x1p8, 0x1p9, 0x1p10, 0x1p11, 0x1p12, 0x1p13,
    0x1p14, 0x1p15, 0x1p16, 0x1p17, 0x1p18, 0x1p19, 0x1p20,
};
static const rg_real level_invs[BP_LEVELS] = {
    0x1p10, 0x1p9, 0x1p8, 0x1p7, 0x1p6, 0x1p5, 0x1p4, 0x1p3,
    0x1p2, 0x1p1, 0x1p0, 0x1p-1, 0x1p-2, 0x1p-3, 0x1p-4, 0x1p-5,
    0x1p-6, 0x1p-7, 0x1p-8, 0x1p-9, 0x1p-10, 0x1p-11, 0x1p-12, 0x1p-13,
    0x1p-14, 0x1p-15, 0x1p-16, 0x1p-17, 0x1p-18, 0x1p-19, 0x1p-20,
};
static const rg_real level_fits[BP_LEVELS] = {
    BP_FIT(0x1p-10), BP_FIT(0x1p-9), BP_FIT(0x1p-8), BP_FIT(0x1p-7), BP_FIT(0x1p-6), BP_FIT(0x1p-5),
    BP_FIT(0x1p-4), BP_FIT(0x1p-3), BP_FIT(0x1p-2), BP_FIT(0x1p-1), BP_FIT(0x1p0), BP_FIT(0x1p1),
    BP_FIT(0x1p2), BP_FIT(0x1p3), BP_FIT(0x1p4), BP_FIT(0x1p5), BP_FIT(0x1p6), BP_FIT(0x1p7),
    BP_FIT(0x1p8), BP_FIT(0x1p9), BP_FIT(0x1p10), BP_FIT(0x1p11), BP_FIT(0x1p12), BP_FIT(0x1p13),
    BP_FIT(0x1p14), BP_FIT(0x1p15), BP_FIT(0x1p16), BP_FIT(0x1p17), BP_FIT(0x1p18), BP_FIT(0x1p19),
    BP_FIT(0x1p20),
};
static inline rg_real level_cell(int li) { return level_cells[li]; }
static inline rg_real level_inv(int li) { return level_invs[li]; }
static inline rg_real level_fit(int li) { return level_fits[li]; }

/* floor(v * inv) clamped to [-LIM, LIM - 1]; inv is a power of two, so v * inv is exact. */
static inline int64_t cell_coord(rg_real v, rg_real inv)
{
    rg_real s = v * inv;
    if (!(s > -(rg_real)BP_LIM)) return -BP_LIM; /* also NaN */
    if (s >= (rg_real)BP_LIM) return BP_LIM - 1;
    /* floor without a library call: truncation, less one below zero off an integer (exact:
     * |s| < 2^28, and a real that large is an integer, so i converts back exactly) */
    int64_t i = (int64_t)s;
    return i - (s < (rg_real)i);
}

static inline uint64_t cell_key(int li, int64_t cx, int64_t cy)
{
    return ((uint64_t)li << 58) | ((uint64_t)(cx + BP_LIM) << 29) | (uint64_t)(cy + BP_LIM);
}

static inline uint32_t bucket_of(const broadphase *bp, uint64_t key)
{
    return (uint32_t)((key * 0x9E3779B97F4A7C15ull) >> (64 - bp->bucket_bits));
}

/* The finest level whose cell exceeds the box by a 1/256 margin (which absorbs the rounding
 * of the box's width), or BP_HUGE. */
static inline int level_of(rg_real lx, rg_real ly, rg_real ux, rg_real uy)
{
    rg_real w = ux - lx, h = uy - ly, top = level_fit(BP_LEVELS - 1);
    if (!(w <= top && h <= top)) return BP_HUGE; /* also NaN */
    rg_real ext = rg_max(w, h);
    if (!(ext > 0)) return 0;
    /* e with 2^(e-1) <= ext < 2^e (frexp's), from the exponent bits; a subnormal ext is
     * below every level */
#ifdef RG_DOUBLE
    uint64_t bits;
    memcpy(&bits, &ext, 8);
    int biased = (int)(bits >> 52);
    int e = biased - 1022;
#else
    uint32_t bits;
    memcpy(&bits, &ext, 4);
    int biased = (int)(bits >> 23);
    int e = biased - 126;
#endif
    if (biased == 0) return 0;
    int li = e - BP_LEVEL_MIN;
    if (li < 0) return 0;
    if (!(ext <= level_fit(li))) li++;
    return li < BP_LEVELS ? li : BP_HUGE;
}

typedef char bp_levels_fit_a_mask[BP_LEVELS <= 32 ? 1 : -1];

/* Counts a member more or less at level li, keeping the mask of occupied levels. */
static void level_count_add(broadphase *bp, int li, int32_t d)
{
    bp->level_count[li] += d;
    if (li == BP_HUGE) return;
    if (bp->level_count[li] > 0)
        bp->levels |= 1u << li;
    else
        bp->levels &= ~(1u << li);
}

/* The member lists of the levels: slot joins or leaves the list of its level (not huge). */
static void level_link(broadphase *bp, int32_t slot)
{
    bp_entry *e = &bp->e[slot];
    if (e->level == BP_HUGE) return;
    e->lprev = -1;
    e->lnext = bp->level_head[e->level];
    if (e->lnext >= 0) bp->e[e->lnext].lprev = slot;
    bp->level_head[e->level] = slot;
}

static void level_unlink(broadphase *bp, int32_t slot)
{
    bp_entry *e = &bp->e[slot];
    if (e->level == BP_HUGE) return;
    if (e->lprev >= 0)
        bp->e[e->lprev].lnext = e->lnext;
    else
        bp->level_head[e->level] = e->lnext;
    if (e->lnext >= 0) bp->e[e->lnext].lprev = e->lprev;
    e->lnext = e->lprev = -1;
}

static void chain_link(broadphase *bp, int32_t slot)
{
    bp_entry *e = &bp->e[slot];
    if (e->level == BP_HUGE) {
        e->next = bp->n_huge;
        e->prev = -1; /* as a restore makes it (a snapshot holds the links) */
        bp->huge[bp->n_huge++] = slot;
        return;
    }
    uint32_t k = bucket_of(bp, e->key);
    e->prev = -1;
    e->next = bp->head[k];
    if (e->next >= 0) bp->e[e->next].prev = slot;
    bp->head[k] = slot;
}

static void chain_unlink(broadphase *bp, int32_t slot)
{
    bp_entry *e = &bp->e[slot];
    if (e->level == BP_HUGE) {
        int32_t i = e->next, last = bp->huge[--bp->n_huge];
        bp->huge[i] = last;
        bp->e[last].next = i;
        return;
    }
    if (e->prev >= 0)
        bp->e[e->prev].next = e->next;
    else
        bp->head[bucket_of(bp, e->key)] = e->next;
    if (e->next >= 0) bp->e[e->next].prev = e->prev;
}

static void set_box(broadphase *bp, int32_t slot, rg_real lx, rg_real ly, rg_real ux, rg_real uy)
{
    bp_entry *e = &bp->e[slot];
    e->lx = lx;
    e->ly = ly;
    e->ux = ux;
    e->uy = uy;
    int li = level_of(lx, ly, ux, uy);
    e->level = (int16_t)li;
    if (li != BP_HUGE) {
        rg_real inv = level_inv(li);
        e->key = cell_key(li, cell_coord(lx, inv), cell_coord(ly, inv));
    } else {
        e->key = 0;
    }
}

/* Room for slots [0, cap): the per-slot arrays grown, their contents kept. */
static rg_status bp_grow_slots(broadphase *bp, const rg_mem *m, int32_t cap)
{
    if (cap <= bp->cap) return RG_OK;
    bp_entry *e = mem_alloc(m, mem_array_size((size_t)cap, sizeof *e));
    int32_t *mem_ = mem_alloc(m, mem_array_size((size_t)cap, sizeof *mem_));
    int32_t *huge = mem_alloc(m, mem_array_size((size_t)cap, sizeof *huge));
    int32_t *moved = mem_alloc(m, mem_array_size((size_t)cap, sizeof *moved));
    int32_t *act = mem_alloc(m, mem_array_size((size_t)cap, sizeof *act));
    if (e == NULL || mem_ == NULL || huge == NULL || moved == NULL || act == NULL) {
        mem_free(m, e, (size_t)cap * sizeof *e);
        mem_free(m, mem_, (size_t)cap * sizeof *mem_);
        mem_free(m, huge, (size_t)cap * sizeof *huge);
        mem_free(m, moved, (size_t)cap * sizeof *moved);
        mem_free(m, act, (size_t)cap * sizeof *act);
        return RG_ERR_OUT_OF_MEMORY;
    }
    if (bp->cap == 0)
        for (int li = 0; li < BP_LEVELS; li++) bp->level_head[li] = -1;
    if (bp->cap > 0) {
        memcpy(e, bp->e, (size_t)bp->cap * sizeof *e);
        memcpy(mem_, bp->members, (size_t)bp->count * sizeof *mem_);
        memcpy(huge, bp->huge, (size_t)bp->n_huge * sizeof *huge);
        memcpy(moved, bp->moved, (size_t)bp->n_moved * sizeof *moved);
        memcpy(act, bp->active, (size_t)bp->n_active * sizeof *act);
    }
    for (int32_t s = bp->cap; s < cap; s++) {
        memset(&e[s], 0, sizeof e[s]);
        e[s].member = -1;
        e[s].next = e[s].prev = -1;
        e[s].lnext = e[s].lprev = -1;
        e[s].apos = -1;
    }
    mem_free(m, bp->e, (size_t)bp->cap * sizeof *bp->e);
    mem_free(m, bp->members, (size_t)bp->cap * sizeof *bp->members);
    mem_free(m, bp->huge, (size_t)bp->cap * sizeof *bp->huge);
    mem_free(m, bp->moved, (size_t)bp->cap * sizeof *bp->moved);
    mem_free(m, bp->active, (size_t)bp->cap * sizeof *bp->active);
    bp->e = e;
    bp->members = mem_;
    bp->huge = huge;
    bp->moved = moved;
    bp->active = act;
    bp->cap = cap;
    return RG_OK;
}

/* The slot capacity that holds `slots`: doubling from 64. */
static int32_t bp_slot_cap(const broadphase *bp, int32_t slots)
{
    int32_t cap = bp->cap;
    if (slots > cap) {
        cap = cap < 64 ? 64 : cap;
        while (cap < slots) cap = cap > (INT32_MAX / 2) ? INT32_MAX : cap * 2;
    }
    return cap;
}

rg_status broadphase_reserve(broadphase *bp, const rg_mem *m, int32_t slots, int32_t members)
{
    int32_t cap = bp_slot_cap(bp, slots);
    int bits = bp->bucket_bits < BP_MIN_BUCKET_BITS ? BP_MIN_BUCKET_BITS : bp->bucket_bits;
    while (((int64_t)1 << bits) < 2 * (int64_t)members) bits++;
    if (cap == bp->cap && bits == bp->bucket_bits) return RG_OK;
    size_t nb = (size_t)1 << bits;
    int32_t *head = NULL;
    if (bits != bp->bucket_bits) {
        head = mem_alloc(m, nb * sizeof *head);
        if (head == NULL) return RG_ERR_OUT_OF_MEMORY;
    }
    if (bp_grow_slots(bp, m, cap) != RG_OK) {
        mem_free(m, head, nb * sizeof *head);
        return RG_ERR_OUT_OF_MEMORY;
    }
    if (head != NULL) {
        mem_free(m, bp->head, ((size_t)1 << bp->bucket_bits) * sizeof *bp->head);
        bp->head = head;
        bp->bucket_bits = bits;
        for (size_t k = 0; k < nb; k++) head[k] = -1;
        /* rechain in member order (deterministic) */
        for (int32_t i = 0; i < bp->count; i++) {
            int32_t s = bp->members[i];
            if (bp->e[s].level != BP_HUGE) chain_link(bp, s);
        }
    }
    return RG_OK;
}

/* ---------------------------------------------------------------- restoring a snapshot */

#if RG_AVX2_PATHS
#include <immintrin.h>

typedef char bp_huge_is_the_level_past_the_last[BP_HUGE == BP_LEVELS ? 1 : -1];

/* floor(v * inv) clamped as cell_coord does it, eight lanes (|v * inv| < 2^28 converts
 * exactly; the lanes past the clamp take its ends). */
__attribute__((target("avx2"))) static inline __m256i bp_coord8(__m256 v, __m256 inv)
{
    __m256 s = _mm256_mul_ps(v, inv);
    __m256i c = _mm256_cvttps_epi32(_mm256_floor_ps(s));
    c = _mm256_blendv_epi8(c, _mm256_set1_epi32(BP_LIM - 1),
                           _mm256_castps_si256(_mm256_cmp_ps(s, _mm256_set1_ps((rg_real)BP_LIM), _CMP_GE_OQ)));
    /* !(s > -LIM), NaN included */
    return _mm256_blendv_epi8(_mm256_set1_epi32(-BP_LIM), c,
                              _mm256_castps_si256(_mm256_cmp_ps(s, _mm256_set1_ps(-(rg_real)BP_LIM), _CMP_GT_OQ)));
}

/* The cell keys of four lanes (cell_key), 0 where huge. */
__attribute__((target("avx2"))) static inline __m256i bp_key4(__m128i li, __m128i cx, __m128i cy, __m128i huge)
{
    __m256i k = _mm256_slli_epi64(_mm256_cvtepu32_epi64(li), 58);
    k = _mm256_or_si256(k, _mm256_slli_epi64(_mm256_cvtepu32_epi64(_mm_add_epi32(cx, _mm_set1_epi32(BP_LIM))), 29));
    k = _mm256_or_si256(k, _mm256_cvtepu32_epi64(_mm_add_epi32(cy, _mm_set1_epi32(BP_LIM))));
    return _mm256_andnot_si256(_mm256_cvtepi32_epi64(huge), k);
}

/* broadphase_locate_boxes for eight boxes: level_of and cell_key lane by lane, bit for bit.
 * The tables' entries are made from their exponents: the fit of level li is 255/256 of
 * 2^(li + BP_LEVEL_MIN), mantissa 0x7F0000 under exponent li + BP_LEVEL_MIN - 1, and its
 * inverse 2^-(li + BP_LEVEL_MIN): the same floats. */
__attribute__((target("avx2"))) static void bp_locate8(const rg_real *box, int16_t *level, uint64_t *key)
{
    /* two boxes a load, unpacked into lanes of boxes 0 2 4 6 1 3 5 7, then put in order */
    __m256 y0 = _mm256_loadu_ps(box), y1 = _mm256_loadu_ps(box + 8);
    __m256 y2 = _mm256_loadu_ps(box + 16), y3 = _mm256_loadu_ps(box + 24);
    __m256 t0 = _mm256_unpacklo_ps(y0, y1), t1 = _mm256_unpackhi_ps(y0, y1);
    __m256 t2 = _mm256_unpacklo_ps(y2, y3), t3 = _mm256_unpackhi_ps(y2, y3);
    const __m256i order = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7);
    __m256 lx = _mm256_permutevar8x32_ps(_mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(1, 0, 1, 0)), order);
    __m256 ly = _mm256_permutevar8x32_ps(_mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2)), order);
    __m256 ux = _mm256_permutevar8x32_ps(_mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0)), order);
    __m256 uy = _mm256_permutevar8x32_ps(_mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(3, 2, 3, 2)), order);
    __m256 w = _mm256_sub_ps(ux, lx), h = _mm256_sub_ps(uy, ly), top = _mm256_set1_ps(level_fit(BP_LEVELS - 1));
    /* within the top level (not NaN) */
    __m256i fits =
        _mm256_castps_si256(_mm256_and_ps(_mm256_cmp_ps(w, top, _CMP_LE_OQ), _mm256_cmp_ps(h, top, _CMP_LE_OQ)));
    __m256 ext = _mm256_max_ps(w, h); /* rg_max: w > h ? w : h */
    /* li from the exponent; 0 where ext is not above 0 or below level 0 (a subnormal too) */
    __m256i li =
        _mm256_sub_epi32(_mm256_srli_epi32(_mm256_castps_si256(ext), 23), _mm256_set1_epi32(126 + BP_LEVEL_MIN));
    __m256i finer = _mm256_or_si256(_mm256_castps_si256(_mm256_cmp_ps(ext, _mm256_setzero_ps(), _CMP_LE_OQ)),
                                    _mm256_cmpgt_epi32(_mm256_setzero_si256(), li));
    __m256i fit_exp = _mm256_slli_epi32(_mm256_add_epi32(li, _mm256_set1_epi32(127 + BP_LEVEL_MIN - 1)), 23);
    __m256 fit = _mm256_castsi256_ps(_mm256_or_si256(fit_exp, _mm256_set1_epi32(0x7F0000)));
    li = _mm256_sub_epi32(li, _mm256_castps_si256(_mm256_cmp_ps(ext, fit, _CMP_GT_OQ))); /* one up past the fit */
    li = _mm256_andnot_si256(finer, li);
    li = _mm256_blendv_epi8(_mm256_set1_epi32(BP_HUGE), li, fits);
    __m256i huge = _mm256_cmpeq_epi32(li, _mm256_set1_epi32(BP_HUGE));
    __m256 inv =
        _mm256_castsi256_ps(_mm256_slli_epi32(_mm256_sub_epi32(_mm256_set1_epi32(127 - BP_LEVEL_MIN), li), 23));
    __m256i cx = bp_coord8(lx, inv), cy = bp_coord8(ly, inv);
    __m128i li0 = _mm256_castsi256_si128(li), li1 = _mm256_extracti128_si256(li, 1);
    _mm_storeu_si128((__m128i *)(void *)level, _mm_packs_epi32(li0, li1));
    _mm256_storeu_si256((__m256i *)(void *)key, bp_key4(li0, _mm256_castsi256_si128(cx), _mm256_castsi256_si128(cy),
                                                        _mm256_castsi256_si128(huge)));
    _mm256_storeu_si256((__m256i *)(void *)(key + 4),
                        bp_key4(li1, _mm256_extracti128_si256(cx, 1), _mm256_extracti128_si256(cy, 1),
                                _mm256_extracti128_si256(huge, 1)));
}
#endif

void broadphase_locate_boxes(const rg_real *box, int32_t n, int16_t *level, uint64_t *key)
{
    int32_t k = 0;
#if RG_AVX2_PATHS
    if (__builtin_cpu_supports("avx2"))
        for (; n - k >= 8; k += 8) bp_locate8(box + 4 * (size_t)k, level + k, key + k);
#endif
    for (box += 4 * (size_t)k; k < n; k++, box += 4) {
        int li = level_of(box[0], box[1], box[2], box[3]);
        uint64_t kk = 0;
        if (li != BP_HUGE) {
            rg_real inv = level_inv(li);
            kk = cell_key(li, cell_coord(box[0], inv), cell_coord(box[1], inv));
        }
        level[k] = (int16_t)li;
        key[k] = kk;
    }
}

uint32_t broadphase_bucket(int bits, uint64_t key)
{
    return (uint32_t)((key * 0x9E3779B97F4A7C15ull) >> (64 - bits));
}

rg_status broadphase_reserve_slots(broadphase *bp, const rg_mem *m, int32_t slots)
{
    return bp_grow_slots(bp, m, bp_slot_cap(bp, slots));
}

void broadphase_clear(broadphase *bp, const rg_mem *m, int32_t *head, int bits, const int32_t *rewritten,
                     int32_t nrewritten)
{
    int fresh = bits != bp->bucket_bits;
    if (fresh) {
        if (bp->head != NULL) mem_free(m, bp->head, ((size_t)1 << bp->bucket_bits) * sizeof *bp->head);
        bp->head = head;
        bp->bucket_bits = bits;
    }
    /* the chains' heads are the members' buckets: reset those alone, or the whole table when
     * the members are many (a pass over it costs less than a write per member to a bucket
     * found through its entry); only members' entries differ from an empty slot's, and those
     * the caller rewrites whole are left to it */
    size_t nb = bp->head != NULL ? (size_t)1 << bp->bucket_bits : 0;
    int whole = bp->head != NULL && (fresh || (size_t)bp->count * 8 >= nb);
    int each = bp->head != NULL && !whole;
    for (int32_t i = 0; i < bp->count; i++) {
        int32_t s = bp->members[i];
        bp_entry *e = &bp->e[s];
        if (each && e->level != BP_HUGE) bp->head[bucket_of(bp, e->key)] = -1;
        if (s < nrewritten && rewritten[s] != 0) continue;
        memset(e, 0, sizeof *e);
        e->member = -1;
        e->next = e->prev = -1;
        e->lnext = e->lprev = -1;
        e->apos = -1;
    }
    if (whole) memset(bp->head, 0xFF, nb * sizeof *bp->head); /* -1 */
    bp->count = bp->n_huge = bp->n_moved = bp->n_active = 0;
    for (int li = 0; li <= BP_LEVELS; li++) bp->level_count[li] = 0;
    for (int li = 0; li < BP_LEVELS; li++) bp->level_head[li] = -1;
    bp->levels = 0;
}

void broadphase_restore_members(broadphase *bp, int32_t count)
{
    for (int32_t k = 0; k < count; k++) {
        int32_t s = bp->members[k];
        bp_entry *e = &bp->e[s];
        level_count_add(bp, e->level, 1);
        if (e->apos >= 0) {
            bp->active[e->apos] = s;
            bp->n_active++;
        }
        if (e->level == BP_HUGE) {
            bp->huge[e->next] = s;
            bp->n_huge++;
            e->prev = e->lnext = e->lprev = -1;
            continue;
        }
        if (e->prev < 0) bp->head[bucket_of(bp, e->key)] = s;
        if (e->lprev < 0) bp->level_head[e->level] = s;
    }
    bp->count = count;
}

void broadphase_release(broadphase *bp, const rg_mem *m)
{
    mem_free(m, bp->e, (size_t)bp->cap * sizeof *bp->e);
    mem_free(m, bp->members, (size_t)bp->cap * sizeof *bp->members);
    mem_free(m, bp->huge, (size_t)bp->cap * sizeof *bp->huge);
    mem_free(m, bp->moved, (size_t)bp->cap * sizeof *bp->moved);
    mem_free(m, bp->active, (size_t)bp->cap * sizeof *bp->active);
    if (bp->head != NULL) mem_free(m, bp->head, ((size_t)1 << bp->bucket_bits) * sizeof *bp->head);
    memset(bp, 0, sizeof *bp);
}

void broadphase_insert(broadphase *bp, int32_t slot, rg_real lx, rg_real ly, rg_real ux, rg_real uy)
{
    set_box(bp, slot, lx, ly, ux, uy);
    bp_entry *e = &bp->e[slot];
    e->member = bp->count;
    e->moved = 0;
    e->apos = -1;
    /* no pair-search mark: the slot's last member may have left one above bp->mark, where a
     * restore moved the mark back (a restore clears only the marks of its members) */
    e->mark = 0;
    bp->members[bp->count++] = slot;
    level_count_add(bp, e->level, 1);
    chain_link(bp, slot);
    level_link(bp, slot);
}

void broadphase_move(broadphase *bp, int32_t slot, rg_real lx, rg_real ly, rg_real ux, rg_real uy)
{
    bp_entry *e = &bp->e[slot];
    int old_level = e->level;
    uint64_t old_key = e->key;
    e->lx = lx;
    e->ly = ly;
    e->ux = ux;
    e->uy = uy;
    int li = level_of(lx, ly, ux, uy);
    uint64_t key = 0;
    if (li != BP_HUGE) {
        rg_real inv = level_inv(li);
        key = cell_key(li, cell_coord(lx, inv), cell_coord(ly, inv));
    }
    if (li == old_level && key == old_key) return; /* same cell: the box alone changed */
    /* unlink with the old level and key, relink with the new */
    e->level = (int16_t)old_level;
    e->key = old_key;
    chain_unlink(bp, slot);
    if (li != old_level) level_unlink(bp, slot);
    level_count_add(bp, old_level, -1);
    e->level = (int16_t)li;
    e->key = key;
    level_count_add(bp, li, 1);
    chain_link(bp, slot);
    if (li != old_level) level_link(bp, slot);
}

void broadphase_activate(broadphase *bp, int32_t slot)
{
    bp_entry *e = &bp->e[slot];
    if (e->apos >= 0) return;
    e->apos = bp->n_active;
    bp->active[bp->n_active++] = slot;
}

void broadphase_deactivate(broadphase *bp, int32_t slot)
{
    bp_entry *e = &bp->e[slot];
    if (e->apos < 0) return;
    int32_t last = bp->active[--bp->n_active];
    bp->active[e->apos] = last;
    bp->e[last].apos = e->apos;
    e->apos = -1;
}

void broadphase_remove(broadphase *bp, int32_t slot)
{
    bp_entry *e = &bp->e[slot];
    broadphase_deactivate(bp, slot);
    chain_unlink(bp, slot);
    level_unlink(bp, slot);
    level_count_add(bp, e->level, -1);
    int32_t i = e->member, last = bp->members[--bp->count];
    bp->members[i] = last;
    bp->e[last].member = i;
    e->member = -1;
    e->next = e->prev = -1;
    if (e->moved) {
        for (int32_t k = 0; k < bp->n_moved; k++) {
            if (bp->moved[k] == slot) {
                memmove(&bp->moved[k], &bp->moved[k + 1], (size_t)(bp->n_moved - k - 1) * sizeof *bp->moved);
                bp->n_moved--;
                break;
            }
        }
        e->moved = 0;
    }
}

void broadphase_mark_moved(broadphase *bp, int32_t slot)
{
    bp_entry *e = &bp->e[slot];
    if (e->moved) return;
    e->moved = 1;
    bp->moved[bp->n_moved++] = slot;
}

static inline int box_overlap(const bp_entry *e, rg_real lx, rg_real ly, rg_real ux, rg_real uy)
{
    return (e->lx <= ux) & (lx <= e->ux) & (e->ly <= uy) & (ly <= e->uy);
}

/* Members of level li overlapping the box: visit the candidate cells, or walk the level's
 * list when the box spans at least as many cells as the level has members. */
static void query_level(const broadphase *bp, int li, rg_real lx, rg_real ly, rg_real ux, rg_real uy,
                        bp_visit_fn visit, void *ctx)
{
    rg_real inv = level_inv(li);
    int64_t x0 = cell_coord(lx, inv) - 1, y0 = cell_coord(ly, inv) - 1;
    int64_t x1 = cell_coord(ux, inv), y1 = cell_coord(uy, inv);
    if (x0 < -BP_LIM) x0 = -BP_LIM;
    if (y0 < -BP_LIM) y0 = -BP_LIM;
    int64_t cells = (x1 - x0 + 1) * (y1 - y0 + 1);
    if (cells >= (int64_t)bp->level_count[li]) {
        for (int32_t s = bp->level_head[li]; s >= 0;) {
            const bp_entry *e = &bp->e[s];
            int32_t next = e->lnext;
            if (box_overlap(e, lx, ly, ux, uy)) visit(ctx, s);
            s = next;
        }
        return;
    }
    for (int64_t cx = x0; cx <= x1; cx++) {
        for (int64_t cy = y0; cy <= y1; cy++) {
            uint64_t key = cell_key(li, cx, cy);
            for (int32_t s = bp->head[bucket_of(bp, key)]; s >= 0;) {
                const bp_entry *e = &bp->e[s];
                int32_t next = e->next;
                if ((e->key == key) & box_overlap(e, lx, ly, ux, uy)) visit(ctx, s);
                s = next;
            }
        }
    }
}

void broadphase_query(const broadphase *bp, rg_real lx, rg_real ly, rg_real ux, rg_real uy,
                      bp_visit_fn visit, void *ctx)
{
    if (bp->count == 0) return;
    for (uint32_t occ = bp->levels; occ != 0; occ &= occ - 1) {
#ifdef __GNUC__
        int li = __builtin_ctz(occ);
#else
        int li = 0;
        while (!(occ & (1u << li))) li++;
#endif
        query_level(bp, li, lx, ly, ux, uy, visit, ctx);
    }
    for (int32_t i = 0; i < bp->n_huge; i++) {
        int32_t s = bp->huge[i];
        if (box_overlap(&bp->e[s], lx, ly, ux, uy)) visit(ctx, s);
    }
}

typedef struct ray_ctx {
    bp_ray_fn fn;
    void *ctx;
    rg_real max_t;
    const broadphase *bp;
    int once, has_prev;     /* once: skip the members the previous chunk's box overlaps */
    rg_real plx, ply, pux, puy;
} ray_ctx;

static void ray_visit(void *p, int32_t slot)
{
    ray_ctx *r = p;
    if (r->has_prev && box_overlap(&r->bp->e[slot], r->plx, r->ply, r->pux, r->puy)) return;
    r->max_t = r->fn(r->ctx, slot, r->max_t);
}

/* The path walks each level in chunks no longer than one cell per axis, each chunk a box
 * query (the chunk's segment grown by the half extents); chunks beyond the closest hit so
 * far are never visited.  A member meets a run of consecutive chunks (the chunk boxes follow
 * a straight path), so skipping those the previous chunk met visits each once. */
void broadphase_sweep(const broadphase *bp, rg_vec2 o, rg_vec2 d, rg_real hx, rg_real hy, int once,
                      bp_ray_fn visit, void *ctx)
{
    if (bp->count == 0) return;
    ray_ctx r = {visit, ctx, 1, bp, once, 0, 0, 0, 0, 0};
    rg_real span = rg_max(rg_fabs(d.x), rg_fabs(d.y));
    for (int i = 0; i < bp->n_huge; i++) ray_visit(&r, bp->huge[i]);
    for (int li = BP_LEVELS - 1; li >= 0; li--) {
        if (bp->level_count[li] == 0) continue;
        rg_real c = level_cell(li);
        /* chunk length in t; a whole-ray chunk when the ray is shorter than a cell */
        rg_real step = span > c ? c / span : 1;
        rg_real nchunks = span > c ? r.max_t / step + 1 : 1;
        r.has_prev = 0;
        if (nchunks * 4 > (rg_real)bp->level_count[li] + 8) {
            /* long ray over a sparse level: test each member of the level once */
            for (int32_t s = bp->level_head[li]; s >= 0;) {
                int32_t next = bp->e[s].lnext;
                ray_visit(&r, s);
                s = next;
            }
            continue;
        }
        for (rg_real t0 = 0; t0 <= r.max_t; t0 += step) {
            rg_real t1 = rg_min(t0 + step, r.max_t);
            rg_real ax = o.x + d.x * t0, ay = o.y + d.y * t0;
            rg_real bx = o.x + d.x * t1, by = o.y + d.y * t1;
            rg_real lx = rg_min(ax, bx) - hx, ly = rg_min(ay, by) - hy;
            rg_real ux = rg_max(ax, bx) + hx, uy = rg_max(ay, by) + hy;
            query_level(bp, li, lx, ly, ux, uy, ray_visit, &r);
            if (step >= 1) break;
            if (once) {
                r.has_prev = 1;
                r.plx = lx;
                r.ply = ly;
                r.pux = ux;
                r.puy = uy;
            }
        }
    }
}

void broadphase_raycast(const broadphase *bp, rg_vec2 o, rg_vec2 d, bp_ray_fn visit, void *ctx)
{
    broadphase_sweep(bp, o, d, 0, 0, 0, visit, ctx);
}
