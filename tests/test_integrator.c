/* test_integrator.c: the four integrators on the undamped oscillator, against theory.
 *
 * The oscillator is a unit mass on a zero-length spring of stiffness k = omega^2 tied to the
 * origin (F = -k x exactly), released from rest at x = A.  z = omega * dt.  Energy
 * E = (v^2 + omega^2 x^2) / 2.  In exact arithmetic:
 *   explicit Euler         E_{n+1} = (1 + z^2) E_n                    (grows for every z > 0)
 *   semi-implicit Euler    E/E0 in [1/(1 + z/2), 1/(1 - z/2)]          for z < 2, blows up beyond
 *   velocity Verlet        E/E0 in [1 - z^2/4, 1]                       for z < 2, blows up beyond
 *   RK4                    E_{n+1} = (1 - z^6/72 + z^8/576) E_n        (|R(iz)|^2), stable to 2*sqrt(2)
 * Rounding: one step does at most ~10 roundings of relative size eps/2 on quantities no
 * larger than the energy norm times (1 + z + z^2) <= 13 for z <= 3, so one step perturbs
 * E/E0 by at most ROUND_PER_STEP = 64 eps relative; n steps by n times that.
 *
 * Where the energy grows, the oscillator starts at A = GROW_A = 1e-12 m instead of 1 m: the
 * step's range guard stops a body beyond RG_MAX_SPEED (rg_world_get_stopped), and the fastest
 * growth here (RK4 at z = 3.2: 5.2x energy per step over 40 steps, a speed of
 * omega A 5.2^20 = 320 * 1e-12 * 2e14 = 7e4 m/s) stays inside it.  Rounding is relative,
 * so no ratio depends on A (and no value comes near the float's smallest normal). */
#include "testutil.h"

#define ROUND_PER_STEP (64.0 * REAL_EPS)
#define GROW_A 1e-12

typedef struct osc {
    rg_world *w;
    rg_body b;
    double omega;
} osc;

static osc osc_make(int integrator, double omega, double amplitude)
{
    osc o;
    uint64_t s = 0;
    o.omega = omega;
    assert_ok(rg_world_create(&o.w));
    assert_ok(rg_world_set_integrator(o.w, integrator));
    o.b = make_body(o.w, 1.0, amplitude, 0.0);
    assert_ok(rg_spring_create(o.w, o.b, 0, v2(0, 0), 0, (rg_real)(omega * omega), 0, &s));
    return o;
}

static double osc_energy(const osc *o)
{
    rg_vec2 p = pos_of(o->w, o->b), v = vel_of(o->w, o->b);
    double x = (double)p.x, y = (double)p.y, vx = (double)v.x, vy = (double)v.y;
    return 0.5 * (vx * vx + vy * vy) + 0.5 * o->omega * o->omega * (x * x + y * y);
}

/* Steps per period 2*pi/z, at least 20 steps: long enough to visit the extremes. */
static int steps_for(double z) { int n = (int)ceil(2.5 * 6.283185307179586 / z); return n < 20 ? 20 : n; }

static void test_explicit_euler_multiplies_energy_by_one_plus_z_squared(void **state)
{
    (void)state;
    const double zs[] = { 0.05, 0.2, 0.5, 1.0 };
    for (size_t k = 0; k < sizeof zs / sizeof zs[0]; k++) {
        double z = zs[k], dt = 0.01, omega = z / dt;
        osc o = osc_make(RG_INTEGRATOR_EXPLICIT_EULER, omega, GROW_A);
        double e0 = osc_energy(&o), expect = e0;
        for (int n = 1; n <= 60; n++) {
            assert_ok(rg_world_step(o.w, (rg_real)dt));
            expect *= 1 + z * z;
            double e = osc_energy(&o);
            assert_near(e / expect, 1.0, n * ROUND_PER_STEP);
        }
        rg_world_destroy(o.w);
    }
}

static void check_bounded(int integrator, double z, double lo, double hi)
{
    double dt = 0.01;
    osc o = osc_make(integrator, z / dt, 1.0);
    double e0 = osc_energy(&o), min = 1, max = 1;
    int n = steps_for(z);
    for (int i = 1; i <= n; i++) {
        assert_ok(rg_world_step(o.w, (rg_real)dt));
        double r = osc_energy(&o) / e0, slack = i * ROUND_PER_STEP;
        if (r < lo - slack || r > hi + slack)
            fail_msg("integrator %d, z = %g, step %d: E/E0 = %.9g outside [%.9g, %.9g]", integrator, z, i, r, lo, hi);
        if (r < min) min = r;
        if (r > max) max = r;
    }
    /* The bounds are reached: the energy really swings across most of the band (for z
     * large enough that the band is wider than rounding), so the test can fail both ways. */
    if (hi - lo > 1e-3) assert_true(max - min > 0.5 * (hi - lo));
    rg_world_destroy(o.w);
}

static void check_blows_up(int integrator, double z)
{
    double dt = 0.01;
    osc o = osc_make(integrator, z / dt, GROW_A);
    double e0 = osc_energy(&o);
    const int n = 20; /* few enough that the state stays far from overflow */
    for (int i = 0; i < n; i++) assert_ok(rg_world_step(o.w, (rg_real)dt));
    /* Beyond z = 2 the step map of both methods has trace 2 - z^2 and determinant 1, so a
     * real eigenvalue of modulus lambda = (z^2 - 2 + sqrt((z^2 - 2)^2 - 4)) / 2 > 1.  The
     * energy grows like lambda^(2n) times the squared share of the release state in that
     * mode; that share is O(1) here, and 1e-4 of it is a safe floor. */
    double c = z * z - 2, lambda = (c + sqrt(c * c - 4)) / 2;
    assert_true(osc_energy(&o) / e0 > 1e-4 * pow(lambda, 2 * n));
    rg_world_destroy(o.w);
}

static void test_semi_implicit_euler_energy_stays_in_band_below_two(void **state)
{
    (void)state;
    const double zs[] = { 0.1, 0.5, 1.0, 1.5, 1.9 };
    for (size_t k = 0; k < sizeof zs / sizeof zs[0]; k++)
        check_bounded(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, zs[k], 1 / (1 + zs[k] / 2), 1 / (1 - zs[k] / 2));
}

static void test_semi_implicit_euler_blows_up_beyond_two(void **state)
{
    (void)state;
    check_blows_up(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, 2.1);
    check_blows_up(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, 2.5);
}

static void test_verlet_energy_stays_in_band_below_two(void **state)
{
    (void)state;
    const double zs[] = { 0.1, 0.5, 1.0, 1.5, 1.9 };
    for (size_t k = 0; k < sizeof zs / sizeof zs[0]; k++)
        check_bounded(RG_INTEGRATOR_VELOCITY_VERLET, zs[k], 1 - zs[k] * zs[k] / 4, 1.0);
}

static void test_verlet_blows_up_beyond_two(void **state)
{
    (void)state;
    check_blows_up(RG_INTEGRATOR_VELOCITY_VERLET, 2.1);
    check_blows_up(RG_INTEGRATOR_VELOCITY_VERLET, 2.5);
}

static void test_rk4_energy_factor_matches_stability_polynomial(void **state)
{
    (void)state;
    const double zs[] = { 0.5, 1.0, 2.0, 2.8, 2.9, 3.2 };
    for (size_t k = 0; k < sizeof zs / sizeof zs[0]; k++) {
        double z = zs[k], dt = 0.01;
        double factor = 1 - pow(z, 6) / 72 + pow(z, 8) / 576;
        osc o = osc_make(RG_INTEGRATOR_RK4, z / dt, GROW_A);
        double e0 = osc_energy(&o), expect = e0;
        for (int n = 1; n <= 40; n++) {
            assert_ok(rg_world_step(o.w, (rg_real)dt));
            expect *= factor;
            assert_near(osc_energy(&o) / expect, 1.0, n * ROUND_PER_STEP);
        }
        /* Below 2*sqrt(2) = 2.828 the energy decays; above it grows. */
        if (z < 2 * sqrt(2.0)) assert_true(osc_energy(&o) < e0);
        else assert_true(osc_energy(&o) > e0);
        rg_world_destroy(o.w);
    }
}

static void test_kinematic_body_moves_by_velocity_only(void **state)
{
    (void)state;
    rg_world *w;
    rg_body k;
    uint64_t s;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_gravity(w, v2(0, -10)));
    assert_ok(rg_world_set_wind(w, v2(5, 5)));
    for (int integ = 0; integ <= 3; integ++) {
        assert_ok(rg_world_set_integrator(w, integ));
        assert_ok(rg_body_create(w, RG_BODY_KINEMATIC, 0, v2(0, 0), &k));
        assert_ok(rg_body_set_velocity(w, k, v2(2, -1)));
        assert_ok(rg_spring_create(w, k, 0, v2(5, 5), 0, 100, 1, &s)); /* cannot pull it */
        for (int i = 0; i < 10; i++) assert_ok(rg_world_step(w, (rg_real)0.1));
        rg_vec2 p = pos_of(w, k), v = vel_of(w, k);
        assert_near(p.x, 2.0, 10 * 4 * REAL_EPS * 2);
        assert_near(p.y, -1.0, 10 * 4 * REAL_EPS * 2);
        assert_true(v.x == 2 && v.y == -1);
        assert_ok(rg_body_destroy(w, k));
    }
    rg_world_destroy(w);
}

static void test_static_body_never_moves(void **state)
{
    (void)state;
    rg_world *w;
    rg_body s, d;
    uint64_t sp;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_gravity(w, v2(0, -10)));
    assert_ok(rg_body_create(w, RG_BODY_STATIC, 0, v2(1, 2), &s));
    d = make_body(w, 1, 0, 0);
    assert_ok(rg_spring_create(w, d, s, v2(0, 0), 1, 50, 0.5, &sp));
    for (int integ = 0; integ <= 3; integ++) {
        assert_ok(rg_world_set_integrator(w, integ));
        for (int i = 0; i < 30; i++) assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
    }
    rg_vec2 p = pos_of(w, s);
    assert_true(p.x == 1 && p.y == 2);
    rg_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_explicit_euler_multiplies_energy_by_one_plus_z_squared),
        cmocka_unit_test(test_semi_implicit_euler_energy_stays_in_band_below_two),
        cmocka_unit_test(test_semi_implicit_euler_blows_up_beyond_two),
        cmocka_unit_test(test_verlet_energy_stays_in_band_below_two),
        cmocka_unit_test(test_verlet_blows_up_beyond_two),
        cmocka_unit_test(test_rk4_energy_factor_matches_stability_polynomial),
        cmocka_unit_test(test_kinematic_body_moves_by_velocity_only),
        cmocka_unit_test(test_static_body_never_moves),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
