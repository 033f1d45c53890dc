/* test_errors_body.c: every error path of the body, force, spring, shape, material,
 * sleeping, gameplay-collision and mover calls: the status, that nothing changed, and that
 * rg_world_last_error names the function and the argument; "" after a success.  Each call
 * that takes a body is given the four kinds of stale handle (0, destroyed, another world's,
 * a spring's). */
#include "errors.h"

static void test_body_lifetime_and_mass_fail_and_say_why(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    rg_body nb = 99;
    int32_t i;
    rg_real r;
    FAILS_SAYING(s, INVALID, "type", "RG_BODY_", rg_body_create(w, 3, 1, v2(0, 0), &nb));
    FAILS(s, INVALID, "type", rg_body_create(w, -1, 1, v2(0, 0), &nb));
    FAILS(s, INVALID, "mass", rg_body_create(w, RG_BODY_DYNAMIC, 0, v2(0, 0), &nb));
    FAILS(s, INVALID, "mass", rg_body_create(w, RG_BODY_DYNAMIC, -1, v2(0, 0), &nb));
    FAILS(s, INVALID, "mass", rg_body_create(w, RG_BODY_DYNAMIC, NaN, v2(0, 0), &nb));
    FAILS_SAYING(s, INVALID, "mass", "RG_MIN_MASS", rg_body_create(w, RG_BODY_DYNAMIC, (rg_real)1e-40, v2(0, 0), &nb));
    FAILS_SAYING(s, INVALID, "mass", "RG_MAX_MASS", rg_body_create(w, RG_BODY_DYNAMIC, 2e9f, v2(0, 0), &nb));
    FAILS(s, INVALID, "mass", rg_body_create(w, RG_BODY_STATIC, INF, v2(0, 0), &nb));
    FAILS_SAYING(s, INVALID, "position.x", "RG_MAX_COORD", rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(3e37, 0), &nb));
    FAILS(s, INVALID, "position.y", rg_body_create(w, RG_BODY_KINEMATIC, 0, v2(0, NaN), &nb));
    FAILS(s, INVALID, "out_body", rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(0, 0), NULL));
    assert_true(nb == 99);
    EACH_STALE(s, h, "body", rg_body_destroy(w, h));
    EACH_STALE(s, h, "body", rg_body_get_type(w, h, &i));
    EACH_STALE(s, h, "body", rg_body_get_mass(w, h, &r));
    EACH_STALE(s, h, "body", rg_body_set_mass(w, h, 1));
    FAILS(s, INVALID, "out_type", rg_body_get_type(w, s->dyn, NULL));
    FAILS(s, INVALID, "out_mass", rg_body_get_mass(w, s->dyn, NULL));
    FAILS(s, INVALID, "mass", rg_body_set_mass(w, s->dyn, 0));
    FAILS(s, INVALID, "mass", rg_body_set_mass(w, s->dyn, 1e10f));
    FAILS_SAYING(s, INVALID, "body", "not dynamic", rg_body_set_mass(w, s->kin, 1));
    SUCCEEDS(s, rg_body_create(w, RG_BODY_STATIC, -5, v2(0, -3), &nb)); /* mass ignored */
    SUCCEEDS(s, rg_body_get_type(w, nb, &i));
    SUCCEEDS(s, rg_body_get_mass(w, s->dyn, &r));
    SUCCEEDS(s, rg_body_set_mass(w, s->dyn, 3));
    SUCCEEDS(s, rg_body_is_valid(w, nb));
    SUCCEEDS(s, rg_body_destroy(w, nb));
}

static void test_body_state_fails_and_says_why(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    rg_vec2 v;
    uint64_t u;
    EACH_STALE(s, h, "body", rg_body_get_position(w, h, &v));
    EACH_STALE(s, h, "body", rg_body_set_position(w, h, v2(0, 0)));
    EACH_STALE(s, h, "body", rg_body_get_velocity(w, h, &v));
    EACH_STALE(s, h, "body", rg_body_set_velocity(w, h, v2(0, 0)));
    EACH_STALE(s, h, "body", rg_body_get_acceleration(w, h, &v));
    EACH_STALE(s, h, "body", rg_body_set_user_data(w, h, 1));
    EACH_STALE(s, h, "body", rg_body_get_user_data(w, h, &u));
    FAILS(s, INVALID, "out", rg_body_get_position(w, s->dyn, NULL));
    FAILS(s, INVALID, "out", rg_body_get_velocity(w, s->dyn, NULL));
    FAILS(s, INVALID, "out", rg_body_get_acceleration(w, s->dyn, NULL));
    FAILS(s, INVALID, "out", rg_body_get_user_data(w, s->dyn, NULL));
    FAILS(s, INVALID, "position.x", rg_body_set_position(w, s->dyn, v2(NaN, 0)));
    FAILS(s, INVALID, "position.y", rg_body_set_position(w, s->dyn, v2(0, -INF)));
    FAILS_SAYING(s, INVALID, "position.y", "-RG_MAX_COORD", rg_body_set_position(w, s->dyn, v2(0, -2e9)));
    FAILS(s, INVALID, "velocity.x", rg_body_set_velocity(w, s->dyn, v2(INF, 0)));
    FAILS_SAYING(s, INVALID, "velocity.y", "RG_MAX_SPEED", rg_body_set_velocity(w, s->kin, v2(0, 2e6)));
    FAILS_SAYING(s, INVALID, "velocity", "static", rg_body_set_velocity(w, s->floor, v2(1, 0)));
    SUCCEEDS(s, rg_body_set_position(w, s->bare, v2(1, 7)));
    SUCCEEDS(s, rg_body_get_position(w, s->bare, &v));
    SUCCEEDS(s, rg_body_set_velocity(w, s->floor, v2(0, 0)));
    SUCCEEDS(s, rg_body_get_velocity(w, s->dyn, &v));
    SUCCEEDS(s, rg_body_get_acceleration(w, s->dyn, &v));
    SUCCEEDS(s, rg_body_set_user_data(w, s->dyn, 42));
    SUCCEEDS(s, rg_body_get_user_data(w, s->dyn, &u));
}

static void test_forces_fail_and_say_why(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    rg_body d = s->dyn;
    EACH_STALE(s, h, "body", rg_body_apply_force(w, h, v2(1, 0)));
    EACH_STALE(s, h, "body", rg_body_apply_impulse(w, h, v2(1, 0)));
    EACH_STALE(s, h, "body", rg_body_set_gravity_scale(w, h, 1));
    EACH_STALE(s, h, "body", rg_body_set_drag(w, h, 0, 0));
    EACH_STALE(s, h, "body", rg_body_set_surface_friction(w, h, 0, 0));
    EACH_STALE(s, h, "body", rg_body_set_speed_limits(w, h, 0, 0));
    rg_real r;
    EACH_STALE(s, h, "body", rg_body_get_gravity_scale(w, h, &r));
    EACH_STALE(s, h, "body", rg_body_get_drag(w, h, &r, &r));
    EACH_STALE(s, h, "body", rg_body_get_speed_limits(w, h, &r, &r));
    FAILS(s, INVALID, "out_scale", rg_body_get_gravity_scale(w, d, NULL));
    FAILS(s, INVALID, "out_quadratic", rg_body_get_drag(w, d, NULL, NULL));
    FAILS(s, INVALID, "out_max_speed", rg_body_get_speed_limits(w, d, NULL, NULL));
    FAILS(s, INVALID, "force.x", rg_body_apply_force(w, d, v2(NaN, 0)));
    FAILS_SAYING(s, INVALID, "force.y", "RG_MAX_FORCE", rg_body_apply_force(w, d, v2(0, -2e12)));
    FAILS(s, INVALID, "impulse.y", rg_body_apply_impulse(w, d, v2(0, INF)));
    FAILS_SAYING(s, INVALID, "impulse.x", "RG_MAX_FORCE", rg_body_apply_impulse(w, d, v2(2e12, 0)));
    FAILS(s, INVALID, "scale", rg_body_set_gravity_scale(w, d, NaN));
    FAILS_SAYING(s, INVALID, "scale", "RG_MAX_GRAVITY_SCALE", rg_body_set_gravity_scale(w, d, -2e3f));
    FAILS(s, INVALID, "linear", rg_body_set_drag(w, d, -1, 0));
    FAILS_SAYING(s, INVALID, "quadratic", "RG_MAX_DRAG", rg_body_set_drag(w, d, 0, 2e9f));
    FAILS(s, INVALID, "mu", rg_body_set_surface_friction(w, d, -1, 1));
    FAILS_SAYING(s, INVALID, "mu", "RG_MAX_FRICTION", rg_body_set_surface_friction(w, d, 2e3f, 1));
    FAILS(s, INVALID, "normal_force", rg_body_set_surface_friction(w, d, 1, INF));
    FAILS(s, INVALID, "normal_force", rg_body_set_surface_friction(w, d, 1, 2e12f));
    FAILS(s, INVALID, "min_speed", rg_body_set_speed_limits(w, d, -1, 0));
    FAILS(s, INVALID, "max_speed", rg_body_set_speed_limits(w, d, 0, 2e6f));
    FAILS_SAYING(s, INVALID, "max_speed", "min_speed", rg_body_set_speed_limits(w, d, 2, 1));
    SUCCEEDS(s, rg_body_apply_force(w, d, v2(1e12, 0)));
    /* forces add up: a sum beyond the range is refused, the first force stays */
    FAILS_SAYING(s, INVALID, "force", "RG_MAX_FORCE", rg_body_apply_force(w, d, v2(1e12, 0)));
    SUCCEEDS(s, rg_body_apply_force(w, d, v2(-1e12, 0)));
    /* an impulse is bounded by the velocity it gives: 2 kg at 1e6 m/s is 2e6 N s */
    FAILS_SAYING(s, INVALID, "impulse", "RG_MAX_SPEED", rg_body_apply_impulse(w, d, v2(0, 3e6)));
    SUCCEEDS(s, rg_body_apply_impulse(w, d, v2(0, 1)));
    SUCCEEDS(s, rg_body_apply_impulse(w, s->floor, v2(1e12, 0))); /* no effect on static bodies */
    SUCCEEDS(s, rg_body_set_gravity_scale(w, d, -1));
    SUCCEEDS(s, rg_body_set_drag(w, d, 1, 0.5f));
    SUCCEEDS(s, rg_body_set_surface_friction(w, d, 0.5f, 10));
    SUCCEEDS(s, rg_body_set_speed_limits(w, d, 0.1f, 0));
    SUCCEEDS(s, rg_body_get_gravity_scale(w, d, &r));
    SUCCEEDS(s, rg_body_get_drag(w, d, NULL, &r));
    SUCCEEDS(s, rg_body_get_speed_limits(w, d, &r, NULL));
}

static void test_springs_fail_and_say_why(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    uint64_t sp = 77;
    rg_body d = s->dyn, k = s->kin;
    FAILS(s, INVALID, "out_spring", rg_spring_create(w, d, k, v2(0, 0), 1, 1, 0, NULL));
    FAILS(s, INVALID, "rest_length", rg_spring_create(w, d, k, v2(0, 0), -1, 1, 0, &sp));
    FAILS_SAYING(s, INVALID, "rest_length", "RG_MAX_COORD", rg_spring_create(w, d, k, v2(0, 0), 2e9f, 1, 0, &sp));
    FAILS(s, INVALID, "stiffness", rg_spring_create(w, d, k, v2(0, 0), 1, NaN, 0, &sp));
    FAILS_SAYING(s, INVALID, "stiffness", "RG_MAX_STIFFNESS", rg_spring_create(w, d, k, v2(0, 0), 1, 2e9f, 0, &sp));
    FAILS(s, INVALID, "damping", rg_spring_create(w, d, k, v2(0, 0), 1, 1, -1, &sp));
    FAILS_SAYING(s, INVALID, "damping", "RG_MAX_DAMPING", rg_spring_create(w, d, k, v2(0, 0), 1, 1, 2e9f, &sp));
    FAILS_SAYING(s, INVALID, "anchor.x", "RG_MAX_COORD", rg_spring_create(w, d, 0, v2(-1e20, 0), 1, 1, 0, &sp));
    FAILS(s, INVALID, "anchor.y", rg_spring_create(w, d, 0, v2(0, NaN), 1, 1, 0, &sp));
    FAILS(s, INVALID, "b", rg_spring_create(w, d, d, v2(0, 0), 1, 1, 0, &sp));
    for (int q = 0; q < 4; q++) {
        rg_body h = s->bad[q];
        if (h != 0) FAILS(s, STALE, "b", rg_spring_create(w, d, h, v2(0, 0), 1, 1, 0, &sp));
        FAILS(s, STALE, "a", rg_spring_create(w, h, d, v2(0, 0), 1, 1, 0, &sp));
    }
    assert_true(sp == 77);
    EACH_STALE(s, h, "spring", rg_spring_destroy(w, h == s->spring ? s->dyn : h)); /* a body is no spring */
    SUCCEEDS(s, rg_spring_create(w, d, 0, v2(1e9, -1e9), 1e9f, 1e9f, 1e9f, &sp));
    SUCCEEDS(s, rg_spring_is_valid(w, sp));
    SUCCEEDS(s, rg_spring_destroy(w, sp));
}

static void test_shapes_and_materials_fail_and_say_why(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    rg_body d = s->dyn;
    int32_t i;
    rg_real r;
    rg_vec2 v;
    uint32_t u;
    EACH_STALE(s, h, "body", rg_body_set_circle(w, h, 1));
    EACH_STALE(s, h, "body", rg_body_set_aabb(w, h, 1, 1));
    EACH_STALE(s, h, "body", rg_body_clear_shape(w, h));
    EACH_STALE(s, h, "body", rg_body_get_shape(w, h, &i, &v));
    EACH_STALE(s, h, "body", rg_body_set_restitution(w, h, 0));
    EACH_STALE(s, h, "body", rg_body_get_restitution(w, h, &r));
    EACH_STALE(s, h, "body", rg_body_set_friction(w, h, 0));
    EACH_STALE(s, h, "body", rg_body_get_friction(w, h, &r));
    EACH_STALE(s, h, "body", rg_body_set_sensor(w, h, 0));
    EACH_STALE(s, h, "body", rg_body_is_sensor(w, h, &i));
    EACH_STALE(s, h, "body", rg_body_set_filter(w, h, 1, 1));
    EACH_STALE(s, h, "body", rg_body_get_filter(w, h, &u, &u));
    EACH_STALE(s, h, "body", rg_body_is_grounded(w, h, &i));
    EACH_STALE(s, h, "body", rg_body_is_awake(w, h, &i));
    EACH_STALE(s, h, "body", rg_body_wake(w, h));
    EACH_STALE(s, h, "body", rg_body_set_one_way(w, h, v2(0, 1)));
    EACH_STALE(s, h, "body", rg_body_get_one_way(w, h, &v));
    FAILS(s, INVALID, "radius", rg_body_set_circle(w, d, 0));
    FAILS(s, INVALID, "radius", rg_body_set_circle(w, d, NaN));
    FAILS_SAYING(s, INVALID, "radius", "RG_MIN_SHAPE_SIZE", rg_body_set_circle(w, d, 1e-7f));
    FAILS_SAYING(s, INVALID, "radius", "RG_MAX_SHAPE_SIZE (1e+07)", rg_body_set_circle(w, d, 1e8f));
    FAILS(s, INVALID, "half_width", rg_body_set_aabb(w, d, -1, 1));
    FAILS(s, INVALID, "half_height", rg_body_set_aabb(w, d, 1, INF));
    FAILS(s, INVALID, "out_half_extents", rg_body_get_shape(w, d, NULL, NULL));
    FAILS(s, INVALID, "restitution", rg_body_set_restitution(w, d, -0.1f));
    FAILS(s, INVALID, "restitution", rg_body_set_restitution(w, d, 1.1f));
    FAILS(s, INVALID, "out", rg_body_get_restitution(w, d, NULL));
    FAILS(s, INVALID, "mu", rg_body_set_friction(w, d, NaN));
    FAILS_SAYING(s, INVALID, "mu", "RG_MAX_FRICTION", rg_body_set_friction(w, d, 1001));
    FAILS(s, INVALID, "out", rg_body_get_friction(w, d, NULL));
    FAILS(s, INVALID, "is_sensor", rg_body_set_sensor(w, d, 2));
    FAILS(s, INVALID, "out_is_sensor", rg_body_is_sensor(w, d, NULL));
    FAILS(s, INVALID, "out_category", rg_body_get_filter(w, d, NULL, &u));
    FAILS(s, INVALID, "out_mask", rg_body_get_filter(w, d, &u, NULL));
    FAILS(s, INVALID, "out_grounded", rg_body_is_grounded(w, d, NULL));
    FAILS(s, INVALID, "out_awake", rg_body_is_awake(w, d, NULL));
    FAILS(s, INVALID, "normal.x", rg_body_set_one_way(w, s->floor, v2(NaN, 1)));
    FAILS_SAYING(s, INVALID, "normal", "length", rg_body_set_one_way(w, s->floor, v2(0, 0.5)));
    FAILS(s, INVALID, "out_normal", rg_body_get_one_way(w, d, NULL));
    SUCCEEDS(s, rg_body_set_circle(w, s->bare, 0.25f));
    SUCCEEDS(s, rg_body_set_aabb(w, s->bare, 0.25f, 0.5f));
    SUCCEEDS(s, rg_body_get_shape(w, s->bare, &i, NULL));
    SUCCEEDS(s, rg_body_clear_shape(w, s->bare));
    SUCCEEDS(s, rg_body_set_restitution(w, d, 1));
    SUCCEEDS(s, rg_body_get_restitution(w, d, &r));
    SUCCEEDS(s, rg_body_set_friction(w, d, 1000));
    SUCCEEDS(s, rg_body_get_friction(w, d, &r));
    SUCCEEDS(s, rg_body_set_sensor(w, s->kin, 1));
    SUCCEEDS(s, rg_body_is_sensor(w, s->kin, &i));
    SUCCEEDS(s, rg_body_set_filter(w, s->kin, 2, 3));
    SUCCEEDS(s, rg_body_get_filter(w, s->kin, &u, &u));
    SUCCEEDS(s, rg_body_is_grounded(w, d, &i));
    SUCCEEDS(s, rg_body_is_awake(w, d, &i));
    SUCCEEDS(s, rg_body_wake(w, d));
    SUCCEEDS(s, rg_body_set_one_way(w, s->floor, v2(0, 1)));
    SUCCEEDS(s, rg_body_get_one_way(w, s->floor, &v));
}

static void test_pairs_contacts_and_the_mover_fail_and_say_why(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    rg_body d = s->dyn;
    rg_contact c[4];
    rg_ray_hit hits[4];
    rg_vec2 end;
    int32_t n;
    EACH_STALE(s, h, "body", rg_body_pass_through(w, h, s->floor));
    EACH_STALE(s, h, "other", rg_body_pass_through(w, d, h));
    EACH_STALE(s, h, "body", rg_body_get_contacts(w, h, c, 4));
    EACH_STALE(s, h, "body", rg_body_move(w, h, v2(1, 1), ALL, RG_MOVE_SLIDE, &end, hits, 4, &n));
    FAILS(s, INVALID, "other", rg_body_pass_through(w, d, d));
    FAILS_SAYING(s, INVALID, "body", "no shape", rg_body_pass_through(w, s->bare, d));
    FAILS_SAYING(s, INVALID, "other", "no shape", rg_body_pass_through(w, d, s->bare));
    FAILS(s, INVALID, "capacity", rg_body_get_contacts(w, d, c, -1));
    FAILS(s, INVALID, "out", rg_body_get_contacts(w, d, NULL, 1));
    FAILS(s, INVALID, "target.x", rg_body_move(w, d, v2(NaN, 0), ALL, RG_MOVE_SLIDE, &end, hits, 4, &n));
    FAILS_SAYING(s, INVALID, "target.y", "RG_MAX_COORD", rg_body_move(w, d, v2(0, 2e9), ALL, RG_MOVE_SLIDE, &end, hits, 4, &n));
    FAILS_SAYING(s, INVALID, "response", "RG_MOVE_", rg_body_move(w, d, v2(1, 1), ALL, 3, &end, hits, 4, &n));
    FAILS(s, INVALID, "capacity", rg_body_move(w, d, v2(1, 1), ALL, RG_MOVE_TOUCH, &end, hits, -1, &n));
    FAILS(s, INVALID, "out_hits", rg_body_move(w, d, v2(1, 1), ALL, RG_MOVE_CROSS, &end, NULL, 2, &n));
    FAILS_SAYING(s, INVALID, "body", "no shape", rg_body_move(w, s->bare, v2(1, 1), ALL, RG_MOVE_SLIDE, &end, hits, 4, &n));
    SUCCEEDS(s, rg_body_get_contacts(w, d, c, 4));
    SUCCEEDS(s, rg_body_get_contacts(w, d, NULL, 0));
    SUCCEEDS(s, rg_body_pass_through(w, d, s->floor));
    SUCCEEDS(s, rg_body_move(w, s->kin, v2(6, 3), ALL, RG_MOVE_SLIDE, NULL, NULL, 0, NULL));
}

int main(void)
{
#define T(f) cmocka_unit_test_setup_teardown(f, scene_setup, scene_teardown)
    const struct CMUnitTest tests[] = {
        T(test_body_lifetime_and_mass_fail_and_say_why),
        T(test_body_state_fails_and_says_why),
        T(test_forces_fail_and_say_why),
        T(test_springs_fail_and_say_why),
        T(test_shapes_and_materials_fail_and_say_why),
        T(test_pairs_contacts_and_the_mover_fail_and_say_why),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
