/* events.c: the contact event buffer and rg_world_get_contact_events. */
#include <string.h>

#include "arg.h"
#include "events.h"
#include "state.h"
#include "vec2.h"

rg_status events_alloc(event_store *fresh, const event_store *cur, const rg_mem *m, int32_t contacts)
{
    int64_t need = (int64_t)cur->base + EVENTS_PER_STEP(contacts);
    if (need > INT32_MAX) return RG_ERR_CAPACITY;
    int32_t cap = cur->cap > need ? cur->cap : (int32_t)need;
    size_t size = mem_array_size((size_t)cap, sizeof(rg_contact_event));
    *fresh = *cur;
    fresh->ev = size > 0 ? mem_alloc(m, size) : NULL;
    fresh->pend = mem_alloc(m, (size_t)contacts * sizeof *fresh->pend);
    if (fresh->ev == NULL || fresh->pend == NULL) {
        mem_free(m, fresh->ev, size);
        mem_free(m, fresh->pend, (size_t)contacts * sizeof *fresh->pend);
        fresh->ev = fresh->pend = NULL;
        fresh->cap = fresh->pend_cap = 0;
        return RG_ERR_OUT_OF_MEMORY;
    }
    fresh->cap = cap;
    fresh->pend_cap = contacts;
    return RG_OK;
}

void events_adopt(event_store *cur, event_store *fresh, const rg_mem *m)
{
    if (cur->n > 0) memcpy(fresh->ev, cur->ev, (size_t)cur->n * sizeof *fresh->ev);
    if (cur->n_pend > 0) memcpy(fresh->pend, cur->pend, (size_t)cur->n_pend * sizeof *fresh->pend);
    events_release(cur, m);
    *cur = *fresh;
}

void events_discard(event_store *fresh, const rg_mem *m)
{
    mem_free(m, fresh->ev, (size_t)fresh->cap * sizeof *fresh->ev);
    mem_free(m, fresh->pend, (size_t)fresh->pend_cap * sizeof *fresh->pend);
}

void events_release(event_store *es, const rg_mem *m)
{
    mem_free(m, es->ev, (size_t)es->cap * sizeof *es->ev);
    mem_free(m, es->pend, (size_t)es->pend_cap * sizeof *es->pend);
    es->ev = es->pend = NULL;
    es->cap = es->pend_cap = 0;
}

void events_clear(event_store *es)
{
    es->n = 0;
    es->base = 0;
}

rg_status events_reserve(rg_world *w)
{
    event_store *es = &w->coll.events;
    int64_t need = (int64_t)es->n + EVENTS_PER_STEP(w->coll.contacts.cap);
    if (need <= es->cap) return RG_OK;
    if (need > INT32_MAX) return RG_ERR_OUT_OF_MEMORY;
    /* grow by half again at least, so a run of busy advances reallocates only a few times */
    int64_t want = (int64_t)es->cap + es->cap / 2;
    int32_t cap = (int32_t)(want > need && want <= INT32_MAX ? want : need);
    size_t size = mem_array_size((size_t)cap, sizeof(rg_contact_event));
    rg_contact_event *ev = size > 0 ? mem_alloc(&w->mem, size) : NULL;
    if (ev == NULL) return RG_ERR_OUT_OF_MEMORY;
    if (es->n > 0) memcpy(ev, es->ev, (size_t)es->n * sizeof *ev);
    mem_free(&w->mem, es->ev, (size_t)es->cap * sizeof *es->ev);
    es->ev = ev;
    es->cap = cap;
    return RG_OK;
}

void events_emit(rg_world *w, const contact *c, int32_t kind)
{
    event_store *es = &w->coll.events;
    rg_contact_event *e = es->in_step ? &es->ev[es->n++] : &es->pend[es->n_pend++];
    e->a = pool_handle(&w->body_pool, c->sa);
    e->b = pool_handle(&w->body_pool, c->sb);
    e->normal = rg_v2(c->nx, c->ny);
    e->point = rg_v2(c->px, c->py);
    e->depth = c->depth;
    e->speed = c->speed;
    e->kind = kind;
    e->sensor = (c->flags & CT_SENSOR) != 0;
}

void events_begin_step(event_store *es)
{
    /* the events of this step follow those of the advance's earlier steps, and start with
     * the ends reported between steps */
    int32_t base = es->n;
    es->base = base;
    if (es->n_pend > 0) memcpy(es->ev + base, es->pend, (size_t)es->n_pend * sizeof *es->ev);
    es->n = base + es->n_pend;
    es->n_pend = 0;
    es->in_step = 1;
}

static int events_less(const rg_contact_event *p, const rg_contact_event *q)
{
    if (p->a != q->a) return p->a < q->a;
    if (p->b != q->b) return p->b < q->b;
    return p->kind > q->kind; /* an end before a begin */
}

static void events_sift_down(rg_contact_event *e, int32_t root, int32_t n)
{
    for (;;) {
        int32_t child = 2 * root + 1;
        if (child >= n) return;
        if (child + 1 < n && events_less(&e[child], &e[child + 1])) child++;
        if (!events_less(&e[root], &e[child])) return;
        rg_contact_event t = e[root];
        e[root] = e[child];
        e[child] = t;
        root = child;
    }
}

/* Heapsort: in place, no allocation; (a, b, kind) is unique within a step. */
static void events_sort(rg_contact_event *e, int32_t n)
{
    for (int32_t i = n / 2 - 1; i >= 0; i--) events_sift_down(e, i, n);
    for (int32_t i = n - 1; i > 0; i--) {
        rg_contact_event t = e[0];
        e[0] = e[i];
        e[i] = t;
        events_sift_down(e, 0, i);
    }
}

void events_end_step(event_store *es)
{
    /* before the first contact there is no buffer: NULL + 0 is undefined in C */
    if (es->n > es->base) events_sort(es->ev + es->base, es->n - es->base);
    es->base = es->n;
    es->in_step = 0;
}

RG_API int32_t rg_world_get_contact_events(const rg_world *world, rg_contact_event *out,
                                           int32_t capacity)
{
    ERROR_BEGIN(world);
    ARG_BUFFER(world, out, capacity);
    const event_store *es = &world->coll.events;
    int32_t n = es->n < capacity ? es->n : capacity;
    if (n > 0) memcpy(out, es->ev, (size_t)n * sizeof *out);
    return es->n;
}
