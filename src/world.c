/* world.c: world lifetime and settings, status strings and the version. */
#include <stdlib.h>
#include <string.h>

#include "body.h"
#include "collide.h"
#include "spring.h"
#include "state.h"
#include "vec2.h"

void *mem_default_alloc(void *user, void *ptr, size_t old_size, size_t new_size)
{
    (void)user;
    (void)old_size;
    if (new_size == 0) {
        free(ptr);
        return NULL;
    }
    return realloc(ptr, new_size);
}

RG_API const char *rg_status_string(rg_status s)
{
    switch (s) {
    case RG_OK: return "ok";
    case RG_ERR_INVALID_ARGUMENT: return "invalid argument";
    case RG_ERR_STALE_HANDLE: return "stale or invalid handle";
    case RG_ERR_OUT_OF_MEMORY: return "out of memory";
    case RG_ERR_CAPACITY: return "capacity exceeded";
    case RG_ERR_LOCKED: return "not allowed at this moment";
    default: return "unknown status";
    }
}

RG_API int32_t rg_version(void) { return RG_VERSION; }
RG_API int32_t rg_real_size(void) { return (int32_t)sizeof(rg_real); }

/* The tag that makes one world's handles foreign to another: taken from the world's
 * address, so two live worlds never share it while they lie within 16 MiB of each other
 * (and otherwise only by a 2^-20 chance), with no global counter. */
static uint32_t world_tag(const rg_world *w)
{
    uintptr_t a = (uintptr_t)w;
    uint32_t t = (uint32_t)(a >> 4) & POOL_TAG_MASK;
    return t;
}

RG_API rg_status rg_world_create_with_allocator(rg_alloc_fn alloc, void *user, rg_world **out_world)
{
    if (alloc == NULL || out_world == NULL) return RG_ERR_INVALID_ARGUMENT;
    rg_world *w = alloc(user, NULL, 0, sizeof *w);
    if (w == NULL) return RG_ERR_OUT_OF_MEMORY;
    memset(w, 0, sizeof *w);
    w->mem.fn = alloc;
    w->mem.user = user;
    uint32_t tag = world_tag(w);
    pool_init(&w->body_pool, tag, 0, RG_MAX_BODIES);
    /* Springs carry another tag so that a body handle is never taken for a spring. */
    pool_init(&w->springs.pool, tag ^ (1u << (POOL_TAG_BITS - 1)), 0, RG_MAX_SPRINGS);
    w->integrator = RG_INTEGRATOR_SEMI_IMPLICIT_EULER;
    w->fixed_dt = 1.0 / 60.0;
    w->max_steps = 8;
    collide_init(w);
    *out_world = w;
    return RG_OK;
}

RG_API rg_status rg_world_create(rg_world **out_world)
{
    return rg_world_create_with_allocator(mem_default_alloc, NULL, out_world);
}

RG_API void rg_world_destroy(rg_world *world)
{
    if (world == NULL || world->locked) return; /* not from inside its own step */
    spring_release(world);
    collide_release(world);
    body_store_release(world);
    rg_mem mem = world->mem;
    mem_free(&mem, world, sizeof *world);
}

RG_API rg_status rg_world_set_gravity(rg_world *world, rg_vec2 gravity)
{
    WORLD_WRITABLE(world);
    if (world == NULL || !rg_vec2_finite(gravity)) return RG_ERR_INVALID_ARGUMENT;
    world->gravity = gravity;
    return RG_OK;
}

RG_API rg_status rg_world_get_gravity(const rg_world *world, rg_vec2 *out_gravity)
{
    if (world == NULL || out_gravity == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out_gravity = world->gravity;
    return RG_OK;
}

RG_API rg_status rg_world_set_wind(rg_world *world, rg_vec2 force)
{
    WORLD_WRITABLE(world);
    if (world == NULL || !rg_vec2_finite(force)) return RG_ERR_INVALID_ARGUMENT;
    world->wind = force;
    return RG_OK;
}

RG_API rg_status rg_world_get_wind(const rg_world *world, rg_vec2 *out_force)
{
    if (world == NULL || out_force == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out_force = world->wind;
    return RG_OK;
}

RG_API rg_status rg_world_set_integrator(rg_world *world, int32_t integrator)
{
    WORLD_WRITABLE(world);
    if (world == NULL || integrator < RG_INTEGRATOR_EXPLICIT_EULER || integrator > RG_INTEGRATOR_RK4)
        return RG_ERR_INVALID_ARGUMENT;
    world->integrator = integrator;
    return RG_OK;
}

RG_API rg_status rg_world_get_integrator(const rg_world *world, int32_t *out_integrator)
{
    if (world == NULL || out_integrator == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out_integrator = world->integrator;
    return RG_OK;
}

RG_API rg_status rg_world_set_fixed_step(rg_world *world, rg_real dt, int32_t max_steps_per_advance)
{
    WORLD_WRITABLE(world);
    if (world == NULL || !rg_finite(dt) || !(dt > 0) || max_steps_per_advance < 1)
        return RG_ERR_INVALID_ARGUMENT;
    world->fixed_dt = (double)dt;
    world->max_steps = max_steps_per_advance;
    return RG_OK;
}

RG_API rg_status rg_world_get_fixed_step(const rg_world *world, rg_real *out_dt, int32_t *out_max_steps)
{
    if (world == NULL || (out_dt == NULL && out_max_steps == NULL)) return RG_ERR_INVALID_ARGUMENT;
    if (out_dt != NULL) *out_dt = (rg_real)world->fixed_dt;
    if (out_max_steps != NULL) *out_max_steps = world->max_steps;
    return RG_OK;
}

RG_API int32_t rg_world_body_count(const rg_world *world)
{
    return world != NULL ? world->b.count : 0;
}
