/* world.c: world lifetime and settings, status strings and the version. */
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "arg.h"
#include "body.h"
#include "collide.h"
#include "island.h"
#include "spring.h"
#include "state.h"
#include "vec2.h"

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

/* A counter of the machine that moves on between any two calls: the time-stamp counter
 * where the compiler can read it, else the process clock (which a fast destroy-and-create
 * may not see move). */
static uint64_t world_ticks(void)
{
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
    return __builtin_ia32_rdtsc();
#elif (defined(__GNUC__) || defined(__clang__)) && defined(__aarch64__)
    uint64_t v;
    __asm__ __volatile__("mrs %0, cntvct_el0" : "=r"(v));
    return v;
#else
    return (uint64_t)clock();
#endif
}

/* 64 bits from the world's address (every bit of it), the machine's tick counter, the time
 * and the address of a local (where the system places the heap and the stack at random),
 * mixed; each call differs in the ticks at least. */
static uint64_t world_entropy(const rg_world *w)
{
    int local = 0;
    uint64_t z = (uint64_t)(uintptr_t)w ^ world_ticks() * 0x9E3779B97F4A7C15ull ^ (uint64_t)time(NULL) << 32 ^
                 (uint64_t)clock() << 16 ^ (uint64_t)(uintptr_t)&local * 0xC2B2AE3D27D4EB4Full;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* The tag that makes one world's handles foreign to another: per world and random
 * (world_entropy).  No state outlives a world, so nothing but chance (2^-20) lets two live
 * worlds, or a world and the one destroyed before it in the same block (a level reload),
 * share a tag; an address alone would give a reloaded level its predecessor's tag every
 * time.  The tag decides no result: every handle of a world carries the same one. */
static uint32_t world_tag(const rg_world *w)
{
    return (uint32_t)world_entropy(w) & POOL_TAG_MASK;
}

/* The world, the text of its last error and its last saves (own.h), in one block. */
#define WORLD_BLOCK (sizeof(rg_world) + ERROR_SIZE + sizeof(own_saves))
typedef char world_error_size_keeps_alignment[ERROR_SIZE % 8 == 0 ? 1 : -1];

RG_API rg_status rg_world_create_with_allocator(rg_alloc_fn alloc, void *user, rg_world **out_world)
{
    if (alloc == NULL || out_world == NULL) return RG_ERR_INVALID_ARGUMENT;
    rg_world *w = alloc(user, NULL, 0, WORLD_BLOCK);
    if (w == NULL) return RG_ERR_OUT_OF_MEMORY;
    memset(w, 0, sizeof *w + ERROR_SIZE);
    w->err = (char *)(w + 1);
    w->own = (own_saves *)(void *)(w->err + ERROR_SIZE);
    w->mem.fn = alloc;
    w->mem.user = user;
    w->mem.locked = &w->locked;
    w->mem.err = w->err;
    uint32_t tag = world_tag(w);
    pool_init(&w->body_pool, tag, 0, RG_MAX_BODIES);
    /* Springs carry another tag so that a body handle is never taken for a spring. */
    pool_init(&w->springs.pool, tag ^ (1u << (POOL_TAG_BITS - 1)), 0, RG_MAX_SPRINGS);
    own_init(w->own, world_entropy(w)); /* a second draw: the tag, which handles show, is not the key */
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
    if (world == NULL || world->locked) return; /* not from inside its own step or callbacks */
    world->locked = 1; /* the allocator's calls on it, while it frees, are refused */
    spring_release(world);
    collide_release(world);
    body_store_release(world);
    rg_mem mem = world->mem;
    mem.locked = NULL; /* the last free takes the lock with it */
    for (int k = 0; k < RG_MAX_SLOTS; k++) /* the kept states (slots.c) */
        if (world->kept[k].p != NULL) mem_free(&mem, world->kept[k].p, world->kept[k].cap);
    mem_free(&mem, world, WORLD_BLOCK);
}

RG_API rg_status rg_world_set_gravity(rg_world *world, rg_vec2 gravity)
{
    WORLD_WRITABLE(world);
    ARG_VEC(world, gravity, RG_MAX_ACCELERATION);
    /* a sleeping body is not integrated: a change it must feel wakes it (a pile at rest
     * under the old gravity may not be under the new) */
    if (gravity.x != world->gravity.x || gravity.y != world->gravity.y) island_wake_all(world);
    world->gravity = gravity;
    return RG_OK;
}

RG_API rg_status rg_world_get_gravity(const rg_world *world, rg_vec2 *out_gravity)
{
    ERROR_BEGIN(world);
    ARG_PTR(world, out_gravity);
    *out_gravity = world->gravity;
    return RG_OK;
}

RG_API rg_status rg_world_set_wind(rg_world *world, rg_vec2 force)
{
    WORLD_WRITABLE(world);
    ARG_VEC(world, force, RG_MAX_FORCE);
    if (force.x != world->wind.x || force.y != world->wind.y) island_wake_all(world); /* as gravity */
    world->wind = force;
    return RG_OK;
}

RG_API rg_status rg_world_get_wind(const rg_world *world, rg_vec2 *out_force)
{
    ERROR_BEGIN(world);
    ARG_PTR(world, out_force);
    *out_force = world->wind;
    return RG_OK;
}

RG_API rg_status rg_world_set_integrator(rg_world *world, int32_t integrator)
{
    WORLD_WRITABLE(world);
    ARG_INT(world, integrator, RG_INTEGRATOR_EXPLICIT_EULER, RG_INTEGRATOR_RK4, "one of RG_INTEGRATOR_* (0..3)");
    world->integrator = integrator;
    return RG_OK;
}

RG_API rg_status rg_world_get_integrator(const rg_world *world, int32_t *out_integrator)
{
    ERROR_BEGIN(world);
    ARG_PTR(world, out_integrator);
    *out_integrator = world->integrator;
    return RG_OK;
}

RG_API rg_status rg_world_set_fixed_step(rg_world *world, rg_real dt, int32_t max_steps_per_advance)
{
    WORLD_WRITABLE(world);
    ARG_ABOVE(world, dt, 0, RG_MAX_DT);
    ARG_INT(world, max_steps_per_advance, 1, INT32_MAX, ">= 1");
    world->fixed_dt = (double)dt;
    world->max_steps = max_steps_per_advance;
    return RG_OK;
}

RG_API rg_status rg_world_get_fixed_step(const rg_world *world, rg_real *out_dt, int32_t *out_max_steps)
{
    ERROR_BEGIN(world);
    if (out_dt == NULL && out_max_steps == NULL)
        return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "out_dt and out_max_steps are both NULL");
    if (out_dt != NULL) *out_dt = (rg_real)world->fixed_dt;
    if (out_max_steps != NULL) *out_max_steps = world->max_steps;
    return RG_OK;
}

RG_API int32_t rg_world_body_count(const rg_world *world)
{
    if (world == NULL) return 0;
    ERROR_CLEAR(world);
    return world->b.count;
}
