/* draw.c: the debug-draw walk (rg_world_draw): shapes, contacts, velocities, fat boxes and
 * springs handed to the caller's callbacks in a fixed order. */
#include "arg.h"
#include "body.h"
#include "contact.h"
#include "state.h"
#include "vec2.h"

/* The colour of body i's shape: sensors first, then by type and sleep state. */
static uint32_t draw_color(const rg_world *w, int32_t i)
{
    const body_store *b = &w->b;
    if (b->cflags[i] & CF_SENSOR) return RG_COLOR_SENSOR;
    if (b->type[i] == RG_BODY_STATIC) return RG_COLOR_STATIC;
    if (b->type[i] == RG_BODY_KINEMATIC) return RG_COLOR_KINEMATIC;
    return body_partition(w, i) == BODY_PART_ACTIVE ? RG_COLOR_AWAKE : RG_COLOR_SLEEPING;
}

/* Every live body in slot order (the order of creation, reused slots in place), which no
 * step, sleep or wake reorders; `flags` is the one layer drawn in this pass. */
static void draw_bodies(const rg_world *w, const rg_debug_draw *d, uint32_t flags)
{
    const body_store *b = &w->b;
    const pool *p = &w->body_pool;
    for (int32_t s = 0; s < p->slot_count; s++) {
        int32_t i = p->index[s];
        if (i < 0 || p->gen[s] == 0) continue;
        rg_body h = pool_handle(p, s);
        rg_vec2 c = rg_v2(b->x[i], b->y[i]);
        uint32_t col = draw_color(w, i);
        if (flags & RG_DRAW_SHAPES) {
            if (b->shape[i] == RG_SHAPE_CIRCLE) {
                if (d->circle != NULL) d->circle(h, c, b->hx[i], col, d->user);
            } else if (b->shape[i] == RG_SHAPE_AABB) {
                if (d->box != NULL)
                    d->box(h, rg_v2(c.x - b->hx[i], c.y - b->hy[i]), rg_v2(c.x + b->hx[i], c.y + b->hy[i]),
                           col, d->user);
            } else if (d->point != NULL) {
                d->point(c, col, d->user);
            }
        }
        if ((flags & RG_DRAW_BOUNDS) && d->box != NULL && broadphase_contains(&w->coll.bp, s)) {
            const bp_entry *e = &w->coll.bp.e[s];
            d->box(h, rg_v2(e->lx, e->ly), rg_v2(e->ux, e->uy), RG_COLOR_BOUNDS, d->user);
        }
        if ((flags & RG_DRAW_VELOCITIES) && d->segment != NULL && b->type[i] != RG_BODY_STATIC &&
            (b->vx[i] != 0 || b->vy[i] != 0)) {
            rg_vec2 tip = rg_v2(c.x + b->vx[i] * RG_R(RG_DRAW_VELOCITY_SCALE), c.y + b->vy[i] * RG_R(RG_DRAW_VELOCITY_SCALE));
            d->segment(c, tip, RG_COLOR_VELOCITY, d->user);
        }
    }
}

/* Touching contacts by id: the point, and the normal from a toward b over RG_DRAW_NORMAL_LENGTH. */
static void draw_contacts(const rg_world *w, const rg_debug_draw *d)
{
    const contact_store *cw = &w->coll.contacts;
    for (int32_t id = 0; id < cw->cap; id++) {
        const contact *c = &cw->c[id];
        if (!(c->flags & CT_TOUCHING)) continue;
        /* where the shapes touch now, as rg_body_get_contacts reports it */
        coll_manifold m;
        contact_manifold_now(w, body_dense(w, c->sa), body_dense(w, c->sb), &m);
        rg_vec2 p = m.point;
        uint32_t col = (c->flags & CT_SENSOR) ? RG_COLOR_SENSOR : RG_COLOR_CONTACT;
        if (d->point != NULL) d->point(p, col, d->user);
        if (d->segment != NULL)
            d->segment(p, rg_v2(p.x + m.normal.x * RG_R(RG_DRAW_NORMAL_LENGTH), p.y + m.normal.y * RG_R(RG_DRAW_NORMAL_LENGTH)),
                       col, d->user);
    }
}

/* Springs in creation order (dense order of the spring store follows it until one is
 * destroyed): a segment between the two ends, or from the body to its anchor. */
static void draw_springs(const rg_world *w, const rg_debug_draw *d)
{
    const body_store *b = &w->b;
    if (d->segment == NULL) return;
    for (int32_t k = 0; k < w->springs.count; k++) {
        const spring *sp = &w->springs.items[k];
        int32_t ia = pool_dense(&w->body_pool, sp->slot_a);
        rg_vec2 pa = rg_v2(b->x[ia], b->y[ia]), pb = sp->anchor;
        if (sp->slot_b >= 0) {
            int32_t ib = pool_dense(&w->body_pool, sp->slot_b);
            pb = rg_v2(b->x[ib], b->y[ib]);
        }
        d->segment(pa, pb, RG_COLOR_SPRING, d->user);
    }
}

RG_API rg_status rg_world_draw(const rg_world *world, const rg_debug_draw *draw)
{
    ERROR_BEGIN(world);
    ARG_PTR(world, draw);
    const uint32_t all = RG_DRAW_SHAPES | RG_DRAW_CONTACTS | RG_DRAW_VELOCITIES | RG_DRAW_BOUNDS | RG_DRAW_SPRINGS;
    if (draw->flags & ~all)
        return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "draw->flags 0x%x has bits outside RG_DRAW_* (0x%x)",
                       (unsigned)draw->flags, (unsigned)all);
    /* The callbacks may call on the world: a change while the walk is on it is refused (the
     * world is locked; its `const` is the caller's promise, not the object's, which
     * rg_world_create made).  A draw from inside a step's callback leaves the step's lock. */
    rg_world *lock = (rg_world *)(uintptr_t)world;
    int32_t was = lock->locked;
    lock->locked = 1;
    /* layers bottom-up: shapes, fat boxes, springs, velocities, contacts */
    if (draw->flags & RG_DRAW_SHAPES) draw_bodies(world, draw, RG_DRAW_SHAPES);
    if (draw->flags & RG_DRAW_BOUNDS) draw_bodies(world, draw, RG_DRAW_BOUNDS);
    if (draw->flags & RG_DRAW_SPRINGS) draw_springs(world, draw);
    if (draw->flags & RG_DRAW_VELOCITIES) draw_bodies(world, draw, RG_DRAW_VELOCITIES);
    if (draw->flags & RG_DRAW_CONTACTS) draw_contacts(world, draw);
    lock->locked = was;
    ERROR_CLEAR(world); /* the callbacks' own calls on the world are not this call's */
    return RG_OK;
}
