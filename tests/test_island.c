/* test_island.c: islands and sleeping: falling asleep, costing nothing asleep, waking when touched,
 * pushed or left without support, springs joining islands, kinematic and static bodies. */
#include "testutil.h"

static void test_a_body_at_rest_sleeps_and_wakes_when_pushed(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    floor_of(w);
    rg_body b = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5, 0.5);
    step_n(w, 60, DT);
    assert_int_equal(flag(rg_body_is_awake, w, b), 0);
    assert_int_equal(rg_world_awake_body_count(w), 0);
    assert_int_equal(flag(rg_body_is_grounded, w, b), 1); /* kept while asleep */
    /* each way of pushing it wakes it */
    for (int how = 0; how < 5; how++) {
        step_n(w, 60, DT);
        assert_int_equal(flag(rg_body_is_awake, w, b), 0);
        switch (how) {
        case 0: assert_ok(rg_body_apply_force(w, b, v2(1, 0))); break;
        case 1: assert_ok(rg_body_apply_impulse(w, b, v2(0.1f, 0))); break;
        case 2: assert_ok(rg_body_set_velocity(w, b, v2(0.2f, 0))); break;
        case 3: assert_ok(rg_body_set_position(w, b, v2(PX(w, b), 0.5))); break;
        default: assert_ok(rg_body_wake(w, b)); break;
        }
        assert_int_equal(flag(rg_body_is_awake, w, b), 1);
    }
    rg_world_destroy(w);
}

static void test_sleeping_bodies_do_not_move_and_cost_no_steps(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    floor_of(w);
    rg_body b[10];
    for (int i = 0; i < 10; i++) b[i] = box_body(w, RG_BODY_DYNAMIC, 1, i * 1.5, 0.5, 0.5, 0.5);
    step_n(w, 60, DT);
    assert_int_equal(rg_world_awake_body_count(w), 0);
    rg_vec2 p[10];
    for (int i = 0; i < 10; i++) p[i] = pos_of(w, b[i]);
    step_n(w, 100, DT);
    for (int i = 0; i < 10; i++) {
        assert_true(pos_of(w, b[i]).x == p[i].x && pos_of(w, b[i]).y == p[i].y);
        assert_near(VY(w, b[i]), 0, 0);
    }
    rg_world_destroy(w);
}

static void test_a_body_landing_on_a_sleeping_pile_wakes_it(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    floor_of(w);
    rg_body base = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5, 0.5);
    rg_body mid = box_body(w, RG_BODY_DYNAMIC, 1, 0, 1.5, 0.5, 0.5);
    step_n(w, 60, DT);
    assert_int_equal(flag(rg_body_is_awake, w, base), 0);
    rg_body drop = circle_body(w, RG_BODY_DYNAMIC, 5, 0, 6, 0.5);
    int woke = 0;
    for (int i = 0; i < 120; i++) {
        assert_ok(rg_world_step(w, (rg_real)DT));
        woke |= flag(rg_body_is_awake, w, mid) && flag(rg_body_is_awake, w, base);
    }
    assert_true(woke);
    assert_true(PY(w, drop) > 2.4); /* it rests on the pile, which held */
    assert_near(PY(w, base), 0.5, 0.01);
    rg_world_destroy(w);
}

static void test_removing_or_moving_a_support_wakes_what_rests_on_it(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    rg_body shelf = box_body(w, RG_BODY_STATIC, 0, 0, -0.5, 3, 0.5);
    rg_body b = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5, 0.5);
    step_n(w, 60, DT);
    assert_int_equal(flag(rg_body_is_awake, w, b), 0);
    assert_ok(rg_body_set_position(w, shelf, v2(0, -3))); /* the static shelf drops away */
    assert_int_equal(flag(rg_body_is_awake, w, b), 1);
    step_n(w, 60, DT);
    assert_true(PY(w, b) < -1.9 && PY(w, b) > -2.1); /* fell onto the shelf's new place */
    /* a sleeping body on a dynamic support that is destroyed */
    rg_body b2 = box_body(w, RG_BODY_DYNAMIC, 1, 10, 0.5, 0.5, 0.5);
    box_body(w, RG_BODY_STATIC, 0, 10, -1.5, 3, 0.5);
    rg_body support = box_body(w, RG_BODY_DYNAMIC, 1, 10, -0.5, 0.5, 0.5);
    step_n(w, 60, DT);
    assert_int_equal(flag(rg_body_is_awake, w, b2), 0);
    assert_ok(rg_body_destroy(w, support));
    assert_int_equal(flag(rg_body_is_awake, w, b2), 1);
    /* a body teleported into a sleeping one wakes it */
    step_n(w, 90, DT);
    assert_int_equal(flag(rg_body_is_awake, w, b2), 0);
    rg_body intruder = circle_body(w, RG_BODY_DYNAMIC, 1, 30, 30, 0.5);
    assert_ok(rg_body_set_position(w, intruder, v2(10, PY(w, b2) + 0.8)));
    assert_ok(rg_world_step(w, (rg_real)DT));
    assert_int_equal(flag(rg_body_is_awake, w, b2), 1);
    rg_world_destroy(w);
}

static void test_disabling_sleep_wakes_everything_and_thresholds_apply(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    floor_of(w);
    rg_body b = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5, 0.5);
    step_n(w, 60, DT);
    assert_int_equal(rg_world_awake_body_count(w), 0);
    assert_ok(rg_world_set_sleeping(w, 0));
    assert_int_equal(rg_world_awake_body_count(w), 1);
    step_n(w, 120, DT);
    assert_int_equal(flag(rg_body_is_awake, w, b), 1);
    /* sleep after 2 s of rest, not 0.5 */
    assert_ok(rg_world_set_sleeping(w, 1));
    assert_ok(rg_world_set_sleep_thresholds(w, 0.05f, 2));
    step_n(w, 100, DT);
    assert_int_equal(flag(rg_body_is_awake, w, b), 1);
    step_n(w, 30, DT);
    assert_int_equal(flag(rg_body_is_awake, w, b), 0);
    /* a sleep time shorter than a step: asleep after one step at rest */
    assert_ok(rg_world_set_sleep_thresholds(w, 0.05f, 0.001f));
    assert_ok(rg_body_wake(w, b));
    assert_ok(rg_world_step(w, (rg_real)DT));
    assert_int_equal(flag(rg_body_is_awake, w, b), 0);
    rg_world_destroy(w);
}

/* Springs join islands: two boxes tied together rest and sleep together; a box tied to a
 * body without a shape that keeps moving never sleeps. */
static void test_springs_join_islands(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    floor_of(w);
    rg_body a = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5, 0.5), b = box_body(w, RG_BODY_DYNAMIC, 1, 3, 0.5, 0.5, 0.5);
    uint64_t sp;
    assert_ok(rg_spring_create(w, a, b, v2(0, 0), 3, 10, 1, &sp));
    step_n(w, 60, DT);
    assert_int_equal(flag(rg_body_is_awake, w, a), 0);
    assert_int_equal(flag(rg_body_is_awake, w, b), 0);
    /* waking one wakes the other: they are one island */
    assert_ok(rg_body_wake(w, a));
    assert_int_equal(flag(rg_body_is_awake, w, b), 1);
    /* a box tied to a swinging weight without a shape stays awake */
    rg_body c = box_body(w, RG_BODY_DYNAMIC, 1, 10, 0.5, 0.5, 0.5);
    rg_body weight = make_body(w, 1, 12, 3);
    assert_ok(rg_body_set_gravity_scale(w, weight, 0));
    assert_ok(rg_body_set_velocity(w, weight, v2(0, 1)));
    uint64_t sp2;
    assert_ok(rg_spring_create(w, c, weight, v2(0, 0), 2, 0.5f, 0, &sp2));
    step_n(w, 120, DT);
    assert_int_equal(flag(rg_body_is_awake, w, c), 1);
    rg_world_destroy(w);
}

static void test_kinematic_and_static_bodies_never_sleep_and_a_moving_platform_wakes_riders(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    rg_body k = box_body(w, RG_BODY_KINEMATIC, 0, 0, -0.5, 3, 0.5);
    rg_body rider = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5, 0.5);
    step_n(w, 60, DT);
    assert_int_equal(flag(rg_body_is_awake, w, k), 1);
    assert_int_equal(flag(rg_body_is_awake, w, rider), 0);
    assert_ok(rg_body_set_velocity(w, k, v2(0, 1))); /* the platform rises */
    step_n(w, 30, DT);
    assert_int_equal(flag(rg_body_is_awake, w, rider), 1);
    assert_true(PY(w, rider) > 0.9); /* carried up */
    assert_ok(rg_body_set_velocity(w, k, v2(0, -1))); /* and goes down: the rider follows */
    step_n(w, 60, DT);
    assert_true(PY(w, rider) < 0.6);
    rg_world_destroy(w);
}

/* The slop: the penetration the solver leaves in a resting contact (rg_world_set_contact_tuning). */
static double slop_of(rg_world *w)
{
    rg_real slop, bias, push, threshold;
    assert_ok(rg_world_get_contact_tuning(w, &slop, &bias, &push, &threshold));
    return (double)slop;
}

/* The step that wakes a sleeping stack solves the stack's own contacts, which the
 * narrowphase of that step saw between bodies it took for the ground: a 5 kg box landing at
 * some 8 m/s drives no box into another, nor the stack into the floor, deeper than the slop,
 * as when the stack is awake (before, the middle box went 35 mm into the one below). */
static void test_the_step_that_wakes_a_stack_holds_it(void **state)
{
    (void)state;
    for (int sleeping = 1; sleeping >= 0; sleeping--) {
        rg_world *w = gravity_world(-10);
        assert_ok(rg_world_set_sleeping(w, sleeping));
        floor_of(w);
        rg_body base = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5, 0.5);
        rg_body mid = box_body(w, RG_BODY_DYNAMIC, 1, 0, 1.5, 0.5, 0.5);
        step_n(w, 60, DT);
        assert_int_equal(flag(rg_body_is_awake, w, mid), !sleeping);
        rg_body drop = box_body(w, RG_BODY_DYNAMIC, 5, 0, 6, 0.5, 0.5);
        double slop = slop_of(w);
        int landed = 0;
        for (int i = 0; i < 120; i++) {
            assert_ok(rg_world_step(w, (rg_real)DT));
            landed |= PY(w, drop) < 2.6;
            assert_true(PY(w, base) >= 0.5 - slop);
            assert_true(PY(w, mid) - PY(w, base) >= 1 - slop);
            assert_true(PY(w, drop) - PY(w, mid) >= 1 - slop);
        }
        assert_true(landed);
        rg_world_destroy(w);
    }
}

/* A kinematic body driven into a sleeping box wakes it and pushes it within the same step:
 * they never overlap deeper than the slop (before, the waking step let the kinematic body
 * travel its whole step, 0.1 m at 6 m/s, into the box). */
static void test_a_kinematic_body_pushes_the_sleeping_box_it_wakes(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    floor_of(w);
    rg_body box = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5, 0.5);
    rg_body k = box_body(w, RG_BODY_KINEMATIC, 0, -3, 0.6, 0.5, 0.5);
    step_n(w, 60, DT);
    assert_int_equal(flag(rg_body_is_awake, w, box), 0);
    assert_ok(rg_body_set_velocity(w, k, v2(6, 0)));
    double slop = slop_of(w);
    for (int i = 0; i < 30; i++) {
        assert_ok(rg_world_step(w, (rg_real)DT));
        assert_true((PX(w, k) + 0.5) - (PX(w, box) - 0.5) <= slop);
    }
    assert_int_equal(flag(rg_body_is_awake, w, box), 1);
    assert_true(PX(w, box) > 0.5); /* pushed along */
    rg_world_destroy(w);
}

/* A row of sleeping balls 1 mm apart, hit at one end by an elastic ball (restitution 1, no
 * gravity), passes the hit on in the step of the impact.  Before, only the ball hit woke
 * (the others did not touch it yet), the solve took the sleeping ones for the ground, and the
 * striker came back at 3.9 m/s as off a wall: momentum was not conserved.  Now a sleeping
 * body in a solved pair with a pusher wakes with it.  Also with the first ball created awake
 * beside the sleeping row.  Contacts give equal and opposite impulses to equal masses, so the
 * total momentum stays 4 kg m/s to rounding: some 2000 float roundings (rows x iterations x
 * steps in contact) of velocities below 4 m/s, each within 2^-22 * 4, keep it within 2e-3;
 * the impulses along the row only push the last ball forward, so it moves. */
static void test_a_sleeping_row_hit_at_one_end_passes_the_hit_on(void **state)
{
    (void)state;
    for (int fresh = 0; fresh <= 1; fresh++) {
        rg_world *w = gravity_world(0);
        rg_body ball[5];
        for (int i = fresh; i < 5; i++) {
            ball[i] = circle_body(w, RG_BODY_DYNAMIC, 1, i * 1.001, 0, 0.5);
            assert_ok(rg_body_set_restitution(w, ball[i], 1));
        }
        step_n(w, 60, DT);
        assert_int_equal(flag(rg_body_is_awake, w, ball[4]), 0);
        if (fresh) {
            ball[0] = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 0, 0.5);
            assert_ok(rg_body_set_restitution(w, ball[0], 1));
        }
        rg_body striker = circle_body(w, RG_BODY_DYNAMIC, 1, -1.2, 0, 0.5);
        assert_ok(rg_body_set_restitution(w, striker, 1));
        assert_ok(rg_body_set_velocity(w, striker, v2(4, 0)));
        step_n(w, 60, DT);
        double p = VX(w, striker);
        for (int i = 0; i < 5; i++) p += VX(w, ball[i]);
        assert_true(fabs(p - 4) <= 2e-3);
        assert_true(VX(w, ball[4]) > 0);
        rg_world_destroy(w);
    }
}

/* Contacts conserve momentum, sleeping on or off: 400 random scenes without gravity or
 * static bodies (20-79 boxes and circles of 0.1-5.1 kg, most at rest, some thrown at up to
 * 5 m/s or 200 m/s, three kicked at step 150; random restitution and friction), 300 steps
 * each.  Sleeping on, with a speed threshold of 1e-9 m/s, so that falling asleep stops
 * nothing that moves (the momentum it could take is below 80 * 5.1 kg * 1e-9 m/s).  Each
 * contact impulse adds P to one body and takes it from the other, so the total stays as
 * given to rounding: some 3e5 velocity updates a scene (rows x iterations x steps), each
 * rounded within 2^-24 of the momentum, add up like a random walk to some
 * sqrt(3e5) * 2^-24 = 3.3e-5 of the sum of |m v|; 1e-4 allows three times that.  Before a
 * sleeping body in a solved pair woke (8df20da's library), seed 43 lost 0.12% of it at step
 * 164 to sleeping bodies that the solve took for the ground. */
static void test_contacts_conserve_momentum_in_random_scenes_asleep_or_awake(void **state)
{
    (void)state;
    double worst = 0;
    for (int seed = 1; seed <= 400; seed++) {
        uint32_t s = (uint32_t)seed * 7919u;
        rg_world *w;
        assert_ok(rg_world_create(&w));
        assert_ok(rg_world_set_sleeping(w, seed % 2));
        assert_ok(rg_world_set_sleep_thresholds(w, (rg_real)1e-9, (rg_real)0.5));
        int n = 20 + (int)(next_uniform(&s) * 60);
        rg_body b[80];
        double m[80], px = 0, py = 0, scale = 0;
        for (int i = 0; i < n; i++) {
            m[i] = 0.1 + next_uniform(&s) * 5;
            double x = next_uniform(&s) * 8, y = next_uniform(&s) * 8;
            int round = next_uniform(&s) < 0.5;
            double hw = 0.1 + next_uniform(&s) * 0.4, hh = round ? hw : 0.1 + next_uniform(&s) * 0.4;
            b[i] = round ? circle_body(w, RG_BODY_DYNAMIC, m[i], x, y, hw) : box_body(w, RG_BODY_DYNAMIC, m[i], x, y, hw, hh);
            assert_ok(rg_body_set_restitution(w, b[i], (rg_real)(next_uniform(&s) < 0.5 ? 0 : next_uniform(&s))));
            assert_ok(rg_body_set_friction(w, b[i], (rg_real)next_uniform(&s)));
            double moving = next_uniform(&s), u = moving < 0.7 ? 0 : next_uniform(&s);
            double speed = moving < 0.7 ? 0 : u * (next_uniform(&s) < 0.2 ? 200 : 5);
            double a = next_uniform(&s) * 6.283;
            assert_ok(rg_body_set_velocity(w, b[i], v2(speed * cos(a), speed * sin(a))));
        }
        for (int i = 0; i < n; i++) {
            px += m[i] * VX(w, b[i]);
            py += m[i] * VY(w, b[i]);
            scale += m[i] * hypot(VX(w, b[i]), VY(w, b[i]));
        }
        for (int step = 0; step < 300; step++) {
            if (step == 150) {
                for (int k = 0; k < 3; k++) {
                    int i = (int)(next_uniform(&s) * n);
                    double speed = next_uniform(&s) * 20, a = next_uniform(&s) * 6.283;
                    double jx = m[i] * speed * cos(a), jy = m[i] * speed * sin(a);
                    assert_ok(rg_body_apply_impulse(w, b[i], v2(jx, jy)));
                    px += jx;
                    py += jy;
                    scale += m[i] * speed;
                }
            }
            assert_ok(rg_world_step(w, (rg_real)DT));
            double qx = 0, qy = 0;
            for (int i = 0; i < n; i++) {
                qx += m[i] * VX(w, b[i]);
                qy += m[i] * VY(w, b[i]);
            }
            double err = hypot(qx - px, qy - py) / scale;
            if (err > worst) worst = err;
            if (err > 1e-4) print_message("seed %d step %d: momentum off by %g of its scale\n", seed, step, err);
            assert_true(err <= 1e-4);
        }
        rg_world_destroy(w);
    }
    print_message("worst momentum error over the scenes: %.2e of the sum of |m v|\n", worst);
}

/* A box asleep on the floor feels a change of gravity, wind or its gravity scale: it wakes
 * and moves (gravity flipped up, or its scale made -1: it rises; wind of 20 N across, beyond
 * friction's 0.6 * 10 N: it slides), and the same gravity set again wakes nothing.  (Until
 * 2026-12-07 the sleeping box, not integrated, ignored all three: a platformer's gravity
 * flip left every resting crate on the floor.) */
static void test_a_change_of_gravity_wind_or_gravity_scale_wakes_sleeping_bodies(void **state)
{
    (void)state;
    for (int change = 0; change < 3; change++) {
        rg_world *w = gravity_world(-10);
        floor_of(w);
        rg_body c = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.25, 0.25, 0.25);
        step_n(w, 120, DT);
        assert_int_equal(flag(rg_body_is_awake, w, c), 0);
        assert_ok(rg_world_set_gravity(w, v2(0, -10)));
        assert_int_equal(flag(rg_body_is_awake, w, c), 0);
        if (change == 0) assert_ok(rg_world_set_gravity(w, v2(0, 10)));
        if (change == 1) assert_ok(rg_world_set_wind(w, v2(20, 0)));
        if (change == 2) assert_ok(rg_body_set_gravity_scale(w, c, -1));
        assert_int_equal(flag(rg_body_is_awake, w, c), 1);
        step_n(w, 30, DT);
        if (change == 1) assert_true(PX(w, c) > 1); /* (20 - 6) N on 1 kg for 0.5 s: some 1.8 m */
        else assert_true(PY(w, c) - 0.25 > 1); /* 10 m/s^2 up for 0.5 s: some 1.3 m */
        rg_world_destroy(w);
    }
}

/* A box asleep on the floor held by friction (0.6 * 10 N) against 5 N of wind slides once
 * what held it changes: its friction or the floor's made 0 (the pair's is their geometric
 * mean), or its mass halved (friction 3 N).  Each wakes it.  (Until 2026-12-07 it slept on.) */
static void test_a_change_of_friction_or_mass_wakes_a_body_friction_held_at_rest(void **state)
{
    (void)state;
    for (int change = 0; change < 3; change++) {
        rg_world *w = gravity_world(-10);
        assert_ok(rg_world_set_wind(w, v2(5, 0)));
        rg_body fl = floor_of(w);
        rg_body c = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.25, 0.25, 0.25);
        step_n(w, 120, DT);
        assert_int_equal(flag(rg_body_is_awake, w, c), 0);
        double x0 = PX(w, c);
        if (change == 0) assert_ok(rg_body_set_friction(w, c, 0));
        if (change == 1) assert_ok(rg_body_set_friction(w, fl, 0));
        if (change == 2) assert_ok(rg_body_set_mass(w, c, 0.5));
        assert_int_equal(flag(rg_body_is_awake, w, c), 1);
        step_n(w, 30, DT);
        /* 5 N on 1 kg, or 5 - 3 N on 0.5 kg: 5 or 4 m/s^2 for 0.5 s, some 0.6 or 0.5 m */
        assert_true(PX(w, c) - x0 > 0.4);
        rg_world_destroy(w);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_change_of_friction_or_mass_wakes_a_body_friction_held_at_rest),
        cmocka_unit_test(test_a_change_of_gravity_wind_or_gravity_scale_wakes_sleeping_bodies),
        cmocka_unit_test(test_a_body_at_rest_sleeps_and_wakes_when_pushed),
        cmocka_unit_test(test_sleeping_bodies_do_not_move_and_cost_no_steps),
        cmocka_unit_test(test_a_body_landing_on_a_sleeping_pile_wakes_it),
        cmocka_unit_test(test_removing_or_moving_a_support_wakes_what_rests_on_it),
        cmocka_unit_test(test_disabling_sleep_wakes_everything_and_thresholds_apply),
        cmocka_unit_test(test_springs_join_islands),
        cmocka_unit_test(test_kinematic_and_static_bodies_never_sleep_and_a_moving_platform_wakes_riders),
        cmocka_unit_test(test_the_step_that_wakes_a_stack_holds_it),
        cmocka_unit_test(test_a_kinematic_body_pushes_the_sleeping_box_it_wakes),
        cmocka_unit_test(test_a_sleeping_row_hit_at_one_end_passes_the_hit_on),
        cmocka_unit_test(test_contacts_conserve_momentum_in_random_scenes_asleep_or_awake),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
