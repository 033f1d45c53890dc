/* accuracy_scenes.h: the accuracy lab's reference scenes with exact solutions, and the
 * failure experiments (stability, naive dissipation, per-frame steps), shared by
 * tools/accuracy.c and tests/test_accuracy.c so that the charts and the tests measure with
 * one piece of code.  Everything here works in double and converts at the library's edge,
 * so the same code measures the float and the double build. */
#ifndef RG_ACCURACY_SCENES_H
#define RG_ACCURACY_SCENES_H

#include <math.h>

#include "rigid.h"

/* INFINITY and NAN are float constants; these are double (no promotion warnings). */
#define ACC_INF ((double)INFINITY)
#define ACC_NAN ((double)NAN)

#define ACC_INTEGRATORS 4
/* "explicit_euler", "semi_implicit_euler", "verlet", "rk4", indexed by RG_INTEGRATOR_*. */
extern const char *const acc_integrator_name[ACC_INTEGRATORS];
/* Global order of accuracy in theory: 1, 1, 2, 4. */
extern const int acc_integrator_order[ACC_INTEGRATORS];

/* How a scene's error is measured. */
enum {
    ACC_TRAJECTORY = 0, /* max over the run of |p_n - p(t_n)| / size */
    ACC_APEX = 1,       /* |apex height - H| / H, apex found by Hermite interpolation */
    ACC_STOP = 2        /* |distance slid until rest - d| / d */
};

typedef struct acc_scene {
    const char *name;
    const char *what;   /* one line for people */
    int kind;           /* ACC_TRAJECTORY, ACC_APEX, ACC_STOP */
    double duration;    /* s simulated per run */
    double mass;        /* kg */
    double gravity;     /* m/s^2, along -y */
    double k, c;        /* spring to the origin: stiffness N/m, damping N*s/m (0 = none) */
    double lin, quad;   /* drag, kg/s and kg/m */
    double fric;        /* surface friction mu*N, N */
    double x0, y0, vx0, vy0;
    double size;        /* the length the error is relative to, m */
} acc_scene;

typedef struct acc_result {
    double error;        /* relative error, dimensionless (see kind); +inf when it blew up */
    double energy_err;   /* max over the run of |E_n - E(t_n)| / E_0 (m*g*size when E_0 = 0) */
    double energy_drift; /* (E_N - E(t_N)) / E_0 at the end of the run */
    double phase_err;    /* oscillators: phase error at the end, rad; apex: time error, s;
                            stop: stop-time error, s (whole steps); else 0 */
    long steps;
    int finite;          /* 0 when the state left the finite numbers or grew past 1e12 */
} acc_result;

int acc_scene_count(void);
const acc_scene *acc_scene_get(int i);
const acc_scene *acc_scene_find(const char *name);

/* Exact state at time t: st = {x, y, vx, vy}. */
void acc_exact(const acc_scene *s, double t, double st[4]);
/* Mechanical energy (kinetic + spring + gravity), J. */
double acc_energy(const acc_scene *s, const double st[4]);

/* Creates a world with n copies of the scene (copy i offset so none share a point) using the
 * given integrator; *out_first receives the first body. */
rg_status acc_build(const acc_scene *s, int integrator, int n, rg_world **out_world,
                    rg_body *out_first);

/* Called after every step of acc_run when not NULL: t, numerical and exact state. */
typedef void (*acc_observer)(void *user, double t, const double num[4], const double exact[4]);

/* One body of the scene stepped with rg_world_step(dt) for the scene's duration (apex
 * scenes stop just after the apex); the error against the exact solution in *out. */
rg_status acc_run(const acc_scene *s, int integrator, double dt, acc_observer obs, void *user,
                  acc_result *out);

/* Median ns per body-step over reps timed runs of n copies stepped at dt for the scene's
 * duration (each run on a fresh world; building it is not timed). */
double acc_time_ns(const acc_scene *s, int integrator, double dt, int n, int reps);

/* ---------------------------------------------------------------- stability */

/* The undamped oscillator x0 = 1, v0 = 0, m = 1 stepped at dt = 1/60 s with k = (z/dt)^2,
 * so that omega*dt = z: the largest E_n/E_0 over n_steps steps (+inf when not finite) and,
 * when out_last is not NULL, E_N/E_0. */
double acc_oscillator_energy_ratio(int integrator, double z, long n_steps, double *out_last);
/* The amplitude factor per step, (E_N/E_0)^(1/2N), of the same run (N = the steps taken
 * before E/E_0 passed 1e30). */
double acc_oscillator_growth(int integrator, double z, long n_steps);
/* omega*dt of the oscillator above as the library sees it (k and dt rounded to rg_real). */
double acc_oscillator_z(double z);
/* Largest z in [lo, hi] with max E_n/E_0 <= bound over n_steps steps, by bisection (iters
 * halvings); lo must be stable. */
double acc_stability_boundary(int integrator, long n_steps, double bound, double lo, double hi,
                              int iters);

/* ---------------------------------------------------------------- dissipation */

/* One step of the naive explicit dissipation the seed used, 1D: v - mu*N/m*dt*sign(v), and
 * v - (lin + quad*|v|)*v/m*dt.  They reverse v when mu*N*dt/m > |v| or
 * (lin + quad*|v|)*dt/m > 1. */
double acc_naive_friction_step(double v, double fric_over_m, double dt);
double acc_naive_drag_step(double v, double lin_over_m, double quad_over_m, double dt);
/* The library on the same problem: a body of mass m moving at (v, 0) with friction fric (N)
 * and drag lin, quad, no gravity, stepped n times at dt; the x velocity after each step in
 * out[0..n-1]. */
rg_status acc_library_dissipation(int integrator, double m, double v, double fric, double lin,
                                  double quad, double dt, int n, double *out);

/* ---------------------------------------------------------------- frame rate */

/* A jump: a body at y = 0 with vy = v0 under gravity g, stepped until it is back below 0 or
 * frames run out.  Naive: one rg_world_step(frame_time) per frame; the apex is the highest
 * y after a frame. */
double acc_jump_naive(int integrator, const double *frames, int n_frames, double v0, double g);
/* Through rg_world_advance(frame_time) with a fixed step dt (max 64 steps per advance); a
 * second world stepped with rg_world_step(dt) in lockstep records every fixed step.  The
 * apex is the highest y over the fixed steps.  *identical is 1 when after every frame the
 * advanced body's position and velocity equal the lockstep world's bit for bit;
 * *out_steps receives the fixed steps taken. */
double acc_jump_fixed(int integrator, double dt, const double *frames, int n_frames, double v0,
                      double g, int *identical, long *out_steps);
/* Exact apex v0^2 / (2g). */
double acc_jump_exact(double v0, double g);

#endif
