/* force.h: the force sum and the force generators (gravity, wind, applied forces, drag,
 * surface friction, springs) as functions of the state, so multi-stage integrators evaluate
 * them at every stage. */
#ifndef RG_FORCE_H
#define RG_FORCE_H

#include <stdint.h>

#include "state.h"

struct rg_world;

/* The acceleration of the forces that do not depend on the state, m/s^2: gravity g times
 * the body's gravity scale gs, plus (wind + applied force f) / m with im = 1/m.  Every
 * integrator sums these in exactly this order (results are pinned to the bit); the state's
 * forces (drag, friction, springs) are added to it by the caller. */
static inline rg_real force_sum(rg_real g, rg_real gs, rg_real wind, rg_real f, rg_real im)
{
    return g * gs + (wind + f) * im;
}

/* The forces stage of the step: the accelerations springs give the active bodies at the
 * start state, into the integrator scratch (scratch.sax, scratch.say); nothing when the
 * world has no spring. */
void force_begin(struct rg_world *w);
/* Spring accelerations at the current state (b.x, b.y, b.vx, b.vy) into sax, say for the
 * active bodies [0, n_active); other bodies feel nothing. */
void force_springs(const struct rg_world *w, rg_real *sax, rg_real *say);
/* Total acceleration at the current state into ax, ay for [0, n_active):
 * force_sum - drag - surface friction + springs.  springs_ready: scratch.sax/say already hold
 * the springs' accelerations at this state (force_begin's, at the start state). */
void force_eval(struct rg_world *w, rg_real *ax, rg_real *ay, int springs_ready);

#endif
