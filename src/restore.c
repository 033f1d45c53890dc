/* restore.c: rg_world_restore: a snapshot (snapshot.h) checked against every structural
 * invariant of the state while still in its buffer (restore_check.c), then loaded; one of
 * the world's own last saves, byte for byte (own.h), and a kept state (slots.c) are loaded
 * unchecked.  Nothing of the world changes until the snapshot is known good and every
 * allocation has succeeded. */
#include "body.h"
#include "broadphase.h"
#include "contact.h"
#include "error.h"
#include "events.h"
#include "snapshot.h"
#include "spring.h"
#include "task.h"
#include "vec2.h"
#include "restore_check.h"

/* ---------------------------------------------------------------- loading */

/* n elements of elem (4 or 8) bytes from the file's order into dst; stride 0 repeats one. */
static void restore_array(void *dst, const uint8_t *src, int32_t n, size_t elem, size_t stride)
{
    if (n <= 0) return;
    if (stride == 0) { /* one value for all: the same bits in every element, the first
                          * written and then copied in doubling runs */
        uint8_t *d = dst;
        if (elem == 8) {
            uint64_t u = snap_get64(src);
            memcpy(d, &u, 8);
        } else {
            uint32_t u = snap_get32(src);
            memcpy(d, &u, 4);
        }
        for (size_t done = elem, total = (size_t)n * elem; done < total;) {
            size_t run = done < total - done ? done : total - done;
            memcpy(d + done, d, run);
            done += run;
        }
        return;
    }
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
    restore_array(p->gen, in->p + gen, slots, 4, 4);
    restore_array(p->index, in->p + index, slots, 4, 4);
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

/* After the bodies: the contacts, their mixed materials from their bodies, the free list
 * in its order, the awake list and each contact's place in it (found through place[id],
 * scratch of ccap entries, so that the contacts are written in one pass by id: in ranges of
 * records, restore_load_range, between restore_contacts_start and _end). */
typedef struct restore_materials {
    int same; /* every body has the same: mu and e */
    rg_real mu, e;
} restore_materials;

static void restore_contacts_start(rg_world *w, const snap_in *in, int32_t *place, restore_materials *mat)
{
    contact_store *cs = &w->coll.contacts;
    const body_store *b = &w->b;
    const snap_scalars *s = &in->s;
    memset(place, 0xFF, (size_t)s->ccap * sizeof *place); /* -1: not awake */
    restore_array(cs->awake, in->p + in->l.awake, s->n_awake, 4, 4);
    for (int32_t k = 0; k < s->n_awake; k++) place[cs->awake[k]] = k;
    /* the mixed materials once for all when every body has the same */
    mat->same = in->l.stride[SNAP_F_mu] == 0 && in->l.stride[SNAP_F_rest] == 0 && b->count > 0;
    mat->mu = mat->same ? rg_sqrt(b->mu[0] * b->mu[0]) : 0;
    mat->e = mat->same ? b->rest[0] : 0;
}

static void restore_contacts_range(rg_world *w, const snap_in *in, const int32_t *place,
                                   const restore_materials *mat, int32_t k0, int32_t k1)
{
    /* what the loop reads of w and in in locals: a store into a contact may alias them */
    contact *cc = w->coll.contacts.c;
    const body_store *b = &w->b;
    const uint8_t *rec0 = rec(in, in->l.contacts, SNAP_CONTACT, 0);
    const int same = mat->same;
    const rg_real mu = mat->mu, e = mat->e;
    for (int32_t k = k0; k < k1; k++) {
        const uint8_t *p = rec0 + SNAP_CONTACT * (size_t)k;
        int32_t id = (int32_t)snap_get32(p);
        contact *c = &cc[id];
#if SNAP_NATIVE /* the record's runs where they lie in the struct (snapshot.h) */
        uint8_t *to = (uint8_t *)c;
        memcpy(to + offsetof(contact, sa), p + SNAP_CONTACT_LINKS, 6 * 4);
        memcpy(&c->flags, p + SNAP_CONTACT_FLAGS, 4);
        memcpy(to + offsetof(contact, nx), p + SNAP_CONTACT_REALS, 10 * SNAP_REAL);
#else
        snap_cursor q = { p + 4 };
        c->sa = cur_i32(&q);
        c->sb = cur_i32(&q);
        c->na = cur_i32(&q);
        c->pa = cur_i32(&q);
        c->nb = cur_i32(&q);
        c->pb = cur_i32(&q);
        c->flags = cur_u32(&q);
        c->nx = cur_real(&q);
        c->ny = cur_real(&q);
        c->px = cur_real(&q);
        c->py = cur_real(&q);
        c->s0 = cur_real(&q);
        c->vn0 = cur_real(&q);
        c->depth = cur_real(&q);
        c->speed = cur_real(&q);
        c->pn = cur_real(&q);
        c->pt = cur_real(&q);
#endif
        c->awake = place[id];
        c->toi = 0;
        c->decided = 0;
        if (same) {
            c->mu = mu;
            c->e = e;
            continue;
        }
        int32_t ia = body_dense(w, c->sa), ib = body_dense(w, c->sb);
        c->mu = rg_sqrt(b->mu[ia] * b->mu[ib]);
        c->e = rg_max(b->rest[ia], b->rest[ib]);
    }
}

static void restore_contacts_end(rg_world *w, const snap_in *in)
{
    contact_store *cs = &w->coll.contacts;
    const snap_scalars *s = &in->s;
    /* a free id holds what contact_destroy leaves that anything reads: no bodies, no links
     * but the free list's, no flags (its other fields are written whole when it is taken) */
    int32_t nfree = s->ccap - s->clive;
    for (int32_t k = 0; k < nfree; k++) {
        contact *c = &cs->c[rd_i32(in, in->l.free, k)];
        c->sa = c->sb = -1;
        c->na = k + 1 < nfree ? rd_i32(in, in->l.free, k + 1) : -1;
        c->pa = c->nb = c->pb = -1;
        c->awake = -1;
        c->flags = 0;
    }
    cs->cap = s->ccap;
    cs->live = s->clive;
    cs->free_head = nfree > 0 ? rd_i32(in, in->l.free, 0) : -1;
    cs->n_awake = s->n_awake;
    cs->n_touching = s->n_touching;
}

/* Members k0..k1-1; their levels and keys come from the checks (restore_check_broadphase)
 * or from a kept state's tail. */
static void restore_members_range(broadphase *bp, const snap_in *in, const restore_scratch *r, int32_t k0,
                                  int32_t k1)
{
    /* what the loop reads of bp, in and r in locals: a store into an entry may alias them */
    const int16_t *level = in->kept_level != NULL ? in->kept_level : r->level;
    const uint64_t *key = in->kept_key != NULL ? in->kept_key : r->key;
    const uint8_t *rec0 = rec(in, in->l.members, SNAP_MEMBER, 0);
    bp_entry *entries = bp->e;
    int32_t *members = bp->members;
    for (int32_t k = k0; k < k1; k++) {
        const uint8_t *p = rec0 + SNAP_MEMBER * (size_t)k;
        int32_t slot = (int32_t)snap_get32(p);
        bp_entry *e = &entries[slot];
#if SNAP_NATIVE /* the record's runs where they lie in the entry (snapshot.h) */
        uint8_t *to = (uint8_t *)e;
        memcpy(to + offsetof(bp_entry, lx), p + SNAP_MEMBER_BOX, 4 * SNAP_REAL);
        memcpy(to + offsetof(bp_entry, next), p + SNAP_MEMBER_LINKS, 4 * 4);
#else
        snap_member m;
        restore_member(in, k, &m);
        e->lx = m.lx;
        e->ly = m.ly;
        e->ux = m.ux;
        e->uy = m.uy;
        e->next = m.next;
        e->prev = m.prev;
        e->lnext = m.lnext;
        e->lprev = m.lprev;
#endif
        e->moved = (int16_t)snap_get32(p + SNAP_MEMBER_LINKS + 16);
        e->apos = (int32_t)snap_get32(p + SNAP_MEMBER_LINKS + 20);
        e->level = level[k];
        e->key = key[k];
        e->member = k;
        e->mark = 0;
        members[k] = slot;
    }
}

static void restore_broadphase_end(broadphase *bp, const snap_in *in)
{
    broadphase_restore_members(bp, in->s.members);
    restore_array(bp->moved, in->p + in->l.moved, in->s.n_moved, 4, 4);
    bp->n_moved = in->s.n_moved;
    bp->mark = in->s.mark;
}

/* The contacts (items [0, clive)) and the broadphase's members (the rest) on the task
 * system: every contact id and member slot is written by its one record (the checks, or
 * the world that kept the state, make them distinct). */
typedef struct restore_load_task {
    rg_world *w;
    const snap_in *in;
    const restore_scratch *r;
    restore_materials mat;
} restore_load_task;

static void restore_load_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    restore_load_task *t = context;
    int32_t nc = t->in->s.clive;
    (void)worker;
    if (begin < nc) restore_contacts_range(t->w, t->in, t->r->rec_of, &t->mat, begin, end < nc ? end : nc);
    if (end > nc) restore_members_range(&t->w->coll.bp, t->in, t->r, (begin > nc ? begin : nc) - nc, end - nc);
}

/* What the snapshot leaves out: inverse masses, flags (as body_update_flags makes them) and
 * the step's displacements.  Without branches (one per body mispredicts on a mix of types)
 * and on the reals' bits, in blocks of RESTORE_BLOCK (a loop of known length), then one by
 * one: so GCC vectorises them at -O2 (on compares of reals and a conversion of the type it
 * did not, -fopt-info-vec: "control flow in loop", "no vectype"). */
#define RESTORE_BLOCK 16

static inline real_sbits restore_bits(rg_real x)
{
    real_sbits u;
    memcpy(&u, &x, sizeof u);
    return u;
}

static inline rg_real restore_real(real_sbits u)
{
    rg_real x;
    memcpy(&x, &u, sizeof x);
    return x;
}

/* 1 / m for a dynamic body, else +0: the reciprocal of m or of 1, masked. */
static inline rg_real restore_inverse_mass(int32_t type, rg_real mass)
{
    real_sbits dynamic = -(real_sbits)(type == RG_BODY_DYNAMIC);
    real_sbits divisor = (restore_bits(mass) & dynamic) | (restore_bits(1) & ~dynamic);
    return restore_real(restore_bits(1 / restore_real(divisor)) & dynamic);
}

/* body_flags_from on the bits: x > 0 is the bits > 0 as a signed integer (a negative real,
 * -0 too, has the sign bit), x != 1 is bits other than 1's; for every real but NaN, which no
 * setter lets in and the checks refuse. */
static inline uint32_t restore_flags(int32_t type, rg_real drag_lin, rg_real drag_quad, rg_real fric,
                                     rg_real min_speed, rg_real max_speed, rg_real gscale)
{
    uint32_t dynamic = type == RG_BODY_DYNAMIC, moving = type != RG_BODY_STATIC;
    uint32_t lin = restore_bits(drag_lin) > 0, quad = restore_bits(drag_quad) > 0, fr = restore_bits(fric) > 0;
    uint32_t lo = restore_bits(min_speed) > 0, hi = restore_bits(max_speed) > 0;
    uint32_t magnitude = quad | fr, dissipative = magnitude | lin, limited = lo | hi;
    uint32_t gscaled = restore_bits(gscale) != restore_bits(1);
    return (dynamic & dissipative) * BODY_F_DISSIPATIVE | (dynamic & magnitude) * BODY_F_MAGNITUDE |
           (dynamic & limited) * BODY_F_LIMITED | (moving & gscaled) * BODY_F_GSCALE;
}

static void restore_flags_all(uint32_t *restrict flags, const int32_t *restrict type, const rg_real *restrict dl,
                              const rg_real *restrict dq, const rg_real *restrict fric, const rg_real *restrict lo,
                              const rg_real *restrict hi, const rg_real *restrict gs, int32_t n)
{
    int32_t i = 0;
    for (; n - i >= RESTORE_BLOCK; i += RESTORE_BLOCK)
        for (int k = 0; k < RESTORE_BLOCK; k++) {
            int32_t j = i + k;
            flags[j] = restore_flags(type[j], dl[j], dq[j], fric[j], lo[j], hi[j], gs[j]);
        }
    for (; i < n; i++) flags[i] = restore_flags(type[i], dl[i], dq[i], fric[i], lo[i], hi[i], gs[i]);
}

static void restore_inverse_masses(rg_real *restrict inv, const rg_real *restrict mass, const int32_t *restrict type,
                                   int32_t n)
{
    int32_t i = 0;
    for (; n - i >= RESTORE_BLOCK; i += RESTORE_BLOCK)
        for (int k = 0; k < RESTORE_BLOCK; k++) inv[i + k] = restore_inverse_mass(type[i + k], mass[i + k]);
    for (; i < n; i++) inv[i] = restore_inverse_mass(type[i], mass[i]);
}

static void restore_derived(rg_world *w)
{
    body_store *b = &w->b;
    const uint32_t *flags = b->flags;
    int32_t n = b->count;
    restore_flags_all(b->flags, b->type, b->drag_lin, b->drag_quad, b->fric, b->min_speed, b->max_speed, b->gscale, n);
    restore_inverse_masses(b->inv_mass, b->mass, b->type, n);
    uint32_t dissipative = 0, limited = 0, gscaled = 0, magnitude = 0;
#define RESTORE_COUNT(f)                               \
    dissipative += ((f) & BODY_F_DISSIPATIVE) != 0;    \
    limited += ((f) & BODY_F_LIMITED) != 0;            \
    gscaled += ((f) & BODY_F_GSCALE) != 0;             \
    magnitude += ((f) & BODY_F_MAGNITUDE) != 0;
    int32_t i = 0;
    for (; n - i >= RESTORE_BLOCK; i += RESTORE_BLOCK)
        for (int k = 0; k < RESTORE_BLOCK; k++) {
            RESTORE_COUNT(flags[i + k])
        }
    for (; i < n; i++) {
        RESTORE_COUNT(flags[i])
    }
#undef RESTORE_COUNT
    if (n > 0) {
        memset(b->dx, 0, (size_t)n * sizeof *b->dx);
        memset(b->dy, 0, (size_t)n * sizeof *b->dy);
    }
    w->dissipative_count = (int32_t)dissipative;
    w->limit_count = (int32_t)limited;
    w->gscale_count = (int32_t)gscaled;
    w->magnitude_count = (int32_t)magnitude;
}

static void restore_load(rg_world *w, const snap_in *in, const restore_scratch *r)
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
#define SNAP_FIELD_LOAD(T, name)                                                          \
    restore_array(b->name, in->p + in->l.field[f], s->count, sizeof(T), in->l.stride[f]); \
    f++;
    SNAP_BODY_FIELDS(SNAP_FIELD_LOAD)
#undef SNAP_FIELD_LOAD
    b->count = s->count;
    b->n_active = s->n_active;
    b->n_moving = s->n_moving;
    restore_derived(w);
    w->stopped_any = 0; /* the flags above hold no BODY_F_STOPPED: a restore is no step */
    w->forces_applied = 1; /* the snapshot's fx, fy may hold forces applied before its step */
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
    restore_load_task t;
    t.w = w;
    t.in = in;
    t.r = r;
    restore_contacts_start(w, in, r->rec_of, &t.mat); /* the checks are done with rec_of */
    task_for(w, restore_load_range, s->clive + s->members, 64, &t);
    restore_contacts_end(w, in);
    restore_broadphase_end(&cw->bp, in);
    event_store *es = &cw->events;
    restore_events(es->ev, in, in->l.ev, s->n_ev);
    restore_events(es->pend, in, in->l.pend, s->n_pend);
    es->n = es->base = s->n_ev;
    es->n_pend = s->n_pend;
    es->in_step = 0;
    cw->shape_count = s->members;
    cw->resolve.gen = 0;
    cw->resolve.pv_valid = 0;
    if (cw->resolve.sstamp != NULL) memset(cw->resolve.sstamp, 0, (size_t)cw->scap * sizeof *cw->resolve.sstamp);
}

/* ---------------------------------------------------------------- the call */

/* A snapshot whose checksum holds but whose state breaks an invariant: forged, or damaged
 * before it was sealed. */
static rg_status restore_refuse(const rg_world *w, const char *fn, const char *what)
{
    return error_set(w, RG_ERR_INVALID_ARGUMENT, fn,
                     "the snapshot's %s break the state's invariants (forged or damaged before it was sealed)", what);
}

/* The checks of the bodies, springs and events; the name of what breaks an invariant, or
 * NULL. */
static const char *restore_check_values(const snap_in *in)
{
    const snap_scalars *s = &in->s;
    if (!restore_check_pool(in, in->l.bgen, in->l.bindex, s->bslots, s->bmax_gen, s->bfree, s->count,
                            in->p + in->l.field[SNAP_F_slot], in->l.stride[SNAP_F_slot]))
        return "body handles";
    if (!restore_check_body_values(in)) return "bodies";
    if (!restore_check_springs(in)) return "springs";
    if (!restore_check_events(in, in->l.ev, s->n_ev) || !restore_check_events(in, in->l.pend, s->n_pend))
        return "events";
    return NULL;
}

/* A state this world wrote itself (a kept slot, or one of its own saves): of the scratch
 * the checks would fill, the load needs the members' places (and, but for a kept state,
 * whose tail holds them, their levels and keys: restore_locate_range). */
static void restore_fill_scratch(const snap_in *in, restore_scratch *r)
{
    memset(r->member_of, 0, (size_t)in->s.bslots * sizeof *r->member_of);
    for (int32_t k = 0; k < in->s.members; k++)
        r->member_of[(int32_t)snap_get32(rec(in, in->l.members, SNAP_MEMBER, k))] = k + 1;
}

/* Members begin..end-1's levels and keys from their boxes, as the checks compute them
 * (restore_links.c), in blocks gathered from the records. */
#define RESTORE_LOCATE 64
typedef struct restore_locate {
    const snap_in *in;
    restore_scratch *r;
} restore_locate;

static void restore_locate_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    const restore_locate *t = context;
    rg_real box[4 * RESTORE_LOCATE];
    (void)worker;
    for (int32_t k0 = begin; k0 < end; k0 += RESTORE_LOCATE) {
        int32_t n = end - k0 < RESTORE_LOCATE ? end - k0 : RESTORE_LOCATE;
        for (int32_t k = 0; k < n; k++) {
            const uint8_t *q = rec(t->in, t->in->l.members, SNAP_MEMBER, k0 + k) + SNAP_MEMBER_BOX;
            for (int j = 0; j < 4; j++) box[4 * k + j] = snap_get_real(q + (size_t)j * SNAP_REAL);
        }
        broadphase_locate_boxes(box, n, t->r->level + k0, t->r->key + k0);
    }
}

/* Checks the state's contacts and broadphase when it comes from outside (RESTORE_CHECKED;
 * the rest is checked before), then grows the world to hold it and loads it. */
static rg_status restore_state(rg_world *w, const char *fn, const snap_in *in, int checked)
{
    const snap_scalars *s = &in->s;
    const rg_mem *m = &w->mem;
    restore_scratch r;
    size_t rsize = 0;
    r.s = s;
    r.checked = checked;
    void *rblock = mem_block(m, restore_check_scratch_layout, &r, &rsize);
    if (rblock == NULL) return error_alloc(w, fn, RG_ERR_OUT_OF_MEMORY, "restore scratch", "RG_MAX_BODIES");
    rg_status st = RG_OK;
    if (checked == RESTORE_CHECKED) {
        memset(rblock, 0, r.zeroed);
        if (!restore_check_islands(in, &r))
            st = restore_refuse(w, fn, "bodies");
        else if (!restore_check_contacts(w, in, &r))
            st = restore_refuse(w, fn, "contacts");
        else if (!restore_check_broadphase(w, in, &r))
            st = restore_refuse(w, fn, "broadphase");
    } else {
        restore_fill_scratch(in, &r);
        if (checked == RESTORE_OWN) {
            restore_locate t = { in, &r };
            task_for(w, restore_locate_range, s->members, RESTORE_LOCATE, &t);
        }
    }
    /* room: growth keeps the world as it is; the contact storage (of exactly the saved
     * capacity, which decides the ids of new contacts) and the bucket table (of exactly the
     * saved size, which decides the chains) are made aside and taken at the end */
    if (st == RG_OK) st = pool_reserve_slots(&w->body_pool, m, s->bslots);
    if (st == RG_OK) st = body_reserve_count(w, s->count);
    if (st == RG_OK) st = pool_reserve_slots(&w->springs.pool, m, s->sslots);
    if (st == RG_OK) st = spring_reserve(w, s->springs);
    if (st == RG_OK && (s->members > 0 || s->bucket_bits > 0))
        st = broadphase_reserve_slots(&w->coll.bp, m, s->bslots);
    contact_block cb;
    if (st == RG_OK) st = contact_block_alloc(&cb, w, s->ccap, s->n_ev, s->n_pend);
    broadphase *bp = &w->coll.bp;
    size_t nb = s->bucket_bits > 0 ? (size_t)1 << s->bucket_bits : 0;
    int32_t *head = s->bucket_bits == bp->bucket_bits ? bp->head : NULL;
    if (st == RG_OK && s->bucket_bits != bp->bucket_bits && s->bucket_bits > 0) {
        head = mem_alloc(m, nb * sizeof *head);
        if (head == NULL) {
            contact_block_free(&cb, m);
            st = RG_ERR_OUT_OF_MEMORY;
        }
    }
    if (st == RG_ERR_OUT_OF_MEMORY || st == RG_ERR_CAPACITY)
        error_alloc(w, fn, st, "the restored world", "RG_MAX_BODIES");
    if (st == RG_OK) {
        /* nothing can fail from here on */
        contact_block_adopt(w, &cb);
        broadphase_clear(bp, m, head, s->bucket_bits, r.member_of, s->bslots); /* members to come: rewritten */
        restore_load(w, in, &r);
    }
    mem_free(m, rblock, rsize);
    return st;
}

/* The checksum (item 0) beside the checks of the settings, counts, bodies, springs and
 * events (item 1), which read the bytes and the scalars alone and write only `in`'s layout:
 * a checksum that fails is what rg_world_restore reports, whatever the checks found. */
typedef struct restore_first {
    snap_in *in;
    int sum_ok, scalars_ok;
    const char *bad;
} restore_first;

static void restore_first_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    restore_first *f = context;
    (void)worker;
    for (int32_t k = begin; k < end; k++) {
        if (k == 0) {
            f->sum_ok = restore_check_sum(f->in);
            continue;
        }
        f->scalars_ok = restore_check_scalars(f->in);
        f->bad = f->scalars_ok ? restore_check_values(f->in) : NULL;
    }
}

rg_status restore_kept(rg_world *w, const void *data, size_t size)
{
    snap_in in;
    memset(&in, 0, sizeof in);
    /* the world wrote it: the header and scalars are checked all the same (they cost
     * nothing), the rest is known good */
    if (!restore_check_header(w, &in, data, size, 0)) return RG_ERR_INVALID_ARGUMENT;
    if (!restore_check_scalars(&in)) return restore_refuse(w, "rg_world_restore_slot", "settings and counts");
    const uint8_t *tail = in.p + size; /* snapshot.h: snap_kept_tail_size */
    in.kept_key = (const uint64_t *)(const void *)tail;
    in.kept_level = (const int16_t *)(const void *)(tail + (size_t)in.s.members * sizeof(uint64_t));
    return restore_state(w, "rg_world_restore_slot", &in, RESTORE_KEPT);
}

static rg_status restore_locked(rg_world *world, const void *data, size_t size);

RG_API rg_status rg_world_restore(rg_world *world, const void *data, size_t size)
{
    WORLD_WRITABLE(world);
    if (data == NULL) return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "data is NULL");
    WORLD_LOCK(world); /* the allocator and the task system may call on it */
    rg_status st = restore_locked(world, data, size);
    WORLD_UNLOCK(world);
    if (st == RG_OK) ERROR_CLEAR(world); /* a callback's failed call is not this call's */
    return st;
}

static rg_status restore_locked(rg_world *world, const void *data, size_t size)
{
    snap_in in;
    memset(&in, 0, sizeof in);
    if (!restore_check_header(world, &in, data, size, 1)) return RG_ERR_INVALID_ARGUMENT;
    if (own_knows(world->own, in.p, size, snap_get64(in.p + OWN_HEAD))) { /* the world's own: as a kept state */
        if (!restore_check_scalars(&in)) return restore_refuse(world, "rg_world_restore", "settings and counts");
        rg_status st = restore_state(world, "rg_world_restore", &in, RESTORE_OWN);
        if (st == RG_OK) own_arm(world->own);
        return st;
    }
    restore_first f;
    f.in = &in;
    task_for(world, restore_first_range, 2, 1, &f);
    if (!f.sum_ok) return error_set(world, RG_ERR_INVALID_ARGUMENT, "rg_world_restore", "checksum mismatch (the snapshot is corrupted)");
    if (!f.scalars_ok) return restore_refuse(world, "rg_world_restore", "settings and counts");
    if (f.bad != NULL) return restore_refuse(world, "rg_world_restore", f.bad);
    rg_status st = restore_state(world, "rg_world_restore", &in, RESTORE_CHECKED);
    if (st == RG_OK) own_arm(world->own); /* a world that restores: its saves are tagged (own.h) */
    return st;
}
