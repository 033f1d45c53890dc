/* test_body.c: body handles, the body API's success and failure cases, and allocation
 * failure at every allocation. */
#include "testutil.h"

static rg_world *new_world(void)
{
    rg_world *w = NULL;
    assert_ok(rg_world_create(&w));
    return w;
}

static void test_create_sets_type_mass_position_and_defaults(void **state)
{
    (void)state;
    rg_world *w = new_world();
    rg_body s, k, d;
    int32_t type;
    rg_real mass;
    uint64_t user = 1;
    assert_ok(rg_body_create(w, RG_BODY_STATIC, 0, v2(1, 2), &s));
    assert_ok(rg_body_create(w, RG_BODY_KINEMATIC, -5, v2(3, 4), &k)); /* mass ignored */
    assert_ok(rg_body_create(w, RG_BODY_DYNAMIC, 2.5f, v2(5, 6), &d));
    assert_int_equal(rg_world_body_count(w), 3);
    assert_ok(rg_body_get_type(w, s, &type));
    assert_int_equal(type, RG_BODY_STATIC);
    assert_ok(rg_body_get_type(w, k, &type));
    assert_int_equal(type, RG_BODY_KINEMATIC);
    assert_ok(rg_body_get_type(w, d, &type));
    assert_int_equal(type, RG_BODY_DYNAMIC);
    assert_ok(rg_body_get_mass(w, d, &mass));
    assert_true(mass == (rg_real)2.5);
    assert_ok(rg_body_get_mass(w, k, &mass));
    assert_true(mass == 0);
    rg_vec2 p = pos_of(w, k), v = vel_of(w, d);
    assert_true(p.x == 3 && p.y == 4 && v.x == 0 && v.y == 0);
    assert_ok(rg_body_get_user_data(w, d, &user));
    assert_true(user == 0);
    assert_ok(rg_body_set_user_data(w, d, 0xDEADBEEFCAFEull));
    assert_ok(rg_body_get_user_data(w, d, &user));
    assert_true(user == 0xDEADBEEFCAFEull);
    assert_ok(rg_body_set_mass(w, d, 4));
    assert_ok(rg_body_get_mass(w, d, &mass));
    assert_true(mass == 4);
    rg_world_destroy(w);
}

/* Bodies keep their data through the swaps that creation and destruction of others cause. */
static void test_bodies_keep_their_state_while_others_come_and_go(void **state)
{
    (void)state;
    rg_world *w = new_world();
    enum { N = 300 };
    rg_body b[N];
    for (int i = 0; i < N; i++) {
        int type = i % 3;
        assert_ok(rg_body_create(w, type, 1, v2(i, -i), &b[i]));
        assert_ok(rg_body_set_user_data(w, b[i], (uint64_t)i));
    }
    for (int i = 0; i < N; i += 2) assert_ok(rg_body_destroy(w, b[i]));
    assert_int_equal(rg_world_body_count(w), N / 2);
    for (int i = 0; i < N; i++) {
        if (i % 2 == 0) {
            assert_false(rg_body_is_valid(w, b[i]));
            continue;
        }
        uint64_t u;
        int32_t type;
        assert_ok(rg_body_get_user_data(w, b[i], &u));
        assert_true(u == (uint64_t)i);
        assert_ok(rg_body_get_type(w, b[i], &type));
        assert_int_equal(type, i % 3);
        rg_vec2 p = pos_of(w, b[i]);
        assert_true(p.x == (rg_real)i && p.y == (rg_real)-i);
    }
    rg_world_destroy(w);
}

static void test_destroyed_zero_foreign_and_forged_handles_are_rejected(void **state)
{
    (void)state;
    rg_world *w = new_world(), *other = new_world();
    rg_body a = make_body(w, 1, 0, 0), b = make_body(w, 1, 0, 0), f = make_body(other, 1, 0, 0);
    uint64_t spring;
    rg_vec2 out;
    assert_ok(rg_spring_create(w, a, 0, v2(0, 0), 0, 1, 0, &spring));
    assert_ok(rg_body_destroy(w, a));
    assert_status(rg_body_destroy(w, a), RG_ERR_STALE_HANDLE); /* double destroy */
    const rg_body bad[] = {
        a,                                   /* destroyed */
        0,                                   /* never a body */
        f,                                   /* another world's live body */
        spring,                              /* a spring is not a body */
        b + 7,                               /* a slot never used */
        b + ((uint64_t)1 << 24),             /* the next generation of a live slot */
        b ^ ((uint64_t)1 << 50),             /* another tag */
        UINT64_MAX,
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_false(rg_body_is_valid(w, bad[i]));
        assert_status(rg_body_get_position(w, bad[i], &out), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_set_velocity(w, bad[i], v2(1, 1)), RG_ERR_STALE_HANDLE);
        assert_status(rg_body_destroy(w, bad[i]), RG_ERR_STALE_HANDLE);
    }
    assert_true(rg_body_is_valid(w, b));
    assert_true(rg_body_is_valid(other, f));
    assert_int_equal(rg_world_body_count(w), 1);
    assert_false(rg_body_is_valid(NULL, b));
    rg_world_destroy(other);
    rg_world_destroy(w);
}

/* 1.1 * 10^6 create/destroy cycles (past the 2^20 - 1 generations after which a slot
 * retires instead of wrapping): every handle ever given out is distinct and stale after its
 * destroy, and the world's memory does not grow. */
static void test_a_million_cycles_never_resurrect_a_handle_and_leak_nothing(void **state)
{
    (void)state;
    enum { CYCLES = 1100000 };
    test_alloc t = { 0, 0, 0, 0 };
    rg_world *w;
    assert_ok(rg_world_create_with_allocator(test_alloc_fn, &t, &w));
    rg_body keep = make_body(w, 1, 0, 0);
    uint64_t *seen = malloc(CYCLES * sizeof *seen);
    assert_non_null(seen);
    long long bytes_after_first = 0;
    for (int i = 0; i < CYCLES; i++) {
        seen[i] = make_body(w, 1, 0, 0);
        assert_ok(rg_body_destroy(w, seen[i]));
        if (i == 0) bytes_after_first = t.live_bytes;
    }
    assert_true(t.live_bytes == bytes_after_first);
    for (int i = 0; i < CYCLES; i++) assert_false(rg_body_is_valid(w, seen[i]));
    /* distinct: sort and compare neighbours */
    for (int gap = CYCLES / 2; gap > 0; gap /= 2) /* shell sort, no qsort callback needed */
        for (int i = gap; i < CYCLES; i++)
            for (int j = i; j >= gap && seen[j - gap] > seen[j]; j -= gap) {
                uint64_t x = seen[j];
                seen[j] = seen[j - gap];
                seen[j - gap] = x;
            }
    for (int i = 1; i < CYCLES; i++) assert_true(seen[i] != seen[i - 1]);
    free(seen);
    assert_true(rg_body_is_valid(w, keep));
    rg_world_destroy(w);
    assert_int_equal(t.live_blocks, 0);
    assert_true(t.live_bytes == 0);
}

/* rg_body_position / rg_body_velocity return what the out-pointer getters store, bit for bit,
 * and (NaN, NaN) with the reason in the last error for a stale handle or a NULL world. */
static void test_by_value_getters_match_the_status_getters(void **state)
{
    (void)state;
    rg_world *w = NULL;
    rg_body b = 0, gone = 0;
    rg_vec2 p, v;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_body_create(w, RG_BODY_DYNAMIC, 2, v2(1.25f, -3.5f), &b));
    assert_ok(rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(0, 0), &gone));
    assert_ok(rg_body_set_velocity(w, b, v2(0.1f, 7)));
    for (int k = 0; k < 10; k++) assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
    assert_ok(rg_body_get_position(w, b, &p));
    assert_ok(rg_body_get_velocity(w, b, &v));
    rg_vec2 pv = rg_body_position(w, b), vv = rg_body_velocity(w, b);
    assert_memory_equal(&pv, &p, sizeof p);
    assert_memory_equal(&vv, &v, sizeof v);
    assert_string_equal(rg_world_last_error(w), "");
    assert_ok(rg_body_destroy(w, gone));
    pv = rg_body_position(w, gone);
    assert_true(pv.x != pv.x && pv.y != pv.y);
    assert_non_null(strstr(rg_world_last_error(w), "rg_body_position: body"));
    vv = rg_body_velocity(w, 0);
    assert_true(vv.x != vv.x && vv.y != vv.y);
    assert_non_null(strstr(rg_world_last_error(w), "rg_body_velocity: body"));
    pv = rg_body_position(NULL, b);
    assert_true(pv.x != pv.x && pv.y != pv.y);
    pv = rg_body_position(w, b); /* a call that succeeds clears the reason */
    assert_string_equal(rg_world_last_error(w), "");
    rg_world_destroy(w);
}

static void test_body_calls_reject_bad_input_and_change_nothing(void **state)
{
    (void)state;
    rg_world *w = new_world();
    rg_body b = make_body(w, 2, 1, 1), s, out = 99;
    const rg_real nan = (rg_real)NAN, inf = (rg_real)INFINITY;
    rg_vec2 v;
    rg_real r;
    int32_t i32;
    uint64_t u64;
    assert_ok(rg_body_create(w, RG_BODY_STATIC, 0, v2(0, 0), &s));
    /* create */
    assert_status(rg_body_create(NULL, RG_BODY_DYNAMIC, 1, v2(0, 0), &out), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(0, 0), NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_create(w, 3, 1, v2(0, 0), &out), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_create(w, -1, 1, v2(0, 0), &out), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_create(w, RG_BODY_DYNAMIC, 0, v2(0, 0), &out), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_create(w, RG_BODY_DYNAMIC, -1, v2(0, 0), &out), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_create(w, RG_BODY_DYNAMIC, nan, v2(0, 0), &out), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_create(w, RG_BODY_DYNAMIC, inf, v2(0, 0), &out), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_create(w, RG_BODY_STATIC, nan, v2(0, 0), &out), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(nan, 0), &out), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(0, -inf), &out), RG_ERR_INVALID_ARGUMENT);
    assert_true(out == 99);
    assert_int_equal(rg_world_body_count(w), 2);
    /* getters */
    assert_status(rg_body_get_position(NULL, b, &v), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_position(w, b, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_velocity(w, b, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_velocity(NULL, b, &v), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_acceleration(w, b, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_acceleration(NULL, b, &v), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_acceleration(w, 0, &v), RG_ERR_STALE_HANDLE);
    assert_status(rg_body_get_interpolated_position(w, b, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_interpolated_position(NULL, b, &v), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_interpolated_position(w, 0, &v), RG_ERR_STALE_HANDLE);
    assert_status(rg_body_get_type(w, b, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_type(NULL, b, &i32), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_type(w, 0, &i32), RG_ERR_STALE_HANDLE);
    assert_status(rg_body_get_mass(w, b, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_mass(NULL, b, &r), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_mass(w, 0, &r), RG_ERR_STALE_HANDLE);
    assert_status(rg_body_get_user_data(w, b, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_user_data(NULL, b, &u64), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_get_user_data(w, 0, &u64), RG_ERR_STALE_HANDLE);
    /* setters */
    assert_status(rg_body_set_position(w, b, v2(nan, 0)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_position(w, b, v2(0, inf)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_position(NULL, b, v2(0, 0)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_position(w, 0, v2(0, 0)), RG_ERR_STALE_HANDLE);
    assert_status(rg_body_set_velocity(w, b, v2(nan, 0)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_velocity(w, b, v2(0, -inf)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_velocity(NULL, b, v2(0, 0)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_velocity(w, s, v2(1, 0)), RG_ERR_INVALID_ARGUMENT); /* static */
    assert_ok(rg_body_set_velocity(w, s, v2(0, 0)));
    assert_status(rg_body_set_mass(w, b, 0), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_mass(w, b, -2), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_mass(w, b, nan), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_mass(w, b, inf), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_mass(w, s, 1), RG_ERR_INVALID_ARGUMENT); /* static */
    assert_status(rg_body_set_mass(NULL, b, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_mass(w, 0, 1), RG_ERR_STALE_HANDLE);
    assert_status(rg_body_set_user_data(NULL, b, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_set_user_data(w, 0, 1), RG_ERR_STALE_HANDLE);
    assert_status(rg_body_destroy(NULL, b), RG_ERR_INVALID_ARGUMENT);
    /* nothing changed */
    rg_vec2 p = pos_of(w, b);
    v = vel_of(w, b);
    assert_true(p.x == 1 && p.y == 1 && v.x == 0 && v.y == 0);
    assert_ok(rg_body_get_mass(w, b, &r));
    assert_true(r == 2);
    assert_ok(rg_body_get_user_data(w, b, &u64));
    assert_true(u64 == 0);
    rg_world_destroy(w);
}

/* A scene of bodies, springs and steps run under an allocator that fails from its Nth
 * allocation on, for every N until the scene completes: each failing call reports
 * RG_ERR_OUT_OF_MEMORY and changes nothing, the world stays usable once memory returns,
 * and nothing leaks. */
static int run_scene(rg_world *w, test_alloc *t, int *failed)
{
    rg_body bodies[150];
    int n = 0;
    for (int i = 0; i < 150; i++) {
        int32_t before = rg_world_body_count(w);
        rg_status st = rg_body_create(w, i % 3, 1, v2(i, 0), &bodies[n]);
        if (st == RG_ERR_OUT_OF_MEMORY) {
            assert_int_equal(rg_world_body_count(w), before);
            *failed = 1;
            t->fail_at = 0; /* memory comes back */
            assert_ok(rg_body_create(w, i % 3, 1, v2(i, 0), &bodies[n]));
        } else {
            assert_ok(st);
        }
        n++;
        if (i % 10 == 9) {
            uint64_t s;
            int32_t before_s = rg_world_spring_count(w);
            st = rg_spring_create(w, bodies[n - 1], bodies[n - 2], v2(0, 0), 1, 1, 0, &s);
            if (st == RG_ERR_OUT_OF_MEMORY) {
                assert_int_equal(rg_world_spring_count(w), before_s);
                *failed = 1;
                t->fail_at = 0;
                assert_ok(rg_spring_create(w, bodies[n - 1], bodies[n - 2], v2(0, 0), 1, 1, 0, &s));
            } else {
                assert_ok(st);
            }
        }
    }
    for (int integ = 0; integ <= 3; integ++) {
        assert_ok(rg_world_set_integrator(w, integ));
        rg_vec2 before = pos_of(w, bodies[2]);
        rg_status st = rg_world_step(w, (rg_real)0.01);
        if (st == RG_ERR_OUT_OF_MEMORY) {
            rg_vec2 after = pos_of(w, bodies[2]);
            assert_true(before.x == after.x && before.y == after.y);
            *failed = 1;
            t->fail_at = 0;
            assert_ok(rg_world_step(w, (rg_real)0.01));
        } else {
            assert_ok(st);
        }
    }
    return n;
}

static void test_every_allocation_failure_is_reported_and_recoverable(void **state)
{
    (void)state;
    int completed_without_failure = 0;
    for (long n = 1; n < 200 && !completed_without_failure; n++) {
        test_alloc t = { 0, n, 0, 0 };
        rg_world *w = NULL;
        rg_status st = rg_world_create_with_allocator(test_alloc_fn, &t, &w);
        if (st != RG_OK) {
            assert_status(st, RG_ERR_OUT_OF_MEMORY);
            assert_null(w);
            assert_int_equal(t.live_blocks, 0);
            continue;
        }
        int failed = 0;
        assert_int_equal(run_scene(w, &t, &failed), 150);
        assert_int_equal(rg_world_body_count(w), 150);
        rg_world_destroy(w);
        assert_int_equal(t.live_blocks, 0);
        assert_true(t.live_bytes == 0);
        if (!failed) completed_without_failure = 1;
    }
    assert_true(completed_without_failure); /* every allocation point was visited */
}

/* Gravity scale, drag and speed limits read back what was set, exactly (they are stored as
 * given), and their defaults: scale 1, no drag, no limits.  A kinematic body's scale is 0,
 * as its mass, and its setter changes nothing. */
static void test_gravity_scale_drag_and_speed_limits_read_back_what_was_set(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    rg_body d = make_body(w, 1, 0, 0), k;
    assert_ok(rg_body_create(w, RG_BODY_KINEMATIC, 0, v2(3, 0), &k));
    rg_real a, b;
    assert_ok(rg_body_get_gravity_scale(w, d, &a));
    assert_true(a == 1);
    assert_ok(rg_body_get_drag(w, d, &a, &b));
    assert_true(a == 0 && b == 0);
    assert_ok(rg_body_get_speed_limits(w, d, &a, &b));
    assert_true(a == 0 && b == 0);
    assert_ok(rg_body_set_gravity_scale(w, d, (rg_real)-0.25));
    assert_ok(rg_body_set_drag(w, d, (rg_real)0.3, (rg_real)0.07));
    assert_ok(rg_body_set_speed_limits(w, d, (rg_real)0.1, 9));
    assert_ok(rg_body_get_gravity_scale(w, d, &a));
    assert_true(a == (rg_real)-0.25);
    assert_ok(rg_body_get_drag(w, d, &a, &b));
    assert_true(a == (rg_real)0.3 && b == (rg_real)0.07);
    assert_ok(rg_body_get_speed_limits(w, d, &a, NULL));
    assert_true(a == (rg_real)0.1);
    assert_ok(rg_body_get_speed_limits(w, d, NULL, &b));
    assert_true(b == 9);
    assert_ok(rg_body_set_gravity_scale(w, k, 5));
    assert_ok(rg_body_get_gravity_scale(w, k, &a));
    assert_true(a == 0);
    rg_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_create_sets_type_mass_position_and_defaults),
        cmocka_unit_test(test_bodies_keep_their_state_while_others_come_and_go),
        cmocka_unit_test(test_destroyed_zero_foreign_and_forged_handles_are_rejected),
        cmocka_unit_test(test_a_million_cycles_never_resurrect_a_handle_and_leak_nothing),
        cmocka_unit_test(test_by_value_getters_match_the_status_getters),
        cmocka_unit_test(test_gravity_scale_drag_and_speed_limits_read_back_what_was_set),
        cmocka_unit_test(test_body_calls_reject_bad_input_and_change_nothing),
        cmocka_unit_test(test_every_allocation_failure_is_reported_and_recoverable),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
