/* contact.c: the collide stage (see contact.h) and the collision API of bodies and world. */
#include <string.h>

#include "collision.h"
#include "contact.h"
#include "vec2.h"
#include "world.h"

#define DEFAULT_FRICTION RG_R(0.6)
/* Fat boxes grow by a margin of FAT_FRACTION of the shape's larger half extent, at least the
 * slop (so that two touching shapes held apart by up to the slop keep their contact) and at
 * most FAT_MARGIN.  A small margin keeps pairs few: neighbours a tenth of their size apart
 * (a settled pile, a spawn grid) are no contact until the look-ahead of their motion brings
 * them closer; it costs more refreshes only for bodies that drift without moving, which
 * sleep. */
#ifndef FAT_MARGIN
#define FAT_MARGIN       RG_R(0.1)  /* m */
#endif
#ifndef FAT_FRACTION
#define FAT_FRACTION     RG_R(0.02)
#endif
#ifndef LOOKAHEAD
#define LOOKAHEAD        RG_R(4)    /* fat boxes reach this many steps of motion ahead */
#endif
#define SPECULATIVE      RG_R(4)    /* solve pairs predicted within SPECULATIVE * slop */
#define COS45            RG_R(0.70710678)
/* per contact: stage, hgt, hgx, ord, tord, map, over, color, imp, key, tkey; then the wide rows */
#define SORT_BYTES (sizeof(solver_constraint) + 2 * sizeof(rg_real) + 6 * sizeof(int32_t) + 2 * sizeof(uint16_t))
#define SORT_SIZE(cap) ((size_t)(cap) * SORT_BYTES + 64 + (size_t)SOLVER_WIDE_ROWS(cap) * sizeof(solver_wide))

static inline int32_t dense_of(const rg_world *w, int32_t slot)
{
    return pool_dense(&w->body_pool, slot);
}

static inline int32_t other_of(const contact *c, int32_t slot) { return c->sa == slot ? c->sb : c->sa; }
static inline int32_t next_of(const contact *c, int32_t slot) { return c->sa == slot ? c->na : c->nb; }

static inline void set_next(contact *c, int32_t slot, int32_t v)
{
    if (c->sa == slot) c->na = v; else c->nb = v;
}

static inline void set_prev(contact *c, int32_t slot, int32_t v)
{
    if (c->sa == slot) c->pa = v; else c->pb = v;
}

/* ---------------------------------------------------------------- storage */

void contact_init(rg_world *w)
{
    contact_world *cw = &w->coll;
    memset(cw, 0, sizeof *cw);
    cw->free_head = -1;
    cw->iterations = 8;
    cw->position = 3;
    cw->sleeping = 1;
    cw->sleep_speed = RG_R(0.05);
    cw->sleep_time = RG_R(0.5);
    cw->continuous = 1;
    cw->slop = RG_R(0.005);
    cw->bias_rate = RG_R(0.2);
    cw->max_push = RG_R(2);
    cw->restitution_threshold = RG_R(1);
}

/* Per-body scratch: 10 reals and 9 int32 per body, and the body views. */
static size_t scratch_block_size(int32_t n)
{
    return (size_t)n * (10 * sizeof(rg_real) + 9 * sizeof(int32_t) + sizeof(cbody)) + 64;
}

void contact_release(rg_world *w)
{
    contact_world *cw = &w->coll;
    const rg_mem *m = &w->mem;
    broadphase_release(&cw->bp, m);
    mem_free(m, cw->c, (size_t)cw->cap * sizeof *cw->c);
    mem_free(m, cw->awake, (size_t)cw->cap * sizeof *cw->awake);
    mem_free(m, cw->ev, (size_t)cw->ev_cap * sizeof *cw->ev);
    mem_free(m, cw->pend, (size_t)cw->cap * sizeof *cw->pend);
    if (cw->cap > 0) mem_free(m, cw->batch.rows, SORT_SIZE(cw->cap));
    mem_free(m, cw->cb, scratch_block_size(cw->scap));
    cw->c = NULL;
    cw->cap = 0;
}

/* Events one step can produce with contact capacity cap: ends of the contacts touching when
 * it starts (found gone or updated), ends reported between steps (pend, at most cap) and
 * begins of the contacts touching when it ends: 3 * cap. */
#define STEP_EVENTS(cap) (3 * (int64_t)(cap))

/* Doubles contact storage (contacts, awake list, solver rows, events); all-or-nothing.  The
 * event buffer keeps the events held and room for the current step at the new capacity. */
static rg_status contact_grow(rg_world *w)
{
    contact_world *cw = &w->coll;
    const rg_mem *m = &w->mem;
    int32_t old = cw->cap;
    if (old > INT32_MAX / 8) return RG_ERR_CAPACITY;
    int32_t cap = old < 256 ? 256 : old * 2;
    int64_t need = (int64_t)cw->ev_base + STEP_EVENTS(cap);
    if (need > INT32_MAX) return RG_ERR_CAPACITY;
    int32_t ev_cap = cw->ev_cap > need ? cw->ev_cap : (int32_t)need;
    contact *c = mem_alloc(m, (size_t)cap * sizeof *c);
    int32_t *awake = mem_alloc(m, (size_t)cap * sizeof *awake);
    size_t ev_size = mem_array_size((size_t)ev_cap, sizeof(rg_contact_event));
    rg_contact_event *ev = ev_size > 0 ? mem_alloc(m, ev_size) : NULL;
    rg_contact_event *pend = mem_alloc(m, (size_t)cap * sizeof *pend);
    char *sortbuf = mem_alloc(m, SORT_SIZE(cap));
    if (c == NULL || awake == NULL || ev == NULL || pend == NULL || sortbuf == NULL) {
        mem_free(m, sortbuf, SORT_SIZE(cap));
        mem_free(m, c, (size_t)cap * sizeof *c);
        mem_free(m, awake, (size_t)cap * sizeof *awake);
        mem_free(m, ev, ev_size);
        mem_free(m, pend, (size_t)cap * sizeof *pend);
        return RG_ERR_OUT_OF_MEMORY;
    }
    if (old > 0) {
        memcpy(c, cw->c, (size_t)old * sizeof *c);
        memcpy(awake, cw->awake, (size_t)cw->n_awake * sizeof *awake);
        memcpy(pend, cw->pend, (size_t)cw->n_pend * sizeof *pend);
    }
    if (cw->n_ev > 0) memcpy(ev, cw->ev, (size_t)cw->n_ev * sizeof *ev);
    mem_free(m, cw->c, (size_t)old * sizeof *cw->c);
    mem_free(m, cw->awake, (size_t)old * sizeof *cw->awake);
    mem_free(m, cw->ev, (size_t)cw->ev_cap * sizeof *cw->ev);
    mem_free(m, cw->pend, (size_t)old * sizeof *cw->pend);
    if (old > 0) mem_free(m, cw->batch.rows, SORT_SIZE(old));
    /* the wide rows first, for their alignment */
    cw->batch.rows = (solver_wide *)(void *)sortbuf;
    cw->stage = (solver_constraint *)(void *)(cw->batch.rows + SOLVER_WIDE_ROWS(cap));
    cw->hgt = (rg_real *)(void *)(cw->stage + cap);
    cw->hgx = cw->hgt + cap;
    cw->ord = (int32_t *)(void *)(cw->hgx + cap);
    cw->tord = cw->ord + cap;
    cw->batch.map = cw->tord + cap;
    cw->batch.over = cw->batch.map + cap;
    cw->color = cw->batch.over + cap;
    cw->imp = cw->color + cap;
    cw->key = (uint16_t *)(void *)(cw->imp + cap);
    cw->tkey = cw->key + cap;
    cw->c = c;
    cw->awake = awake;
    cw->ev = ev;
    cw->ev_cap = ev_cap;
    cw->pend = pend;
    cw->cap = cap;
    /* new ids on the free list, lowest first */
    for (int32_t id = cap - 1; id >= old; id--) {
        memset(&c[id], 0, sizeof c[id]);
        c[id].na = cw->free_head;
        c[id].awake = -1;
        cw->free_head = id;
    }
    return RG_OK;
}

rg_status contact_prepare(rg_world *w)
{
    contact_world *cw = &w->coll;
    if (cw->shape_count == 0) return RG_OK;
    int32_t n = w->b.capacity + 1;
    if (cw->scap >= n) return RG_OK;
    size_t size = scratch_block_size(n);
    char *p = mem_alloc(&w->mem, size);
    if (p == NULL) return RG_ERR_OUT_OF_MEMORY;
    mem_free(&w->mem, cw->cb, scratch_block_size(cw->scap));
    size_t r = (size_t)n * sizeof(rg_real), q = (size_t)n * sizeof(int32_t);
    cw->cb = (cbody *)(void *)p; p += (size_t)n * sizeof(cbody);
    cw->sx0 = (rg_real *)(void *)p; p += r;
    cw->sy0 = (rg_real *)(void *)p; p += r;
    cw->svx0 = (rg_real *)(void *)p; p += r;
    cw->svy0 = (rg_real *)(void *)p; p += r;
    cw->umin = (rg_real *)(void *)p; p += r;
    cw->sv = (rg_real *)(void *)p; p += 2 * r;
    cw->spv = (rg_real *)(void *)p; p += 2 * r;
    cw->stoi = (rg_real *)(void *)p; p += r;
    cw->adense = (int32_t *)(void *)p; p += q;
    cw->sidx = (int32_t *)(void *)p; p += q;
    cw->sstamp = (uint32_t *)(void *)p; p += q;
    cw->sbody = (int32_t *)(void *)p; p += q;
    cw->uf = (int32_t *)(void *)p; p += q;
    cw->ihead = (int32_t *)(void *)p; p += q;
    cw->itail = (int32_t *)(void *)p; p += q;
    cw->list = (int32_t *)(void *)p; p += q;
    cw->cmask = (uint32_t *)(void *)p;
    memset(cw->sstamp, 0, q);
    cw->gen = 0;
    cw->scap = n;
    return RG_OK;
}

int contact_stage_needed(const rg_world *w)
{
    const contact_world *cw = &w->coll;
    return cw->shape_count > 0 || cw->n_pend > 0;
}

void contact_events_clear(rg_world *w)
{
    w->coll.n_ev = 0;
    w->coll.ev_base = 0;
}

rg_status contact_events_reserve(rg_world *w)
{
    contact_world *cw = &w->coll;
    int64_t need = (int64_t)cw->n_ev + STEP_EVENTS(cw->cap);
    if (need <= cw->ev_cap) return RG_OK;
    if (need > INT32_MAX) return RG_ERR_OUT_OF_MEMORY;
    /* grow by half again at least, so a run of busy advances reallocates only a few times */
    int64_t want = (int64_t)cw->ev_cap + cw->ev_cap / 2;
    int32_t cap = (int32_t)(want > need && want <= INT32_MAX ? want : need);
    size_t size = mem_array_size((size_t)cap, sizeof(rg_contact_event));
    rg_contact_event *ev = size > 0 ? mem_alloc(&w->mem, size) : NULL;
    if (ev == NULL) return RG_ERR_OUT_OF_MEMORY;
    if (cw->n_ev > 0) memcpy(ev, cw->ev, (size_t)cw->n_ev * sizeof *ev);
    mem_free(&w->mem, cw->ev, (size_t)cw->ev_cap * sizeof *cw->ev);
    cw->ev = ev;
    cw->ev_cap = cap;
    return RG_OK;
}

/* ---------------------------------------------------------------- contacts */

static void awake_add(contact_world *cw, int32_t id)
{
    cw->c[id].awake = cw->n_awake;
    cw->awake[cw->n_awake++] = id;
}

static void awake_remove(contact_world *cw, int32_t id)
{
    int32_t k = cw->c[id].awake, last = cw->awake[--cw->n_awake];
    cw->awake[k] = last;
    cw->c[last].awake = k;
    cw->c[id].awake = -1;
}

static void emit(rg_world *w, const contact *c, int32_t kind)
{
    contact_world *cw = &w->coll;
    rg_contact_event *e = cw->in_step ? &cw->ev[cw->n_ev++] : &cw->pend[cw->n_pend++];
    e->a = pool_handle(&w->body_pool, c->sa);
    e->b = pool_handle(&w->body_pool, c->sb);
    e->normal = rg_v2(c->nx, c->ny);
    e->point = rg_v2(c->px, c->py);
    e->depth = c->depth;
    e->speed = c->speed;
    e->kind = kind;
    e->sensor = (c->flags & CT_SENSOR) != 0;
}

static void list_link(rg_world *w, int32_t id, int32_t slot)
{
    contact_world *cw = &w->coll;
    int32_t i = dense_of(w, slot);
    int32_t head = w->b.chead[i] - 1;
    set_prev(&cw->c[id], slot, -1);
    set_next(&cw->c[id], slot, head);
    if (head >= 0) set_prev(&cw->c[head], slot, id);
    w->b.chead[i] = id + 1;
}

static void list_unlink(rg_world *w, int32_t id, int32_t slot)
{
    contact_world *cw = &w->coll;
    contact *c = &cw->c[id];
    int32_t next = c->sa == slot ? c->na : c->nb;
    int32_t prev = c->sa == slot ? c->pa : c->pb;
    if (prev >= 0)
        set_next(&cw->c[prev], slot, next);
    else
        w->b.chead[dense_of(w, slot)] = next + 1;
    if (next >= 0) set_prev(&cw->c[next], slot, prev);
}

/* A new contact between slots s and t, or -1 when memory runs out. */
static int32_t contact_create(rg_world *w, int32_t s, int32_t t)
{
    contact_world *cw = &w->coll;
    if (cw->free_head < 0 && contact_grow(w) != RG_OK) return -1;
    if (pool_handle(&w->body_pool, s) > pool_handle(&w->body_pool, t)) {
        int32_t tmp = s;
        s = t;
        t = tmp;
    }
    const body_store *b = &w->b;
    int32_t id = cw->free_head;
    contact *c = &cw->c[id];
    cw->free_head = c->na;
    cw->live++;
    int32_t ia = dense_of(w, s), ib = dense_of(w, t);
    memset(c, 0, sizeof *c);
    c->sa = s;
    c->sb = t;
    c->awake = -1;
    c->flags = ((b->cflags[ia] | b->cflags[ib]) & CF_SENSOR) ? CT_SENSOR : 0;
    c->mu = rg_sqrt(b->mu[ia] * b->mu[ib]);
    c->e = rg_max(b->rest[ia], b->rest[ib]);
    list_link(w, id, s);
    list_link(w, id, t);
    if (ia < b->n_active || ib < b->n_active) awake_add(cw, id);
    return id;
}

static void contact_destroy(rg_world *w, int32_t id)
{
    contact_world *cw = &w->coll;
    contact *c = &cw->c[id];
    if (c->flags & CT_TOUCHING) {
        emit(w, c, RG_CONTACT_END);
        cw->n_touching--;
    }
    list_unlink(w, id, c->sa);
    list_unlink(w, id, c->sb);
    if (c->awake >= 0) awake_remove(cw, id);
    c->flags = 0;
    c->na = cw->free_head;
    cw->free_head = id;
    cw->live--;
}

/* ---------------------------------------------------------------- sleeping */

static void wake_island(rg_world *w, int32_t i)
{
    contact_world *cw = &w->coll;
    body_store *b = &w->b;
    if (body_partition(w, i) != BODY_PART_ASLEEP) return;
    int32_t s = b->isl_head[i] - 1;
    if (s < 0) s = b->slot[i]; /* not in a list: wake it alone */
    while (s >= 0) {
        int32_t j = dense_of(w, s);
        int32_t next = b->isl_next[j] - 1;
        b->isl_head[j] = 0;
        b->isl_next[j] = 0;
        b->sleep_t[j] = 0;
        b->dx[j] = 0;
        b->dy[j] = 0;
        b->cflags[j] &= ~CF_GROUNDED;
        if (body_partition(w, j) == BODY_PART_ASLEEP) j = body_move_to_partition(w, j, BODY_PART_ACTIVE);
        if (b->shape[j] != RG_SHAPE_NONE) broadphase_activate(&cw->bp, s);
        for (int32_t id = b->chead[j] - 1; id >= 0; id = next_of(&cw->c[id], s))
            if (cw->c[id].awake < 0) awake_add(cw, id);
        s = next;
    }
}

static void wake_all(rg_world *w)
{
    while (w->b.n_moving > w->b.n_active) wake_island(w, w->b.n_active);
}

/* Wakes the sleeping bodies that touch slot's body (it moved, changed or goes away). */
static void wake_touching(rg_world *w, int32_t slot)
{
    contact_world *cw = &w->coll;
    int32_t id = w->b.chead[dense_of(w, slot)] - 1;
    while (id >= 0) {
        const contact *c = &cw->c[id];
        int32_t next = next_of(c, slot);
        int32_t j = dense_of(w, other_of(c, slot));
        if (body_partition(w, j) == BODY_PART_ASLEEP) wake_island(w, j);
        id = next;
    }
}

static int32_t find_root(int32_t *uf, int32_t i)
{
    while (uf[i] != i) {
        uf[i] = uf[uf[i]];
        i = uf[i];
    }
    return i;
}

static void unite(int32_t *uf, int32_t a, int32_t b)
{
    a = find_root(uf, a);
    b = find_root(uf, b);
    /* the lower index becomes the root: deterministic */
    if (a < b) uf[b] = a; else if (b < a) uf[a] = b;
}

/* Islands: dynamic bodies joined by touching solid contacts and springs.  An island whose
 * every body rested (speed below sleep_speed) for sleep_time falls asleep as a whole.  The
 * union-find runs over the awake shaped bodies (their places in the broadphase's active
 * list), so bodies without shapes, static and sleeping ones cost nothing here. */
static void sleep_islands(rg_world *w, rg_real dt, int united)
{
    contact_world *cw = &w->coll;
    body_store *b = &w->b;
    broadphase *bp = &cw->bp;
    int32_t na = bp->n_active;
    int32_t *uf = cw->uf;
    rg_real thr2 = cw->sleep_speed * cw->sleep_speed;
    int any = 0, near = 0;
    const rg_real *pv = cw->spv;
    int pv_valid = cw->pv_valid;
    cw->pv_valid = 0;
    for (int32_t k = 0; k < na; k++) {
        int32_t i = dense_of(w, bp->active[k]);
        if (b->type[i] != RG_BODY_DYNAMIC) continue;
        rg_real v2 = b->vx[i] * b->vx[i] + b->vy[i] * b->vy[i];
        /* a body still being pushed out of a penetration is not at rest either */
        if (pv_valid && cw->sstamp[i] == cw->gen) {
            int32_t q = cw->sidx[i];
            v2 = rg_max(v2, pv[2 * q] * pv[2 * q] + pv[2 * q + 1] * pv[2 * q + 1]);
        }
        rg_real t = v2 < thr2 ? b->sleep_t[i] + dt : 0;
        b->sleep_t[i] = t;
        any |= t >= cw->sleep_time;
        near |= t + 2 * dt >= cw->sleep_time;
    }
    /* the narrowphase joins islands only when some body is about to fall asleep */
    cw->near_sleep = near;
    if (!any) return;
    if (!united) {
        for (int32_t k = 0; k < na; k++) uf[k] = k;
        for (int32_t k = 0; k < cw->n_awake; k++) {
            const contact *c = &cw->c[cw->awake[k]];
            if ((c->flags & (CT_TOUCHING | CT_SENSOR)) != CT_TOUCHING) continue;
            int32_t pa = bp->e[c->sa].apos, pb = bp->e[c->sb].apos;
            if (pa < 0 || pb < 0) continue;
            if (b->type[dense_of(w, c->sa)] == RG_BODY_DYNAMIC && b->type[dense_of(w, c->sb)] == RG_BODY_DYNAMIC)
                unite(uf, pa, pb);
        }
    }
    /* island minimum of the rest time; kinematic bodies do not take part */
    rg_real *umin = cw->umin;
    for (int32_t k = 0; k < na; k++) umin[k] = RG_HUGE;
    for (int32_t k = 0; k < w->springs.count; k++) {
        const spring *sp = &w->springs.items[k];
        if (sp->slot_b < 0) continue;
        int32_t ia = dense_of(w, sp->slot_a), ib = dense_of(w, sp->slot_b);
        if (b->type[ia] != RG_BODY_DYNAMIC || b->type[ib] != RG_BODY_DYNAMIC) continue;
        int32_t pa = sp->slot_a < bp->cap ? bp->e[sp->slot_a].apos : -1;
        int32_t pb = sp->slot_b < bp->cap ? bp->e[sp->slot_b].apos : -1;
        if (pa >= 0 && pb >= 0) {
            unite(uf, pa, pb);
        } else {
            /* tied to a body that moves without a shape, or to a sleeping one: awake */
            int a_moving = pa < 0 && ia < b->n_active, b_moving = pb < 0 && ib < b->n_active;
            int a_asleep = body_partition(w, ia) == BODY_PART_ASLEEP;
            int b_asleep = body_partition(w, ib) == BODY_PART_ASLEEP;
            if (pa >= 0 && (b_moving || b_asleep)) umin[pa] = -1;
            if (pb >= 0 && (a_moving || a_asleep)) umin[pb] = -1;
        }
    }
    for (int32_t k = 0; k < na; k++) {
        if (umin[k] < 0) umin[find_root(uf, k)] = 0;
    }
    for (int32_t k = 0; k < na; k++) {
        int32_t i = dense_of(w, bp->active[k]);
        if (b->type[i] != RG_BODY_DYNAMIC) continue;
        int32_t r = find_root(uf, k);
        if (b->sleep_t[i] < umin[r]) umin[r] = b->sleep_t[i];
    }
    /* link each sleeping island's members, in active-list order */
    int32_t *head = cw->ihead, *tail = cw->itail, *list = cw->list;
    int32_t count = 0;
    for (int32_t k = 0; k < na; k++) head[k] = -1;
    for (int32_t k = 0; k < na; k++) {
        int32_t s = bp->active[k];
        int32_t i = dense_of(w, s);
        if (b->type[i] != RG_BODY_DYNAMIC) continue;
        int32_t r = find_root(uf, k);
        if (!(umin[r] >= cw->sleep_time)) continue;
        if (head[r] < 0) {
            head[r] = s;
        } else {
            b->isl_next[dense_of(w, tail[r])] = s + 1;
        }
        tail[r] = s;
        b->isl_head[i] = head[r] + 1;
        b->isl_next[i] = 0;
        list[count++] = s;
    }
    if (count == 0) return;
    for (int32_t k = 0; k < count; k++) {
        int32_t i = dense_of(w, list[k]);
        b->vx[i] = b->vy[i] = 0;
        b->dx[i] = b->dy[i] = 0;
        body_move_to_partition(w, i, BODY_PART_ASLEEP);
        broadphase_deactivate(bp, list[k]);
    }
    /* contacts with no awake body leave the awake list */
    for (int32_t k = 0; k < count; k++) {
        int32_t s = list[k];
        for (int32_t id = b->chead[dense_of(w, s)] - 1; id >= 0; id = next_of(&cw->c[id], s)) {
            contact *c = &cw->c[id];
            if (c->awake < 0) continue;
            if (dense_of(w, c->sa) >= b->n_active && dense_of(w, c->sb) >= b->n_active)
                awake_remove(cw, id);
        }
    }
}

/* ---------------------------------------------------------------- broadphase upkeep */

static inline rg_real fat_margin(const contact_world *cw, const body_store *b, int32_t i)
{
    return rg_min(FAT_MARGIN, rg_max(cw->slop, FAT_FRACTION * rg_max(b->hx[i], b->hy[i])));
}

/* The fat box of a body at rest: its box grown by the margin. */
static void rest_box(const contact_world *cw, const body_store *b, int32_t i, rg_real box[4])
{
    rg_real m = fat_margin(cw, b, i);
    box[0] = b->x[i] - b->hx[i] - m;
    box[1] = b->y[i] - b->hy[i] - m;
    box[2] = b->x[i] + b->hx[i] + m;
    box[3] = b->y[i] + b->hy[i] + m;
}

static inline int box_inside(const bp_entry *e, rg_real lx, rg_real ly, rg_real ux, rg_real uy)
{
    return lx >= e->lx && ly >= e->ly && ux <= e->ux && uy <= e->uy;
}

/* Refreshes the fat box of active body i from its box [l, u], a displacement (mx, my) and
 * its change over the last step (ax, ay) to look ahead by, when the box [l, u] left the fat
 * box, or when the body's pairs are to be searched anyway (new, teleported: its fat box is
 * then the box at rest, which has no look-ahead yet); marks it moved. */
static void refresh_fat_now(rg_world *w, int32_t i, rg_real lx, rg_real ly, rg_real ux, rg_real uy,
                            rg_real mx, rg_real my, rg_real ax, rg_real ay)
{
    broadphase *bp = &w->coll.bp;
    int32_t slot = w->b.slot[i];
    rg_real m = fat_margin(&w->coll, &w->b, i);
    mx *= LOOKAHEAD;
    my *= LOOKAHEAD;
    ax = mx + ax * (LOOKAHEAD * (LOOKAHEAD + 1) / 2);
    ay = my + ay * (LOOKAHEAD * (LOOKAHEAD + 1) / 2);
    rg_real flx = rg_min(lx, rg_min(lx + mx, lx + ax)) - m, fly = rg_min(ly, rg_min(ly + my, ly + ay)) - m;
    rg_real fux = rg_max(ux, rg_max(ux + mx, ux + ax)) + m, fuy = rg_max(uy, rg_max(uy + my, uy + ay)) + m;
    broadphase_move(bp, slot, flx, fly, fux, fuy);
    broadphase_mark_moved(bp, slot);
}

/* The test inline, the refresh out of line: most bodies stay inside their fat box. */
static inline void refresh_fat(rg_world *w, int32_t i, rg_real lx, rg_real ly, rg_real ux, rg_real uy,
                               rg_real mx, rg_real my, rg_real ax, rg_real ay)
{
    const bp_entry *e = &w->coll.bp.e[w->b.slot[i]];
    if (!e->moved && box_inside(e, lx, ly, ux, uy)) return;
    refresh_fat_now(w, i, lx, ly, ux, uy, mx, my, ax, ay);
}

/* ---------------------------------------------------------------- pairs */

typedef struct pair_ctx {
    rg_world *w;
    int32_t s, is;
    uint32_t mark;    /* the bodies s has a contact with carry it */
    int teleported;
    int failed;
    int woke;
} pair_ctx;

static int pair_admitted(const body_store *b, int32_t i, int32_t j)
{
    int32_t ti = b->type[i], tj = b->type[j];
    int sensor = ((b->cflags[i] | b->cflags[j]) & CF_SENSOR) != 0;
    if (ti != RG_BODY_DYNAMIC && tj != RG_BODY_DYNAMIC) {
        if (!sensor || (ti == RG_BODY_STATIC && tj == RG_BODY_STATIC)) return 0;
    }
    return (b->cat[i] & b->mask[j]) != 0 && (b->cat[j] & b->mask[i]) != 0;
}

static void pair_visit(void *p, int32_t t)
{
    pair_ctx *q = p;
    rg_world *w = q->w;
    contact_world *cw = &w->coll;
    int32_t s = q->s;
    if (t == s) return;
    bp_entry *et = &cw->bp.e[t];
    if (et->moved && t < s) return;     /* t's own query finds the pair */
    if (et->mark == q->mark) return;    /* s has a contact with t */
    const body_store *b = &w->b;
    int32_t it = dense_of(w, t);
    if (!pair_admitted(b, q->is, it)) return;
    if (contact_create(w, s, t) < 0) {
        q->failed = 1;
        return;
    }
    et->mark = q->mark;
    /* a teleported body landing on a sleeping one wakes it */
    if (q->teleported && body_partition(w, it) == BODY_PART_ASLEEP) {
        wake_island(w, it);
        q->is = dense_of(w, s);
        q->woke = 1;
    }
}

/* Searches the pairs of the moved bodies; returns 1 when that woke sleeping bodies. */
static int find_pairs(rg_world *w)
{
    contact_world *cw = &w->coll;
    broadphase *bp = &cw->bp;
    int32_t n = bp->n_moved, kept = 0;
    int woke = 0;
    for (int32_t k = 0; k < n; k++) {
        int32_t s = bp->moved[k];
        const bp_entry *e = &bp->e[s];
        /* contacts whose fat boxes no longer overlap end; the others' bodies are marked,
         * so the query knows its existing pairs in O(1) */
        uint32_t mark = broadphase_new_mark(bp);
        for (int32_t id = w->b.chead[dense_of(w, s)] - 1; id >= 0;) {
            int32_t next = next_of(&cw->c[id], s), t = other_of(&cw->c[id], s);
            if (!broadphase_overlap(bp, s, t))
                contact_destroy(w, id);
            else
                bp->e[t].mark = mark;
            id = next;
        }
        pair_ctx q;
        q.w = w;
        q.s = s;
        q.mark = mark;
        q.is = dense_of(w, s);
        q.teleported = (w->b.cflags[q.is] & CF_TELEPORTED) != 0;
        q.failed = 0;
        q.woke = 0;
        broadphase_query(bp, e->lx, e->ly, e->ux, e->uy, pair_visit, &q);
        woke |= q.woke;
        if (q.failed)
            bp->e[s].moved = 2; /* out of memory: search again next step */
        else
            w->b.cflags[dense_of(w, s)] &= ~CF_TELEPORTED;
    }
    for (int32_t k = 0; k < n; k++) {
        int32_t s = bp->moved[k];
        if (bp->e[s].moved == 2) {
            bp->e[s].moved = 1;
            bp->moved[kept++] = s;
        } else {
            bp->e[s].moved = 0;
        }
    }
    bp->n_moved = kept;
    return woke;
}

/* ---------------------------------------------------------------- narrowphase */

static int pusher(const body_store *b, int32_t j, int touching)
{
    if (b->type[j] == RG_BODY_DYNAMIC) return touching;
    return b->type[j] == RG_BODY_KINEMATIC && (b->vx[j] != 0 || b->vy[j] != 0);
}

/* Grounded flag of a body with gravity scale gs touching a surface whose normal, pointing
 * toward the body, is (nx, ny): the normal points against its gravity within 45 degrees. */
static inline int is_ground(rg_real gx, rg_real gy, rg_real gs, rg_real nx, rg_real ny)
{
    rg_real ex = gx * gs, ey = gy * gs;
    rg_real up = -(nx * ex + ny * ey);
    rg_real g2 = ex * ex + ey * ey;
    return g2 > 0 && up > 0 && up * up >= COS45 * COS45 * g2;
}

/* What the narrowphase hands on: solver rows staged in contact order with their sort keys,
 * and whether it woke anything (then the rows are rebuilt). */
typedef struct narrow_ctx {
    int32_t n;          /* active bodies when the stage started (those with a body view) */
    int32_t na;         /* awake shaped bodies then (the island list's range) */
    int32_t nc;         /* staged rows */
    int32_t ns;         /* solver bodies, 0 being the ground */
    int32_t nimp;       /* staged impact rows (cw->imp) */
    int woke;
    int unite;          /* join islands (sleeping is near) */
    solver_params p;
} narrow_ctx;

/* Solver index of dense body i: the ground (0) unless it is awake; awake bodies get
 * consecutive indices in the order rows meet them, so the solver's arrays cover the bodies
 * in contact and nothing else. */
static inline int32_t solver_index(contact_world *cw, int32_t i, int32_t n, narrow_ctx *x)
{
    if (i >= n) return 0;
    if (cw->sstamp[i] != cw->gen) {
        cw->sstamp[i] = cw->gen;
        cw->sidx[i] = ++x->ns;
        cw->sbody[x->ns] = i;
    }
    return cw->sidx[i];
}

/* The step's view of body i: start position, displacement, velocity, half extents.  Awake
 * bodies come from the per-step cache, the others rest: no displacement, no velocity. */
static inline const cbody *body_view(const rg_world *w, int32_t i, int32_t n, cbody *o)
{
    if (i < n) return &w->coll.cb[i];
    const body_store *b = &w->b;
    o->sx = b->x[i];
    o->sy = b->y[i];
    o->dx = o->dy = o->vx = o->vy = 0;
    o->hx = b->hx[i];
    o->hy = b->hy[i];
    o->gs = o->im = 0;
    o->kind = b->shape[i];
    return o;
}

/* Whether a pair that is not touching is too far apart for the narrowphase below to solve
 * it or find it touching, so it can be skipped with the same result.  The gap G between the
 * two boxes at the start bounds every separation that test takes from below: the manifold's
 * (a circle lies in its box) unless a box grazes (then the separation is the gap along one
 * axis, within slop of zero: excluded), and a time of impact needs |r| >= G.  The test solves
 * when s0 - reach < SPECULATIVE * slop with reach <= |dA| + |dB| (1-norms bound both), and
 * finds touching only when s0 <= |r|.  The margin covers the rounding of the exact tests:
 * slop, and a few ulps of the coordinates. */
static inline int far_apart(const cbody *A, const cbody *B, int32_t ka, int32_t kb, rg_real slop)
{
    rg_real gx = rg_fabs(B->sx - A->sx) - (A->hx + B->hx);
    rg_real gy = rg_fabs(B->sy - A->sy) - (A->hy + B->hy);
    rg_real reach = rg_fabs(A->dx) + rg_fabs(A->dy) + rg_fabs(B->dx) + rg_fabs(B->dy);
    rg_real ulps = (rg_fabs(A->sx) + rg_fabs(A->sy) + rg_fabs(B->sx) + rg_fabs(B->sy) + reach +
                    A->hx + A->hy + B->hx + B->hy) * (64 * RG_EPSILON);
    rg_real need = reach + (SPECULATIVE + 1) * slop + ulps;
    if (!(rg_max(gx, gy) >= need)) return 0; /* also NaN */
    /* a box may graze along an axis whose gap is within slop of zero */
    if (ka == RG_SHAPE_CIRCLE && kb == RG_SHAPE_CIRCLE) return 1;
    return rg_fabs(gx) > slop && rg_fabs(gy) > slop;
}

/* Updates contact id from the step's motion (the broadphase keeps only pairs whose fat
 * boxes overlap): manifold at the start of the step or at the time of impact, touching
 * state and events, grounded flags, islands, waking, and the solver row. */
static void narrow_one(rg_world *w, int32_t id, narrow_ctx *x)
{
    contact_world *cw = &w->coll;
    body_store *b = &w->b;
    contact *c = &cw->c[id];
    int32_t ia = dense_of(w, c->sa), ib = dense_of(w, c->sb);
    cbody rest_a, rest_b;
    const cbody *A = body_view(w, ia, x->n, &rest_a), *B = body_view(w, ib, x->n, &rest_b);
    int32_t ka = A->kind, kb = B->kind;
    rg_vec2 ha = rg_v2(A->hx, A->hy), hb = rg_v2(B->hx, B->hy);
    rg_vec2 r = rg_v2(B->dx - A->dx, B->dy - A->dy); /* b's motion relative to a over the step */
    if (cw->continuous && !(c->flags & CT_TOUCHING) && far_apart(A, B, ka, kb, cw->slop)) {
        /* what the full test below would conclude: not solved, not touching */
        c->flags &= ~(CT_SOLVE | CT_CLOSING);
        c->pn = c->pt = 0;
        return;
    }
    coll_manifold m;
    rg_real s0 = RG_HUGE;
    int active = 1;
    if (!cw->continuous) {
        /* discrete: the shapes where the step left them, extrapolated back */
        coll_manifold_of(ka, rg_v2(A->sx + A->dx, A->sy + A->dy), ha, kb, rg_v2(B->sx + B->dx, B->sy + B->dy), hb, &m);
        s0 = -m.depth - rg_v2_dot(r, m.normal);
    } else {
        if (ka == RG_SHAPE_CIRCLE && kb == RG_SHAPE_CIRCLE) {
            /* the common case inline: two circles at the start of the step */
            rg_real ex = B->sx - A->sx, ey = B->sy - A->sy;
            rg_real dist = rg_sqrt(ex * ex + ey * ey);
            rg_real nx = 0, ny = 1;
            if (dist > 0) {
                rg_real inv = 1 / dist;
                nx = ex * inv;
                ny = ey * inv;
            }
            m.normal = rg_v2(nx, ny);
            s0 = dist - ha.x - hb.x;
            rg_real f = ha.x + RG_R(0.5) * s0; /* halfway between the surfaces, from a */
            m.point = rg_v2(A->sx + nx * f, A->sy + ny * f);
        } else {
            coll_contact(ka, rg_v2(A->sx, A->sy), ha, kb, rg_v2(B->sx, B->sy), hb, r, cw->slop, &m);
            s0 = -m.depth;
        }
        /* apart at the start and fast (moving more than half the smaller shape): the time
         * of impact instead */
        rg_real size = rg_min(rg_min(ha.x, ha.y), rg_min(hb.x, hb.y));
        if (s0 > cw->slop && !(r.x * r.x + r.y * r.y <= RG_R(0.25) * size * size)) {
            rg_real t;
            if (coll_sweep(ka, rg_v2(A->sx, A->sy), ha, kb, rg_v2(B->sx, B->sy), hb, r, &t, &m))
                s0 = t > 0 ? -t * rg_v2_dot(r, m.normal) : -m.depth;
            else
                active = 0;
        }
    }
    uint32_t was = c->flags & CT_TOUCHING, now = 0;
    c->flags &= ~(CT_SOLVE | CT_CLOSING);
    if (active) {
        rg_real nx = m.normal.x, ny = m.normal.y;
        rg_real vn0 = (B->vx - A->vx) * nx + (B->vy - A->vy) * ny;
        rg_real d = s0 + r.x * nx + r.y * ny; /* predicted separation */
        /* touching: the step ends with the pair in contact (the free motion closes the gap,
         * which the solver then holds); a slop of hysteresis keeps resting pairs steady */
        if (d <= 0 || (was && d < cw->slop)) now = CT_TOUCHING;
        c->nx = nx;
        c->ny = ny;
        c->px = m.point.x;
        c->py = m.point.y;
        c->s0 = s0;
        c->vn0 = vn0;
        if (d < 0) c->flags |= CT_CLOSING;
        /* solved when the pair could close within the step: not only by the free motion
         * (d), but also when the solver stops either body (an impact below it) while the
         * other moves on, so each body's own motion toward the other counts */
        rg_real reach = rg_fabs(A->dx * nx + A->dy * ny) + rg_fabs(B->dx * nx + B->dy * ny);
        if (!(c->flags & CT_SENSOR) && s0 - reach < SPECULATIVE * cw->slop && rg_finite(s0) &&
            rg_finite(vn0)) {
            int32_t n = x->n;
            rg_real ima = A->im, imb = B->im;
            if (ima + imb > 0) {
                c->flags |= CT_SOLVE;
                solver_constraint *q = &cw->stage[x->nc];
                cw->hgt[x->nc] = m.point.y; /* replaced by the height along gravity */
                cw->hgx[x->nc] = m.point.x;
                q->a = solver_index(cw, ia, n, x);
                q->b = solver_index(cw, ib, n, x);
                q->ima = ima;
                q->imb = imb;
                q->nx = nx;
                q->ny = ny;
                q->m = 1 / (ima + imb);
                q->mu = c->mu;
                q->s0 = s0;
                q->vmin = solver_vmin(s0, vn0, c->e, d < 0, &x->p);
                /* An impact: the free motion closes the gap of a pair that was apart, at
                 * the fraction toi of the step (solve decides whether to time it).  A pair
                 * in contact (touching after the last step, or overlapping) has toi 0: it
                 * may carry weight or pass on an impulse at any moment of the step.  A pair
                 * apart that the free motion does not close has toi -1. */
                rg_real toi = was || s0 <= 0 ? 0 : -1;
                if (d < 0) toi = s0 > 0 && !was ? s0 / (s0 - d) : 0;
                if (toi > 0) cw->imp[x->nimp++] = x->nc;
                q->toi = c->toi = toi;
                q->pn = c->pn;
                q->pt = c->pt;
                q->cid = id;
                x->nc++;
            }
        }
    }
    if (!(c->flags & CT_SOLVE)) c->pn = c->pt = 0;
    if (now != was) {
        c->flags ^= CT_TOUCHING;
        if (now) {
            c->depth = rg_max(-c->s0, 0);
            c->speed = rg_max(-c->vn0, 0);
            cw->n_touching++;
            emit(w, c, RG_CONTACT_BEGIN);
        } else {
            cw->n_touching--;
            emit(w, c, RG_CONTACT_END);
        }
    }
    if (c->flags & CT_SENSOR) return;
    if (now) {
        if (A->gs != 0 && is_ground(w->gravity.x, w->gravity.y, A->gs, -c->nx, -c->ny))
            b->cflags[ia] |= CF_GROUNDED;
        if (B->gs != 0 && is_ground(w->gravity.x, w->gravity.y, B->gs, c->nx, c->ny))
            b->cflags[ib] |= CF_GROUNDED;
        if (x->unite) {
            int32_t pa = cw->bp.e[c->sa].apos, pb = cw->bp.e[c->sb].apos;
            if (pa >= 0 && pb >= 0 && pa < x->na && pb < x->na && b->type[ia] == RG_BODY_DYNAMIC &&
                b->type[ib] == RG_BODY_DYNAMIC)
                unite(cw->uf, pa, pb);
        }
    }
    /* a sleeping body (dense index past the awake ones) touched by a pusher wakes */
    if ((now | was) && (ia >= b->n_active || ib >= b->n_active)) {
        int pa_ = body_partition(w, ia), pb_ = body_partition(w, ib);
        if (pa_ == BODY_PART_ASLEEP && pb_ == BODY_PART_ACTIVE && pusher(b, ib, now != 0)) {
            wake_island(w, ia);
            x->woke = 1;
        } else if (pb_ == BODY_PART_ASLEEP && pa_ == BODY_PART_ACTIVE && pusher(b, ia, now != 0)) {
            wake_island(w, ib);
            x->woke = 1;
        }
    }
}

/* ---------------------------------------------------------------- the stage */

void contact_begin(rg_world *w)
{
    contact_world *cw = &w->coll;
    if (cw->shape_count == 0) return;
    const broadphase *bp = &cw->bp;
    const body_store *b = &w->b;
    for (int32_t k = 0; k < bp->n_active; k++) {
        int32_t i = dense_of(w, bp->active[k]);
        cw->adense[k] = i;
        cw->sx0[k] = b->x[i];
        cw->sy0[k] = b->y[i];
        cw->svx0[k] = b->vx[i];
        cw->svy0[k] = b->vy[i];
    }
}

static int event_less(const rg_contact_event *p, const rg_contact_event *q)
{
    if (p->a != q->a) return p->a < q->a;
    if (p->b != q->b) return p->b < q->b;
    return p->kind > q->kind; /* an end before a begin */
}

static void sift_down(rg_contact_event *e, int32_t root, int32_t n)
{
    for (;;) {
        int32_t child = 2 * root + 1;
        if (child >= n) return;
        if (child + 1 < n && event_less(&e[child], &e[child + 1])) child++;
        if (!event_less(&e[root], &e[child])) return;
        rg_contact_event t = e[root];
        e[root] = e[child];
        e[child] = t;
        root = child;
    }
}

/* Heapsort: in place, no allocation; (a, b, kind) is unique within a step. */
static void sort_events(rg_contact_event *e, int32_t n)
{
    for (int32_t i = n / 2 - 1; i >= 0; i--) sift_down(e, i, n);
    for (int32_t i = n - 1; i > 0; i--) {
        rg_contact_event t = e[0];
        e[0] = e[i];
        e[i] = t;
        sift_down(e, 0, i);
    }
}

/* Post-solve safety net: a body whose whole motion this step (integration, contacts and
 * position correction) exceeds half its size is swept from its start to where the step left
 * it against the static, kinematic and sleeping shapes it has contacts with; if the path
 * crosses one, the body stops just short of the first impact and loses its velocity into it.
 * The solver's time-of-impact rows normally make this a no-op; it catches what an
 * unconverged solve (a light body crushed by a far heavier one) would push through. */
static void clamp_fast(rg_world *w, int32_t na)
{
    contact_world *cw = &w->coll;
    body_store *b = &w->b;
    for (int32_t k = 0; k < na; k++) {
        int32_t i = cw->adense[k];
        if (b->type[i] != RG_BODY_DYNAMIC) continue;
        rg_vec2 p0 = rg_v2(cw->sx0[k], cw->sy0[k]), p1 = rg_v2(b->x[i], b->y[i]);
        rg_vec2 D = rg_v2_sub(p1, p0), hf = rg_v2(b->hx[i], b->hy[i]);
        rg_real h = rg_min(hf.x, hf.y);
        if (!(D.x * D.x + D.y * D.y > RG_R(0.25) * h * h)) continue;
        int32_t s = b->slot[i];
        rg_real tmin = 1;
        rg_vec2 nbest = rg_v2(0, 0), vbest = rg_v2(0, 0);
        for (int32_t id = b->chead[i] - 1; id >= 0; id = next_of(&cw->c[id], s)) {
            const contact *c = &cw->c[id];
            if (c->flags & CT_SENSOR) continue;
            int32_t j = dense_of(w, other_of(c, s));
            int active = j < b->n_active;
            if (b->type[j] == RG_BODY_DYNAMIC && active) continue;
            rg_vec2 ho = rg_v2(b->hx[j], b->hy[j]);
            rg_vec2 o1 = rg_v2(b->x[j], b->y[j]);
            rg_vec2 dob = active ? rg_v2(b->dx[j], b->dy[j]) : rg_v2(0, 0);
            rg_vec2 o0 = rg_v2_sub(o1, dob);
            rg_real t;
            coll_manifold hit, end;
            if (!coll_sweep(b->shape[j], o0, ho, b->shape[i], p0, hf, rg_v2_sub(D, dob), &t, &hit)) continue;
            if (!(t > 0 && t < tmin)) continue;
            coll_manifold_of(b->shape[j], o1, ho, b->shape[i], p1, hf, &end);
            if (end.depth >= 0 && end.depth <= cw->slop) continue; /* resting at the end */
            tmin = t;
            nbest = hit.normal;
            vbest = active ? rg_v2(b->vx[j], b->vy[j]) : rg_v2(0, 0);
        }
        if (tmin >= 1) continue;
        rg_real len = rg_v2_len(D);
        rg_real tb = len > 0 ? rg_max(tmin - RG_R(0.5) * cw->slop / len, 0) : 0;
        b->x[i] = p0.x + D.x * tb;
        b->y[i] = p0.y + D.y * tb;
        rg_real vn = (b->vx[i] - vbest.x) * nbest.x + (b->vy[i] - vbest.y) * nbest.y;
        if (vn < 0) {
            b->vx[i] -= vn * nbest.x;
            b->vy[i] -= vn * nbest.y;
        }
    }
}

/* LSD radix sort of n (key, value) pairs by 16-bit key, two passes of 8 bits; stable. */
static void radix_sort16(uint16_t *key, int32_t *val, uint16_t *tkey, int32_t *tval, int32_t n)
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

/* Rows staged again from the contacts flagged CT_SOLVE, after the narrowphase woke bodies
 * (their indices and the ground index changed). */
/* A new generation of solver indices (stamps of the old one no longer match). */
static void next_gen(contact_world *cw)
{
    if (++cw->gen == 0) {
        memset(cw->sstamp, 0, (size_t)cw->scap * sizeof *cw->sstamp);
        cw->gen = 1;
    }
}

static void restage(rg_world *w, narrow_ctx *x)
{
    contact_world *cw = &w->coll;
    const body_store *b = &w->b;
    int32_t n = b->n_active, nc = 0;
    next_gen(cw);
    x->ns = 0;
    x->nimp = 0;
    for (int32_t k = 0; k < cw->n_awake; k++) {
        int32_t id = cw->awake[k];
        contact *c = &cw->c[id];
        if (!(c->flags & CT_SOLVE)) continue;
        int32_t ia = dense_of(w, c->sa), ib = dense_of(w, c->sb);
        rg_real ima = ia < n ? b->inv_mass[ia] : 0, imb = ib < n ? b->inv_mass[ib] : 0;
        if (!(ima + imb > 0)) {
            c->flags &= ~CT_SOLVE;
            c->pn = c->pt = 0;
            continue;
        }
        solver_constraint *q = &cw->stage[nc];
        cw->hgt[nc] = c->py;
        cw->hgx[nc] = c->px;
        q->a = solver_index(cw, ia, n, x);
        q->b = solver_index(cw, ib, n, x);
        q->ima = ima;
        q->imb = imb;
        q->nx = c->nx;
        q->ny = c->ny;
        q->m = 1 / (ima + imb);
        q->mu = c->mu;
        q->s0 = c->s0;
        q->vmin = solver_vmin(c->s0, c->vn0, c->e, (c->flags & CT_CLOSING) != 0, &x->p);
        q->toi = c->toi;
        if (q->toi > 0) cw->imp[x->nimp++] = nc;
        q->pn = c->pn;
        q->pt = c->pt;
        q->cid = id;
        nc++;
    }
    x->n = n;
    x->nc = nc;
}

/* Impacts of one body within this fraction of the step of each other count as one (a box
 * across a tile seam meets both tiles at once, to rounding). */
#define SAME_IMPACT RG_R(1e-4)

/* The fraction of the step at which movable body i (dense) meets what it meets, if it can be
 * timed, else 0.  It can when its solved rows are impacts at one moment and rows with
 * immovable bodies that stay apart, with at most one of them with another movable body, an
 * impact (*partner: that body, else -1).  No body in contact with it, and no body near it
 * but that partner, then has a velocity that depends on the moment of its impact. */
static rg_real impact_time(const rg_world *w, int32_t i, int32_t n, int32_t *partner)
{
    const contact_world *cw = &w->coll;
    const body_store *b = &w->b;
    int32_t s = b->slot[i];
    rg_real t0 = RG_HUGE, t1 = 0;
    *partner = -1;
    for (int32_t id = b->chead[i] - 1; id >= 0; id = next_of(&cw->c[id], s)) {
        const contact *c = &cw->c[id];
        if (!(c->flags & CT_SOLVE)) continue;
        int32_t j = dense_of(w, other_of(c, s));
        int impact = c->toi > 0;
        if (c->toi >= 0) {
            if (!impact) return 0;
            t0 = rg_min(t0, c->toi);
            t1 = rg_max(t1, c->toi);
        }
        if (j < n && b->inv_mass[j] > 0) {
            if (!impact || *partner >= 0) return 0;
            *partner = j;
        }
    }
    return t0 <= t1 && t1 - t0 <= SAME_IMPACT ? t0 : 0;
}

/* Whether movable body i is timed, at *t: it can be, and so can the partner of its impact with
 * another movable body (whose only such row is that impact). */
static int timed_body(const rg_world *w, int32_t i, int32_t n, rg_real *t)
{
    int32_t p, q;
    *t = impact_time(w, i, n, &p);
    return *t > 0 && (p < 0 || impact_time(w, p, n, &q) > 0);
}

/* Timed impacts (contact.h): an impact row whose movable bodies are all timed aims at the
 * velocity the impact leaves (solver_vout), and stoi[q] becomes the fraction of the step at
 * which solver body q's velocity changes (0: at the start, as the speculative rows assume).
 * A body that is not timed shares no row with a timed one but with immovable bodies, so it
 * solves exactly as without timing.  Costs nothing in a step without impacts.  Returns
 * whether any body is timed. */
static int time_impacts(rg_world *w, narrow_ctx *x)
{
    contact_world *cw = &w->coll;
    const body_store *b = &w->b;
    if (x->nimp == 0) return 0;
    memset(cw->stoi, 0, (size_t)(x->ns + 1) * sizeof *cw->stoi);
    int any = 0;
    for (int32_t k = 0; k < x->nimp; k++) {
        solver_constraint *r = &cw->stage[cw->imp[k]];
        int32_t ia = r->a > 0 ? cw->sbody[r->a] : -1, ib = r->b > 0 ? cw->sbody[r->b] : -1;
        rg_real ta = 0, tb = 0;
        if (r->ima > 0 && !timed_body(w, ia, x->n, &ta)) continue;
        if (r->imb > 0 && !timed_body(w, ib, x->n, &tb)) continue;
        rg_real v1n = 0;
        if (ib >= 0) v1n += b->vx[ib] * r->nx + b->vy[ib] * r->ny;
        if (ia >= 0) v1n -= b->vx[ia] * r->nx + b->vy[ia] * r->ny;
        const contact *c = &cw->c[r->cid];
        r->vmin = solver_vout(c->vn0, v1n, r->toi, c->e, &x->p);
        if (r->ima > 0) cw->stoi[r->a] = ta;
        if (r->imb > 0) cw->stoi[r->b] = tb;
        any = 1;
    }
    return any;
}

static void solve(rg_world *w, narrow_ctx *x)
{
    contact_world *cw = &w->coll;
    body_store *b = &w->b;
    if (x->woke) restage(w, x);
    int32_t nc = x->nc;
    if (nc == 0) return;
    rg_real dt = x->p.dt;
    solver_constraint *con = cw->stage;
    /* under gravity, bottom-up by the height of the contact point: Gauss-Seidel then
     * carries support up a stack within a sweep, and the shock sweep needs the order */
    rg_real gx = w->gravity.x, gy = w->gravity.y, gl = rg_sqrt(gx * gx + gy * gy);
    int shock = gl > 0 && rg_finite(gl);
    if (shock) {
        gx /= gl;
        gy /= gl;
        rg_real *h = cw->hgt;
        rg_real hmin = RG_HUGE, hmax = -RG_HUGE;
        for (int32_t k = 0; k < nc; k++) {
            h[k] = -(cw->hgx[k] * gx + h[k] * gy);
            hmin = rg_min(hmin, h[k]);
            hmax = rg_max(hmax, h[k]);
        }
        rg_real scale = hmax > hmin ? RG_R(65535) / (hmax - hmin) : 0;
        if (!rg_finite(scale)) scale = 0;
        for (int32_t k = 0; k < nc; k++) {
            rg_real q = (h[k] - hmin) * scale;
            cw->key[k] = (uint16_t)(q >= 0 && q <= RG_R(65535) ? q : 0);
            cw->ord[k] = k;
        }
        radix_sort16(cw->key, cw->ord, cw->tkey, cw->tord, nc);
    } else {
        for (int32_t k = 0; k < nc; k++) cw->ord[k] = k;
    }
    const int32_t *ord = cw->ord;
    int timed = time_impacts(w, x);
    /* the solver's bodies: 0 is the ground, 1..ns the awake bodies the rows meet */
    int32_t ns = x->ns;
    const int32_t *sbody = cw->sbody;
    rg_real *v = cw->sv;
    v[0] = v[1] = 0;
    for (int32_t q = 1; q <= ns; q++) {
        v[2 * q] = b->vx[sbody[q]];
        v[2 * q + 1] = b->vy[sbody[q]];
    }
    solver_batch *sb = &cw->batch;
    solver_pack(con, ord, nc, ns + 1, cw->cmask, cw->color, sb);
    solver_wide_warm_start(sb, v);
    solver_warm_start(con, sb->over, sb->nover, v);
    for (int32_t it = 0; it < cw->iterations; it++) {
        solver_wide_iterate(sb, v);
        solver_iterate(con, sb->over, sb->nover, v);
    }
    solver_unpack(sb, con, nc, 0);
    if (shock) solver_shock(con, ord, nc, v, gx, gy);
    solver_fixed_rows(con, nc, v, 0);
    /* positions move with the solved velocities, then by the pseudo-velocities of the
     * position pass, which leave the velocities alone.  A timed body's velocity changes at
     * its impact, t into the step; v then holds the velocity of its whole step's motion, for
     * the position pass to see where the step leaves it. */
    for (int32_t q = 1; q <= ns; q++) {
        int32_t i = sbody[q];
        rg_real dvx = v[2 * q] - b->vx[i], dvy = v[2 * q + 1] - b->vy[i];
        rg_real t = timed ? cw->stoi[q] : 0;
        if (t > 0) {
            rg_real after = 1 - t, fx = b->vx[i], fy = b->vy[i];
            b->x[i] += dvx * after * dt;
            b->y[i] += dvy * after * dt;
            b->vx[i] = v[2 * q];
            b->vy[i] = v[2 * q + 1];
            v[2 * q] = fx + dvx * after;
            v[2 * q + 1] = fy + dvy * after;
        } else {
            b->x[i] += dvx * dt;
            b->y[i] += dvy * dt;
            b->vx[i] = v[2 * q];
            b->vy[i] = v[2 * q + 1];
        }
    }
    if (cw->position > 0 && solver_prepare_position(con, nc, v, &x->p) > 0) {
        rg_real *pv = cw->spv;
        memset(pv, 0, (size_t)(2 * ns + 2) * sizeof *pv);
        solver_pack_position(sb, con, nc);
        for (int32_t it = 0; it < cw->position; it++) {
            solver_wide_iterate_position(sb, pv);
            solver_iterate_position(con, sb->over, sb->nover, pv);
        }
        solver_unpack(sb, con, nc, 1);
        if (shock) solver_shock_position(con, ord, nc, pv, gx, gy);
        solver_fixed_rows(con, nc, pv, 1);
        cw->pv_valid = 1;
        for (int32_t q = 1; q <= ns; q++) {
            b->x[sbody[q]] += pv[2 * q] * dt;
            b->y[sbody[q]] += pv[2 * q + 1] * dt;
        }
    }
    for (int32_t k = 0; k < nc; k++) {
        contact *c = &cw->c[con[k].cid];
        c->pn = con[k].pn;
        c->pt = con[k].pt;
    }
}

/* Optional phase timers for development: build with -DRG_CONTACT_PROFILE (POSIX clock). */
#ifdef RG_CONTACT_PROFILE
#include <stdio.h>
#include <time.h>
static double prof_acc[8], prof_last, prof_moved;
#define PROF_MOVED(n) (prof_moved += (n))
static double prof_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}
#define PROF(k) do { double t_ = prof_now(); if ((k) >= 0) prof_acc[(k)] += t_ - prof_last; prof_last = t_; } while (0)
#define PROF_REPORT(w)                                                                         \
    do {                                                                                       \
        if ((w)->step_count % 10 == 9) {                                                      \
            fprintf(stderr, "contacts %d rows %d active %d | ms/step:", (w)->coll.n_awake,     \
                    nx.nc, (w)->coll.bp.n_active);                                             \
            const char *names[] = {"bodies", "pairs", "narrow", "solve", "fast+fat", "sleep"}; \
            for (int q_ = 0; q_ < 6; q_++) fprintf(stderr, " %s %.3f", names[q_], prof_acc[q_] * 1e3 / 10); \
            fprintf(stderr, " moved/step %.0f\n", prof_moved / 10); prof_moved = 0;             \
            memset(prof_acc, 0, sizeof prof_acc);                                              \
        }                                                                                      \
    } while (0)
#else
#define PROF(k) ((void)0)
#define PROF_MOVED(n) ((void)0)
#define PROF_REPORT(w) ((void)0)
#endif

void contact_step(rg_world *w, rg_real dt)
{
    contact_world *cw = &w->coll;
    body_store *b = &w->b;
    /* the events of this step follow those of the advance's earlier steps, and start with
     * the ends reported between steps */
    int32_t base = cw->n_ev;
    cw->ev_base = base;
    if (cw->n_pend > 0) memcpy(cw->ev + base, cw->pend, (size_t)cw->n_pend * sizeof *cw->ev);
    cw->n_ev = base + cw->n_pend;
    cw->n_pend = 0;
    cw->in_step = 1;
    if (cw->shape_count > 0) {
        PROF(-1);
        int32_t n = b->n_active;
        broadphase *bp = &cw->bp;
        int32_t na = bp->n_active;
        narrow_ctx nx;
        cw->pv_valid = 0;
        next_gen(cw);
        nx.n = n;
        nx.na = na;
        nx.nc = 0;
        nx.ns = 0;
        nx.nimp = 0;
        nx.woke = 0;
        nx.unite = cw->sleeping && cw->near_sleep;
        nx.p.dt = dt;
        nx.p.inv_dt = 1 / dt;
        nx.p.slop = cw->slop;
        nx.p.bias_rate = cw->bias_rate;
        nx.p.max_push = cw->max_push;
        nx.p.restitution_threshold = cw->restitution_threshold;
        nx.p.stagger = w->integrator == RG_INTEGRATOR_SEMI_IMPLICIT_EULER ? RG_R(0.5)
                     : w->integrator == RG_INTEGRATOR_EXPLICIT_EULER     ? RG_R(-0.5)
                                                                         : 0;
        /* the awake shaped bodies only: displacements of the integration, the step's view
         * of each, swept boxes and fat boxes */
        cbody *cb = cw->cb;
        for (int32_t k = 0; k < na; k++) {
            int32_t i = cw->adense[k];
            rg_real x1 = b->x[i], y1 = b->y[i], hx = b->hx[i], hy = b->hy[i];
            rg_real mx = x1 - cw->sx0[k], my = y1 - cw->sy0[k];
            b->dx[i] = mx;
            b->dy[i] = my;
            b->cflags[i] &= ~CF_GROUNDED; /* set again by the touching contacts */
            cb[i].sx = cw->sx0[k];
            cb[i].sy = cw->sy0[k];
            cb[i].dx = mx;
            cb[i].dy = my;
            cb[i].vx = cw->svx0[k];
            cb[i].vy = cw->svy0[k];
            cb[i].hx = hx;
            cb[i].hy = hy;
            cb[i].gs = b->type[i] == RG_BODY_DYNAMIC ? b->gscale[i] : 0;
            cb[i].im = b->inv_mass[i];
            cb[i].kind = b->shape[i];
            cb[i].pad = 0;
            rg_real lx = x1 - hx, ly = y1 - hy, ux = x1 + hx, uy = y1 + hy;
            if (cw->continuous) {
                lx = rg_min(lx, lx - mx);
                ly = rg_min(ly, ly - my);
                ux = rg_max(ux, ux - mx);
                uy = rg_max(uy, uy - my);
            }
            refresh_fat(w, i, lx, ly, ux, uy, mx, my, (b->vx[i] - cw->svx0[k]) * dt, (b->vy[i] - cw->svy0[k]) * dt);
        }
        if (nx.unite)
            for (int32_t k = 0; k < na; k++) cw->uf[k] = k;
        PROF(0);
        PROF_MOVED(bp->n_moved);
        nx.woke = find_pairs(w);
        PROF(1);
        for (int32_t k = 0; k < cw->n_awake; k++) {
            narrow_one(w, cw->awake[k], &nx);
        }
        PROF(2);
        solve(w, &nx);
        PROF(3);
        if (cw->continuous) clamp_fast(w, na);
        /* fat boxes must hold the final boxes, for queries and the next step */
        for (int32_t k = 0; k < bp->n_active; k++) {
            int32_t i = dense_of(w, bp->active[k]);
            rg_real x1 = b->x[i], y1 = b->y[i], hx = b->hx[i], hy = b->hy[i];
            /* bodies woken during the step (k >= na) have no start velocity: no trend */
            rg_real ax = k < na ? (b->vx[i] - cw->svx0[k]) * dt : 0, ay = k < na ? (b->vy[i] - cw->svy0[k]) * dt : 0;
            refresh_fat(w, i, x1 - hx, y1 - hy, x1 + hx, y1 + hy, b->vx[i] * dt, b->vy[i] * dt, ax, ay);
        }
        PROF(4);
        if (cw->sleeping) sleep_islands(w, dt, nx.unite && !nx.woke);
        PROF(5);
        PROF_REPORT(w);
    }
    sort_events(cw->ev + base, cw->n_ev - base);
    cw->ev_base = cw->n_ev;
    cw->in_step = 0;
}

/* ---------------------------------------------------------------- hooks for the body API */

void contact_body_init(rg_world *w, int32_t i)
{
    body_store *b = &w->b;
    b->mu[i] = DEFAULT_FRICTION;
    b->cat[i] = 1;
    b->mask[i] = 0xFFFFFFFFu;
}

int32_t contact_body_wake(rg_world *w, int32_t i)
{
    body_store *b = &w->b;
    if (body_partition(w, i) == BODY_PART_ASLEEP) {
        int32_t s = b->slot[i];
        wake_island(w, i);
        i = dense_of(w, s);
    }
    b->sleep_t[i] = 0;
    return i;
}

/* The body's fat box becomes its box at rest, and its pairs are searched at the next step. */
static void teleported(rg_world *w, int32_t i)
{
    body_store *b = &w->b;
    int32_t s = b->slot[i];
    rg_real box[4];
    rest_box(&w->coll, b, i, box);
    broadphase_move(&w->coll.bp, s, box[0], box[1], box[2], box[3]);
    broadphase_mark_moved(&w->coll.bp, s);
    b->cflags[i] |= CF_TELEPORTED;
    wake_touching(w, s);
}

void contact_body_moved(rg_world *w, int32_t i)
{
    if (w->b.shape[i] != RG_SHAPE_NONE) teleported(w, i);
}

/* Ends every contact of slot s (end events reported with the next step), waking the
 * sleeping bodies on the other side. */
static void end_contacts(rg_world *w, int32_t s)
{
    contact_world *cw = &w->coll;
    for (;;) {
        int32_t id = w->b.chead[dense_of(w, s)] - 1;
        if (id < 0) return;
        int32_t j = dense_of(w, other_of(&cw->c[id], s));
        if (body_partition(w, j) == BODY_PART_ASLEEP) wake_island(w, j);
        contact_destroy(w, id);
    }
}

static void remove_shape(rg_world *w, int32_t i)
{
    body_store *b = &w->b;
    int32_t s = b->slot[i];
    end_contacts(w, s);
    i = dense_of(w, s);
    broadphase_remove(&w->coll.bp, s);
    w->coll.shape_count--;
    b->shape[i] = RG_SHAPE_NONE;
    b->hx[i] = b->hy[i] = 0;
    b->cflags[i] &= ~(CF_GROUNDED | CF_TELEPORTED);
}

int32_t contact_body_destroy(rg_world *w, int32_t i)
{
    int32_t s = w->b.slot[i];
    i = contact_body_wake(w, i);
    if (w->b.shape[i] != RG_SHAPE_NONE) remove_shape(w, i);
    return dense_of(w, s);
}

/* ---------------------------------------------------------------- body API */

#define BODY_GET(world, body, i)                               \
    if ((world) == NULL) return RG_ERR_INVALID_ARGUMENT;       \
    int32_t i = body_lookup((world), (body));                  \
    if (i < 0) return RG_ERR_STALE_HANDLE

static int size_ok(rg_real v) { return rg_finite(v) && v > 0 && v <= (rg_real)RG_MAX_SHAPE_SIZE; }

static rg_status set_shape(rg_world *w, int32_t i, int32_t kind, rg_real hx, rg_real hy)
{
    contact_world *cw = &w->coll;
    body_store *b = &w->b;
    int32_t s = b->slot[i];
    int fresh = b->shape[i] == RG_SHAPE_NONE;
    if (fresh) {
        rg_status st = broadphase_reserve(&cw->bp, &w->mem, w->body_pool.slot_count, cw->bp.count + 1);
        if (st != RG_OK) return st;
    }
    i = contact_body_wake(w, i);
    b->shape[i] = kind;
    b->hx[i] = hx;
    b->hy[i] = hy;
    if (fresh) {
        rg_real box[4];
        rest_box(cw, b, i, box);
        broadphase_insert(&cw->bp, s, box[0], box[1], box[2], box[3]);
        if (b->type[i] != RG_BODY_STATIC) broadphase_activate(&cw->bp, s);
        cw->shape_count++;
    }
    teleported(w, i);
    return RG_OK;
}

RG_API rg_status rg_body_set_circle(rg_world *world, rg_body body, rg_real radius)
{
    BODY_GET(world, body, i);
    if (!size_ok(radius)) return RG_ERR_INVALID_ARGUMENT;
    return set_shape(world, i, RG_SHAPE_CIRCLE, radius, radius);
}

RG_API rg_status rg_body_set_aabb(rg_world *world, rg_body body, rg_real half_width,
                                  rg_real half_height)
{
    BODY_GET(world, body, i);
    if (!size_ok(half_width) || !size_ok(half_height)) return RG_ERR_INVALID_ARGUMENT;
    return set_shape(world, i, RG_SHAPE_AABB, half_width, half_height);
}

RG_API rg_status rg_body_clear_shape(rg_world *world, rg_body body)
{
    BODY_GET(world, body, i);
    if (world->b.shape[i] == RG_SHAPE_NONE) return RG_OK;
    i = contact_body_wake(world, i);
    remove_shape(world, i);
    return RG_OK;
}

RG_API rg_status rg_body_get_shape(const rg_world *world, rg_body body, int32_t *out_kind,
                                   rg_vec2 *out_half_extents)
{
    BODY_GET(world, body, i);
    if (out_kind == NULL && out_half_extents == NULL) return RG_ERR_INVALID_ARGUMENT;
    if (out_kind != NULL) *out_kind = world->b.shape[i];
    if (out_half_extents != NULL) *out_half_extents = rg_v2(world->b.hx[i], world->b.hy[i]);
    return RG_OK;
}

/* Refreshes the mixed materials of slot s's contacts. */
static void refresh_materials(rg_world *w, int32_t s)
{
    contact_world *cw = &w->coll;
    const body_store *b = &w->b;
    for (int32_t id = b->chead[dense_of(w, s)] - 1; id >= 0; id = next_of(&cw->c[id], s)) {
        contact *c = &cw->c[id];
        int32_t ia = dense_of(w, c->sa), ib = dense_of(w, c->sb);
        c->mu = rg_sqrt(b->mu[ia] * b->mu[ib]);
        c->e = rg_max(b->rest[ia], b->rest[ib]);
    }
}

RG_API rg_status rg_body_set_restitution(rg_world *world, rg_body body, rg_real restitution)
{
    BODY_GET(world, body, i);
    if (!rg_finite(restitution) || restitution < 0 || restitution > 1) return RG_ERR_INVALID_ARGUMENT;
    world->b.rest[i] = restitution;
    refresh_materials(world, world->b.slot[i]);
    return RG_OK;
}

RG_API rg_status rg_body_get_restitution(const rg_world *world, rg_body body, rg_real *out)
{
    BODY_GET(world, body, i);
    if (out == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out = world->b.rest[i];
    return RG_OK;
}

RG_API rg_status rg_body_set_friction(rg_world *world, rg_body body, rg_real mu)
{
    BODY_GET(world, body, i);
    if (!rg_finite(mu) || mu < 0) return RG_ERR_INVALID_ARGUMENT;
    world->b.mu[i] = mu;
    refresh_materials(world, world->b.slot[i]);
    return RG_OK;
}

RG_API rg_status rg_body_get_friction(const rg_world *world, rg_body body, rg_real *out)
{
    BODY_GET(world, body, i);
    if (out == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out = world->b.mu[i];
    return RG_OK;
}

RG_API rg_status rg_body_set_sensor(rg_world *world, rg_body body, int32_t is_sensor)
{
    BODY_GET(world, body, i);
    if (is_sensor != 0 && is_sensor != 1) return RG_ERR_INVALID_ARGUMENT;
    body_store *b = &world->b;
    if (((b->cflags[i] & CF_SENSOR) != 0) == (is_sensor != 0)) return RG_OK;
    int32_t s = b->slot[i];
    i = contact_body_wake(world, i);
    if (b->shape[i] != RG_SHAPE_NONE) {
        end_contacts(world, s);
        i = dense_of(world, s);
        broadphase_mark_moved(&world->coll.bp, s);
    }
    b->cflags[i] ^= CF_SENSOR;
    return RG_OK;
}

RG_API rg_status rg_body_is_sensor(const rg_world *world, rg_body body, int32_t *out_is_sensor)
{
    BODY_GET(world, body, i);
    if (out_is_sensor == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out_is_sensor = (world->b.cflags[i] & CF_SENSOR) != 0;
    return RG_OK;
}

RG_API rg_status rg_body_set_filter(rg_world *world, rg_body body, uint32_t category, uint32_t mask)
{
    BODY_GET(world, body, i);
    body_store *b = &world->b;
    contact_world *cw = &world->coll;
    if (b->cat[i] == category && b->mask[i] == mask) return RG_OK;
    int32_t s = b->slot[i];
    i = contact_body_wake(world, i);
    b->cat[i] = category;
    b->mask[i] = mask;
    if (b->shape[i] == RG_SHAPE_NONE) return RG_OK;
    /* end the contacts the new filter rejects; new pairs are searched at the next step */
    int32_t id = b->chead[i] - 1;
    while (id >= 0) {
        int32_t next = next_of(&cw->c[id], s);
        int32_t j = dense_of(world, other_of(&cw->c[id], s));
        if (!pair_admitted(b, dense_of(world, s), j)) {
            if (body_partition(world, j) == BODY_PART_ASLEEP) {
                wake_island(world, j);
                next = next_of(&cw->c[id], s);
            }
            contact_destroy(world, id);
        }
        id = next;
    }
    broadphase_mark_moved(&cw->bp, s);
    return RG_OK;
}

RG_API rg_status rg_body_get_filter(const rg_world *world, rg_body body, uint32_t *out_category,
                                    uint32_t *out_mask)
{
    BODY_GET(world, body, i);
    if (out_category == NULL || out_mask == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out_category = world->b.cat[i];
    *out_mask = world->b.mask[i];
    return RG_OK;
}

RG_API rg_status rg_body_is_grounded(const rg_world *world, rg_body body, int32_t *out_grounded)
{
    BODY_GET(world, body, i);
    if (out_grounded == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out_grounded = world->b.type[i] == RG_BODY_DYNAMIC && (world->b.cflags[i] & CF_GROUNDED) != 0;
    return RG_OK;
}

RG_API rg_status rg_body_is_awake(const rg_world *world, rg_body body, int32_t *out_awake)
{
    BODY_GET(world, body, i);
    if (out_awake == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out_awake = body_partition(world, i) == BODY_PART_ACTIVE;
    return RG_OK;
}

RG_API rg_status rg_body_wake(rg_world *world, rg_body body)
{
    BODY_GET(world, body, i);
    if (world->b.type[i] != RG_BODY_STATIC) contact_body_wake(world, i);
    return RG_OK;
}

/* ---------------------------------------------------------------- world API */

RG_API int32_t rg_world_awake_body_count(const rg_world *world)
{
    return world != NULL ? world->b.n_active : 0;
}

RG_API int32_t rg_world_touching_count(const rg_world *world)
{
    return world != NULL ? world->coll.n_touching : 0;
}

RG_API rg_status rg_world_set_sleeping(rg_world *world, int32_t enabled)
{
    if (world == NULL || (enabled != 0 && enabled != 1)) return RG_ERR_INVALID_ARGUMENT;
    if (!enabled) wake_all(world);
    world->coll.sleeping = enabled;
    return RG_OK;
}

RG_API rg_status rg_world_get_sleeping(const rg_world *world, int32_t *out_enabled)
{
    if (world == NULL || out_enabled == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out_enabled = world->coll.sleeping;
    return RG_OK;
}

RG_API rg_status rg_world_set_sleep_thresholds(rg_world *world, rg_real speed, rg_real time)
{
    if (world == NULL || !rg_finite(speed) || !rg_finite(time) || speed < 0 || !(time > 0))
        return RG_ERR_INVALID_ARGUMENT;
    world->coll.sleep_speed = speed;
    world->coll.sleep_time = time;
    return RG_OK;
}

RG_API rg_status rg_world_get_sleep_thresholds(const rg_world *world, rg_real *out_speed,
                                               rg_real *out_time)
{
    if (world == NULL || out_speed == NULL || out_time == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out_speed = world->coll.sleep_speed;
    *out_time = world->coll.sleep_time;
    return RG_OK;
}

RG_API rg_status rg_world_set_solver_iterations(rg_world *world, int32_t velocity, int32_t position)
{
    if (world == NULL || velocity < 1 || velocity > 64 || position < 0 || position > 64)
        return RG_ERR_INVALID_ARGUMENT;
    world->coll.iterations = velocity;
    world->coll.position = position;
    return RG_OK;
}

RG_API rg_status rg_world_get_solver_iterations(const rg_world *world, int32_t *out_velocity,
                                                int32_t *out_position)
{
    if (world == NULL || out_velocity == NULL || out_position == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out_velocity = world->coll.iterations;
    *out_position = world->coll.position;
    return RG_OK;
}

RG_API rg_status rg_world_set_contact_tuning(rg_world *world, rg_real slop, rg_real bias_rate,
                                             rg_real max_push, rg_real restitution_threshold)
{
    if (world == NULL || !rg_finite(slop) || !rg_finite(bias_rate) || !rg_finite(max_push) ||
        !rg_finite(restitution_threshold) || slop < 0 || !(bias_rate > 0) || bias_rate > 1 ||
        !(max_push > 0) || restitution_threshold < 0)
        return RG_ERR_INVALID_ARGUMENT;
    contact_world *cw = &world->coll;
    cw->slop = slop;
    cw->bias_rate = bias_rate;
    cw->max_push = max_push;
    cw->restitution_threshold = restitution_threshold;
    return RG_OK;
}

RG_API rg_status rg_world_get_contact_tuning(const rg_world *world, rg_real *out_slop,
                                             rg_real *out_bias_rate, rg_real *out_max_push,
                                             rg_real *out_restitution_threshold)
{
    if (world == NULL || out_slop == NULL || out_bias_rate == NULL || out_max_push == NULL ||
        out_restitution_threshold == NULL)
        return RG_ERR_INVALID_ARGUMENT;
    const contact_world *cw = &world->coll;
    *out_slop = cw->slop;
    *out_bias_rate = cw->bias_rate;
    *out_max_push = cw->max_push;
    *out_restitution_threshold = cw->restitution_threshold;
    return RG_OK;
}

RG_API rg_status rg_world_set_continuous(rg_world *world, int32_t enabled)
{
    if (world == NULL || (enabled != 0 && enabled != 1)) return RG_ERR_INVALID_ARGUMENT;
    world->coll.continuous = enabled;
    return RG_OK;
}

RG_API rg_status rg_world_get_continuous(const rg_world *world, int32_t *out_enabled)
{
    if (world == NULL || out_enabled == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out_enabled = world->coll.continuous;
    return RG_OK;
}

RG_API int32_t rg_world_get_contact_events(const rg_world *world, rg_contact_event *out,
                                           int32_t capacity)
{
    if (world == NULL || capacity < 0 || (out == NULL && capacity > 0)) return RG_ERR_INVALID_ARGUMENT;
    const contact_world *cw = &world->coll;
    int32_t n = cw->n_ev < capacity ? cw->n_ev : capacity;
    if (n > 0) memcpy(out, cw->ev, (size_t)n * sizeof *out);
    return cw->n_ev;
}
