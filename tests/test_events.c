/* test_events.c: contact events: one begin and one end per touch, their order, ends reported between
 * steps, the events of an advance, and their buffer's memory. */
#include "mem.h" /* mem_default_alloc: malloc and free, as a world's allocator */
#include "testutil.h"

/* A ball (r 0.1) at 6 m/s, 0.1 m per 1/60 s step, toward a sensor 4 cm thick whose near face
 * is 8 cm ahead of the ball: its free motion ends overlapping the sensor after steps 1, 2
 * and 3, and 8 cm past it after step 4.  So one begin in step 1 and one end in step 4. */
static rg_world *sensor_gate(rg_alloc_fn alloc, void *user, rg_body *gate, rg_body *ball)
{
    rg_world *w;
    assert_ok(rg_world_create_with_allocator(alloc, user, &w));
    *gate = box_body(w, RG_BODY_STATIC, 0, 0, 0, 0.02, 1);
    assert_ok(rg_body_set_sensor(w, *gate, 1));
    *ball = circle_body(w, RG_BODY_DYNAMIC, 1, -0.2, 0, 0.1);
    assert_ok(rg_body_set_velocity(w, *ball, v2(6, 0)));
    assert_ok(rg_world_set_fixed_step(w, (rg_real)DT, 8));
    return w;
}


static void assert_gate_event(const rg_contact_event *e, int32_t kind, rg_body gate, rg_body ball)
{
    assert_int_equal(e->kind, kind);
    assert_int_equal(e->sensor, 1);
    assert_true(e->a == (gate < ball ? gate : ball) && e->b == (gate < ball ? ball : gate));
}

static void test_event_arguments_are_checked(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_contact_event ev;
    assert_int_equal(rg_world_get_contact_events(w, NULL, 0), 0);
    assert_int_equal(rg_world_get_contact_events(w, &ev, -1), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_get_contact_events(w, NULL, 1), RG_ERR_INVALID_ARGUMENT);
    rg_world_destroy(w);
}

static void test_a_pair_that_touches_once_gives_one_begin_and_one_end(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body wall = box_body(w, RG_BODY_STATIC, 0, 3, 0, 0.5, 2);
    rg_body ball = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 0.3, 0.5);
    assert_ok(rg_body_set_restitution(w, ball, 1));
    assert_ok(rg_body_set_velocity(w, ball, v2(5, 0)));
    int begins = 0, ends = 0;
    for (int i = 0; i < 120; i++) {
        assert_ok(rg_world_step(w, (rg_real)DT));
        rg_contact_event ev[4];
        int32_t n = get_events(w, ev, 4);
        for (int k = 0; k < n; k++) {
            assert_true(ev[k].a < ev[k].b);
            assert_true((ev[k].a == wall && ev[k].b == ball) || (ev[k].a == ball && ev[k].b == wall));
            assert_int_equal(ev[k].sensor, 0);
            /* normal from a toward b: the ball is to the wall's left */
            double sx = ev[k].a == wall ? -1 : 1;
            assert_near(ev[k].normal.x, sx, 1e-6);
            assert_near(ev[k].normal.y, 0, 1e-6);
            assert_near(ev[k].point.x, 2.5, 0.1); /* on the wall's face */
            assert_near(ev[k].point.y, 0.3, 1e-5);
            assert_near(ev[k].depth, 0, 1e-6);
            assert_near(ev[k].speed, 5, 1e-4); /* approach speed when it began */
            if (ev[k].kind == RG_CONTACT_BEGIN) begins++;
            if (ev[k].kind == RG_CONTACT_END) ends++;
        }
    }
    assert_int_equal(begins, 1);
    assert_int_equal(ends, 1);
    assert_near(VX(w, ball), -5, 1e-4); /* bounced back elastically */
    rg_world_destroy(w);
}

static void test_events_are_sorted_and_capacity_only_limits_the_copy(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    rg_body fl = floor_of(w);
    for (int i = 0; i < 6; i++) circle_body(w, RG_BODY_DYNAMIC, 1, i * 2.0, 0.55, 0.5);
    rg_contact_event ev[16];
    int32_t n = 0;
    for (int i = 0; i < 10 && n == 0; i++) {
        assert_ok(rg_world_step(w, (rg_real)DT));
        n = get_events(w, ev, 16);
    }
    assert_int_equal(n, 6);
    for (int k = 0; k < n; k++) {
        assert_int_equal(ev[k].kind, RG_CONTACT_BEGIN);
        assert_true(ev[k].a == fl || ev[k].b == fl);
        if (k > 0) assert_true(ev[k - 1].a < ev[k].a || (ev[k - 1].a == ev[k].a && ev[k - 1].b < ev[k].b));
    }
    /* a smaller buffer gets the first ones; the count is the full count */
    rg_contact_event few[2];
    assert_int_equal(rg_world_get_contact_events(w, few, 2), 6);
    assert_memory_equal(few, ev, sizeof few);
    assert_int_equal(rg_world_get_contact_events(w, NULL, 0), 6);
    /* the next step has no news */
    assert_ok(rg_world_step(w, (rg_real)DT));
    assert_int_equal(rg_world_get_contact_events(w, NULL, 0), 0);
    assert_int_equal(rg_world_touching_count(w), 6);
    rg_world_destroy(w);
}

static void test_destroying_a_body_ends_its_contacts_with_an_end_event(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    rg_body fl = floor_of(w);
    rg_body a = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5);
    rg_body top = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 1.5, 0.5);
    step_n(w, 10, DT);
    assert_int_equal(rg_world_touching_count(w), 2);
    assert_ok(rg_body_destroy(w, a));
    assert_int_equal(rg_world_touching_count(w), 0);
    assert_ok(rg_world_step(w, (rg_real)DT));
    rg_contact_event ev[8];
    int32_t n = get_events(w, ev, 8);
    int ends = 0;
    for (int k = 0; k < n; k++) {
        if (ev[k].kind == RG_CONTACT_END) {
            ends++;
            assert_true(ev[k].a == a || ev[k].b == a); /* the destroyed body's handle, now stale */
        }
    }
    assert_int_equal(ends, 2);
    assert_int_equal(rg_body_is_valid(w, a), 0);
    /* the top ball falls onto the floor: a new begin later */
    int begun = 0;
    for (int i = 0; i < 60 && !begun; i++) {
        assert_ok(rg_world_step(w, (rg_real)DT));
        n = get_events(w, ev, 8);
        for (int k = 0; k < n; k++)
            begun |= ev[k].kind == RG_CONTACT_BEGIN && ((ev[k].a == fl && ev[k].b == top) || (ev[k].a == top && ev[k].b == fl));
    }
    assert_true(begun);
    rg_world_destroy(w);
}

static void test_clearing_a_shape_or_changing_the_filter_ends_contacts(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    floor_of(w);
    rg_body a = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5);
    rg_body c = circle_body(w, RG_BODY_DYNAMIC, 1, 3, 0.5, 0.5);
    step_n(w, 5, DT);
    assert_int_equal(rg_world_touching_count(w), 2);
    assert_ok(rg_body_clear_shape(w, a));
    assert_ok(rg_body_set_filter(w, c, 2, 0xFFFFFFFFu & ~1u)); /* rejects the floor (category 1) */
    assert_int_equal(rg_world_touching_count(w), 0);
    assert_ok(rg_world_step(w, (rg_real)DT));
    rg_contact_event ev[8];
    int32_t n = get_events(w, ev, 8);
    assert_int_equal(n, 2);
    assert_int_equal(ev[0].kind, RG_CONTACT_END);
    assert_int_equal(ev[1].kind, RG_CONTACT_END);
    step_n(w, 30, DT);
    assert_true(PY(w, a) < 0 && PY(w, c) < 0); /* both fall through the floor now */
    rg_world_destroy(w);
}

static void test_an_end_and_a_new_begin_of_one_pair_come_end_first(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    rg_body fl = floor_of(w);
    rg_body b = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5, 0.5);
    step_n(w, 5, DT);
    assert_int_equal(rg_world_touching_count(w), 1);
    /* off and on again between two steps: the contact ends now and begins anew */
    assert_ok(rg_body_set_filter(w, b, 1, 0));
    assert_ok(rg_body_set_filter(w, b, 1, 0xFFFFFFFFu));
    assert_ok(rg_world_step(w, (rg_real)DT));
    rg_contact_event ev[4];
    assert_int_equal(get_events(w, ev, 4), 2);
    assert_int_equal(ev[0].kind, RG_CONTACT_END);
    assert_int_equal(ev[1].kind, RG_CONTACT_BEGIN);
    assert_true(ev[0].a == ev[1].a && ev[0].b == ev[1].b);
    assert_true(ev[0].a == (fl < b ? fl : b));
    rg_world_destroy(w);
}

/* A slow frame: one advance takes four steps, the ball enters the sensor in the first and
 * leaves it in the fourth.  Both events are there, in step order (a step's own order puts
 * an end before a begin, so a sort over the whole advance would not). */
static void test_an_advance_reports_the_events_of_every_step_it_took(void **state)
{
    (void)state;
    rg_body gate, ball;
    rg_world *w = sensor_gate(mem_default_alloc, NULL, &gate, &ball);
    int32_t steps = 0;
    assert_ok(rg_world_advance(w, (rg_real)(4.5 * DT), &steps));
    assert_int_equal(steps, 4);
    rg_contact_event ev[4];
    assert_int_equal(get_events(w, ev, 4), 2);
    assert_gate_event(&ev[0], RG_CONTACT_BEGIN, gate, ball);
    assert_gate_event(&ev[1], RG_CONTACT_END, gate, ball);
    /* the same through single steps, one event in the first and one in the fourth */
    rg_body gate2, ball2;
    rg_world *w2 = sensor_gate(mem_default_alloc, NULL, &gate2, &ball2);
    int32_t per_step[4];
    for (int i = 0; i < 4; i++) {
        assert_ok(rg_world_step(w2, (rg_real)DT));
        per_step[i] = get_events(w2, NULL, 0);
    }
    assert_int_equal(per_step[0], 1);
    assert_int_equal(per_step[1], 0);
    assert_int_equal(per_step[2], 0);
    assert_int_equal(per_step[3], 1);
    rg_world_destroy(w2);
    /* an advance that takes no step has no events to report; a direct step reports its own */
    assert_ok(rg_world_advance(w, (rg_real)(0.25 * DT), &steps));
    assert_int_equal(steps, 0);
    assert_int_equal(get_events(w, NULL, 0), 0);
    rg_world_destroy(w);
}

/* Advances that keep producing events reach a buffer size and stop allocating. */
static void test_busy_advances_do_not_allocate_in_steady_state(void **state)
{
    (void)state;
    test_alloc ta = {0, 0, 0, 0};
    rg_world *w;
    assert_ok(rg_world_create_with_allocator(test_alloc_fn, &ta, &w));
    assert_ok(rg_world_set_fixed_step(w, (rg_real)DT, 8));
    /* balls shuttling elastically between two walls 1.2 m apart, touching one every 7 steps */
    box_body(w, RG_BODY_STATIC, 0, -1.1, 0, 0.5, 20);
    box_body(w, RG_BODY_STATIC, 0, 1.1, 0, 0.5, 20);
    for (int i = 0; i < 30; i++) {
        rg_body b = circle_body(w, RG_BODY_DYNAMIC, 1, -0.3 + 0.02 * i, i * 1.0 - 15, 0.2);
        assert_ok(rg_body_set_restitution(w, b, 1));
        assert_ok(rg_body_set_friction(w, b, 0));
        assert_ok(rg_body_set_velocity(w, b, v2(3, 0)));
    }
    long total = 0;
    for (int i = 0; i < 60; i++) {
        int32_t steps;
        assert_ok(rg_world_advance(w, (rg_real)(8 * DT), &steps));
        total += get_events(w, NULL, 0);
    }
    assert_true(total > 100);
    long before = ta.calls;
    for (int i = 0; i < 60; i++) {
        int32_t steps;
        assert_ok(rg_world_advance(w, (rg_real)(8 * DT), &steps));
        assert_true(get_events(w, NULL, 0) > 0);
    }
    assert_int_equal(ta.calls, before);
    rg_world_destroy(w);
    assert_int_equal(ta.live_blocks, 0);
}

/* An advance whose event buffer cannot grow stops after the steps whose events it holds; the
 * time of the others stays in the accumulator and the next advance takes them.  Nothing is
 * lost, and the end state is the one of four single steps. */
static void test_an_advance_out_of_memory_for_events_stops_early_and_loses_nothing(void **state)
{
    (void)state;
    test_alloc ta = {0, 0, 0, 0};
    rg_body gate, ball;
    rg_world *w = sensor_gate(test_alloc_fn, &ta, &gate, &ball);
    /* a first step from farther away allocates the scratch and the contact (not touching) */
    assert_ok(rg_body_set_position(w, ball, v2(-0.5, 0)));
    assert_ok(rg_world_step(w, (rg_real)DT));
    assert_int_equal(get_events(w, NULL, 0), 0);
    assert_ok(rg_body_set_position(w, ball, v2(-0.2, 0)));
    ta.fail_at = ta.calls + 1;
    int32_t steps = -1;
    assert_ok(rg_world_advance(w, (rg_real)(4.5 * DT), &steps));
    assert_int_equal(steps, 1); /* step 2 needed room after the begin event */
    rg_contact_event ev[4];
    assert_int_equal(get_events(w, ev, 4), 1);
    assert_gate_event(&ev[0], RG_CONTACT_BEGIN, gate, ball);
    rg_real alpha;
    assert_ok(rg_world_get_alpha(w, &alpha));
    assert_near(alpha, 3.5, 1e-3);
    ta.fail_at = 0;
    assert_ok(rg_world_advance(w, 0, &steps));
    assert_int_equal(steps, 3);
    assert_int_equal(get_events(w, ev, 4), 1);
    assert_gate_event(&ev[0], RG_CONTACT_END, gate, ball);
    /* the same four steps as a fresh world's */
    rg_body gate2, ball2;
    rg_world *w2 = sensor_gate(mem_default_alloc, NULL, &gate2, &ball2);
    for (int i = 0; i < 4; i++) assert_ok(rg_world_step(w2, (rg_real)DT));
    assert_true(pos_of(w, ball).x == pos_of(w2, ball2).x);
    rg_world_destroy(w2);
    rg_world_destroy(w);
    assert_int_equal(ta.live_blocks, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_event_arguments_are_checked),
        cmocka_unit_test(test_a_pair_that_touches_once_gives_one_begin_and_one_end),
        cmocka_unit_test(test_events_are_sorted_and_capacity_only_limits_the_copy),
        cmocka_unit_test(test_destroying_a_body_ends_its_contacts_with_an_end_event),
        cmocka_unit_test(test_clearing_a_shape_or_changing_the_filter_ends_contacts),
        cmocka_unit_test(test_an_end_and_a_new_begin_of_one_pair_come_end_first),
        cmocka_unit_test(test_an_advance_reports_the_events_of_every_step_it_took),
        cmocka_unit_test(test_busy_advances_do_not_allocate_in_steady_state),
        cmocka_unit_test(test_an_advance_out_of_memory_for_events_stops_early_and_loses_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
