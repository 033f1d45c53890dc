/* island.c: islands, the sleep stage, waking, and the sleeping API. */
#include "arg.h"
#include "body.h"
#include "contact.h"
#include "island.h"
#include "state.h"
#include "task.h"
#include "vec2.h"

void island_layout(mem_layout *l, island_state *s, int32_t n)
{
    s->umin = mem_take(l, (size_t)n, sizeof(rg_real));
    s->uf = mem_take(l, (size_t)n, sizeof(int32_t));
    s->ihead = mem_take(l, (size_t)n, sizeof(int32_t));
    s->itail = mem_take(l, (size_t)n, sizeof(int32_t));
    s->list = mem_take(l, (size_t)n, sizeof(int32_t));
}

void island_wake(rg_world *w, int32_t slot)
{
    collide_world *cw = &w->coll;
    contact_store *cs = &cw->contacts;
    body_store *b = &w->b;
    int32_t i = body_dense(w, slot);
    if (body_partition(w, i) != BODY_PART_ASLEEP) return;
    int32_t s = b->isl_head[i] - 1;
    if (s < 0) s = slot; /* not in a list: wake it alone */
    while (s >= 0) {
        int32_t j = body_dense(w, s);
        int32_t next = b->isl_next[j] - 1;
        b->isl_head[j] = 0;
        b->isl_next[j] = 0;
        b->sleep_t[j] = 0;
        b->dx[j] = 0;
        b->dy[j] = 0;
        b->cflags[j] &= ~CF_GROUNDED;
        if (body_partition(w, j) == BODY_PART_ASLEEP) j = body_move_to_partition(w, j, BODY_PART_ACTIVE);
        if (b->shape[j] != RG_SHAPE_NONE) broadphase_activate(&cw->bp, s);
        for (int32_t id = b->chead[j] - 1; id >= 0; id = contact_next(&cs->c[id], s))
            if (cs->c[id].awake < 0) contact_awake_add(cs, id);
        s = next;
    }
}

void island_wake_all(rg_world *w)
{
    while (w->b.n_moving > w->b.n_active) island_wake(w, w->b.slot[w->b.n_active]);
}

void island_wake_touching(rg_world *w, int32_t slot)
{
    contact_store *cs = &w->coll.contacts;
    int32_t id = w->b.chead[body_dense(w, slot)] - 1;
    while (id >= 0) {
        const contact *c = &cs->c[id];
        int32_t next = contact_next(c, slot);
        int32_t other = contact_other(c, slot);
        if (body_partition(w, body_dense(w, other)) == BODY_PART_ASLEEP) island_wake(w, other);
        id = next;
    }
}

typedef struct sleep_task {
    rg_world *w;
    rg_real dt;
    int pv_valid;
    int32_t any[RG_MAX_WORKERS], near[RG_MAX_WORKERS];
} sleep_task;

/* The rest timers of awake shaped bodies [begin, end) (their places in the broadphase's
 * active list), each body's own; whether one reached the sleep time, or will within two
 * steps, per worker. */
static void island_timers(int32_t begin, int32_t end, int32_t worker, void *context)
{
    sleep_task *t = context;
    rg_world *w = t->w;
    const collide_world *cw = &w->coll;
    const resolve_state *rs = &cw->resolve;
    body_store *b = &w->b;
    const rg_real *pv = rs->spv;
    rg_real thr2 = cw->sleep_speed * cw->sleep_speed, dt = t->dt;
    int any = 0, near = 0;
    for (int32_t k = begin; k < end; k++) {
        int32_t i = body_dense(w, cw->bp.active[k]);
        if (b->type[i] != RG_BODY_DYNAMIC) continue;
        rg_real v2 = b->vx[i] * b->vx[i] + b->vy[i] * b->vy[i];
        /* a body still being pushed out of a penetration is not at rest either */
        if (t->pv_valid && rs->sstamp[i] == rs->gen) { /* rows met it: solver body i + 1 */
            int32_t q = i + 1;
            v2 = rg_max(v2, pv[2 * q] * pv[2 * q] + pv[2 * q + 1] * pv[2 * q + 1]);
        }
        rg_real r = v2 < thr2 ? b->sleep_t[i] + dt : 0;
        b->sleep_t[i] = r;
        any |= r >= cw->sleep_time;
        near |= r + 2 * dt >= cw->sleep_time;
    }
    t->any[worker] |= any;
    t->near[worker] |= near;
}

/* Bodies per timer range. */
#define ISLAND_RANGE 512

/* The union-find runs over the awake shaped bodies (their places in the broadphase's active
 * list), so bodies without shapes, static and sleeping ones cost nothing here. */
void island_sleep(rg_world *w, rg_real dt, int united)
{
    collide_world *cw = &w->coll;
    contact_store *cs = &cw->contacts;
    island_state *is = &cw->island;
    resolve_state *rs = &cw->resolve;
    body_store *b = &w->b;
    broadphase *bp = &cw->bp;
    int32_t na = bp->n_active;
    int32_t *uf = is->uf;
    int any = 0, near = 0;
    sleep_task t;
    t.w = w;
    t.dt = dt;
    t.pv_valid = rs->pv_valid;
    rs->pv_valid = 0;
    if (!cw->sleeping) return;
    int32_t workers = task_workers(w);
    for (int32_t k = 0; k < workers; k++) t.any[k] = t.near[k] = 0;
    task_for(w, island_timers, na, ISLAND_RANGE, &t);
    for (int32_t k = 0; k < workers; k++) {
        any |= t.any[k];
        near |= t.near[k];
    }
    /* the narrowphase joins islands only when some body is about to fall asleep */
    is->near_sleep = near;
    if (!any) return;
    if (!united) {
        for (int32_t k = 0; k < na; k++) uf[k] = k;
        for (int32_t k = 0; k < cs->n_awake; k++) {
            const contact *c = &cs->c[cs->awake[k]];
            /* touching or solved (narrow.c's narrow_commit) */
            if ((c->flags & CT_SENSOR) || !(c->flags & (CT_TOUCHING | CT_SOLVE))) continue;
            int32_t pa = bp->e[c->sa].apos, pb = bp->e[c->sb].apos;
            if (pa < 0 || pb < 0) continue;
            if (b->type[body_dense(w, c->sa)] == RG_BODY_DYNAMIC && b->type[body_dense(w, c->sb)] == RG_BODY_DYNAMIC)
                island_unite(uf, pa, pb);
        }
    }
    /* island minimum of the rest time; kinematic bodies do not take part */
    rg_real *umin = is->umin;
    for (int32_t k = 0; k < na; k++) umin[k] = RG_HUGE;
    for (int32_t k = 0; k < w->springs.count; k++) {
        const spring *sp = &w->springs.items[k];
        if (sp->slot_b < 0) continue;
        int32_t ia = body_dense(w, sp->slot_a), ib = body_dense(w, sp->slot_b);
        if (b->type[ia] != RG_BODY_DYNAMIC || b->type[ib] != RG_BODY_DYNAMIC) continue;
        int32_t pa = sp->slot_a < bp->cap ? bp->e[sp->slot_a].apos : -1;
        int32_t pb = sp->slot_b < bp->cap ? bp->e[sp->slot_b].apos : -1;
        if (pa >= 0 && pb >= 0) {
            island_unite(uf, pa, pb);
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
        if (umin[k] < 0) umin[island_root(uf, k)] = 0;
    }
    for (int32_t k = 0; k < na; k++) {
        int32_t i = body_dense(w, bp->active[k]);
        if (b->type[i] != RG_BODY_DYNAMIC) continue;
        int32_t r = island_root(uf, k);
        if (b->sleep_t[i] < umin[r]) umin[r] = b->sleep_t[i];
    }
    /* link each sleeping island's members, in active-list order */
    int32_t *head = is->ihead, *tail = is->itail, *list = is->list;
    int32_t count = 0;
    for (int32_t k = 0; k < na; k++) head[k] = -1;
    for (int32_t k = 0; k < na; k++) {
        int32_t s = bp->active[k];
        int32_t i = body_dense(w, s);
        if (b->type[i] != RG_BODY_DYNAMIC) continue;
        int32_t r = island_root(uf, k);
        if (!(umin[r] >= cw->sleep_time)) continue;
        if (head[r] < 0) {
            head[r] = s;
        } else {
            b->isl_next[body_dense(w, tail[r])] = s + 1;
        }
        tail[r] = s;
        b->isl_head[i] = head[r] + 1;
        b->isl_next[i] = 0;
        list[count++] = s;
    }
    if (count == 0) return;
    for (int32_t k = 0; k < count; k++) {
        int32_t i = body_dense(w, list[k]);
        b->vx[i] = b->vy[i] = 0;
        b->dx[i] = b->dy[i] = 0;
        body_move_to_partition(w, i, BODY_PART_ASLEEP);
        broadphase_deactivate(bp, list[k]);
    }
    /* contacts with no awake body leave the awake list */
    for (int32_t k = 0; k < count; k++) {
        int32_t s = list[k];
        for (int32_t id = b->chead[body_dense(w, s)] - 1; id >= 0; id = contact_next(&cs->c[id], s)) {
            contact *c = &cs->c[id];
            if (c->awake < 0) continue;
            if (body_dense(w, c->sa) >= b->n_active && body_dense(w, c->sb) >= b->n_active)
                contact_awake_remove(cs, id);
        }
    }
}

/* ---------------------------------------------------------------- API */

RG_API rg_status rg_body_is_awake(const rg_world *world, rg_body body, int32_t *out_awake)
{
    BODY_GET(world, body, i);
    ARG_PTR(world, out_awake);
    *out_awake = body_partition(world, i) == BODY_PART_ACTIVE;
    return RG_OK;
}

RG_API rg_status rg_body_wake(rg_world *world, rg_body body)
{
    BODY_SET(world, body, i);
    if (world->b.type[i] != RG_BODY_STATIC) island_touch(world, world->b.slot[i]);
    return RG_OK;
}

RG_API int32_t rg_world_awake_body_count(const rg_world *world)
{
    if (world == NULL) return 0;
    ERROR_CLEAR(world);
    return world->b.n_active;
}

RG_API rg_status rg_world_set_sleeping(rg_world *world, int32_t enabled)
{
    WORLD_WRITABLE(world);
    ARG_INT(world, enabled, 0, 1, "0 or 1");
    if (!enabled) island_wake_all(world);
    world->coll.sleeping = enabled;
    return RG_OK;
}

RG_API rg_status rg_world_get_sleeping(const rg_world *world, int32_t *out_enabled)
{
    ERROR_BEGIN(world);
    ARG_PTR(world, out_enabled);
    *out_enabled = world->coll.sleeping;
    return RG_OK;
}

RG_API rg_status rg_world_set_sleep_thresholds(rg_world *world, rg_real speed, rg_real time)
{
    WORLD_WRITABLE(world);
    ARG_IN(world, speed, 0, RG_MAX_SPEED);
    ARG_ABOVE(world, time, 0, HUGE_VAL);
    world->coll.sleep_speed = speed;
    world->coll.sleep_time = time;
    return RG_OK;
}

RG_API rg_status rg_world_get_sleep_thresholds(const rg_world *world, rg_real *out_speed,
                                               rg_real *out_time)
{
    ERROR_BEGIN(world);
    ARG_PTR(world, out_speed);
    ARG_PTR(world, out_time);
    *out_speed = world->coll.sleep_speed;
    *out_time = world->coll.sleep_time;
    return RG_OK;
}
