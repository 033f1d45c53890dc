/* step.c: the step as one pipeline, rg_world_step, and the fixed-step accumulator. */
#include <math.h>
#include <string.h>

#include "arg.h"
#include "bounds.h"
#include "collide.h"
#include "contact.h"
#include "continuous.h"
#include "events.h"
#include "force.h"
#include "integrator.h"
#include "island.h"
#include "narrow.h"
#include "pairs.h"
#include "resolve.h"
#include "sense.h"
#include "speed_limits.h"
#include "state.h"
#include "step.h"
#include "vec2.h"
#include "views.h"

/* The collide stage, in order: views and fat boxes, pairs, narrowphase, solve (and the
 * pairs it pressed together), the continuous sweep, sensors, fat boxes refit, speed limits,
 * sleep.  Only with shapes. */
static void step_collide(rg_world *w, rg_real dt)
{
    collide_step x;
    collide_step_begin(w, &x, dt);
    STEP_PROF(-1);
    views_build(w, &x, dt);
    STEP_PROF(0);
    STEP_PROF_MOVED(w->coll.bp.n_moved);
    x.woke = pairs_find(w);
    STEP_PROF(1);
    narrow_run(w, &x);
    if (x.woke) views_woken(w, &x);
    STEP_PROF(2);
    resolve_run(w, &x);
    if (x.pressed > 0) narrow_press(w, &x);
    STEP_PROF(3);
    x.woke |= continuous_sweep(w, &x);
    if (w->pre_solve != NULL) narrow_unskip(w);
    sense_run(w, &x);
    pairs_refit(w, &x, dt);
    speed_limits_apply(w); /* where the step ends: on what the collisions left */
    STEP_PROF(4);
    island_sleep(w, dt, x.unite && !x.woke);
    STEP_PROF(5);
    STEP_PROF_REPORT(w, x);
}

/* One step after validation and preparation; cannot fail.  The pipeline of the header's
 * rg_world_step: forces, integrate, range guard, collide (then speed limits and sleep; the
 * limits right after integration where there are no shapes, nothing else changing a
 * velocity), events, clear. */
static void step_run(rg_world *w, rg_real dt)
{
    body_store *b = &w->b;
    int collide = collide_needed(w);
    int shapes = w->coll.shape_count > 0;
    if (shapes) views_record_start(w);  /* where the step begins, for the collide stage */
    force_begin(w);
    int out = integrator_step(w, dt);
    if (!shapes) speed_limits_apply(w); /* the step's end (else step_collide's, before sleep) */
    if (out) {
        /* Verlet and RK4 keep where the step began (the integrator's scratch) */
        int kept = w->integrator == RG_INTEGRATOR_VELOCITY_VERLET || w->integrator == RG_INTEGRATOR_RK4;
        bounds_guard(w, kept ? w->scratch.x0 : NULL, kept ? w->scratch.y0 : NULL);
    }
    if (collide) {
        events_begin_step(&w->coll.events);
        if (shapes) {
            step_collide(w, dt);
            /* a collision may have pushed a body at the edge of the range past it: every
             * step ends with every state in range (what a snapshot's restore checks) */
            bounds_guard(w, NULL, NULL);
        }
        events_end_step(&w->coll.events);
    }
    /* Applied forces last one step; where none was applied they are +0 already.  (An empty
     * world has no arrays: memset(NULL, 0, 0) is undefined.) */
    if (w->forces_applied && b->n_moving > 0) {
        memset(b->fx, 0, (size_t)b->n_moving * sizeof *b->fx);
        memset(b->fy, 0, (size_t)b->n_moving * sizeof *b->fy);
    }
    w->forces_applied = 0;
    w->step_count++;
}

/* The contact storage a pair search ran out of (pairs.c: its bodies search again in this
 * step), grown before the step changes anything. */
static rg_status step_contacts_owed(rg_world *w)
{
    if (!w->coll.pairs_short) return RG_OK;
    rg_status st = contact_reserve(w);
    if (st == RG_OK) w->coll.pairs_short = 0;
    return st;
}

/* What a step allocates, before anything changes, so that a failing step changes nothing;
 * `func` is the entry point that steps. */
static rg_status step_prepare(rg_world *w, const char *func)
{
    rg_status st = integrator_prepare(w);
    if (st != RG_OK) return error_alloc(w, func, st, "integrator scratch", "RG_MAX_BODIES");
    st = collide_prepare(w);
    if (st != RG_OK) return error_alloc(w, func, st, "collision scratch", "RG_MAX_BODIES");
    st = step_contacts_owed(w);
    if (st != RG_OK) return error_alloc(w, func, st, "contact storage", "2^28 contacts");
    return RG_OK;
}

RG_API rg_status rg_world_step(rg_world *world, rg_real dt)
{
    WORLD_WRITABLE(world);
    ARG_ABOVE(world, dt, 0, RG_MAX_DT);
    WORLD_LOCK(world); /* the allocator, the task system and the hook may call on it */
    rg_status st = step_prepare(world, __func__);
    if (st != RG_OK) {
        WORLD_UNLOCK(world);
        return st;
    }
    events_clear(&world->coll.events);
    bounds_begin(world);
    step_run(world, dt);
    world->prev_valid = 0;
    WORLD_UNLOCK(world);
    ERROR_CLEAR(world); /* a callback's failed call inside the step is not this call's */
    return RG_OK;
}

RG_API rg_status rg_world_advance(rg_world *world, rg_real frame_time, int32_t *out_steps)
{
    WORLD_WRITABLE(world);
    ARG_IN(world, frame_time, 0, HUGE_VAL);
    WORLD_LOCK(world); /* the allocator, the task system and the hook may call on it */
    rg_status st = step_prepare(world, __func__);
    if (st != RG_OK) {
        WORLD_UNLOCK(world);
        return st;
    }
    body_store *b = &world->b;
    rg_real dt = (rg_real)world->fixed_dt;
    int32_t steps = 0;
    int cut = 0;
    /* The events readable after an advance are those of all its steps, in step order. */
    events_clear(&world->coll.events);
    bounds_begin(world);
    world->accumulator += (double)frame_time;
    while (world->accumulator >= world->fixed_dt && steps < world->max_steps) {
        /* The first step's events always fit (their room comes with the contact storage);
         * a later one needs room after the events held, and the contacts the step before
         * could not store.  Without it the advance stops here and the steps not taken
         * wait in the accumulator for the next advance: no event is lost and the
         * simulation is the same, only later. */
        if (steps > 0 && (events_reserve(world) != RG_OK || step_contacts_owed(world) != RG_OK)) {
            cut = 1;
            break;
        }
        if (b->n_moving > 0) {
            memcpy(b->px, b->x, (size_t)b->n_moving * sizeof *b->x);
            memcpy(b->py, b->y, (size_t)b->n_moving * sizeof *b->y);
        }
        step_run(world, dt);
        world->accumulator -= world->fixed_dt;
        steps++;
    }
    /* Past the cap, whole steps are dropped (no spiral of death); the fraction stays. */
    if (!cut && world->accumulator >= world->fixed_dt)
        world->accumulator = fmod(world->accumulator, world->fixed_dt);
    if (steps > 0) world->prev_valid = 1;
    if (out_steps != NULL) *out_steps = steps;
    WORLD_UNLOCK(world);
    ERROR_CLEAR(world); /* a callback's failed call inside a step is not this call's */
    return RG_OK;
}

RG_API rg_status rg_world_get_alpha(const rg_world *world, rg_real *out_alpha)
{
    ERROR_BEGIN(world);
    ARG_PTR(world, out_alpha);
    *out_alpha = (rg_real)(world->accumulator / world->fixed_dt);
    return RG_OK;
}
