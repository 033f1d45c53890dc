/* accuracy.c: the accuracy lab.  Every integrator over a sweep of steps on scenes with exact
 * solutions: error, energy, cost; stability boundaries; frame-rate dependence; and which
 * integrator and step a scene should use.
 *
 *   accuracy [--out DIR] [--quick] [--bodies N] [--reps R]
 *       writes DIR/{sweep,orders,energy60,stability,growth,framerate,dissipation}_REAL.csv,
 *       and tunnel_REAL.csv and pile_REAL.csv when built with collision (ACC_COLLISION)
 *       (REAL = float or double, the build) and prints the 60 Hz table and summaries
 *   accuracy --recommend [BUDGET]
 *       for each scene and error budget (relative; default 1e-2, 1e-3, 1e-4) the cheapest
 *       integrator and step that meet it, and the cheapest integrator at 60 Hz
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accuracy_scenes.h"
#ifdef ACC_COLLISION
#include "accuracy_collision.h"
#endif

#ifdef RG_DOUBLE
#define REAL_NAME "double"
#define REAL_EPS DBL_EPSILON
#else
#define REAL_NAME "float"
#define REAL_EPS ((double)FLT_EPSILON)
#endif

/* Steps per second: 60 Hz times powers of two, and the 4/3 steps between them. */
static const double rates_full[] = {15,  20,   30,   40,   60,   80,   120,  160,  240,  320,  480,
                                    640, 960, 1280, 1920, 2560, 3840, 5120, 7680, 10240, 15360};
static const double rates_quick[] = {15, 30, 60, 120, 240, 480, 960, 1920};

#define MAX_RATES 21
#define MAX_SCENES 16

typedef struct point {
    acc_result r;
    double rate;
    double ns;   /* ns per body-step */
    double cost; /* ns per simulated second per body = ns * rate */
    int pareto;
} point;

typedef struct lab {
    const double *rates;
    int n_rates;
    int bodies, reps;
    int n_scenes;
    point pts[MAX_SCENES][ACC_INTEGRATORS][MAX_RATES];
    double ns[MAX_SCENES][ACC_INTEGRATORS];
} lab;

static FILE *open_csv(const char *dir, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s_%s.csv", dir, name, REAL_NAME);
    FILE *f = fopen(path, "w");
    if (f == NULL) {
        fprintf(stderr, "accuracy: cannot write %s\n", path);
        exit(1);
    }
    return f;
}

/* ---------------------------------------------------------------- sweep */

static int cmp_ns(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Cost does not depend on the step (the same work per step), so it is measured once per
 * scene and integrator: at 60 Hz over the scene's duration with many bodies, so the figure
 * is per body.  The repetitions go round-robin over all of them, so a burst of load on the
 * machine spreads over every figure instead of spoiling one, and the median is reported. */
static void time_all(lab *L)
{
    static double t[MAX_SCENES][ACC_INTEGRATORS][64];
    for (int r = 0; r < L->reps; r++)
        for (int si = 0; si < L->n_scenes; si++)
            for (int ig = 0; ig < ACC_INTEGRATORS; ig++)
                t[si][ig][r] = acc_time_ns(acc_scene_get(si), ig, 1.0 / 60, L->bodies, 1);
    for (int si = 0; si < L->n_scenes; si++)
        for (int ig = 0; ig < ACC_INTEGRATORS; ig++) {
            double *v = t[si][ig];
            qsort(v, (size_t)L->reps, sizeof v[0], cmp_ns);
            L->ns[si][ig] = L->reps % 2 ? v[L->reps / 2] : (v[L->reps / 2 - 1] + v[L->reps / 2]) / 2;
        }
}

static void sweep(lab *L)
{
    L->n_scenes = acc_scene_count();
    time_all(L);
    for (int si = 0; si < L->n_scenes; si++) {
        const acc_scene *s = acc_scene_get(si);
        for (int ig = 0; ig < ACC_INTEGRATORS; ig++) {
            for (int ri = 0; ri < L->n_rates; ri++) {
                point *p = &L->pts[si][ig][ri];
                p->rate = L->rates[ri];
                if (acc_run(s, ig, 1.0 / p->rate, NULL, NULL, &p->r) != RG_OK) {
                    fprintf(stderr, "accuracy: %s %s failed\n", s->name, acc_integrator_name[ig]);
                    exit(1);
                }
                p->ns = L->ns[si][ig];
                p->cost = p->ns * p->rate;
            }
        }
        /* Pareto front: no other run is both cheaper (or as cheap) and more accurate.  Errors
         * within a millionth of each other are the same result (runs that end identically
         * but for rounding, such as friction stops inside one step), as the CSV's six digits
         * show them: of those the cheapest is on the front, not every one. */
        for (int ig = 0; ig < ACC_INTEGRATORS; ig++)
            for (int ri = 0; ri < L->n_rates; ri++) {
                point *p = &L->pts[si][ig][ri];
                int dominated = !(p->r.error < ACC_INF);
                for (int jg = 0; jg < ACC_INTEGRATORS && !dominated; jg++)
                    for (int rj = 0; rj < L->n_rates && !dominated; rj++) {
                        const point *q = &L->pts[si][jg][rj];
                        double tie = 1e-6 * fmax(q->r.error, p->r.error);
                        int better = q->r.error < p->r.error - tie, same = fabs(q->r.error - p->r.error) <= tie;
                        if (q == p) continue;
                        if (q->cost <= p->cost && (better || same) && (q->cost < p->cost || better))
                            dominated = 1;
                    }
                p->pareto = !dominated;
            }
    }
}

static void write_sweep(const lab *L, const char *dir)
{
    FILE *f = open_csv(dir, "sweep");
    fprintf(f, "scene,integrator,real,rate_hz,dt,steps,error,energy_err,energy_drift,phase_err,"
               "ns_per_body_step,cost_ns_per_body_s,pareto\n");
    for (int si = 0; si < L->n_scenes; si++)
        for (int ig = 0; ig < ACC_INTEGRATORS; ig++)
            for (int ri = 0; ri < L->n_rates; ri++) {
                const point *p = &L->pts[si][ig][ri];
                fprintf(f, "%s,%s,%s,%g,%.10g,%ld,%.6e,%.6e,%.6e,%.6e,%.4g,%.6g,%d\n",
                        acc_scene_get(si)->name, acc_integrator_name[ig], REAL_NAME, p->rate,
                        1.0 / p->rate, p->r.steps, p->r.error, p->r.energy_err, p->r.energy_drift,
                        p->r.phase_err, p->ns, p->cost, p->pareto);
            }
    fclose(f);
}

/* ---------------------------------------------------------------- convergence order */

/* Least-squares slope of log(error) against log(dt) over the runs in the asymptotic range:
 * error below 0.05 (the leading term dominates) and above 10*eps*steps (round-off, which
 * grows with the number of steps, stays under a tenth of it).  ACC_NAN with fewer than 3. */
static double fit_order(const lab *L, int si, int ig, double *dt_lo, double *dt_hi, int *used)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    *dt_lo = ACC_INF;
    *dt_hi = 0;
    for (int ri = 0; ri < L->n_rates; ri++) {
        const point *p = &L->pts[si][ig][ri];
        double e = p->r.error, floor_e = 10 * REAL_EPS * (double)p->r.steps;
        if (!(e < 0.05) || !(e > floor_e)) continue;
        double x = log(1.0 / p->rate), y = log(e);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        n++;
        if (1.0 / p->rate < *dt_lo) *dt_lo = 1.0 / p->rate;
        if (1.0 / p->rate > *dt_hi) *dt_hi = 1.0 / p->rate;
    }
    *used = n;
    if (n < 3) return ACC_NAN;
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

static void write_orders(const lab *L, const char *dir)
{
    FILE *f = open_csv(dir, "orders");
    fprintf(f, "scene,integrator,real,theory,measured,points,dt_min,dt_max\n");
    printf("\nmeasured convergence order (%s; least squares over 0.05 > error > 10*eps*steps)\n",
           REAL_NAME);
    printf("%-26s", "scene");
    for (int ig = 0; ig < ACC_INTEGRATORS; ig++) printf(" %20s", acc_integrator_name[ig]);
    printf("\n");
    for (int si = 0; si < L->n_scenes; si++) {
        printf("%-26s", acc_scene_get(si)->name);
        for (int ig = 0; ig < ACC_INTEGRATORS; ig++) {
            double lo, hi;
            int n;
            double p = fit_order(L, si, ig, &lo, &hi, &n);
            fprintf(f, "%s,%s,%s,%d,%.4f,%d,%.6g,%.6g\n", acc_scene_get(si)->name,
                    acc_integrator_name[ig], REAL_NAME, acc_integrator_order[ig], p, n,
                    n ? lo : ACC_NAN, n ? hi : ACC_NAN);
            if (isnan(p))
                printf(" %20s", "-");
            else
                printf(" %13.2f (th %d)", p, acc_integrator_order[ig]);
        }
        printf("\n");
    }
    fclose(f);
}

/* ---------------------------------------------------------------- the 60 Hz table */

static int rate_index(const lab *L, double rate)
{
    for (int ri = 0; ri < L->n_rates; ri++)
        if (L->rates[ri] == rate) return ri;
    return -1;
}

static void print_table60(const lab *L)
{
    int r60 = rate_index(L, 60);
    printf("\n60 Hz, %s build: error relative to the scene's size; energy error max |E - E_exact|/E0;"
           " cost median ns per body-step (%d bodies, %d runs)\n\n",
           REAL_NAME, L->bodies, L->reps);
    printf("| scene | integrator | error | energy error | ns/body-step |\n");
    printf("|---|---|---:|---:|---:|\n");
    for (int si = 0; si < L->n_scenes; si++)
        for (int ig = 0; ig < ACC_INTEGRATORS; ig++) {
            const point *p = &L->pts[si][ig][r60];
            printf("| %s | %s | %.2e | %.2e | %.1f |\n", acc_scene_get(si)->name,
                   acc_integrator_name[ig], p->r.error, p->r.energy_err, p->ns);
        }
}

/* ---------------------------------------------------------------- energy over time */

typedef struct energy_obs {
    FILE *f;
    const acc_scene *s;
    int ig;
    double e0;
} energy_obs;

static void energy_sample(void *user, double t, const double num[4], const double exact[4])
{
    energy_obs *o = user;
    fprintf(o->f, "%s,%s,%.6f,%.9e,%.9e\n", o->s->name, acc_integrator_name[o->ig], t,
            acc_energy(o->s, num) / o->e0, acc_energy(o->s, exact) / o->e0);
}

static void write_energy60(const char *dir)
{
    FILE *f = open_csv(dir, "energy60");
    fprintf(f, "scene,integrator,t,energy_ratio,exact_ratio\n");
    const char *names[] = {"oscillator", "damped_oscillator"};
    for (int k = 0; k < 2; k++) {
        const acc_scene *s = acc_scene_find(names[k]);
        double st[4];
        acc_exact(s, 0, st);
        for (int ig = 0; ig < ACC_INTEGRATORS; ig++) {
            energy_obs o = {f, s, ig, acc_energy(s, st)};
            acc_result r;
            acc_run(s, ig, 1.0 / 60, energy_sample, &o, &r);
        }
    }
    fclose(f);
}

/* ---------------------------------------------------------------- stability */

static const double stab_theory[ACC_INTEGRATORS] = {0, 2, 2, 2.8284271247461903};

/* The per-step amplitude factor in theory: explicit Euler sqrt(1 + z^2); semi-implicit Euler
 * and Verlet share the characteristic polynomial l^2 - (2 - z^2) l + 1, so |l| = 1 up to
 * z = 2 and (z^2 - 2 + z sqrt(z^2 - 4))/2 past it; RK4 |R(iz)| = sqrt(1 - z^6/72 + z^8/576). */
static double growth_theory(int ig, double z)
{
    switch (ig) {
    case RG_INTEGRATOR_EXPLICIT_EULER: return sqrt(1 + z * z);
    case RG_INTEGRATOR_RK4: return sqrt(1 - pow(z, 6) / 72 + pow(z, 8) / 576);
    default: return z <= 2 ? 1 : (z * z - 2 + z * sqrt(z * z - 4)) / 2;
    }
}

static void write_stability(const char *dir)
{
    /* Stable: the energy stays within STAB_BOUND times its start over STAB_STEPS steps.
     * The bound is wide enough that a stable method near its edge (semi-implicit Euler's
     * energy swings by (1 + z/2)/(1 - z/2)) is not taken for unstable more than 0.02% below
     * the edge, and the horizon long enough that RK4 1% past its edge grows e^28-fold. */
    const long STAB_STEPS = 2000;
    const double STAB_BOUND = 1e4;
    FILE *f = open_csv(dir, "stability");
    fprintf(f, "integrator,real,boundary,theory,steps,energy_bound,stiffest_k_at_60hz\n");
    printf("\nstability boundary: largest omega*dt with E_n/E_0 <= %g over %ld steps (bisection)\n",
           STAB_BOUND, STAB_STEPS);
    for (int ig = 0; ig < ACC_INTEGRATORS; ig++) {
        double zb = acc_oscillator_z(acc_stability_boundary(ig, STAB_STEPS, STAB_BOUND, 0, 4, 40));
        double k = (zb * 60) * (zb * 60); /* m = 1 kg */
        fprintf(f, "%s,%s,%.6f,%.6f,%ld,%g,%.6g\n", acc_integrator_name[ig], REAL_NAME, zb,
                stab_theory[ig], STAB_STEPS, STAB_BOUND, k);
        if (ig == RG_INTEGRATOR_EXPLICIT_EULER)
            printf("  %-20s %.4f  (theory: none; energy x(1+z^2) per step, so over %ld steps "
                   "z <= sqrt(%g^(1/%ld) - 1) = %.4f)\n",
                   acc_integrator_name[ig], zb, STAB_STEPS, STAB_BOUND, STAB_STEPS,
                   sqrt(pow(STAB_BOUND, 1.0 / (double)STAB_STEPS) - 1));
        else
            printf("  %-20s %.4f  (theory %.4f, %+.3f%%): at 60 Hz a 1 kg body takes k <= %.0f N/m\n",
                   acc_integrator_name[ig], zb, stab_theory[ig],
                   100 * (zb - stab_theory[ig]) / stab_theory[ig], k);
    }
    fclose(f);
    f = open_csv(dir, "growth");
    fprintf(f, "integrator,real,z,growth,theory\n");
    for (int ig = 0; ig < ACC_INTEGRATORS; ig++)
        for (int i = 1; i <= 200; i++) {
            double z = 0.02 * i;
            fprintf(f, "%s,%s,%.4f,%.9g,%.9g\n", acc_integrator_name[ig], REAL_NAME,
                    acc_oscillator_z(z), acc_oscillator_growth(ig, z, 400),
                    growth_theory(ig, acc_oscillator_z(z)));
        }
    fclose(f);
}

/* ---------------------------------------------------------------- frame rate */

#define JUMP_V0 5.0
#define JUMP_G 9.81
#define JUMP_FRAMES 2000

static void write_framerate(const char *dir)
{
    static const double rates[] = {30, 40, 50, 60, 72, 75, 90, 100, 120, 144, 165, 200, 240};
    enum { NR = sizeof rates / sizeof rates[0], NP = NR + 5 };
    static double frames[JUMP_FRAMES];
    double naive[NP][ACC_INTEGRATORS], fixed[NP][ACC_INTEGRATORS], mean[NP];
    int same[NP][ACC_INTEGRATORS];
    double exact = acc_jump_exact(JUMP_V0, JUMP_G);
    /* steady frame rates, then jittered frames (uniform in [1/144, 1/30] s, fixed seeds) */
    for (int pi = 0; pi < NP; pi++) {
        if (pi < NR) {
            for (int i = 0; i < JUMP_FRAMES; i++) frames[i] = 1.0 / rates[pi];
            mean[pi] = rates[pi];
        } else {
            unsigned long long x = 0x9E3779B97F4A7C15ull * (unsigned long long)(pi - NR + 1);
            double sum = 0;
            for (int i = 0; i < JUMP_FRAMES; i++) {
                x = x * 6364136223846793005ull + 1442695040888963407ull;
                double u = (double)(x >> 11) / 9007199254740992.0;
                frames[i] = 1.0 / 144 + u * (1.0 / 30 - 1.0 / 144);
                sum += frames[i];
            }
            mean[pi] = JUMP_FRAMES / sum;
        }
        for (int ig = 0; ig < ACC_INTEGRATORS; ig++) {
            long steps = 0;
            naive[pi][ig] = acc_jump_naive(ig, frames, JUMP_FRAMES, JUMP_V0, JUMP_G);
            fixed[pi][ig] = acc_jump_fixed(ig, 1.0 / 60, frames, JUMP_FRAMES, JUMP_V0, JUMP_G,
                                           &same[pi][ig], &steps);
        }
    }
    /* one integrator's runs together, so a plotted series is contiguous */
    FILE *f = open_csv(dir, "framerate");
    fprintf(f, "pattern,frame_rate_hz,integrator,real,naive_apex,fixed_apex,identical,exact\n");
    printf("\njump at %.0f m/s (exact apex %.4f m), frames at 30..240 Hz and jittered:\n", JUMP_V0, exact);
    int all_same = 1;
    for (int ig = 0; ig < ACC_INTEGRATORS; ig++) {
        double lo = ACC_INF, hi = -ACC_INF;
        for (int pi = 0; pi < NP; pi++) {
            fprintf(f, "%s,%.3f,%s,%s,%.9f,%.9f,%d,%.9f\n", pi < NR ? "steady" : "jitter", mean[pi],
                    acc_integrator_name[ig], REAL_NAME, naive[pi][ig], fixed[pi][ig], same[pi][ig],
                    exact);
            if (memcmp(&fixed[pi][ig], &fixed[0][ig], sizeof(double)) != 0 || !same[pi][ig])
                all_same = 0;
            if (naive[pi][ig] < lo) lo = naive[pi][ig];
            if (naive[pi][ig] > hi) hi = naive[pi][ig];
        }
        printf("  %-20s naive per-frame apex %.4f .. %.4f m; through the 60 Hz accumulator %.6f m\n",
               acc_integrator_name[ig], lo, hi, fixed[0][ig]);
    }
    fclose(f);
    printf("  accumulator results bit-identical across every frame pattern: %s\n",
           all_same ? "yes" : "NO");
}

/* ---------------------------------------------------------------- dissipation */

static void write_dissipation(const char *dir)
{
    /* One step from v = 1 m/s, m = 1 kg: friction with mu*N*dt/m = r (naive: v' = 1 - r),
     * quadratic drag with quad*|v|*dt/m = r (naive: v' = 1 - r).  Grouped by force and
     * method so each plotted series is contiguous. */
    FILE *f = open_csv(dir, "dissipation");
    fprintf(f, "force,r,method,real,v_after\n");
    const double dt = 1.0 / 60;
    for (int force = 0; force < 2; force++)
        for (int ig = -1; ig < ACC_INTEGRATORS; ig++)
            for (int i = 0; i <= 80; i++) {
                double r = 0.05 * i, v = 0;
                if (ig < 0)
                    v = force == 0 ? acc_naive_friction_step(1, r / dt, dt)
                                   : acc_naive_drag_step(1, 0, r / dt, dt);
                else if (force == 0)
                    acc_library_dissipation(ig, 1, 1, r / dt, 0, 0, dt, 1, &v);
                else
                    acc_library_dissipation(ig, 1, 1, 0, 0, r / dt, dt, 1, &v);
                fprintf(f, "%s,%.3f,%s,%s,%.9g\n", force == 0 ? "friction" : "drag", r,
                        ig < 0 ? "naive" : acc_integrator_name[ig], REAL_NAME, v);
            }
    fclose(f);
}

#ifdef ACC_COLLISION
/* ---------------------------------------------------------------- collision scenes */

#define WALL_PHASES 64

/* A 10 cm ball (r = 0.05 m) against a 1 cm wall at 60 Hz, speeds 1..1000 m/s, 64 phases
 * each: the fraction of runs that end past the wall, with the lab's naive discrete check,
 * the library's discrete check (continuous off) and the library's continuous collision. */
static void write_tunnel(const char *dir)
{
    FILE *f = open_csv(dir, "tunnel");
    fprintf(f, "method,real,speed,rate_hz,fraction,theory\n");
    const double r = 0.05, wall = 0.01, dt = 1.0 / 60;
    double at300[3] = {0, 0, 0};
    for (int method = 0; method < 3; method++)
        for (int k = 0; k <= 30; k++) {
            double speed = pow(10.0, k / 10.0), vdt = speed * dt;
            int tunnels = 0;
            for (int i = 0; i < WALL_PHASES; i++) {
                acc_wall s = {r, wall, speed, dt, (i + 0.5) / WALL_PHASES};
                int t = method == 0 ? acc_tunnel_naive(&s)
                                    : acc_tunnel_library(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, method == 2, &s);
                tunnels += t > 0;
            }
            double frac = (double)tunnels / WALL_PHASES;
            double theory = method == 0 ? fmax(0, 1 - (wall + 2 * r) / vdt)
                          : method == 1 ? fmax(0, 1 - (wall / 2 + r) / vdt) : 0;
            fprintf(f, "%s,%s,%.6g,60,%.6f,%.6f\n",
                    method == 0 ? "lab_naive" : method == 1 ? "discrete" : "continuous", REAL_NAME,
                    speed, frac, theory);
        }
    for (int method = 0; method < 3; method++) {
        int tunnels = 0;
        for (int i = 0; i < WALL_PHASES; i++) {
            acc_wall s = {r, wall, 300, dt, (i + 0.5) / WALL_PHASES};
            int t = method == 0 ? acc_tunnel_naive(&s)
                                : acc_tunnel_library(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, method == 2, &s);
            tunnels += t > 0;
        }
        at300[method] = (double)tunnels / WALL_PHASES;
    }
    fclose(f);
    printf("\n10 cm ball at 300 m/s against a 1 cm wall at 60 Hz (%d start phases): tunnels in\n"
           "  %.1f%% with the lab's naive discrete check (theory %.1f%%), %.1f%% with the library's\n"
           "  discrete check (theory %.1f%%), %.1f%% with continuous collision (theory 0)\n",
           WALL_PHASES, 100 * at300[0], 100 * (1 - 0.11 / 5), 100 * at300[1], 100 * (1 - 0.055 / 5),
           100 * at300[2]);
}

/* Five 1 m boxes, masses 1 .. ratio kg from the bottom up, started at rest in contact: equal
 * masses and ratio 100 with the solver's default iterations, and ratio 100 with 64. */
static void write_pile(const char *dir)
{
    FILE *f = open_csv(dir, "pile");
    fprintf(f, "integrator,real,ratio,iterations,rate_hz,max_err,final_err,final_speed,max_drift\n");
    static const double ratios[] = {1, 100, 100};
    static const int iters[] = {0, 0, 64};
    static const double prates[] = {30, 60, 120, 240};
    printf("\npile of 5 boxes (masses 1..ratio kg, bottom up) started at rest, 5 s: largest\n"
           "|y - y_rest| over the run, m (a box is 1 m; >= 0.5 means boxes passed into each other)\n");
    printf("  %-20s %6s %10s", "integrator", "ratio", "iterations");
    for (int ri = 0; ri < 4; ri++) printf(" %9g Hz", prates[ri]);
    printf("\n");
    for (int ig = 0; ig < ACC_INTEGRATORS; ig++)
        for (int k = 0; k < 3; k++) {
            printf("  %-20s %6g %10s", acc_integrator_name[ig], ratios[k], iters[k] ? "64" : "default");
            for (int ri = 0; ri < 4; ri++) {
                acc_pile_result p;
                if (acc_pile(ig, 1.0 / prates[ri], ratios[k], 5, 5.0, iters[k], &p) != RG_OK) {
                    fprintf(stderr, "accuracy: pile failed\n");
                    exit(1);
                }
                fprintf(f, "%s,%s,%g,%d,%g,%.6e,%.6e,%.6e,%.6e\n", acc_integrator_name[ig],
                        REAL_NAME, ratios[k], iters[k], prates[ri], p.max_err, p.final_err,
                        p.final_speed, p.max_drift);
                printf(" %12.2e", p.max_err);
            }
            printf("\n");
        }
    fclose(f);
}
#endif

/* ---------------------------------------------------------------- recommend */

static void recommend(const lab *L, const double *budgets, int nb)
{
    int r60 = rate_index(L, 60);
    printf("recommend (%s build): the cheapest integrator and step whose error (relative to the\n"
           "scene's size) meets the budget; cost = ns per body-step x steps per second\n", REAL_NAME);
    for (int bi = 0; bi < nb; bi++) {
        double budget = budgets[bi];
        printf("\nbudget %g:\n", budget);
        printf("  %-24s %-20s %7s %9s %12s | at 60 Hz\n", "scene", "cheapest", "Hz", "error",
               "ns/body/s");
        for (int si = 0; si < L->n_scenes; si++) {
            const point *best = NULL;
            int best_ig = -1;
            for (int ig = 0; ig < ACC_INTEGRATORS; ig++)
                for (int ri = 0; ri < L->n_rates; ri++) {
                    const point *p = &L->pts[si][ig][ri];
                    if (!(p->r.error <= budget)) continue;
                    if (best == NULL || p->cost < best->cost ||
                        (p->cost == best->cost && p->r.error < best->r.error)) {
                        best = p;
                        best_ig = ig;
                    }
                }
            printf("  %-24s ", acc_scene_get(si)->name);
            if (best == NULL)
                printf("%-20s %7s %9s %12s", "none in the sweep", "-", "-", "-");
            else
                printf("%-20s %7g %9.2e %12.0f", acc_integrator_name[best_ig], best->rate,
                       best->r.error, best->cost);
            /* at the game's usual fixed step */
            const point *b60 = NULL;
            int b60_ig = -1;
            for (int ig = 0; ig < ACC_INTEGRATORS && r60 >= 0; ig++) {
                const point *p = &L->pts[si][ig][r60];
                if (p->r.error <= budget && (b60 == NULL || p->cost < b60->cost)) {
                    b60 = p;
                    b60_ig = ig;
                }
            }
            if (b60 != NULL)
                printf(" | %s (%.2e)\n", acc_integrator_name[b60_ig], b60->r.error);
            else
                printf(" | none meets it at 60 Hz\n");
        }
    }
}

#ifdef ACC_COLLISION
/* Random soups (accuracy_soup.c): momentum and kinetic energy through contacts, with and
 * without restitution and friction, at the default 8 velocity iterations and at 64. */
static void print_soups(int quick)
{
    static const struct {
        int restitution, friction;
        double speed;
    } kinds[] = {{0, 1, 50}, {1, 0, 5}, {1, 1, 5}, {1, 1, 50}};
    static const int iterations[] = {8, 64};
    int scenes = quick ? 60 : 300;
    printf("random soups: %d scenes of 20-79 boxes and circles, 300 steps at 60 Hz, no gravity, sleeping off\n"
           "(a scene gains when its kinetic energy rises by more than 0.1%% of the start's)\n",
           scenes);
    printf("%-11s %-9s %9s %10s %14s %11s %15s\n", "restitution", "friction", "speed m/s", "iterations",
           "scenes gaining", "worst gain", "worst momentum");
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        for (size_t i = 0; i < sizeof iterations / sizeof iterations[0]; i++) {
            acc_soup s;
            acc_soup_result r;
            s.scenes = scenes;
            s.steps = 300;
            s.restitution = kinds[k].restitution;
            s.friction = kinds[k].friction;
            s.max_speed = kinds[k].speed;
            s.velocity_iterations = iterations[i];
            rg_status st = acc_soup_run(&s, &r);
            if (st != RG_OK) {
                printf("soup failed: %s\n", rg_status_string(st));
                continue;
            }
            printf("%-11s %-9s %9.0f %10d %8d of %-3d %10.2f%% %15.1e\n", s.restitution ? "0-1" : "0",
                   s.friction ? "0-1" : "0", s.max_speed, s.velocity_iterations, r.gaining, scenes,
                   100 * r.worst_gain, r.worst_momentum);
        }
    }
    static const double ratios[] = {1, 4, 8, 30};
    static const int push_iterations[] = {8, 16, 32, 64};
    printf("\na box of m kg run at 5 m/s into a 1 kg box against a wall (floor without friction, gravity,\n"
           "restitution 0): the fastest it moves back, m/s (exact: 0)\n%-10s", "iterations");
    for (size_t r = 0; r < sizeof ratios / sizeof ratios[0]; r++) printf(" %8s%-3.0f", "m = ", ratios[r]);
    printf("\n");
    for (size_t i = 0; i < sizeof push_iterations / sizeof push_iterations[0]; i++) {
        printf("%-10d", push_iterations[i]);
        for (size_t r = 0; r < sizeof ratios / sizeof ratios[0]; r++) {
            double back = 0;
            if (acc_push_rebound(ratios[r], 5, push_iterations[i], &back) != RG_OK) back = -1;
            printf(" %11.2f", back);
        }
        printf("\n");
    }
    static const double bands[][2] = {{5, 25}, {25, 50}, {50, 100}, {100, 200}};
    int paddle_scenes = quick ? 100 : 400;
    printf("\na kinematic paddle 2-12 cm thick driven through 1-19 loose bodies (%d scenes a band of\n"
           "speeds): the bodies that end a step behind it (exact: none)\n", paddle_scenes);
    for (size_t k = 0; k < sizeof bands / sizeof bands[0]; k++) {
        int through, bodies;
        if (acc_paddle_run(paddle_scenes, bands[k][0], bands[k][1], &through, &bodies) != RG_OK) through = -1;
        printf("  %3.0f-%3.0f m/s  %d of %d\n", bands[k][0], bands[k][1], through, bodies);
    }
}
#endif

/* ---------------------------------------------------------------- main */

static void usage(void)
{
    fprintf(stderr, "usage: accuracy [--out DIR] [--quick] [--bodies N] [--reps R]\n"
                    "       accuracy --recommend [BUDGET] [--quick]\n"
                    "       accuracy --soup [--quick]\n"
                    "       accuracy --contacts [--quick]\n");
    exit(2);
}

int main(int argc, char **argv)
{
    static lab L;
    const char *dir = "build/charts";
    int quick = 0, do_recommend = 0, do_soup = 0, do_contacts = 0;
    double budgets[8] = {1e-2, 1e-3, 1e-4};
    int nb = 3;
    L.bodies = 1024;
    L.reps = 7;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--out") == 0 && i + 1 < argc) {
            dir = argv[++i];
        } else if (strcmp(argv[i], "--quick") == 0) {
            quick = 1;
        } else if (strcmp(argv[i], "--bodies") == 0 && i + 1 < argc) {
            L.bodies = atoi(argv[++i]);
        } else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc) {
            L.reps = atoi(argv[++i]);
        } else if (strcmp(argv[i], "--soup") == 0) {
            do_soup = 1;
        } else if (strcmp(argv[i], "--contacts") == 0) {
            do_contacts = 1;
        } else if (strcmp(argv[i], "--recommend") == 0) {
            do_recommend = 1;
            if (i + 1 < argc && argv[i + 1][0] != '-') {
                char *end;
                double b = strtod(argv[++i], &end);
                if (*end != '\0' || !(b > 0)) usage();
                budgets[0] = b;
                nb = 1;
            }
        } else {
            usage();
        }
    }
    if (L.bodies < 1 || L.reps < 1 || L.reps > 64) usage();
    L.rates = quick ? rates_quick : rates_full;
    L.n_rates = quick ? (int)(sizeof rates_quick / sizeof rates_quick[0])
                      : (int)(sizeof rates_full / sizeof rates_full[0]);
    if (quick) {
        L.bodies = L.bodies > 256 ? 256 : L.bodies;
        L.reps = L.reps > 3 ? 3 : L.reps;
    }
    if (rg_real_size() != (int32_t)sizeof(rg_real)) {
        fprintf(stderr, "accuracy: library/header real size mismatch\n");
        return 1;
    }
    if (do_soup || do_contacts) {
#ifdef ACC_COLLISION
        if (do_soup) print_soups(quick);
        return do_contacts && acc_contacts_print(quick) != 0;
#else
        fprintf(stderr, "accuracy: --soup and --contacts need the library's collision\n");
        return 1;
#endif
    }
    sweep(&L);
    if (do_recommend) {
        recommend(&L, budgets, nb);
        return 0;
    }
    write_sweep(&L, dir);
    print_table60(&L);
    write_orders(&L, dir);
    write_energy60(dir);
    write_stability(dir);
    write_framerate(dir);
    write_dissipation(dir);
#ifdef ACC_COLLISION
    write_tunnel(dir);
    write_pile(dir);
#endif
    printf("\nCSV written to %s/*_%s.csv\n", dir, REAL_NAME);
    return 0;
}
