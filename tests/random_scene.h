/* random_scene.h: random changes between steps, for the tests that run random scenes
 * (test_touching.c, test_rollback.c, test_random_workers.c, test_random_more.c): bodies of
 * every type and shape created and destroyed, sensors toggled, filters, shapes, teleports,
 * impulses, velocities, pass-through, waking and sleeping switched (random_change); springs
 * made and destroyed, one-way normals, masses, drag, frictions, speed limits, gravity scales,
 * materials, the integrator, the solver's iterations, continuous collision, the contact
 * tuning, gravity and wind, forces, moves and the pre-solve hook (random_more); drawn from a
 * 32-bit state in one order on every compiler. */
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

/* ---- random_more's record of what it did that the tests check against */

#define MAXS 24 /* springs a random scene records */
#define MAXLIM 64 /* speed limits it records */
typedef struct random_extra {
    uint64_t spring[MAXS];
    rg_body end_a[MAXS], end_b[MAXS]; /* end_b 0: tied to a point */
    int ns;
    int hook;                         /* the pre-solve hook is installed */
    rg_body lim_body[MAXLIM];         /* speed limits set, in order (the last one holds) */
    double lim_min[MAXLIM], lim_max[MAXLIM];
    int nlim;
} random_extra;

/* The pre-solve hook: skips one pair in five, chosen by the bodies' handles without the
 * world's tag (their low 40 bits), so that a world and its restored clone skip the same. */
static inline int32_t random_hook(rg_body a, rg_body b, rg_vec2 normal, rg_real separation, void *user)
{
    (void)normal;
    (void)separation;
    (void)user;
    return ((a & 0xFFFFFFFFFFull) * 3 + (b & 0xFFFFFFFFFFull)) % 5 != 0;
}

/* Installs the hook or not, as e->hook says. */
static inline void random_hook_set(rg_world *w, const random_extra *e)
{
    assert_ok(rg_world_set_pre_solve(w, e->hook ? random_hook : NULL, NULL));
}

static inline void random_tolerate(rg_status st)
{
    assert_true(st == RG_OK || st == RG_ERR_INVALID_ARGUMENT);
}

/* One more change between steps, drawn at random (e records springs, limits and the hook). */
static inline void random_more(rg_world *w, uint32_t *s, rg_body *bodies, int nb, random_extra *e)
{
    int op = (int)(next_uniform(s) * 17);
    rg_body x = bodies[(int)(next_uniform(s) * nb)], y = bodies[(int)(next_uniform(s) * nb)];
    if (op == 0 && e->ns < MAXS) {
        uint64_t sp;
        rg_body other = next_uniform(s) < 0.3 ? 0 : y;
        rg_status st = rg_spring_create(w, x, other, random_v(s, -3, 3), (rg_real)(2 * next_uniform(s)),
                                        (rg_real)(300 * next_uniform(s)), (rg_real)(5 * next_uniform(s)), &sp);
        random_tolerate(st); /* x == y */
        if (st == RG_OK) {
            e->spring[e->ns] = sp;
            e->end_a[e->ns] = x;
            e->end_b[e->ns++] = other;
        }
    } else if (op == 1 && e->ns > 0) {
        int k = (int)(next_uniform(s) * e->ns);
        rg_status st = rg_spring_destroy(w, e->spring[k]);
        assert_true(st == RG_OK || st == RG_ERR_STALE_HANDLE); /* gone with a body */
        e->ns--;
        e->spring[k] = e->spring[e->ns];
        e->end_a[k] = e->end_a[e->ns];
        e->end_b[k] = e->end_b[e->ns];
    } else if (op == 2) {
        double t = next_uniform(s);
        assert_ok(rg_body_set_one_way(w, x, t < 0.4 ? v2(0, 1) : t < 0.7 ? v2(0, 0) : t < 0.85 ? v2(1, 0) : v2(0, -1)));
    } else if (op == 3) {
        random_tolerate(rg_body_set_mass(w, x, (rg_real)(0.1 + 5 * next_uniform(s)))); /* not dynamic */
    } else if (op == 4) {
        assert_ok(rg_body_set_drag(w, x, (rg_real)(3 * next_uniform(s)), (rg_real)next_uniform(s)));
    } else if (op == 5) {
        assert_ok(rg_body_set_surface_friction(w, x, (rg_real)next_uniform(s), (rg_real)(20 * next_uniform(s))));
    } else if (op == 6) {
        rg_real lo = (rg_real)(0.5 * next_uniform(s));
        rg_real hi = next_uniform(s) < 0.3 ? 0 : (rg_real)(0.5 + 8 * next_uniform(s));
        assert_ok(rg_body_set_speed_limits(w, x, lo, hi));
        if (e->nlim < MAXLIM) {
            e->lim_body[e->nlim] = x;
            e->lim_min[e->nlim] = (double)lo;
            e->lim_max[e->nlim++] = (double)hi;
        }
    } else if (op == 7) {
        assert_ok(rg_body_set_gravity_scale(w, x, (rg_real)(-1 + 3 * next_uniform(s))));
    } else if (op == 8) {
        assert_ok(rg_body_set_friction(w, x, (rg_real)(2 * next_uniform(s))));
        assert_ok(rg_body_set_restitution(w, x, (rg_real)next_uniform(s)));
    } else if (op == 9) {
        assert_ok(rg_world_set_integrator(w, (int32_t)(next_uniform(s) * 4)));
    } else if (op == 10) {
        assert_ok(rg_world_set_solver_iterations(w, 1 + (int32_t)(next_uniform(s) * 10), (int32_t)(next_uniform(s) * 5)));
    } else if (op == 11) {
        int32_t on;
        assert_ok(rg_world_get_continuous(w, &on));
        assert_ok(rg_world_set_continuous(w, !on));
    } else if (op == 12) {
        assert_ok(rg_world_set_contact_tuning(w, (rg_real)(0.02 * next_uniform(s)), (rg_real)(0.05 + 0.95 * next_uniform(s)),
                                              (rg_real)(0.05 + next_uniform(s)), (rg_real)(2 * next_uniform(s))));
    } else if (op == 13) {
        assert_ok(rg_world_set_wind(w, random_v(s, -5, 5)));
        if (next_uniform(s) < 0.3) assert_ok(rg_world_set_gravity(w, random_v(s, -15, 5)));
    } else if (op == 14) {
        assert_ok(rg_body_apply_force(w, x, random_v(s, -50, 50)));
    } else if (op == 15) {
        rg_vec2 p, d = random_v(s, -2, 2);
        assert_ok(rg_body_get_position(w, x, &p));
        random_tolerate(rg_body_move(w, x, v2(p.x + d.x, p.y + d.y), 0xFFFFFFFFu, (int32_t)(next_uniform(s) * 3),
                                     NULL, NULL, 0, NULL)); /* no shape */
    } else {
        e->hook = next_uniform(s) < 0.5;
        random_hook_set(w, e);
    }
}

/* Up to three changes of either kind. */
static inline void random_changes(rg_world *w, uint32_t *s, rg_body *bodies, int *nb, random_extra *e)
{
    int changes = (int)(next_uniform(s) * 4);
    for (int k = 0; k < changes; k++) {
        if (next_uniform(s) < 0.5) random_change(w, s, bodies, nb);
        else random_more(w, s, bodies, *nb, e);
    }
}

/* A step, or (one time in four, *advanced set) an advance of a random frame time, which may
 * take no step or several; returns the steps taken. */
static inline int32_t random_step(rg_world *w, uint32_t *s, int *advanced)
{
    int32_t steps = 1;
    *advanced = next_uniform(s) < 0.25;
    if (*advanced) assert_ok(rg_world_advance(w, (rg_real)(0.05 * next_uniform(s)), &steps));
    else assert_ok(rg_world_step(w, (rg_real)DT));
    return steps;
}

/* Both, as the random scenes take them. */
static inline int32_t random_changes_and_step(rg_world *w, uint32_t *s, rg_body *bodies, int *nb, random_extra *e)
{
    int advanced;
    random_changes(w, s, bodies, nb, e);
    return random_step(w, s, &advanced);
}

#endif
