/* test_one_way.c: one-way shapes and passing through: landing on a platform, jumping up
 * through it, walking through its side, fast bodies, dropping down, any normal. */
#include "testutil.h"

#define SLOP 0.005
#define G 10.0

/* A static one-way platform (top at y = 0.1) 4 m wide, facing up. */
static rg_body platform(rg_world *w, double x, double y, double hw, double hh)
{
    rg_body p = box_body(w, RG_BODY_STATIC, 0, x, y, hw, hh);
    assert_ok(rg_body_set_one_way(w, p, v2(0, 1)));
    return p;
}

static void test_a_body_falling_onto_a_one_way_platform_rests_on_it(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-G);
    rg_body p = platform(w, 0, 0, 2, 0.1);
    rg_body ball = circle_body(w, RG_BODY_DYNAMIC, 1, 0.3, 2, 0.25);
    rg_body crate = box_body(w, RG_BODY_DYNAMIC, 1, -1, 3, 0.25, 0.25);
    step_n(w, 180, DT);
    /* resting on the top face (y = 0.1) within the slop the solver leaves */
    assert_true(fabs(PY(w, ball) - 0.35) <= SLOP);
    assert_true(fabs(PY(w, crate) - 0.35) <= SLOP);
    assert_int_equal(flag(rg_body_is_grounded, w, ball), 1);
    assert_int_equal(flag(rg_body_is_grounded, w, crate), 1);
    rg_vec2 n;
    assert_ok(rg_body_get_one_way(w, p, &n));
    assert_true(n.x == 0 && n.y == 1);
    rg_world_destroy(w);
}

/* Jumping up from below: while it passes, the body flies exactly as it would without the
 * platform (no contact is solved: the same bits), and then it lands on top. */
static void test_a_body_jumping_up_through_it_is_not_slowed_and_lands_on_top(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-G), *free = gravity_world(-G);
    platform(w, 0, 1, 2, 0.1);
    rg_body b = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.3, 0.25, 0.25);
    rg_body f = box_body(free, RG_BODY_DYNAMIC, 1, 0, 0.3, 0.25, 0.25);
    /* v0 = 6 m/s: the apex (0.3 + 36/20 = 2.1 m) is well above the top (1.1 + 0.25) */
    assert_ok(rg_body_set_velocity(w, b, v2(0, 6)));
    assert_ok(rg_body_set_velocity(free, f, v2(0, 6)));
    int passed = 0;
    for (int k = 0; k < 60 && VY(free, f) > 0; k++) {
        step_n(w, 1, DT);
        step_n(free, 1, DT);
        assert_true(PY(w, b) == PY(free, f) && VY(w, b) == VY(free, f));
        assert_int_equal(flag(rg_body_is_grounded, w, b), 0);
        passed |= PY(w, b) - 0.25 > 1.1;
    }
    assert_true(passed);
    step_n(w, 120, DT);
    assert_true(fabs(PY(w, b) - 1.35) <= SLOP);
    assert_int_equal(flag(rg_body_is_grounded, w, b), 1);
    rg_world_destroy(free);
    rg_world_destroy(w);
}

/* The highest bottom of a box leaving y0 at v0 up in semi-implicit Euler steps of DT:
 * v_k = v0 - k g dt, y_k = y_(k-1) + v_k dt. */
static double discrete_apex(double y0, double v0)
{
    double y = y0, v = v0, top = y0;
    while (v > 0) {
        v -= G * DT;
        y += v * DT;
        if (y > top) top = y;
    }
    return top;
}

/* Clearing the top by 1 cm only, the pair stays a contact (the fat boxes keep overlapping):
 * it passes up through while it overlaps, and lands once a step ended apart. */
static void test_a_body_that_barely_clears_the_top_lands_on_it(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-G);
    platform(w, 0, 1, 2, 0.1);
    rg_body b = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.3, 0.25, 0.25);
    double lo = 3, hi = 6; /* v0 whose apex puts the bottom 1 cm above the top (y = 1.1) */
    for (int k = 0; k < 60; k++) {
        double mid = (lo + hi) / 2;
        if (discrete_apex(0.05, mid) < 1.11) lo = mid; else hi = mid;
    }
    assert_ok(rg_body_set_velocity(w, b, v2(0, lo)));
    step_n(w, 180, DT);
    assert_true(fabs(PY(w, b) - 1.35) <= SLOP);
    assert_int_equal(flag(rg_body_is_grounded, w, b), 1);
    rg_world_destroy(w);
}

/* A low platform whose height the walker overlaps: walking into its side, the walker is not
 * pushed up or back: it walks through as if the platform were not there. */
static void test_walking_into_its_side_while_overlapping_is_not_pushed(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-G);
    floor_of(w);
    platform(w, 3, 0.3, 1, 0.1); /* spans y 0.2 .. 0.4; the walker spans 0 .. 0.5 */
    rg_body walker = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.25, 0.25, 0.25);
    assert_ok(rg_body_set_friction(w, walker, 0));
    step_n(w, 30, DT);
    double y0 = PY(w, walker);
    assert_ok(rg_body_set_velocity(w, walker, v2(3, 0)));
    for (int k = 0; k < 120; k++) {
        step_n(w, 1, DT);
        assert_true(fabs(PY(w, walker) - y0) <= SLOP);
        assert_true(fabs(VX(w, walker) - 3) <= 1e-4);
    }
    assert_true(PX(w, walker) > 5.5); /* through and past the platform's far end (x = 4) */
    rg_world_destroy(w);
}

/* From above at a speed that crosses the thin platform in one step: it still lands. */
static void test_a_fast_body_from_above_lands_on_a_thin_platform(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-G);
    platform(w, 0, 0, 2, 0.01);
    rg_body b = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 3, 0.1);
    assert_ok(rg_body_set_velocity(w, b, v2(0, -120))); /* 2 m per step */
    step_n(w, 120, DT);
    assert_true(fabs(PY(w, b) - 0.11) <= SLOP);
    rg_world_destroy(w);
}

/* Dropping down: a body resting on a platform passes through it after rg_body_pass_through;
 * on a two-way box the pair collides again once apart (thrown back up, it hits the underside). */
static void test_pass_through_drops_a_resting_body_and_it_collides_again_once_apart(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-G);
    floor_of(w);
    rg_body p = platform(w, 0, 2, 2, 0.1);
    rg_body b = box_body(w, RG_BODY_DYNAMIC, 1, 0, 2.5, 0.25, 0.25);
    step_n(w, 60, DT);
    assert_true(fabs(PY(w, b) - 2.35) <= SLOP);
    assert_ok(rg_body_pass_through(w, b, p));
    step_n(w, 120, DT);
    assert_true(fabs(PY(w, b) - 0.25) <= SLOP); /* on the floor */
    /* a two-way shelf */
    rg_body shelf = box_body(w, RG_BODY_STATIC, 0, 6, 2, 1, 0.1);
    rg_body c = box_body(w, RG_BODY_DYNAMIC, 1, 6, 2.5, 0.25, 0.25);
    step_n(w, 60, DT);
    assert_true(fabs(PY(w, c) - 2.35) <= SLOP);
    assert_ok(rg_body_pass_through(w, shelf, c)); /* either order */
    step_n(w, 120, DT);
    assert_true(fabs(PY(w, c) - 0.25) <= SLOP);
    /* apart now: thrown up, it hits the shelf's underside (y = 1.9) and falls back */
    assert_ok(rg_body_set_velocity(w, c, v2(0, 8)));
    double top = 0;
    for (int k = 0; k < 90; k++) {
        step_n(w, 1, DT);
        if (PY(w, c) > top) top = PY(w, c);
    }
    assert_true(top <= 1.9 - 0.25 + SLOP);
    assert_true(top > 1.9 - 0.25 - 0.2);
    /* pass_through on a pair that is apart does nothing */
    assert_ok(rg_body_pass_through(w, c, shelf));
    assert_ok(rg_body_set_velocity(w, c, v2(0, 8)));
    top = 0;
    for (int k = 0; k < 90; k++) {
        step_n(w, 1, DT);
        if (PY(w, c) > top) top = PY(w, c);
    }
    assert_true(top <= 1.9 - 0.25 + SLOP);
    rg_world_destroy(w);
}

/* A row of flush one-way tiles is a floor like a two-way one: a box or a ball sliding across
 * their seams rests on their tops (within the slop) all the way, at walking and running
 * speeds.  A box whose edge starts on a seam meets the next tile's corner first, with a side
 * normal; judged by that normal alone the pair passed and the box fell through the next tile
 * as it left the first. */
static void test_sliding_across_the_seams_of_flush_tiles_never_falls_through(void **state)
{
    (void)state;
    const double speeds[] = { 0.2, 1, 3, 8 };
    for (size_t k = 0; k < sizeof speeds / sizeof speeds[0]; k++)
        for (int round = 0; round < 2; round++) {
            rg_world *w = gravity_world(-G);
            for (int t = 0; t < 12; t++) {
                rg_body tile = platform(w, t + 0.5, -0.5, 0.5, 0.5);
                assert_ok(rg_body_set_friction(w, tile, 0));
            }
            rg_body b = round == 0 ? box_body(w, RG_BODY_DYNAMIC, 1, 0.6, 0.4, 0.4, 0.4)
                                   : circle_body(w, RG_BODY_DYNAMIC, 1, 0.6, 0.4, 0.4);
            assert_ok(rg_body_set_friction(w, b, 0));
            step_n(w, 30, DT);
            assert_ok(rg_body_set_velocity(w, b, v2(speeds[k], 0)));
            while (PX(w, b) < 11.4) {
                step_n(w, 1, DT);
                if (!(PY(w, b) >= 0.4 - SLOP))
                    fail_msg("%s at %g m/s: y = %g at x = %g", round == 0 ? "box" : "ball", speeds[k],
                             PY(w, b), PX(w, b));
            }
            rg_world_destroy(w);
        }
}

/* A wall facing +x blocks what comes from +x moving -x and lets the rest through; a diagonal
 * normal blocks from its side. */
static void test_normals_in_any_direction(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body wall = box_body(w, RG_BODY_STATIC, 0, 0, 0, 0.1, 2);
    assert_ok(rg_body_set_one_way(w, wall, v2(1, 0)));
    rg_body from_right = circle_body(w, RG_BODY_DYNAMIC, 1, 2, 1, 0.2);
    rg_body from_left = circle_body(w, RG_BODY_DYNAMIC, 1, -2, -1, 0.2);
    assert_ok(rg_body_set_velocity(w, from_right, v2(-4, 0)));
    assert_ok(rg_body_set_velocity(w, from_left, v2(4, 0)));
    step_n(w, 60, DT);
    assert_true(PX(w, from_right) >= 0.1 + 0.2 - SLOP);  /* stopped at the wall's face */
    assert_true(PX(w, from_left) > 1.5);                  /* passed through */
    /* normal (0.6, 0.8): a ball coming down onto the box is held, one rising into it is not */
    rg_body slab = box_body(w, RG_BODY_STATIC, 0, 10, 0, 1, 0.1);
    assert_ok(rg_body_set_one_way(w, slab, v2(0.6, 0.8)));
    rg_body down = circle_body(w, RG_BODY_DYNAMIC, 1, 10, 1, 0.2);
    rg_body up = circle_body(w, RG_BODY_DYNAMIC, 1, 10.5, -1, 0.2);
    assert_ok(rg_body_set_velocity(w, down, v2(0, -3)));
    assert_ok(rg_body_set_velocity(w, up, v2(0, 3)));
    step_n(w, 60, DT);
    assert_true(PY(w, down) >= 0.1 + 0.2 - SLOP);
    assert_true(PY(w, up) > 1.5);
    rg_vec2 n;
    assert_ok(rg_body_get_one_way(w, slab, &n));
    assert_near(n.x, 0.6, 1e-6);
    assert_near(n.y, 0.8, 1e-6);
    /* (0, 0) makes it two-way again: the ball rising into it is stopped */
    assert_ok(rg_body_set_one_way(w, slab, v2(0, 0)));
    rg_body up2 = circle_body(w, RG_BODY_DYNAMIC, 1, 9.5, -1, 0.2);
    assert_ok(rg_body_set_velocity(w, up2, v2(0, 3)));
    step_n(w, 60, DT);
    assert_true(PY(w, up2) <= -0.1 - 0.2 + SLOP);
    rg_world_destroy(w);
}

static void test_bad_input_is_rejected_and_changes_nothing(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-G);
    rg_body p = platform(w, 0, 0, 2, 0.1);
    rg_body b = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 1, 0.2);
    rg_body bare = make_body(w, 1, 5, 5);
    const double bad[][2] = { { (double)NAN, 1 }, { 0, (double)INFINITY }, { 0.5, 0 }, { 0, 1.01 },
                              { 1e30, 1e30 } };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        assert_status(rg_body_set_one_way(w, p, v2(bad[k][0], bad[k][1])), RG_ERR_INVALID_ARGUMENT);
    rg_vec2 n;
    assert_ok(rg_body_get_one_way(w, p, &n));
    assert_true(n.x == 0 && n.y == 1);
    assert_status(rg_body_get_one_way(w, p, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_one_way(NULL, p, &n), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_one_way(NULL, p, v2(0, 1)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_one_way(w, 12345, v2(0, 1)), RG_ERR_STALE_HANDLE);
    assert_status(rg_body_pass_through(w, b, b), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_pass_through(w, b, bare), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_pass_through(w, b, 999), RG_ERR_STALE_HANDLE);
    assert_status(rg_body_pass_through(w, 999, b), RG_ERR_STALE_HANDLE);
    assert_status(rg_body_pass_through(NULL, b, p), RG_ERR_INVALID_ARGUMENT);
    /* a tiny error of length is accepted and normalised */
    assert_ok(rg_body_set_one_way(w, p, v2(0, 1.0005)));
    assert_ok(rg_body_get_one_way(w, p, &n));
    assert_near(n.y, 1, 4 * REAL_EPS);
    rg_world_destroy(w);
}

/* A ball drifting down at 0.5 m/s toward a 1 cm one-way platform 1.5 cm below it, hit from
 * above by a 10 kg box at 3-100 m/s, with gravity and without: it ends resting on the
 * platform and never sinks into it by more than the slop.  Before, at 10 m/s it fell through:
 * its drift was more than half the platform's thickness, so its pair was measured by a sweep,
 * which missed and left no row, and the hit drove it 1.4 cm into the platform, deeper than
 * the slop, where a one-way shape lets a body through. */
static void test_a_ball_driven_onto_a_thin_platform_by_a_hit_from_above_stays_on_it(void **state)
{
    (void)state;
    const double speeds[] = {3, 10, 30, 100};
    for (int g = 0; g < 2; g++) {
        for (int k = 0; k < 4; k++) {
            rg_world *w = gravity_world(g ? -G : 0);
            platform(w, 0, 0, 2, 0.005);
            rg_body ball = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 0.005 + 0.015 + 0.27, 0.27);
            assert_ok(rg_body_set_velocity(w, ball, v2(0, -0.5)));
            rg_body hammer = box_body(w, RG_BODY_DYNAMIC, 10, 0, 0.56 + 0.05 + 0.3, 0.3, 0.3);
            assert_ok(rg_body_set_velocity(w, hammer, v2(0, -speeds[k])));
            for (int i = 0; i < 120; i++) {
                assert_ok(rg_world_step(w, (rg_real)DT));
                assert_true(PY(w, ball) >= 0.005 + 0.27 - SLOP);
            }
            rg_world_destroy(w);
        }
    }
}

/* 1,000 scenes of ten boxes and circles (0.05-0.4 m) thrown down at up to 200 m/s or up at up
 * to 110 m/s around a one-way platform 2-32 cm thick (static, or kinematic drifting at up to
 * 1 m/s), under gravity for 4 s, where they land on and hit each other: none that started
 * above ends below it.  Before, 5 of these 10,000 bodies fell through (64 of 100,000 in a
 * longer run), each driven into the platform by a body landing on it. */
static void test_bodies_thrown_onto_a_one_way_platform_never_fall_through(void **state)
{
    (void)state;
    int fell = 0;
    for (int seed = 1; seed <= 1000; seed++) {
        uint32_t s = (uint32_t)seed * 31337u;
        rg_world *w = gravity_world(-G);
        assert_ok(rg_world_set_sleeping(w, seed % 2));
        double th = 0.02 + next_uniform(&s) * 0.3;
        int kinematic = next_uniform(&s) < 0.3;
        rg_body p = box_body(w, kinematic ? RG_BODY_KINEMATIC : RG_BODY_STATIC, 0, 0, 0, 5, th / 2);
        assert_ok(rg_body_set_one_way(w, p, v2(0, 1)));
        if (kinematic) {
            double vx = next_uniform(&s) * 2 - 1;
            assert_ok(rg_body_set_velocity(w, p, v2(vx, next_uniform(&s) * 2 - 1)));
        }
        rg_body b[10];
        int above[10];
        for (int i = 0; i < 10; i++) {
            above[i] = next_uniform(&s) < 0.6;
            double y = above[i] ? th / 2 + 0.5 + next_uniform(&s) * 5 : -th / 2 - 0.6 - next_uniform(&s) * 2;
            double m = 0.5 + next_uniform(&s) * 3, r = 0.05 + next_uniform(&s) * 0.35;
            if (next_uniform(&s) < 0.5)
                b[i] = circle_body(w, RG_BODY_DYNAMIC, m, -4 + i * 0.9, y, r);
            else
                b[i] = box_body(w, RG_BODY_DYNAMIC, m, -4 + i * 0.9, y, r, 0.05 + next_uniform(&s) * 0.35);
            double u = next_uniform(&s), fast = next_uniform(&s) < 0.3;
            double vy = above[i] ? -u * (fast ? 200 : 15) : 8 + u * (fast ? 100 : 10);
            double vx = next_uniform(&s) * 4 - 2;
            assert_ok(rg_body_set_velocity(w, b[i], v2(vx, vy)));
            assert_ok(rg_body_set_restitution(w, b[i], (rg_real)(next_uniform(&s) < 0.5 ? 0 : next_uniform(&s))));
        }
        step_n(w, 240, DT);
        for (int i = 0; i < 10; i++) {
            rg_vec2 h;
            assert_ok(rg_body_get_shape(w, b[i], NULL, &h));
            double top = PY(w, p) + th / 2, bottom = PY(w, b[i]) - (double)h.y;
            if (above[i] && fabs(PX(w, b[i]) - PX(w, p)) < 5 && PY(w, b[i]) < PY(w, p) && bottom < top - SLOP) {
                print_message("seed %d: body %d fell through\n", seed, i);
                fell++;
            }
        }
        rg_world_destroy(w);
    }
    assert_int_equal(fell, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_body_falling_onto_a_one_way_platform_rests_on_it),
        cmocka_unit_test(test_a_body_jumping_up_through_it_is_not_slowed_and_lands_on_top),
        cmocka_unit_test(test_a_body_that_barely_clears_the_top_lands_on_it),
        cmocka_unit_test(test_walking_into_its_side_while_overlapping_is_not_pushed),
        cmocka_unit_test(test_a_fast_body_from_above_lands_on_a_thin_platform),
        cmocka_unit_test(test_a_ball_driven_onto_a_thin_platform_by_a_hit_from_above_stays_on_it),
        cmocka_unit_test(test_bodies_thrown_onto_a_one_way_platform_never_fall_through),
        cmocka_unit_test(test_pass_through_drops_a_resting_body_and_it_collides_again_once_apart),
        cmocka_unit_test(test_sliding_across_the_seams_of_flush_tiles_never_falls_through),
        cmocka_unit_test(test_normals_in_any_direction),
        cmocka_unit_test(test_bad_input_is_rejected_and_changes_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
