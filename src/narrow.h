/* narrow.h: the narrowphase: the step's view of each awake shaped body, manifolds at the
 * start of the step extrapolated over it, touching (events, grounded flags, islands),
 * waking, and the solver rows.
 *
 * The manifold is taken at the start of the step (positions minus the step's displacement)
 * and extrapolated linearly: s0 is the start separation along the normal and the solver
 * keeps s0 + vn*dt >= 0 (speculative contacts), so a body moving less than its size stops
 * exactly at a surface.  A pair whose relative motion exceeds half the smaller shape uses
 * the time of impact instead (continuous collision).  A pair is solved when it could close
 * within the step, counting each body's own motion toward the other (the solver may stop
 * either).  Touching (events, grounded, islands) means the step's free motion ends in
 * contact, with a slop of hysteresis, or, after the solve, that the solve pressed the pair
 * together (narrow_press).  Sensor pairs are neither measured nor decided here: sense.h
 * tests them where the step ends. */
#ifndef RG_NARROW_H
#define RG_NARROW_H

#include <stdint.h>

#include "state.h"

struct rg_world;

/* Updates every awake contact from the step's motion (the views, views.h) and stages the
 * rows to solve: manifolds measured and decisions taken in parallel, what must happen in
 * order (the pre-solve hook, one-way decisions, events, islands, waking) on this thread;
 * when nothing can wake (no body asleep) and no pair was decided in order, the commits in
 * contact order (events, grounded flags, islands) are left in x->late, for the solve to run
 * beside its own first part. */
void narrow_run(struct rg_world *w, collide_step *x);

/* After the solve: the pairs it pressed together though the step's free motion left them
 * apart (a body pushed into another by a third; x->pressed) touch from this step on, as the
 * step ends with them in contact: their begin events and grounded flags come now, not a step
 * late. */
void narrow_press(struct rg_world *w, collide_step *x);
/* After the post-solve sweep of a step with a pre-solve hook: clears the pairs' CT_SKIPPED. */
void narrow_unskip(struct rg_world *w);

#endif
