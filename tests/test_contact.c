/* test_contact.c: the collision API: validation, events, sensors, filters, grounded,
 * sleeping, queries, continuous collision, allocation and robustness. */
#include "testutil.h"

#define DT (1.0 / 60)

static rg_body floor_of(rg_world *w) { return box_body(w, RG_BODY_STATIC, 0, 0, -0.5, 100, 0.5); }

static double PX(rg_world *w, rg_body b) { return (double)pos_of(w, b).x; }
static double PY(rg_world *w, rg_body b) { return (double)pos_of(w, b).y; }
static double VX(rg_world *w, rg_body b) { return (double)vel_of(w, b).x; }
static double VY(rg_world *w, rg_body b) { return (double)vel_of(w, b).y; }

static void step_n(rg_world *w, int n)
{
    for (int i = 0; i < n; i++) assert_ok(rg_world_step(w, (rg_real)DT));
}

static int32_t flag(rg_status (*get)(const rg_world *, rg_body, int32_t *), rg_world *w, rg_body b)
{
    int32_t v = -1;
    assert_ok(get(w, b, &v));
    return v;
}

static int32_t events(rg_world *w, rg_contact_event *ev, int32_t cap)
{
    int32_t n = rg_world_get_contact_events(w, ev, cap);
    assert_true(n >= 0);
    return n;
}

/* ---------------------------------------------------------------- validation */

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
    static const double bad[] = {0, -1, (double)NAN, (double)INFINITY, -(double)INFINITY, 1e8};
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
    static const double bad_e[] = {-0.1, 1.1, (double)NAN, (double)INFINITY};
    for (int i = 0; i < 4; i++) assert_status(rg_body_set_restitution(w, b, (rg_real)bad_e[i]), RG_ERR_INVALID_ARGUMENT);
    static const double bad_mu[] = {-0.1, (double)NAN, (double)INFINITY};
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

static void test_event_and_query_arguments_are_checked(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_contact_event ev;
    assert_int_equal(rg_world_get_contact_events(w, NULL, 0), 0);
    assert_int_equal(rg_world_get_contact_events(w, &ev, -1), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_get_contact_events(w, NULL, 1), RG_ERR_INVALID_ARGUMENT);
    rg_ray_hit hit;
    hit.body = 77;
    assert_int_equal(rg_world_raycast(w, v2(NAN, 0), v2(1, 0), 1, &hit), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_raycast(w, v2(0, 0), v2(INFINITY, 0), 1, &hit), RG_ERR_INVALID_ARGUMENT);
    assert_true(hit.body == 77);
    rg_body out[2];
    assert_int_equal(rg_world_query_aabb(w, v2(0, NAN), v2(1, 1), 1, out, 2), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_query_aabb(w, v2(0, 0), v2(INFINITY, 1), 1, out, 2), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_query_aabb(w, v2(2, 0), v2(1, 1), 1, out, 2), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_query_aabb(w, v2(0, 2), v2(1, 1), 1, out, 2), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_query_aabb(w, v2(0, 0), v2(1, 1), 1, out, -1), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_query_aabb(w, v2(0, 0), v2(1, 1), 1, NULL, 1), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_query_aabb(w, v2(0, 0), v2(1, 1), 1, NULL, 0), 0);
    rg_world_destroy(w);
}

/* ---------------------------------------------------------------- events */

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
        int32_t n = events(w, ev, 4);
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
        n = events(w, ev, 16);
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
    step_n(w, 10);
    assert_int_equal(rg_world_touching_count(w), 2);
    assert_ok(rg_body_destroy(w, a));
    assert_int_equal(rg_world_touching_count(w), 0);
    assert_ok(rg_world_step(w, (rg_real)DT));
    rg_contact_event ev[8];
    int32_t n = events(w, ev, 8);
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
        n = events(w, ev, 8);
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
    step_n(w, 5);
    assert_int_equal(rg_world_touching_count(w), 2);
    assert_ok(rg_body_clear_shape(w, a));
    assert_ok(rg_body_set_filter(w, c, 2, 0xFFFFFFFFu & ~1u)); /* rejects the floor (category 1) */
    assert_int_equal(rg_world_touching_count(w), 0);
    assert_ok(rg_world_step(w, (rg_real)DT));
    rg_contact_event ev[8];
    int32_t n = events(w, ev, 8);
    assert_int_equal(n, 2);
    assert_int_equal(ev[0].kind, RG_CONTACT_END);
    assert_int_equal(ev[1].kind, RG_CONTACT_END);
    step_n(w, 30);
    assert_true(PY(w, a) < 0 && PY(w, c) < 0); /* both fall through the floor now */
    rg_world_destroy(w);
}

static void test_an_end_and_a_new_begin_of_one_pair_come_end_first(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    rg_body fl = floor_of(w);
    rg_body b = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5, 0.5);
    step_n(w, 5);
    assert_int_equal(rg_world_touching_count(w), 1);
    /* off and on again between two steps: the contact ends now and begins anew */
    assert_ok(rg_body_set_filter(w, b, 1, 0));
    assert_ok(rg_body_set_filter(w, b, 1, 0xFFFFFFFFu));
    assert_ok(rg_world_step(w, (rg_real)DT));
    rg_contact_event ev[4];
    assert_int_equal(events(w, ev, 4), 2);
    assert_int_equal(ev[0].kind, RG_CONTACT_END);
    assert_int_equal(ev[1].kind, RG_CONTACT_BEGIN);
    assert_true(ev[0].a == ev[1].a && ev[0].b == ev[1].b);
    assert_true(ev[0].a == (fl < b ? fl : b));
    rg_world_destroy(w);
}

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

static void *plain_alloc(void *user, void *ptr, size_t old_size, size_t new_size)
{
    (void)user;
    (void)old_size;
    if (new_size == 0) {
        free(ptr);
        return NULL;
    }
    return realloc(ptr, new_size);
}

static void assert_gate_event(const rg_contact_event *e, int32_t kind, rg_body gate, rg_body ball)
{
    assert_int_equal(e->kind, kind);
    assert_int_equal(e->sensor, 1);
    assert_true(e->a == (gate < ball ? gate : ball) && e->b == (gate < ball ? ball : gate));
}

/* A slow frame: one advance takes four steps, the ball enters the sensor in the first and
 * leaves it in the fourth.  Both events are there, in step order (a step's own order puts
 * an end before a begin, so a sort over the whole advance would not). */
static void test_an_advance_reports_the_events_of_every_step_it_took(void **state)
{
    (void)state;
    rg_body gate, ball;
    rg_world *w = sensor_gate(plain_alloc, NULL, &gate, &ball);
    int32_t steps = 0;
    assert_ok(rg_world_advance(w, (rg_real)(4.5 * DT), &steps));
    assert_int_equal(steps, 4);
    rg_contact_event ev[4];
    assert_int_equal(events(w, ev, 4), 2);
    assert_gate_event(&ev[0], RG_CONTACT_BEGIN, gate, ball);
    assert_gate_event(&ev[1], RG_CONTACT_END, gate, ball);
    /* the same through single steps, one event in the first and one in the fourth */
    rg_body gate2, ball2;
    rg_world *w2 = sensor_gate(plain_alloc, NULL, &gate2, &ball2);
    int32_t per_step[4];
    for (int i = 0; i < 4; i++) {
        assert_ok(rg_world_step(w2, (rg_real)DT));
        per_step[i] = events(w2, NULL, 0);
    }
    assert_int_equal(per_step[0], 1);
    assert_int_equal(per_step[1], 0);
    assert_int_equal(per_step[2], 0);
    assert_int_equal(per_step[3], 1);
    rg_world_destroy(w2);
    /* an advance that takes no step has no events to report; a direct step reports its own */
    assert_ok(rg_world_advance(w, (rg_real)(0.25 * DT), &steps));
    assert_int_equal(steps, 0);
    assert_int_equal(events(w, NULL, 0), 0);
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
        total += events(w, NULL, 0);
    }
    assert_true(total > 100);
    long before = ta.calls;
    for (int i = 0; i < 60; i++) {
        int32_t steps;
        assert_ok(rg_world_advance(w, (rg_real)(8 * DT), &steps));
        assert_true(events(w, NULL, 0) > 0);
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
    assert_int_equal(events(w, NULL, 0), 0);
    assert_ok(rg_body_set_position(w, ball, v2(-0.2, 0)));
    ta.fail_at = ta.calls + 1;
    int32_t steps = -1;
    assert_ok(rg_world_advance(w, (rg_real)(4.5 * DT), &steps));
    assert_int_equal(steps, 1); /* step 2 needed room after the begin event */
    rg_contact_event ev[4];
    assert_int_equal(events(w, ev, 4), 1);
    assert_gate_event(&ev[0], RG_CONTACT_BEGIN, gate, ball);
    rg_real alpha;
    assert_ok(rg_world_get_alpha(w, &alpha));
    assert_near(alpha, 3.5, 1e-3);
    ta.fail_at = 0;
    assert_ok(rg_world_advance(w, 0, &steps));
    assert_int_equal(steps, 3);
    assert_int_equal(events(w, ev, 4), 1);
    assert_gate_event(&ev[0], RG_CONTACT_END, gate, ball);
    /* the same four steps as a fresh world's */
    rg_body gate2, ball2;
    rg_world *w2 = sensor_gate(plain_alloc, NULL, &gate2, &ball2);
    for (int i = 0; i < 4; i++) assert_ok(rg_world_step(w2, (rg_real)DT));
    assert_true(pos_of(w, ball).x == pos_of(w2, ball2).x);
    rg_world_destroy(w2);
    rg_world_destroy(w);
    assert_int_equal(ta.live_blocks, 0);
}

/* ---------------------------------------------------------------- sensors and filters */

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
            int32_t n = events(w, ev, 4);
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
    step_n(w, 60);
    assert_near(VX(w, a), 3, 0);
    assert_near(VX(w, b), 0, 0);
    assert_int_equal(rg_world_touching_count(w), 0);
    /* now both accept: b is hit when a comes back from the right */
    assert_ok(rg_body_set_filter(w, a, 2, 4));
    assert_ok(rg_body_set_filter(w, b, 4, 2));
    assert_ok(rg_body_set_position(w, a, v2(6, 0)));
    assert_ok(rg_body_set_velocity(w, a, v2(-3, 0)));
    step_n(w, 60);
    assert_true(VX(w, b) < -1);
    rg_world_destroy(w);
}

/* ---------------------------------------------------------------- grounded */

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
        touched |= events(w, ev, 4) > 0;
        assert_int_equal(flag(rg_body_is_grounded, w, b), 0);
    }
    assert_true(touched);
    /* under a ceiling with gravity scale -1 (falls up): the ceiling is its ground */
    rg_body up = box_body(w, RG_BODY_DYNAMIC, 1, -10, 9.4, 0.5, 0.5);
    box_body(w, RG_BODY_STATIC, 0, -10, 10.5, 2, 0.5);
    assert_ok(rg_body_set_gravity_scale(w, up, -1));
    step_n(w, 30);
    assert_int_equal(flag(rg_body_is_grounded, w, up), 1);
    /* no gravity: never grounded */
    rg_world *z = gravity_world(0);
    floor_of(z);
    rg_body r = circle_body(z, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5);
    step_n(z, 10);
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
        step_n(w, 3);
        assert_int_equal(flag(rg_body_is_grounded, w, top), k == 0);
        rg_world_destroy(w);
    }
}

/* ---------------------------------------------------------------- sleeping */

static void test_a_body_at_rest_sleeps_and_wakes_when_pushed(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    floor_of(w);
    rg_body b = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5, 0.5);
    step_n(w, 60);
    assert_int_equal(flag(rg_body_is_awake, w, b), 0);
    assert_int_equal(rg_world_awake_body_count(w), 0);
    assert_int_equal(flag(rg_body_is_grounded, w, b), 1); /* kept while asleep */
    /* each way of pushing it wakes it */
    for (int how = 0; how < 5; how++) {
        step_n(w, 60);
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
    step_n(w, 60);
    assert_int_equal(rg_world_awake_body_count(w), 0);
    rg_vec2 p[10];
    for (int i = 0; i < 10; i++) p[i] = pos_of(w, b[i]);
    step_n(w, 100);
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
    step_n(w, 60);
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
    step_n(w, 60);
    assert_int_equal(flag(rg_body_is_awake, w, b), 0);
    assert_ok(rg_body_set_position(w, shelf, v2(0, -3))); /* the static shelf drops away */
    assert_int_equal(flag(rg_body_is_awake, w, b), 1);
    step_n(w, 60);
    assert_true(PY(w, b) < -1.9 && PY(w, b) > -2.1); /* fell onto the shelf's new place */
    /* a sleeping body on a dynamic support that is destroyed */
    rg_body b2 = box_body(w, RG_BODY_DYNAMIC, 1, 10, 0.5, 0.5, 0.5);
    box_body(w, RG_BODY_STATIC, 0, 10, -1.5, 3, 0.5);
    rg_body support = box_body(w, RG_BODY_DYNAMIC, 1, 10, -0.5, 0.5, 0.5);
    step_n(w, 60);
    assert_int_equal(flag(rg_body_is_awake, w, b2), 0);
    assert_ok(rg_body_destroy(w, support));
    assert_int_equal(flag(rg_body_is_awake, w, b2), 1);
    /* a body teleported into a sleeping one wakes it */
    step_n(w, 90);
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
    step_n(w, 60);
    assert_int_equal(rg_world_awake_body_count(w), 0);
    assert_ok(rg_world_set_sleeping(w, 0));
    assert_int_equal(rg_world_awake_body_count(w), 1);
    step_n(w, 120);
    assert_int_equal(flag(rg_body_is_awake, w, b), 1);
    /* sleep after 2 s of rest, not 0.5 */
    assert_ok(rg_world_set_sleeping(w, 1));
    assert_ok(rg_world_set_sleep_thresholds(w, 0.05f, 2));
    step_n(w, 100);
    assert_int_equal(flag(rg_body_is_awake, w, b), 1);
    step_n(w, 30);
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
    step_n(w, 60);
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
    step_n(w, 120);
    assert_int_equal(flag(rg_body_is_awake, w, c), 1);
    rg_world_destroy(w);
}

static void test_kinematic_and_static_bodies_never_sleep_and_a_moving_platform_wakes_riders(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    rg_body k = box_body(w, RG_BODY_KINEMATIC, 0, 0, -0.5, 3, 0.5);
    rg_body rider = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5, 0.5);
    step_n(w, 60);
    assert_int_equal(flag(rg_body_is_awake, w, k), 1);
    assert_int_equal(flag(rg_body_is_awake, w, rider), 0);
    assert_ok(rg_body_set_velocity(w, k, v2(0, 1))); /* the platform rises */
    step_n(w, 30);
    assert_int_equal(flag(rg_body_is_awake, w, rider), 1);
    assert_true(PY(w, rider) > 0.9); /* carried up */
    assert_ok(rg_body_set_velocity(w, k, v2(0, -1))); /* and goes down: the rider follows */
    step_n(w, 60);
    assert_true(PY(w, rider) < 0.6);
    rg_world_destroy(w);
}

/* ---------------------------------------------------------------- queries */

static void test_raycast_finds_the_closest_shape_with_point_normal_and_fraction(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body near_box = box_body(w, RG_BODY_STATIC, 0, 5, 0, 1, 1);
    rg_body far_ball = circle_body(w, RG_BODY_DYNAMIC, 1, 10, 0, 1);
    rg_body side = circle_body(w, RG_BODY_DYNAMIC, 1, 2, 3, 0.5);
    (void)side;
    rg_ray_hit hit;
    /* before any step */
    assert_int_equal(rg_world_raycast(w, v2(0, 0), v2(20, 0), 0xFFFFFFFFu, &hit), 1);
    assert_true(hit.body == near_box);
    assert_near(hit.fraction, 4.0 / 20, 1e-6);
    assert_near(hit.point.x, 4, 1e-5);
    assert_near(hit.normal.x, -1, 0);
    assert_near(hit.normal.y, 0, 0);
    /* masked out: the ball behind it */
    assert_ok(rg_body_set_filter(w, near_box, 2, 0xFFFFFFFFu));
    assert_int_equal(rg_world_raycast(w, v2(0, 0), v2(20, 0), 1, &hit), 1);
    assert_true(hit.body == far_ball);
    assert_near(hit.point.x, 9, 1e-5);
    /* too short, and nothing at all */
    assert_int_equal(rg_world_raycast(w, v2(0, 0), v2(3, 0), 0xFFFFFFFFu, &hit), 0);
    assert_int_equal(rg_world_raycast(w, v2(0, 0), v2(0, -20), 0xFFFFFFFFu, &hit), 0);
    /* from inside the box: the box is ignored, the ball is hit */
    assert_int_equal(rg_world_raycast(w, v2(5, 0), v2(20, 0), 0xFFFFFFFFu, &hit), 1);
    assert_true(hit.body == far_ball);
    /* at an angle onto the ball: normal from its centre */
    assert_int_equal(rg_world_raycast(w, v2(10, 5), v2(0, -10), 0xFFFFFFFFu, &hit), 1);
    assert_true(hit.body == far_ball);
    assert_near(hit.point.y, 1, 1e-5);
    assert_near(hit.normal.y, 1, 1e-6);
    /* a teleported body is seen where it is now */
    assert_ok(rg_body_set_position(w, far_ball, v2(10, 50)));
    assert_int_equal(rg_world_raycast(w, v2(10, 5), v2(0, -10), 0xFFFFFFFFu, &hit), 0);
    rg_world_destroy(w);
}

static void test_raycast_ties_go_to_the_lower_handle_and_long_rays_work(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body a = box_body(w, RG_BODY_STATIC, 0, 5000, 1, 1, 1), b = box_body(w, RG_BODY_STATIC, 0, 5000, -1, 1, 1);
    for (int i = 0; i < 200; i++) box_body(w, RG_BODY_STATIC, 0, i * 3.0, 10, 0.5, 0.5);
    rg_ray_hit hit;
    assert_int_equal(rg_world_raycast(w, v2(0, 0), v2(10000, 0), 0xFFFFFFFFu, &hit), 1);
    assert_true(hit.body == (a < b ? a : b));
    assert_near(hit.point.x, 4999, 0.01);
    rg_world_destroy(w);
}

static void test_aabb_query_returns_sorted_handles_and_the_full_count(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body b[10];
    for (int i = 0; i < 10; i++) b[i] = circle_body(w, RG_BODY_DYNAMIC, 1, i, 0, 0.25);
    rg_body none = make_body(w, 1, 3, 0); /* no shape: never found */
    (void)none;
    assert_ok(rg_body_set_sensor(w, b[4], 1));         /* sensors are found */
    assert_ok(rg_body_set_filter(w, b[5], 8, 0xFFFFFFFFu)); /* masked out below */
    rg_body out[10];
    /* circle i spans [i - 0.25, i + 0.25]: the box [2.25, 5.75] touches circles 2 and 6 at
     * their edges and overlaps 3, 4, 5; 5 is masked out, the sensor 4 is found */
    int32_t n = rg_world_query_aabb(w, v2(2.25, -1), v2(5.75, 1), 1, out, 10);
    assert_int_equal(n, 4);
    rg_body expect[4] = {b[2], b[3], b[4], b[6]};
    for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++)
            if (expect[j] < expect[i]) {
                rg_body t = expect[i];
                expect[i] = expect[j];
                expect[j] = t;
            }
    assert_memory_equal(out, expect, sizeof expect);
    rg_world_destroy(w);
}

static void test_aabb_query_counts_beyond_capacity_and_sees_teleports(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body b[20];
    for (int i = 0; i < 20; i++) b[i] = box_body(w, i % 2 ? RG_BODY_STATIC : RG_BODY_DYNAMIC, 1, i, 0, 0.4, 0.4);
    rg_body out[20];
    assert_int_equal(rg_world_query_aabb(w, v2(-1, -1), v2(30, 1), 0xFFFFFFFFu, out, 20), 20);
    for (int k = 1; k < 20; k++) assert_true(out[k - 1] < out[k]);
    rg_body few[3];
    assert_int_equal(rg_world_query_aabb(w, v2(-1, -1), v2(30, 1), 0xFFFFFFFFu, few, 3), 20);
    /* the three smallest handles */
    assert_memory_equal(few, out, sizeof few);
    assert_int_equal(rg_world_query_aabb(w, v2(-1, -1), v2(30, 1), 0xFFFFFFFFu, NULL, 0), 20);
    /* masks and teleports */
    assert_ok(rg_body_set_filter(w, b[3], 2, 0xFFFFFFFFu));
    assert_int_equal(rg_world_query_aabb(w, v2(2.5, -1), v2(3.5, 1), 1, out, 20), 0);
    assert_int_equal(rg_world_query_aabb(w, v2(2.5, -1), v2(3.5, 1), 2, out, 20), 1);
    assert_ok(rg_body_set_position(w, b[3], v2(100, 100)));
    assert_int_equal(rg_world_query_aabb(w, v2(99, 99), v2(101, 101), 0xFFFFFFFFu, out, 20), 1);
    assert_true(out[0] == b[3]);
    /* exactly touching edges count */
    assert_int_equal(rg_world_query_aabb(w, v2(0.4, -1), v2(0.4, 1), 0xFFFFFFFFu, out, 20), 1);
    assert_true(out[0] == b[0]);
    rg_world_destroy(w);
}

/* ---------------------------------------------------------------- continuous collision */

/* The case in the world: a 10 cm ball at 300 m/s against a 1 cm static wall at
 * 60 Hz, from many start phases.  Without continuous collision the step sees the ball on
 * one side, then on the other, and it passes; with it, never. */
static int ball_passes_wall(int continuous, double phase, int32_t wall_type, int box_shape)
{
    rg_world *w = gravity_world(0);
    assert_ok(rg_world_set_continuous(w, continuous));
    rg_body wall = box_body(w, wall_type, 0, 0, 0, 0.005, 1);
    (void)wall;
    double x0 = -1 - phase * 300 * DT;
    rg_body ball = box_shape ? box_body(w, RG_BODY_DYNAMIC, 1, x0, 0.3, 0.05, 0.05)
                             : circle_body(w, RG_BODY_DYNAMIC, 1, x0, 0.3, 0.05);
    assert_ok(rg_body_set_velocity(w, ball, v2(300, 0)));
    step_n(w, 4);
    int passed = PX(w, ball) > 0;
    rg_world_destroy(w);
    return passed;
}

static void test_a_fast_ball_tunnels_through_a_thin_wall_without_continuous_collision(void **state)
{
    (void)state;
    int passed = 0;
    for (int k = 0; k < 32; k++) passed += ball_passes_wall(0, (k + 0.5) / 32, RG_BODY_STATIC, 0);
    /* theory: caught only when a sample lands within 5.5 cm of the wall, 1.1% of 5 m */
    assert_true(passed >= 30);
}

static void test_continuous_collision_stops_fast_balls_and_boxes_at_thin_walls(void **state)
{
    (void)state;
    for (int k = 0; k < 32; k++) {
        double phase = (k + 0.5) / 32;
        assert_int_equal(ball_passes_wall(1, phase, RG_BODY_STATIC, 0), 0);
        assert_int_equal(ball_passes_wall(1, phase, RG_BODY_STATIC, 1), 0);
        assert_int_equal(ball_passes_wall(1, phase, RG_BODY_KINEMATIC, 0), 0);
    }
}

static void test_a_fast_ball_is_stopped_by_a_thin_dynamic_plank_too(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body plank = box_body(w, RG_BODY_DYNAMIC, 10, 0, 0, 0.005, 1);
    rg_body ball = circle_body(w, RG_BODY_DYNAMIC, 1, -2.3, 0.2, 0.05);
    assert_ok(rg_body_set_velocity(w, ball, v2(300, 0)));
    step_n(w, 3);
    assert_true(PX(w, ball) < PX(w, plank));
    /* momentum went into the plank (perfectly inelastic here: they move together) */
    assert_near(VX(w, plank), 300.0 / 11, 0.5);
    rg_world_destroy(w);
}

static void test_a_fast_fall_onto_a_thin_floor_lands_on_it(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    box_body(w, RG_BODY_STATIC, 0, 0, 0, 5, 0.005);
    rg_body b = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 20, 0.05);
    assert_ok(rg_body_set_velocity(w, b, v2(0, -500)));
    step_n(w, 30);
    assert_near(PY(w, b), 0.055, 0.006);
    assert_near(VY(w, b), 0, 1e-3);
    assert_int_equal(flag(rg_body_is_grounded, w, b), 1);
    rg_world_destroy(w);
}

/* A light ball at 300 m/s rammed from behind by a body ten thousand times heavier, at a thin
 * wall: whatever the solver makes of that, the ball never ends past the wall. */
static void test_a_fast_ball_rammed_into_a_thin_wall_stays_on_its_side(void **state)
{
    (void)state;
    for (int k = 0; k < 16; k++) {
        rg_world *w = gravity_world(0);
        box_body(w, RG_BODY_STATIC, 0, 0, 0, 0.005, 1);
        double x0 = -1 - (k / 16.0) * 5;
        rg_body ball = circle_body(w, RG_BODY_DYNAMIC, 1, x0, 0, 0.05);
        rg_body ram = box_body(w, RG_BODY_DYNAMIC, 1e4, x0 - 0.3, 0, 0.2, 0.2);
        assert_ok(rg_body_set_velocity(w, ball, v2(300, 0)));
        assert_ok(rg_body_set_velocity(w, ram, v2(300, 0)));
        step_n(w, 6);
        assert_true(PX(w, ball) < 0);
        rg_world_destroy(w);
    }
}

/* ---------------------------------------------------------------- cost and memory */

static rg_world *world_with(test_alloc *ta)
{
    rg_world *w;
    assert_ok(rg_world_create_with_allocator(test_alloc_fn, ta, &w));
    assert_ok(rg_world_set_gravity(w, v2(0, -10)));
    return w;
}

static void test_a_world_without_shapes_allocates_nothing_for_collision(void **state)
{
    (void)state;
    test_alloc ta = {0, 0, 0, 0};
    rg_world *w = world_with(&ta);
    for (int i = 0; i < 100; i++) make_body(w, 1, i, 0);
    long before = ta.calls;
    step_n(w, 50);
    assert_int_equal(ta.calls, before);
    rg_world_destroy(w);
    assert_int_equal(ta.live_blocks, 0);
}

static void test_steady_state_steps_do_not_allocate(void **state)
{
    (void)state;
    test_alloc ta = {0, 0, 0, 0};
    rg_world *w = world_with(&ta);
    assert_ok(rg_world_set_sleeping(w, 0));
    floor_of(w);
    for (int i = 0; i < 200; i++) circle_body(w, RG_BODY_DYNAMIC, 1, (i % 20) * 1.05, 1 + (i / 20) * 1.05, 0.5);
    step_n(w, 240); /* settled: the contact set stops growing */
    long before = ta.calls;
    step_n(w, 60);
    assert_int_equal(ta.calls, before);
    rg_world_destroy(w);
    assert_int_equal(ta.live_blocks, 0);
}

static void test_out_of_memory_on_set_shape_or_step_changes_nothing(void **state)
{
    (void)state;
    test_alloc ta = {0, 0, 0, 0};
    rg_world *w = world_with(&ta);
    rg_body b = make_body(w, 1, 0, 1);
    ta.fail_at = ta.calls + 1;
    assert_status(rg_body_set_circle(w, b, 0.5f), RG_ERR_OUT_OF_MEMORY);
    int32_t kind;
    assert_ok(rg_body_get_shape(w, b, &kind, NULL));
    assert_int_equal(kind, RG_SHAPE_NONE);
    assert_int_equal(rg_world_query_aabb(w, v2(-1, 0), v2(1, 2), 0xFFFFFFFFu, NULL, 0), 0);
    ta.fail_at = 0;
    assert_ok(rg_body_set_circle(w, b, 0.5f));
    /* the first step with shapes needs its scratch: failing, it changes nothing */
    ta.fail_at = ta.calls + 1;
    rg_vec2 p = pos_of(w, b);
    assert_status(rg_world_step(w, (rg_real)DT), RG_ERR_OUT_OF_MEMORY);
    assert_true(pos_of(w, b).y == p.y);
    ta.fail_at = 0;
    assert_ok(rg_world_step(w, (rg_real)DT));
    assert_true(PY(w, b) < (double)p.y);
    rg_world_destroy(w);
    assert_int_equal(ta.live_blocks, 0);
}

/* When contact storage cannot grow inside a step, the step still succeeds; the pairs it
 * could not store are searched again at the next step. */
static void test_contacts_that_cannot_be_stored_are_found_again_later(void **state)
{
    (void)state;
    test_alloc ta = {0, 0, 0, 0};
    rg_world *w = world_with(&ta);
    floor_of(w);
    enum { N = 300 };
    rg_body b[N];
    for (int i = 0; i < N; i++) b[i] = circle_body(w, RG_BODY_DYNAMIC, 1, i * 1.01 - 150, 1000 + i * 2.0, 0.5);
    assert_ok(rg_world_step(w, (rg_real)DT)); /* scratch allocated; no contacts yet */
    /* two rows on the floor, the second resting on the first: 300 contacts */
    for (int i = 0; i < N; i++) assert_ok(rg_body_set_position(w, b[i], v2((i % 150) * 1.2 - 90, 0.5 + (i / 150))));
    ta.fail_at = ta.calls + 1; /* every allocation from now on fails */
    for (int i = 0; i < 3; i++) assert_ok(rg_world_step(w, (rg_real)DT)); /* no room: no contacts */
    assert_true(PY(w, b[0]) < 0.5);
    ta.fail_at = 0;
    step_n(w, 60);
    for (int i = 0; i < N; i++) {
        assert_near(PY(w, b[i]), 0.5 + (i / 150), 0.012); /* back in place */
        assert_int_equal(flag(rg_body_is_grounded, w, b[i]), 1);
    }
    rg_world_destroy(w);
    assert_int_equal(ta.live_blocks, 0);
}

/* ---------------------------------------------------------------- robustness */

static void test_bodies_far_away_or_thrown_to_infinity_do_no_harm(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    floor_of(w);
    rg_body ok = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5);
    rg_body far = circle_body(w, RG_BODY_DYNAMIC, 1, 3e37, -3e37, 0.5);
    rg_body fast = box_body(w, RG_BODY_DYNAMIC, 1e-30, 5, 5, 0.5, 0.5);
    assert_ok(rg_body_apply_impulse(w, fast, v2(1e8, 0))); /* 1e38 m/s */
    rg_body huge = box_body(w, RG_BODY_STATIC, 0, 0, -1e6, (double)(rg_real)RG_MAX_SHAPE_SIZE, 1);
    (void)huge;
    step_n(w, 200);
    assert_near(PY(w, ok), 0.5, 0.006);
    assert_true(isfinite(PX(w, far)));
    rg_ray_hit hit;
    assert_true(rg_world_raycast(w, v2(0, 5), v2(0, -10), 0xFFFFFFFFu, &hit) == 1);
    assert_true(hit.body == ok);
    rg_body out[8];
    assert_true(rg_world_query_aabb(w, v2(-1, 0), v2(1, 1), 0xFFFFFFFFu, out, 8) == 2);
    rg_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults_and_getters),
        cmocka_unit_test(test_bad_shape_sizes_are_rejected_and_change_nothing),
        cmocka_unit_test(test_every_entry_point_rejects_null_and_stale_handles),
        cmocka_unit_test(test_bad_materials_flags_and_settings_are_rejected_and_change_nothing),
        cmocka_unit_test(test_event_and_query_arguments_are_checked),
        cmocka_unit_test(test_a_pair_that_touches_once_gives_one_begin_and_one_end),
        cmocka_unit_test(test_events_are_sorted_and_capacity_only_limits_the_copy),
        cmocka_unit_test(test_destroying_a_body_ends_its_contacts_with_an_end_event),
        cmocka_unit_test(test_clearing_a_shape_or_changing_the_filter_ends_contacts),
        cmocka_unit_test(test_an_end_and_a_new_begin_of_one_pair_come_end_first),
        cmocka_unit_test(test_an_advance_reports_the_events_of_every_step_it_took),
        cmocka_unit_test(test_busy_advances_do_not_allocate_in_steady_state),
        cmocka_unit_test(test_an_advance_out_of_memory_for_events_stops_early_and_loses_nothing),
        cmocka_unit_test(test_a_sensor_reports_begin_and_end_but_never_pushes),
        cmocka_unit_test(test_filters_decide_which_pairs_collide),
        cmocka_unit_test(test_grounded_is_false_in_the_air_and_true_at_rest),
        cmocka_unit_test(test_walls_and_ceilings_are_not_ground_unless_gravity_says_so),
        cmocka_unit_test(test_grounded_on_a_slope_within_45_degrees_only),
        cmocka_unit_test(test_a_body_at_rest_sleeps_and_wakes_when_pushed),
        cmocka_unit_test(test_sleeping_bodies_do_not_move_and_cost_no_steps),
        cmocka_unit_test(test_a_body_landing_on_a_sleeping_pile_wakes_it),
        cmocka_unit_test(test_removing_or_moving_a_support_wakes_what_rests_on_it),
        cmocka_unit_test(test_disabling_sleep_wakes_everything_and_thresholds_apply),
        cmocka_unit_test(test_springs_join_islands),
        cmocka_unit_test(test_kinematic_and_static_bodies_never_sleep_and_a_moving_platform_wakes_riders),
        cmocka_unit_test(test_raycast_finds_the_closest_shape_with_point_normal_and_fraction),
        cmocka_unit_test(test_raycast_ties_go_to_the_lower_handle_and_long_rays_work),
        cmocka_unit_test(test_aabb_query_returns_sorted_handles_and_the_full_count),
        cmocka_unit_test(test_aabb_query_counts_beyond_capacity_and_sees_teleports),
        cmocka_unit_test(test_a_fast_ball_tunnels_through_a_thin_wall_without_continuous_collision),
        cmocka_unit_test(test_continuous_collision_stops_fast_balls_and_boxes_at_thin_walls),
        cmocka_unit_test(test_a_fast_ball_is_stopped_by_a_thin_dynamic_plank_too),
        cmocka_unit_test(test_a_fast_fall_onto_a_thin_floor_lands_on_it),
        cmocka_unit_test(test_a_fast_ball_rammed_into_a_thin_wall_stays_on_its_side),
        cmocka_unit_test(test_a_world_without_shapes_allocates_nothing_for_collision),
        cmocka_unit_test(test_steady_state_steps_do_not_allocate),
        cmocka_unit_test(test_out_of_memory_on_set_shape_or_step_changes_nothing),
        cmocka_unit_test(test_contacts_that_cannot_be_stored_are_found_again_later),
        cmocka_unit_test(test_bodies_far_away_or_thrown_to_infinity_do_no_harm),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
