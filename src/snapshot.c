/* snapshot.c: the snapshot writer (rg_world_save), the state hash (rg_world_hash) and the
 * format's layout (see snapshot.h; its hash function: snap_hash.c). */
#include "error.h"
#include "snapshot.h"

typedef char snap_checksum_ends_the_header[OWN_HEAD + 8 == SNAP_HEADER ? 1 : -1]; /* own.h */

#define SNAP_COUNT(T, name) +1
typedef char snap_fields_are_all_there[(0 RG_BODY_FIELDS(SNAP_COUNT)) == SNAP_FIELDS + SNAP_DERIVED_FIELDS ? 1 : -1];
#undef SNAP_COUNT

/* ---------------------------------------------------------------- the writer */

size_t snap_scalars_size(void)
{
    /* 10 reals, 2 doubles, 1 uint64, the rest 4-byte words: see snap_write_scalars */
    return 10 * SNAP_REAL + 2 * 8 + 8 + 36 * 4;
}

/* Where the stream goes: a buffer (save) or a hash (hash), which takes it in chunks.  A
 * save hashes its buffer as it goes (the checksum, and the keyed tags by which the world
 * knows it again: own.h), a few KB behind the writer, so that the bytes are hashed while
 * they are still in the cache. */
#define SNAP_CHUNK 4096
#define SNAP_HASH_BEHIND (4 * SNAP_CHUNK)
typedef struct snap_out {
    uint8_t *buf;
    size_t at;
    size_t hashed;      /* save: bytes of buf hashed so far */
    snap_hasher *hash;  /* NULL: a kept state (slots.c), written unsealed */
    keyed_hasher *keyed; /* a save's keyed tags, or NULL */
    int anonymous;      /* the world tag left out (rg_world_hash) */
    const int *uniform; /* per body field: all its values equal */
    uint64_t *kept_key; /* a kept state's tail (snap_kept_tail_size), or NULL */
    int16_t *kept_level;
    size_t nchunk;
    uint8_t chunk[SNAP_CHUNK];
} snap_out;

/* A save's bytes written since the last call into its hashes. */
static void snap_hash_behind(snap_out *o)
{
    snap_hash_bytes(o->hash, o->buf + o->hashed, o->at - o->hashed);
    if (o->keyed != NULL) keyed_bytes(o->keyed, o->buf + o->hashed, o->at - o->hashed);
    o->hashed = o->at;
}

static void snap_flush(snap_out *o)
{
    snap_hash_bytes(o->hash, o->chunk, o->nchunk);
    o->nchunk = 0;
}

static void snap_emit(snap_out *o, const void *p, size_t n)
{
    o->at += n;
    if (o->buf != NULL) {
        memcpy(o->buf + o->at - n, p, n);
        if (o->hash != NULL && o->at - o->hashed >= SNAP_HASH_BEHIND) snap_hash_behind(o);
        return;
    }
    if (o->nchunk + n > SNAP_CHUNK) snap_flush(o);
    if (n > SNAP_CHUNK) {
        snap_hash_bytes(o->hash, p, n);
        return;
    }
    memcpy(o->chunk + o->nchunk, p, n);
    o->nchunk += n;
}

/* Room for a record of n (at most SNAP_CHUNK) bytes, to be written in place: in the buffer
 * (then hashed behind the writer as snap_emit does) or in the chunk. */
static uint8_t *snap_record(snap_out *o, size_t n)
{
    if (o->buf != NULL) {
        if (o->hash != NULL && o->at - o->hashed >= SNAP_HASH_BEHIND) snap_hash_behind(o);
        o->at += n;
        return o->buf + o->at - n;
    }
    if (o->nchunk + n > SNAP_CHUNK) snap_flush(o);
    o->at += n;
    o->nchunk += n;
    return o->chunk + o->nchunk - n;
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

/* Whether the n values of elem bytes at p are all equal, bit for bit: each equal to the
 * next (memcmp stops at the first difference). */
static int snap_uniform(const void *p, int32_t n, size_t elem)
{
    const uint8_t *q = p;
    return n > 0 && memcmp(q, q + elem, (size_t)(n - 1) * elem) == 0;
}

/* A body field: its uniformity word, then one element or all n. */
static void snap_field(snap_out *o, const void *p, int32_t n, size_t elem, int uniform)
{
    snap_pad(o);
    snap_u32(o, (uint32_t)uniform);
    snap_array(o, p, uniform ? 1 : n, elem);
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
    s->n_awake = cw->contacts.n_awake;
    s->n_touching = cw->contacts.n_touching;
    s->n_ev = cw->events.n;
    s->n_pend = cw->events.n_pend;
    s->members = cw->bp.count;
    s->bucket_bits = cw->bp.head != NULL ? cw->bp.bucket_bits : 0;
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
        uint8_t r[SNAP_EVENT], *q = r;
        snap_put64(q, snap_handle(o, e[k].a));
        snap_put64(q + 8, snap_handle(o, e[k].b));
        q += 16;
        const rg_real reals[6] = { e[k].normal.x, e[k].normal.y, e[k].point.x, e[k].point.y, e[k].depth, e[k].speed };
        for (int f = 0; f < 6; f++) snap_put_real(q + SNAP_REAL * (size_t)f, reals[f]);
        q += 6 * SNAP_REAL;
        snap_put32(q, (uint32_t)e[k].kind);
        snap_put32(q + 4, (uint32_t)e[k].sensor);
        snap_emit(o, r, SNAP_EVENT);
    }
}

/* The live contacts by ascending id (a free id has sa = -1, contact.c), then the free ids
 * in the order of the free list. */
static void snap_write_contacts(snap_out *o, const contact_store *cs)
{
    snap_pad(o);
    for (int32_t k = 0; k < cs->cap; k++) {
        const contact *c = &cs->c[k];
        if (c->sa < 0) continue;
        uint8_t *q = snap_record(o, SNAP_CONTACT);
#if SNAP_NATIVE
        const uint8_t *from = (const uint8_t *)c;
        memcpy(q, &k, 4);
        memcpy(q + SNAP_CONTACT_LINKS, from + offsetof(contact, sa), 6 * 4);
        memcpy(q + SNAP_CONTACT_FLAGS, &c->flags, 4);
        memcpy(q + SNAP_CONTACT_REALS, from + offsetof(contact, nx), 10 * SNAP_REAL);
#else
        const int32_t ints[8] = { k, c->sa, c->sb, c->na, c->pa, c->nb, c->pb, (int32_t)c->flags };
        for (int f = 0; f < 8; f++) snap_put32(q + 4 * f, (uint32_t)ints[f]);
        q += 32;
        const rg_real reals[10] = { c->nx, c->ny, c->px, c->py, c->s0, c->vn0, c->depth, c->speed, c->pn, c->pt };
        for (int f = 0; f < 10; f++) snap_put_real(q + SNAP_REAL * (size_t)f, reals[f]);
#endif
    }
    snap_pad(o);
    for (int32_t id = cs->free_head; id >= 0; id = cs->c[id].na) snap_i32(o, id);
}

static void snap_write(const rg_world *w, snap_out *o, const snap_scalars *s)
{
    const body_store *b = &w->b;
    const collide_world *cw = &w->coll;
    snap_write_scalars(o, s);
    snap_array(o, w->body_pool.gen, s->bslots, 4);
    snap_array(o, w->body_pool.index, s->bslots, 4);
    int field = 0;
#define SNAP_FIELD_WRITE(T, name) snap_field(o, b->name, s->count, sizeof(T), o->uniform[field++]);
    SNAP_BODY_FIELDS(SNAP_FIELD_WRITE)
#undef SNAP_FIELD_WRITE
    snap_array(o, w->springs.pool.gen, s->sslots, 4);
    snap_array(o, w->springs.pool.index, s->sslots, 4);
    snap_pad(o);
    for (int32_t k = 0; k < s->springs; k++) {
        const spring *sp = &w->springs.items[k];
        uint8_t r[SNAP_SPRING], *q = r;
        snap_put32(q, (uint32_t)sp->slot_a);
        snap_put32(q + 4, (uint32_t)sp->slot_b);
        snap_put32(q + 8, (uint32_t)sp->self_slot);
        q += 12;
        const rg_real reals[5] = { sp->anchor.x, sp->anchor.y, sp->rest, sp->k, sp->c };
        for (int f = 0; f < 5; f++) snap_put_real(q + SNAP_REAL * (size_t)f, reals[f]);
        snap_emit(o, r, SNAP_SPRING);
    }
    snap_write_contacts(o, &cw->contacts);
    snap_array(o, cw->contacts.awake, s->n_awake, 4);
    snap_write_events(o, cw->events.ev, s->n_ev);
    snap_write_events(o, cw->events.pend, s->n_pend);
    snap_pad(o);
    for (int32_t k = 0; k < s->members; k++) {
        int32_t slot = cw->bp.members[k];
        const bp_entry *e = &cw->bp.e[slot];
        uint8_t *q = snap_record(o, SNAP_MEMBER);
        snap_put32(q, (uint32_t)slot);
#if SNAP_NATIVE
        const uint8_t *from = (const uint8_t *)e;
        memcpy(q + SNAP_MEMBER_BOX, from + offsetof(bp_entry, lx), 4 * SNAP_REAL);
        memcpy(q + SNAP_MEMBER_LINKS, from + offsetof(bp_entry, next), 4 * 4);
        snap_put32(q + SNAP_MEMBER_LINKS + 16, (uint32_t)(int32_t)e->moved);
        snap_put32(q + SNAP_MEMBER_LINKS + 20, (uint32_t)e->apos);
#else
        q += 4;
        snap_put_real(q, e->lx);
        snap_put_real(q + SNAP_REAL, e->ly);
        snap_put_real(q + 2 * SNAP_REAL, e->ux);
        snap_put_real(q + 3 * SNAP_REAL, e->uy);
        q += 4 * SNAP_REAL;
        const int32_t ints[6] = { e->next, e->prev, e->lnext, e->lprev, e->moved, e->apos };
        for (int f = 0; f < 6; f++) snap_put32(q + 4 * f, (uint32_t)ints[f]);
#endif
        if (o->kept_key != NULL) {
            o->kept_key[k] = e->key;
            o->kept_level[k] = e->level;
        }
    }
    snap_array(o, cw->bp.moved, s->n_moved, 4);
    snap_pad(o);
}

/* Which body fields are uniform. */
static void snap_uniforms(const rg_world *w, int *uniform)
{
    const body_store *b = &w->b;
    int f = 0;
#define SNAP_FIELD_UNIFORM(T, name) uniform[f++] = snap_uniform(b->name, b->count, sizeof(T));
    SNAP_BODY_FIELDS(SNAP_FIELD_UNIFORM)
#undef SNAP_FIELD_UNIFORM
}

/* The size of the snapshot, from its counts and uniform fields. */
static size_t snap_size(const snap_scalars *s, const int *uniform)
{
    size_t at = SNAP_HEADER + snap_scalars_size();
#define SNAP_ADD(n, elem) at = ((at + 7u) & ~(size_t)7u) + (size_t)(n) * (elem)
    SNAP_ADD(s->bslots, 4);
    SNAP_ADD(s->bslots, 4);
    int f = 0;
#define SNAP_FIELD_SIZE(T, name)                  \
    SNAP_ADD(1, 4);                               \
    SNAP_ADD(uniform[f] ? 1 : s->count, sizeof(T)); \
    f++;
    SNAP_BODY_FIELDS(SNAP_FIELD_SIZE)
#undef SNAP_FIELD_SIZE
    SNAP_ADD(s->sslots, 4);
    SNAP_ADD(s->sslots, 4);
    SNAP_ADD(s->springs, SNAP_SPRING);
    SNAP_ADD(s->clive, SNAP_CONTACT);
    SNAP_ADD(s->ccap - s->clive, 4);
    SNAP_ADD(s->n_awake, 4);
    SNAP_ADD(s->n_ev, SNAP_EVENT);
    SNAP_ADD(s->n_pend, SNAP_EVENT);
    SNAP_ADD(s->members, SNAP_MEMBER);
    SNAP_ADD(s->n_moved, 4);
#undef SNAP_ADD
    return (at + 7u) & ~(size_t)7u;
}

void snap_plan_of(const rg_world *w, snap_plan *plan)
{
    snap_scalars_of(w, &plan->s);
    snap_uniforms(w, plan->uniform);
    plan->size = snap_size(&plan->s, plan->uniform);
}

size_t snap_kept_tail_size(const snap_plan *plan)
{
    size_t n = (size_t)plan->s.members;
    return (n * (sizeof(uint64_t) + sizeof(int16_t)) + 7u) & ~(size_t)7u;
}

void snap_write_planned(const rg_world *w, const snap_plan *plan, uint8_t *p, int sealed)
{
    memcpy(p, SNAP_MAGIC, 8);
    snap_put32(p + 8, SNAP_VERSION);
    snap_put32(p + 12, (uint32_t)sizeof(rg_real));
    snap_put64(p + 16, (uint64_t)plan->size);
    snap_put64(p + 24, 0);
    snap_hasher h;
    snap_hash_init(&h);
    keyed_hasher kh;
    snap_out o;
    o.keyed = NULL;
    if (sealed && own_tagging(w->own)) { /* a world that restores: own.h */
        keyed_init(&kh, &w->own->key);
        own_header(&kh, p);
        o.keyed = &kh;
    }
    o.buf = p;
    o.at = SNAP_HEADER;
    o.hashed = SNAP_HEADER;
    o.hash = sealed ? &h : NULL;
    o.anonymous = 0;
    o.uniform = plan->uniform;
    o.nchunk = 0;
    /* the tail: p and plan->size are multiples of 8, the allocator's blocks aligned */
    o.kept_key = sealed ? NULL : (uint64_t *)(void *)(p + plan->size);
    o.kept_level = sealed ? NULL : (int16_t *)(void *)(p + plan->size + (size_t)plan->s.members * sizeof(uint64_t));
    snap_write(w, &o, &plan->s);
    if (!sealed) return;
    snap_hash_bytes(&h, p + o.hashed, plan->size - o.hashed);
    uint64_t sum = snap_hash_final(&h); /* = snap_hash(p + SNAP_HEADER, size - SNAP_HEADER) */
    snap_put64(p + 24, sum);
    if (o.keyed == NULL) return;
    keyed_bytes(o.keyed, p + o.hashed, plan->size - o.hashed);
    own_remember(w->own, o.keyed, (uint64_t)plan->size, sum);
}

RG_API rg_status rg_world_save(const rg_world *world, void *out, size_t capacity, size_t *out_size)
{
    ERROR_BEGIN(world);
    if (out_size == NULL) return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "out_size is NULL");
    if (out == NULL && capacity > 0)
        return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "out is NULL with capacity %lu", (unsigned long)capacity);
    snap_plan plan;
    snap_plan_of(world, &plan);
    *out_size = plan.size;
    if (out == NULL && capacity == 0) return RG_OK;
    if (capacity < plan.size)
        return RG_FAIL(world, RG_ERR_CAPACITY, "capacity %lu is below the snapshot's size %lu", (unsigned long)capacity,
                       (unsigned long)plan.size);
    snap_write_planned(world, &plan, out, 1);
    return RG_OK;
}

RG_API rg_status rg_world_hash(const rg_world *world, uint64_t *out_hash)
{
    ERROR_BEGIN(world);
    if (out_hash == NULL) return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "out_hash is NULL");
    snap_scalars s;
    snap_hasher h;
    int uniform[SNAP_FIELDS];
    snap_scalars_of(world, &s);
    snap_uniforms(world, uniform);
    snap_hash_init(&h);
    snap_out o;
    o.buf = NULL;
    o.at = SNAP_HEADER;
    o.hashed = 0;
    o.hash = &h;
    o.keyed = NULL;
    o.anonymous = 1;
    o.uniform = uniform;
    o.nchunk = 0;
    o.kept_key = NULL;
    o.kept_level = NULL;
    uint8_t real_size[4];
    snap_put32(real_size, (uint32_t)sizeof(rg_real));
    snap_emit(&o, real_size, 4);
    snap_write(world, &o, &s);
    snap_flush(&o);
    *out_hash = snap_hash_final(&h);
    return RG_OK;
}
