/* test_speed_limits.c: speed limits apply where the step ends, after its collisions, so the
 * velocity read after any step obeys them: on the ground too (where the integration alone
 * adds gravity's g*dt to every resting body's speed) and after a bounce. */
#include "testutil.h"

/* A frictionless crate sliding on the floor at 0.05 m/s, its min speed 0.1, is at rest
 * (exactly) after one step and stays there.  (Until 2026-12-07 the limits ran right after
 * the integration, where the crate's speed was |(0.05, -g dt)| = 0.17 > 0.1: it slid on at
 * 0.05 m/s for ever, as did every grounded body below g dt = 0.17 m/s.) */
static void test_a_crate_sliding_slower_than_its_min_speed_on_the_ground_snaps_to_rest(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    assert_ok(rg_world_set_sleeping(w, 0));
    floor_of(w);
    rg_body b = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5, 0.5);
    assert_ok(rg_body_set_friction(w, b, 0));
    step_n(w, 60, DT); /* settled */
    assert_ok(rg_body_set_velocity(w, b, v2(0.05, 0)));
    assert_ok(rg_body_set_speed_limits(w, b, (rg_real)0.1, 0));
    double x0 = PX(w, b);
    for (int i = 0; i < 120; i++) {
        step_n(w, 1, DT);
        assert_true(VX(w, b) == 0 && VY(w, b) == 0);
    }
    /* it moved in the first step only: 0.05 * dt, to the rounding of a coordinate near 0 */
    assert_near(PX(w, b) - x0, 0.05 * DT, 4 * REAL_EPS);
    assert_true(flag(rg_body_is_grounded, w, b));
    rg_world_destroy(w);
}

/* A ball dropped from 5 m onto the floor with restitution 1 and max speed 3: after every
 * step, its speed is at most 3 (to the rounding of the clamp's scale, a few eps), and it does
 * reach 3.  (Until 2026-12-07 the bounce came after the clamp: 3.15 m/s after it.) */
static void test_a_bounce_never_leaves_a_body_faster_than_its_max_speed(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    floor_of(w);
    rg_body c = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 5, 0.25);
    assert_ok(rg_body_set_restitution(w, c, 1));
    assert_ok(rg_body_set_speed_limits(w, c, 0, 3));
    double most = 0;
    int bounced = 0;
    for (int i = 0; i < 300; i++) {
        step_n(w, 1, DT);
        double s = hypot(VX(w, c), VY(w, c));
        assert_true(s <= 3 * (1 + 4 * REAL_EPS));
        most = fmax(most, s);
        bounced |= VY(w, c) > 0;
    }
    assert_true(bounced);
    assert_near(most, 3, 3 * 4 * REAL_EPS);
    rg_world_destroy(w);
}

/* A body falling at its max speed 5 beside shapes (so the limits run after the collide
 * stage): each semi-implicit step starts from 5 m/s, adds g dt and moves (5 + g dt) dt, the
 * bound the header gives, then reads 5 again. */
static void test_a_body_held_at_max_speed_moves_the_documented_distance_a_step(void **state)
{
    (void)state;
    const double g = 10;
    rg_world *w = gravity_world(-g);
    box_body(w, RG_BODY_STATIC, 0, 50, 0, 1, 1); /* a shape elsewhere */
    rg_body b = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 0, 0.25);
    assert_ok(rg_body_set_speed_limits(w, b, 0, 5));
    assert_ok(rg_body_set_velocity(w, b, v2(0, -5)));
    for (int i = 0; i < 60; i++) {
        double y0 = PY(w, b);
        step_n(w, 1, DT);
        /* the move's rounding: y, up to some 35 m, in eps of it */
        assert_near(y0 - PY(w, b), (5 + g * DT) * DT, 4 * REAL_EPS * (fabs(y0) + 1));
        assert_near(VY(w, b), -5, 5 * 4 * REAL_EPS);
    }
    rg_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_crate_sliding_slower_than_its_min_speed_on_the_ground_snaps_to_rest),
        cmocka_unit_test(test_a_bounce_never_leaves_a_body_faster_than_its_max_speed),
        cmocka_unit_test(test_a_body_held_at_max_speed_moves_the_documented_distance_a_step),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
