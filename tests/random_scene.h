/* random_scene.h: random changes between steps, for the tests that run random scenes
 * (test_touching.c, test_rollback.c): bodies of every type and shape created and destroyed,
 * sensors toggled, filters, shapes, teleports, impulses, velocities, pass-through, waking and
 * sleeping switched, drawn from a 32-bit state in one order on every compiler. */
#ifndef RG_RANDOM_SCENE_H
#define RG_RANDOM_SCENE_H

#include "testutil.h"

#define MAXB 40 /* bodies a random scene holds at most */

static inline int32_t body_type(rg_world *w, rg_body b)
{
    int32_t t;
    assert_ok(rg_body_get_type(w, b, &t));
    return t;
}

static inline rg_vec2 random_v(uint32_t *s, double lo, double hi)
{
    double x = lo + (hi - lo) * next_uniform(s);
    double y = lo + (hi - lo) * next_uniform(s);
    return v2((rg_real)x, (rg_real)y);
}

/* One change between steps, drawn at random: a body created (dynamic, kinematic or static,
 * a circle or a box, some sensors, some bouncy), destroyed (not bodies[0], the floor), made
 * a sensor or solid, given a filter, a new shape or none, moved, pushed, sent off, passed
 * through another, woken, or sleeping switched. */
static inline void random_change(rg_world *w, uint32_t *s, rg_body *bodies, int *nb)
{
    int op = (int)(next_uniform(s) * 13);
    rg_body x = bodies[(int)(next_uniform(s) * *nb)];
    if (op <= 3 && *nb < MAXB) {
        double t = next_uniform(s);
        int32_t type = t < 0.7 ? RG_BODY_DYNAMIC : t < 0.85 ? RG_BODY_KINEMATIC : RG_BODY_STATIC;
        rg_vec2 at = random_v(s, 0, 1);
        rg_body b;
        assert_ok(rg_body_create(w, type, (rg_real)(0.5 + 3 * next_uniform(s)), v2(-4 + 8 * at.x, (rg_real)0.2 + 4 * at.y), &b));
        rg_vec2 h = random_v(s, 0.1, 0.6);
        if (next_uniform(s) < 0.5) assert_ok(rg_body_set_circle(w, b, h.x));
        else assert_ok(rg_body_set_aabb(w, b, h.x, h.y));
        rg_vec2 v = random_v(s, -3, 3);
        if (type != RG_BODY_STATIC) assert_ok(rg_body_set_velocity(w, b, v));
        if (next_uniform(s) < 0.25) assert_ok(rg_body_set_sensor(w, b, 1));
        if (next_uniform(s) < 0.2) assert_ok(rg_body_set_restitution(w, b, (rg_real)next_uniform(s)));
        bodies[(*nb)++] = b;
    } else if (op == 4 && *nb > 1) {
        int k = 1 + (int)(next_uniform(s) * (*nb - 1)); /* the floor stays */
        assert_ok(rg_body_destroy(w, bodies[k]));
        bodies[k] = bodies[--*nb];
    } else if (op == 5) {
        assert_ok(rg_body_set_sensor(w, x, !flag(rg_body_is_sensor, w, x)));
    } else if (op == 6) {
        uint32_t cat = 1u << (int)(next_uniform(s) * 2);
        uint32_t mask = next_uniform(s) < 0.67 ? 0xFFFFFFFFu : 1u << (int)(next_uniform(s) * 2);
        assert_ok(rg_body_set_filter(w, x, cat, mask));
    } else if (op == 7) {
        double t = next_uniform(s);
        rg_vec2 h = random_v(s, 0.1, 0.6);
        if (t < 0.33) assert_ok(rg_body_clear_shape(w, x));
        else if (t < 0.67) assert_ok(rg_body_set_circle(w, x, h.x));
        else assert_ok(rg_body_set_aabb(w, x, h.x, h.y));
    } else if (op == 8) {
        rg_vec2 at = random_v(s, 0, 1);
        assert_ok(rg_body_set_position(w, x, v2(-4 + 8 * at.x, (rg_real)0.2 + 4 * at.y)));
    } else if (op == 9) {
        rg_vec2 j = random_v(s, -3, 3);
        if (body_type(w, x) == RG_BODY_DYNAMIC) assert_ok(rg_body_apply_impulse(w, x, j));
    } else if (op == 10) {
        rg_status st = rg_body_pass_through(w, x, bodies[(int)(next_uniform(s) * *nb)]);
        assert_true(st == RG_OK || st == RG_ERR_INVALID_ARGUMENT); /* itself, or no shape */
    } else if (op == 11) {
        rg_vec2 v = random_v(s, -8, 8);
        if (body_type(w, x) != RG_BODY_STATIC) assert_ok(rg_body_set_velocity(w, x, v));
    } else {
        int32_t on;
        assert_ok(rg_world_get_sleeping(w, &on));
        if (next_uniform(s) < 0.2) assert_ok(rg_world_set_sleeping(w, !on));
        else assert_ok(rg_body_wake(w, x));
    }
}

/* A pool of two threads, its task system in *tasks: the scenes that run on two workers. */
static inline rg_thread_pool *random_pool(rg_task_system *tasks)
{
    rg_thread_pool *pool;
    assert_ok(rg_thread_pool_create(2, &pool));
    assert_ok(rg_thread_pool_task_system(pool, tasks));
    return pool;
}

/* Random scene `scene`'s world, gravity 10, on `tasks` (NULL: one thread), sleeping on in two
 * scenes of three with a random sleep time, and its floor (10 m each side of x = 0, top at
 * y = 0) as bodies[0]; *s is the scene's random state. */
static inline rg_world *random_world(int scene, uint32_t *s, const rg_task_system *tasks, rg_body *bodies, int *nb)
{
    rg_world *w = gravity_world(-10);
    if (tasks != NULL) assert_ok(rg_world_set_task_system(w, tasks));
    assert_ok(rg_world_set_sleeping(w, scene % 3 != 0));
    assert_ok(rg_world_set_sleep_thresholds(w, (rg_real)0.05, (rg_real)(0.1 + 0.3 * next_uniform(s))));
    *nb = 0;
    bodies[(*nb)++] = box_body(w, RG_BODY_STATIC, 0, 0, -0.5, 10, 0.5);
    return w;
}

#endif
