/* accuracy_collision.h: the accuracy lab's collision scenes (a fast ball against a thin wall,
 * a pile with a large mass ratio), shared by tools/accuracy.c and tests/test_accuracy.c.
 * Built only when the library has collision (accuracy.mk defines ACC_COLLISION). */
#ifndef RG_ACCURACY_COLLISION_H
#define RG_ACCURACY_COLLISION_H

#include "rigid.h"

/* The vector (x, y) in rg_real, for the scenes below. */
static inline rg_vec2 acc_cv2(double x, double y)
{
    rg_vec2 v;
    v.x = (rg_real)x;
    v.y = (rg_real)y;
    return v;
}

/* ---------------------------------------------------------------- tunnelling */

/* The scene: a 1 kg ball of radius r (m) on y = 0 moving at +speed (m/s), no gravity, toward
 * a static wall at x = 0, wall m thick and 2 m tall.  The ball starts at
 * x0 = -(0.5 + r + wall/2) - phase*speed*dt (phase in [0, 1) sets where the samples
 * x0 + n*speed*dt fall relative to the wall) and is stepped until it is 0.5 m past the wall
 * if nothing stops it. */
typedef struct acc_wall {
    double radius, wall, speed, dt, phase;
} acc_wall;

/* The lab's own naive discrete check, no library collision: the ball moves by speed*dt per
 * step and is caught only when a sample overlaps the wall, |x| < wall/2 + r.  1 when it
 * tunnels.  Theory: over uniform phases it tunnels with probability
 * max(0, 1 - (wall + 2r) / (speed*dt)). */
int acc_tunnel_naive(const acc_wall *s);
/* The library: shapes on both bodies, restitution 0, rg_world_set_continuous(continuous).
 * 1 when the ball ends past the wall (x > 0), 0 when it stayed on its side, -1 on an error
 * status.  A discrete check catches at most the samples that overlap and always one in the
 * wall's near half, -(wall/2 + r) < x < 0 (past the middle it may push the ball out of the
 * far face): it tunnels with a probability between max(0, 1 - (wall + 2r) / (speed*dt))
 * and max(0, 1 - (wall/2 + r) / (speed*dt)); continuous collision: never. */
int acc_tunnel_library(int integrator, int continuous, const acc_wall *s);

/* ---------------------------------------------------------------- pile */

typedef struct acc_pile_result {
    double max_err;     /* max over the run and the boxes of |y_i - y_i(rest)|, m */
    double final_err;   /* the same at the end */
    double final_speed; /* largest |v| at the end, m/s */
    double max_drift;   /* max over the run of |x_i|, m */
    int finite;
} acc_pile_result;

/* n boxes 1 m wide on a static ground, started exactly at rest in contact (box i centred at
 * y = 0.5 + i), masses ratio^(i/(n-1)) kg from the bottom (1 kg) to the top (ratio kg):
 * heavy on light, the hard case for an iterative contact solver.  Exact solution: nothing
 * moves.  Stepped at dt for seconds with the solver's default iterations, or with
 * velocity_iterations (and 2 relax iterations) when it is > 0. */
rg_status acc_pile(int integrator, double dt, double ratio, int n, double seconds,
                   int velocity_iterations, acc_pile_result *out);

/* ---------------------------------------------------------------- soups */

/* `scenes` random soups of 20-79 boxes and circles (0.1-5.1 kg, 0.1-0.4 m, apart at the
 * start) without gravity, sleeping off, half of them thrown at up to max_speed (m/s);
 * restitution 0, or (restitution 1) 1 for a third of the bodies and uniform in [0, 1) for the
 * others; friction 0, or (friction 1) 0 for half of them and uniform in [0, 1) for the
 * others; velocity_iterations per step and 3 position iterations; `steps` steps at 1/60 s.
 * Exact: every contact impulse is equal and opposite, so momentum stays; with restitution 0
 * every impact takes energy, and with restitution 1 a single one keeps it. */
typedef struct acc_soup {
    int scenes, steps, restitution, friction, velocity_iterations;
    double max_speed;
} acc_soup;

typedef struct acc_soup_result {
    double worst_momentum; /* largest |p - p0| over the sum of |m v0|, any scene and step */
    double worst_gain;     /* largest rise of the kinetic energy over its lowest before, / KE0 */
    int gaining;           /* scenes whose kinetic energy rose by more than 0.1% of KE0 */
} acc_soup_result;

rg_status acc_soup_run(const acc_soup *s, acc_soup_result *r);

/* A box of `ratio` kg (0.6 m) run at speed (m/s) along a frictionless floor, under gravity,
 * into a 1 kg box (0.5 m) resting against a wall, restitution 0 everywhere, with
 * velocity_iterations per step: the fastest it moves back over 2 s.  Exact: 0 (it stops). */
rg_status acc_push_rebound(double ratio, double speed, int velocity_iterations, double *out_back);

/* `scenes` scenes of a kinematic paddle (2-12 cm thick, 3 m tall, standing on the floor)
 * driven at a speed uniform in [lo, hi) m/s through 1-19 bodies (circles and boxes of 3-33
 * cm, 0.1-5.1 kg, at rest on a 3 m band above the floor ahead of it), gravity 0 or 10, 2 s at
 * 60 Hz, continuous collision on: *out_through of *out_bodies end a step behind the paddle
 * (ahead of its centre at the step's start, behind it at the end, below its top).  Exact: 0
 * (the paddle pushes all of them ahead, or over its top). */
rg_status acc_paddle_run(int scenes, double lo, double hi, int *out_through, int *out_bodies);

/* ---------------------------------------------------------------- contacts */

/* accuracy --contacts: the contact scenes of tools/accuracy_contacts.c under each integrator
 * (jumps into a ceiling, bounces, a landing, friction holding and stopping, a pile going to
 * sleep), a table on stdout; fewer scenes when quick.  Returns how many integrators failed
 * to run (a status other than RG_OK). */
int acc_contacts_print(int quick);

#endif
