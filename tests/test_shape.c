/* test_shape.c: the shape, material, sensor and filter API: defaults, validation (bad input changes
 * nothing, every entry point rejects NULL and stale handles), sensors that never push, filters. */
#include "testutil.h"

/* Everything a failing call could change, for comparison. */
typedef struct body_snapshot {
    int32_t kind, sensor;
    rg_vec2 half;
    rg_real rest, mu;
    uint32_t cat, mask;
    rg_vec2 p, v;
} body_snapshot;

static body_snapshot snap(rg_world *w, rg_body b)
{
    body_snapshot s;
    memset(&s, 0, sizeof s);
    assert_ok(rg_body_get_shape(w, b, &s.kind, &s.half));
    assert_ok(rg_body_is_sensor(w, b, &s.sensor));
    assert_ok(rg_body_get_restitution(w, b, &s.rest));
    assert_ok(rg_body_get_friction(w, b, &s.mu));
    assert_ok(rg_body_get_filter(w, b, &s.cat, &s.mask));
    s.p = pos_of(w, b);
    s.v = vel_of(w, b);
    return s;
}

static void test_defaults_and_getters(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body b = make_body(w, 1, 0, 0);
    body_snapshot s = snap(w, b);
    assert_int_equal(s.kind, RG_SHAPE_NONE);
    assert_near(s.half.x, 0, 0);
    assert_int_equal(s.sensor, 0);
    assert_near(s.rest, 0, 0);
    assert_near(s.mu, 0.6, 1e-7);
    assert_int_equal(s.cat, 1);
    assert_int_equal(s.mask, 0xFFFFFFFFu);
    assert_ok(rg_body_set_circle(w, b, 0.25f));
    s = snap(w, b);
    assert_int_equal(s.kind, RG_SHAPE_CIRCLE);
    assert_near(s.half.x, 0.25, 0);
    assert_near(s.half.y, 0.25, 0);
    assert_ok(rg_body_set_aabb(w, b, 2, 0.5f));
    int32_t kind;
    assert_ok(rg_body_get_shape(w, b, &kind, NULL));
    assert_int_equal(kind, RG_SHAPE_AABB);
    rg_vec2 half;
    assert_ok(rg_body_get_shape(w, b, NULL, &half));
    assert_near(half.x, 2, 0);
    assert_near(half.y, 0.5, 0);
    assert_ok(rg_body_set_restitution(w, b, 0.5f));
    assert_ok(rg_body_set_friction(w, b, 2));
    assert_ok(rg_body_set_sensor(w, b, 1));
    assert_ok(rg_body_set_filter(w, b, 4, 6));
    s = snap(w, b);
    assert_near(s.rest, 0.5, 0);
    assert_near(s.mu, 2, 0);
    assert_int_equal(s.sensor, 1);
    assert_int_equal(s.cat, 4);
    assert_int_equal(s.mask, 6);
    assert_ok(rg_body_clear_shape(w, b));
    assert_ok(rg_body_clear_shape(w, b)); /* twice is fine */
    assert_ok(rg_body_get_shape(w, b, &kind, &half));
    assert_int_equal(kind, RG_SHAPE_NONE);
    int32_t sleeping, cont, vel, pos;
    rg_real speed, time, slop, rate, push, thr;
    assert_ok(rg_world_get_sleeping(w, &sleeping));
    assert_int_equal(sleeping, 1);
    assert_ok(rg_world_get_sleep_thresholds(w, &speed, &time));
    assert_near(speed, 0.05, 1e-7);
    assert_near(time, 0.5, 1e-7);
    assert_ok(rg_world_get_continuous(w, &cont));
    assert_int_equal(cont, 1);
    assert_ok(rg_world_get_solver_iterations(w, &vel, &pos));
    assert_true(vel >= 1 && pos >= 0);
    assert_ok(rg_world_get_contact_tuning(w, &slop, &rate, &push, &thr));
    assert_near(slop, 0.005, 1e-7);
    assert_near(thr, 1, 0);
    rg_world_destroy(w);
}

static void test_bad_shape_sizes_are_rejected_and_change_nothing(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body b = make_body(w, 1, 0, 0);
    assert_ok(rg_body_set_circle(w, b, 0.5f));
    body_snapshot before = snap(w, b);
    const double bad[] = {0, -1, (double)NAN, (double)INFINITY, -(double)INFINITY, 1e8};
    for (int i = 0; i < 6; i++) {
        rg_real v = (rg_real)bad[i];
        assert_status(rg_body_set_circle(w, b, v), RG_ERR_INVALID_ARGUMENT);
        assert_status(rg_body_set_aabb(w, b, v, 1), RG_ERR_INVALID_ARGUMENT);
        assert_status(rg_body_set_aabb(w, b, 1, v), RG_ERR_INVALID_ARGUMENT);
    }
    body_snapshot after = snap(w, b);
    assert_memory_equal(&before, &after, sizeof before);
    assert_ok(rg_body_set_circle(w, b, (rg_real)RG_MAX_SHAPE_SIZE)); /* the largest is fine */
    rg_world_destroy(w);
}

static void test_every_entry_point_rejects_null_and_stale_handles(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body b = make_body(w, 1, 0, 0), dead = make_body(w, 1, 5, 0);
    assert_ok(rg_body_destroy(w, dead));
    rg_body handles[3] = {dead, 0, 0xFFFFFFFFFFFFull};
    uint32_t u;
    int32_t i32;
    rg_real r;
    rg_vec2 v;
    for (int k = 0; k < 3; k++) {
        rg_body h = handles[k];
        assert_status(rg_body_set_circle(w, h, 1), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_set_aabb(w, h, 1, 1), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_clear_shape(w, h), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_get_shape(w, h, &i32, &v), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_set_restitution(w, h, 0), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_get_restitution(w, h, &r), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_set_friction(w, h, 0), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_get_friction(w, h, &r), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_set_sensor(w, h, 1), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_is_sensor(w, h, &i32), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_set_filter(w, h, 1, 1), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_get_filter(w, h, &u, &u), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_is_grounded(w, h, &i32), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_is_awake(w, h, &i32), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_wake(w, h), RG_ERR_STALE_HANDLE);
    }
    /* NULL world */
    assert_status(rg_body_set_circle(NULL, b, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_aabb(NULL, b, 1, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_clear_shape(NULL, b), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_shape(NULL, b, &i32, &v), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_restitution(NULL, b, 0), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_restitution(NULL, b, &r), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_friction(NULL, b, 0), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_friction(NULL, b, &r), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_sensor(NULL, b, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_is_sensor(NULL, b, &i32), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_filter(NULL, b, 1, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_filter(NULL, b, &u, &u), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_is_grounded(NULL, b, &i32), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_is_awake(NULL, b, &i32), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_wake(NULL, b), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_sleeping(NULL, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_sleeping(NULL, &i32), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_sleep_thresholds(NULL, 1, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_sleep_thresholds(NULL, &r, &r), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_solver_iterations(NULL, 4, 2), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_solver_iterations(NULL, &i32, &i32), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_contact_tuning(NULL, 0, 0.2f, 1, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_contact_tuning(NULL, &r, &r, &r, &r), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_continuous(NULL, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_continuous(NULL, &i32), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_awake_body_count(NULL), 0);
    assert_int_equal(rg_world_touching_count(NULL), 0);
    assert_int_equal(rg_world_get_contact_events(NULL, NULL, 0), RG_ERR_INVALID_ARGUMENT);
    rg_ray_hit hit;
    assert_true(rg_world_raycast(NULL, v2(0, 0), v2(1, 0), 1, &hit) < 0);
    assert_true(rg_world_query_aabb(NULL, v2(0, 0), v2(1, 1), 1, NULL, 0) < 0);
    /* NULL outputs */
    assert_status(rg_body_get_shape(w, b, NULL, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_restitution(w, b, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_friction(w, b, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_is_sensor(w, b, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_filter(w, b, NULL, &u), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_filter(w, b, &u, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_is_grounded(w, b, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_is_awake(w, b, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_sleeping(w, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_sleep_thresholds(w, &r, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_solver_iterations(w, NULL, &i32), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_contact_tuning(w, &r, &r, NULL, &r), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_continuous(w, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_true(rg_world_raycast(w, v2(0, 0), v2(1, 0), 1, NULL) < 0);
    rg_world_destroy(w);
}

static void test_bad_materials_flags_and_settings_are_rejected_and_change_nothing(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body b = make_body(w, 1, 0, 0);
    assert_ok(rg_body_set_circle(w, b, 1));
    body_snapshot before = snap(w, b);
    const double bad_e[] = {-0.1, 1.1, (double)NAN, (double)INFINITY};
    for (int i = 0; i < 4; i++) assert_status(rg_body_set_restitution(w, b, (rg_real)bad_e[i]), RG_ERR_INVALID_ARGUMENT);
    const double bad_mu[] = {-0.1, (double)NAN, (double)INFINITY};
    for (int i = 0; i < 3; i++) assert_status(rg_body_set_friction(w, b, (rg_real)bad_mu[i]), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_sensor(w, b, 2), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_sensor(w, b, -1), RG_ERR_INVALID_ARGUMENT);
    body_snapshot after = snap(w, b);
    assert_memory_equal(&before, &after, sizeof before);

    int32_t s0, v0, p0, c0;
    rg_real sp0, t0, sl0, r0, m0, th0;
    assert_ok(rg_world_get_sleeping(w, &s0));
    assert_ok(rg_world_get_sleep_thresholds(w, &sp0, &t0));
    assert_ok(rg_world_get_solver_iterations(w, &v0, &p0));
    assert_ok(rg_world_get_continuous(w, &c0));
    assert_ok(rg_world_get_contact_tuning(w, &sl0, &r0, &m0, &th0));
    assert_status(rg_world_set_sleeping(w, 2), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_sleeping(w, -1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_sleep_thresholds(w, -1, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_sleep_thresholds(w, 1, 0), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_sleep_thresholds(w, (rg_real)NAN, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_sleep_thresholds(w, 1, (rg_real)INFINITY), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_solver_iterations(w, 0, 2), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_solver_iterations(w, 65, 2), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_solver_iterations(w, 4, -1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_solver_iterations(w, 4, 65), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_continuous(w, 2), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_contact_tuning(w, -0.1f, 0.2f, 1, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_contact_tuning(w, 0.01f, 0, 1, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_contact_tuning(w, 0.01f, 1.5f, 1, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_contact_tuning(w, 0.01f, 0.2f, 0, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_contact_tuning(w, 0.01f, 0.2f, 1, -1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_contact_tuning(w, (rg_real)NAN, 0.2f, 1, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_contact_tuning(w, 0.01f, 0.2f, (rg_real)INFINITY, 1), RG_ERR_INVALID_ARGUMENT);
    int32_t s1, v1, p1, c1;
    rg_real sp1, t1, sl1, r1, m1, th1;
    assert_ok(rg_world_get_sleeping(w, &s1));
    assert_ok(rg_world_get_sleep_thresholds(w, &sp1, &t1));
    assert_ok(rg_world_get_solver_iterations(w, &v1, &p1));
    assert_ok(rg_world_get_continuous(w, &c1));
    assert_ok(rg_world_get_contact_tuning(w, &sl1, &r1, &m1, &th1));
    assert_true(s0 == s1 && v0 == v1 && p0 == p1 && c0 == c1);
    assert_true(sp0 == sp1 && t0 == t1 && sl0 == sl1 && r0 == r1 && m0 == m1 && th0 == th1);
    /* and the good values take */
    assert_ok(rg_world_set_solver_iterations(w, 12, 0));
    assert_ok(rg_world_get_solver_iterations(w, &v1, &p1));
    assert_true(v1 == 12 && p1 == 0);
    assert_ok(rg_world_set_sleep_thresholds(w, 0, 2));
    assert_ok(rg_world_set_contact_tuning(w, 0, 1, 10, 0));
    rg_world_destroy(w);
}

static void test_a_sensor_reports_begin_and_end_but_never_pushes(void **state)
{
    (void)state;
    for (int which = 0; which < 2; which++) {
        rg_world *w = gravity_world(-10);
        rg_body zone = box_body(w, RG_BODY_STATIC, 0, 0, 0, 2, 0.5);
        rg_body ball = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 3, 0.5);
        assert_ok(rg_body_set_sensor(w, which == 0 ? zone : ball, 1));
        rg_body free_ball = circle_body(w, RG_BODY_DYNAMIC, 1, 50, 3, 0.5); /* the same fall, alone */
        int begins = 0, ends = 0;
        for (int i = 0; i < 90; i++) {
            assert_ok(rg_world_step(w, (rg_real)DT));
            rg_contact_event ev[4];
            int32_t n = get_events(w, ev, 4);
            for (int k = 0; k < n; k++) {
                assert_int_equal(ev[k].sensor, 1);
                begins += ev[k].kind == RG_CONTACT_BEGIN;
                ends += ev[k].kind == RG_CONTACT_END;
            }
            assert_near(PY(w, ball), PY(w, free_ball), 0);
            assert_near(VY(w, ball), VY(w, free_ball), 0);
        }
        assert_int_equal(begins, 1);
        assert_int_equal(ends, 1);
        rg_world_destroy(w);
    }
}

static void test_filters_decide_which_pairs_collide(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body a = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 0, 0.5), b = circle_body(w, RG_BODY_DYNAMIC, 1, 3, 0, 0.5);
    assert_ok(rg_body_set_velocity(w, a, v2(3, 0)));
    /* a in category 2 masks out 4; b in category 4: one side refuses, no collision */
    assert_ok(rg_body_set_filter(w, a, 2, ~4u));
    assert_ok(rg_body_set_filter(w, b, 4, 0xFFFFFFFFu));
    step_n(w, 60, DT);
    assert_near(VX(w, a), 3, 0);
    assert_near(VX(w, b), 0, 0);
    assert_int_equal(rg_world_touching_count(w), 0);
    /* now both accept: b is hit when a comes back from the right */
    assert_ok(rg_body_set_filter(w, a, 2, 4));
    assert_ok(rg_body_set_filter(w, b, 4, 2));
    assert_ok(rg_body_set_position(w, a, v2(6, 0)));
    assert_ok(rg_body_set_velocity(w, a, v2(-3, 0)));
    step_n(w, 60, DT);
    assert_true(VX(w, b) < -1);
    rg_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults_and_getters),
        cmocka_unit_test(test_bad_shape_sizes_are_rejected_and_change_nothing),
        cmocka_unit_test(test_every_entry_point_rejects_null_and_stale_handles),
        cmocka_unit_test(test_bad_materials_flags_and_settings_are_rejected_and_change_nothing),
        cmocka_unit_test(test_a_sensor_reports_begin_and_end_but_never_pushes),
        cmocka_unit_test(test_filters_decide_which_pairs_collide),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
