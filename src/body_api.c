/* body_api.c: the rg_body_* API of body lifetime, state and forces. */
#include "body.h"
#include "island.h"
#include "pairs.h"
#include "shape.h"
#include "spring.h"
#include "state.h"
#include "vec2.h"

RG_API rg_status rg_body_create(rg_world *world, int32_t type, rg_real mass, rg_vec2 position,
                                rg_body *out_body)
{
    WORLD_WRITABLE(world);
    if (world == NULL || out_body == NULL || !rg_vec2_finite(position) || !rg_finite(mass))
        return RG_ERR_INVALID_ARGUMENT;
    if (type != RG_BODY_STATIC && type != RG_BODY_KINEMATIC && type != RG_BODY_DYNAMIC)
        return RG_ERR_INVALID_ARGUMENT;
    if (type == RG_BODY_DYNAMIC && !(mass > 0)) return RG_ERR_INVALID_ARGUMENT;
    rg_status st = body_reserve(world);
    if (st != RG_OK) return st;
    *out_body = body_add(world, type, mass, position);
    return RG_OK;
}

RG_API rg_status rg_body_destroy(rg_world *world, rg_body body)
{
    WORLD_WRITABLE(world);
    if (world == NULL) return RG_ERR_INVALID_ARGUMENT;
    int32_t i = body_lookup(world, body);
    if (i < 0) return RG_ERR_STALE_HANDLE;
    int32_t s = world->b.slot[i];
    shape_remove(world, s); /* ends its contacts, wakes what rested on it */
    spring_detach_body(world, s);
    body_remove(world, body);
    return RG_OK;
}

RG_API int32_t rg_body_is_valid(const rg_world *world, rg_body body)
{
    return world != NULL && body_lookup(world, body) >= 0;
}

RG_API rg_status rg_body_get_type(const rg_world *world, rg_body body, int32_t *out_type)
{
    BODY_GET(world, body, i);
    if (out_type == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out_type = world->b.type[i];
    return RG_OK;
}

RG_API rg_status rg_body_get_mass(const rg_world *world, rg_body body, rg_real *out_mass)
{
    BODY_GET(world, body, i);
    if (out_mass == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out_mass = world->b.mass[i];
    return RG_OK;
}

RG_API rg_status rg_body_set_mass(rg_world *world, rg_body body, rg_real mass)
{
    BODY_SET(world, body, i);
    if (!rg_finite(mass) || !(mass > 0) || world->b.type[i] != RG_BODY_DYNAMIC)
        return RG_ERR_INVALID_ARGUMENT;
    world->b.mass[i] = mass;
    world->b.inv_mass[i] = 1 / mass;
    return RG_OK;
}

static rg_status get_pair(const rg_world *world, rg_body body, const rg_real *xs,
                          const rg_real *ys, rg_vec2 *out)
{
    BODY_GET(world, body, i);
    if (out == NULL) return RG_ERR_INVALID_ARGUMENT;
    out->x = xs[i];
    out->y = ys[i];
    return RG_OK;
}

RG_API rg_status rg_body_get_position(const rg_world *world, rg_body body, rg_vec2 *out)
{
    if (world == NULL) return RG_ERR_INVALID_ARGUMENT;
    return get_pair(world, body, world->b.x, world->b.y, out);
}

RG_API rg_status rg_body_get_velocity(const rg_world *world, rg_body body, rg_vec2 *out)
{
    if (world == NULL) return RG_ERR_INVALID_ARGUMENT;
    return get_pair(world, body, world->b.vx, world->b.vy, out);
}

RG_API rg_status rg_body_get_acceleration(const rg_world *world, rg_body body, rg_vec2 *out)
{
    if (world == NULL) return RG_ERR_INVALID_ARGUMENT;
    return get_pair(world, body, world->b.ax, world->b.ay, out);
}

RG_API rg_status rg_body_get_interpolated_position(const rg_world *world, rg_body body,
                                                   rg_vec2 *out)
{
    BODY_GET(world, body, i);
    if (out == NULL) return RG_ERR_INVALID_ARGUMENT;
    const body_store *b = &world->b;
    if (!world->prev_valid) {
        out->x = b->x[i];
        out->y = b->y[i];
        return RG_OK;
    }
    rg_real alpha = (rg_real)(world->accumulator / world->fixed_dt);
    out->x = b->px[i] + alpha * (b->x[i] - b->px[i]);
    out->y = b->py[i] + alpha * (b->y[i] - b->py[i]);
    return RG_OK;
}

RG_API rg_status rg_body_set_position(rg_world *world, rg_body body, rg_vec2 position)
{
    BODY_SET(world, body, i);
    if (!rg_vec2_finite(position)) return RG_ERR_INVALID_ARGUMENT;
    body_store *b = &world->b;
    int32_t s = b->slot[i];
    b->x[i] = b->px[i] = position.x; /* a teleport is not interpolated */
    b->y[i] = b->py[i] = position.y;
    island_touch(world, s);
    pairs_teleported(world, s);
    return RG_OK;
}

RG_API rg_status rg_body_set_velocity(rg_world *world, rg_body body, rg_vec2 velocity)
{
    BODY_SET(world, body, i);
    if (!rg_vec2_finite(velocity)) return RG_ERR_INVALID_ARGUMENT;
    body_store *b = &world->b;
    if (b->type[i] == RG_BODY_STATIC && (velocity.x != 0 || velocity.y != 0))
        return RG_ERR_INVALID_ARGUMENT;
    b->vx[i] = velocity.x;
    b->vy[i] = velocity.y;
    island_touch(world, b->slot[i]);
    return RG_OK;
}

RG_API rg_status rg_body_apply_force(rg_world *world, rg_body body, rg_vec2 force)
{
    BODY_SET(world, body, i);
    if (!rg_vec2_finite(force)) return RG_ERR_INVALID_ARGUMENT;
    body_store *b = &world->b;
    if (b->type[i] != RG_BODY_DYNAMIC) return RG_OK;
    rg_real fx = b->fx[i] + force.x, fy = b->fy[i] + force.y;
    if (!rg_finite(fx) || !rg_finite(fy)) return RG_ERR_INVALID_ARGUMENT; /* sum overflowed */
    b->fx[i] = fx;
    b->fy[i] = fy;
    island_touch(world, b->slot[i]);
    return RG_OK;
}

RG_API rg_status rg_body_apply_impulse(rg_world *world, rg_body body, rg_vec2 impulse)
{
    BODY_SET(world, body, i);
    if (!rg_vec2_finite(impulse)) return RG_ERR_INVALID_ARGUMENT;
    body_store *b = &world->b;
    if (b->type[i] != RG_BODY_DYNAMIC) return RG_OK;
    rg_real vx = b->vx[i] + impulse.x * b->inv_mass[i];
    rg_real vy = b->vy[i] + impulse.y * b->inv_mass[i];
    if (!rg_finite(vx) || !rg_finite(vy)) return RG_ERR_INVALID_ARGUMENT;
    b->vx[i] = vx;
    b->vy[i] = vy;
    island_touch(world, b->slot[i]);
    return RG_OK;
}

RG_API rg_status rg_body_set_gravity_scale(rg_world *world, rg_body body, rg_real scale)
{
    BODY_SET(world, body, i);
    if (!rg_finite(scale)) return RG_ERR_INVALID_ARGUMENT;
    if (world->b.type[i] == RG_BODY_DYNAMIC) world->b.gscale[i] = scale;
    return RG_OK;
}

RG_API rg_status rg_body_set_drag(rg_world *world, rg_body body, rg_real linear, rg_real quadratic)
{
    BODY_SET(world, body, i);
    if (!rg_finite(linear) || !rg_finite(quadratic) || linear < 0 || quadratic < 0)
        return RG_ERR_INVALID_ARGUMENT;
    world->b.drag_lin[i] = linear;
    world->b.drag_quad[i] = quadratic;
    body_update_flags(world, i);
    return RG_OK;
}

RG_API rg_status rg_body_set_surface_friction(rg_world *world, rg_body body, rg_real mu,
                                              rg_real normal_force)
{
    BODY_SET(world, body, i);
    if (!rg_finite(mu) || !rg_finite(normal_force) || mu < 0 || normal_force < 0)
        return RG_ERR_INVALID_ARGUMENT;
    rg_real f = mu * normal_force;
    if (!rg_finite(f)) return RG_ERR_INVALID_ARGUMENT;
    world->b.fric[i] = f;
    body_update_flags(world, i);
    return RG_OK;
}

RG_API rg_status rg_body_set_speed_limits(rg_world *world, rg_body body, rg_real min_speed,
                                          rg_real max_speed)
{
    BODY_SET(world, body, i);
    if (!rg_finite(min_speed) || !rg_finite(max_speed) || min_speed < 0 || max_speed < 0 ||
        (max_speed > 0 && max_speed < min_speed))
        return RG_ERR_INVALID_ARGUMENT;
    world->b.min_speed[i] = min_speed;
    world->b.max_speed[i] = max_speed;
    body_update_flags(world, i);
    return RG_OK;
}

RG_API rg_status rg_body_set_user_data(rg_world *world, rg_body body, uint64_t user_data)
{
    BODY_SET(world, body, i);
    world->b.user[i] = user_data;
    return RG_OK;
}

RG_API rg_status rg_body_get_user_data(const rg_world *world, rg_body body, uint64_t *out)
{
    BODY_GET(world, body, i);
    if (out == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out = world->b.user[i];
    return RG_OK;
}
