/* test_touching.c: what touching means after a step.  A sensor touches where the step leaves
 * the shapes (a wall that stops a body short of a sensor behind it gives no event; a body
 * knocked into a sensor touches it in that step), or a body that crosses it within the step;
 * a pair the solve presses together touches in that step; and in random scenes with every
 * kind of change between steps, the events' ledger, the contact lists and the touching count
 * agree. */
#include "random_scene.h"

#define SLOP 0.005 /* the default contact slop (rg_world_get_contact_tuning) */

/* A ball (r 0.25) thrown at a static wall 0.2 m thick (x from 1.0 to 1.2) with a sensor
 * right behind it (x from 1.2 to 2.0): the wall stops it at x = 0.75, its edge 0.2 m short
 * of the sensor, at any speed.  So the sensor never touches it.  (When a sensor's touching
 * came from the step's free motion, the balls thrown at 20 m/s and more, whose free motion
 * ends inside the sensor, began touching it for a step.) */
static void test_a_wall_stops_a_ball_short_of_a_sensor_behind_it_and_no_event_comes(void **state)
{
    (void)state;
    const double speeds[] = {3, 10, 20, 30, 60, 120};
    for (size_t s = 0; s < sizeof speeds / sizeof speeds[0]; s++) {
        rg_world *w = gravity_world(0);
        box_body(w, RG_BODY_STATIC, 0, 1.1, 0, 0.1, 2);
        rg_body zone = box_body(w, RG_BODY_STATIC, 0, 1.6, 0, 0.4, 2);
        assert_ok(rg_body_set_sensor(w, zone, 1));
        rg_body ball = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 0, 0.25);
        assert_ok(rg_body_set_velocity(w, ball, v2((rg_real)speeds[s], 0)));
        int events = 0;
        for (int i = 0; i < 60; i++) {
            assert_ok(rg_world_step(w, (rg_real)DT));
            rg_contact_event ev[8];
            int32_t n = get_events(w, ev, 8);
            for (int k = 0; k < n; k++) events += ev[k].sensor;
            assert_true(PX(w, ball) <= 0.75 + SLOP);
        }
        if (events != 0) fail_msg("thrown at %g m/s: %d sensor events", speeds[s], events);
        rg_world_destroy(w);
    }
}

/* A ball (r 5 cm) sent at 1-256 m/s through a static sensor 5 cm thick, from 64 start phases:
 * the sensor reports exactly one begin and one end.  The begin comes in the step whose path
 * crosses the sensor (the ball's left edge starts it short of the sensor's far face and its
 * right edge ends it past the near face), with the normal along the path, whether or not the
 * ball ends that step inside; the pair touches after it, and it ends in a step that leaves
 * the ball past the sensor (after a crossing, the next).  (Until 2026-12-07 a sensor touched
 * only the shapes where each step left them: from 16 m/s the ball crossed it unseen at some
 * phases.) */
static void test_a_body_crossing_a_thin_sensor_within_a_step_touches_it_for_that_step(void **state)
{
    (void)state;
    for (double speed = 1; speed <= 256; speed *= 2) {
        for (int phase = 0; phase < 64; phase++) {
            rg_world *w = gravity_world(0);
            rg_body zone = box_body(w, RG_BODY_STATIC, 0, 5, 0, 0.025, 1);
            assert_ok(rg_body_set_sensor(w, zone, 1));
            rg_body ball = circle_body(w, RG_BODY_DYNAMIC, 1, speed * DT * phase / 64, 0, 0.05);
            assert_ok(rg_body_set_velocity(w, ball, v2((rg_real)speed, 0)));
            int begins = 0, ends = 0, touching = 0;
            for (int i = 0; (PX(w, ball) < 7 || touching) && i < 1000; i++) {
                double x0 = PX(w, ball);
                assert_ok(rg_world_step(w, (rg_real)DT));
                double x1 = PX(w, ball);
                rg_contact_event ev[8];
                int32_t n = get_events(w, ev, 8);
                for (int k = 0; k < n; k++) {
                    if (ev[k].kind == RG_CONTACT_BEGIN) {
                        begins++;
                        /* the path crossed the sensor in this step */
                        assert_true(x0 - 0.05 < 5.025 && x1 + 0.05 > 4.975);
                        assert_near(fabs((double)ev[k].normal.x), 1, 1e-6);
                    } else {
                        ends++;
                        assert_true(x1 - 0.05 > 5.025); /* apart where this step leaves it */
                    }
                    touching = ev[k].kind == RG_CONTACT_BEGIN;
                }
                assert_int_equal(rg_world_touching_count(w), touching);
            }
            if (begins != 1 || ends != 1) fail_msg("%g m/s, phase %d: %d begins, %d ends", speed, phase, begins, ends);
            rg_world_destroy(w);
        }
    }
}

/* The touching of pair (a, b) that the events of the last step leave, given it before. */
static int touching_after(rg_world *w, rg_body a, rg_body b, int was)
{
    rg_contact_event ev[16];
    int32_t n = get_events(w, ev, 16);
    for (int k = 0; k < n; k++) {
        if (!((ev[k].a == a && ev[k].b == b) || (ev[k].a == b && ev[k].b == a))) continue;
        assert_int_equal(ev[k].kind, was ? RG_CONTACT_END : RG_CONTACT_BEGIN);
        was = !was;
    }
    return was;
}

/* Elastic balls (r 0.25) in zero gravity: A at 6 m/s (0.1 m a step) toward B, at rest 1 cm
 * short of a sensor box (near enough for their pair to be found at rest: within the two
 * fat boxes' margins, 5 mm and 1 cm).  A meets B 0.2 of the way into step 7 and stops; B
 * leaves at 6 m/s and covers the 1 cm within that step, so it ends that step inside the
 * sensor, which its free motion (at rest) never would.  Step by step the pair touches
 * exactly when the shapes end the step overlapping, or, touching before, less than the slop
 * apart: B enters in the step of the hit, crosses and leaves. */
static void test_a_body_knocked_into_a_sensor_touches_it_in_that_step(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body zone = box_body(w, RG_BODY_STATIC, 0, 2, 0, 0.5, 0.5);
    assert_ok(rg_body_set_sensor(w, zone, 1));
    rg_body a = circle_body(w, RG_BODY_DYNAMIC, 1, 0.12, 0, 0.25);
    rg_body b = circle_body(w, RG_BODY_DYNAMIC, 1, 1.24, 0, 0.25);
    assert_ok(rg_body_set_restitution(w, a, 1));
    assert_ok(rg_body_set_restitution(w, b, 1));
    assert_ok(rg_body_set_velocity(w, a, v2(6, 0)));
    int touching = 0, entered = -1, left = -1;
    for (int i = 1; i <= 40; i++) {
        assert_ok(rg_world_step(w, (rg_real)DT));
        touching = touching_after(w, zone, b, touching);
        double gap = surface_gap(w, zone, b), tol = gap_rounding(w, zone, b);
        if (gap <= -tol || (touching && gap < SLOP - tol)) assert_int_equal(touching, 1);
        if (gap > tol && !(touching && gap < SLOP + tol)) assert_int_equal(touching, 0);
        if (touching && entered < 0) entered = i;
        if (!touching && entered > 0 && left < 0) left = i;
    }
    assert_int_equal(entered, 7);
    assert_true(left > entered);
    /* equal masses, elastic: the hit hands A's 6 m/s to B, within a few roundings of 6 */
    assert_near(VX(w, b), 6, 8 * 6 * REAL_EPS);
    rg_world_destroy(w);
}

/* A sensor blocks nothing, so a one-way normal changes nothing for it: balls crossing a
 * one-way sensor facing up, one rising through it from below and one falling through it from
 * above (zero gravity, 3 m/s), each give one begin and one end. */
static void test_a_one_way_sensor_reports_bodies_from_either_side(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body zone = box_body(w, RG_BODY_STATIC, 0, 0, 0, 1, 0.2);
    assert_ok(rg_body_set_sensor(w, zone, 1));
    assert_ok(rg_body_set_one_way(w, zone, v2(0, 1)));
    rg_body up = circle_body(w, RG_BODY_DYNAMIC, 1, -0.5, -0.6, 0.1);
    rg_body down = circle_body(w, RG_BODY_DYNAMIC, 1, 0.5, 0.6, 0.1);
    assert_ok(rg_body_set_velocity(w, up, v2(0, 3)));
    assert_ok(rg_body_set_velocity(w, down, v2(0, -3)));
    int begins[2] = {0, 0}, ends[2] = {0, 0};
    for (int i = 0; i < 40; i++) {
        assert_ok(rg_world_step(w, (rg_real)DT));
        rg_contact_event ev[8];
        int32_t n = get_events(w, ev, 8);
        for (int k = 0; k < n; k++) {
            int who = (ev[k].a == down || ev[k].b == down);
            if (ev[k].kind == RG_CONTACT_BEGIN) begins[who]++;
            else ends[who]++;
        }
    }
    assert_true(begins[0] == 1 && ends[0] == 1 && begins[1] == 1 && ends[1] == 1);
    assert_true(VY(w, up) == 3 && VY(w, down) == -3); /* no force acted: neither was slowed */
    rg_world_destroy(w);
}

/* Gravity 10: a box B at rest 1 cm above the floor (its free motion falls 2.8 mm in a step,
 * so alone it would reach the floor in its third step) and a box A falling onto it at 3 m/s
 * from 1 cm above.  A hits B early in the first step and drives it down onto the floor
 * within that step: the solve presses B onto the floor, so B touches it and stands on it
 * after that step (begin event and grounded flag), as the step ends with them in contact
 * (the floor's row holds the gap at or above zero; the slop bounds the overlap the
 * position pass leaves). */
static void test_a_body_pressed_onto_the_floor_by_a_landing_one_touches_it_in_that_step(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    rg_body fl = floor_of(w);
    rg_body b = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.26, 0.25, 0.25);
    rg_body a = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.77, 0.25, 0.25);
    assert_ok(rg_body_set_velocity(w, a, v2(0, -3)));
    assert_ok(rg_world_step(w, (rg_real)DT));
    assert_int_equal(touching_after(w, fl, b, 0), 1);
    assert_int_equal(flag(rg_body_is_grounded, w, b), 1);
    double gap = surface_gap(w, fl, b);
    assert_true(gap < SLOP && gap > -SLOP);
    rg_world_destroy(w);
}

/* ---- random scenes: the ledger of begins and ends against the world's own lists */


typedef struct ledger {
    rg_body a[4096], b[4096];
    int n;
    rg_body ba[2048], bb[2048]; /* the pairs the last call began */
    int nb;
} ledger;

static int ledger_find(const ledger *l, rg_body a, rg_body b)
{
    for (int i = 0; i < l->n; i++)
        if (l->a[i] == a && l->b[i] == b) return i;
    return -1;
}

/* Applies the last step's events: a begin of a pair not in the ledger, an end of one in it. */
static void ledger_apply(rg_world *w, ledger *l)
{
    static rg_contact_event ev[2048];
    int32_t n = get_events(w, ev, 2048);
    l->nb = 0;
    for (int k = 0; k < n; k++) {
        assert_true(ev[k].a < ev[k].b);
        if (ev[k].kind == RG_CONTACT_BEGIN) {
            l->ba[l->nb] = ev[k].a;
            l->bb[l->nb++] = ev[k].b;
        }
        int i = ledger_find(l, ev[k].a, ev[k].b);
        if (ev[k].kind == RG_CONTACT_BEGIN) {
            if (i >= 0) fail_msg("a begin of a pair that touches");
            assert_true(l->n < 4096);
            l->a[l->n] = ev[k].a;
            l->b[l->n++] = ev[k].b;
        } else {
            if (i < 0) fail_msg("an end of a pair that does not touch");
            l->n--;
            l->a[i] = l->a[l->n];
            l->b[i] = l->b[l->n];
        }
    }
}

/* Whether the last call began pair (a, b). */
static int ledger_began(const ledger *l, rg_body a, rg_body b)
{
    for (int i = 0; i < l->nb; i++)
        if (l->ba[i] == a && l->bb[i] == b) return 1;
    return 0;
}

/* After a step: the ledger holds the pairs of live bodies only, each body's contacts are its
 * pairs in the ledger, the touching count is the ledger's size, and a touching sensor pair's
 * shapes end the step less than the slop apart, unless the pair began in it (a body that
 * crossed the sensor within the step touches it for that step). */
static void ledger_check(rg_world *w, const ledger *l, const rg_body *bodies, int nb)
{
    assert_int_equal(rg_world_touching_count(w), l->n);
    int listed = 0;
    for (int i = 0; i < nb; i++) {
        rg_contact c[MAXB];
        int32_t n = rg_body_get_contacts(w, bodies[i], c, MAXB);
        assert_true(n >= 0 && n <= MAXB);
        for (int k = 0; k < n; k++) {
            rg_body lo = bodies[i] < c[k].other ? bodies[i] : c[k].other;
            rg_body hi = bodies[i] < c[k].other ? c[k].other : bodies[i];
            if (ledger_find(l, lo, hi) < 0) fail_msg("a contact the events never began");
            if (c[k].sensor) {
                double gap = surface_gap(w, lo, hi);
                if (!(gap < SLOP + gap_rounding(w, lo, hi)) && !ledger_began(l, lo, hi))
                    fail_msg("a touching sensor pair %.4f m apart, touching since an earlier step", gap);
            }
        }
        listed += n;
    }
    for (int i = 0; i < l->n; i++) assert_true(rg_body_is_valid(w, l->a[i]) && rg_body_is_valid(w, l->b[i]));
    assert_int_equal(listed, 2 * l->n); /* each pair from both sides */
}

/* 300 scenes of 300 steps (a quarter of them advances of a random frame time, which may take
 * no step or several) on one thread and on two workers: after every step the ledger of the
 * events agrees with the contact lists and the touching count, and no sensor touches a shape
 * that ends the step more than the slop away but in the step it crossed it. */
static void test_events_contacts_and_the_touching_count_agree_in_random_scenes(void **state)
{
    (void)state;
    static ledger l;
    rg_task_system tasks;
    rg_thread_pool *pool = random_pool(&tasks);
    for (int scene = 0; scene < 300; scene++) {
        uint32_t s = 7000u + (uint32_t)scene;
        rg_body bodies[MAXB];
        int nb;
        rg_world *w = random_world(scene, &s, scene % 2 ? &tasks : NULL, bodies, &nb);
        l.n = 0;
        for (int i = 0; i < 300; i++) {
            int changes = (int)(next_uniform(&s) * 3);
            for (int k = 0; k < changes; k++) random_change(w, &s, bodies, &nb);
            int32_t steps = 1;
            if (next_uniform(&s) < 0.25) assert_ok(rg_world_advance(w, (rg_real)(0.05 * next_uniform(&s)), &steps));
            else assert_ok(rg_world_step(w, (rg_real)DT));
            if (steps == 0) continue; /* no step: ends held for the next */
            ledger_apply(w, &l);
            ledger_check(w, &l, bodies, nb);
        }
        rg_world_destroy(w);
    }
    rg_thread_pool_destroy(pool);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_wall_stops_a_ball_short_of_a_sensor_behind_it_and_no_event_comes),
        cmocka_unit_test(test_a_body_crossing_a_thin_sensor_within_a_step_touches_it_for_that_step),
        cmocka_unit_test(test_a_body_knocked_into_a_sensor_touches_it_in_that_step),
        cmocka_unit_test(test_a_one_way_sensor_reports_bodies_from_either_side),
        cmocka_unit_test(test_a_body_pressed_onto_the_floor_by_a_landing_one_touches_it_in_that_step),
        cmocka_unit_test(test_events_contacts_and_the_touching_count_agree_in_random_scenes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
