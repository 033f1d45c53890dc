/* narrow_reach.h: how far a pair can close within a step, for the narrowphase (narrow.c):
 * the test that skips a pair too far apart to meet, and the integrator's term of a body's
 * motion that the views do not hold (explicit Euler, Verlet, RK4). */
#ifndef RG_NARROW_REACH_H
#define RG_NARROW_REACH_H

#include "state.h"
#include "vec2.h"

/* Whether a pair that is not touching is too far apart for the narrowphase below to solve
 * it or find it touching, so it can be skipped with the same result.  The gap G between the
 * two boxes at the start bounds every separation that test takes from below: the manifold's
 * (a circle lies in its box) unless a box grazes (then the separation is the gap along one
 * axis, within slop of zero: excluded), and a time of impact needs |r| >= G.  The test solves
 * when s0 - reach < SPECULATIVE * slop with reach <= |dA| + |dB| (1-norms bound both), and
 * finds touching only when s0 <= |r|.  The margin covers the rounding of the exact tests:
 * slop, and a few ulps of the coordinates. */
static inline int narrow_far_apart(const cbody *A, const cbody *B, int32_t ka, int32_t kb, rg_real slop,
                                    rg_real more)
{
    rg_real gx = rg_fabs(B->sx - A->sx) - (A->hx + B->hx);
    rg_real gy = rg_fabs(B->sy - A->sy) - (A->hy + B->hy);
    rg_real reach = rg_fabs(A->dx) + rg_fabs(A->dy) + rg_fabs(B->dx) + rg_fabs(B->dy) + more;
    rg_real ulps = (rg_fabs(A->sx) + rg_fabs(A->sy) + rg_fabs(B->sx) + rg_fabs(B->sy) + reach +
                    A->hx + A->hy + B->hx + B->hy) * (64 * RG_EPSILON);
    rg_real need = reach + (SPECULATIVE + 1) * slop + ulps;
    if (!(rg_max(gx, gy) >= need)) return 0; /* also NaN */
    /* a box may graze along an axis whose gap is within slop of zero */
    if (ka == RG_SHAPE_CIRCLE && kb == RG_SHAPE_CIRCLE) return 1;
    return rg_fabs(gx) > slop && rg_fabs(gy) > slop;
}

/* The integrator's term o of view A's motion (collide_world's offk): the body's own motion is
 * v dt + o, its view's v dt (views_build).  0 under semi-implicit Euler, and for a view at
 * rest or a body with no acceleration. */
static inline rg_vec2 narrow_off(const collide_world *cw, const cbody *A)
{
    rg_real k = cw->offk, dt = cw->offdt;
    return rg_v2(-k * (A->dx - A->vx * dt), -k * (A->dy - A->vy * dt));
}

/* Whether contact c (views A, B) is skipped as far apart (narrow_far_apart): only a pair that
 * is not touching, with continuous collision.  Both the measurement and the decision take it. */
static inline int narrow_far(const rg_world *w, const contact *c, const cbody *A, const cbody *B)
{
    const collide_world *cw = &w->coll;
    rg_real more = 0;
    if (cw->offk > 0) {
        /* the integrator's own motion, v dt + o, reaches as far as v dt and o together */
        rg_vec2 oa = narrow_off(cw, A), ob = narrow_off(cw, B);
        more = rg_fabs(oa.x) + rg_fabs(oa.y) + rg_fabs(ob.x) + rg_fabs(ob.y);
    }
    return cw->continuous && !(c->flags & CT_TOUCHING) && narrow_far_apart(A, B, A->kind, B->kind, cw->slop, more);
}

#endif
