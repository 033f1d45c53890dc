/* test_bounds.c: the step's range guard.  A scene whose forces are far beyond its scale drives
 * a body out of the accepted range (or, within one RK4 or Verlet step, past the float range);
 * the step stops it at the edge, keeps every state finite and lists it (rg_world_get_stopped). */
#include "testutil.h"

static const double max_coord = RG_MAX_COORD, max_speed = RG_MAX_SPEED;

static int32_t stopped(rg_world *w, rg_body *out, int32_t cap)
{
    int32_t n = rg_world_get_stopped(w, out, cap);
    assert_true(n >= 0);
    return n;
}

/* The body is stopped in range: position finite and within +-RG_MAX_COORD, velocity and
 * acceleration exactly 0, interpolated position finite. */
static void assert_stopped_in_range(rg_world *w, rg_body b)
{
    rg_vec2 p = pos_of(w, b), v = vel_of(w, b), a, ip;
    assert_ok(rg_body_get_acceleration(w, b, &a));
    assert_ok(rg_body_get_interpolated_position(w, b, &ip));
    if (!(fabs((double)p.x) <= max_coord && fabs((double)p.y) <= max_coord))
        fail_msg("position (%g, %g) out of range", (double)p.x, (double)p.y);
    if (!(isfinite(ip.x) && isfinite(ip.y)))
        fail_msg("interpolated position (%g, %g) not finite", (double)ip.x, (double)ip.y);
    assert_true(v.x == 0 && v.y == 0 && a.x == 0 && a.y == 0);
}

/* RG_MAX_FORCE on RG_MIN_MASS over RG_MAX_DT: v = F h / m = 1e19 m/s, past RG_MAX_SPEED, and
 * the semi-implicit position v h = 1e20 m, past RG_MAX_COORD: every integrator's step leaves
 * the range (explicit Euler by its velocity only, its position moving by v0 h = 0). */
static void test_a_force_beyond_the_scale_stops_the_body_at_the_edge(void **state)
{
    (void)state;
    for (int integ = 0; integ <= 3; integ++) {
        rg_world *w;
        assert_ok(rg_world_create(&w));
        assert_ok(rg_world_set_integrator(w, integ));
        rg_body calm = make_body(w, 1, 5, 0);
        assert_ok(rg_body_set_velocity(w, calm, v2(1, 0)));
        rg_body b = make_body(w, RG_MIN_MASS, 0, 0);
        assert_ok(rg_body_apply_force(w, b, v2(RG_MAX_FORCE, 0)));
        assert_ok(rg_world_step(w, RG_MAX_DT));
        rg_body out[4] = { 0 };
        assert_int_equal(stopped(w, out, 4), 1);
        assert_true(out[0] == b);
        assert_stopped_in_range(w, b);
        if (integ == RG_INTEGRATOR_SEMI_IMPLICIT_EULER) assert_true(pos_of(w, b).x == (rg_real)max_coord);
        if (integ == RG_INTEGRATOR_EXPLICIT_EULER) assert_true(pos_of(w, b).x == 0);
        /* the body in range is untouched: x = 5 + 1 m/s * 10 s */
        assert_true(pos_of(w, calm).x == 15 && vel_of(w, calm).x == 1);
        /* the next step has nothing to stop, and the list says so */
        rg_vec2 p = pos_of(w, b);
        assert_ok(rg_world_step(w, RG_MAX_DT));
        assert_int_equal(stopped(w, out, 4), 0);
        assert_true(pos_of(w, b).x == p.x);
        rg_world_destroy(w);
    }
}

/* A spring of the largest stiffness and damping (1e9 each) on the lightest body 1e9 m from
 * its anchor: a0 = k d / m = 1e24 m/s^2, and over h = 10 s RK4's second stage meets a
 * damping force c |v| / m = 1e9 * 5e24 / 1e-6 = 5e39, past FLT_MAX (3.4e38): in the float
 * build the step's end state is not finite and the body goes back to where the step began;
 * in the double build it is finite and far out of range, and is clamped.  Verlet's end
 * acceleration (k * 5e25 / m = 5e40) overflows the same way. */
static void test_an_overflow_within_a_step_never_reaches_the_world(void **state)
{
    (void)state;
    const int multi[2] = { RG_INTEGRATOR_VELOCITY_VERLET, RG_INTEGRATOR_RK4 };
    for (int k = 0; k < 2; k++) {
        rg_world *w;
        uint64_t sp;
        assert_ok(rg_world_create(&w));
        assert_ok(rg_world_set_integrator(w, multi[k]));
        rg_body b = make_body(w, RG_MIN_MASS, 0, 0);
        assert_ok(rg_spring_create(w, b, 0, v2(max_coord, 0), 0, RG_MAX_STIFFNESS, RG_MAX_DAMPING, &sp));
        assert_ok(rg_world_step(w, RG_MAX_DT));
        assert_int_equal(stopped(w, NULL, 0), 1);
        assert_stopped_in_range(w, b);
#ifndef RG_DOUBLE
        if (multi[k] == RG_INTEGRATOR_RK4) assert_true(pos_of(w, b).x == 0 && pos_of(w, b).y == 0);
#endif
        /* stopped again (from the start) or at rest on the anchor: in range either way */
        for (int s = 0; s < 5; s++) {
            assert_ok(rg_world_step(w, RG_MAX_DT));
            if (stopped(w, NULL, 0) == 1) {
                assert_stopped_in_range(w, b);
            } else {
                rg_vec2 p = pos_of(w, b), v = vel_of(w, b);
                assert_true(fabs((double)p.x) <= max_coord && fabs((double)v.x) <= max_speed);
            }
        }
        rg_world_destroy(w);
    }
}

/* A kinematic body moves by its velocity alone: at RG_MAX_SPEED it crosses the edge
 * (1e9 - 5e5 m + 1e6 m/s * 1 s) and stops there. */
static void test_a_kinematic_body_stops_at_the_edge(void **state)
{
    (void)state;
    rg_world *w;
    rg_body k;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_body_create(w, RG_BODY_KINEMATIC, 0, v2(max_coord - 5e5, 0), &k));
    assert_ok(rg_body_set_velocity(w, k, v2(max_speed, 0)));
    assert_ok(rg_world_step(w, 1));
    assert_int_equal(stopped(w, NULL, 0), 1);
    assert_stopped_in_range(w, k);
    assert_true(pos_of(w, k).x == (rg_real)max_coord);
    rg_world_destroy(w);
}

/* The list covers every step of an advance, clears with the next stepping call and with a
 * restore, and copies the smallest handles in ascending order when the buffer is short. */
static void test_the_list_covers_an_advance_and_clears(void **state)
{
    (void)state;
    rg_world *w;
    int32_t steps = 0;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_fixed_step(w, RG_MAX_DT, 4));
    rg_body b[3];
    for (int i = 0; i < 3; i++) {
        b[i] = make_body(w, RG_MIN_MASS, 0, i);
        assert_ok(rg_body_apply_force(w, b[i], v2(0, -RG_MAX_FORCE)));
    }
    size_t n = 0;
    assert_ok(rg_world_save(w, NULL, 0, &n));
    void *snap = malloc(n);
    assert_non_null(snap);
    assert_ok(rg_world_save(w, snap, n, &n));
    /* the force lasts the first step; the advance takes three */
    assert_ok(rg_world_advance(w, 3 * RG_MAX_DT, &steps));
    assert_int_equal(steps, 3);
    rg_body out[2] = { 0, 0 }, lo = b[0], mid = b[1];
    for (int i = 1; i < 3; i++) {
        if (b[i] < lo) { mid = lo; lo = b[i]; }
        else if (b[i] < mid || mid == lo) mid = b[i];
    }
    assert_int_equal(stopped(w, out, 2), 3);
    assert_true(out[0] == lo && out[1] == mid && lo < mid);
    for (int i = 0; i < 3; i++) assert_stopped_in_range(w, b[i]);
    assert_ok(rg_world_advance(w, 0, &steps)); /* a stepping call, even of no step */
    assert_int_equal(stopped(w, NULL, 0), 0);
    assert_ok(rg_world_step(w, RG_MAX_DT));
    assert_ok(rg_world_restore(w, snap, n)); /* the forces come back with the state */
    assert_ok(rg_world_step(w, RG_MAX_DT));
    assert_int_equal(stopped(w, NULL, 0), 3);
    assert_ok(rg_world_restore(w, snap, n));
    assert_int_equal(stopped(w, NULL, 0), 0);
    free(snap);
    rg_world_destroy(w);
}

static void test_the_list_refuses_bad_input(void **state)
{
    (void)state;
    rg_world *w;
    rg_body out[1];
    assert_ok(rg_world_create(&w));
    assert_int_equal(rg_world_get_stopped(NULL, out, 1), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_get_stopped(w, out, -1), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_get_stopped(w, NULL, 1), RG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(rg_world_last_error(w), "rg_world_get_stopped"));
    assert_int_equal(rg_world_get_stopped(w, NULL, 0), 0);
    rg_world_destroy(w);
}

/* The collide stage can throw a body past the speed range: an elastic impact of a 1e9 kg box
 * at RG_MAX_SPEED on a 1 kg box at rest sends the light one off at nearly twice that (v' =
 * 2 M V / (M + m)), which no integration step made.  The step ends with the guard too (found
 * as a snapshot the restore refuses: a world must restore what it saved), so the light box
 * ends the impact's step stopped in range and listed, and every body's state after every
 * step is within the ranges. */
static void test_an_impact_past_the_speed_range_is_stopped_at_the_step_end(void **state)
{
    (void)state;
    rg_world *w;
    assert_ok(rg_world_create(&w));
    rg_body heavy = box_body(w, RG_BODY_DYNAMIC, 1e9, 0, 0, 1, 1);
    rg_body light = box_body(w, RG_BODY_DYNAMIC, 1, 30000, 0, 1, 1);
    assert_ok(rg_body_set_restitution(w, heavy, 1));
    assert_ok(rg_body_set_restitution(w, light, 1));
    assert_ok(rg_body_set_velocity(w, heavy, v2((rg_real)max_speed, 0)));
    int hit = 0;
    for (int k = 0; k < 4; k++) {
        assert_ok(rg_world_step(w, (rg_real)DT));
        rg_body b[2] = { heavy, light };
        for (int j = 0; j < 2; j++) {
            rg_vec2 p = pos_of(w, b[j]), v = vel_of(w, b[j]);
            if (!(fabs((double)p.x) <= max_coord && fabs((double)v.x) <= max_speed && fabs((double)v.y) <= max_speed))
                fail_msg("step %d: body %d at %g with velocity (%g, %g), out of range", k + 1, j, (double)p.x,
                         (double)v.x, (double)v.y);
        }
        rg_body out[2];
        if (stopped(w, out, 2) == 1 && out[0] == light) {
            assert_stopped_in_range(w, light);
            hit = 1;
        }
    }
    assert_true(hit);   /* the impact happened, and threw the light box past the range */
    rg_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_force_beyond_the_scale_stops_the_body_at_the_edge),
        cmocka_unit_test(test_an_overflow_within_a_step_never_reaches_the_world),
        cmocka_unit_test(test_a_kinematic_body_stops_at_the_edge),
        cmocka_unit_test(test_an_impact_past_the_speed_range_is_stopped_at_the_step_end),
        cmocka_unit_test(test_the_list_covers_an_advance_and_clears),
        cmocka_unit_test(test_the_list_refuses_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
