/* test_narrow.c: the narrowphase's grounded flag: in the air, at rest, against walls and ceilings, on
 * slopes. */
#include "testutil.h"

static void test_grounded_is_false_in_the_air_and_true_at_rest(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    floor_of(w);
    rg_body ball = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 2, 0.5);
    assert_int_equal(flag(rg_body_is_grounded, w, ball), 0);
    int landed_at = -1;
    for (int i = 0; i < 120; i++) {
        assert_ok(rg_world_step(w, (rg_real)DT));
        int32_t g = flag(rg_body_is_grounded, w, ball);
        if (PY(w, ball) > 0.6) assert_int_equal(g, 0);
        if (g && landed_at < 0) landed_at = i;
        if (landed_at >= 0) assert_int_equal(g, 1);
    }
    assert_true(landed_at > 0);
    /* a jump leaves the ground at once */
    assert_ok(rg_body_apply_impulse(w, ball, v2(0, 5)));
    assert_ok(rg_world_step(w, (rg_real)DT));
    assert_int_equal(flag(rg_body_is_grounded, w, ball), 0);
    rg_world_destroy(w);
}

static void test_walls_and_ceilings_are_not_ground_unless_gravity_says_so(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    /* a box pressed against a wall in the air */
    box_body(w, RG_BODY_STATIC, 0, 1, 5, 0.5, 5);
    rg_body b = box_body(w, RG_BODY_DYNAMIC, 1, 0, 5, 0.5, 0.5);
    assert_ok(rg_body_set_velocity(w, b, v2(2, 0)));
    assert_ok(rg_body_set_friction(w, b, 0));
    rg_contact_event ev[4];
    int touched = 0;
    for (int i = 0; i < 10; i++) {
        assert_ok(rg_body_apply_force(w, b, v2(50, 0)));
        assert_ok(rg_world_step(w, (rg_real)DT));
        touched |= get_events(w, ev, 4) > 0;
        assert_int_equal(flag(rg_body_is_grounded, w, b), 0);
    }
    assert_true(touched);
    /* under a ceiling with gravity scale -1 (falls up): the ceiling is its ground */
    rg_body up = box_body(w, RG_BODY_DYNAMIC, 1, -10, 9.4, 0.5, 0.5);
    box_body(w, RG_BODY_STATIC, 0, -10, 10.5, 2, 0.5);
    assert_ok(rg_body_set_gravity_scale(w, up, -1));
    step_n(w, 30, DT);
    assert_int_equal(flag(rg_body_is_grounded, w, up), 1);
    /* no gravity: never grounded */
    rg_world *z = gravity_world(0);
    floor_of(z);
    rg_body r = circle_body(z, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5);
    step_n(z, 10, DT);
    assert_int_equal(flag(rg_body_is_grounded, z, r), 0);
    rg_world_destroy(z);
    rg_world_destroy(w);
}

static void test_grounded_on_a_slope_within_45_degrees_only(void **state)
{
    (void)state;
    for (int k = 0; k < 2; k++) {
        double theta = k == 0 ? 0.5 : 0.9; /* 29 and 52 degrees */
        rg_world *w = gravity_world(-10);
        circle_body(w, RG_BODY_STATIC, 0, 0, 0, 0.5);
        rg_body top = circle_body(w, RG_BODY_DYNAMIC, 1, sin(theta), cos(theta), 0.5);
        assert_ok(rg_body_set_friction(w, top, 10)); /* holds it there */
        step_n(w, 3, DT);
        assert_int_equal(flag(rg_body_is_grounded, w, top), k == 0);
        rg_world_destroy(w);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_grounded_is_false_in_the_air_and_true_at_rest),
        cmocka_unit_test(test_walls_and_ceilings_are_not_ground_unless_gravity_says_so),
        cmocka_unit_test(test_grounded_on_a_slope_within_45_degrees_only),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
