/* test_spring.c: a spring made or removed wakes the bodies it ties, so a sleeping body feels
 * the change: a crate resting asleep on a rope falls when the rope is cut or its other end
 * destroyed, and a sleeping crate a new spring pulls moves.  (Until 2026-12-07 a spring made
 * or removed woke nothing: a sleeping body, not integrated, ignored it; each test below fails
 * on dd1af3b.) */
#include "testutil.h"

/* A crate hanging at rest on a rope (a stiff damped spring, 2 m) from the point (0, 8), or
 * from body `hook` (0: the point): sleeping on (thresholds: under 0.05 m/s for 0.5 s), it
 * sleeps within 10 s of damped swinging. */
static rg_body hanging_crate(rg_world *w, rg_body hook, uint64_t *rope)
{
    rg_body c = box_body(w, RG_BODY_DYNAMIC, 1, 0, 5, 0.25, 0.25);
    assert_ok(rg_spring_create(w, c, hook, v2(0, 8), 2, 200, 20, rope));
    step_n(w, 600, DT);
    assert_int_equal(flag(rg_body_is_awake, w, c), 0);
    return c;
}

/* Crate c, its rope gone, is awake and falls freely: semi-implicit Euler from rest under
 * g = 10, after n steps it has fallen g dt^2 n (n + 1) / 2; 30 steps, 1.29 m, to the rounding
 * of 30 steps at y < 6, some 30 * 2 * 6 eps. */
static void falls_freely(rg_world *w, rg_body c)
{
    double y0 = PY(w, c);
    assert_int_equal(flag(rg_body_is_awake, w, c), 1);
    step_n(w, 30, DT);
    assert_near(y0 - PY(w, c), 10 * DT * DT * 30 * 31 / 2, 30 * 2 * 6 * REAL_EPS);
}

static void test_a_sleeping_crate_falls_when_its_rope_is_cut(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    uint64_t rope;
    rg_body c = hanging_crate(w, 0, &rope);
    assert_ok(rg_spring_destroy(w, rope));
    falls_freely(w, c);
    rg_world_destroy(w);
}

/* The rope tied to a hook (a static box) instead of a point: destroying the hook cuts it. */
static void test_a_sleeping_crate_falls_when_the_body_holding_its_rope_is_destroyed(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    rg_body hook = box_body(w, RG_BODY_STATIC, 0, 0, 8, 0.1, 0.1);
    uint64_t rope;
    rg_body c = hanging_crate(w, hook, &rope);
    assert_ok(rg_body_destroy(w, hook));
    assert_int_equal(rg_spring_is_valid(w, rope), 0);
    falls_freely(w, c);
    rg_world_destroy(w);
}

/* A crate asleep on the floor, a spring to a point 3 m to its right made: it wakes and moves
 * right (friction 0, so the spring's pull, 10 N/m over 3 m, is all that acts sideways). */
static void test_a_sleeping_crate_a_new_spring_pulls_moves(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    floor_of(w);
    rg_body c = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.25, 0.25, 0.25);
    assert_ok(rg_body_set_friction(w, c, 0));
    step_n(w, 120, DT);
    assert_int_equal(flag(rg_body_is_awake, w, c), 0);
    uint64_t sp;
    assert_ok(rg_spring_create(w, c, 0, v2(3, 0.25), 0, 10, 0, &sp));
    assert_int_equal(flag(rg_body_is_awake, w, c), 1);
    step_n(w, 10, DT);
    /* semi-implicit Euler under F = 10 (3 - x) N on 1 kg (the spring level with the crate's
     * centre, zero rest length), from rest: 0.447 m, to the rounding of 10 steps of x < 3 */
    double x = 0, v = 0;
    for (int i = 0; i < 10; i++) {
        v += 10 * (3 - x) * DT;
        x += v * DT;
    }
    assert_near(PX(w, c), x, 10 * 4 * 3 * REAL_EPS);
    rg_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_sleeping_crate_falls_when_its_rope_is_cut),
        cmocka_unit_test(test_a_sleeping_crate_falls_when_the_body_holding_its_rope_is_destroyed),
        cmocka_unit_test(test_a_sleeping_crate_a_new_spring_pulls_moves),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
