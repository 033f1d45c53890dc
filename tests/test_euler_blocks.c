/* test_euler_blocks.c: a body's step does not depend on the bodies it is stepped beside.
 *
 * The Euler pass runs the active bodies in blocks of 64 and takes shortcuts where a whole
 * block allows them (no dissipation, linear drag only, no gravity scale, one acceleration for
 * the block without wind, applied forces or springs), keyed by per-body flags the setters
 * keep; a world of one body runs its body alone, through the pass's plain per-body code.
 * Every body of a world of 512, with settings mixed so that blocks of each kind occur
 * (uniform linear drag, no dissipation, a gravity scale in a block, quadratic drag,
 * surface friction, kinematic bodies, bodies at rest, a gravity scale set back to 1), must end
 * with the same bits of position and velocity as the same body alone in a world of its own,
 * for every integrator, with and without wind and applied forces.  The comparison is exact:
 * both do the same IEEE operations in the same order, so any difference is a shortcut taken
 * where it does not hold (a flag left stale, a constant where a value differs). */
#include <string.h>

#include "testutil.h"

#define N_BODIES 512
#define STEPS 120

enum { SCENE_GRAVITY, SCENE_WIND, SCENE_FORCES, SCENE_COUNT };

/* Body i's settings, by blocks of 64: 0 linear drag on all and 1 nothing (the uniform
 * paths), 2 linear drag with one gravity scale, 3 a mix of linear drag, gravity scales (one
 * set back to 1) and kinematic bodies (the mixed path), 4 and 5 that mix with one body of
 * surface friction or of quadratic drag (which must take the block off the fast path),
 * 6 everything and bodies at rest, 7 friction on every body. */
static rg_body make_configured(rg_world *w, int i)
{
    int block = i / 64, mixed = block >= 3 && block <= 6;
    int kinematic = mixed && i % 19 == 0;
    rg_body b = 0;
    rg_vec2 p = v2((rg_real)(10 * i), (rg_real)(i % 9));
    assert_ok(rg_body_create(w, kinematic ? RG_BODY_KINEMATIC : RG_BODY_DYNAMIC,
                             (rg_real)(1.0 + 0.5 * (i % 4)), p, &b));
    int rest = block >= 6 && i % 23 == 0;
    rg_vec2 v = rest ? v2(0, 0) : v2((rg_real)(0.25 * (i % 13) - 1.5), (rg_real)(0.5 * (i % 5) + 0.25));
    assert_ok(rg_body_set_velocity(w, b, v));
    if (kinematic) return b;
    if (block == 0 || block == 2 || (mixed && i % 5 == 0))
        assert_ok(rg_body_set_drag(w, b, (rg_real)(0.1 + 0.01 * (i % 7)), 0));
    if (i == 150 || (mixed && i % 13 == 0)) assert_ok(rg_body_set_gravity_scale(w, b, 0.5f));
    if (mixed && i % 17 == 0) { /* set and set back: its flag must clear */
        assert_ok(rg_body_set_gravity_scale(w, b, 2));
        assert_ok(rg_body_set_gravity_scale(w, b, 1));
    }
    if (i == 340 || (block == 6 && i % 7 == 0)) assert_ok(rg_body_set_drag(w, b, 0.05f, 0.02f));
    if (i == 300 || (block == 6 && i % 11 == 0) || block == 7)
        assert_ok(rg_body_set_surface_friction(w, b, 0.2f, (rg_real)9.81));
    return b;
}

static rg_world *make_world(int integrator, int scene)
{
    rg_world *w = NULL;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_integrator(w, integrator));
    assert_ok(rg_world_set_gravity(w, v2(0, (rg_real)-9.81)));
    assert_ok(rg_world_set_sleeping(w, 0));
    if (scene == SCENE_WIND) assert_ok(rg_world_set_wind(w, v2((rg_real)0.7, (rg_real)-0.2)));
    return w;
}

static void push(rg_world *w, rg_body b, int scene, int i, int k)
{
    if (scene == SCENE_FORCES && i % 3 == 0)
        assert_ok(rg_body_apply_force(w, b, v2((rg_real)(0.5 * (k % 4)), (rg_real)(i % 2))));
}

/* How a case makes body i, and what it does to it before step k. */
typedef rg_body make_fn(rg_world *w, int i);
typedef void act_fn(rg_world *w, rg_body b, int scene, int i, int k);

/* Every body of a world of N_BODIES made by `make` ends as it ends alone. */
static void run_case(int integrator, int scene, make_fn *make, act_fn *act)
{
    rg_world *w = make_world(integrator, scene);
    rg_body b[N_BODIES];
    for (int i = 0; i < N_BODIES; i++) b[i] = make(w, i);
    for (int k = 0; k < STEPS; k++) {
        for (int i = 0; i < N_BODIES; i++) act(w, b[i], scene, i, k);
        assert_ok(rg_world_step(w, (rg_real)(1.0 / 60.0)));
    }
    int differ = 0;
    for (int i = 0; i < N_BODIES; i++) {
        rg_world *alone = make_world(integrator, scene);
        rg_body a = make(alone, i);
        for (int k = 0; k < STEPS; k++) {
            act(alone, a, scene, i, k);
            assert_ok(rg_world_step(alone, (rg_real)(1.0 / 60.0)));
        }
        rg_vec2 pw = pos_of(w, b[i]), vw = vel_of(w, b[i]), pa = pos_of(alone, a), va = vel_of(alone, a);
        if (memcmp(&pw, &pa, sizeof pw) != 0 || memcmp(&vw, &va, sizeof vw) != 0) {
            if (differ < 5)
                print_message("integrator %d scene %d body %d: (%.9g, %.9g) v (%.9g, %.9g) beside others, "
                              "(%.9g, %.9g) v (%.9g, %.9g) alone\n",
                              integrator, scene, i, (double)pw.x, (double)pw.y, (double)vw.x, (double)vw.y,
                              (double)pa.x, (double)pa.y, (double)va.x, (double)va.y);
            differ++;
        }
        rg_world_destroy(alone);
    }
    rg_world_destroy(w);
    assert_int_equal(differ, 0);
}

static void test_a_body_steps_alike_alone_and_in_any_block(void **state)
{
    (void)state;
    for (int integrator = RG_INTEGRATOR_EXPLICIT_EULER; integrator <= RG_INTEGRATOR_RK4; integrator++)
        for (int scene = 0; scene < SCENE_COUNT; scene++) run_case(integrator, scene, make_configured, push);
}

/* A world whose every body has linear drag and nothing else takes the blocks' flags as known
 * without reading them (the pass's `linear` case, free0's); a body given quadratic drag or a
 * gravity scale for a while, then set back, must turn the case off and on again (the world's
 * counts kept by the setters).  Every body must end as it ends alone, for every integrator. */
static void linear_configure(rg_world *w, rg_body b, int scene, int i, int k)
{
    rg_real lin = (rg_real)(0.1 + 0.01 * (i % 7));
    (void)scene;
    if (i == 7 && k == 40) assert_ok(rg_body_set_drag(w, b, lin, 0.02f));
    if (i == 7 && k == 80) assert_ok(rg_body_set_drag(w, b, lin, 0));
    if (i == 9 && k == 50) assert_ok(rg_body_set_gravity_scale(w, b, 2));
    if (i == 9 && k == 70) assert_ok(rg_body_set_gravity_scale(w, b, 1));
}

static rg_body linear_body(rg_world *w, int i)
{
    rg_body b = 0;
    assert_ok(rg_body_create(w, RG_BODY_DYNAMIC, (rg_real)(1.0 + 0.5 * (i % 4)), v2((rg_real)(10 * i), 0), &b));
    assert_ok(rg_body_set_velocity(w, b, v2((rg_real)(0.25 * (i % 13) - 1.5), (rg_real)(0.5 * (i % 5) + 0.25))));
    assert_ok(rg_body_set_drag(w, b, (rg_real)(0.1 + 0.01 * (i % 7)), 0));
    return b;
}

static void test_a_world_of_linear_drag_only_steps_as_each_body_alone(void **state)
{
    (void)state;
    for (int integrator = RG_INTEGRATOR_EXPLICIT_EULER; integrator <= RG_INTEGRATOR_RK4; integrator++)
        run_case(integrator, SCENE_GRAVITY, linear_body, linear_configure);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_body_steps_alike_alone_and_in_any_block),
        cmocka_unit_test(test_a_world_of_linear_drag_only_steps_as_each_body_alone),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
