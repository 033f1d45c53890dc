/* contact.c: contact storage: creation, destruction, body lists and the awake set. */
#include <string.h>

#include "body.h"
#include "contact.h"
#include "events.h"
#include "state.h"
#include "vec2.h"

static inline void contact_set_next(contact *c, int32_t slot, int32_t v)
{
    if (c->sa == slot) c->na = v; else c->nb = v;
}

static inline void contact_set_prev(contact *c, int32_t slot, int32_t v)
{
    if (c->sa == slot) c->pa = v; else c->pb = v;
}

void contact_init(contact_store *cs)
{
    memset(cs, 0, sizeof *cs);
    cs->free_head = -1;
}

void contact_release(rg_world *w)
{
    collide_world *cw = &w->coll;
    contact_store *cs = &cw->contacts;
    const rg_mem *m = &w->mem;
    mem_free(m, cs->c, (size_t)cs->cap * sizeof *cs->c);
    mem_free(m, cs->awake, (size_t)cs->cap * sizeof *cs->awake);
    events_release(&cw->events, m);
    solver_rows_release(&cw->rows, m);
    cs->c = NULL;
    cs->awake = NULL;
    cs->cap = 0;
}

/* Grows contact storage (contacts, awake list) to cap with what is sized by it (solver rows,
 * event buffer); all-or-nothing.  The event buffer keeps the events held and room for the
 * current step at the new capacity. */
static rg_status contact_grow_to(rg_world *w, int32_t cap)
{
    collide_world *cw = &w->coll;
    contact_store *cs = &cw->contacts;
    const rg_mem *m = &w->mem;
    int32_t old = cs->cap;
    event_store ev;
    rg_status st = events_alloc(&ev, &cw->events, m, cap);
    if (st != RG_OK) return st;
    solver_rows rows;
    st = solver_rows_alloc(&rows, m, cap);
    contact *c = mem_alloc(m, (size_t)cap * sizeof *c);
    int32_t *awake = mem_alloc(m, (size_t)cap * sizeof *awake);
    if (st != RG_OK || c == NULL || awake == NULL) {
        if (st == RG_OK) solver_rows_release(&rows, m);
        mem_free(m, c, (size_t)cap * sizeof *c);
        mem_free(m, awake, (size_t)cap * sizeof *awake);
        events_discard(&ev, m);
        return RG_ERR_OUT_OF_MEMORY;
    }
    if (old > 0) {
        memcpy(c, cs->c, (size_t)old * sizeof *c);
        memcpy(awake, cs->awake, (size_t)cs->n_awake * sizeof *awake);
    }
    mem_free(m, cs->c, (size_t)old * sizeof *cs->c);
    mem_free(m, cs->awake, (size_t)old * sizeof *cs->awake);
    events_adopt(&cw->events, &ev, m);
    solver_rows_release(&cw->rows, m);
    cw->rows = rows;
    cs->c = c;
    cs->awake = awake;
    cs->cap = cap;
    /* new ids on the free list, lowest first */
    for (int32_t id = cap - 1; id >= old; id--) {
        memset(&c[id], 0, sizeof c[id]);
        c[id].sa = c[id].sb = -1; /* free */
        c[id].na = cs->free_head;
        c[id].awake = -1;
        cs->free_head = id;
    }
    return RG_OK;
}

/* Doubles contact storage, or where that is more memory than there is, grows it by a
 * quarter, then by a sixteenth (the new ids come lowest first whatever the size). */
static rg_status contact_grow(rg_world *w)
{
    int32_t old = w->coll.contacts.cap;
    if (old > INT32_MAX / 8) return RG_ERR_CAPACITY;
    if (old < 256) return contact_grow_to(w, 256);
    rg_status st = contact_grow_to(w, old * 2);
    if (st == RG_ERR_OUT_OF_MEMORY) st = contact_grow_to(w, old + old / 4);
    if (st == RG_ERR_OUT_OF_MEMORY) st = contact_grow_to(w, old + old / 16);
    return st;
}

rg_status contact_reserve(rg_world *w) { return contact_grow(w); }

void contact_awake_add(contact_store *cs, int32_t id)
{
    cs->c[id].awake = cs->n_awake;
    cs->awake[cs->n_awake++] = id;
}

void contact_awake_remove(contact_store *cs, int32_t id)
{
    int32_t k = cs->c[id].awake, last = cs->awake[--cs->n_awake];
    cs->awake[k] = last;
    cs->c[last].awake = k;
    cs->c[id].awake = -1;
}

static void contact_link(rg_world *w, int32_t id, int32_t slot)
{
    contact_store *cs = &w->coll.contacts;
    int32_t i = body_dense(w, slot);
    int32_t head = w->b.chead[i] - 1;
    contact_set_prev(&cs->c[id], slot, -1);
    contact_set_next(&cs->c[id], slot, head);
    if (head >= 0) contact_set_prev(&cs->c[head], slot, id);
    w->b.chead[i] = id + 1;
}

static void contact_unlink(rg_world *w, int32_t id, int32_t slot)
{
    contact_store *cs = &w->coll.contacts;
    contact *c = &cs->c[id];
    int32_t next = c->sa == slot ? c->na : c->nb;
    int32_t prev = c->sa == slot ? c->pa : c->pb;
    if (prev >= 0)
        contact_set_next(&cs->c[prev], slot, next);
    else
        w->b.chead[body_dense(w, slot)] = next + 1;
    if (next >= 0) contact_set_prev(&cs->c[next], slot, prev);
}

static inline void contact_mix(contact *c, const body_store *b, int32_t ia, int32_t ib)
{
    c->mu = rg_sqrt(b->mu[ia] * b->mu[ib]);
    c->e = rg_max(b->rest[ia], b->rest[ib]);
}

static inline uint32_t contact_one_way(const body_store *b, int32_t ia, int32_t ib)
{
    return (b->owx[ia] != 0 || b->owy[ia] != 0 || b->owx[ib] != 0 || b->owy[ib] != 0) ? CT_ONEWAY : 0;
}

int32_t contact_create(rg_world *w, int32_t s, int32_t t)
{
    contact_store *cs = &w->coll.contacts;
    if (cs->free_head < 0 && contact_grow(w) != RG_OK) return -1;
    if (pool_handle(&w->body_pool, s) > pool_handle(&w->body_pool, t)) {
        int32_t tmp = s;
        s = t;
        t = tmp;
    }
    const body_store *b = &w->b;
    int32_t id = cs->free_head;
    contact *c = &cs->c[id];
    cs->free_head = c->na;
    cs->live++;
    int32_t ia = body_dense(w, s), ib = body_dense(w, t);
    memset(c, 0, sizeof *c);
    c->sa = s;
    c->sb = t;
    c->awake = -1;
    c->flags = ((b->cflags[ia] | b->cflags[ib]) & CF_SENSOR) ? CT_SENSOR : 0;
    c->flags |= contact_one_way(b, ia, ib);
    contact_mix(c, b, ia, ib);
    contact_link(w, id, s);
    contact_link(w, id, t);
    if (ia < b->n_active || ib < b->n_active) contact_awake_add(cs, id);
    return id;
}

void contact_destroy(rg_world *w, int32_t id)
{
    contact_store *cs = &w->coll.contacts;
    contact *c = &cs->c[id];
    if (c->flags & CT_TOUCHING) {
        events_emit(w, c, RG_CONTACT_END);
        cs->n_touching--;
    }
    contact_unlink(w, id, c->sa);
    contact_unlink(w, id, c->sb);
    if (c->awake >= 0) contact_awake_remove(cs, id);
    c->flags = 0;
    c->sa = c->sb = -1; /* free */
    c->na = cs->free_head;
    cs->free_head = id;
    cs->live--;
}

void contact_refresh_materials(rg_world *w, int32_t s)
{
    contact_store *cs = &w->coll.contacts;
    const body_store *b = &w->b;
    for (int32_t id = b->chead[body_dense(w, s)] - 1; id >= 0; id = contact_next(&cs->c[id], s)) {
        contact *c = &cs->c[id];
        contact_mix(c, b, body_dense(w, c->sa), body_dense(w, c->sb));
    }
}

void contact_refresh_flags(rg_world *w, int32_t s)
{
    contact_store *cs = &w->coll.contacts;
    const body_store *b = &w->b;
    for (int32_t id = b->chead[body_dense(w, s)] - 1; id >= 0; id = contact_next(&cs->c[id], s)) {
        contact *c = &cs->c[id];
        c->flags = (c->flags & ~CT_ONEWAY) | contact_one_way(b, body_dense(w, c->sa), body_dense(w, c->sb));
    }
}

int32_t contact_find(const rg_world *w, int32_t s, int32_t t)
{
    const contact_store *cs = &w->coll.contacts;
    for (int32_t id = w->b.chead[body_dense(w, s)] - 1; id >= 0; id = contact_next(&cs->c[id], s))
        if (contact_other(&cs->c[id], s) == t) return id;
    return -1;
}

rg_status contact_block_alloc(contact_block *b, const rg_world *w, int32_t cap, int32_t n_ev, int32_t n_pend)
{
    const contact_store *cs = &w->coll.contacts;
    const event_store *es = &w->coll.events;
    const rg_mem *m = &w->mem;
    int64_t need = EVENTS_PER_STEP(cap) > n_ev ? EVENTS_PER_STEP(cap) : n_ev;
    if (need > INT32_MAX || n_pend > cap) return RG_ERR_CAPACITY;
    memset(b, 0, sizeof *b);
    b->cap = cap;
    b->new_contacts = cs->cap != cap;
    b->new_events = b->new_contacts || es->cap < need || es->pend_cap < cap;
    if (b->new_contacts && cap > 0) {
        b->c = mem_alloc(m, (size_t)cap * sizeof *b->c);
        b->awake = mem_alloc(m, (size_t)cap * sizeof *b->awake);
        rg_status st = solver_rows_alloc(&b->rows, m, cap);
        if (b->c == NULL || b->awake == NULL || st != RG_OK) {
            if (st == RG_OK) solver_rows_release(&b->rows, m);
            mem_free(m, b->c, (size_t)cap * sizeof *b->c);
            mem_free(m, b->awake, (size_t)cap * sizeof *b->awake);
            return RG_ERR_OUT_OF_MEMORY;
        }
    }
    if (b->new_events && need > 0) {
        event_store none;
        memset(&none, 0, sizeof none);
        none.base = (int32_t)(need - EVENTS_PER_STEP(cap));
        rg_status st = events_alloc(&b->ev, &none, m, cap > 0 ? cap : 1);
        if (st != RG_OK) {
            b->new_events = 0; /* nothing of it allocated */
            contact_block_free(b, m);
            return st;
        }
    }
    return RG_OK;
}

void contact_block_free(contact_block *b, const rg_mem *m)
{
    if (b->new_contacts && b->cap > 0) {
        solver_rows_release(&b->rows, m);
        mem_free(m, b->c, (size_t)b->cap * sizeof *b->c);
        mem_free(m, b->awake, (size_t)b->cap * sizeof *b->awake);
    }
    if (b->new_events) events_discard(&b->ev, m);
    b->new_contacts = b->new_events = 0;
}

void contact_block_adopt(rg_world *w, contact_block *b)
{
    collide_world *cw = &w->coll;
    contact_store *cs = &cw->contacts;
    const rg_mem *m = &w->mem;
    if (b->new_contacts) {
        mem_free(m, cs->c, (size_t)cs->cap * sizeof *cs->c);
        mem_free(m, cs->awake, (size_t)cs->cap * sizeof *cs->awake);
        solver_rows_release(&cw->rows, m);
        cs->c = b->c;
        cs->awake = b->awake;
        cs->cap = b->cap;
        if (b->cap > 0) cw->rows = b->rows;
    }
    if (b->new_events) {
        events_release(&cw->events, m);
        cw->events = b->ev;
    }
    b->new_contacts = b->new_events = 0;
}

void contact_manifold_now(const rg_world *w, int32_t i, int32_t j, coll_manifold *m)
{
    const body_store *b = &w->b;
    coll_manifold_of(b->shape[i], rg_v2(b->x[i], b->y[i]), rg_v2(b->hx[i], b->hy[i]), b->shape[j],
                     rg_v2(b->x[j], b->y[j]), rg_v2(b->hx[j], b->hy[j]), m);
}
