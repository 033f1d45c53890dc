/* shape.c: the shape, material, sensor, filter and grounded API of bodies. */
#include "arg.h"
#include "body.h"
#include "contact.h"
#include "island.h"
#include "pairs.h"
#include "shape.h"
#include "state.h"
#include "vec2.h"

/* Ends every contact of slot s (end events reported with the next step), waking the
 * sleeping bodies on the other side. */
static void shape_end_contacts(rg_world *w, int32_t s)
{
    contact_store *cs = &w->coll.contacts;
    for (;;) {
        int32_t id = w->b.chead[body_dense(w, s)] - 1;
        if (id < 0) return;
        int32_t other = contact_other(&cs->c[id], s);
        if (body_partition(w, body_dense(w, other)) == BODY_PART_ASLEEP) island_wake(w, other);
        contact_destroy(w, id);
    }
}

static void shape_clear(rg_world *w, int32_t s)
{
    body_store *b = &w->b;
    shape_end_contacts(w, s);
    int32_t i = body_dense(w, s);
    broadphase_remove(&w->coll.bp, s);
    w->coll.shape_count--;
    b->shape[i] = RG_SHAPE_NONE;
    b->hx[i] = b->hy[i] = 0;
    b->cflags[i] &= ~(CF_GROUNDED | CF_TELEPORTED);
}

void shape_remove(rg_world *w, int32_t slot)
{
    island_touch(w, slot);
    if (w->b.shape[body_dense(w, slot)] != RG_SHAPE_NONE) shape_clear(w, slot);
}

static rg_status shape_set(rg_world *w, const char *func, int32_t i, int32_t kind, rg_real hx,
                           rg_real hy)
{
    collide_world *cw = &w->coll;
    body_store *b = &w->b;
    int32_t s = b->slot[i];
    int fresh = b->shape[i] == RG_SHAPE_NONE;
    if (fresh) {
        rg_status st = broadphase_reserve(&cw->bp, &w->mem, w->body_pool.slot_count, cw->bp.count + 1);
        if (st != RG_OK) return error_alloc(w, func, st, "broadphase", "RG_MAX_BODIES");
    }
    island_touch(w, s);
    i = body_dense(w, s);
    b->shape[i] = kind;
    b->hx[i] = hx;
    b->hy[i] = hy;
    if (fresh) {
        pairs_insert(w, s);
        cw->shape_count++;
    }
    pairs_teleported(w, s);
    return RG_OK;
}

RG_API rg_status rg_body_set_circle(rg_world *world, rg_body body, rg_real radius)
{
    BODY_SET(world, body, i);
    ARG_IN(world, radius, RG_MIN_SHAPE_SIZE, RG_MAX_SHAPE_SIZE);
    return shape_set(world, __func__, i, RG_SHAPE_CIRCLE, radius, radius);
}

RG_API rg_status rg_body_set_aabb(rg_world *world, rg_body body, rg_real half_width,
                                  rg_real half_height)
{
    BODY_SET(world, body, i);
    ARG_IN(world, half_width, RG_MIN_SHAPE_SIZE, RG_MAX_SHAPE_SIZE);
    ARG_IN(world, half_height, RG_MIN_SHAPE_SIZE, RG_MAX_SHAPE_SIZE);
    return shape_set(world, __func__, i, RG_SHAPE_AABB, half_width, half_height);
}

RG_API rg_status rg_body_clear_shape(rg_world *world, rg_body body)
{
    BODY_SET(world, body, i);
    if (world->b.shape[i] == RG_SHAPE_NONE) return RG_OK;
    shape_remove(world, world->b.slot[i]);
    return RG_OK;
}

RG_API rg_status rg_body_get_shape(const rg_world *world, rg_body body, int32_t *out_kind,
                                   rg_vec2 *out_half_extents)
{
    BODY_GET(world, body, i);
    if (out_kind == NULL && out_half_extents == NULL)
        return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "out_kind and out_half_extents are both NULL");
    if (out_kind != NULL) *out_kind = world->b.shape[i];
    if (out_half_extents != NULL) *out_half_extents = rg_v2(world->b.hx[i], world->b.hy[i]);
    return RG_OK;
}

RG_API rg_status rg_body_set_restitution(rg_world *world, rg_body body, rg_real restitution)
{
    BODY_SET(world, body, i);
    ARG_IN(world, restitution, 0, 1);
    world->b.rest[i] = restitution;
    contact_refresh_materials(world, world->b.slot[i]);
    return RG_OK;
}

RG_API rg_status rg_body_get_restitution(const rg_world *world, rg_body body, rg_real *out)
{
    BODY_GET(world, body, i);
    ARG_PTR(world, out);
    *out = world->b.rest[i];
    return RG_OK;
}

RG_API rg_status rg_body_set_friction(rg_world *world, rg_body body, rg_real mu)
{
    BODY_SET(world, body, i);
    ARG_IN(world, mu, 0, RG_MAX_FRICTION);
    int changed = mu != world->b.mu[i];
    world->b.mu[i] = mu;
    int32_t s = world->b.slot[i];
    contact_refresh_materials(world, s);
    if (changed) {
        /* what its friction held at rest (against wind, sideways gravity) may slide: the
         * body and what touches it wake (a static body never sleeps) */
        if (world->b.type[i] != RG_BODY_STATIC) island_touch(world, s);
        island_wake_touching(world, s);
    }
    return RG_OK;
}

RG_API rg_status rg_body_get_friction(const rg_world *world, rg_body body, rg_real *out)
{
    BODY_GET(world, body, i);
    ARG_PTR(world, out);
    *out = world->b.mu[i];
    return RG_OK;
}

RG_API rg_status rg_body_set_sensor(rg_world *world, rg_body body, int32_t is_sensor)
{
    BODY_SET(world, body, i);
    ARG_INT(world, is_sensor, 0, 1, "0 or 1");
    body_store *b = &world->b;
    if (((b->cflags[i] & CF_SENSOR) != 0) == (is_sensor != 0)) return RG_OK;
    int32_t s = b->slot[i];
    island_touch(world, s);
    if (b->shape[body_dense(world, s)] != RG_SHAPE_NONE) {
        shape_end_contacts(world, s);
        broadphase_mark_moved(&world->coll.bp, s);
    }
    b->cflags[body_dense(world, s)] ^= CF_SENSOR;
    return RG_OK;
}

RG_API rg_status rg_body_is_sensor(const rg_world *world, rg_body body, int32_t *out_is_sensor)
{
    BODY_GET(world, body, i);
    ARG_PTR(world, out_is_sensor);
    *out_is_sensor = (world->b.cflags[i] & CF_SENSOR) != 0;
    return RG_OK;
}

RG_API rg_status rg_body_set_filter(rg_world *world, rg_body body, uint32_t category, uint32_t mask)
{
    BODY_SET(world, body, i);
    body_store *b = &world->b;
    contact_store *cs = &world->coll.contacts;
    if (b->cat[i] == category && b->mask[i] == mask) return RG_OK;
    int32_t s = b->slot[i];
    b->cat[i] = category;
    b->mask[i] = mask;
    island_touch(world, s);
    if (b->shape[body_dense(world, s)] == RG_SHAPE_NONE) return RG_OK;
    /* end the contacts the new filter rejects; new pairs are searched at the next step */
    int32_t id = b->chead[body_dense(world, s)] - 1;
    while (id >= 0) {
        int32_t next = contact_next(&cs->c[id], s);
        int32_t other = contact_other(&cs->c[id], s);
        if (!pairs_admitted(world, body_dense(world, s), body_dense(world, other))) {
            if (body_partition(world, body_dense(world, other)) == BODY_PART_ASLEEP) {
                island_wake(world, other);
                next = contact_next(&cs->c[id], s);
            }
            contact_destroy(world, id);
        }
        id = next;
    }
    broadphase_mark_moved(&world->coll.bp, s);
    return RG_OK;
}

RG_API rg_status rg_body_get_filter(const rg_world *world, rg_body body, uint32_t *out_category,
                                    uint32_t *out_mask)
{
    BODY_GET(world, body, i);
    ARG_PTR(world, out_category);
    ARG_PTR(world, out_mask);
    *out_category = world->b.cat[i];
    *out_mask = world->b.mask[i];
    return RG_OK;
}

RG_API rg_status rg_body_set_one_way(rg_world *world, rg_body body, rg_vec2 normal)
{
    BODY_SET(world, body, i);
    ARG_VEC_FINITE(world, normal);
    rg_real len = rg_v2_len(normal);
    int two_way = normal.x == 0 && normal.y == 0;
    if (!two_way && !(rg_fabs(len - 1) <= RG_R(1e-3)))
        return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "normal (%g, %g) has length %g, not 1 (within 1e-3) nor 0",
                       (double)normal.x, (double)normal.y, (double)len);
    body_store *b = &world->b;
    b->owx[i] = two_way ? 0 : normal.x / len;
    b->owy[i] = two_way ? 0 : normal.y / len;
    contact_refresh_flags(world, b->slot[i]);
    return RG_OK;
}

RG_API rg_status rg_body_get_one_way(const rg_world *world, rg_body body, rg_vec2 *out_normal)
{
    BODY_GET(world, body, i);
    ARG_PTR(world, out_normal);
    *out_normal = rg_v2(world->b.owx[i], world->b.owy[i]);
    return RG_OK;
}

RG_API rg_status rg_body_is_grounded(const rg_world *world, rg_body body, int32_t *out_grounded)
{
    BODY_GET(world, body, i);
    ARG_PTR(world, out_grounded);
    *out_grounded = world->b.type[i] == RG_BODY_DYNAMIC && (world->b.cflags[i] & CF_GROUNDED) != 0;
    return RG_OK;
}
