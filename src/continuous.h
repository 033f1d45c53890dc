/* continuous.h: continuous collision: timed impacts inside the solve, and the post-solve
 * sweep.  (The time of impact of a fast pair's manifold is the narrowphase's, coll_sweep.)
 *
 * Timed impacts: an impact is a pair apart after the last step whose free motion closes the
 * gap s0 > 0 within this one, at the fraction t = s0 / (approach distance) of the step.  A
 * body whose rows are impacts at one t (one, or several at once: a box landing across a
 * tile seam) and rows with immovable bodies that stay apart moves freely until t and with
 * its solved velocity after it: it ends at x_free + (1 - t) dt (v - v_free), so a bounce turns
 * at the surface and leaves at solver_vout for the rest of the step, and a landing ends on
 * the surface with no velocity into it.  It may share a row with one other movable body if
 * that row is an impact timed at both ends (two balls colliding).  Every other body (in
 * contact with something, near another body, meeting two things at different moments)
 * keeps the speculative rows, which stop it at the surface from where the step began, and
 * shares no row with a timed one but with immovable bodies, so it solves as without timing.
 *
 * The sweep: a body whose whole motion this step (integration, contacts and position
 * correction) exceeds half its size, or that the solve moved more than the slop off its free
 * motion (an impact it took: the pairs the step did not solve were judged by that free
 * motion, and the fat box holds it), is swept from its start to where the step left it
 * against the static, kinematic and sleeping shapes it has contacts with, and, where it
 * ended out of its fat box, those on its path it has none with (the pair search never
 * looked there).  If the path crosses one, the body stops just short of the first impact and
 * loses its velocity into it; at a static or kinematic shape the rest of its motion, relative
 * to that shape and less its part into the surface, goes on along it with the shape's own
 * motion (a kinematic paddle carries what it meets), swept again, up to 4 legs; a sleeping
 * body ends the sweep and, on the stepping thread, wakes and takes the momentum (an
 * inelastic impact of the two).  The solver's time-of-impact rows normally make this a
 * no-op; it catches what an unconverged solve (a light body crushed by a far heavier one)
 * would push through, and a body an impact drives into a shape it had no row with (a ball
 * hit toward a thin wall, or down onto a one-way platform it hovered over). */
#ifndef RG_CONTINUOUS_H
#define RG_CONTINUOUS_H

#include "state.h"

struct rg_world;

/* Times the impact rows whose movable bodies can all be timed: their vmin becomes the
 * velocity the impact leaves (solver_vout), and resolve.stoi[q] the fraction of the step at
 * which solver body q's velocity changes (0: at the start, as the speculative rows assume).
 * Costs nothing in a step without impacts.  Returns whether any body is timed. */
int continuous_time_impacts(struct rg_world *w, collide_step *x);
/* The post-solve sweep over the x->na bodies awake at the start of the stage and those the
 * step woke (views_woken; nothing when continuous collision is off).  Returns whether it
 * woke a sleeping body. */
int continuous_sweep(struct rg_world *w, const collide_step *x);

#endif
