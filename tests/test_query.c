/* test_query.c: raycasts and box queries against the shapes as they are now. */
#include "testutil.h"

static void test_query_arguments_are_checked(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_query_arguments_are_checked),
        cmocka_unit_test(test_raycast_finds_the_closest_shape_with_point_normal_and_fraction),
        cmocka_unit_test(test_raycast_ties_go_to_the_lower_handle_and_long_rays_work),
        cmocka_unit_test(test_aabb_query_returns_sorted_handles_and_the_full_count),
        cmocka_unit_test(test_aabb_query_counts_beyond_capacity_and_sees_teleports),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
