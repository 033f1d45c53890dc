/* test_accuracy.c: what the accuracy lab shows, asserted against theory with the lab's own
 * measuring code (tools/accuracy_scenes.c): convergence orders, stability boundaries found
 * by bisection, and each failure where theory puts it next to the library's remedy.
 *
 * Rounding, used throughout: an rg_real operation rounds with relative error <= eps/2
 * (REAL_EPS = 2^-52 double, 2^-23 float).  A step of these integrators does a few dozen
 * such operations on quantities no larger than the state's norm, so the state after n steps
 * carries a relative rounding error of at most about c*n*eps with c ~ 10-30; and the
 * parameters themselves (k, dt, g) are rg_real-rounded, which the exact solutions here take
 * into account where it matters (acc_oscillator_z, the actual step (rg_real)dt). */
#include "testutil.h"

#include "accuracy_scenes.h"
#ifdef ACC_COLLISION
#include "accuracy_collision.h"
#endif

/* ---------------------------------------------------------------- convergence order */

/* Least-squares slope of log(error) against log(dt) on the 1 Hz oscillator (omega = 2 pi,
 * A = 1 m) over ONE period (T = 1 s), the error being the lab's: max over the run of
 * |x_n - x(t_n)| / A.
 *
 * Why this scene and these steps.  The global error is e(h) = C h^p (1 + r(h)) + rounding.
 *  - Truncation: r(h) = O(omega h) for all four, except that explicit Euler's amplitude
 *    grows as (1 + z^2)^(n/2) = e^(omega^2 h t / 2)(1 + ...), so its error is
 *    e^x - 1 = x (1 + x/2 + ...) with x = omega^2 h T / 2 = 19.7 h; one period keeps x small.
 *  - The slope over three steps h, h/2, h/4 (equally spaced in log) is
 *    (log e1 - log e3) / log 4, so relative perturbations d of the errors move it by at most
 *    log((1 + d)/(1 - d)) / log 4 ~ 1.44 d.  We need truncation + rounding d < 0.06.
 *  - Double: Euler types at 1000..4000 Hz: x <= 0.02, z = omega h <= 0.0063, so r < 0.02
 *    (slope off by < 0.03); Verlet at 100..400 Hz: r = O(z^2) <= 0.004; RK4 at 50..200 Hz:
 *    r = O(z^2) <= 0.016, and its smallest error ~ omega T z^4 / 120 = 5e-8 stays 1e6 times
 *    above rounding (200 steps * 30 * 2.2e-16 = 1.3e-12).
 *  - Float rounds at 6e-8: 1000 steps leave up to ~1e-4 (worst case, ~4e-6 typical) of
 *    rounding.  Explicit and semi-implicit Euler at 250..1000 Hz: errors 3e-3..8e-2, so
 *    d <= 0.03 worst case, and x <= 0.08 gives explicit Euler a slope of at most 1.05.
 *    Verlet at 50..200 Hz: errors 4e-3..2.6e-4, d <= 200 steps * 30 * 6e-8 / 2.6e-4 = 0.014.
 *    RK4's error 1e-5 at 50 Hz already meets float rounding, so float can only show its
 *    order where steps are large: 15..30 Hz (15, 21.2, 30 Hz: errors 2e-3..1e-4, z <= 0.42
 *    where the double build measures local orders 3.99-4.01, i.e. r(h) < 0.01, and
 *    rounding d <= 60 * 30 * 6e-8 / 1e-4 = 0.001). */
static double measured_order(int integrator, double rate_lo)
{
    acc_scene s = *acc_scene_find("oscillator");
    s.duration = 1.0;
    double x[3], y[3];
    for (int i = 0; i < 3; i++) {
        double rate = rate_lo * pow(2.0, i);
        acc_result r;
        assert_ok(acc_run(&s, integrator, 1.0 / rate, NULL, NULL, &r));
        assert_true(r.finite);
        x[i] = log(1.0 / rate);
        y[i] = log(r.error);
    }
    return (y[0] - y[2]) / (x[0] - x[2]);
}

static void check_order(int integrator, double rate_lo)
{
    double p = measured_order(integrator, rate_lo);
    print_message("  %s (%s, from %g Hz): measured order %.3f, theory %d\n",
                  acc_integrator_name[integrator], rg_real_size() == 8 ? "double" : "float",
                  rate_lo, p, acc_integrator_order[integrator]);
    assert_near(p, acc_integrator_order[integrator], 0.1);
}

#ifdef RG_DOUBLE
#define EULER_RATE 1000.0
#define RK4_RATE 50.0
#else
#define EULER_RATE 250.0
#define RK4_RATE 15.0
#endif

static void test_order_explicit_euler_is_1(void **state)
{
    (void)state;
    check_order(RG_INTEGRATOR_EXPLICIT_EULER, EULER_RATE);
}

static void test_order_semi_implicit_euler_is_1(void **state)
{
    (void)state;
    check_order(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, EULER_RATE);
}

static void test_order_verlet_is_2(void **state)
{
    (void)state;
    check_order(RG_INTEGRATOR_VELOCITY_VERLET, 50.0 * (rg_real_size() == 8 ? 2 : 1));
}

static void test_order_rk4_is_4(void **state)
{
    (void)state;
    /* in float over 15, 30, 60 Hz would reach rounding; use the ratio sqrt(2) instead */
    if (rg_real_size() == 8) {
        check_order(RG_INTEGRATOR_RK4, RK4_RATE);
        return;
    }
    acc_scene s = *acc_scene_find("oscillator");
    s.duration = 1.0;
    double x[3], y[3];
    for (int i = 0; i < 3; i++) {
        double rate = RK4_RATE * pow(2.0, 0.5 * i);
        acc_result r;
        assert_ok(acc_run(&s, RG_INTEGRATOR_RK4, 1.0 / rate, NULL, NULL, &r));
        x[i] = log(1.0 / rate);
        y[i] = log(r.error);
    }
    double p = (y[0] - y[2]) / (x[0] - x[2]);
    print_message("  rk4 (float, 15..30 Hz): measured order %.3f, theory 4\n", p);
    assert_near(p, 4, 0.1);
}

/* The lab's own scenes agree: every integrator's error falls as it should between 60 and
 * 240 Hz on the linear-drag projectile (no rest start, no stop: smooth all the way), i.e.
 * a 4x smaller step divides the error by about 4^p.  Double only: in float Verlet and RK4
 * are at rounding there (errors 1e-6 of a 13 m path). */
static void test_projectile_error_falls_as_4_to_the_p(void **state)
{
    (void)state;
    if (rg_real_size() != 8) {
        print_message("  skipped in float: Verlet and RK4 errors there are float rounding\n");
        return;
    }
    const acc_scene *s = acc_scene_find("projectile_linear_drag");
    for (int ig = 0; ig < ACC_INTEGRATORS; ig++) {
        acc_result a, b;
        assert_ok(acc_run(s, ig, 1.0 / 60, NULL, NULL, &a));
        assert_ok(acc_run(s, ig, 1.0 / 240, NULL, NULL, &b));
        double p = log(a.error / b.error) / log(4.0);
        /* tau = 2 s: h/tau <= 1/120, so r(h) < 0.01 and the slope is off by < 0.02 */
        assert_near(p, acc_integrator_order[ig], 0.1);
    }
}

/* ---------------------------------------------------------------- stability */

/* Bisection on omega*dt for the largest step at which the undamped oscillator's energy stays
 * within B = 1e4 of its start over N = 2000 steps.  How far the finite test can sit from the
 * asymptotic boundary z*, in theory:
 *  - semi-implicit Euler, Verlet (z* = 2): below it the energy is bounded, by
 *    (1 + z/2)/(1 - z/2) resp. 1; that stays under B up to z = 2 (B - 1)/(B + 1) = 2 (1 - 2e-4).
 *    Past it |l| = (z^2 - 2 + z sqrt(z^2 - 4))/2 >= 1 + sqrt(z - 2) roughly, so at 2 (1 + 1e-4)
 *    the energy grows by e^(2 N sqrt(2e-4)) = e^57 >> B.
 *  - RK4 (z* = 2 sqrt 2): below it |R(iz)| <= 1; past it by d (relative)
 *    |R|^2 = 1 + z^6 (z^2 - 8) / 576 ~ 1 + 14 d, so E_N/E_0 = e^(14 d N) passes B when
 *    d > ln(B) / (14 N) = 3.3e-4.
 *  So the bisection must land within 0.04% of z*, well inside the required 1%.
 *  - explicit Euler has no boundary: E_N/E_0 = (1 + z^2)^N exactly, so the finite test finds
 *    z = sqrt(B^(1/N) - 1) = 0.068 and that goes to 0 as N grows: unstable for every z > 0. */
#define STAB_N 2000
#define STAB_B 1e4

static double boundary(int integrator)
{
    return acc_oscillator_z(acc_stability_boundary(integrator, STAB_N, STAB_B, 0, 4, 32));
}

static void test_stability_boundary_semi_implicit_euler_is_2(void **state)
{
    (void)state;
    assert_near(boundary(RG_INTEGRATOR_SEMI_IMPLICIT_EULER), 2.0, 0.01 * 2.0);
}

static void test_stability_boundary_verlet_is_2(void **state)
{
    (void)state;
    assert_near(boundary(RG_INTEGRATOR_VELOCITY_VERLET), 2.0, 0.01 * 2.0);
}

static void test_stability_boundary_rk4_is_2_sqrt_2(void **state)
{
    (void)state;
    assert_near(boundary(RG_INTEGRATOR_RK4), 2 * sqrt(2.0), 0.01 * 2 * sqrt(2.0));
}

static void test_explicit_euler_has_no_stable_step(void **state)
{
    (void)state;
    double zb = boundary(RG_INTEGRATOR_EXPLICIT_EULER);
    double theory = sqrt(pow(STAB_B, 1.0 / STAB_N) - 1);
    assert_near(zb, theory, 0.01 * theory);
    /* and a ten times longer horizon finds a sqrt(10) times smaller "boundary": none */
    double zb10 = acc_oscillator_z(
        acc_stability_boundary(RG_INTEGRATOR_EXPLICIT_EULER, 10 * STAB_N, STAB_B, 0, 4, 32));
    double theory10 = sqrt(pow(STAB_B, 1.0 / (10 * STAB_N)) - 1);
    assert_near(zb10, theory10, 0.01 * theory10);
    assert_true(zb10 < zb / 3);
}

/* ---------------------------------------------------------------- energy: the failure and the remedy */

/* The 1 Hz spring at 60 Hz (z = 2 pi / 60) for 10 s = 600 steps.  Explicit Euler's energy is
 * multiplied by exactly (1 + z^2)^600 = 695; the remedies hold it: semi-implicit Euler within
 * [1/(1 + z/2), 1/(1 - z/2)] (it conserves x^2 + u^2 - z x u, u = v/omega), Verlet within
 * [1 - z^2/4, 1] (it conserves (1 - z^2/4) x^2 + u^2), RK4 loses (1 - z^6/72 + z^8/576)^600.
 * Tolerance: 600 steps * 64 eps relative (see the top of the file). */
typedef struct energy_track {
    double e0, lo, hi, last;
} energy_track;

static void track_energy(void *user, double t, const double num[4], const double exact[4])
{
    (void)t;
    (void)exact;
    energy_track *e = user;
    const acc_scene *s = acc_scene_find("oscillator");
    double r = acc_energy(s, num) / e->e0;
    if (r < e->lo) e->lo = r;
    if (r > e->hi) e->hi = r;
    e->last = r;
}

static energy_track energy_at_60hz(int integrator)
{
    const acc_scene *s = acc_scene_find("oscillator");
    double st[4];
    acc_exact(s, 0, st);
    energy_track e = {acc_energy(s, st), 1, 1, 1};
    acc_result r;
    assert_ok(acc_run(s, integrator, 1.0 / 60, track_energy, &e, &r));
    assert_int_equal(r.steps, 600);
    return e;
}

static void test_explicit_euler_energy_grows_the_others_hold_it(void **state)
{
    (void)state;
    const acc_scene *s = acc_scene_find("oscillator");
    /* z as the library sees it: k and dt rounded to rg_real */
    double h = (double)(rg_real)(1.0 / 60), z = sqrt((double)(rg_real)s->k) * h;
    double tol = 600 * 64 * REAL_EPS;
    energy_track ee = energy_at_60hz(RG_INTEGRATOR_EXPLICIT_EULER);
    double growth = pow(1 + z * z, 600);
    print_message("  explicit Euler: E/E0 after 10 s at 60 Hz = %.1f (theory %.1f)\n", ee.last, growth);
    assert_near(ee.last / growth, 1, tol);
    assert_true(ee.last > 600);

    energy_track si = energy_at_60hz(RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
    assert_true(si.lo >= 1 / (1 + z / 2) - tol && si.hi <= 1 / (1 - z / 2) + tol);
    energy_track vv = energy_at_60hz(RG_INTEGRATOR_VELOCITY_VERLET);
    assert_true(vv.lo >= 1 - z * z / 4 - tol && vv.hi <= 1 + tol);
    energy_track rk = energy_at_60hz(RG_INTEGRATOR_RK4);
    assert_near(rk.last / pow(1 - pow(z, 6) / 72 + pow(z, 8) / 576, 600), 1, tol);
}

/* ---------------------------------------------------------------- dissipation: overshoot and remedy */

/* Naive explicit friction v' = v - mu N dt/m sign(v) reverses v exactly when
 * r = mu N dt / (m |v|) > 1; the library never reverses: for r >= 1 the body stops at exactly
 * 0 and stays there, for r < 1 every integrator gives v (1 - r) (constant deceleration, which
 * all four integrate exactly while v keeps its sign).  Tolerance: a few roundings of v. */
static void test_friction_naive_overshoots_library_stops_at_zero(void **state)
{
    (void)state;
    const double dt = 1.0 / 60, m = 2.0, v = 1.5;
    const double rs[] = {0.25, 0.9, 1.01, 2.0, 10.0};
    for (size_t k = 0; k < sizeof rs / sizeof rs[0]; k++) {
        double r = rs[k], fric = r * m * v / dt; /* mu*N */
        double naive = acc_naive_friction_step(v, fric / m, dt);
        assert_true(r > 1 ? naive < 0 : naive > 0); /* flips exactly past r = 1 */
        for (int ig = 0; ig < ACC_INTEGRATORS; ig++) {
            double out[12];
            assert_ok(acc_library_dissipation(ig, m, v, fric, 0, 0, dt, 12, out));
            if (r >= 1) {
                for (int i = 0; i < 12; i++) assert_true(out[i] == 0.0); /* exactly, forever */
            } else {
                assert_near(out[0], v * (1 - r), 16 * REAL_EPS * v);
                for (int i = 0; i < 12; i++) assert_true(out[i] >= 0.0); /* ends at 0, never below */
                assert_true(out[11] == 0.0);
            }
        }
    }
}

/* Naive explicit quadratic drag v' = v (1 - r), r = quad |v| dt / m, reverses v for r > 1 and
 * for r > 2 diverges (|1 - r| > 1 and r grows with |v|).  The library treats such a step by
 * backward Euler: s + r s^2 / |v| = |v|, s = 2 |v| / (1 + sqrt(1 + 4 r)), always in (0, |v|),
 * and after it r is smaller, so the velocity falls monotonically and never flips.  Linear
 * drag likewise: naive v (1 - c dt/m), library v / (1 + c dt/m) when c dt/m > 1. */
static void test_drag_naive_overshoots_library_never_reverses(void **state)
{
    (void)state;
    const double dt = 1.0 / 30, m = 1.0, v = 4.0, r = 3.0;
    double quad = r * m / (v * dt);
    double vn = v;
    for (int i = 0; i < 3; i++) vn = acc_naive_drag_step(vn, 0, quad / m, dt);
    assert_true(fabs(vn) > 10 * v); /* -2v, then 10v, then -... : diverged */
    assert_true(acc_naive_drag_step(v, 0, quad / m, dt) < 0);
    for (int ig = 0; ig < ACC_INTEGRATORS; ig++) {
        double out[20];
        assert_ok(acc_library_dissipation(ig, m, v, 0, 0, quad, dt, 20, out));
        assert_near(out[0], 2 * v / (1 + sqrt(1 + 4 * r)), 16 * REAL_EPS * v);
        double prev = v;
        for (int i = 0; i < 20; i++) {
            assert_true(out[i] > 0 && out[i] < prev);
            prev = out[i];
        }
    }
    /* linear drag with c dt/m = 2: naive flips to -v, library gives v/3 */
    double lin = 2 * m / dt;
    assert_near(acc_naive_drag_step(v, lin / m, 0, dt), -v, 16 * REAL_EPS * v);
    for (int ig = 0; ig < ACC_INTEGRATORS; ig++) {
        double out[1];
        assert_ok(acc_library_dissipation(ig, m, v, 0, lin, 0, dt, 1, out));
        assert_near(out[0], v / 3, 16 * REAL_EPS * v);
    }
}

/* ---------------------------------------------------------------- frame rate */

/* A 5 m/s jump under g = 9.81.  Semi-implicit Euler stepped once per frame with h = the
 * frame time reaches y_n = n h v0 - g h^2 n (n + 1) / 2, whose maximum over whole n is the
 * apex: it depends on h (about v0^2/(2g) - v0 h / 2), so 30 and 144 Hz displays give jumps
 * 6 cm apart.  Through rg_world_advance at a fixed 1/60 s, every frame pattern gives
 * bit-identical states and the same apex as plain 60 Hz stepping.  Tolerance for the
 * closed form: ~100 steps of rounding on values ~1 m: 100 * 16 eps. */
static double sie_apex(double h, double v0, double g)
{
    double best = 0;
    for (int n = 1; n < 100000; n++) {
        double y = n * h * v0 - g * h * h * n * (n + 1) / 2;
        if (y < best) break;
        best = y;
    }
    return best;
}

static void fill(double *f, int n, double value)
{
    for (int i = 0; i < n; i++) f[i] = value;
}

static void test_jump_height_depends_on_frame_rate_unless_accumulated(void **state)
{
    (void)state;
    enum { N = 600 };
    static double frames[N];
    const double v0 = 5, g = 9.81;
    const int sie = RG_INTEGRATOR_SEMI_IMPLICIT_EULER;
    const double rates[] = {30, 60, 144};
    double naive[3];
    for (int i = 0; i < 3; i++) {
        fill(frames, N, 1.0 / rates[i]);
        naive[i] = acc_jump_naive(sie, frames, N, v0, g);
        double h = (double)(rg_real)(1.0 / rates[i]);
        assert_near(naive[i], sie_apex(h, v0, (double)(rg_real)g), 100 * 16 * REAL_EPS);
    }
    print_message("  naive per-frame apex: %.4f m at 30 Hz, %.4f m at 60 Hz, %.4f m at 144 Hz\n",
                  naive[0], naive[1], naive[2]);
    assert_true(naive[2] - naive[0] > 0.05);

    /* the accumulator: steady 30 Hz, steady 144 Hz, and jittered frames 1/144..1/30 s */
    fill(frames, N, 1.0 / 30);
    int same = 0;
    long steps = 0;
    double ref = acc_jump_fixed(sie, 1.0 / 60, frames, N, v0, g, &same, &steps);
    assert_true(same);
    assert_true(memcmp(&ref, &naive[1], sizeof ref) == 0); /* = plain 60 Hz stepping */
    fill(frames, N, 1.0 / 144);
    double a144 = acc_jump_fixed(sie, 1.0 / 60, frames, N, v0, g, &same, &steps);
    assert_true(same);
    assert_true(memcmp(&ref, &a144, sizeof ref) == 0);
    unsigned long long x = 12345;
    for (int i = 0; i < N; i++) {
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        frames[i] = 1.0 / 144 + (double)(x >> 11) / 9007199254740992.0 * (1.0 / 30 - 1.0 / 144);
    }
    double jit = acc_jump_fixed(sie, 1.0 / 60, frames, N, v0, g, &same, &steps);
    assert_true(same);
    assert_true(memcmp(&ref, &jit, sizeof ref) == 0);
}

/* ---------------------------------------------------------------- drag from rest */

/* Found by this lab and fixed in b8d5b08: a body with drag that started a step at rest took
 * the implicit-dissipation fallback meant for static friction, whose position update
 * x0 + h v1 is first order, so Verlet and RK4 fell g h^2 instead of g h^2 / 2 on that step
 * and the fall-from-rest scene converged at order 2, not 4.  Kept as a regression test. */
static void test_drag_from_rest_keeps_order(void **state)
{
    (void)state;
    rg_world *w = NULL;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_gravity(w, v2(0, -9.81)));
    assert_ok(rg_world_set_integrator(w, RG_INTEGRATOR_RK4));
    rg_body b = make_body(w, 1, 0, 0);
    assert_ok(rg_body_set_drag(w, b, 0, 1e-9));
    double h = (double)(rg_real)(1.0 / 60);
    assert_ok(rg_world_step(w, (rg_real)h));
    double y = (double)pos_of(w, b).y, g = (double)(rg_real)9.81;
    rg_world_destroy(w);
    /* the drag decelerates by at most quad (g h)^2 / m over the step, moving the body by at
     * most quad (g h)^2 h^2 / m = 3.7e-15 m: the exact g h^2/2 within that and rounding */
    assert_near(y, -g * h * h / 2, 64 * REAL_EPS * g * h * h + 1e-9 * (g * h) * (g * h) * h * h);
}

#ifdef ACC_COLLISION
/* ---------------------------------------------------------------- tunnelling */

/* A 10 cm ball (r = 0.05 m) against a 1 cm wall at 60 Hz, N = 64 start phases (i + 1/2)/N.
 * A discrete check sees the ball only at x0 + n v dt.  The lab's naive check catches it when
 * a sample overlaps the wall, an interval of length L = wall + 2r = 0.11 m, so a share
 * max(0, 1 - L / (v dt)) of the phases tunnels.  The library's discrete check (continuous
 * off) can catch no more than the overlapping samples, and always catches one whose centre
 * is in the wall's near half (length L/2; past the middle the contact may push the ball out
 * of the far face), so its share lies between 1 - L/(v dt) and 1 - L/(2 v dt).  Counting N
 * equally spaced phases in an interval misses its share by at most 1/N.  With continuous
 * collision: none, for every phase and integrator. */
#define PHASES 64

static double tunnel_fraction(int method, int integrator, double speed)
{
    int n = 0;
    for (int i = 0; i < PHASES; i++) {
        acc_wall s = {0.05, 0.01, speed, 1.0 / 60, (i + 0.5) / PHASES};
        int t = method == 0 ? acc_tunnel_naive(&s) : acc_tunnel_library(integrator, method == 2, &s);
        assert_true(t >= 0);
        n += t;
    }
    return (double)n / PHASES;
}

static void test_thin_wall_tunnels_without_continuous_collision_never_with_it(void **state)
{
    (void)state;
    const double vdt = 300.0 / 60, L = 0.01 + 2 * 0.05;
    double naive = tunnel_fraction(0, 0, 300), discrete = tunnel_fraction(1, RG_INTEGRATOR_SEMI_IMPLICIT_EULER, 300);
    print_message("  300 m/s at 60 Hz: tunnels %.1f%% (lab naive), %.1f%% (library discrete)\n",
                  100 * naive, 100 * discrete);
    assert_near(naive, 1 - L / vdt, 1.0 / PHASES);
    assert_true(discrete >= 1 - L / vdt - 1.0 / PHASES && discrete <= 1 - L / (2 * vdt) + 1.0 / PHASES);
    for (int ig = 0; ig < ACC_INTEGRATORS; ig++) assert_true(tunnel_fraction(2, ig, 300) == 0);
    /* slow enough that v dt < L/2: even the discrete check always catches it */
    assert_true(tunnel_fraction(1, RG_INTEGRATOR_SEMI_IMPLICIT_EULER, 3.0) == 0);
    assert_true(tunnel_fraction(0, 0, 3.0) == 0);
}

/* ---------------------------------------------------------------- pile */

/* Five 1 m boxes, masses 1, 3.2, 10, 32, 100 kg from the bottom up, started at rest in
 * contact: the exact solution is that nothing moves.  What the physics requires whatever
 * the solver: the pile stands (no box sinks half a box into the one below, which would be
 * a pass-through), the state stays finite, and the scene is symmetric about x = 0 with
 * vertical normals, so no tangential impulse arises and x stays 0 up to rounding.
 * With the default solver settings each of the five resting contacts (ground and four
 * box-box) may sit up to the contact slop deep (5 mm, rg_world_get_contact_tuning), so no
 * box may move more than 5 slops; 64 iterations must do no worse.  (This pile used to pass
 * through itself at the default iterations; the shock-propagation pass fixed that.) */
static void test_pile_with_mass_ratio_100_stands(void **state)
{
    (void)state;
    for (int ig = 0; ig < ACC_INTEGRATORS; ig++) {
        acc_pile_result p, q;
        assert_ok(acc_pile(ig, 1.0 / 60, 100, 5, 5.0, 0, &p));
        assert_true(p.finite);
        assert_true(p.max_drift <= 64 * REAL_EPS);
        print_message("  %s, default iterations: largest sink %.4f m\n", acc_integrator_name[ig], p.max_err);
        assert_true(p.max_err <= 5 * 0.005);
        assert_ok(acc_pile(ig, 1.0 / 60, 100, 5, 5.0, 64, &q));
        print_message("  %s, 64 iterations: largest sink %.4f m\n", acc_integrator_name[ig], q.max_err);
        assert_true(q.finite);
        assert_true(q.max_err <= 5 * 0.005);
        assert_true(q.max_drift <= 64 * REAL_EPS);
    }
}
#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_order_explicit_euler_is_1),
        cmocka_unit_test(test_order_semi_implicit_euler_is_1),
        cmocka_unit_test(test_order_verlet_is_2),
        cmocka_unit_test(test_order_rk4_is_4),
        cmocka_unit_test(test_projectile_error_falls_as_4_to_the_p),
        cmocka_unit_test(test_stability_boundary_semi_implicit_euler_is_2),
        cmocka_unit_test(test_stability_boundary_verlet_is_2),
        cmocka_unit_test(test_stability_boundary_rk4_is_2_sqrt_2),
        cmocka_unit_test(test_explicit_euler_has_no_stable_step),
        cmocka_unit_test(test_explicit_euler_energy_grows_the_others_hold_it),
        cmocka_unit_test(test_friction_naive_overshoots_library_stops_at_zero),
        cmocka_unit_test(test_drag_naive_overshoots_library_never_reverses),
        cmocka_unit_test(test_jump_height_depends_on_frame_rate_unless_accumulated),
        cmocka_unit_test(test_drag_from_rest_keeps_order),
#ifdef ACC_COLLISION
        cmocka_unit_test(test_thin_wall_tunnels_without_continuous_collision_never_with_it),
        cmocka_unit_test(test_pile_with_mass_ratio_100_stands),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
