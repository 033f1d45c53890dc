/* snapshot.c: the snapshot writer (rg_world_save), the state hash (rg_world_hash), the
 * format's layout and its hash function (see snapshot.h). */
#include "snapshot.h"

typedef char snap_contact_is_packed[sizeof(contact) == SNAP_CONTACT ? 1 : -1];

/* ---------------------------------------------------------------- the hash */

#define SNAP_K1 0x9E3779B97F4A7C15ull
#define SNAP_K2 0xC2B2AE3D27D4EB4Full

void snap_hash_init(snap_hasher *h)
{
    h->lane[0] = 0x243F6A8885A308D3ull;
    h->lane[1] = 0x13198A2E03707344ull;
    h->lane[2] = 0xA4093822299F31D0ull;
    h->lane[3] = 0x082EFA98EC4E6C89ull;
    h->npending = 0;
    h->length = 0;
}

static inline uint64_t snap_lane(uint64_t lane, uint64_t w)
{
    lane = (lane ^ w) * SNAP_K1;
    return lane ^ (lane >> 29);
}

/* 32 bytes: one word into each lane. */
static inline void snap_block(snap_hasher *h, const uint8_t *p)
{
    h->lane[0] = snap_lane(h->lane[0], snap_get64(p));
    h->lane[1] = snap_lane(h->lane[1], snap_get64(p + 8));
    h->lane[2] = snap_lane(h->lane[2], snap_get64(p + 16));
    h->lane[3] = snap_lane(h->lane[3], snap_get64(p + 24));
}

void snap_hash_bytes(snap_hasher *h, const void *data, size_t n)
{
    const uint8_t *p = data;
    h->length += n;
    if (h->npending > 0) {
        size_t take = 32 - h->npending < n ? 32 - h->npending : n;
        memcpy(h->pending + h->npending, p, take);
        h->npending += take;
        p += take;
        n -= take;
        if (h->npending < 32) return;
        snap_block(h, h->pending);
        h->npending = 0;
    }
    for (; n >= 32; p += 32, n -= 32) snap_block(h, p);
    memcpy(h->pending, p, n);
    h->npending = n;
}

static inline uint64_t snap_mix(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

uint64_t snap_hash_final(snap_hasher *h)
{
    if (h->npending > 0) {
        memset(h->pending + h->npending, 0, 32 - h->npending);
        snap_block(h, h->pending);
        h->npending = 0;
    }
    uint64_t r = snap_mix(h->length * SNAP_K2);
    for (int k = 0; k < 4; k++) r = snap_mix(r ^ snap_mix(h->lane[k] + (uint64_t)k * SNAP_K1));
    return r;
}

uint64_t snap_hash(const void *p, size_t n)
{
    snap_hasher h;
    snap_hash_init(&h);
    snap_hash_bytes(&h, p, n);
    return snap_hash_final(&h);
}

/* ---------------------------------------------------------------- layout */

size_t snap_scalars_size(void)
{
    /* 10 reals, 2 doubles, 1 uint64, the rest 4-byte words: see snap_write_scalars */
    return 10 * SNAP_REAL + 2 * 8 + 8 + 37 * 4;
}

/* Adds an array of n elements of size elem at the next multiple of 8; returns its offset. */
static size_t snap_take(snap_layout *l, size_t *at, int64_t n, size_t elem)
{
    size_t start = (*at + 7u) & ~(size_t)7u;
    if (n < 0 || (uint64_t)n > ((uint64_t)1 << 40) / (elem > 0 ? elem : 1)) {
        l->ok = 0;
        return start;
    }
    *at = start + (size_t)n * elem;
    return start;
}

void snap_layout_of(const snap_scalars *s, snap_layout *l)
{
    size_t at = SNAP_HEADER + snap_scalars_size();
    int f = 0;
    l->ok = 1;
    l->bgen = snap_take(l, &at, s->bslots, 4);
    l->bindex = snap_take(l, &at, s->bslots, 4);
#define RG_FIELD_LAYOUT(T, name) l->field[f++] = snap_take(l, &at, s->count, sizeof(T));
    RG_BODY_FIELDS(RG_FIELD_LAYOUT)
#undef RG_FIELD_LAYOUT
    l->sgen = snap_take(l, &at, s->sslots, 4);
    l->sindex = snap_take(l, &at, s->sslots, 4);
    l->springs = snap_take(l, &at, s->springs, SNAP_SPRING);
    l->contacts = snap_take(l, &at, s->ccap, SNAP_CONTACT);
    l->awake = snap_take(l, &at, s->n_awake, 4);
    l->ev = snap_take(l, &at, s->n_ev, SNAP_EVENT);
    l->pend = snap_take(l, &at, s->n_pend, SNAP_EVENT);
    l->members = snap_take(l, &at, s->members, SNAP_MEMBER);
    l->moved = snap_take(l, &at, s->n_moved, 4);
    l->size = (at + 7u) & ~(size_t)7u;
}

/* ---------------------------------------------------------------- the writer */

/* Where the stream goes: a buffer (save), a hash (hash), or both. */
typedef struct snap_out {
    uint8_t *buf;
    size_t at;
    snap_hasher *hash;
    int anonymous;      /* the world tag left out (rg_world_hash) */
} snap_out;

static void snap_emit(snap_out *o, const void *p, size_t n)
{
    if (n == 0) return;
    if (o->buf != NULL) memcpy(o->buf + o->at, p, n);
    if (o->hash != NULL) snap_hash_bytes(o->hash, p, n);
    o->at += n;
}

static void snap_pad(snap_out *o)
{
    static const uint8_t zero[8] = {0};
    snap_emit(o, zero, ((o->at + 7u) & ~(size_t)7u) - o->at);
}

static void snap_u32(snap_out *o, uint32_t v)
{
    uint8_t b[4];
    snap_put32(b, v);
    snap_emit(o, b, 4);
}

static void snap_i32(snap_out *o, int32_t v) { snap_u32(o, (uint32_t)v); }

static void snap_u64(snap_out *o, uint64_t v)
{
    uint8_t b[8];
    snap_put64(b, v);
    snap_emit(o, b, 8);
}

static void snap_f64(snap_out *o, double v)
{
    uint64_t u;
    memcpy(&u, &v, 8);
    snap_u64(o, u);
}

static void snap_real(snap_out *o, rg_real v)
{
    uint8_t b[8];
    snap_put_real(b, v);
    snap_emit(o, b, SNAP_REAL);
}

/* An array of n elements of elem bytes (integers or reals, each in the file's order). */
static void snap_array(snap_out *o, const void *p, int32_t n, size_t elem)
{
    snap_pad(o);
    if (n <= 0) return;
#if SNAP_NATIVE
    snap_emit(o, p, (size_t)n * elem);
#else
    const uint8_t *q = p;
    for (int32_t i = 0; i < n; i++, q += elem) {
        uint8_t b[8];
        if (elem == 8) {
            uint64_t u;
            memcpy(&u, q, 8);
            snap_put64(b, u);
        } else {
            uint32_t u;
            memcpy(&u, q, 4);
            snap_put32(b, u);
        }
        snap_emit(o, b, elem);
    }
#endif
}

static uint64_t snap_handle(const snap_out *o, uint64_t h)
{
    return o->anonymous ? h & ((1ull << (POOL_SLOT_BITS + POOL_GEN_BITS)) - 1u) : h;
}

static void snap_scalars_of(const rg_world *w, snap_scalars *s)
{
    const collide_world *cw = &w->coll;
    s->gravity = w->gravity;
    s->wind = w->wind;
    s->integrator = w->integrator;
    s->max_steps = w->max_steps;
    s->prev_valid = w->prev_valid;
    s->fixed_dt = w->fixed_dt;
    s->accumulator = w->accumulator;
    s->step_count = w->step_count;
    s->iterations = cw->iterations;
    s->position = cw->position;
    s->sleeping = cw->sleeping;
    s->continuous = cw->continuous;
    s->near_sleep = cw->island.near_sleep;
    s->sleep_speed = cw->sleep_speed;
    s->sleep_time = cw->sleep_time;
    s->slop = cw->slop;
    s->bias_rate = cw->bias_rate;
    s->max_push = cw->max_push;
    s->restitution_threshold = cw->restitution_threshold;
    s->btag = w->body_pool.tag;
    s->bmax_gen = w->body_pool.max_gen;
    s->bmax_slots = w->body_pool.max_slots;
    s->bslots = w->body_pool.slot_count;
    s->bfree = w->body_pool.free_head;
    s->blive = w->body_pool.live;
    s->count = w->b.count;
    s->n_active = w->b.n_active;
    s->n_moving = w->b.n_moving;
    s->stag = w->springs.pool.tag;
    s->smax_gen = w->springs.pool.max_gen;
    s->smax_slots = w->springs.pool.max_slots;
    s->sslots = w->springs.pool.slot_count;
    s->sfree = w->springs.pool.free_head;
    s->slive = w->springs.pool.live;
    s->springs = w->springs.count;
    s->ccap = cw->contacts.cap;
    s->clive = cw->contacts.live;
    s->cfree = cw->contacts.free_head;
    s->n_awake = cw->contacts.n_awake;
    s->n_touching = cw->contacts.n_touching;
    s->n_ev = cw->events.n;
    s->n_pend = cw->events.n_pend;
    s->members = cw->bp.count;
    s->bucket_bits = cw->bp.count > 0 || cw->bp.head != NULL ? cw->bp.bucket_bits : 0;
    s->n_huge = cw->bp.n_huge;
    s->n_moved = cw->bp.n_moved;
    s->n_bp_active = cw->bp.n_active;
    s->mark = cw->bp.mark;
}

static void snap_write_scalars(snap_out *o, const snap_scalars *s)
{
    snap_real(o, s->gravity.x);
    snap_real(o, s->gravity.y);
    snap_real(o, s->wind.x);
    snap_real(o, s->wind.y);
    snap_i32(o, s->integrator);
    snap_i32(o, s->max_steps);
    snap_i32(o, s->prev_valid);
    snap_f64(o, s->fixed_dt);
    snap_f64(o, s->accumulator);
    snap_u64(o, s->step_count);
    snap_i32(o, s->iterations);
    snap_i32(o, s->position);
    snap_i32(o, s->sleeping);
    snap_i32(o, s->continuous);
    snap_i32(o, s->near_sleep);
    snap_real(o, s->sleep_speed);
    snap_real(o, s->sleep_time);
    snap_real(o, s->slop);
    snap_real(o, s->bias_rate);
    snap_real(o, s->max_push);
    snap_real(o, s->restitution_threshold);
    snap_u32(o, o->anonymous ? 0 : s->btag);
    snap_u32(o, s->bmax_gen);
    snap_i32(o, s->bmax_slots);
    snap_i32(o, s->bslots);
    snap_i32(o, s->bfree);
    snap_i32(o, s->blive);
    snap_i32(o, s->count);
    snap_i32(o, s->n_active);
    snap_i32(o, s->n_moving);
    snap_u32(o, o->anonymous ? 0 : s->stag);
    snap_u32(o, s->smax_gen);
    snap_i32(o, s->smax_slots);
    snap_i32(o, s->sslots);
    snap_i32(o, s->sfree);
    snap_i32(o, s->slive);
    snap_i32(o, s->springs);
    snap_i32(o, s->ccap);
    snap_i32(o, s->clive);
    snap_i32(o, s->cfree);
    snap_i32(o, s->n_awake);
    snap_i32(o, s->n_touching);
    snap_i32(o, s->n_ev);
    snap_i32(o, s->n_pend);
    snap_i32(o, s->members);
    snap_i32(o, s->bucket_bits);
    snap_i32(o, s->n_huge);
    snap_i32(o, s->n_moved);
    snap_i32(o, s->n_bp_active);
    snap_u32(o, s->mark);
}

static void snap_write_events(snap_out *o, const rg_contact_event *e, int32_t n)
{
    snap_pad(o);
    for (int32_t k = 0; k < n; k++) {
        snap_u64(o, snap_handle(o, e[k].a));
        snap_u64(o, snap_handle(o, e[k].b));
        snap_real(o, e[k].normal.x);
        snap_real(o, e[k].normal.y);
        snap_real(o, e[k].point.x);
        snap_real(o, e[k].point.y);
        snap_real(o, e[k].depth);
        snap_real(o, e[k].speed);
        snap_i32(o, e[k].kind);
        snap_i32(o, e[k].sensor);
    }
}

/* Contacts by id; a free one as sa = -1 and its free-list link, the rest zero. */
static void snap_write_contacts(snap_out *o, const contact_store *cs)
{
    snap_pad(o);
    contact blank;
    memset(&blank, 0, sizeof blank);
    blank.sa = -1;
    for (int32_t k = 0; k < cs->cap; k++) {
        const contact *c = &cs->c[k];
        contact r;
        if (c->sa >= 0) {
            r = *c;
        } else { /* free (contact.c keeps sa = -1 on free ids) */
            r = blank;
            r.na = c->na;
        }
        uint8_t b[SNAP_CONTACT];
#if SNAP_NATIVE
        memcpy(b, &r, SNAP_CONTACT);
#else
        snap_put32(b, (uint32_t)r.sa);
        snap_put32(b + 4, (uint32_t)r.sb);
        snap_put32(b + 8, (uint32_t)r.na);
        snap_put32(b + 12, (uint32_t)r.pa);
        snap_put32(b + 16, (uint32_t)r.nb);
        snap_put32(b + 20, (uint32_t)r.pb);
        snap_put32(b + 24, (uint32_t)r.awake);
        snap_put32(b + 28, r.flags);
        const rg_real *reals = &r.mu;
        for (int q = 0; q < 13; q++) snap_put_real(b + 32 + q * SNAP_REAL, reals[q]);
#endif
        snap_emit(o, b, SNAP_CONTACT);
    }
}

static void snap_write(const rg_world *w, snap_out *o, const snap_scalars *s)
{
    const body_store *b = &w->b;
    const collide_world *cw = &w->coll;
    snap_write_scalars(o, s);
    snap_array(o, w->body_pool.gen, s->bslots, 4);
    snap_array(o, w->body_pool.index, s->bslots, 4);
#define RG_FIELD_WRITE(T, name) snap_array(o, b->name, s->count, sizeof(T));
    RG_BODY_FIELDS(RG_FIELD_WRITE)
#undef RG_FIELD_WRITE
    snap_array(o, w->springs.pool.gen, s->sslots, 4);
    snap_array(o, w->springs.pool.index, s->sslots, 4);
    snap_pad(o);
    for (int32_t k = 0; k < s->springs; k++) {
        const spring *sp = &w->springs.items[k];
        snap_i32(o, sp->slot_a);
        snap_i32(o, sp->slot_b);
        snap_i32(o, sp->self_slot);
        snap_real(o, sp->anchor.x);
        snap_real(o, sp->anchor.y);
        snap_real(o, sp->rest);
        snap_real(o, sp->k);
        snap_real(o, sp->c);
    }
    snap_write_contacts(o, &cw->contacts);
    snap_array(o, cw->contacts.awake, s->n_awake, 4);
    snap_write_events(o, cw->events.ev, s->n_ev);
    snap_write_events(o, cw->events.pend, s->n_pend);
    snap_pad(o);
    for (int32_t k = 0; k < s->members; k++) {
        int32_t slot = cw->bp.members[k];
        const bp_entry *e = &cw->bp.e[slot];
        snap_i32(o, slot);
        snap_real(o, e->lx);
        snap_real(o, e->ly);
        snap_real(o, e->ux);
        snap_real(o, e->uy);
        snap_i32(o, e->next);
        snap_i32(o, e->prev);
        snap_i32(o, e->lnext);
        snap_i32(o, e->lprev);
        snap_i32(o, e->moved);
        snap_i32(o, e->apos);
    }
    snap_array(o, cw->bp.moved, s->n_moved, 4);
    snap_pad(o);
}

RG_API rg_status rg_world_save(const rg_world *world, void *out, size_t capacity, size_t *out_size)
{
    if (world == NULL || out_size == NULL || (out == NULL && capacity > 0)) return RG_ERR_INVALID_ARGUMENT;
    snap_scalars s;
    snap_layout l;
    snap_scalars_of(world, &s);
    snap_layout_of(&s, &l);
    *out_size = l.size;
    if (out == NULL && capacity == 0) return RG_OK;
    if (capacity < l.size) return RG_ERR_CAPACITY;
    uint8_t *p = out;
    memcpy(p, SNAP_MAGIC, 8);
    snap_put32(p + 8, SNAP_VERSION);
    snap_put32(p + 12, (uint32_t)sizeof(rg_real));
    snap_put64(p + 16, (uint64_t)l.size);
    snap_out o = { p, SNAP_HEADER, NULL, 0 };
    snap_write(world, &o, &s);
    snap_put64(p + 24, snap_hash(p + SNAP_HEADER, l.size - SNAP_HEADER));
    return RG_OK;
}

RG_API rg_status rg_world_hash(const rg_world *world, uint64_t *out_hash)
{
    if (world == NULL || out_hash == NULL) return RG_ERR_INVALID_ARGUMENT;
    snap_scalars s;
    snap_hasher h;
    snap_scalars_of(world, &s);
    snap_hash_init(&h);
    uint32_t real_size = (uint32_t)sizeof(rg_real);
    snap_hash_bytes(&h, &real_size, 4);
    snap_out o = { NULL, SNAP_HEADER, &h, 1 };
    snap_write(world, &o, &s);
    *out_hash = snap_hash_final(&h);
    return RG_OK;
}
