/* collide.h: the collide stage (its state in state.h), shared by its modules: pairs.c (fat boxes and
 * the pair search), views.c (the step's view of each body), narrow.c (manifolds, touching,
 * grounded), resolve.c (the solve driver),
 * continuous.c (timed impacts and the post-solve sweep), island.c (islands and sleeping),
 * contact.c and events.c (storage); collide.c holds its settings, scratch and lifetime.
 *
 * Who pays: only bodies with a shape are in the broadphase, and only the awake ones among
 * them (the broadphase's active list) are visited per step; static and sleeping bodies and
 * bodies without shapes cost nothing.  A world with no shape skips the stage.
 *
 * The stage, step by step (step.c calls them in this order):
 *   views_record_start   before integration: where the awake shaped bodies start
 *   views_build          the step's view of each (displacement, velocity, size); fat boxes
 *   pairs_find           new pairs for the bodies that left their fat boxes
 *   narrow_run           manifolds, touching and events, grounded flags, solver rows
 *   resolve_run          the solve, timed impacts (continuous_time_impacts)
 *   continuous_sweep     the post-solve safety net
 *   pairs_refit          fat boxes hold the final boxes
 *   island_sleep         islands at rest fall asleep */
#ifndef RG_COLLIDE_H
#define RG_COLLIDE_H

#include <stdint.h>

#include "state.h"


struct rg_world;

void collide_init(struct rg_world *w);
void collide_release(struct rg_world *w);
/* Scratch a step needs; call before anything changes. */
rg_status collide_prepare(struct rg_world *w);
/* Whether the step must run the collide stage (shapes, or ended contacts to report). */
int collide_needed(const struct rg_world *w);
/* The step's solver parameters and counters, before views_build. */
void collide_step_begin(struct rg_world *w, collide_step *x, rg_real dt);

#endif
