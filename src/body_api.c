/* body_api.c: the rg_body_* API of body lifetime, state and forces. */
#include "arg.h"
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
    ARG_INT(world, type, RG_BODY_STATIC, RG_BODY_DYNAMIC, "one of RG_BODY_* (0..2)");
    if (type == RG_BODY_DYNAMIC)
        ARG_IN(world, mass, RG_MIN_MASS, RG_MAX_MASS);
    else
        ARG_FINITE(world, mass);
    ARG_VEC(world, position, RG_MAX_COORD);
    ARG_PTR(world, out_body);
    rg_status st = body_reserve(world);
    if (st != RG_OK) return error_alloc(world, __func__, st, "body storage", "RG_MAX_BODIES");
    *out_body = body_add(world, type, mass, position);
    return RG_OK;
}

RG_API rg_status rg_body_destroy(rg_world *world, rg_body body)
{
    BODY_SET(world, body, i);
    int32_t s = world->b.slot[i];
    shape_remove(world, s); /* ends its contacts, wakes what rested on it */
    spring_detach_body(world, s);
    body_remove(world, body);
    return RG_OK;
}

RG_API int32_t rg_body_is_valid(const rg_world *world, rg_body body)
{
    if (world == NULL) return 0;
    ERROR_CLEAR(world);
    return body_lookup(world, body) >= 0;
}

RG_API rg_status rg_body_get_type(const rg_world *world, rg_body body, int32_t *out_type)
{
    BODY_GET(world, body, i);
    ARG_PTR(world, out_type);
    *out_type = world->b.type[i];
    return RG_OK;
}

RG_API rg_status rg_body_get_mass(const rg_world *world, rg_body body, rg_real *out_mass)
{
    BODY_GET(world, body, i);
    ARG_PTR(world, out_mass);
    *out_mass = world->b.mass[i];
    return RG_OK;
}

RG_API rg_status rg_body_set_mass(rg_world *world, rg_body body, rg_real mass)
{
    BODY_SET(world, body, i);
    ARG_IN(world, mass, RG_MIN_MASS, RG_MAX_MASS);
    if (world->b.type[i] != RG_BODY_DYNAMIC)
        return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "body is not dynamic (only a dynamic body has a mass)");
    int changed = mass != world->b.mass[i];
    world->b.mass[i] = mass;
    world->b.inv_mass[i] = 1 / mass;
    /* asleep, it would not feel it (held by a spring, or by friction against wind) */
    if (changed) island_touch(world, world->b.slot[i]);
    return RG_OK;
}

/* (xs[i], ys[i]) of body into *out, for the getter `func` of a pair of fields. */
static rg_status get_pair(const rg_world *world, const char *func, rg_body body,
                          const rg_real *xs, const rg_real *ys, rg_vec2 *out)
{
    int32_t i = arg_handle(world, func, "body", &world->body_pool, body);
    if (i < 0) return RG_ERR_STALE_HANDLE;
    if (!arg_ptr(world, func, "out", out)) return RG_ERR_INVALID_ARGUMENT;
    out->x = xs[i];
    out->y = ys[i];
    return RG_OK;
}

RG_API rg_status rg_body_get_position(const rg_world *world, rg_body body, rg_vec2 *out)
{
    ERROR_BEGIN(world);
    return get_pair(world, __func__, body, world->b.x, world->b.y, out);
}

RG_API rg_status rg_body_get_velocity(const rg_world *world, rg_body body, rg_vec2 *out)
{
    ERROR_BEGIN(world);
    return get_pair(world, __func__, body, world->b.vx, world->b.vy, out);
}

/* (xs[i], ys[i]) of body, or (NaN, NaN) and the error set, for the by-value getter func. */
static rg_vec2 pair_value(const rg_world *world, const char *func, rg_body body,
                          const rg_real *xs, const rg_real *ys)
{
    int32_t i = arg_handle(world, func, "body", &world->body_pool, body);
    if (i < 0) return (rg_vec2){ (rg_real)NAN, (rg_real)NAN };
    return (rg_vec2){ xs[i], ys[i] };
}

RG_API rg_vec2 rg_body_position(const rg_world *world, rg_body body)
{
    if (world == NULL) return (rg_vec2){ (rg_real)NAN, (rg_real)NAN };
    ERROR_CLEAR(world);
    return pair_value(world, __func__, body, world->b.x, world->b.y);
}

RG_API rg_vec2 rg_body_velocity(const rg_world *world, rg_body body)
{
    if (world == NULL) return (rg_vec2){ (rg_real)NAN, (rg_real)NAN };
    ERROR_CLEAR(world);
    return pair_value(world, __func__, body, world->b.vx, world->b.vy);
}

RG_API rg_status rg_body_get_acceleration(const rg_world *world, rg_body body, rg_vec2 *out)
{
    ERROR_BEGIN(world);
    return get_pair(world, __func__, body, world->b.ax, world->b.ay, out);
}

RG_API rg_status rg_body_get_interpolated_position(const rg_world *world, rg_body body,
                                                   rg_vec2 *out)
{
    BODY_GET(world, body, i);
    ARG_PTR(world, out);
    const body_store *b = &world->b;
    if (!world->prev_valid) {
        out->x = b->x[i];
        out->y = b->y[i];
        return RG_OK;
    }
    /* at most 1: where the next advance owes steps (memory, a shorter fixed step), the
     * current position, never one ahead of it */
    rg_real alpha = (rg_real)rg_min(world->accumulator / world->fixed_dt, 1.0);
    out->x = b->px[i] + alpha * (b->x[i] - b->px[i]);
    out->y = b->py[i] + alpha * (b->y[i] - b->py[i]);
    return RG_OK;
}

RG_API rg_status rg_body_set_position(rg_world *world, rg_body body, rg_vec2 position)
{
    BODY_SET(world, body, i);
    ARG_VEC(world, position, RG_MAX_COORD);
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
    ARG_VEC(world, velocity, RG_MAX_SPEED);
    body_store *b = &world->b;
    if (b->type[i] == RG_BODY_STATIC && (velocity.x != 0 || velocity.y != 0))
        return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "velocity (%g, %g) of a static body is not 0",
                       (double)velocity.x, (double)velocity.y);
    b->vx[i] = velocity.x;
    b->vy[i] = velocity.y;
    island_touch(world, b->slot[i]);
    return RG_OK;
}

RG_API rg_status rg_body_apply_force(rg_world *world, rg_body body, rg_vec2 force)
{
    BODY_SET(world, body, i);
    ARG_VEC(world, force, RG_MAX_FORCE);
    body_store *b = &world->b;
    if (b->type[i] != RG_BODY_DYNAMIC) return RG_OK;
    rg_real fx = b->fx[i] + force.x, fy = b->fy[i] + force.y;
    if (!(rg_fabs(fx) <= (rg_real)RG_MAX_FORCE && rg_fabs(fy) <= (rg_real)RG_MAX_FORCE)) {
        int g = arg_digits((double)rg_max(rg_fabs(fx), rg_fabs(fy)), RG_MAX_FORCE);
        return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT,
                       "force (%g, %g) makes the step's applied force (%.*g, %.*g), beyond RG_MAX_FORCE (%g)",
                       (double)force.x, (double)force.y, g, (double)fx, g, (double)fy, RG_MAX_FORCE);
    }
    b->fx[i] = fx;
    b->fy[i] = fy;
    world->forces_applied = 1;
    island_touch(world, b->slot[i]);
    return RG_OK;
}

RG_API rg_status rg_body_apply_impulse(rg_world *world, rg_body body, rg_vec2 impulse)
{
    BODY_SET(world, body, i);
    ARG_VEC(world, impulse, RG_MAX_FORCE);
    body_store *b = &world->b;
    if (b->type[i] != RG_BODY_DYNAMIC) return RG_OK;
    rg_real vx = b->vx[i] + impulse.x * b->inv_mass[i];
    rg_real vy = b->vy[i] + impulse.y * b->inv_mass[i];
    if (!(rg_fabs(vx) <= (rg_real)RG_MAX_SPEED && rg_fabs(vy) <= (rg_real)RG_MAX_SPEED)) {
        int g = arg_digits((double)rg_max(rg_fabs(vx), rg_fabs(vy)), RG_MAX_SPEED);
        return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT,
                       "impulse (%g, %g) makes the velocity (%.*g, %.*g), beyond RG_MAX_SPEED (%g)",
                       (double)impulse.x, (double)impulse.y, g, (double)vx, g, (double)vy, RG_MAX_SPEED);
    }
    b->vx[i] = vx;
    b->vy[i] = vy;
    island_touch(world, b->slot[i]);
    return RG_OK;
}

RG_API rg_status rg_body_set_gravity_scale(rg_world *world, rg_body body, rg_real scale)
{
    BODY_SET(world, body, i);
    ARG_ABS(world, scale, RG_MAX_GRAVITY_SCALE);
    if (world->b.type[i] != RG_BODY_DYNAMIC) return RG_OK;
    int changed = scale != world->b.gscale[i];
    world->b.gscale[i] = scale;
    body_update_flags(world, i);
    if (changed) island_touch(world, world->b.slot[i]); /* asleep, it would not feel it */
    return RG_OK;
}

RG_API rg_status rg_body_set_drag(rg_world *world, rg_body body, rg_real linear, rg_real quadratic)
{
    BODY_SET(world, body, i);
    ARG_IN(world, linear, 0, RG_MAX_DRAG);
    ARG_IN(world, quadratic, 0, RG_MAX_DRAG);
    world->b.drag_lin[i] = linear;
    world->b.drag_quad[i] = quadratic;
    body_update_flags(world, i);
    return RG_OK;
}

RG_API rg_status rg_body_set_surface_friction(rg_world *world, rg_body body, rg_real mu,
                                              rg_real normal_force)
{
    BODY_SET(world, body, i);
    ARG_IN(world, mu, 0, RG_MAX_FRICTION);
    ARG_IN(world, normal_force, 0, RG_MAX_FORCE);
    rg_real fric = mu * normal_force; /* <= 1e15 N */
    int changed = fric != world->b.fric[i];
    world->b.fric[i] = fric;
    body_update_flags(world, i);
    if (changed) island_touch(world, world->b.slot[i]); /* what it held at rest may move */
    return RG_OK;
}

RG_API rg_status rg_body_get_gravity_scale(const rg_world *world, rg_body body, rg_real *out_scale)
{
    BODY_GET(world, body, i);
    ARG_PTR(world, out_scale);
    *out_scale = world->b.gscale[i];
    return RG_OK;
}

/* (as[i], bs[i]) of body into *out_a and *out_b (either may be NULL, not both: `names`
 * says so), for the getter `func` of two fields. */
static rg_status get_two(const rg_world *world, const char *func, rg_body body, const rg_real *as,
                         const rg_real *bs, rg_real *out_a, rg_real *out_b, const char *names)
{
    int32_t i = arg_handle(world, func, "body", &world->body_pool, body);
    if (i < 0) return RG_ERR_STALE_HANDLE;
    if (out_a == NULL && out_b == NULL)
        return error_set(world, RG_ERR_INVALID_ARGUMENT, func, "%s are both NULL", names);
    if (out_a != NULL) *out_a = as[i];
    if (out_b != NULL) *out_b = bs[i];
    return RG_OK;
}

RG_API rg_status rg_body_get_drag(const rg_world *world, rg_body body, rg_real *out_linear,
                                  rg_real *out_quadratic)
{
    ERROR_BEGIN(world);
    return get_two(world, __func__, body, world->b.drag_lin, world->b.drag_quad, out_linear, out_quadratic,
                   "out_linear and out_quadratic");
}

RG_API rg_status rg_body_get_speed_limits(const rg_world *world, rg_body body, rg_real *out_min_speed,
                                          rg_real *out_max_speed)
{
    ERROR_BEGIN(world);
    return get_two(world, __func__, body, world->b.min_speed, world->b.max_speed, out_min_speed,
                   out_max_speed, "out_min_speed and out_max_speed");
}

RG_API rg_status rg_body_set_speed_limits(rg_world *world, rg_body body, rg_real min_speed,
                                          rg_real max_speed)
{
    BODY_SET(world, body, i);
    ARG_IN(world, min_speed, 0, RG_MAX_SPEED);
    ARG_IN(world, max_speed, 0, RG_MAX_SPEED);
    if (max_speed > 0 && max_speed < min_speed)
        return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "max_speed %g is below min_speed %g (and not 0: no limit)",
                       (double)max_speed, (double)min_speed);
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
    ARG_PTR(world, out);
    *out = world->b.user[i];
    return RG_OK;
}
