/* test_ranges.c: the accepted ranges of include/rigid.h (RG_MIN_* / RG_MAX_*): each call
 * accepts the edge of its range and refuses the next rg_real beyond it (naming the argument
 * and the constant, changing nothing); what the fuzzer found (a denormal mass, a step of
 * 1e30 s, bodies 1e20 m apart, positions near the float range) is refused; and scenes with
 * every value at its edge stay finite. */
#include "errors.h"

/* `call`, an expression of x, succeeds with x at the edge and fails with x the next rg_real
 * beyond it (toward `toward`), naming `arg` and the range's constant. */
#define EDGE(s, arg, constant, edge, toward, call)               \
    do {                                                         \
        rg_real x = (rg_real)(edge);                             \
        SUCCEEDS((s), call);                                     \
        x = next_real((edge), (toward));                         \
        FAILS_SAYING((s), INVALID, arg, constant, call);         \
    } while (0)
/* A maximum of |x|: both signs. */
#define EDGE_ABS(s, arg, constant, max, call)                    \
    do {                                                         \
        EDGE(s, arg, constant, (max), INF, call);           \
        EDGE(s, arg, constant, -(max), -INF, call);         \
    } while (0)

static rg_vec2 xy(rg_real x, rg_real y)
{
    rg_vec2 v = { x, y };
    return v;
}

static void test_world_and_step_ranges_accept_the_edge_and_refuse_beyond(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    EDGE_ABS(s, "gravity.x", "RG_MAX_ACCELERATION", RG_MAX_ACCELERATION, rg_world_set_gravity(w, xy(x, 0)));
    EDGE_ABS(s, "gravity.y", "RG_MAX_ACCELERATION", RG_MAX_ACCELERATION, rg_world_set_gravity(w, xy(0, x)));
    EDGE_ABS(s, "force.x", "RG_MAX_FORCE", RG_MAX_FORCE, rg_world_set_wind(w, xy(x, 0)));
    EDGE_ABS(s, "force.y", "RG_MAX_FORCE", RG_MAX_FORCE, rg_world_set_wind(w, xy(0, x)));
    EDGE(s, "dt", "RG_MAX_DT", RG_MAX_DT, INF, rg_world_set_fixed_step(w, x, 8));
    EDGE(s, "speed", "RG_MAX_SPEED", RG_MAX_SPEED, INF, rg_world_set_sleep_thresholds(w, x, 1));
    EDGE(s, "slop", "RG_MAX_SHAPE_SIZE", RG_MAX_SHAPE_SIZE, INF, rg_world_set_contact_tuning(w, x, 0.2f, 2, 1));
    EDGE(s, "max_push", "RG_MAX_SPEED", RG_MAX_SPEED, INF, rg_world_set_contact_tuning(w, 0, 0.2f, x, 1));
    EDGE(s, "restitution_threshold", "RG_MAX_SPEED", RG_MAX_SPEED, INF,
         rg_world_set_contact_tuning(w, 0, 0.2f, 2, x));
    assert_ok(rg_world_set_contact_tuning(w, 0.005f, 0.2f, 2, 1));
    assert_ok(rg_world_set_wind(w, v2(0, 0)));
    assert_ok(rg_world_set_gravity(w, v2(0, -10)));
    /* the longest step, last: the scene takes it */
    EDGE(s, "dt", "RG_MAX_DT", RG_MAX_DT, INF, rg_world_step(w, x));
}

static void test_body_ranges_accept_the_edge_and_refuse_beyond(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    rg_body d = s->dyn, k = s->kin, nb, heavy = make_body(w, RG_MAX_MASS, 0, 9), one = make_body(w, 1, 0, 12);
    EDGE(s, "mass", "RG_MIN_MASS", RG_MIN_MASS, 0, rg_body_create(w, RG_BODY_DYNAMIC, x, v2(0, 20), &nb));
    EDGE(s, "mass", "RG_MAX_MASS", RG_MAX_MASS, INF, rg_body_create(w, RG_BODY_DYNAMIC, x, v2(0, 20), &nb));
    EDGE(s, "mass", "RG_MIN_MASS", RG_MIN_MASS, 0, rg_body_set_mass(w, d, x));
    EDGE(s, "mass", "RG_MAX_MASS", RG_MAX_MASS, INF, rg_body_set_mass(w, d, x));
    EDGE_ABS(s, "position.x", "RG_MAX_COORD", RG_MAX_COORD, rg_body_create(w, RG_BODY_STATIC, 0, xy(x, 0), &nb));
    EDGE_ABS(s, "position.y", "RG_MAX_COORD", RG_MAX_COORD, rg_body_create(w, RG_BODY_KINEMATIC, 0, xy(0, x), &nb));
    EDGE_ABS(s, "position.x", "RG_MAX_COORD", RG_MAX_COORD, rg_body_set_position(w, s->bare, xy(x, 0)));
    EDGE_ABS(s, "position.y", "RG_MAX_COORD", RG_MAX_COORD, rg_body_set_position(w, s->bare, xy(0, x)));
    EDGE_ABS(s, "velocity.x", "RG_MAX_SPEED", RG_MAX_SPEED, rg_body_set_velocity(w, k, xy(x, 0)));
    EDGE_ABS(s, "velocity.y", "RG_MAX_SPEED", RG_MAX_SPEED, rg_body_set_velocity(w, d, xy(0, x)));
    EDGE_ABS(s, "force.x", "RG_MAX_FORCE", RG_MAX_FORCE, rg_body_apply_force(w, heavy, xy(x, 0)));
    EDGE_ABS(s, "force.y", "RG_MAX_FORCE", RG_MAX_FORCE, rg_body_apply_force(w, heavy, xy(0, x)));
    EDGE_ABS(s, "impulse.x", "RG_MAX_FORCE", RG_MAX_FORCE, rg_body_apply_impulse(w, heavy, xy(x, 0)));
    EDGE_ABS(s, "impulse.y", "RG_MAX_FORCE", RG_MAX_FORCE, rg_body_apply_impulse(w, heavy, xy(0, x)));
    /* an impulse that brings a 1 kg body from rest exactly to RG_MAX_SPEED, and one beyond */
    SUCCEEDS(s, rg_body_apply_impulse(w, one, v2(RG_MAX_SPEED, 0)));
    assert_ok(rg_body_set_velocity(w, one, v2(0, 0)));
    FAILS_SAYING(s, INVALID, "impulse", "RG_MAX_SPEED",
                 rg_body_apply_impulse(w, one, xy(next_real(RG_MAX_SPEED, INF), 0)));
    EDGE_ABS(s, "scale", "RG_MAX_GRAVITY_SCALE", RG_MAX_GRAVITY_SCALE, rg_body_set_gravity_scale(w, d, x));
    EDGE(s, "linear", "RG_MAX_DRAG", RG_MAX_DRAG, INF, rg_body_set_drag(w, d, x, 0));
    EDGE(s, "quadratic", "RG_MAX_DRAG", RG_MAX_DRAG, INF, rg_body_set_drag(w, d, 0, x));
    EDGE(s, "mu", "RG_MAX_FRICTION", RG_MAX_FRICTION, INF, rg_body_set_surface_friction(w, d, x, 1));
    EDGE(s, "normal_force", "RG_MAX_FORCE", RG_MAX_FORCE, INF, rg_body_set_surface_friction(w, d, 1, x));
    EDGE(s, "min_speed", "RG_MAX_SPEED", RG_MAX_SPEED, INF, rg_body_set_speed_limits(w, d, x, 0));
    EDGE(s, "max_speed", "RG_MAX_SPEED", RG_MAX_SPEED, INF, rg_body_set_speed_limits(w, d, 0, x));
    EDGE(s, "radius", "RG_MIN_SHAPE_SIZE", RG_MIN_SHAPE_SIZE, 0, rg_body_set_circle(w, d, x));
    EDGE(s, "radius", "RG_MAX_SHAPE_SIZE", RG_MAX_SHAPE_SIZE, INF, rg_body_set_circle(w, d, x));
    EDGE(s, "half_width", "RG_MIN_SHAPE_SIZE", RG_MIN_SHAPE_SIZE, 0, rg_body_set_aabb(w, d, x, 1));
    EDGE(s, "half_height", "RG_MAX_SHAPE_SIZE", RG_MAX_SHAPE_SIZE, INF, rg_body_set_aabb(w, d, 1, x));
    EDGE(s, "mu", "RG_MAX_FRICTION", RG_MAX_FRICTION, INF, rg_body_set_friction(w, d, x));
    EDGE_ABS(s, "target.x", "RG_MAX_COORD", RG_MAX_COORD, rg_body_move(w, k, xy(x, 0), ALL, RG_MOVE_CROSS, NULL, NULL, 0, NULL));
    EDGE_ABS(s, "target.y", "RG_MAX_COORD", RG_MAX_COORD, rg_body_move(w, k, xy(0, x), ALL, RG_MOVE_CROSS, NULL, NULL, 0, NULL));
    /* forces add up to at most RG_MAX_FORCE per component */
    assert_ok(rg_body_set_mass(w, d, 1));
    SUCCEEDS(s, rg_body_apply_force(w, d, v2(RG_MAX_FORCE / 2, -RG_MAX_FORCE / 2)));
    SUCCEEDS(s, rg_body_apply_force(w, d, v2(RG_MAX_FORCE / 2, -RG_MAX_FORCE / 2)));
    FAILS_SAYING(s, INVALID, "force", "RG_MAX_FORCE", rg_body_apply_force(w, d, v2(1e6, 0)));
    FAILS_SAYING(s, INVALID, "force", "RG_MAX_FORCE", rg_body_apply_force(w, d, v2(0, -1e6)));
}

static void test_spring_and_query_ranges_accept_the_edge_and_refuse_beyond(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    rg_body d = s->dyn;
    uint64_t sp;
    rg_ray_hit hit, hits[2];
    rg_body out[2];
    EDGE(s, "rest_length", "RG_MAX_COORD", RG_MAX_COORD, INF, rg_spring_create(w, d, s->kin, v2(0, 0), x, 1, 0, &sp));
    EDGE(s, "stiffness", "RG_MAX_STIFFNESS", RG_MAX_STIFFNESS, INF, rg_spring_create(w, d, s->kin, v2(0, 0), 1, x, 0, &sp));
    EDGE(s, "damping", "RG_MAX_DAMPING", RG_MAX_DAMPING, INF, rg_spring_create(w, d, s->kin, v2(0, 0), 1, 1, x, &sp));
    EDGE_ABS(s, "anchor.x", "RG_MAX_COORD", RG_MAX_COORD, rg_spring_create(w, d, 0, xy(x, 0), 1, 1, 0, &sp));
    EDGE_ABS(s, "anchor.y", "RG_MAX_COORD", RG_MAX_COORD, rg_spring_create(w, d, 0, xy(0, x), 1, 1, 0, &sp));
    const double q = RG_MAX_QUERY_COORD;
    EDGE_ABS(s, "origin.x", "RG_MAX_QUERY_COORD", q, rg_world_raycast(w, xy(x, 0), v2(0, -1), ALL, &hit));
    EDGE_ABS(s, "translation.y", "RG_MAX_QUERY_COORD", q, rg_world_raycast(w, v2(0, 5), xy(0, x), ALL, &hit));
    EDGE_ABS(s, "origin.y", "RG_MAX_QUERY_COORD", q, rg_world_raycast_all(w, xy(0, x), v2(1, 0), ALL, hits, 2));
    EDGE_ABS(s, "translation.x", "RG_MAX_QUERY_COORD", q, rg_world_raycast_all(w, v2(0, 5), xy(x, 0), ALL, hits, 2));
    EDGE_ABS(s, "lower.x", "RG_MAX_QUERY_COORD", q, rg_world_query_aabb(w, xy(x, 0), xy(x, 1), ALL, out, 2));
    EDGE_ABS(s, "upper.y", "RG_MAX_QUERY_COORD", q, rg_world_query_aabb(w, xy(0, -(rg_real)q), xy(1, x), ALL, out, 2));
    EDGE_ABS(s, "point.x", "RG_MAX_QUERY_COORD", q, rg_world_query_point(w, xy(x, 0), ALL, out, 2));
    EDGE_ABS(s, "origin.x", "RG_MAX_QUERY_COORD", q,
             rg_world_cast_shape(w, RG_SHAPE_CIRCLE, v2(1, 0), xy(x, 5), v2(0, -1), ALL, &hit));
    EDGE_ABS(s, "translation.x", "RG_MAX_QUERY_COORD", q,
             rg_world_cast_shape(w, RG_SHAPE_AABB, v2(1, 1), v2(0, 5), xy(x, 0), ALL, &hit));
    EDGE(s, "size.x", "RG_MIN_SHAPE_SIZE", RG_MIN_SHAPE_SIZE, 0,
         rg_world_cast_shape(w, RG_SHAPE_CIRCLE, xy(x, 0), v2(0, 5), v2(0, -10), ALL, &hit));
    EDGE(s, "size.y", "RG_MAX_SHAPE_SIZE", RG_MAX_SHAPE_SIZE, INF,
         rg_world_cast_shape(w, RG_SHAPE_AABB, xy(1, x), v2(0, 5), v2(0, -10), ALL, &hit));
}

/* What the fuzzer found put inf or NaN into the world; each is refused now and changes
 * nothing. */
static void test_the_fuzzers_findings_are_refused(void **state)
{
    scene *s = *state;
    rg_world *w = s->w;
    rg_body nb, d = s->dyn;
    uint64_t sp;
    const double near_float_max = 3e38;
    /* a denormal mass passed mass > 0, and 1/mass was inf */
    FAILS(s, INVALID, "mass", rg_body_create(w, RG_BODY_DYNAMIC, (rg_real)1e-40, v2(0, 0), &nb));
    FAILS(s, INVALID, "mass", rg_body_set_mass(w, d, (rg_real)1e-40));
    /* finite positions and velocities near the float range overflowed in a step */
    FAILS(s, INVALID, "position.x", rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(near_float_max, 0), &nb));
    FAILS(s, INVALID, "position.y", rg_body_set_position(w, d, v2(0, -near_float_max)));
    FAILS(s, INVALID, "velocity.x", rg_body_set_velocity(w, d, v2(near_float_max, 0)));
    /* step(1e30) */
    FAILS(s, INVALID, "dt", rg_world_step(w, 1e30f));
    FAILS(s, INVALID, "dt", rg_world_set_fixed_step(w, 1e30f, 1));
    /* a spring between bodies 1e20 m apart overflowed dx*dx + dy*dy */
    FAILS(s, INVALID, "position.x", rg_body_set_position(w, s->bare, v2(1e20, 0)));
    FAILS(s, INVALID, "anchor.x", rg_spring_create(w, d, 0, v2(1e20, 1e20), 0, 1, 0, &sp));
}

static int all_finite(rg_world *w, const rg_body *b, int n)
{
    for (int k = 0; k < n; k++) {
        rg_vec2 p = pos_of(w, b[k]), v = vel_of(w, b[k]), a, ip;
        assert_ok(rg_body_get_acceleration(w, b[k], &a));
        assert_ok(rg_body_get_interpolated_position(w, b[k], &ip));
        if (!(isfinite((double)p.x) && isfinite((double)p.y) && isfinite((double)v.x) && isfinite((double)v.y) &&
              isfinite((double)a.x) && isfinite((double)a.y) && isfinite((double)ip.x) && isfinite((double)ip.y)))
            return 0;
    }
    return 1;
}

/* Every integrator, at 60 Hz and at RG_MAX_DT, for 100 steps (then 100 fixed steps through
 * rg_world_advance): bodies with every value at its edge stay finite.  Body 0: RG_MIN_MASS
 * at (RG_MAX_COORD, -RG_MAX_COORD) moving at RG_MAX_SPEED, gravity RG_MAX_ACCELERATION times
 * RG_MAX_GRAVITY_SCALE, wind RG_MAX_FORCE; body 1: RG_MIN_MASS at RG_MAX_SPEED with the
 * largest drag; body 2: the same with the largest surface friction; body 3: a RG_MIN_SHAPE_SIZE
 * circle pushed by RG_MAX_FORCE toward a RG_MAX_SHAPE_SIZE static box; bodies 4 and 5: of
 * RG_MAX_MASS at +-RG_MAX_COORD (2.8e9 m apart: the fuzzer's 1e20 m spring, at the edge)
 * tied by the stiffest, most damped spring. */
static void test_bodies_at_every_edge_stay_finite(void **state)
{
    (void)state;
    const double dts[] = { DT, RG_MAX_DT };
    for (int integ = RG_INTEGRATOR_EXPLICIT_EULER; integ <= RG_INTEGRATOR_RK4; integ++) {
        for (int k = 0; k < 2; k++) {
            rg_world *w;
            rg_body b[7];
            uint64_t sp;
            assert_ok(rg_world_create(&w));
            assert_ok(rg_world_set_integrator(w, integ));
            assert_ok(rg_world_set_gravity(w, v2(RG_MAX_ACCELERATION, -RG_MAX_ACCELERATION)));
            assert_ok(rg_world_set_wind(w, v2(RG_MAX_FORCE, RG_MAX_FORCE)));
            assert_ok(rg_world_set_fixed_step(w, (rg_real)dts[k], 8));
            b[0] = make_body(w, RG_MIN_MASS, RG_MAX_COORD, -RG_MAX_COORD);
            assert_ok(rg_body_set_velocity(w, b[0], v2(RG_MAX_SPEED, -RG_MAX_SPEED)));
            assert_ok(rg_body_set_gravity_scale(w, b[0], (rg_real)RG_MAX_GRAVITY_SCALE));
            b[1] = make_body(w, RG_MIN_MASS, 0, 0);
            assert_ok(rg_body_set_velocity(w, b[1], v2(RG_MAX_SPEED, -RG_MAX_SPEED)));
            assert_ok(rg_body_set_drag(w, b[1], (rg_real)RG_MAX_DRAG, (rg_real)RG_MAX_DRAG));
            b[2] = make_body(w, RG_MIN_MASS, 0, 0);
            assert_ok(rg_body_set_velocity(w, b[2], v2(-RG_MAX_SPEED, RG_MAX_SPEED)));
            assert_ok(rg_body_set_surface_friction(w, b[2], (rg_real)RG_MAX_FRICTION, (rg_real)RG_MAX_FORCE));
            b[3] = circle_body(w, RG_BODY_DYNAMIC, RG_MIN_MASS, 0, 10, RG_MIN_SHAPE_SIZE);
            assert_ok(rg_body_set_velocity(w, b[3], v2(RG_MAX_SPEED, -RG_MAX_SPEED)));
            assert_ok(rg_body_apply_force(w, b[3], v2(-RG_MAX_FORCE, -RG_MAX_FORCE)));
            b[6] = box_body(w, RG_BODY_STATIC, 0, 0, -RG_MAX_SHAPE_SIZE, RG_MAX_SHAPE_SIZE, RG_MAX_SHAPE_SIZE);
            b[4] = make_body(w, RG_MAX_MASS, RG_MAX_COORD, RG_MAX_COORD);
            b[5] = make_body(w, RG_MAX_MASS, -RG_MAX_COORD, -RG_MAX_COORD);
            assert_ok(rg_body_set_gravity_scale(w, b[4], 0));
            assert_ok(rg_body_set_gravity_scale(w, b[5], 0));
            if (k == 0) /* a spring that stiff is unstable at RG_MAX_DT (omega dt = 14 > 2) */
                assert_ok(rg_spring_create(w, b[4], b[5], v2(0, 0), 0, (rg_real)RG_MAX_STIFFNESS,
                                           (rg_real)RG_MAX_DAMPING, &sp));
            for (int n = 0; n < 100; n++) {
                assert_ok(rg_world_step(w, (rg_real)dts[k]));
                if (!all_finite(w, b, 7)) fail_msg("integrator %d, dt %g: not finite after step %d", integ, dts[k], n + 1);
            }
            for (int n = 0; n < 100; n++) {
                assert_ok(rg_world_advance(w, (rg_real)(dts[k] * 1.5), NULL));
                if (!all_finite(w, b, 7)) fail_msg("integrator %d, dt %g: not finite after advance %d", integ, dts[k], n + 1);
            }
            rg_world_destroy(w);
        }
    }
}

int main(void)
{
#define T(f) cmocka_unit_test_setup_teardown(f, scene_setup, scene_teardown)
    const struct CMUnitTest tests[] = {
        T(test_world_and_step_ranges_accept_the_edge_and_refuse_beyond),
        T(test_body_ranges_accept_the_edge_and_refuse_beyond),
        T(test_spring_and_query_ranges_accept_the_edge_and_refuse_beyond),
        T(test_the_fuzzers_findings_are_refused),
        cmocka_unit_test(test_bodies_at_every_edge_stay_finite),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
