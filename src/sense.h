/* sense.h: sensors touch where the step ends.
 *
 * A solid pair's touching is decided before the solve, from the step's free motion, because
 * the solve needs it (and after it for the pairs the solve pressed together: narrow.h).  A
 * sensor's is not: the narrowphase leaves sensor pairs alone, and once the solve and the
 * continuous sweep have placed every body, sense_run tests each awake sensor pair's shapes
 * where they are.  So a body that a wall stops short of a sensor behind it never reports
 * entering it, and one that a collision throws into a sensor reports it in that step.  A
 * pair apart at both ends of the step whose bodies' straight paths crossed (a bullet through
 * a thin trigger) touches for that step, and ends with the next. */
#ifndef RG_SENSE_H
#define RG_SENSE_H

#include "state.h"

struct rg_world;

/* The awake sensor pairs' touching from their shapes' places at the end of the step (with a
 * slop of hysteresis: a touching pair stays so while less than the slop apart), or from their
 * paths over it (a crossing: the starts of the x->nv bodies with a view), their begin and
 * end events, and their normals and points; a pair passing through (CT_PASS) touches
 * nothing until a step ends with it apart.  Runs only when the narrowphase met a sensor pair
 * (x->sensed). */
void sense_run(struct rg_world *w, const collide_step *x);

#endif
