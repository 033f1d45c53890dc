/* accuracy_scenes.c: reference scenes with exact solutions and the failure experiments. */
#if !defined(_POSIX_C_SOURCE) || _POSIX_C_SOURCE < 199309L
#undef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 199309L /* clock_gettime */
#endif
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "accuracy_scenes.h"

#define ACC_PI 3.14159265358979323846
#define ACC_G 9.81

const char *const acc_integrator_name[ACC_INTEGRATORS] = {
    "explicit_euler", "semi_implicit_euler", "verlet", "rk4"};
const int acc_integrator_order[ACC_INTEGRATORS] = {1, 1, 2, 4};

/* Game-sized scenes: a 1 Hz spring, a ball thrown at 14 m/s, a 10 m/s terminal velocity,
 * a box sliding at 5 m/s.  size is filled in by scene_init. */
static acc_scene scenes[] = {
    {"oscillator", "1 kg on a 1 Hz spring (k = 4 pi^2 N/m) from x = 1 m at rest, 10 s",
     ACC_TRAJECTORY, 10.0, 1.0, 0.0, 4 * ACC_PI * ACC_PI, 0.0, 0.0, 0.0, 0.0,
     1.0, 0.0, 0.0, 0.0, 0.0},
    {"damped_oscillator", "the same spring with damping ratio 0.1 (c = 0.4 pi N*s/m), 5 s",
     ACC_TRAJECTORY, 5.0, 1.0, 0.0, 4 * ACC_PI * ACC_PI, 0.4 * ACC_PI, 0.0, 0.0, 0.0,
     1.0, 0.0, 0.0, 0.0, 0.0},
    {"projectile_linear_drag", "1 kg thrown at (10, 10) m/s, linear drag 0.5 kg/s (tau = 2 s), 2 s",
     ACC_TRAJECTORY, 2.0, 1.0, ACC_G, 0.0, 0.0, 0.5, 0.0, 0.0,
     0.0, 0.0, 10.0, 10.0, 0.0},
    {"fall_quadratic_drag", "1 kg falling from rest, terminal velocity 10 m/s, 3 s",
     ACC_TRAJECTORY, 3.0, 1.0, ACC_G, 0.0, 0.0, 0.0, ACC_G / 100.0, 0.0,
     0.0, 0.0, 0.0, 0.0, 0.0},
    {"throw_up_quadratic_drag", "1 kg thrown up at 20 m/s, terminal velocity 10 m/s: apex height",
     ACC_APEX, 2.3, 1.0, ACC_G, 0.0, 0.0, 0.0, ACC_G / 100.0, 0.0,
     0.0, 0.0, 0.0, 20.0, 0.0},
    {"slide_friction", "1 kg box sliding at 5 m/s, mu*N = 0.5 * 9.81 N: stopping distance",
     ACC_STOP, 1.6, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.5 * ACC_G,
     0.0, 0.0, 3.0, 4.0, 0.0},
};
#define N_SCENES ((int)(sizeof scenes / sizeof scenes[0]))

static double terminal_velocity(const acc_scene *s) { return sqrt(s->mass * s->gravity / s->quad); }

static void scene_init(void)
{
    static int done = 0;
    if (done) return;
    for (int i = 0; i < N_SCENES; i++) {
        acc_scene *s = &scenes[i];
        if (s->k > 0) {
            s->size = sqrt(s->x0 * s->x0 + s->y0 * s->y0); /* the amplitude */
        } else if (s->kind == ACC_APEX) {
            double vt = terminal_velocity(s);
            s->size = vt * vt / (2 * s->gravity) * log1p(s->vy0 * s->vy0 / (vt * vt));
        } else if (s->kind == ACC_STOP) {
            double v2 = s->vx0 * s->vx0 + s->vy0 * s->vy0;
            s->size = v2 / (2 * s->fric / s->mass);
        } else {
            /* the farthest the exact path gets from its start */
            double st[4], m = 0;
            for (int j = 1; j <= 4000; j++) {
                acc_exact(s, s->duration * j / 4000.0, st);
                double d = hypot(st[0] - s->x0, st[1] - s->y0);
                if (d > m) m = d;
            }
            s->size = m;
        }
    }
    done = 1;
}

int acc_scene_count(void) { return N_SCENES; }

const acc_scene *acc_scene_get(int i)
{
    scene_init();
    return i >= 0 && i < N_SCENES ? &scenes[i] : NULL;
}

const acc_scene *acc_scene_find(const char *name)
{
    for (int i = 0; i < N_SCENES; i++)
        if (strcmp(scenes[i].name, name) == 0) return acc_scene_get(i);
    return NULL;
}

/* ---------------------------------------------------------------- exact solutions */

void acc_exact(const acc_scene *s, double t, double st[4])
{
    double m = s->mass, g = s->gravity;
    if (s->k > 0) {
        /* x'' + 2 sigma x' + w^2 x = 0, underdamped, along x:
         * x = e^(-sigma t) (x0 cos wd t + (v0 + sigma x0)/wd sin wd t)
         * v = e^(-sigma t) (v0 cos wd t - (w^2 x0 + sigma v0)/wd sin wd t) */
        double w2 = s->k / m, sigma = s->c / (2 * m), wd = sqrt(w2 - sigma * sigma);
        double e = exp(-sigma * t), cs = cos(wd * t), sn = sin(wd * t);
        st[0] = e * (s->x0 * cs + (s->vx0 + sigma * s->x0) / wd * sn);
        st[2] = e * (s->vx0 * cs - (w2 * s->x0 + sigma * s->vx0) / wd * sn);
        st[1] = s->y0;
        st[3] = 0;
    } else if (s->fric > 0) {
        /* constant deceleration a = mu*N/m along -v0 until rest at t = |v0|/a */
        double a = s->fric / m, v0 = hypot(s->vx0, s->vy0);
        double ts = t < v0 / a ? t : v0 / a;
        double sp = v0 - a * ts, d = v0 * ts - a * ts * ts / 2;
        st[0] = s->x0 + d * s->vx0 / v0;
        st[1] = s->y0 + d * s->vy0 / v0;
        st[2] = sp * s->vx0 / v0;
        st[3] = sp * s->vy0 / v0;
    } else if (s->lin > 0) {
        /* tau = m/c: x = v0x tau (1 - e^(-t/tau)), y = (v0y + g tau) tau (1 - e^(-t/tau)) - g tau t */
        double tau = m / s->lin, f = -expm1(-t / tau), e = exp(-t / tau);
        st[0] = s->x0 + s->vx0 * tau * f;
        st[1] = s->y0 + (s->vy0 + g * tau) * tau * f - g * tau * t;
        st[2] = s->vx0 * e;
        st[3] = (s->vy0 + g * tau) * e - g * tau;
    } else if (s->quad > 0) {
        /* vertical motion with F = -quad |v| v, vt = sqrt(m g / quad).  Rising from v0 > 0:
         * v = vt tan(th0 - g t/vt), y = vt^2/g ln(cos(th0 - g t/vt) / cos th0), th0 = atan(v0/vt),
         * apex at ta = vt/g th0, H = vt^2/(2g) ln(1 + v0^2/vt^2); then falling from rest:
         * v = -vt tanh(g (t - ta)/vt), y = H - vt^2/g ln cosh(g (t - ta)/vt). */
        double vt = terminal_velocity(s), th0 = atan(s->vy0 / vt), ta = vt / g * th0;
        double h = vt * vt / (2 * g) * log1p(s->vy0 * s->vy0 / (vt * vt));
        if (t < ta) {
            double th = th0 - g * t / vt;
            st[1] = s->y0 + vt * vt / g * log(cos(th) / cos(th0));
            st[3] = vt * tan(th);
        } else {
            double u = g * (t - ta) / vt;
            /* ln cosh u = u + ln(1 + e^(-2u)) - ln 2, exact for large u too */
            st[1] = s->y0 + h - vt * vt / g * (u + log1p(exp(-2 * u)) - log(2.0));
            st[3] = -vt * tanh(u);
        }
        st[0] = s->x0;
        st[2] = 0;
    } else {
        st[0] = s->x0 + s->vx0 * t;
        st[1] = s->y0 + s->vy0 * t - g * t * t / 2;
        st[2] = s->vx0;
        st[3] = s->vy0 - g * t;
    }
}

double acc_energy(const acc_scene *s, const double st[4])
{
    return 0.5 * s->mass * (st[2] * st[2] + st[3] * st[3]) +
           0.5 * s->k * (st[0] * st[0] + st[1] * st[1]) + s->mass * s->gravity * st[1];
}

/* ---------------------------------------------------------------- running */

static rg_vec2 acc_v2(double x, double y)
{
    rg_vec2 v;
    v.x = (rg_real)x;
    v.y = (rg_real)y;
    return v;
}

rg_status acc_build(const acc_scene *s, int integrator, int n, rg_world **out_world,
                    rg_body *out_first)
{
    rg_world *w = NULL;
    rg_status st = rg_world_create(&w);
    if (st != RG_OK) return st;
    st = rg_world_set_gravity(w, acc_v2(0, -s->gravity));
    if (st == RG_OK) st = rg_world_set_integrator(w, integrator);
    for (int i = 0; i < n && st == RG_OK; i++) {
        /* copies on a grid 10 m apart, each with its own spring anchor */
        double ox = 10.0 * (i % 64), oy = 10.0 * (i / 64);
        rg_body b = 0;
        st = rg_body_create(w, RG_BODY_DYNAMIC, (rg_real)s->mass, acc_v2(s->x0 + ox, s->y0 + oy), &b);
        if (st == RG_OK) st = rg_body_set_velocity(w, b, acc_v2(s->vx0, s->vy0));
        if (st == RG_OK && (s->lin > 0 || s->quad > 0))
            st = rg_body_set_drag(w, b, (rg_real)s->lin, (rg_real)s->quad);
        if (st == RG_OK && s->fric > 0) st = rg_body_set_surface_friction(w, b, 1, (rg_real)s->fric);
        if (st == RG_OK && s->k > 0) {
            uint64_t sp;
            st = rg_spring_create(w, b, 0, acc_v2(ox, oy), 0, (rg_real)s->k, (rg_real)s->c, &sp);
        }
        if (i == 0 && out_first != NULL) *out_first = b;
    }
    if (st != RG_OK) {
        rg_world_destroy(w);
        return st;
    }
    *out_world = w;
    return RG_OK;
}

static void read_state(rg_world *w, rg_body b, double st[4])
{
    rg_vec2 p = {0, 0}, v = {0, 0};
    rg_body_get_position(w, b, &p);
    rg_body_get_velocity(w, b, &v);
    st[0] = (double)p.x;
    st[1] = (double)p.y;
    st[2] = (double)v.x;
    st[3] = (double)v.y;
}

static int state_ok(const double st[4])
{
    for (int i = 0; i < 4; i++)
        if (!isfinite(st[i]) || fabs(st[i]) > 1e12) return 0;
    return 1;
}

/* Phase of an underdamped oscillator state: x = R e^(-sigma t) cos psi and
 * -(v + sigma x)/wd = R e^(-sigma t) sin psi, so psi = atan2(-(v + sigma x)/wd, x). */
static double osc_phase(const acc_scene *s, const double st[4])
{
    double w2 = s->k / s->mass, sigma = s->c / (2 * s->mass), wd = sqrt(w2 - sigma * sigma);
    return atan2(-(st[2] + sigma * st[0]) / wd, st[0]);
}

/* Cubic Hermite on [0, 1] through f0, f1 with slopes d0, d1 (already times the interval). */
static double hermite(double f0, double d0, double f1, double d1, double u)
{
    double u2 = u * u, u3 = u2 * u;
    return (2 * u3 - 3 * u2 + 1) * f0 + (u3 - 2 * u2 + u) * d0 + (-2 * u3 + 3 * u2) * f1 +
           (u3 - u2) * d1;
}

/* Acceleration of the vertical quadratic-drag body at velocity v: -g - quad |v| v / m. */
static double quad_accel(const acc_scene *s, double v)
{
    return -s->gravity - s->quad * fabs(v) * v / s->mass;
}

rg_status acc_run(const acc_scene *s, int integrator, double dt, acc_observer obs, void *user,
                  acc_result *out)
{
    rg_world *w = NULL;
    rg_body b = 0;
    rg_status st = acc_build(s, integrator, 1, &w, &b);
    if (st != RG_OK) return st;
    rg_real hr = (rg_real)dt;
    double h = (double)hr; /* the step the library takes */
    long n = (long)ceil(s->duration / h - 1e-9);
    double prev[4], num[4], ex[4];
    acc_exact(s, 0, ex);
    read_state(w, b, prev);
    /* E_0, or for a scene that starts with none (a fall from rest at y = 0) m*g*size */
    double e0 = acc_energy(s, ex);
    if (!(fabs(e0) > 0)) e0 = s->mass * s->gravity * s->size;
    acc_result r;
    memset(&r, 0, sizeof r);
    r.finite = 1;
    double stop_t = -1;
    int apex_found = 0;
    long i;
    for (i = 1; i <= n; i++) {
        st = rg_world_step(w, hr);
        if (st != RG_OK) break;
        double t = (double)i * h;
        read_state(w, b, num);
        acc_exact(s, t, ex);
        if (obs != NULL) obs(user, t, num, ex);
        if (!state_ok(num)) {
            r.finite = 0;
            break;
        }
        double de = (acc_energy(s, num) - acc_energy(s, ex)) / e0;
        if (fabs(de) > r.energy_err) r.energy_err = fabs(de);
        r.energy_drift = de;
        r.steps = i;
        if (s->kind == ACC_TRAJECTORY) {
            double e = hypot(num[0] - ex[0], num[1] - ex[1]) / s->size;
            if (e > r.error) r.error = e;
        } else if (s->kind == ACC_APEX && prev[3] > 0 && num[3] <= 0) {
            /* The apex time from the cubic Hermite of v (slopes: the force law at each end),
             * the height from the cubic Hermite of y (slopes: v); both O(h^4) accurate, so
             * the measurement does not cap RK4's order. */
            double a0 = quad_accel(s, prev[3]) * h, a1 = quad_accel(s, num[3]) * h;
            double lo = 0, hi = 1;
            for (int k = 0; k < 60; k++) {
                double mid = (lo + hi) / 2;
                if (hermite(prev[3], a0, num[3], a1, mid) > 0) lo = mid; else hi = mid;
            }
            double u = (lo + hi) / 2;
            double apex = hermite(prev[1], prev[3] * h, num[1], num[3] * h, u) - s->y0;
            double vt = terminal_velocity(s);
            r.error = fabs(apex - s->size) / s->size;
            r.phase_err = (t - h + u * h) - vt / s->gravity * atan(s->vy0 / vt);
            apex_found = 1;
            break;
        } else if (s->kind == ACC_STOP && stop_t < 0 && num[2] == 0 && num[3] == 0) {
            stop_t = t;
        }
        memcpy(prev, num, sizeof prev);
    }
    if (st == RG_OK && r.finite) {
        if (s->k > 0) {
            double dp = osc_phase(s, num) - osc_phase(s, ex);
            r.phase_err = atan2(sin(dp), cos(dp));
        } else if (s->kind == ACC_APEX && !apex_found) {
            r.error = ACC_INF;
        } else if (s->kind == ACC_STOP) {
            double a = s->fric / s->mass, v0 = hypot(s->vx0, s->vy0);
            double d = hypot(num[0] - s->x0, num[1] - s->y0);
            r.error = stop_t < 0 ? ACC_INF : fabs(d - s->size) / s->size;
            r.phase_err = stop_t < 0 ? ACC_INF : stop_t - v0 / a;
        }
    }
    if (!r.finite) {
        r.error = r.energy_err = r.energy_drift = ACC_INF;
    }
    rg_world_destroy(w);
    *out = r;
    return st;
}

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double acc_time_ns(const acc_scene *s, int integrator, double dt, int n, int reps)
{
    double t[64];
    if (reps > 64) reps = 64;
    long steps = (long)ceil(s->duration / dt - 1e-9);
    for (int r = 0; r < reps; r++) {
        rg_world *w = NULL;
        if (acc_build(s, integrator, n, &w, NULL) != RG_OK) return ACC_NAN;
        double t0 = now_ns();
        for (long i = 0; i < steps; i++) rg_world_step(w, (rg_real)dt);
        t[r] = (now_ns() - t0) / ((double)n * (double)steps);
        rg_world_destroy(w);
    }
    qsort(t, (size_t)reps, sizeof t[0], cmp_double);
    return reps % 2 ? t[reps / 2] : (t[reps / 2 - 1] + t[reps / 2]) / 2;
}

/* ---------------------------------------------------------------- stability */

#define STAB_DT (1.0 / 60.0)

double acc_oscillator_z(double z)
{
    double k = (double)(rg_real)((z / STAB_DT) * (z / STAB_DT));
    return sqrt(k) * (double)(rg_real)STAB_DT;
}

/* The oscillator above stepped n_steps times (or until E/E0 passes 1e30): the largest
 * and the last E_n/E_0 and the steps taken.  It starts at A = 1e-12 m: the step's range
 * guard stops a body past RG_MAX_SPEED, and E/E0 = 1e30 is an amplitude of 1e15 A = 1e3 m and
 * a speed of at most omega 1e3 = 2.4e5 m/s (z <= 4), inside it.  Rounding is relative, so
 * the ratios do not depend on A. */
static double oscillator_run(int integrator, double z, long n_steps, double *out_last,
                             long *out_steps)
{
    rg_world *w = NULL;
    rg_body b = 0;
    uint64_t sp;
    double om = z / STAB_DT;
    rg_real k = (rg_real)(om * om);
    if (rg_world_create(&w) != RG_OK) return ACC_NAN;
    rg_world_set_integrator(w, integrator);
    const double a = (double)(rg_real)1e-12;
    rg_body_create(w, RG_BODY_DYNAMIC, 1, acc_v2(a, 0), &b);
    rg_spring_create(w, b, 0, acc_v2(0, 0), 0, k, 0, &sp);
    double kd = (double)k, e0 = 0.5 * kd * a * a, mx = 1, last = 1;
    long i;
    for (i = 0; i < n_steps; i++) {
        rg_world_step(w, (rg_real)STAB_DT);
        double st[4];
        read_state(w, b, st);
        double e = (0.5 * (st[2] * st[2] + st[3] * st[3]) +
                    0.5 * kd * (st[0] * st[0] + st[1] * st[1])) / e0;
        if (!isfinite(e)) break;
        last = e;
        if (e > mx) mx = e;
        if (e > 1e30) {
            i++;
            break;
        }
    }
    rg_world_destroy(w);
    if (out_last != NULL) *out_last = last;
    if (out_steps != NULL) *out_steps = i;
    return mx;
}

double acc_oscillator_energy_ratio(int integrator, double z, long n_steps, double *out_last)
{
    long done = 0;
    double mx = oscillator_run(integrator, z, n_steps, out_last, &done);
    return done < n_steps ? ACC_INF : mx;
}

double acc_oscillator_growth(int integrator, double z, long n_steps)
{
    long done = 0;
    double last = 1;
    oscillator_run(integrator, z, n_steps, &last, &done);
    return done > 0 ? pow(last, 1.0 / (2.0 * (double)done)) : ACC_NAN;
}

double acc_stability_boundary(int integrator, long n_steps, double bound, double lo, double hi,
                              int iters)
{
    if (acc_oscillator_energy_ratio(integrator, hi, n_steps, NULL) <= bound) return hi;
    for (int i = 0; i < iters; i++) {
        double mid = (lo + hi) / 2;
        if (acc_oscillator_energy_ratio(integrator, mid, n_steps, NULL) <= bound)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* ---------------------------------------------------------------- dissipation */

double acc_naive_friction_step(double v, double fric_over_m, double dt)
{
    return v - fric_over_m * dt * (v > 0 ? 1 : v < 0 ? -1 : 0);
}

double acc_naive_drag_step(double v, double lin_over_m, double quad_over_m, double dt)
{
    return v - (lin_over_m + quad_over_m * fabs(v)) * v * dt;
}

rg_status acc_library_dissipation(int integrator, double m, double v, double fric, double lin,
                                  double quad, double dt, int n, double *out)
{
    rg_world *w = NULL;
    rg_body b = 0;
    rg_status st = rg_world_create(&w);
    if (st != RG_OK) return st;
    st = rg_world_set_integrator(w, integrator);
    if (st == RG_OK) st = rg_body_create(w, RG_BODY_DYNAMIC, (rg_real)m, acc_v2(0, 0), &b);
    if (st == RG_OK) st = rg_body_set_velocity(w, b, acc_v2(v, 0));
    if (st == RG_OK && fric > 0) st = rg_body_set_surface_friction(w, b, 1, (rg_real)fric);
    if (st == RG_OK && (lin > 0 || quad > 0)) st = rg_body_set_drag(w, b, (rg_real)lin, (rg_real)quad);
    for (int i = 0; i < n && st == RG_OK; i++) {
        st = rg_world_step(w, (rg_real)dt);
        double s4[4];
        read_state(w, b, s4);
        out[i] = s4[2];
    }
    rg_world_destroy(w);
    return st;
}

/* ---------------------------------------------------------------- frame rate */

static rg_status jump_world(int integrator, double v0, double g, rg_world **w, rg_body *b)
{
    rg_status st = rg_world_create(w);
    if (st != RG_OK) return st;
    st = rg_world_set_gravity(*w, acc_v2(0, -g));
    if (st == RG_OK) st = rg_world_set_integrator(*w, integrator);
    if (st == RG_OK) st = rg_body_create(*w, RG_BODY_DYNAMIC, 1, acc_v2(0, 0), b);
    if (st == RG_OK) st = rg_body_set_velocity(*w, *b, acc_v2(0, v0));
    if (st != RG_OK) rg_world_destroy(*w);
    return st;
}

double acc_jump_naive(int integrator, const double *frames, int n_frames, double v0, double g)
{
    rg_world *w = NULL;
    rg_body b = 0;
    if (jump_world(integrator, v0, g, &w, &b) != RG_OK) return ACC_NAN;
    double apex = 0;
    for (int i = 0; i < n_frames; i++) {
        rg_world_step(w, (rg_real)frames[i]);
        double st[4];
        read_state(w, b, st);
        if (st[1] > apex) apex = st[1];
        if (st[1] < 0) break;
    }
    rg_world_destroy(w);
    return apex;
}

double acc_jump_fixed(int integrator, double dt, const double *frames, int n_frames, double v0,
                      double g, int *identical, long *out_steps)
{
    rg_world *w = NULL, *ref = NULL;
    rg_body b = 0, rb = 0;
    if (jump_world(integrator, v0, g, &w, &b) != RG_OK) return ACC_NAN;
    if (jump_world(integrator, v0, g, &ref, &rb) != RG_OK) {
        rg_world_destroy(w);
        return ACC_NAN;
    }
    rg_world_set_fixed_step(w, (rg_real)dt, 64);
    double apex = 0;
    long steps = 0;
    int same = 1, landed = 0;
    for (int i = 0; i < n_frames && !landed; i++) {
        int32_t k = 0;
        rg_world_advance(w, (rg_real)frames[i], &k);
        for (int32_t j = 0; j < k; j++) {
            double st[4];
            rg_world_step(ref, (rg_real)dt);
            read_state(ref, rb, st);
            if (st[1] > apex) apex = st[1];
            if (st[1] < 0) landed = 1;
        }
        steps += k;
        rg_vec2 p, q, v, u;
        rg_body_get_position(w, b, &p);
        rg_body_get_position(ref, rb, &q);
        rg_body_get_velocity(w, b, &v);
        rg_body_get_velocity(ref, rb, &u);
        if (memcmp(&p, &q, sizeof p) != 0 || memcmp(&v, &u, sizeof v) != 0) same = 0;
    }
    rg_world_destroy(w);
    rg_world_destroy(ref);
    if (identical != NULL) *identical = same;
    if (out_steps != NULL) *out_steps = steps;
    return apex;
}

double acc_jump_exact(double v0, double g) { return v0 * v0 / (2 * g); }
