/* world.h: the world structure shared by the modules inside src/ (never exported). */
#ifndef RG_WORLD_H
#define RG_WORLD_H

#include <stdint.h>

#include "body.h"
#include "collide.h"
#include "force.h"
#include "mem.h"
#include "pool.h"
#include "spring.h"

struct rg_world {
    rg_mem mem;
    pool body_pool;
    body_store b;          /* dense structure-of-arrays body storage */
    spring_store springs;

    rg_vec2 gravity;       /* m/s^2 */
    rg_vec2 wind;          /* N */
    int32_t integrator;    /* RG_INTEGRATOR_* */

    /* What the scene uses, so a stage nobody uses costs nothing. */
    int32_t dissipative_count; /* dynamic bodies with drag or surface friction */
    int32_t limit_count;       /* dynamic bodies with speed limits */

    /* Fixed-step accumulator (double, so that long runs do not drift). */
    double fixed_dt;
    int32_t max_steps;
    double accumulator;
    int32_t prev_valid;    /* b.px/b.py hold the positions before the last advance step */
    uint64_t step_count;

    /* Per-body scratch for the integrators, grown with the body capacity when first needed. */
    scratch_store scratch;

    /* Collision: broadphase, contacts, events, islands, settings (collide.h). */
    collide_world coll;
};

/* See body.h. */
static inline int32_t body_dense(const struct rg_world *w, int32_t slot)
{
    return pool_dense(&w->body_pool, slot);
}

#endif
