/* test_contact.c: contact storage: what collision allocates (nothing without shapes, nothing in steady
 * state), out of memory changing nothing, and bodies far away or thrown to infinity. */
#include "testutil.h"

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
    step_n(w, 50, DT);
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
    step_n(w, 240, DT); /* settled: the contact set stops growing */
    long before = ta.calls;
    step_n(w, 60, DT);
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

/* When contact storage cannot grow inside a step, the step runs without the pairs it could
 * not store, and they are searched again at the next step, which first grows the storage
 * and, while it cannot, fails changing nothing (tests/test_errors_world.c).  A step learns
 * that it cannot grow once: it asks the allocator for at most one grow's blocks (events 2,
 * solver rows 1, contacts and their awake list 2) at each of its three sizes (double, a
 * quarter more, a sixteenth more), not one grow per pair it meets (300 here; 44,850 for 300
 * overlapping bodies, which took a fuzzed step 39 s). */
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
    for (int i = 0; i < 3; i++) {
        long before = ta.calls;
        /* no room: the first step runs without the contacts, the next ones fail */
        assert_status(rg_world_step(w, (rg_real)DT), i == 0 ? RG_OK : RG_ERR_OUT_OF_MEMORY);
        if (ta.calls - before > 15) fail_msg("step %d asked for %ld blocks", i, ta.calls - before);
    }
    assert_true(PY(w, b[0]) < 0.5);
    ta.fail_at = 0;
    step_n(w, 60, DT);
    for (int i = 0; i < N; i++) {
        assert_near(PY(w, b[i]), 0.5 + (i / 150), 0.012); /* back in place */
        assert_int_equal(flag(rg_body_is_grounded, w, b[i]), 1);
    }
    rg_world_destroy(w);
    assert_int_equal(ta.live_blocks, 0);
}

/* Bodies at the edges of the accepted ranges (RG_MAX_COORD away, RG_MAX_SPEED fast,
 * RG_MIN_MASS light, a RG_MAX_SHAPE_SIZE floor) do no harm to the others; values beyond them
 * (the 3e37 m, 1e-30 kg and 1e38 m/s this test used before the ranges) are refused and
 * change nothing. */
static void test_bodies_far_away_or_thrown_to_infinity_do_no_harm(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    floor_of(w);
    rg_body ok = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5), refused = 0;
    rg_body far = circle_body(w, RG_BODY_DYNAMIC, 1, RG_MAX_COORD, -RG_MAX_COORD, 0.5);
    rg_body fast = box_body(w, RG_BODY_DYNAMIC, RG_MIN_MASS, 5, 5, 0.5, 0.5);
    assert_ok(rg_body_set_velocity(w, fast, v2(RG_MAX_SPEED, 0)));
    assert_status(rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(3e37, -3e37), &refused), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_create(w, RG_BODY_DYNAMIC, (rg_real)1e-30, v2(5, 5), &refused), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_body_apply_impulse(w, fast, v2(1e8, 0)), RG_ERR_INVALID_ARGUMENT); /* 1e14 m/s */
    assert_true(refused == 0 && rg_world_body_count(w) == 4);
    assert_true(VX(w, fast) == (double)(rg_real)RG_MAX_SPEED);
    rg_body huge = box_body(w, RG_BODY_STATIC, 0, 0, -1e6, (double)(rg_real)RG_MAX_SHAPE_SIZE, 1);
    (void)huge;
    step_n(w, 200, DT);
    assert_near(PY(w, ok), 0.5, 0.006);
    assert_true(isfinite(PX(w, far)) && isfinite(PY(w, far)));
    assert_true(isfinite(PX(w, fast)) && isfinite(PY(w, fast)) && isfinite(VX(w, fast)));
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
        cmocka_unit_test(test_a_world_without_shapes_allocates_nothing_for_collision),
        cmocka_unit_test(test_steady_state_steps_do_not_allocate),
        cmocka_unit_test(test_out_of_memory_on_set_shape_or_step_changes_nothing),
        cmocka_unit_test(test_contacts_that_cannot_be_stored_are_found_again_later),
        cmocka_unit_test(test_bodies_far_away_or_thrown_to_infinity_do_no_harm),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
