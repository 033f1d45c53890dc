/* test_force.c: every force generator against its closed form, and the overshoot of the
 * naive explicit dissipation that the library's non-reversing treatment removes. */
#include "testutil.h"

static rg_world *world_with(int integrator, double gx, double gy)
{
    rg_world *w;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_integrator(w, integrator));
    assert_ok(rg_world_set_gravity(w, v2(gx, gy)));
    return w;
}

static double speed_of(rg_world *w, rg_body b)
{
    rg_vec2 v = vel_of(w, b);
    return hypot((double)v.x, (double)v.y);
}

/* v' = g - c v|v| / m has the fixed point vt = sqrt(m g / c), and every integrator's step
 * maps vt to itself (all stage derivatives vanish there).  From rest, the distance to vt
 * shrinks by at least (1 - c vt dt / m) per step (the linearisation 1 - 2 c vt dt/m, and the
 * curve above it), so after n steps it is below vt * (1 - c vt dt/m)^n.  In floating point
 * the iteration stalls once a step's increment |a| dt ~ 2 g |vt - v| dt / vt drops below
 * half an ulp of v (<= eps v / 2): within eps vt^2 / (4 g dt) of vt; rounding of the
 * force adds a few eps vt. */
static void test_quadratic_drag_reaches_terminal_speed(void **state)
{
    (void)state;
    const double m = 2, g = 9.81, c = 0.1, dt = 1.0 / 60, vt = sqrt(m * g / c);
    const int n = 1800;
    for (int integ = 0; integ <= 3; integ++) {
        rg_world *w = world_with(integ, 0, -g);
        rg_body b = make_body(w, m, 0, 1000);
        assert_ok(rg_body_set_drag(w, b, 0, (rg_real)c));
        for (int i = 0; i < n; i++) assert_ok(rg_world_step(w, (rg_real)dt));
        rg_vec2 v = vel_of(w, b);
        double tol = vt * pow(1 - c * vt * dt / m, n) + REAL_EPS * vt * vt / (4 * g * dt) + 8 * REAL_EPS * vt;
        assert_near(-v.y, vt, tol);
        assert_near(v.x, 0, 0);
        rg_world_destroy(w);
    }
}

/* Linear drag c with gravity: tau = m/c,
 *   x = v0x tau (1 - e^(-t/tau)),  y = (v0y + g tau) tau (1 - e^(-t/tau)) - g tau t.
 * RK4 on this linear ODE truncates the exponential after h^4: its local error is
 * h^5 y^(5) / 120, which is q^5 (v + g tau) / 120 for v and q^5 tau (v + g tau) / 120 for x
 * (q = h/tau, since v^(k) = (-1/tau)^(k-1) (v + g tau)).  A velocity error feeds x through
 * at most tau, and errors never grow (the transient decays), so after n steps
 * |x error| <= n q^5 / 120 * S with S = 2 tau (|v0| + g tau); rounding adds ~8 n eps S. */
static void test_linear_drag_projectile_matches_closed_form(void **state)
{
    (void)state;
    const double m = 1.5, c = 0.75, g = 9.81, v0x = 12, v0y = 20, dt = 1.0 / 60, tau = m / c;
    const int n = 240;
    rg_world *w = world_with(RG_INTEGRATOR_RK4, 0, -g);
    rg_body b = make_body(w, m, 0, 0);
    assert_ok(rg_body_set_velocity(w, b, v2(v0x, v0y)));
    assert_ok(rg_body_set_drag(w, b, (rg_real)c, 0));
    const double q = dt / tau, S = 2 * tau * (hypot(v0x, v0y) + g * tau);
    for (int i = 1; i <= n; i++) {
        assert_ok(rg_world_step(w, (rg_real)dt));
        double t = i * dt, e = 1 - exp(-t / tau);
        double x = v0x * tau * e, y = (v0y + g * tau) * tau * e - g * tau * t;
        double tol = i * (pow(q, 5) / 120 + 8 * REAL_EPS) * S;
        rg_vec2 p = pos_of(w, b);
        assert_near(p.x, x, tol);
        assert_near(p.y, y, tol);
    }
    rg_world_destroy(w);
}

/* Surface friction a = mu N / m stops a body from v0 after v0^2/(2a).  The discrete stop
 * differs from the continuous one by less than one step of travel, v0 dt; the last step
 * lands on exactly zero speed and later steps keep it there. */
static void test_friction_stops_within_one_step_and_stays_at_exact_zero(void **state)
{
    (void)state;
    const double m = 2, mu = 0.5, N = m * 9.81, v0 = 5, dt = 1.0 / 60;
    const double a = mu * N / m, d = v0 * v0 / (2 * a);
    for (int integ = 0; integ <= 3; integ++) {
        rg_world *w = world_with(integ, 0, 0);
        rg_body b = make_body(w, m, 0, 0);
        assert_ok(rg_body_set_velocity(w, b, v2(v0 * 0.6, v0 * 0.8)));
        assert_ok(rg_body_set_surface_friction(w, b, (rg_real)mu, (rg_real)N));
        int steps = 0;
        while (speed_of(w, b) > 0 && steps < 1000) {
            assert_ok(rg_world_step(w, (rg_real)dt));
            steps++;
        }
        rg_vec2 p = pos_of(w, b);
        assert_near(hypot((double)p.x, (double)p.y), d, v0 * dt);
        assert_near(steps * dt, v0 / a, dt);
        for (int i = 0; i < 60; i++) assert_ok(rg_world_step(w, (rg_real)dt));
        rg_vec2 v = vel_of(w, b), p2 = pos_of(w, b);
        assert_true(v.x == 0 && v.y == 0);
        assert_true(p2.x == p.x && p2.y == p.y);
        rg_world_destroy(w);
    }
}

/* Static friction: a resting body with mu N = 10 N does not move under a 6 N push, and
 * under 14 N it accelerates at (14 - 10)/m. */
static void test_friction_holds_a_resting_body_against_a_smaller_force(void **state)
{
    (void)state;
    const double m = 2, dt = 1.0 / 60;
    for (int integ = 0; integ <= 3; integ++) {
        rg_world *w = world_with(integ, 0, 0);
        rg_body b = make_body(w, m, 0, 0);
        assert_ok(rg_body_set_surface_friction(w, b, 1, 10));
        for (int i = 0; i < 30; i++) {
            assert_ok(rg_body_apply_force(w, b, v2(6, 0)));
            assert_ok(rg_world_step(w, (rg_real)dt));
        }
        rg_vec2 p = pos_of(w, b);
        assert_true(p.x == 0 && p.y == 0);
        for (int i = 0; i < 30; i++) {
            assert_ok(rg_body_apply_force(w, b, v2(14, 0)));
            assert_ok(rg_world_step(w, (rg_real)dt));
        }
        assert_near(vel_of(w, b).x, 30 * dt * (14 - 10) / m, 30 * 8 * REAL_EPS);
        rg_world_destroy(w);
    }
}

/* The seed's naive explicit update v -= (mu N / m) dt sign(v) reverses the velocity when
 * mu N dt / m > |v|; v -= c |v| v dt / m reverses it when c |v| dt / m > 1 (and grows it
 * past 2).  The library, at the same numbers, stops at exactly 0 / slows without turning. */
static void test_naive_dissipation_overshoots_where_the_library_does_not(void **state)
{
    (void)state;
    const double m = 1, dt = 0.1;
    /* friction: mu N dt / m = 0.8 > |v| = 0.3 */
    double v = 0.3, muN = 8;
    double naive = v - muN / m * dt * (v > 0 ? 1 : -1);
    assert_true(naive < 0); /* the failure: it now slides backwards */
    /* quadratic drag: c |v| dt / m = 3 > 1 */
    double c = 1.5, u = 20;
    double naive_u = u - c * fabs(u) * u * dt / m;
    assert_true(naive_u < 0 && fabs(naive_u) > u); /* reversed and faster: divergence */
    for (int integ = 0; integ <= 3; integ++) {
        rg_world *w = world_with(integ, 0, 0);
        rg_body f = make_body(w, m, 0, 0), d = make_body(w, m, 0, 5);
        assert_ok(rg_body_set_velocity(w, f, v2(v, 0)));
        assert_ok(rg_body_set_surface_friction(w, f, 1, (rg_real)muN));
        assert_ok(rg_body_set_velocity(w, d, v2(u, 0)));
        assert_ok(rg_body_set_drag(w, d, 0, (rg_real)c));
        double prev = u;
        for (int i = 0; i < 50; i++) {
            assert_ok(rg_world_step(w, (rg_real)dt));
            rg_vec2 vf = vel_of(w, f), vd = vel_of(w, d);
            assert_true(vf.x == 0 && vf.y == 0);
            assert_true(vd.x >= 0 && (double)vd.x <= prev); /* never turns, never speeds up */
            prev = (double)vd.x;
        }
        /* and it still decays like drag: backward Euler's s' = s/(1 + c s' dt/m) */
        assert_true(prev < u / 10);
        rg_world_destroy(w);
    }
}

/* A stiff step: the dissipation rate k (drag and friction per unit speed over the mass)
 * reaches 1/h.  Mass 1, drag (1000, 1000), dt 0.1: kh >= 100, where RK4's stages (factor
 * 1 - z + z^2/2 - z^3/6 + z^4/24 at z = 100) and explicit Euler's (1 - z) grow and turn a
 * velocity.  Every integrator takes the backward-Euler step there: from rest each step's
 * speed is below what free fall adds in one step (g dt), never upward, and it contracts by
 * 1 / (1 + kh) <= 1/101 per step to the terminal speed vt (1000 vt + 1000 vt^2 = m g), so
 * after 10 steps it is vt to rounding: a few ulps of vt from the quadratic's formula. */
static void test_stiff_drag_never_grows_or_turns_a_velocity(void **state)
{
    (void)state;
    const double g = 9.81, dt = 0.1, vt = (-1000 + sqrt(1e6 + 4 * 1000 * g)) / 2000;
    for (int integ = 0; integ <= 3; integ++) {
        rg_world *w = world_with(integ, 0, -g);
        rg_body b = make_body(w, 1, 0, 0);
        assert_ok(rg_body_set_drag(w, b, 1000, 1000));
        for (int k = 0; k < 10; k++) {
            assert_ok(rg_world_step(w, (rg_real)dt));
            rg_vec2 v = vel_of(w, b);
            if (!(speed_of(w, b) <= g * dt * (1 + 8 * REAL_EPS) && v.y <= 0 && v.x == 0))
                fail_msg("integrator %d step %d: v = (%g, %g), free fall adds %g", integ, k + 1,
                         (double)v.x, (double)v.y, g * dt);
        }
        assert_near(-vel_of(w, b).y, vt, 16 * REAL_EPS * vt);
        rg_world_destroy(w);
    }
}

/* Friction on a slow body under a perpendicular force: mu N h / m = 0.01 m/s takes more than
 * the whole speed 0.005 along x, but gravity keeps the new velocity pointing along v_free, so
 * the direction test alone would let the explicit step turn vx to -0.005.  kh = 2 >= 1 makes
 * the step implicit: v' is v_free shortened, so vx keeps its sign and never grows. */
static void test_friction_never_turns_a_velocity_that_a_perpendicular_force_keeps(void **state)
{
    (void)state;
    const double dt = 1.0 / 60, v0 = 0.005;
    for (int integ = 0; integ <= 3; integ++) {
        rg_world *w = world_with(integ, 0, -9.81);
        rg_body b = make_body(w, 1, 0, 0);
        assert_ok(rg_body_set_velocity(w, b, v2(v0, 0)));
        assert_ok(rg_body_set_surface_friction(w, b, 0.3f, 2));
        double prev = v0;
        for (int k = 0; k < 30; k++) {
            assert_ok(rg_world_step(w, (rg_real)dt));
            double vx = (double)vel_of(w, b).x;
            if (!(vx >= 0 && vx <= prev))
                fail_msg("integrator %d step %d: vx %g after %g", integ, k + 1, vx, prev);
            prev = vx;
        }
        rg_world_destroy(w);
    }
}

/* Wind is a force: a = wind / m, so a light body feels more.  Semi-implicit Euler from rest
 * under constant a: v_n = n a h, x_n = a h^2 n (n + 1) / 2. */
static void test_wind_is_a_force_shared_by_dynamic_bodies(void **state)
{
    (void)state;
    const double h = 1.0 / 60;
    const int n = 60;
    rg_world *w = world_with(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, 0, 0);
    assert_ok(rg_world_set_wind(w, v2(3, -1)));
    rg_body light = make_body(w, 1, 0, 0), heavy = make_body(w, 4, 0, 0);
    rg_body st;
    assert_ok(rg_body_create(w, RG_BODY_STATIC, 0, v2(0, 0), &st));
    for (int i = 0; i < n; i++) assert_ok(rg_world_step(w, (rg_real)h));
    const double masses[2] = { 1, 4 };
    rg_body bodies[2] = { light, heavy };
    for (int k = 0; k < 2; k++) {
        double ax = 3 / masses[k], ay = -1 / masses[k];
        rg_vec2 v = vel_of(w, bodies[k]), p = pos_of(w, bodies[k]);
        assert_near(v.x, n * ax * h, n * 4 * REAL_EPS);
        assert_near(v.y, n * ay * h, n * 4 * REAL_EPS);
        assert_near(p.x, ax * h * h * n * (n + 1) / 2, n * 4 * REAL_EPS);
        assert_near(p.y, ay * h * h * n * (n + 1) / 2, n * 4 * REAL_EPS);
    }
    rg_vec2 ps = pos_of(w, st);
    assert_true(ps.x == 0 && ps.y == 0);
    rg_world_destroy(w);
}

static void test_gravity_scale_multiplies_gravity(void **state)
{
    (void)state;
    const double h = 0.01, g = -10;
    const int n = 100;
    const double scales[] = { 0, 1, 2, -1 };
    rg_world *w = world_with(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, 0, g);
    rg_body b[4];
    for (int k = 0; k < 4; k++) {
        b[k] = make_body(w, 1 + k, 0, 0);
        assert_ok(rg_body_set_gravity_scale(w, b[k], (rg_real)scales[k]));
    }
    for (int i = 0; i < n; i++) assert_ok(rg_world_step(w, (rg_real)h));
    for (int k = 0; k < 4; k++)
        assert_near(vel_of(w, b[k]).y, scales[k] * g * n * h, n * 4 * REAL_EPS * 20);
    assert_true(pos_of(w, b[0]).y == 0);
    rg_world_destroy(w);
}

static void test_impulse_changes_momentum_at_once(void **state)
{
    (void)state;
    rg_world *w = world_with(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, 0, 0);
    rg_body b = make_body(w, 4, 1, 1), k;
    assert_ok(rg_body_create(w, RG_BODY_KINEMATIC, 0, v2(0, 0), &k));
    assert_ok(rg_body_apply_impulse(w, b, v2(2, -8)));
    rg_vec2 v = vel_of(w, b), p = pos_of(w, b);
    assert_true(v.x == (rg_real)0.5 && v.y == -2); /* J/m, before any step */
    assert_true(p.x == 1 && p.y == 1);
    assert_ok(rg_body_apply_impulse(w, k, v2(100, 100))); /* infinite mass: no effect */
    v = vel_of(w, k);
    assert_true(v.x == 0 && v.y == 0);
    rg_world_destroy(w);
}

/* An applied force holds for exactly one step: v = F/m h after it, unchanged after the next. */
static void test_applied_force_lasts_one_step(void **state)
{
    (void)state;
    for (int integ = 0; integ <= 3; integ++) {
        rg_world *w = world_with(integ, 0, 0);
        rg_body b = make_body(w, 2, 0, 0);
        assert_ok(rg_body_apply_force(w, b, v2(3, 0)));
        assert_ok(rg_body_apply_force(w, b, v2(1, 2))); /* forces add up */
        assert_ok(rg_world_step(w, (rg_real)0.5));
        rg_vec2 v1 = vel_of(w, b), a = { 0, 0 };
        assert_near(v1.x, 4.0 / 2 * 0.5, 4 * REAL_EPS);
        assert_near(v1.y, 2.0 / 2 * 0.5, 4 * REAL_EPS);
        assert_ok(rg_body_get_acceleration(w, b, &a)); /* a = sum(f)/m */
        assert_near(a.x, 2.0, 4 * REAL_EPS);
        assert_near(a.y, 1.0, 4 * REAL_EPS);
        assert_ok(rg_world_step(w, (rg_real)0.5));
        rg_vec2 v2_ = vel_of(w, b);
        assert_true(v2_.x == v1.x && v2_.y == v1.y);
        rg_world_destroy(w);
    }
}

static void test_speed_limits_snap_to_rest_and_clamp(void **state)
{
    (void)state;
    rg_world *w = world_with(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, 0, -10);
    rg_body slow = make_body(w, 1, 0, 0), fast = make_body(w, 1, 0, 0);
    assert_ok(rg_body_set_gravity_scale(w, slow, 0));
    assert_ok(rg_body_set_velocity(w, slow, v2(0.03, 0.04))); /* |v| = 0.05 */
    assert_ok(rg_body_set_speed_limits(w, slow, (rg_real)0.1, 0));
    assert_ok(rg_body_set_velocity(w, fast, v2(3, 0)));
    assert_ok(rg_body_set_speed_limits(w, fast, 0, 5));
    for (int i = 0; i < 120; i++) {
        assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
        assert_true(speed_of(w, fast) <= 5 * (1 + 4 * REAL_EPS));
    }
    rg_vec2 v = vel_of(w, slow);
    assert_true(v.x == 0 && v.y == 0);
    assert_near(speed_of(w, fast), 5, 5 * 4 * REAL_EPS);
    /* the clamp keeps the direction: vx/vy went from 3/0 toward gravity, never reversed */
    assert_true(vel_of(w, fast).x > 0 && vel_of(w, fast).y < 0);
    rg_world_destroy(w);
}

/* Two bodies on a spring: internal forces, so momentum stays zero (to rounding of
 * inv_mass * mass, 4 eps per step on each), and with no damping RK4 at small z keeps the
 * energy to its truncation (z^6/72 per step).  With damping the energy only falls. */
static void test_body_spring_conserves_momentum_and_damping_dissipates(void **state)
{
    (void)state;
    const double m1 = 1, m2 = 3, k = 40, L = 1, dt = 0.005;
    const int n = 2000;
    for (int damped = 0; damped <= 1; damped++) {
        rg_world *w = world_with(RG_INTEGRATOR_RK4, 0, 0);
        rg_body a = make_body(w, m1, 0, 0), b = make_body(w, m2, 1.5, 0);
        uint64_t s;
        assert_ok(rg_spring_create(w, a, b, v2(0, 0), (rg_real)L, (rg_real)k, damped ? 0.5f : 0, &s));
        assert_int_equal(rg_world_spring_count(w), 1);
        double e_prev = 0.5 * k * 0.25, z = sqrt(k * (m1 + m2) / (m1 * m2)) * dt;
        for (int i = 1; i <= n; i++) {
            assert_ok(rg_world_step(w, (rg_real)dt));
            rg_vec2 va = vel_of(w, a), vb = vel_of(w, b), pa = pos_of(w, a), pb = pos_of(w, b);
            double p = m1 * (double)va.x + m2 * (double)vb.x;
            assert_near(p, 0, i * 8 * REAL_EPS * 10);
            double stretch = (double)pb.x - (double)pa.x - L;
            double e = 0.5 * m1 * (double)va.x * (double)va.x + 0.5 * m2 * (double)vb.x * (double)vb.x +
                       0.5 * k * stretch * stretch;
            if (damped) {
                assert_true(e <= e_prev * (1 + 64 * REAL_EPS));
                e_prev = e;
            } else {
                assert_near(e / (0.5 * k * 0.25), 1, i * (pow(z, 6) / 72 + 64 * REAL_EPS));
            }
        }
        if (damped) assert_true(e_prev < 0.5 * 0.5 * k * 0.25);
        rg_world_destroy(w);
    }
}

static void test_destroying_a_body_destroys_its_springs(void **state)
{
    (void)state;
    rg_world *w = world_with(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, 0, 0);
    rg_body a = make_body(w, 1, 0, 0), b = make_body(w, 1, 1, 0), c = make_body(w, 1, 2, 0);
    uint64_t s1, s2, s3;
    assert_ok(rg_spring_create(w, a, b, v2(0, 0), 1, 1, 0, &s1));
    assert_ok(rg_spring_create(w, b, c, v2(0, 0), 1, 1, 0, &s2));
    assert_ok(rg_spring_create(w, c, 0, v2(5, 5), 1, 1, 0, &s3));
    assert_ok(rg_body_destroy(w, b));
    assert_false(rg_spring_is_valid(w, s1));
    assert_false(rg_spring_is_valid(w, s2));
    assert_true(rg_spring_is_valid(w, s3));
    assert_int_equal(rg_world_spring_count(w), 1);
    assert_status(rg_spring_destroy(w, s1), RG_ERR_STALE_HANDLE);
    assert_ok(rg_spring_destroy(w, s3));
    assert_status(rg_spring_destroy(w, s3), RG_ERR_STALE_HANDLE);
    assert_ok(rg_world_step(w, (rg_real)0.1));
    rg_world_destroy(w);
}

static void test_spring_rejects_bad_input_and_changes_nothing(void **state)
{
    (void)state;
    rg_world *w = world_with(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, 0, 0), *other;
    assert_ok(rg_world_create(&other));
    rg_body a = make_body(w, 1, 0, 0), b = make_body(w, 1, 1, 0), foreign = make_body(other, 1, 0, 0);
    uint64_t s = 77;
    const rg_real nan = (rg_real)NAN, inf = (rg_real)INFINITY;
    assert_status(rg_spring_create(NULL, a, b, v2(0, 0), 1, 1, 0, &s), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_spring_create(w, a, b, v2(0, 0), 1, 1, 0, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_spring_create(w, a, b, v2(0, 0), -1, 1, 0, &s), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_spring_create(w, a, b, v2(0, 0), 1, -1, 0, &s), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_spring_create(w, a, b, v2(0, 0), 1, 1, -1, &s), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_spring_create(w, a, b, v2(0, 0), nan, 1, 0, &s), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_spring_create(w, a, b, v2(0, 0), 1, inf, 0, &s), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_spring_create(w, a, b, v2(0, 0), 1, 1, nan, &s), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_spring_create(w, a, 0, v2(nan, 0), 1, 1, 0, &s), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_spring_create(w, a, a, v2(0, 0), 1, 1, 0, &s), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_spring_create(w, 0, b, v2(0, 0), 1, 1, 0, &s), RG_ERR_STALE_HANDLE);
    assert_status(rg_spring_create(w, a, foreign, v2(0, 0), 1, 1, 0, &s), RG_ERR_STALE_HANDLE);
    assert_status(rg_spring_create(w, a, a + (1u << 24), v2(0, 0), 1, 1, 0, &s), RG_ERR_STALE_HANDLE); /* next generation */
    assert_true(s == 77);
    assert_int_equal(rg_world_spring_count(w), 0);
    assert_status(rg_spring_destroy(NULL, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_spring_destroy(w, 0), RG_ERR_STALE_HANDLE);
    assert_status(rg_spring_destroy(w, a), RG_ERR_STALE_HANDLE); /* a body is not a spring */
    assert_false(rg_spring_is_valid(NULL, 1));
    assert_int_equal(rg_world_spring_count(NULL), 0);
    rg_world_destroy(other);
    rg_world_destroy(w);
}

static void test_force_setters_reject_bad_input_and_change_nothing(void **state)
{
    (void)state;
    rg_world *w = world_with(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, 0, 0);
    /* heavy enough that the accepted force keeps the body in range (5e5 m/s over 1 s) */
    const double m = 1e6;
    rg_body b = make_body(w, m, 0, 0);
    const rg_real nan = (rg_real)NAN, inf = (rg_real)INFINITY;
    assert_status(rg_body_apply_force(w, b, v2(nan, 0)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_apply_force(w, b, v2(0, inf)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_apply_force(NULL, b, v2(0, 0)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_apply_force(w, 0, v2(0, 0)), RG_ERR_STALE_HANDLE);
    /* a force whose sum with the step's applied force leaves RG_MAX_FORCE is refused, the
     * first one stays (before the ranges: two forces whose sum overflowed) */
    assert_ok(rg_body_apply_force(w, b, v2(RG_MAX_FORCE / 2, 0)));
    assert_status(rg_body_apply_force(w, b, v2(RG_MAX_FORCE, 0)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_apply_impulse(w, b, v2(nan, 0)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_apply_impulse(w, b, v2(0, -inf)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_apply_impulse(NULL, b, v2(0, 0)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_gravity_scale(w, b, nan), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_gravity_scale(w, b, inf), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_drag(w, b, -1, 0), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_drag(w, b, 0, -1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_drag(w, b, nan, 0), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_drag(w, b, 0, inf), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_surface_friction(w, b, -1, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_surface_friction(w, b, 1, -1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_surface_friction(w, b, nan, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_surface_friction(w, b, 1, inf), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_surface_friction(w, b, (rg_real)(REAL_MAX / 4), 8), RG_ERR_INVALID_ARGUMENT); /* mu beyond RG_MAX_FRICTION */
    assert_status(rg_body_set_speed_limits(w, b, -1, 0), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_speed_limits(w, b, 0, -1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_speed_limits(w, b, 2, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_speed_limits(w, b, nan, 0), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_speed_limits(w, b, 0, inf), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_drag(NULL, b, 0, 0), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_surface_friction(w, 0, 0, 0), RG_ERR_STALE_HANDLE);
    assert_status(rg_body_set_speed_limits(w, 0, 0, 0), RG_ERR_STALE_HANDLE);
    assert_status(rg_body_set_gravity_scale(NULL, b, 1), RG_ERR_INVALID_ARGUMENT);
    /* none of it took: one step moves the body by the one accepted force only, no drag */
    assert_ok(rg_world_step(w, 1));
    rg_vec2 v = vel_of(w, b);
    assert_near(v.x, RG_MAX_FORCE / 2 / m, 2 * REAL_EPS * RG_MAX_FORCE / 2 / m); /* F (1/m) h, rounded twice */
    assert_true(v.y == 0);
    rg_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_quadratic_drag_reaches_terminal_speed),
        cmocka_unit_test(test_linear_drag_projectile_matches_closed_form),
        cmocka_unit_test(test_friction_stops_within_one_step_and_stays_at_exact_zero),
        cmocka_unit_test(test_friction_holds_a_resting_body_against_a_smaller_force),
        cmocka_unit_test(test_naive_dissipation_overshoots_where_the_library_does_not),
        cmocka_unit_test(test_stiff_drag_never_grows_or_turns_a_velocity),
        cmocka_unit_test(test_friction_never_turns_a_velocity_that_a_perpendicular_force_keeps),
        cmocka_unit_test(test_wind_is_a_force_shared_by_dynamic_bodies),
        cmocka_unit_test(test_gravity_scale_multiplies_gravity),
        cmocka_unit_test(test_impulse_changes_momentum_at_once),
        cmocka_unit_test(test_applied_force_lasts_one_step),
        cmocka_unit_test(test_speed_limits_snap_to_rest_and_clamp),
        cmocka_unit_test(test_body_spring_conserves_momentum_and_damping_dissipates),
        cmocka_unit_test(test_destroying_a_body_destroys_its_springs),
        cmocka_unit_test(test_spring_rejects_bad_input_and_changes_nothing),
        cmocka_unit_test(test_force_setters_reject_bad_input_and_change_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
