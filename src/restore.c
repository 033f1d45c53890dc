/* restore.c: rg_world_restore: a snapshot (snapshot.h) read, checked against every
 * structural invariant of the state while still in its buffer, then loaded.  Nothing of the
 * world changes until the snapshot is known good and every allocation has succeeded. */
#include "body.h"
#include "broadphase.h"
#include "contact.h"
#include "events.h"
#include "snapshot.h"
#include "spring.h"
#include "vec2.h"

#define RG_FIELD_ENUM(T, name) SNAP_F_##name,
enum { RG_BODY_FIELDS(RG_FIELD_ENUM) SNAP_FIELDS };
#undef RG_FIELD_ENUM
typedef char snap_fields_fit[SNAP_FIELDS <= 64 ? 1 : -1];

typedef struct snap_in {
    const uint8_t *p;
    size_t size;
    snap_scalars s;
    snap_layout l;
    int32_t *seen;      /* scratch, nseen entries */
    size_t nseen;
} snap_in;

#define BAD 0

/* ---------------------------------------------------------------- reading */

static inline int32_t rd_i32(const snap_in *in, size_t off, int32_t i)
{
    return (int32_t)snap_get32(in->p + off + 4 * (size_t)i);
}

static inline uint32_t rd_u32(const snap_in *in, size_t off, int32_t i)
{
    return snap_get32(in->p + off + 4 * (size_t)i);
}

static inline rg_real rd_real(const snap_in *in, size_t off, int32_t i)
{
    return snap_get_real(in->p + off + SNAP_REAL * (size_t)i);
}

/* Field k of body i (an int32/uint32 or an rg_real array). */
#define BF_I(in, f, i) rd_i32((in), (in)->l.field[SNAP_F_##f], (i))
#define BF_U(in, f, i) rd_u32((in), (in)->l.field[SNAP_F_##f], (i))
#define BF_R(in, f, i) rd_real((in), (in)->l.field[SNAP_F_##f], (i))

/* A record field: byte offset within record `rec` of size `size` of the array at `off`. */
static inline const uint8_t *rec(const snap_in *in, size_t off, size_t size, int32_t k)
{
    return in->p + off + size * (size_t)k;
}

typedef struct snap_cursor {
    const uint8_t *p;
} snap_cursor;

static int32_t cur_i32(snap_cursor *c)
{
    int32_t v = (int32_t)snap_get32(c->p);
    c->p += 4;
    return v;
}

static uint32_t cur_u32(snap_cursor *c)
{
    uint32_t v = snap_get32(c->p);
    c->p += 4;
    return v;
}

static rg_real cur_real(snap_cursor *c)
{
    rg_real v = snap_get_real(c->p);
    c->p += SNAP_REAL;
    return v;
}

static double cur_f64(snap_cursor *c)
{
    uint64_t u = snap_get64(c->p);
    double v;
    memcpy(&v, &u, 8);
    c->p += 8;
    return v;
}

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
    s->cfree = cur_i32(&c);
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

/* ---------------------------------------------------------------- checks */

static int fin(rg_real v) { return rg_finite(v); }
static int nonneg(rg_real v) { return rg_finite(v) && v >= 0; }

static int restore_check_header(snap_in *in, const void *data, size_t size)
{
    in->p = data;
    in->size = size;
    if (size < SNAP_HEADER + snap_scalars_size()) return BAD;
    if (memcmp(in->p, SNAP_MAGIC, 8) != 0) return BAD;
    if (snap_get32(in->p + 8) != SNAP_VERSION || snap_get32(in->p + 12) != sizeof(rg_real)) return BAD;
    if (snap_get64(in->p + 16) != (uint64_t)size) return BAD;
    if (snap_get64(in->p + 24) != snap_hash(in->p + SNAP_HEADER, size - SNAP_HEADER)) return BAD;
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

static int restore_check_scalars(snap_in *in)
{
    const snap_scalars *s = &in->s;
    if (!rg_vec2_finite(s->gravity) || !rg_vec2_finite(s->wind)) return BAD;
    if (s->integrator < RG_INTEGRATOR_EXPLICIT_EULER || s->integrator > RG_INTEGRATOR_RK4) return BAD;
    if (s->max_steps < 1 || (s->prev_valid != 0 && s->prev_valid != 1)) return BAD;
    if (!(isfinite(s->fixed_dt) && s->fixed_dt > 0) || !(isfinite(s->accumulator) && s->accumulator >= 0))
        return BAD;
    if (s->iterations < 1 || s->iterations > 64 || s->position < 0 || s->position > 64) return BAD;
    if ((s->sleeping | s->continuous | s->near_sleep) & ~1) return BAD;
    if (!nonneg(s->sleep_speed) || !(fin(s->sleep_time) && s->sleep_time > 0) || !nonneg(s->slop)) return BAD;
    if (!(fin(s->bias_rate) && s->bias_rate > 0 && s->bias_rate <= 1)) return BAD;
    if (!(fin(s->max_push) && s->max_push > 0) || !nonneg(s->restitution_threshold)) return BAD;
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
        if (s->ccap < 256 || s->ccap > INT32_MAX / 4) return BAD;
        for (int32_t c = s->ccap; c > 256; c /= 2)
            if (c % 2) return BAD;
    }
    if (s->clive < 0 || s->clive > s->ccap || s->cfree < -1 || s->cfree >= s->ccap) return BAD;
    if (s->n_awake < 0 || s->n_awake > s->clive || s->n_touching < 0 || s->n_touching > s->clive) return BAD;
    if (s->n_ev < 0 || s->n_pend < 0 || s->n_pend > s->ccap) return BAD;
    if (s->members < 0 || s->members > s->count) return BAD;
    if (s->bucket_bits != 0 && (s->bucket_bits < 6 || s->bucket_bits > restore_max_bits(s->bslots))) return BAD;
    if (s->bucket_bits == 0 && s->members > 0) return BAD;
    if (s->n_huge < 0 || s->n_huge > s->members || s->n_moved < 0 || s->n_moved > s->members) return BAD;
    if (s->n_bp_active < 0 || s->n_bp_active > s->members) return BAD;
    snap_layout_of(s, &in->l);
    return in->l.ok && in->l.size == in->size;
}

/* A pool's slots: live ones map to distinct dense places, free ones form one list from
 * `head` (a walk that ends in exactly as many steps as there are free slots cannot repeat).
 * slot_of(dense) must give back the slot. */
static int restore_check_pool(const snap_in *in, size_t gen, size_t index, int32_t slots, uint32_t max_gen,
                              int32_t head, int32_t live, size_t slot_field, size_t slot_stride)
{
    int32_t nlive = 0, nfree = 0;
    for (int32_t s = 0; s < slots; s++) {
        uint32_t g = rd_u32(in, gen, s);
        int32_t i = rd_i32(in, index, s);
        if (g > max_gen) return BAD;
        if (i >= 0) {
            if (g == 0 || i >= live) return BAD;
            if ((int32_t)snap_get32(in->p + slot_field + slot_stride * (size_t)i) != s) return BAD;
            nlive++;
        } else if (g == 0) {
            if (i != -1) return BAD; /* retired */
        } else {
            int32_t next = -i - 2;
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

static int restore_unit_or_zero(rg_real x, rg_real y)
{
    if (x == 0 && y == 0) return 1;
    rg_real len = rg_sqrt(x * x + y * y);
    return fin(x) && fin(y) && rg_fabs(len - 1) <= RG_R(1e-3);
}

static int restore_check_bodies(const snap_in *in)
{
    const snap_scalars *s = &in->s;
    int32_t shaped = 0;
    for (int32_t i = 0; i < s->count; i++) {
        int32_t type = BF_I(in, type, i);
        int part = i < s->n_active ? BODY_PART_ACTIVE : i < s->n_moving ? BODY_PART_ASLEEP : BODY_PART_STATIC;
        if (type < RG_BODY_STATIC || type > RG_BODY_DYNAMIC) return BAD;
        if ((part == BODY_PART_STATIC) != (type == RG_BODY_STATIC)) return BAD;
        rg_real reals[] = { BF_R(in, x, i), BF_R(in, y, i), BF_R(in, vx, i), BF_R(in, vy, i), BF_R(in, fx, i),
                            BF_R(in, fy, i), BF_R(in, ax, i), BF_R(in, ay, i), BF_R(in, px, i), BF_R(in, py, i),
                            BF_R(in, gscale, i), BF_R(in, dx, i), BF_R(in, dy, i) };
        for (size_t k = 0; k < sizeof reals / sizeof reals[0]; k++)
            if (!fin(reals[k])) return BAD;
        rg_real mass = BF_R(in, mass, i), inv = BF_R(in, inv_mass, i);
        if (type == RG_BODY_DYNAMIC) {
            if (!(fin(mass) && mass > 0) || inv != 1 / mass || !fin(inv)) return BAD;
        } else if (mass != 0 || inv != 0 || BF_R(in, gscale, i) != 0) {
            return BAD;
        }
        rg_real lin = BF_R(in, drag_lin, i), quad = BF_R(in, drag_quad, i), fric = BF_R(in, fric, i);
        rg_real lo = BF_R(in, min_speed, i), hi = BF_R(in, max_speed, i);
        if (!nonneg(lin) || !nonneg(quad) || !nonneg(fric) || !nonneg(lo) || !nonneg(hi) || (hi > 0 && hi < lo))
            return BAD;
        uint32_t f = 0;
        if (type == RG_BODY_DYNAMIC) {
            if (lin > 0 || quad > 0 || fric > 0) f |= BODY_F_DISSIPATIVE;
            if (lo > 0 || hi > 0) f |= BODY_F_LIMITED;
        }
        if (BF_U(in, flags, i) != f) return BAD;
        int32_t shape = BF_I(in, shape, i);
        rg_real hx = BF_R(in, hx, i), hy = BF_R(in, hy, i);
        if (shape == RG_SHAPE_NONE) {
            if (hx != 0 || hy != 0 || BF_I(in, chead, i) != 0 || part == BODY_PART_ASLEEP) return BAD;
        } else if (shape == RG_SHAPE_CIRCLE || shape == RG_SHAPE_AABB) {
            if (!(fin(hx) && hx > 0 && hx <= (rg_real)RG_MAX_SHAPE_SIZE && fin(hy) && hy > 0 &&
                  hy <= (rg_real)RG_MAX_SHAPE_SIZE))
                return BAD;
            if (shape == RG_SHAPE_CIRCLE && hx != hy) return BAD;
            shaped++;
        } else {
            return BAD;
        }
        rg_real rest = BF_R(in, rest, i), mu = BF_R(in, mu, i);
        if (!(fin(rest) && rest >= 0 && rest <= 1) || !nonneg(mu) || !nonneg(BF_R(in, sleep_t, i))) return BAD;
        if (BF_U(in, cflags, i) & ~(CF_SENSOR | CF_GROUNDED | CF_TELEPORTED)) return BAD;
        if (!restore_unit_or_zero(BF_R(in, owx, i), BF_R(in, owy, i))) return BAD;
        int32_t chead = BF_I(in, chead, i);
        if (chead < 0 || chead > s->ccap) return BAD;
        int32_t ih = BF_I(in, isl_head, i), inx = BF_I(in, isl_next, i);
        if (part == BODY_PART_ASLEEP) {
            if (ih < 1 || ih > s->bslots || inx < 0 || inx > s->bslots) return BAD;
        } else if (ih != 0 || inx != 0) {
            return BAD;
        }
    }
    if (shaped != s->members) return BAD;
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

static int restore_check_springs(const snap_in *in)
{
    const snap_scalars *s = &in->s;
    if (!restore_check_pool(in, in->l.sgen, in->l.sindex, s->sslots, s->smax_gen, s->sfree, s->springs,
                            in->l.springs + 8, SNAP_SPRING))
        return BAD;
    for (int32_t k = 0; k < s->springs; k++) {
        snap_cursor c = { rec(in, in->l.springs, SNAP_SPRING, k) };
        int32_t a = cur_i32(&c), b = cur_i32(&c);
        cur_i32(&c); /* self: checked with the pool */
        if (restore_dense(in, a) < 0 || (b != -1 && (b == a || restore_dense(in, b) < 0))) return BAD;
        rg_real ax = cur_real(&c), ay = cur_real(&c), rest = cur_real(&c), k2 = cur_real(&c), damp = cur_real(&c);
        if (!fin(ax) || !fin(ay) || !nonneg(rest) || !nonneg(k2) || !nonneg(damp)) return BAD;
    }
    return 1;
}

/* The int fields of contact k: sa, sb, na, pa, nb, pb, awake, flags. */
static inline int32_t ct_i(const snap_in *in, int32_t k, int field)
{
    return (int32_t)snap_get32(rec(in, in->l.contacts, SNAP_CONTACT, k) + 4 * field);
}

enum { CT_SA, CT_SB, CT_NA, CT_PA, CT_NB, CT_PB, CT_AWAKE, CT_FLAGS };

static int restore_check_contacts(const snap_in *in)
{
    const snap_scalars *s = &in->s;
    int32_t nfree = 0, live = 0, touching = 0, awake = 0;
    const uint32_t valid = CT_TOUCHING | CT_SENSOR | CT_SOLVE | CT_CLOSING | CT_ONEWAY | CT_PASS;
    for (int32_t k = 0; k < s->ccap; k++) {
        int32_t sa = ct_i(in, k, CT_SA), sb = ct_i(in, k, CT_SB);
        if (sa == -1) {
            int32_t next = ct_i(in, k, CT_NA);
            if (next < -1 || next >= s->ccap) return BAD;
            nfree++;
            continue;
        }
        int32_t ia = restore_dense(in, sa), ib = restore_dense(in, sb);
        if (ia < 0 || ib < 0 || sa == sb || !(restore_handle(in, sa) < restore_handle(in, sb))) return BAD;
        if (BF_I(in, shape, ia) == RG_SHAPE_NONE || BF_I(in, shape, ib) == RG_SHAPE_NONE) return BAD;
        uint32_t flags = (uint32_t)ct_i(in, k, CT_FLAGS);
        if (flags & ~valid) return BAD;
        int sensor = ((BF_U(in, cflags, ia) | BF_U(in, cflags, ib)) & CF_SENSOR) != 0;
        int one_way = BF_R(in, owx, ia) != 0 || BF_R(in, owy, ia) != 0 || BF_R(in, owx, ib) != 0 ||
                      BF_R(in, owy, ib) != 0;
        if (((flags & CT_SENSOR) != 0) != sensor || ((flags & CT_ONEWAY) != 0) != one_way) return BAD;
        int32_t a = ct_i(in, k, CT_AWAKE);
        int should = ia < s->n_active || ib < s->n_active;
        if ((a >= 0) != should || a >= s->n_awake || a < -1) return BAD;
        if (a >= 0 && rd_i32(in, in->l.awake, a) != k) return BAD;
        for (int f = CT_NA; f <= CT_PB; f++)
            if (ct_i(in, k, f) < -1 || ct_i(in, k, f) >= s->ccap) return BAD;
        const uint8_t *r = rec(in, in->l.contacts, SNAP_CONTACT, k) + 32;
        for (int q = 0; q < 13; q++)
            if (!fin(snap_get_real(r + SNAP_REAL * (size_t)q))) return BAD;
        live++;
        awake += a >= 0;
        touching += (flags & CT_TOUCHING) != 0;
    }
    if (live != s->clive || awake != s->n_awake || touching != s->n_touching || nfree != s->ccap - s->clive)
        return BAD;
    for (int32_t at = s->cfree, steps = 0; at >= 0; steps++) {
        if (steps >= nfree || ct_i(in, at, CT_SA) != -1) return BAD;
        at = ct_i(in, at, CT_NA);
    }
    /* each body's list: its contacts, each once, linked both ways; all lists together hold
     * every live contact twice */
    int64_t visits = 0;
    for (int32_t i = 0; i < s->count; i++) {
        int32_t slot = BF_I(in, slot, i), prev = -1, steps = 0;
        for (int32_t id = BF_I(in, chead, i) - 1; id >= 0; steps++) {
            if (steps >= s->clive) return BAD;
            int32_t sa = ct_i(in, id, CT_SA), sb = ct_i(in, id, CT_SB);
            if (sa == -1 || (sa != slot && sb != slot)) return BAD;
            if ((sa == slot ? ct_i(in, id, CT_PA) : ct_i(in, id, CT_PB)) != prev) return BAD;
            prev = id;
            id = sa == slot ? ct_i(in, id, CT_NA) : ct_i(in, id, CT_NB);
            visits++;
        }
    }
    return visits == 2 * (int64_t)s->clive;
}

static int restore_check_events(const snap_in *in, size_t off, int32_t n)
{
    for (int32_t k = 0; k < n; k++) {
        const uint8_t *r = rec(in, off, SNAP_EVENT, k) + 16;
        for (int q = 0; q < 6; q++)
            if (!fin(snap_get_real(r + SNAP_REAL * (size_t)q))) return BAD;
        uint32_t kind = snap_get32(r + 6 * SNAP_REAL), sensor = snap_get32(r + 6 * SNAP_REAL + 4);
        if (kind > 1 || sensor > 1) return BAD;
    }
    return 1;
}

/* A member record: slot, box, next, prev, lnext, lprev, moved, apos. */
typedef struct snap_member {
    int32_t slot;
    rg_real lx, ly, ux, uy;
    int32_t next, prev, lnext, lprev, moved, apos;
    int16_t level;
    uint64_t key;
} snap_member;

static void restore_member(const snap_in *in, int32_t k, snap_member *m)
{
    snap_cursor c = { rec(in, in->l.members, SNAP_MEMBER, k) };
    m->slot = cur_i32(&c);
    m->lx = cur_real(&c);
    m->ly = cur_real(&c);
    m->ux = cur_real(&c);
    m->uy = cur_real(&c);
    m->next = cur_i32(&c);
    m->prev = cur_i32(&c);
    m->lnext = cur_i32(&c);
    m->lprev = cur_i32(&c);
    m->moved = cur_i32(&c);
    m->apos = cur_i32(&c);
    broadphase_locate(m->lx, m->ly, m->ux, m->uy, &m->level, &m->key);
}

/* The scratch restore_check_broadphase needs: member_of (slots), bucket heads (buckets),
 * huge indices and active places used. */
static size_t restore_scratch_size(const snap_scalars *s)
{
    size_t nb = s->bucket_bits > 0 ? (size_t)1 << s->bucket_bits : 0;
    return (size_t)s->bslots + nb + (size_t)s->n_huge + (size_t)s->n_bp_active + 1;
}

/* Walks the list starting at member `head` along next (chain) or lnext (level), checking
 * the back links and that every node is a member like the head (same bucket or level);
 * returns the length, or -1. */
static int32_t restore_walk(const snap_in *in, const int32_t *member_of, const snap_member *head, int level_list)
{
    const snap_scalars *s = &in->s;
    uint32_t bk = broadphase_bucket(s->bucket_bits, head->key);
    int32_t prev = -1, steps = 0;
    for (int32_t at = head->slot; at >= 0; steps++) {
        if (steps >= s->members || at >= s->bslots || member_of[at] == 0) return -1;
        snap_member m;
        restore_member(in, member_of[at] - 1, &m);
        if (m.level == BP_HUGE) return -1;
        if (level_list ? (m.level != head->level || m.lprev != prev)
                       : (m.prev != prev || broadphase_bucket(s->bucket_bits, m.key) != bk))
            return -1;
        prev = at;
        at = level_list ? m.lnext : m.next;
    }
    return steps;
}

/* The broadphase: members are the shaped bodies, each once, awake ones in the active list;
 * every bucket chain and level list is a consistent doubly linked list of members of that
 * bucket or level, at most one per bucket or level, together holding each member once; the
 * huge indices, the active places and the move buffer are permutations of their members. */
static int restore_check_broadphase(snap_in *in)
{
    const snap_scalars *s = &in->s;
    size_t nb = s->bucket_bits > 0 ? (size_t)1 << s->bucket_bits : 0;
    int32_t *member_of = in->seen;                            /* slot -> member index + 1 */
    int32_t *bucket_head = member_of + s->bslots;             /* bucket -> has a head */
    int32_t *huge_used = bucket_head + nb;                    /* huge index -> used */
    int32_t *active_used = huge_used + s->n_huge;             /* active place -> used */
    memset(in->seen, 0, in->nseen * sizeof *in->seen);
    int32_t huge = 0, moved = 0, active = 0;
    uint32_t level_seen = 0;
    for (int32_t k = 0; k < s->members; k++) {
        snap_member m;
        restore_member(in, k, &m);
        int32_t i = restore_dense(in, m.slot);
        if (i < 0 || BF_I(in, shape, i) == RG_SHAPE_NONE || member_of[m.slot] != 0) return BAD;
        member_of[m.slot] = k + 1;
        if (!(fin(m.lx) && fin(m.ly) && fin(m.ux) && fin(m.uy) && m.lx <= m.ux && m.ly <= m.uy)) return BAD;
        if ((m.moved & ~1) != 0) return BAD;
        moved += m.moved;
        if ((m.apos >= 0) != (i < s->n_active) || m.apos < -1 || m.apos >= s->n_bp_active) return BAD;
        if (m.apos >= 0) {
            if (active_used[m.apos]++) return BAD;
            active++;
        }
        if (m.level == BP_HUGE) {
            if (m.next < 0 || m.next >= s->n_huge || huge_used[m.next]++) return BAD;
            huge++;
            continue;
        }
        if (m.prev == -1) {
            uint32_t bk = broadphase_bucket(s->bucket_bits, m.key);
            if (bucket_head[bk]++) return BAD; /* two chains in one bucket */
        }
        if (m.lprev == -1) {
            if (level_seen & (1u << m.level)) return BAD;
            level_seen |= 1u << m.level;
        }
    }
    if (huge != s->n_huge || moved != s->n_moved || active != s->n_bp_active) return BAD;
    int32_t chained = 0, listed = 0;
    for (int32_t k = 0; k < s->members; k++) {
        snap_member h;
        restore_member(in, k, &h);
        if (h.level == BP_HUGE) continue;
        if (h.prev == -1) {
            int32_t n = restore_walk(in, member_of, &h, 0);
            if (n < 0) return BAD;
            chained += n;
        }
        if (h.lprev == -1) {
            int32_t n = restore_walk(in, member_of, &h, 1);
            if (n < 0) return BAD;
            listed += n;
        }
    }
    if (chained != s->members - s->n_huge || listed != s->members - s->n_huge) return BAD;
    /* the move buffer: members marked moved, each listed once (a listing flips the mark) */
    for (int32_t k = 0; k < s->n_moved; k++) {
        int32_t slot = rd_i32(in, in->l.moved, k);
        if (slot < 0 || slot >= s->bslots || member_of[slot] <= 0) return BAD;
        snap_member m;
        restore_member(in, member_of[slot] - 1, &m);
        if (m.moved != 1) return BAD;
        member_of[slot] = -member_of[slot];
    }
    return 1;
}

/* ---------------------------------------------------------------- loading */

/* n elements of elem (4 or 8) bytes from the file's order into dst. */
static void restore_array(void *dst, const uint8_t *src, int32_t n, size_t elem)
{
    if (n <= 0) return;
#if SNAP_NATIVE
    memcpy(dst, src, (size_t)n * elem);
#else
    uint8_t *d = dst;
    for (int32_t i = 0; i < n; i++, d += elem, src += elem) {
        if (elem == 8) {
            uint64_t u = snap_get64(src);
            memcpy(d, &u, 8);
        } else {
            uint32_t u = snap_get32(src);
            memcpy(d, &u, 4);
        }
    }
#endif
}

static void restore_pool(pool *p, const snap_in *in, size_t gen, size_t index, int32_t slots, uint32_t tag,
                         uint32_t max_gen, int32_t max_slots, int32_t head, int32_t live)
{
    restore_array(p->gen, in->p + gen, slots, 4);
    restore_array(p->index, in->p + index, slots, 4);
    p->slot_count = slots;
    p->free_head = head;
    p->live = live;
    p->tag = tag;
    p->max_gen = max_gen;
    p->max_slots = max_slots;
}

static void restore_events(rg_contact_event *e, const snap_in *in, size_t off, int32_t n)
{
    for (int32_t k = 0; k < n; k++) {
        snap_cursor c = { rec(in, off, SNAP_EVENT, k) };
        e[k].a = snap_get64(c.p);
        e[k].b = snap_get64(c.p + 8);
        c.p += 16;
        e[k].normal.x = cur_real(&c);
        e[k].normal.y = cur_real(&c);
        e[k].point.x = cur_real(&c);
        e[k].point.y = cur_real(&c);
        e[k].depth = cur_real(&c);
        e[k].speed = cur_real(&c);
        e[k].kind = cur_i32(&c);
        e[k].sensor = cur_i32(&c);
    }
}

static void restore_contacts(contact_store *cs, const snap_in *in)
{
    for (int32_t k = 0; k < in->s.ccap; k++) {
        contact *c = &cs->c[k];
        const uint8_t *r = rec(in, in->l.contacts, SNAP_CONTACT, k);
        if ((int32_t)snap_get32(r) == -1) {
            memset(c, 0, sizeof *c);
            c->sa = c->sb = -1;
            c->awake = -1;
            c->na = (int32_t)snap_get32(r + 8);
            continue;
        }
#if SNAP_NATIVE
        memcpy(c, r, SNAP_CONTACT);
#else
        snap_cursor q = { r };
        c->sa = cur_i32(&q);
        c->sb = cur_i32(&q);
        c->na = cur_i32(&q);
        c->pa = cur_i32(&q);
        c->nb = cur_i32(&q);
        c->pb = cur_i32(&q);
        c->awake = cur_i32(&q);
        c->flags = cur_u32(&q);
        rg_real *reals = &c->mu;
        for (int f = 0; f < 13; f++) reals[f] = cur_real(&q);
#endif
    }
    cs->cap = in->s.ccap;
    cs->live = in->s.clive;
    cs->free_head = in->s.cfree;
    cs->n_awake = in->s.n_awake;
    cs->n_touching = in->s.n_touching;
    restore_array(cs->awake, in->p + in->l.awake, in->s.n_awake, 4);
}

static void restore_broadphase(broadphase *bp, const snap_in *in)
{
    for (int32_t k = 0; k < in->s.members; k++) {
        snap_member m;
        restore_member(in, k, &m);
        bp_entry *e = &bp->e[m.slot];
        e->lx = m.lx;
        e->ly = m.ly;
        e->ux = m.ux;
        e->uy = m.uy;
        e->level = m.level;
        e->key = m.key;
        e->next = m.next;
        e->prev = m.prev;
        e->lnext = m.lnext;
        e->lprev = m.lprev;
        e->moved = (int16_t)m.moved;
        e->apos = m.apos;
        e->member = k;
        e->mark = 0;
        bp->members[k] = m.slot;
    }
    bp->count = in->s.members;
    restore_array(bp->moved, in->p + in->l.moved, in->s.n_moved, 4);
    bp->n_moved = in->s.n_moved;
    bp->mark = in->s.mark;
    broadphase_restore_finish(bp);
}

static void restore_load(rg_world *w, const snap_in *in)
{
    const snap_scalars *s = &in->s;
    collide_world *cw = &w->coll;
    body_store *b = &w->b;
    w->gravity = s->gravity;
    w->wind = s->wind;
    w->integrator = s->integrator;
    w->max_steps = s->max_steps;
    w->prev_valid = s->prev_valid;
    w->fixed_dt = s->fixed_dt;
    w->accumulator = s->accumulator;
    w->step_count = s->step_count;
    cw->iterations = s->iterations;
    cw->position = s->position;
    cw->sleeping = s->sleeping;
    cw->continuous = s->continuous;
    cw->island.near_sleep = s->near_sleep;
    cw->sleep_speed = s->sleep_speed;
    cw->sleep_time = s->sleep_time;
    cw->slop = s->slop;
    cw->bias_rate = s->bias_rate;
    cw->max_push = s->max_push;
    cw->restitution_threshold = s->restitution_threshold;
    restore_pool(&w->body_pool, in, in->l.bgen, in->l.bindex, s->bslots, s->btag, s->bmax_gen, s->bmax_slots,
                 s->bfree, s->blive);
    int f = 0;
#define RG_FIELD_LOAD(T, name) restore_array(b->name, in->p + in->l.field[f++], s->count, sizeof(T));
    RG_BODY_FIELDS(RG_FIELD_LOAD)
#undef RG_FIELD_LOAD
    b->count = s->count;
    b->n_active = s->n_active;
    b->n_moving = s->n_moving;
    w->dissipative_count = w->limit_count = 0;
    for (int32_t i = 0; i < b->count; i++) {
        w->dissipative_count += (b->flags[i] & BODY_F_DISSIPATIVE) != 0;
        w->limit_count += (b->flags[i] & BODY_F_LIMITED) != 0;
    }
    restore_pool(&w->springs.pool, in, in->l.sgen, in->l.sindex, s->sslots, s->stag, s->smax_gen,
                 s->smax_slots, s->sfree, s->slive);
    for (int32_t k = 0; k < s->springs; k++) {
        snap_cursor c = { rec(in, in->l.springs, SNAP_SPRING, k) };
        spring *sp = &w->springs.items[k];
        sp->slot_a = cur_i32(&c);
        sp->slot_b = cur_i32(&c);
        sp->self_slot = cur_i32(&c);
        sp->anchor.x = cur_real(&c);
        sp->anchor.y = cur_real(&c);
        sp->rest = cur_real(&c);
        sp->k = cur_real(&c);
        sp->c = cur_real(&c);
    }
    w->springs.count = s->springs;
    restore_contacts(&cw->contacts, in);
    event_store *es = &cw->events;
    restore_events(es->ev, in, in->l.ev, s->n_ev);
    restore_events(es->pend, in, in->l.pend, s->n_pend);
    es->n = es->base = s->n_ev;
    es->n_pend = s->n_pend;
    es->in_step = 0;
    restore_broadphase(&cw->bp, in);
    cw->shape_count = s->members;
    cw->resolve.gen = 0;
    cw->resolve.pv_valid = 0;
    if (cw->resolve.sstamp != NULL) memset(cw->resolve.sstamp, 0, (size_t)cw->scap * sizeof *cw->resolve.sstamp);
}

/* ---------------------------------------------------------------- the call */

static rg_status restore_checked(rg_world *w, snap_in *in)
{
    const snap_scalars *s = &in->s;
    const rg_mem *m = &w->mem;
    if (!restore_check_pool(in, in->l.bgen, in->l.bindex, s->bslots, s->bmax_gen, s->bfree, s->count,
                            in->l.field[SNAP_F_slot], 4) ||
        !restore_check_bodies(in) || !restore_check_springs(in) || !restore_check_contacts(in) ||
        !restore_check_events(in, in->l.ev, s->n_ev) || !restore_check_events(in, in->l.pend, s->n_pend))
        return RG_ERR_INVALID_ARGUMENT;
    in->nseen = restore_scratch_size(s);
    in->seen = mem_alloc(m, mem_array_size(in->nseen, sizeof *in->seen));
    if (in->seen == NULL) return RG_ERR_OUT_OF_MEMORY;
    int good = restore_check_broadphase(in);
    mem_free(m, in->seen, in->nseen * sizeof *in->seen);
    if (!good) return RG_ERR_INVALID_ARGUMENT;
    /* room: growth keeps the world as it is; the contact storage (of exactly the saved
     * capacity, which decides the ids of new contacts) and the bucket table (of exactly the
     * saved size, which decides the chains) are made aside and taken at the end */
    rg_status st = pool_reserve_slots(&w->body_pool, m, s->bslots);
    if (st == RG_OK) st = body_reserve_count(w, s->count);
    if (st == RG_OK) st = pool_reserve_slots(&w->springs.pool, m, s->sslots);
    if (st == RG_OK) st = spring_reserve(w, s->springs);
    if (st == RG_OK && (s->members > 0 || s->bucket_bits > 0))
        st = broadphase_reserve_slots(&w->coll.bp, m, s->bslots);
    if (st != RG_OK) return st;
    contact_block cb;
    st = contact_block_alloc(&cb, w, s->ccap, s->n_ev, s->n_pend);
    if (st != RG_OK) return st;
    broadphase *bp = &w->coll.bp;
    size_t nb = s->bucket_bits > 0 ? (size_t)1 << s->bucket_bits : 0;
    int32_t *head = s->bucket_bits == bp->bucket_bits ? bp->head : NULL;
    if (s->bucket_bits != bp->bucket_bits && s->bucket_bits > 0) {
        head = mem_alloc(m, nb * sizeof *head);
        if (head == NULL) {
            contact_block_free(&cb, m);
            return RG_ERR_OUT_OF_MEMORY;
        }
    }
    /* nothing can fail from here on */
    contact_block_adopt(w, &cb);
    broadphase_clear(bp, m, head, s->bucket_bits);
    restore_load(w, in);
    return RG_OK;
}

RG_API rg_status rg_world_restore(rg_world *world, const void *data, size_t size)
{
    WORLD_WRITABLE(world);
    if (world == NULL || data == NULL) return RG_ERR_INVALID_ARGUMENT;
    snap_in in;
    memset(&in, 0, sizeof in);
    if (!restore_check_header(&in, data, size) || !restore_check_scalars(&in)) return RG_ERR_INVALID_ARGUMENT;
    return restore_checked(world, &in);
}
