/* restore_check.c: the checks of rg_world_restore (restore_check.h): every structural
 * invariant of a snapshot checked while it is still in its buffer (the lists' in
 * restore_links.c), and every value against the range of the setter it would enter by (the
 * body fields' in restore_body.c). */
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
    restore_read_scalars(in);
    return 1;
}

int restore_check_sum(const snap_in *in)
{
    return snap_get64(in->p + 24) == snap_hash(in->p + SNAP_HEADER, in->size - SNAP_HEADER);
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
