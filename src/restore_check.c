/* restore_check.c: the checks of rg_world_restore (restore_check.h): every structural
 * invariant of a snapshot checked while it is still in its buffer, and every value against
 * the range of the setter it would enter by (the body fields' in restore_body.c). */
#include "body.h"
#include "broadphase.h"
#include "contact.h"
#include "error.h"
#include "events.h"
#include "snapshot.h"
#include "spring.h"
#include "vec2.h"
#include "restore_check.h"

#define BAD 0

static void restore_read_scalars(snap_in *in)
{
    snap_scalars *s = &in->s;
    snap_cursor c = { in->p + SNAP_HEADER };
    s->gravity.x = cur_real(&c);
    s->gravity.y = cur_real(&c);
    s->wind.x = cur_real(&c);
    s->wind.y = cur_real(&c);
    s->integrator = cur_i32(&c);
    s->max_steps = cur_i32(&c);
    s->prev_valid = cur_i32(&c);
    s->fixed_dt = cur_f64(&c);
    s->accumulator = cur_f64(&c);
    s->step_count = snap_get64(c.p);
    c.p += 8;
    s->iterations = cur_i32(&c);
    s->position = cur_i32(&c);
    s->sleeping = cur_i32(&c);
    s->continuous = cur_i32(&c);
    s->near_sleep = cur_i32(&c);
    s->sleep_speed = cur_real(&c);
    s->sleep_time = cur_real(&c);
    s->slop = cur_real(&c);
    s->bias_rate = cur_real(&c);
    s->max_push = cur_real(&c);
    s->restitution_threshold = cur_real(&c);
    s->btag = cur_u32(&c);
    s->bmax_gen = cur_u32(&c);
    s->bmax_slots = cur_i32(&c);
    s->bslots = cur_i32(&c);
    s->bfree = cur_i32(&c);
    s->blive = cur_i32(&c);
    s->count = cur_i32(&c);
    s->n_active = cur_i32(&c);
    s->n_moving = cur_i32(&c);
    s->stag = cur_u32(&c);
    s->smax_gen = cur_u32(&c);
    s->smax_slots = cur_i32(&c);
    s->sslots = cur_i32(&c);
    s->sfree = cur_i32(&c);
    s->slive = cur_i32(&c);
    s->springs = cur_i32(&c);
    s->ccap = cur_i32(&c);
    s->clive = cur_i32(&c);
    s->n_awake = cur_i32(&c);
    s->n_touching = cur_i32(&c);
    s->n_ev = cur_i32(&c);
    s->n_pend = cur_i32(&c);
    s->members = cur_i32(&c);
    s->bucket_bits = cur_i32(&c);
    s->n_huge = cur_i32(&c);
    s->n_moved = cur_i32(&c);
    s->n_bp_active = cur_i32(&c);
    s->mark = cur_u32(&c);
}

/* The layout, read in order; 0 when an array would run past the end. */
typedef struct snap_walk {
    const snap_in *in;
    size_t at;
    int ok;
} snap_walk;

static size_t walk_take(snap_walk *wk, int64_t n, size_t elem)
{
    size_t start = (wk->at + 7u) & ~(size_t)7u;
    if (n < 0 || start > wk->in->size || (uint64_t)n > (uint64_t)(wk->in->size - start) / elem) {
        wk->ok = 0;
        return start;
    }
    wk->at = start + (size_t)n * elem;
    return start;
}

static int restore_layout(snap_in *in)
{
    const snap_scalars *s = &in->s;
    snap_layout *l = &in->l;
    snap_walk wk = { in, SNAP_HEADER + snap_scalars_size(), 1 };
    l->bgen = walk_take(&wk, s->bslots, 4);
    l->bindex = walk_take(&wk, s->bslots, 4);
    int f = 0;
#define SNAP_FIELD_LAYOUT(T, name)                                                        \
    {                                                                                     \
        size_t flag = walk_take(&wk, 1, 4);                                               \
        uint32_t uniform = wk.ok ? snap_get32(in->p + flag) : 0;                         \
        if (uniform > 1 || (uniform && s->count == 0)) wk.ok = 0;                         \
        l->field[f] = walk_take(&wk, uniform ? 1 : s->count, sizeof(T));                  \
        l->stride[f++] = uniform ? 0 : sizeof(T);                                         \
    }
    SNAP_BODY_FIELDS(SNAP_FIELD_LAYOUT)
#undef SNAP_FIELD_LAYOUT
    l->sgen = walk_take(&wk, s->sslots, 4);
    l->sindex = walk_take(&wk, s->sslots, 4);
    l->springs = walk_take(&wk, s->springs, SNAP_SPRING);
    l->contacts = walk_take(&wk, s->clive, SNAP_CONTACT);
    l->free = walk_take(&wk, (int64_t)s->ccap - s->clive, 4);
    l->awake = walk_take(&wk, s->n_awake, 4);
    l->ev = walk_take(&wk, s->n_ev, SNAP_EVENT);
    l->pend = walk_take(&wk, s->n_pend, SNAP_EVENT);
    l->members = walk_take(&wk, s->members, SNAP_MEMBER);
    l->moved = walk_take(&wk, s->n_moved, 4);
    l->size = (wk.at + 7u) & ~(size_t)7u;
    return wk.ok && l->size == in->size;
}

/* ---------------------------------------------------------------- checks */

static int fin(rg_real v) { return rg_finite(v); }
/* In the range the setter it enters by accepts (rigid.h), compared as the setters compare,
 * after rounding the bounds to rg_real: a state no call could make is refused, since the
 * step's arithmetic stays finite only within the ranges (bounds.c). */
static int within(rg_real v, double lo, double hi) { return fin(v) && v >= (rg_real)lo && v <= (rg_real)hi; }
static int within_vec(rg_vec2 v, double max) { return within(v.x, -max, max) && within(v.y, -max, max); }

/* The header; 1, or 0 with the reason set. */
int restore_check_header(const rg_world *w, snap_in *in, const void *data, size_t size, int sealed)
{
    const char *f = sealed ? "rg_world_restore" : "rg_world_restore_slot";
    in->p = data;
    in->size = size;
    if (size < SNAP_HEADER + snap_scalars_size() || memcmp(in->p, SNAP_MAGIC, 8) != 0) {
        error_set(w, RG_ERR_INVALID_ARGUMENT, f, "data (%lu bytes) is no snapshot", (unsigned long)size);
        return 0;
    }
    if (snap_get32(in->p + 8) != SNAP_VERSION) {
        error_set(w, RG_ERR_INVALID_ARGUMENT, f, "snapshot of format %u; this build reads format %u",
                  (unsigned)snap_get32(in->p + 8), (unsigned)SNAP_VERSION);
        return 0;
    }
    if (snap_get32(in->p + 12) != sizeof(rg_real)) {
        error_set(w, RG_ERR_INVALID_ARGUMENT, f, "snapshot of a build with rg_real of %u bytes; this build's has %u",
                  (unsigned)snap_get32(in->p + 12), (unsigned)sizeof(rg_real));
        return 0;
    }
    if (snap_get64(in->p + 16) != (uint64_t)size) {
        error_set(w, RG_ERR_INVALID_ARGUMENT, f, "size %lu, the snapshot says %llu (truncated or extended)",
                  (unsigned long)size, (unsigned long long)snap_get64(in->p + 16));
        return 0;
    }
    if (sealed && snap_get64(in->p + 24) != snap_hash(in->p + SNAP_HEADER, size - SNAP_HEADER)) {
        error_set(w, RG_ERR_INVALID_ARGUMENT, f, "checksum mismatch (the snapshot is corrupted)");
        return 0;
    }
    restore_read_scalars(in);
    return 1;
}

/* The largest bucket table a world with `slots` body slots can have grown: enough for twice
 * as many members as slots. */
static int restore_max_bits(int32_t slots)
{
    int bits = 6;
    while (((int64_t)1 << bits) < 2 * ((int64_t)slots + 1)) bits++;
    return bits;
}

int restore_check_scalars(snap_in *in)
{
    const snap_scalars *s = &in->s;
    if (!within_vec(s->gravity, RG_MAX_ACCELERATION) || !within_vec(s->wind, RG_MAX_FORCE)) return BAD;
    if (s->integrator < RG_INTEGRATOR_EXPLICIT_EULER || s->integrator > RG_INTEGRATOR_RK4) return BAD;
    if (s->max_steps < 1 || (s->prev_valid != 0 && s->prev_valid != 1)) return BAD;
    if (!(s->fixed_dt > 0 && s->fixed_dt <= (double)(rg_real)RG_MAX_DT && (rg_real)s->fixed_dt > 0) ||
        !(isfinite(s->accumulator) && s->accumulator >= 0))
        return BAD;
    if (s->iterations < 1 || s->iterations > 64 || s->position < 0 || s->position > 64) return BAD;
    if ((s->sleeping | s->continuous | s->near_sleep) & ~1) return BAD;
    if (!within(s->sleep_speed, 0, RG_MAX_SPEED) || !(fin(s->sleep_time) && s->sleep_time > 0) ||
        !within(s->slop, 0, RG_MAX_SHAPE_SIZE))
        return BAD;
    if (!(fin(s->bias_rate) && s->bias_rate > 0 && s->bias_rate <= 1)) return BAD;
    if (!(within(s->max_push, 0, RG_MAX_SPEED) && s->max_push > 0) ||
        !within(s->restitution_threshold, 0, RG_MAX_SPEED))
        return BAD;
    /* pools: the spring tag is the body tag with its top bit flipped (world.c) */
    if (s->btag > POOL_TAG_MASK || s->stag != (s->btag ^ (1u << (POOL_TAG_BITS - 1)))) return BAD;
    if (s->bmax_gen < 1 || s->bmax_gen > POOL_MAX_GEN || s->smax_gen < 1 || s->smax_gen > POOL_MAX_GEN) return BAD;
    if (s->bmax_slots < 1 || s->bmax_slots > RG_MAX_BODIES || s->smax_slots < 1 || s->smax_slots > RG_MAX_SPRINGS)
        return BAD;
    if (s->bslots < 0 || s->bslots > s->bmax_slots || s->sslots < 0 || s->sslots > s->smax_slots) return BAD;
    if (s->bfree < -1 || s->bfree >= s->bslots || s->sfree < -1 || s->sfree >= s->sslots) return BAD;
    if (s->blive != s->count || s->count < 0 || s->count > s->bslots) return BAD;
    if (!(0 <= s->n_active && s->n_active <= s->n_moving && s->n_moving <= s->count)) return BAD;
    if (s->slive != s->springs || s->springs < 0 || s->springs > s->sslots) return BAD;
    /* contacts: 0 or 256 doubled */
    if (s->ccap != 0) {
        if (s->ccap < 256 || s->ccap > INT32_MAX / 8) return BAD;
        for (int32_t c = s->ccap; c > 256; c /= 2)
            if (c % 2) return BAD;
    }
    if (s->clive < 0 || s->clive > s->ccap) return BAD;
    if (s->n_awake < 0 || s->n_awake > s->clive || s->n_touching < 0 || s->n_touching > s->clive) return BAD;
    if (s->n_ev < 0 || s->n_pend < 0 || s->n_pend > s->ccap) return BAD;
    if (s->members < 0 || s->members > s->count) return BAD;
    if (s->bucket_bits != 0 && (s->bucket_bits < 6 || s->bucket_bits > restore_max_bits(s->bslots))) return BAD;
    if (s->bucket_bits == 0 && s->members > 0) return BAD;
    if (s->n_huge < 0 || s->n_huge > s->members || s->n_moved < 0 || s->n_moved > s->members) return BAD;
    if (s->n_bp_active < 0 || s->n_bp_active > s->members) return BAD;
    return restore_layout(in);
}

/* A pool's slots: live ones map to distinct dense places, free ones form one list from
 * `head` (a walk that ends in exactly as many steps as there are free slots cannot repeat).
 * slot_at(dense) must give back the slot. */
int restore_check_pool(const snap_in *in, size_t gen, size_t index, int32_t slots, uint32_t max_gen,
                       int32_t head, int32_t live, const uint8_t *slot_of, size_t slot_stride)
{
    int32_t nlive = 0, nfree = 0;
    for (int32_t s = 0; s < slots; s++) {
        uint32_t g = rd_u32(in, gen, s);
        int32_t i = rd_i32(in, index, s);
        if (g > max_gen) return BAD;
        if (i >= 0) {
            if (g == 0 || i >= live) return BAD;
            if ((int32_t)snap_get32(slot_of + slot_stride * (size_t)i) != s) return BAD;
            nlive++;
        } else if (g == 0) {
            if (i != -1) return BAD; /* retired */
        } else {
            int64_t next = -(int64_t)i - 2; /* in 64 bits: a forged INT32_MIN must not overflow */
            if (next < -1 || next >= slots) return BAD;
            nfree++;
        }
    }
    if (nlive != live) return BAD;
    int32_t at = head, steps = 0;
    while (at >= 0) {
        if (steps++ >= nfree) return BAD;
        int32_t i = rd_i32(in, index, at);
        if (rd_u32(in, gen, at) == 0 || i >= 0) return BAD;
        at = -i - 2;
    }
    return steps == nfree;
}

static uint64_t restore_handle(const snap_in *in, int32_t slot)
{
    return ((uint64_t)in->s.btag << (POOL_SLOT_BITS + POOL_GEN_BITS)) |
           ((uint64_t)rd_u32(in, in->l.bgen, slot) << POOL_SLOT_BITS) | (uint64_t)slot;
}

/* Dense index of a live body slot, or -1. */
static int32_t restore_dense(const snap_in *in, int32_t slot)
{
    if (slot < 0 || slot >= in->s.bslots) return -1;
    return rd_i32(in, in->l.bindex, slot);
}

int restore_check_bodies(const snap_in *in)
{
    const snap_scalars *s = &in->s;
    if (!restore_check_body_values(in)) return BAD;
    /* the islands: each sleeping body's list head is a sleeping body heading its own list,
     * and the lists (acyclic: no walk is longer than the sleeping bodies) cover each
     * sleeping body once */
    int32_t asleep = s->n_moving - s->n_active, visited = 0;
    for (int32_t i = s->n_active; i < s->n_moving; i++) {
        int32_t self = BF_I(in, slot, i) + 1;
        if (BF_I(in, isl_head, i) != self) continue;
        for (int32_t at = self, steps = 0; at != 0; steps++) {
            int32_t j = restore_dense(in, at - 1);
            if (steps >= asleep || j < s->n_active || j >= s->n_moving || BF_I(in, isl_head, j) != self)
                return BAD;
            visited++;
            at = BF_I(in, isl_next, j);
        }
    }
    return visited == asleep;
}

int restore_check_springs(const snap_in *in)
{
    const snap_scalars *s = &in->s;
    if (!restore_check_pool(in, in->l.sgen, in->l.sindex, s->sslots, s->smax_gen, s->sfree, s->springs,
                            in->p + in->l.springs + 8, SNAP_SPRING))
        return BAD;
    for (int32_t k = 0; k < s->springs; k++) {
        snap_cursor c = { rec(in, in->l.springs, SNAP_SPRING, k) };
        int32_t a = cur_i32(&c), b = cur_i32(&c);
        cur_i32(&c); /* self: checked with the pool */
        if (restore_dense(in, a) < 0 || (b != -1 && (b == a || restore_dense(in, b) < 0))) return BAD;
        rg_real ax = cur_real(&c), ay = cur_real(&c), rest = cur_real(&c), k2 = cur_real(&c), damp = cur_real(&c);
        if (!within(ax, -RG_MAX_COORD, RG_MAX_COORD) || !within(ay, -RG_MAX_COORD, RG_MAX_COORD) ||
            !within(rest, 0, RG_MAX_COORD) || !within(k2, 0, RG_MAX_STIFFNESS) || !within(damp, 0, RG_MAX_DAMPING))
            return BAD;
    }
    return 1;
}


void restore_check_scratch_layout(mem_layout *l, void *ctx)
{
    restore_scratch *r = ctx;
    const snap_scalars *s = r->s;
    r->rec_of = mem_take(l, (size_t)s->ccap, sizeof(int32_t));
    r->member_of = mem_take(l, (size_t)s->bslots, sizeof(int32_t));
    r->key = mem_take(l, (size_t)s->members, sizeof(uint64_t));
    r->level = mem_take(l, (size_t)s->members, sizeof(int16_t));
    r->bucket_head = mem_take(l, s->bucket_bits > 0 ? (size_t)1 << s->bucket_bits : 0, 1);
    r->huge_used = mem_take(l, (size_t)s->n_huge, 1);
    r->active_used = mem_take(l, (size_t)s->n_bp_active, 1);
}

/* The int fields of live contact record k. */
enum { CT_ID, CT_SA, CT_SB, CT_NA, CT_PA, CT_NB, CT_PB, CT_FLAGS };

static inline int32_t ct_i(const snap_in *in, int32_t k, int field)
{
    return (int32_t)snap_get32(rec(in, in->l.contacts, SNAP_CONTACT, k) + 4 * field);
}

int restore_check_contacts(const snap_in *in, restore_scratch *r)
{
    const snap_scalars *s = &in->s;
    int32_t touching = 0, should_wake = 0;
    const uint32_t valid = CT_TOUCHING | CT_SENSOR | CT_SOLVE | CT_CLOSING | CT_ONEWAY | CT_PASS;
    /* a contact's sensor and one-way flags follow from its bodies: once for all when the
     * fields they come from are uniform */
    int fixed = col_uniform(in, SNAP_F_cflags) && col_uniform(in, SNAP_F_owx) && col_uniform(in, SNAP_F_owy);
    uint32_t fixed_flags = 0;
    if (fixed && s->count > 0)
        fixed_flags = ((BF_U(in, cflags, 0) & CF_SENSOR) ? CT_SENSOR : 0) |
                      ((BF_R(in, owx, 0) != 0 || BF_R(in, owy, 0) != 0) ? CT_ONEWAY : 0);
    snap_col shape = col_of(in, SNAP_F_shape);
    const real_sbits impulse = real_magnitude((rg_real)CONTACT_MAX_IMPULSE), big = real_magnitude((rg_real)REAL_MAX);
    int32_t last = -1;
    for (int32_t k = 0; k < s->clive; k++) {
        const uint8_t *q = rec(in, in->l.contacts, SNAP_CONTACT, k);
        int32_t id = (int32_t)snap_get32(q), sa = (int32_t)snap_get32(q + 4), sb = (int32_t)snap_get32(q + 8);
        if (id <= last || id >= s->ccap) return BAD; /* ascending ids */
        last = id;
        r->rec_of[id] = k + 1;
        int32_t ia = restore_dense(in, sa), ib = restore_dense(in, sb);
        if (ia < 0 || ib < 0 || sa == sb || !(restore_handle(in, sa) < restore_handle(in, sb))) return BAD;
        if (col_i32(shape, ia) == RG_SHAPE_NONE || col_i32(shape, ib) == RG_SHAPE_NONE) return BAD;
        uint32_t flags = snap_get32(q + 28);
        if (flags & ~valid) return BAD;
        uint32_t derived = fixed_flags;
        if (!fixed) {
            int sensor = ((BF_U(in, cflags, ia) | BF_U(in, cflags, ib)) & CF_SENSOR) != 0;
            int one_way = BF_R(in, owx, ia) != 0 || BF_R(in, owy, ia) != 0 || BF_R(in, owx, ib) != 0 ||
                          BF_R(in, owy, ib) != 0;
            derived = (sensor ? CT_SENSOR : 0) | (one_way ? CT_ONEWAY : 0);
        }
        if ((flags & (CT_SENSOR | CT_ONEWAY)) != derived) return BAD;
        int bad = 0;
        for (int f = CT_NA; f <= CT_PB; f++) {
            int32_t link = (int32_t)snap_get32(q + 4 * f);
            bad |= (link < -1) | (link >= s->ccap);
        }
        /* the reals finite, the warm start's impulses within what the solve keeps (state.h) */
        const uint8_t *reals = q + 32;
        for (int f = 0; f < 8; f++) bad |= real_out(real_get(reals + SNAP_REAL * (size_t)f), 0, big, big);
        bad |= real_out(real_get(reals + SNAP_REAL * 8), 0, impulse, 0);
        bad |= real_out(real_get(reals + SNAP_REAL * 9), 0, impulse, impulse);
        if (bad) return BAD;
        touching += (flags & CT_TOUCHING) != 0;
        should_wake += ia < s->n_active || ib < s->n_active;
    }
    if (touching != s->n_touching || should_wake != s->n_awake) return BAD;
    /* the free ids: the rest, each once */
    for (int32_t k = 0; k < s->ccap - s->clive; k++) {
        int32_t id = rd_i32(in, in->l.free, k);
        if (id < 0 || id >= s->ccap || r->rec_of[id] != 0) return BAD;
        r->rec_of[id] = -1;
    }
    /* the awake list: every contact with an awake body, each once */
    for (int32_t k = 0; k < s->n_awake; k++) {
        int32_t id = rd_i32(in, in->l.awake, k);
        if (id < 0 || id >= s->ccap || r->rec_of[id] <= 0) return BAD;
        int32_t q = r->rec_of[id] - 1;
        int32_t ia = restore_dense(in, ct_i(in, q, CT_SA)), ib = restore_dense(in, ct_i(in, q, CT_SB));
        if (!(ia < s->n_active || ib < s->n_active)) return BAD;
        r->rec_of[id] = -r->rec_of[id] - 2; /* listed; a second listing finds it negative */
    }
    for (int32_t k = 0; k < s->n_awake; k++) {
        int32_t id = rd_i32(in, in->l.awake, k);
        r->rec_of[id] = -(r->rec_of[id] + 2);
    }
    /* each body's list: its contacts, each once, linked both ways; all lists together hold
     * every live contact twice */
    int64_t visits = 0;
    for (int32_t i = 0; i < s->count; i++) {
        int32_t slot = BF_I(in, slot, i), prev = -1, steps = 0;
        for (int32_t id = BF_I(in, chead, i) - 1; id >= 0; steps++) {
            if (steps >= s->clive || r->rec_of[id] <= 0) return BAD;
            int32_t q = r->rec_of[id] - 1;
            int32_t sa = ct_i(in, q, CT_SA), sb = ct_i(in, q, CT_SB);
            if (sa != slot && sb != slot) return BAD;
            if ((sa == slot ? ct_i(in, q, CT_PA) : ct_i(in, q, CT_PB)) != prev) return BAD;
            prev = id;
            id = sa == slot ? ct_i(in, q, CT_NA) : ct_i(in, q, CT_NB);
            visits++;
        }
    }
    return visits == 2 * (int64_t)s->clive;
}

int restore_check_events(const snap_in *in, size_t off, int32_t n)
{
    for (int32_t k = 0; k < n; k++) {
        const uint8_t *q = rec(in, off, SNAP_EVENT, k);
        if (!(snap_get64(q) < snap_get64(q + 8))) return BAD; /* a < b, as every contact's pair */
        q += 16;
        for (int f = 0; f < 6; f++)
            if (!fin(snap_get_real(q + SNAP_REAL * (size_t)f))) return BAD;
        uint32_t kind = snap_get32(q + 6 * SNAP_REAL), sensor = snap_get32(q + 6 * SNAP_REAL + 4);
        if (kind > 1 || sensor > 1) return BAD;
    }
    return 1;
}


/* A member's link (0 next, 1 prev, 2 lnext, 3 lprev, 4 moved) without reading the rest. */
static inline int32_t restore_link(const snap_in *in, int32_t k, int which)
{
    return (int32_t)snap_get32(rec(in, in->l.members, SNAP_MEMBER, k) + 4 + 4 * SNAP_REAL + 4 * (size_t)which);
}

/* Walks the list starting at member `head` along next (chain) or lnext (level), checking
 * the back links and that every node is a member like the head (same bucket or level);
 * returns the length, or -1. */
static int32_t restore_walk(const snap_in *in, const restore_scratch *r, int32_t head, int level_list)
{
    const snap_scalars *s = &in->s;
    uint32_t bk = broadphase_bucket(s->bucket_bits, r->key[head]);
    int16_t lv = r->level[head];
    int32_t prev = -1, steps = 0;
    for (int32_t at = (int32_t)snap_get32(rec(in, in->l.members, SNAP_MEMBER, head)); at >= 0; steps++) {
        if (steps >= s->members || at >= s->bslots || r->member_of[at] <= 0) return -1;
        int32_t k = r->member_of[at] - 1;
        if (r->level[k] == BP_HUGE) return -1;
        if (level_list ? (r->level[k] != lv || restore_link(in, k, 3) != prev)
                       : (restore_link(in, k, 1) != prev || broadphase_bucket(s->bucket_bits, r->key[k]) != bk))
            return -1;
        prev = at;
        at = restore_link(in, k, level_list ? 2 : 0);
    }
    return steps;
}

/* The broadphase: members are the shaped bodies, each once, awake ones in the active list;
 * every bucket chain and level list is a consistent doubly linked list of members of that
 * bucket or level, at most one per bucket or level, together holding each member once; the
 * huge indices, the active places and the move buffer are permutations of their members. */
int restore_check_broadphase(const snap_in *in, restore_scratch *r)
{
    const snap_scalars *s = &in->s;
    int32_t huge = 0, moved = 0, active = 0;
    uint32_t level_seen = 0;
    for (int32_t k = 0; k < s->members; k++) {
        snap_member m;
        restore_member(in, k, &m);
        int32_t i = restore_dense(in, m.slot);
        if (i < 0 || BF_I(in, shape, i) == RG_SHAPE_NONE || r->member_of[m.slot] != 0) return BAD;
        r->member_of[m.slot] = k + 1;
        if (!(fin(m.lx) && fin(m.ly) && fin(m.ux) && fin(m.uy) && m.lx <= m.ux && m.ly <= m.uy)) return BAD;
        broadphase_locate(m.lx, m.ly, m.ux, m.uy, &r->level[k], &r->key[k]);
        if ((m.moved & ~1) != 0) return BAD;
        moved += m.moved;
        if ((m.apos >= 0) != (i < s->n_active) || m.apos < -1 || m.apos >= s->n_bp_active) return BAD;
        if (m.apos >= 0) {
            if (r->active_used[m.apos]++) return BAD;
            active++;
        }
        if (r->level[k] == BP_HUGE) {
            if (m.next < 0 || m.next >= s->n_huge || r->huge_used[m.next]++) return BAD;
            huge++;
            continue;
        }
        if (m.prev == -1 && r->bucket_head[broadphase_bucket(s->bucket_bits, r->key[k])]++) return BAD;
        if (m.lprev == -1) {
            if (level_seen & (1u << r->level[k])) return BAD; /* two lists of one level */
            level_seen |= 1u << r->level[k];
        }
    }
    if (huge != s->n_huge || moved != s->n_moved || active != s->n_bp_active) return BAD;
    int32_t chained = 0, listed = 0;
    for (int32_t k = 0; k < s->members; k++) {
        if (r->level[k] == BP_HUGE) continue;
        if (restore_link(in, k, 1) == -1) {
            int32_t n = restore_walk(in, r, k, 0);
            if (n < 0) return BAD;
            chained += n;
        }
        if (restore_link(in, k, 3) == -1) {
            int32_t n = restore_walk(in, r, k, 1);
            if (n < 0) return BAD;
            listed += n;
        }
    }
    if (chained != s->members - s->n_huge || listed != s->members - s->n_huge) return BAD;
    /* the move buffer: members marked moved, each listed once (a listing flips the sign of
     * member_of; the load reads it through its absolute value) */
    for (int32_t k = 0; k < s->n_moved; k++) {
        int32_t slot = rd_i32(in, in->l.moved, k);
        if (slot < 0 || slot >= s->bslots || r->member_of[slot] <= 0) return BAD;
        if (restore_link(in, r->member_of[slot] - 1, 4) != 1) return BAD;
        r->member_of[slot] = -r->member_of[slot];
    }
    return 1;
}

