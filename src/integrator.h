/* integrator.h: explicit Euler, semi-implicit Euler, velocity Verlet and RK4 over the
 * active bodies, with non-reversing dissipation. */
#ifndef RG_INTEGRATOR_H
#define RG_INTEGRATOR_H

#include "rigid.h"

struct rg_world;

/* Does the scratch allocation a step of the world's integrator needs; call before any
 * change so that a failing step changes nothing. */
rg_status integrator_prepare(struct rg_world *w);
/* Advances the active bodies by h seconds from the forces stage's start state (force_begin):
 * integration and the dissipation guard.  Records the start-of-step acceleration in b.ax,
 * b.ay.  Returns 1 when a body may be out of range (the Euler passes check each body as they
 * write it; Verlet and RK4 leave it to the range guard, bounds.h), else 0. */
int integrator_step(struct rg_world *w, rg_real h);

#endif
