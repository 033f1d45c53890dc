/* bounds.h: the range guard of the step: every body's state stays finite and in range. */
#ifndef RG_BOUNDS_H
#define RG_BOUNDS_H

#include "rigid.h"
#include "vec2.h"

struct rg_world;

/* Whether a body's state is out of range or not finite (NaN fails every compare): 1 or 0,
 * branch-free, for the integrator's vectorised loops. */
static inline int32_t bounds_out(rg_real x, rg_real y, rg_real vx, rg_real vy)
{
    const rg_real c = (rg_real)RG_MAX_COORD, s = (rg_real)RG_MAX_SPEED;
    return !((rg_fabs(x) <= c) & (rg_fabs(y) <= c) & (rg_fabs(vx) <= s) & (rg_fabs(vy) <= s));
}

/* Before a call's first step: forgets the bodies the previous call stopped. */
void bounds_begin(struct rg_world *w);

/* After integration and the speed limits, before the collide stage, when the integrator
 * found a body out (integrator_step), and after the collide stage: every active body whose
 * position left +-RG_MAX_COORD, whose velocity left +-RG_MAX_SPEED, or whose state is not
 * finite is stopped: each coordinate clamped to the range (a non-finite one set back to x0,
 * y0, where the step began, or to 0 when the integrator kept no start), velocity and
 * acceleration 0, and the body listed for rg_world_get_stopped. */
void bounds_guard(struct rg_world *w, const rg_real *x0, const rg_real *y0);

#endif
