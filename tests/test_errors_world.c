/* test_errors_world.c: every error path of the world, stepping, query, event, draw and
 * count calls: the status, that nothing changed, and that rg_world_last_error names the
 * function and the argument; "" after a success.  Locked calls (from a pre-solve hook) and
 * out of memory for every call that allocates are here too. */
#include "errors.h"

static void test_last_error_is_never_null_and_empty_after_a_success(void **state)
{
    scene *s = *state;
    rg_world *w = NULL;
    assert_string_equal(rg_world_last_error(NULL), "rg_world_last_error: world is NULL");
    assert_ok(rg_world_create(&w));
    assert_string_equal(rg_world_last_error(w), "");
    assert_status(rg_body_set_circle(w, 0, 1e8f), STALE); /* the handle is looked at first */
    assert_string_equal(rg_world_last_error(w), "rg_body_set_circle: body is 0 (never a handle)");
    rg_body b = make_body(w, 1, 0, 0);
    assert_status(rg_body_set_circle(w, b, 1e8f), INVALID);
    assert_string_equal(rg_world_last_error(w), "rg_body_set_circle: radius 1e+08 is above RG_MAX_SHAPE_SIZE (1e+07)");
    assert_status(rg_world_step(w, -1), INVALID);
    assert_string_equal(rg_world_last_error(w), "rg_world_step: dt -1 is not > 0");
    assert_status(rg_body_set_velocity(w, b, v2(NaN, 0)), INVALID);
    assert_string_equal(rg_world_last_error(w), "rg_body_set_velocity: velocity.x is NaN");
    assert_status(rg_body_set_mass(w, b, (rg_real)1e-40), INVALID); /* a denormal in float */
    assert_non_null(strstr(rg_world_last_error(w), "rg_body_set_mass: mass "));
    assert_non_null(strstr(rg_world_last_error(w), " is below RG_MIN_MASS (1e-06)"));
    /* a getter that succeeds clears it, and one failure does not outlive the next call */
    rg_vec2 p;
    assert_ok(rg_body_get_position(w, b, &p));
    assert_string_equal(rg_world_last_error(w), "");
    assert_status(rg_body_destroy(w, b), RG_OK);
    assert_status(rg_body_get_position(w, b, &p), STALE);
    char want[128];
    snprintf(want, sizeof want, "rg_body_get_position: body 0x%" PRIx64 " is stale (destroyed, forged or of another world)", b);
    assert_string_equal(rg_world_last_error(w), want);
    assert_int_equal(rg_world_body_count(w), 0);
    assert_string_equal(rg_world_last_error(w), "");
    /* another world's errors are its own */
    assert_status(rg_world_step(s->other, 0), INVALID);
    assert_string_equal(rg_world_last_error(w), "");
    rg_world_destroy(w);
}

static void test_creating_a_world_fails_without_a_world_to_tell(void **state)
{
    (void)state;
    rg_world *w = (rg_world *)&w;
    test_alloc ta = { 0, 1, 0, 0 };
    assert_status(rg_world_create(NULL), INVALID);
    assert_status(rg_world_create_with_allocator(NULL, NULL, &w), INVALID);
    assert_status(rg_world_create_with_allocator(test_alloc_fn, &ta, NULL), INVALID);
    assert_status(rg_world_create_with_allocator(test_alloc_fn, &ta, &w), RG_ERR_OUT_OF_MEMORY);
    assert_true(w == (rg_world *)&w && ta.live_blocks == 0);
    rg_world_destroy(NULL); /* a no-op, nothing to report */
}

static void test_world_settings_fail_and_say_why(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    rg_vec2 v;
    rg_real r;
    int32_t i;
    FAILS(s, INVALID, "gravity.x", rg_world_set_gravity(w, v2(NaN, 0)));
    FAILS(s, INVALID, "gravity.y", rg_world_set_gravity(w, v2(0, INF)));
    FAILS_SAYING(s, INVALID, "gravity.y", "RG_MAX_ACCELERATION", rg_world_set_gravity(w, v2(0, -2e6)));
    FAILS(s, INVALID, "out_gravity", rg_world_get_gravity(w, NULL));
    FAILS(s, INVALID, "force.x", rg_world_set_wind(w, v2(-INF, 0)));
    FAILS_SAYING(s, INVALID, "force.y", "RG_MAX_FORCE", rg_world_set_wind(w, v2(0, 2e12)));
    FAILS(s, INVALID, "out_force", rg_world_get_wind(w, NULL));
    FAILS_SAYING(s, INVALID, "integrator", "RG_INTEGRATOR_", rg_world_set_integrator(w, 4));
    FAILS(s, INVALID, "integrator", rg_world_set_integrator(w, -1));
    FAILS(s, INVALID, "out_integrator", rg_world_get_integrator(w, NULL));
    FAILS(s, INVALID, "dt", rg_world_set_fixed_step(w, 0, 8));
    FAILS(s, INVALID, "dt", rg_world_set_fixed_step(w, NaN, 8));
    FAILS_SAYING(s, INVALID, "dt", "RG_MAX_DT", rg_world_set_fixed_step(w, 11, 8));
    FAILS(s, INVALID, "max_steps_per_advance", rg_world_set_fixed_step(w, 0.01f, 0));
    FAILS(s, INVALID, "out_max_steps", rg_world_get_fixed_step(w, NULL, NULL));
    FAILS(s, INVALID, "enabled", rg_world_set_sleeping(w, 2));
    FAILS(s, INVALID, "out_enabled", rg_world_get_sleeping(w, NULL));
    FAILS(s, INVALID, "speed", rg_world_set_sleep_thresholds(w, -1, 1));
    FAILS_SAYING(s, INVALID, "speed", "RG_MAX_SPEED", rg_world_set_sleep_thresholds(w, 2e6f, 1));
    FAILS(s, INVALID, "time", rg_world_set_sleep_thresholds(w, 1, 0));
    FAILS(s, INVALID, "time", rg_world_set_sleep_thresholds(w, 1, INF));
    FAILS(s, INVALID, "out_speed", rg_world_get_sleep_thresholds(w, NULL, &r));
    FAILS(s, INVALID, "out_time", rg_world_get_sleep_thresholds(w, &r, NULL));
    FAILS(s, INVALID, "velocity", rg_world_set_solver_iterations(w, 0, 3));
    FAILS(s, INVALID, "velocity", rg_world_set_solver_iterations(w, 65, 3));
    FAILS(s, INVALID, "position", rg_world_set_solver_iterations(w, 8, -1));
    FAILS(s, INVALID, "position", rg_world_set_solver_iterations(w, 8, 65));
    FAILS(s, INVALID, "out_velocity", rg_world_get_solver_iterations(w, NULL, &i));
    FAILS(s, INVALID, "out_position", rg_world_get_solver_iterations(w, &i, NULL));
    FAILS(s, INVALID, "slop", rg_world_set_contact_tuning(w, -1, 0.2f, 2, 1));
    FAILS_SAYING(s, INVALID, "slop", "RG_MAX_SHAPE_SIZE", rg_world_set_contact_tuning(w, 2e7f, 0.2f, 2, 1));
    FAILS(s, INVALID, "bias_rate", rg_world_set_contact_tuning(w, 0.01f, 0, 2, 1));
    FAILS(s, INVALID, "bias_rate", rg_world_set_contact_tuning(w, 0.01f, 1.5f, 2, 1));
    FAILS(s, INVALID, "max_push", rg_world_set_contact_tuning(w, 0.01f, 0.2f, 0, 1));
    FAILS(s, INVALID, "max_push", rg_world_set_contact_tuning(w, 0.01f, 0.2f, 2e6f, 1));
    FAILS(s, INVALID, "restitution_threshold", rg_world_set_contact_tuning(w, 0.01f, 0.2f, 2, -1));
    FAILS(s, INVALID, "restitution_threshold", rg_world_set_contact_tuning(w, 0.01f, 0.2f, 2, NaN));
    FAILS(s, INVALID, "out_slop", rg_world_get_contact_tuning(w, NULL, &r, &r, &r));
    FAILS(s, INVALID, "out_bias_rate", rg_world_get_contact_tuning(w, &r, NULL, &r, &r));
    FAILS(s, INVALID, "out_max_push", rg_world_get_contact_tuning(w, &r, &r, NULL, &r));
    FAILS(s, INVALID, "out_restitution_threshold", rg_world_get_contact_tuning(w, &r, &r, &r, NULL));
    FAILS(s, INVALID, "enabled", rg_world_set_continuous(w, -1));
    FAILS(s, INVALID, "out_enabled", rg_world_get_continuous(w, NULL));
    FAILS(s, INVALID, "slot", rg_world_save_slot(w, -1));
    FAILS(s, INVALID, "slot", rg_world_save_slot(w, RG_MAX_SLOTS));
    FAILS(s, INVALID, "slot", rg_world_restore_slot(w, RG_MAX_SLOTS));
    FAILS_SAYING(s, INVALID, "slot", "empty", rg_world_restore_slot(w, 3));
    FAILS(s, INVALID, "slot", rg_world_drop_slot(w, -1));
    /* each succeeds with good input and leaves "" */
    SUCCEEDS(s, rg_world_set_gravity(w, v2(0, -9.81)));
    SUCCEEDS(s, rg_world_get_gravity(w, &v));
    SUCCEEDS(s, rg_world_set_wind(w, v2(1, 0)));
    SUCCEEDS(s, rg_world_get_wind(w, &v));
    SUCCEEDS(s, rg_world_set_integrator(w, RG_INTEGRATOR_RK4));
    SUCCEEDS(s, rg_world_get_integrator(w, &i));
    SUCCEEDS(s, rg_world_set_fixed_step(w, 0.01f, 4));
    SUCCEEDS(s, rg_world_get_fixed_step(w, &r, NULL));
    SUCCEEDS(s, rg_world_set_sleeping(w, 0));
    SUCCEEDS(s, rg_world_get_sleeping(w, &i));
    SUCCEEDS(s, rg_world_set_sleep_thresholds(w, 0.1f, 1));
    SUCCEEDS(s, rg_world_get_sleep_thresholds(w, &r, &r));
    SUCCEEDS(s, rg_world_set_solver_iterations(w, 10, 4));
    SUCCEEDS(s, rg_world_get_solver_iterations(w, &i, &i));
    SUCCEEDS(s, rg_world_set_contact_tuning(w, 0.01f, 0.3f, 3, 0.5f));
    SUCCEEDS(s, rg_world_get_contact_tuning(w, &r, &r, &r, &r));
    SUCCEEDS(s, rg_world_set_continuous(w, 0));
    SUCCEEDS(s, rg_world_get_continuous(w, &i));
    SUCCEEDS(s, rg_world_set_pre_solve(w, NULL, NULL));
}

static void test_stepping_fails_and_says_why(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    rg_vec2 v;
    rg_real r;
    int32_t steps = 42;
    FAILS(s, INVALID, "dt", rg_world_step(w, 0));
    FAILS(s, INVALID, "dt", rg_world_step(w, -1));
    FAILS_SAYING(s, INVALID, "dt", "NaN", rg_world_step(w, NaN));
    FAILS_SAYING(s, INVALID, "dt", "inf", rg_world_step(w, INF));
    FAILS_SAYING(s, INVALID, "dt", "RG_MAX_DT (10)", rg_world_step(w, 1e30f));
    FAILS(s, INVALID, "frame_time", rg_world_advance(w, -1, &steps));
    FAILS(s, INVALID, "frame_time", rg_world_advance(w, NaN, &steps));
    FAILS(s, INVALID, "frame_time", rg_world_advance(w, -INF, &steps));
    assert_int_equal(steps, 42);
    FAILS(s, INVALID, "out_alpha", rg_world_get_alpha(w, NULL));
    FAILS(s, INVALID, "out", rg_body_get_interpolated_position(w, s->dyn, NULL));
    EACH_STALE(s, h, "body", rg_body_get_interpolated_position(w, h, &v));
    SUCCEEDS(s, rg_world_step(w, (rg_real)DT));
    SUCCEEDS(s, rg_world_advance(w, (rg_real)DT, &steps));
    SUCCEEDS(s, rg_world_advance(w, 1e30f, NULL)); /* any finite frame time: the cap holds */
    SUCCEEDS(s, rg_world_get_alpha(w, &r));
    SUCCEEDS(s, rg_body_get_interpolated_position(w, s->dyn, &v));
}

static void test_queries_events_draw_and_counts_fail_and_say_why(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    rg_ray_hit hit, hits[4];
    rg_body out[4];
    rg_contact_event ev[4];
    const double far = 2e12;
    FAILS(s, INVALID, "out_hit", rg_world_raycast(w, v2(0, 5), v2(0, -10), ALL, NULL));
    FAILS(s, INVALID, "origin.x", rg_world_raycast(w, v2(NaN, 5), v2(0, -10), ALL, &hit));
    FAILS_SAYING(s, INVALID, "translation.y", "RG_MAX_QUERY_COORD", rg_world_raycast(w, v2(0, 5), v2(0, -far), ALL, &hit));
    FAILS(s, INVALID, "origin.y", rg_world_raycast_all(w, v2(0, far), v2(0, -10), ALL, hits, 4));
    FAILS(s, INVALID, "translation.x", rg_world_raycast_all(w, v2(0, 5), v2(INF, 0), ALL, hits, 4));
    FAILS(s, INVALID, "capacity", rg_world_raycast_all(w, v2(0, 5), v2(0, -10), ALL, hits, -1));
    FAILS(s, INVALID, "out", rg_world_raycast_all(w, v2(0, 5), v2(0, -10), ALL, NULL, 2));
    FAILS(s, INVALID, "lower.x", rg_world_query_aabb(w, v2(NaN, 0), v2(1, 1), ALL, out, 4));
    FAILS(s, INVALID, "upper.y", rg_world_query_aabb(w, v2(0, 0), v2(1, far), ALL, out, 4));
    FAILS(s, INVALID, "lower", rg_world_query_aabb(w, v2(2, 0), v2(1, 1), ALL, out, 4));
    FAILS(s, INVALID, "upper", rg_world_query_aabb(w, v2(0, 2), v2(1, 1), ALL, out, 4));
    FAILS(s, INVALID, "capacity", rg_world_query_aabb(w, v2(0, 0), v2(1, 1), ALL, out, -1));
    FAILS(s, INVALID, "out", rg_world_query_aabb(w, v2(0, 0), v2(1, 1), ALL, NULL, 1));
    FAILS(s, INVALID, "point.x", rg_world_query_point(w, v2(-far, 0), ALL, out, 4));
    FAILS(s, INVALID, "point.y", rg_world_query_point(w, v2(0, NaN), ALL, out, 4));
    FAILS(s, INVALID, "capacity", rg_world_query_point(w, v2(0, 0), ALL, out, -3));
    FAILS(s, INVALID, "out", rg_world_query_point(w, v2(0, 0), ALL, NULL, 3));
    FAILS_SAYING(s, INVALID, "shape", "RG_SHAPE_CIRCLE", rg_world_cast_shape(w, RG_SHAPE_NONE, v2(1, 1), v2(0, 5), v2(0, -5), ALL, &hit));
    FAILS(s, INVALID, "shape", rg_world_cast_shape(w, 3, v2(1, 1), v2(0, 5), v2(0, -5), ALL, &hit));
    FAILS_SAYING(s, INVALID, "size.x", "RG_MIN_SHAPE_SIZE", rg_world_cast_shape(w, RG_SHAPE_CIRCLE, v2(0, 0), v2(0, 5), v2(0, -5), ALL, &hit));
    FAILS(s, INVALID, "size.x", rg_world_cast_shape(w, RG_SHAPE_AABB, v2(2e7, 1), v2(0, 5), v2(0, -5), ALL, &hit));
    FAILS(s, INVALID, "size.y", rg_world_cast_shape(w, RG_SHAPE_AABB, v2(1, 1e-7), v2(0, 5), v2(0, -5), ALL, &hit));
    FAILS(s, INVALID, "size.y", rg_world_cast_shape(w, RG_SHAPE_CIRCLE, v2(1, NaN), v2(0, 5), v2(0, -5), ALL, &hit));
    FAILS(s, INVALID, "origin.x", rg_world_cast_shape(w, RG_SHAPE_CIRCLE, v2(1, 0), v2(far, 5), v2(0, -5), ALL, &hit));
    FAILS(s, INVALID, "translation.y", rg_world_cast_shape(w, RG_SHAPE_CIRCLE, v2(1, 0), v2(0, 5), v2(0, -far), ALL, &hit));
    FAILS(s, INVALID, "out_hit", rg_world_cast_shape(w, RG_SHAPE_CIRCLE, v2(1, 0), v2(0, 5), v2(0, -5), ALL, NULL));
    FAILS(s, INVALID, "capacity", rg_world_get_contact_events(w, ev, -1));
    FAILS(s, INVALID, "out", rg_world_get_contact_events(w, NULL, 4));
    rg_debug_draw d;
    memset(&d, 0, sizeof d);
    d.flags = 0x40;
    FAILS(s, INVALID, "draw", rg_world_draw(w, NULL));
    FAILS_SAYING(s, INVALID, "draw->flags", "RG_DRAW_", rg_world_draw(w, &d));
    SUCCEEDS(s, rg_world_raycast(w, v2(0, 5), v2(0, -10), ALL, &hit));
    SUCCEEDS(s, rg_world_raycast_all(w, v2(0, 5), v2(0, -10), ALL, hits, 4));
    SUCCEEDS(s, rg_world_query_aabb(w, v2(-1, -1), v2(1, 1), ALL, out, 4));
    SUCCEEDS(s, rg_world_query_point(w, v2(0, 0.5), ALL, out, 4));
    SUCCEEDS(s, rg_world_cast_shape(w, RG_SHAPE_AABB, v2(0.1, 0.1), v2(0, 5), v2(0, -5), ALL, &hit));
    SUCCEEDS(s, rg_world_get_contact_events(w, NULL, 0));
    d.flags = RG_DRAW_SHAPES | RG_DRAW_SPRINGS; /* no callbacks: every one is skipped */
    SUCCEEDS(s, rg_world_draw(w, &d));
    SUCCEEDS(s, rg_world_body_count(w));
    SUCCEEDS(s, rg_world_spring_count(w));
    SUCCEEDS(s, rg_world_awake_body_count(w));
    SUCCEEDS(s, rg_world_touching_count(w));
    SUCCEEDS(s, rg_body_is_valid(w, s->bad[1]));
    SUCCEEDS(s, rg_spring_is_valid(w, s->dyn));
}

/* Every call that takes a world, given NULL: RG_ERR_INVALID_ARGUMENT (counts and validity
 * tests: 0); nothing is stored anywhere. */
static void test_a_null_world_is_refused_everywhere(void **state)
{
    scene *s = *state;
    rg_body b = s->dyn, out[2];
    rg_vec2 v;
    rg_real r;
    int32_t i;
    uint32_t u;
    uint64_t u64;
    rg_ray_hit hit;
    rg_contact c;
    rg_contact_event ev;
    rg_debug_draw d;
    memset(&d, 0, sizeof d);
    rg_world *const W = NULL;
    NULL_WORLD(INVALID, rg_world_set_gravity(W, v2(0, 0)));
    NULL_WORLD(INVALID, rg_world_get_gravity(W, &v));
    NULL_WORLD(INVALID, rg_world_set_wind(W, v2(0, 0)));
    NULL_WORLD(INVALID, rg_world_get_wind(W, &v));
    NULL_WORLD(INVALID, rg_world_set_integrator(W, 0));
    NULL_WORLD(INVALID, rg_world_get_integrator(W, &i));
    NULL_WORLD(INVALID, rg_world_step(W, 1));
    NULL_WORLD(INVALID, rg_world_set_fixed_step(W, 1, 1));
    NULL_WORLD(INVALID, rg_world_get_fixed_step(W, &r, &i));
    NULL_WORLD(INVALID, rg_world_advance(W, 1, &i));
    NULL_WORLD(INVALID, rg_world_get_alpha(W, &r));
    NULL_WORLD(INVALID, rg_body_get_interpolated_position(W, b, &v));
    NULL_WORLD(0, rg_world_body_count(W));
    NULL_WORLD(0, rg_world_spring_count(W));
    NULL_WORLD(INVALID, rg_body_create(W, RG_BODY_DYNAMIC, 1, v2(0, 0), out));
    NULL_WORLD(INVALID, rg_body_destroy(W, b));
    NULL_WORLD(0, rg_body_is_valid(W, b));
    NULL_WORLD(INVALID, rg_body_get_type(W, b, &i));
    NULL_WORLD(INVALID, rg_body_get_mass(W, b, &r));
    NULL_WORLD(INVALID, rg_body_set_mass(W, b, 1));
    NULL_WORLD(INVALID, rg_body_get_position(W, b, &v));
    NULL_WORLD(INVALID, rg_body_set_position(W, b, v2(0, 0)));
    NULL_WORLD(INVALID, rg_body_get_velocity(W, b, &v));
    NULL_WORLD(INVALID, rg_body_set_velocity(W, b, v2(0, 0)));
    NULL_WORLD(INVALID, rg_body_get_acceleration(W, b, &v));
    NULL_WORLD(INVALID, rg_body_apply_force(W, b, v2(0, 0)));
    NULL_WORLD(INVALID, rg_body_apply_impulse(W, b, v2(0, 0)));
    NULL_WORLD(INVALID, rg_body_set_gravity_scale(W, b, 1));
    NULL_WORLD(INVALID, rg_body_set_drag(W, b, 0, 0));
    NULL_WORLD(INVALID, rg_body_set_surface_friction(W, b, 0, 0));
    NULL_WORLD(INVALID, rg_body_set_speed_limits(W, b, 0, 0));
    NULL_WORLD(INVALID, rg_body_set_user_data(W, b, 1));
    NULL_WORLD(INVALID, rg_body_get_user_data(W, b, &u64));
    NULL_WORLD(INVALID, rg_spring_create(W, b, 0, v2(0, 0), 0, 1, 0, &u64));
    NULL_WORLD(INVALID, rg_spring_destroy(W, s->spring));
    NULL_WORLD(0, rg_spring_is_valid(W, s->spring));
    NULL_WORLD(INVALID, rg_body_set_circle(W, b, 1));
    NULL_WORLD(INVALID, rg_body_set_aabb(W, b, 1, 1));
    NULL_WORLD(INVALID, rg_body_clear_shape(W, b));
    NULL_WORLD(INVALID, rg_body_get_shape(W, b, &i, &v));
    NULL_WORLD(INVALID, rg_body_set_restitution(W, b, 0));
    NULL_WORLD(INVALID, rg_body_get_restitution(W, b, &r));
    NULL_WORLD(INVALID, rg_body_get_gravity_scale(W, b, &r));
    NULL_WORLD(INVALID, rg_body_get_drag(W, b, &r, &r));
    NULL_WORLD(INVALID, rg_body_get_speed_limits(W, b, &r, &r));
    NULL_WORLD(INVALID, rg_body_set_friction(W, b, 0));
    NULL_WORLD(INVALID, rg_body_get_friction(W, b, &r));
    NULL_WORLD(INVALID, rg_body_set_sensor(W, b, 0));
    NULL_WORLD(INVALID, rg_body_is_sensor(W, b, &i));
    NULL_WORLD(INVALID, rg_body_set_filter(W, b, 1, 1));
    NULL_WORLD(INVALID, rg_body_get_filter(W, b, &u, &u));
    NULL_WORLD(INVALID, rg_body_is_grounded(W, b, &i));
    NULL_WORLD(INVALID, rg_world_set_sleeping(W, 1));
    NULL_WORLD(INVALID, rg_world_get_sleeping(W, &i));
    NULL_WORLD(INVALID, rg_world_set_sleep_thresholds(W, 1, 1));
    NULL_WORLD(INVALID, rg_world_get_sleep_thresholds(W, &r, &r));
    NULL_WORLD(INVALID, rg_body_is_awake(W, b, &i));
    NULL_WORLD(INVALID, rg_body_wake(W, b));
    NULL_WORLD(0, rg_world_awake_body_count(W));
    NULL_WORLD(INVALID, rg_world_set_solver_iterations(W, 8, 3));
    NULL_WORLD(INVALID, rg_world_get_solver_iterations(W, &i, &i));
    NULL_WORLD(INVALID, rg_world_set_contact_tuning(W, 0, 1, 1, 0));
    NULL_WORLD(INVALID, rg_world_get_contact_tuning(W, &r, &r, &r, &r));
    NULL_WORLD(INVALID, rg_world_set_continuous(W, 1));
    NULL_WORLD(INVALID, rg_world_get_continuous(W, &i));
    NULL_WORLD(0, rg_world_touching_count(W));
    NULL_WORLD(INVALID, rg_world_get_contact_events(W, &ev, 1));
    NULL_WORLD(INVALID, rg_world_raycast(W, v2(0, 0), v2(1, 0), ALL, &hit));
    NULL_WORLD(INVALID, rg_world_query_aabb(W, v2(0, 0), v2(1, 1), ALL, out, 2));
    NULL_WORLD(INVALID, rg_body_set_one_way(W, b, v2(0, 1)));
    NULL_WORLD(INVALID, rg_body_get_one_way(W, b, &v));
    NULL_WORLD(INVALID, rg_body_pass_through(W, b, s->floor));
    NULL_WORLD(INVALID, rg_world_set_pre_solve(W, NULL, NULL));
    NULL_WORLD(INVALID, rg_body_get_contacts(W, b, &c, 1));
    NULL_WORLD(INVALID, rg_world_raycast_all(W, v2(0, 0), v2(1, 0), ALL, &hit, 1));
    NULL_WORLD(INVALID, rg_world_query_point(W, v2(0, 0), ALL, out, 2));
    NULL_WORLD(INVALID, rg_world_save_slot(W, 0));
    NULL_WORLD(INVALID, rg_world_restore_slot(W, 0));
    NULL_WORLD(INVALID, rg_world_drop_slot(W, 0));
    NULL_WORLD(INVALID, rg_world_cast_shape(W, RG_SHAPE_CIRCLE, v2(1, 0), v2(0, 0), v2(1, 0), ALL, &hit));
    NULL_WORLD(INVALID, rg_body_move(W, b, v2(1, 0), ALL, RG_MOVE_SLIDE, &v, NULL, 0, &i));
    NULL_WORLD(INVALID, rg_world_draw(W, &d));
    assert_string_equal(rg_world_last_error(W), "rg_world_last_error: world is NULL");
    assert_string_equal(rg_world_last_error(s->w), ""); /* the scene's world saw none of it */
}

/* ---------------------------------------------------------------- locked */

typedef struct locked_run {
    scene *s;
    int calls;
    unsigned char snap[4096]; /* a save of the scene, for a restore the lock refuses */
    size_t snap_size;
} locked_run;

#define LOCKED(s, call) FAILS((s), RG_ERR_LOCKED, "locked", call)

static void locked_run_init(locked_run *l, scene *s)
{
    l->s = s;
    l->calls = 0;
    assert_ok(rg_world_save(s->w, l->snap, sizeof l->snap, &l->snap_size));
}

/* Inside a callback of the world (the pre-solve hook, the task system's enqueue in a step or
 * a restore, the allocator, a draw's callback) every call that changes the world is refused,
 * names itself and "locked", and changes nothing; getters and queries work and leave "". */
static void locked_calls(locked_run *l)
{
    scene *s = l->s;
    rg_world *w = s->w;
    rg_body d = s->dyn, nb;
    uint64_t sp;
    rg_vec2 v;
    int32_t n;
    LOCKED(s, rg_world_set_gravity(w, v2(0, 0)));
    LOCKED(s, rg_world_set_wind(w, v2(1, 0)));
    LOCKED(s, rg_world_set_integrator(w, RG_INTEGRATOR_RK4));
    LOCKED(s, rg_world_step(w, (rg_real)DT));
    LOCKED(s, rg_world_set_fixed_step(w, 0.01f, 2));
    LOCKED(s, rg_world_advance(w, (rg_real)DT, &n));
    LOCKED(s, rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(0, 0), &nb));
    LOCKED(s, rg_body_destroy(w, s->bare));
    LOCKED(s, rg_body_set_mass(w, d, 3));
    LOCKED(s, rg_body_set_position(w, d, v2(1, 1)));
    LOCKED(s, rg_body_set_velocity(w, d, v2(1, 1)));
    LOCKED(s, rg_body_apply_force(w, d, v2(1, 1)));
    LOCKED(s, rg_body_apply_impulse(w, d, v2(1, 1)));
    LOCKED(s, rg_body_set_gravity_scale(w, d, 2));
    LOCKED(s, rg_body_set_drag(w, d, 1, 1));
    LOCKED(s, rg_body_set_surface_friction(w, d, 1, 1));
    LOCKED(s, rg_body_set_speed_limits(w, d, 0, 9));
    LOCKED(s, rg_body_set_user_data(w, d, 7));
    LOCKED(s, rg_spring_create(w, d, 0, v2(0, 9), 1, 1, 0, &sp));
    LOCKED(s, rg_spring_destroy(w, s->spring));
    LOCKED(s, rg_body_set_circle(w, d, 1));
    LOCKED(s, rg_body_set_aabb(w, d, 1, 1));
    LOCKED(s, rg_body_clear_shape(w, d));
    LOCKED(s, rg_body_set_restitution(w, d, 0.5f));
    LOCKED(s, rg_body_set_friction(w, d, 0.1f));
    LOCKED(s, rg_body_set_sensor(w, d, 1));
    LOCKED(s, rg_body_set_filter(w, d, 2, 2));
    LOCKED(s, rg_world_set_sleeping(w, 0));
    LOCKED(s, rg_world_set_sleep_thresholds(w, 1, 1));
    LOCKED(s, rg_body_wake(w, d));
    LOCKED(s, rg_world_set_solver_iterations(w, 4, 1));
    LOCKED(s, rg_world_set_contact_tuning(w, 0.01f, 0.5f, 1, 1));
    LOCKED(s, rg_world_set_continuous(w, 0));
    LOCKED(s, rg_body_set_one_way(w, d, v2(0, 1)));
    LOCKED(s, rg_body_pass_through(w, d, s->floor));
    LOCKED(s, rg_world_set_pre_solve(w, NULL, NULL));
    LOCKED(s, rg_body_move(w, d, v2(1, 1), ALL, RG_MOVE_SLIDE, &v, NULL, 0, &n));
    LOCKED(s, rg_world_save_slot(w, 0));
    LOCKED(s, rg_world_restore_slot(w, 0));
    LOCKED(s, rg_world_drop_slot(w, 0));
    LOCKED(s, rg_world_restore(w, l->snap, l->snap_size));
    LOCKED(s, rg_world_set_task_system(w, NULL));
    rg_world_destroy(w); /* a no-op from inside */
    assert_true(rg_body_is_valid(w, d));
    SUCCEEDS(s, rg_body_get_position(w, d, &v));
    SUCCEEDS(s, rg_world_query_point(w, v2(0, 0.5), ALL, NULL, 0));
    assert_status(rg_world_set_gravity(w, v2(0, 1)), RG_ERR_LOCKED); /* the call must clear it */
}

static int32_t locked_hook(rg_body a, rg_body b, rg_vec2 normal, rg_real separation, void *user)
{
    (void)a, (void)b, (void)normal, (void)separation;
    locked_run *l = user;
    if (l->calls++ == 0) locked_calls(l);
    return 1;
}

static void test_calls_from_inside_a_step_are_locked_and_say_so(void **state)
{
    scene *s = *state;
    static locked_run l;
    locked_run_init(&l, s);
    assert_ok(rg_world_set_pre_solve(s->w, locked_hook, &l));
    SUCCEEDS(s, rg_world_step(s->w, (rg_real)DT));
    assert_true(l.calls > 0);
    l.calls = 0;
    int32_t steps = 0;
    SUCCEEDS(s, rg_world_advance(s->w, (rg_real)DT, &steps));
    assert_true(steps == 1 && l.calls > 0);
}

/* A task system that runs each task at once, after the calls of locked_calls on its first. */
static void *locked_enqueue(rg_task_fn *fn, int32_t count, int32_t min_range, void *context, void *user)
{
    (void)min_range;
    locked_run *l = user;
    if (l->calls++ == 0) locked_calls(l);
    fn(0, count, 0, context);
    return NULL;
}

static void locked_finish(void *task, void *user) { (void)task, (void)user; }

/* The task system is called inside steps and restores (this scene's snapshot from outside
 * is checked on it; a kept one is too small to spread): a game's job system that calls on the
 * world from there (to destroy a body, step again, destroy the world) is refused, and the
 * step or restore goes on unharmed. */
static void test_calls_from_the_task_system_are_locked_and_say_so(void **state)
{
    scene *s = *state;
    static locked_run l;
    locked_run_init(&l, s);
    rg_task_system tasks = { 2, locked_enqueue, locked_finish, &l };
    assert_ok(rg_world_set_task_system(s->w, &tasks));
    SUCCEEDS(s, rg_world_step(s->w, (rg_real)DT));
    assert_true(l.calls > 0);
    l.calls = 0;
    SUCCEEDS(s, rg_world_restore(s->w, l.snap, l.snap_size));
    assert_true(l.calls > 0);
    assert_ok(rg_world_set_task_system(s->w, NULL));
    SUCCEEDS(s, rg_world_set_gravity(s->w, v2(0, -9)));
}

/* The allocator: the scene's counting allocator, which runs locked_calls once when armed. */
static locked_run *alloc_run;

static void *locked_alloc_fn(void *user, void *ptr, size_t old_size, size_t new_size)
{
    locked_run *l = alloc_run;
    if (l != NULL && new_size > 0) {
        alloc_run = NULL;
        l->calls++;
        locked_calls(l);
    }
    return test_alloc_fn(user, ptr, old_size, new_size);
}

static int locked_alloc_setup(void **state) { return scene_setup_on(state, locked_alloc_fn); }

/* Armed, the allocator's next allocation runs locked_calls; `call` must make one and
 * succeed with "" (the refused calls' errors are not its own). */
#define ALLOC_LOCKED(s, l, call)                                 \
    do {                                                         \
        (l)->calls = 0;                                          \
        alloc_run = (l);                                         \
        SUCCEEDS((s), call);                                     \
        assert_true((l)->calls == 1 && alloc_run == NULL);       \
    } while (0)

/* The allocator is called from inside the calls that grow the world (a body, a step's
 * scratch, a slot): what it calls on the world that would change it is refused. */
static void test_calls_from_the_allocator_are_locked_and_say_so(void **state)
{
    scene *s = *state;
    static locked_run l;
    locked_run_init(&l, s);
    rg_body nb = 0;
    /* bodies until one grows the body storage */
    long before = s->ta.calls;
    for (int k = 0; k < 1000 && s->ta.calls == before; k++) {
        alloc_run = &l;
        l.calls = 0;
        SUCCEEDS(s, rg_body_create(s->w, RG_BODY_DYNAMIC, 1, v2(40 + k, 40), &nb));
    }
    assert_true(s->ta.calls > before && l.calls == 1 && alloc_run == NULL);
    for (int k = 0; k < 600; k++) make_body(s->w, 1, 100 + 3 * (k / 2), 50);
    ALLOC_LOCKED(s, &l, rg_world_step(s->w, (rg_real)DT)); /* the integrator's scratch grows */
    ALLOC_LOCKED(s, &l, rg_world_save_slot(s->w, 2));
    SUCCEEDS(s, rg_world_set_gravity(s->w, v2(0, -9)));
}

/* A draw's callbacks: a change of the world in the middle of the walk is refused. */
static void locked_draw_box(rg_body body, rg_vec2 lower, rg_vec2 upper, uint32_t rgba, void *user)
{
    (void)body, (void)lower, (void)upper, (void)rgba;
    locked_run *l = user;
    if (l->calls++ == 0) locked_calls(l);
}

static void locked_draw_circle(rg_body body, rg_vec2 center, rg_real radius, uint32_t rgba, void *user)
{
    (void)center, (void)radius;
    locked_draw_box(body, center, center, rgba, user);
}

static void test_calls_from_a_draw_are_locked_and_say_so(void **state)
{
    scene *s = *state;
    static locked_run l;
    locked_run_init(&l, s);
    rg_debug_draw d;
    memset(&d, 0, sizeof d);
    d.circle = locked_draw_circle;
    d.box = locked_draw_box;
    d.flags = RG_DRAW_SHAPES;
    d.user = &l;
    SUCCEEDS(s, rg_world_draw(s->w, &d));
    assert_true(l.calls > 0);
    SUCCEEDS(s, rg_world_set_gravity(s->w, v2(0, -9)));
}

/* ---------------------------------------------------------------- out of memory */

/* Repeats `call` (each with its own target k) with every allocation failing until one
 * needs memory: that one returns RG_ERR_OUT_OF_MEMORY, names its function and what it
 * could not grow, and changes nothing. */
#define OOM_EVENTUALLY(s, what, k, limit, call)                                    \
    do {                                                                           \
        (s)->ta.fail_at = (s)->ta.calls + 1;                                       \
        int done_ = 0;                                                             \
        for (int k = 0; k < (limit) && !done_; k++) {                              \
            fp before_;                                                            \
            fingerprint((s), &before_);                                            \
            long calls_ = (s)->ta.calls;                                           \
            int32_t got_ = (int32_t)(call);                                        \
            if (got_ == RG_OK && (s)->ta.calls == calls_) continue;                \
            check_failed((s), &before_, got_, RG_ERR_OUT_OF_MEMORY, "out of memory", \
                         what, #call, __LINE__);                                   \
            done_ = 1;                                                             \
        }                                                                          \
        (s)->ta.fail_at = 0;                                                       \
        assert_true(done_);                                                        \
    } while (0)

static void test_out_of_memory_says_what_could_not_grow(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    enum { N = 600 };
    static rg_body extra[N];
    rg_body nb;
    uint64_t sp;
    OOM_EVENTUALLY(s, "body storage", k, 100, rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(30 + k, 30), &nb));
    OOM_EVENTUALLY(s, "spring storage", k, 100, rg_spring_create(w, s->bare, 0, v2(k, 0), 1, 1, 0, &sp));
    for (int k = 0; k < N; k++) extra[k] = make_body(w, 1, 100 + 3 * (k / 2), 50);
    OOM_EVENTUALLY(s, "integrator scratch", k, 1, rg_world_step(w, (rg_real)DT));
    OOM_EVENTUALLY(s, "integrator scratch", k, 1, rg_world_advance(w, (rg_real)DT, NULL));
    OOM_EVENTUALLY(s, "broadphase", k, N, rg_body_set_circle(w, extra[k], 0.5f + 0.1f * (float)(k % 2)));
    /* overlapping pairs that no pair search has met yet, so that pass_through stores each */
    for (int k = 0; k < N; k++) assert_ok(rg_body_set_circle(w, extra[k], 0.5f + 0.1f * (float)(k % 2)));
    OOM_EVENTUALLY(s, "contact storage", k, N / 2, rg_body_pass_through(w, extra[2 * k], extra[2 * k + 1]));
    /* with memory again, every one of them works */
    SUCCEEDS(s, rg_world_step(w, (rg_real)DT));
    SUCCEEDS(s, rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(0, 40), &nb));
}

/* Collision scratch: a world whose integrator needs no scratch, grown past its collide
 * stage's scratch, fails its next step there. */
static void test_out_of_memory_in_the_collision_scratch(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    assert_ok(rg_spring_destroy(w, s->spring)); /* springs need the integrator scratch */
    for (int k = 0; k < 70; k++) make_body(w, 1, 200 + k, 0);
    OOM_EVENTUALLY(s, "collision scratch", k, 1, rg_world_step(w, (rg_real)DT));
}

/* A pair search that cannot store its new contacts lets its step run without them (they are
 * looked for again in the next step), and the next step grows the storage before it changes
 * anything: without memory it fails, changing nothing, so no body falls through what it
 * stands on while memory is short; with memory again every step works and the pile rests
 * on the floor.  (Until this test, every step returned RG_OK and ran without the pairs: a
 * pile fell through its floor.) */
static void test_a_step_out_of_contact_storage_fails_the_next_one_cleanly(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    enum { COLS = 40, ROWS = 10, N = COLS * ROWS };
    static rg_body drop[N];
    /* a block of circles that touch their neighbours, above the scene, colliding with
     * nothing until a step has grown the scratch for them */
    for (int k = 0; k < N; k++) {
        drop[k] = circle_body(w, RG_BODY_DYNAMIC, 1, -19.5 + k % COLS, 6.5 + k / COLS, 0.5);
        assert_ok(rg_body_set_filter(w, drop[k], 2, 0));
    }
    assert_ok(rg_world_step(w, (rg_real)DT));
    for (int k = 0; k < N; k++) assert_ok(rg_body_set_filter(w, drop[k], 1, 0xFFFFFFFFu));
    s->ta.fail_at = s->ta.calls + 1; /* from now on every allocation fails */
    long calls = s->ta.calls;
    assert_ok(rg_world_step(w, (rg_real)DT)); /* runs without the pairs it could not store */
    assert_true(s->ta.calls > calls);
    for (int k = 0; k < 120; k++) {
        uint64_t h0 = 0, h1 = 0;
        assert_ok(rg_world_hash(w, &h0));
        FAILS_SAYING(s, RG_ERR_OUT_OF_MEMORY, "out of memory", "contact storage", rg_world_step(w, (rg_real)DT));
        int32_t steps = -1;
        FAILS_SAYING(s, RG_ERR_OUT_OF_MEMORY, "out of memory", "contact storage",
                     rg_world_advance(w, (rg_real)DT, &steps));
        assert_int_equal(steps, -1);
        assert_ok(rg_world_hash(w, &h1));
        assert_true(h0 == h1);
    }
    s->ta.fail_at = 0;
    for (int k = 0; k < 180; k++) SUCCEEDS(s, rg_world_step(w, (rg_real)DT));
    /* no circle over the floor (|x| < 20; the pile spreads past its ends) sunk half its
     * radius into it (the lowest rest at y = 0.5 less the slop; one that fell through is
     * below 0) */
    for (int k = 0; k < N; k++) {
        rg_vec2 p = pos_of(w, drop[k]);
        if (fabs((double)p.x) < 20) assert_true((double)p.y > 0.25);
    }
}

int main(void)
{
#define T(f) cmocka_unit_test_setup_teardown(f, scene_setup, scene_teardown)
    const struct CMUnitTest tests[] = {
        T(test_last_error_is_never_null_and_empty_after_a_success),
        T(test_creating_a_world_fails_without_a_world_to_tell),
        T(test_world_settings_fail_and_say_why),
        T(test_stepping_fails_and_says_why),
        T(test_queries_events_draw_and_counts_fail_and_say_why),
        T(test_a_null_world_is_refused_everywhere),
        T(test_calls_from_inside_a_step_are_locked_and_say_so),
        T(test_calls_from_the_task_system_are_locked_and_say_so),
        cmocka_unit_test_setup_teardown(test_calls_from_the_allocator_are_locked_and_say_so, locked_alloc_setup,
                                        scene_teardown),
        T(test_calls_from_a_draw_are_locked_and_say_so),
        T(test_out_of_memory_says_what_could_not_grow),
        T(test_out_of_memory_in_the_collision_scratch),
        T(test_a_step_out_of_contact_storage_fails_the_next_one_cleanly),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
