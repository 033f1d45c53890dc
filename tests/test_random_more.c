/* test_random_more.c: random scenes with every kind of change between steps, random_change's
 * and random_more's (springs, one-way normals, masses, drag, frictions, speed limits, gravity
 * scales, the integrator, the solver, continuous collision, the contact tuning, gravity and
 * wind, forces, moves and the pre-solve hook): they step alike on one and two workers, replay
 * alike after a restore into themselves or into a fresh world, and keep after every step what
 * the header promises of each change. */
#include <math.h>

#include "random_scene.h"

#define SCENES 100
#define STEPS 300

/* A scene's world, bodies and record. */
typedef struct rscene {
    rg_world *w;
    uint32_t s;
    rg_body bodies[MAXB];
    int nb;
    random_extra e;
} rscene;

static void rscene_begin(rscene *r, int scene, const rg_task_system *tasks)
{
    r->s = 31000u + (uint32_t)scene;
    r->w = random_world(scene, &r->s, tasks, r->bodies, &r->nb);
    memset(&r->e, 0, sizeof r->e);
}

static uint64_t hash_of(const rg_world *w)
{
    uint64_t h;
    assert_ok(rg_world_hash(w, &h));
    return h;
}

/* 100 scenes of 300 steps on one thread and on two workers: every step's hash is the one
 * thread's. */
static void test_random_scenes_with_every_change_step_alike_on_one_and_two_workers(void **state)
{
    (void)state;
    static uint64_t one[STEPS];
    rg_task_system tasks;
    rg_thread_pool *pool = random_pool(&tasks);
    for (int scene = 0; scene < SCENES; scene++) {
        for (int run = 0; run < 2; run++) {
            rscene r;
            rscene_begin(&r, scene, run ? &tasks : NULL);
            for (int i = 0; i < STEPS; i++) {
                random_changes_and_step(r.w, &r.s, r.bodies, &r.nb, &r.e);
                if (run == 0) one[i] = hash_of(r.w);
                else if (hash_of(r.w) != one[i]) fail_msg("scene %d: step %d differs on two workers", scene, i + 1);
            }
            rg_world_destroy(r.w);
        }
    }
    rg_thread_pool_destroy(pool);
}

/* Every 40 steps a scene saves its state, takes 15 steps with their changes, and then takes
 * them again: by turns in itself, restored from the snapshot or from a kept slot, and in a
 * fresh world restored from the snapshot and then given the hook (the hook is the world's
 * own, not saved; installing it changes nothing).  Each step of the second run hashes as the
 * first; the fresh world hashes as the saved one at once.  (On 0424ea4, whose set_pre_solve
 * woke every sleeping body, a world restored and then given its hook hashed otherwise.) */
static void test_random_scenes_with_every_change_replay_alike_after_a_restore(void **state)
{
    (void)state;
    static unsigned char saved[1 << 20];
    rg_task_system tasks;
    rg_thread_pool *pool = random_pool(&tasks);
    for (int scene = 0; scene < SCENES; scene++) {
        rscene r;
        rscene_begin(&r, scene, scene % 2 ? &tasks : NULL);
        for (int i = 0; i < STEPS; i++) {
            if (i % 40 != 17) {
                random_changes_and_step(r.w, &r.s, r.bodies, &r.nb, &r.e);
                continue;
            }
            int how = (i / 40) % 3; /* 0 snapshot, 1 slot, 2 a fresh world */
            size_t size = 0;
            if (how == 1) assert_ok(rg_world_save_slot(r.w, 0));
            else assert_ok(rg_world_save(r.w, saved, sizeof saved, &size));
            uint64_t at_save = hash_of(r.w);
            rscene before = r, after;
            uint64_t first[15];
            for (int k = 0; k < 15; k++) {
                random_changes_and_step(r.w, &r.s, r.bodies, &r.nb, &r.e);
                first[k] = hash_of(r.w);
            }
            after = r;
            r = before;
            if (how == 0) assert_ok(rg_world_restore(r.w, saved, size));
            if (how == 1) assert_ok(rg_world_restore_slot(r.w, 0));
            if (how == 2) {
                assert_ok(rg_world_create(&r.w));
                assert_ok(rg_world_restore(r.w, saved, size));
                if (scene % 3 == 0) assert_ok(rg_world_set_task_system(r.w, &tasks));
            }
            random_hook_set(r.w, &r.e);
            if (hash_of(r.w) != at_save) fail_msg("scene %d: the restore (%d) at step %d hashes otherwise", scene, how, i);
            for (int k = 0; k < 15; k++) {
                random_changes_and_step(r.w, &r.s, r.bodies, &r.nb, &r.e);
                if (hash_of(r.w) != first[k])
                    fail_msg("scene %d: step %d of the replay (%d) after step %d differs", scene, k + 1, how, i);
            }
            if (how == 2) {
                rg_world_destroy(r.w);
                r = after;
            }
            i += 15;
        }
        rg_world_destroy(r.w);
    }
    rg_thread_pool_destroy(pool);
}

/* What a step must leave, given the states before it (p0, v0, type, awake) and steps, the
 * steps it took (an advance may take none). */
static void check_step(const rscene *r, const rg_vec2 *p0, const rg_vec2 *v0, const int32_t *type,
                       const int32_t *awake, int32_t steps, rg_real alpha, int advanced, int scene, int i)
{
    rg_world *w = r->w;
    const random_extra *e = &r->e;
    int live = 0;
    for (int k = 0; k < e->ns; k++) {
        if (!rg_spring_is_valid(w, e->spring[k])) continue;
        live++;
        /* a spring ties its dynamic bodies' sleep: they wake together (made, cut or not) */
        rg_body a = e->end_a[k], b = e->end_b[k];
        if (b == 0 || body_type(w, a) != RG_BODY_DYNAMIC || body_type(w, b) != RG_BODY_DYNAMIC) continue;
        if (flag(rg_body_is_awake, w, a) != flag(rg_body_is_awake, w, b))
            fail_msg("scene %d, step %d: a spring ties an awake body to a sleeping one", scene, i);
    }
    assert_int_equal(live, rg_world_spring_count(w));
    for (int k = 0; k < r->nb; k++) {
        rg_body b = r->bodies[k];
        rg_vec2 p = pos_of(w, b), v = vel_of(w, b);
        if (!(isfinite(p.x) && isfinite(p.y) && isfinite(v.x) && isfinite(v.y))) fail_msg("scene %d: a state not finite", scene);
        if (steps == 0) continue;
        int limited = -1;
        for (int q = 0; q < e->nlim; q++)
            if (e->lim_body[q] == b) limited = q;
        double speed = hypot((double)v.x, (double)v.y);
        /* the limits hold where the step ends: the velocity read now obeys them */
        if (limited >= 0 && type[k] == RG_BODY_DYNAMIC) {
            double lo = e->lim_min[limited], hi = e->lim_max[limited];
            if (hi > 0 && speed > hi * (1 + 8 * REAL_EPS)) fail_msg("scene %d, step %d: speed %g over its max %g", scene, i, speed, hi);
            if (speed > 0 && speed < lo * (1 - 8 * REAL_EPS)) fail_msg("scene %d, step %d: speed %g under its min %g", scene, i, speed, lo);
        }
        if (type[k] == RG_BODY_STATIC && (p.x != p0[k].x || p.y != p0[k].y)) fail_msg("scene %d: a static body moved", scene);
        /* an awake kinematic body keeps its velocity and moves steps * v dt (to rounding) */
        if (type[k] == RG_BODY_KINEMATIC && awake[k] && limited < 0) {
            assert_true(v.x == v0[k].x && v.y == v0[k].y);
            double ex = (double)p0[k].x + steps * DT * (double)v0[k].x, ey = (double)p0[k].y + steps * DT * (double)v0[k].y;
            double tol = 4 * steps * REAL_EPS * (fabs(ex) + fabs(ey) + 1);
            assert_near((double)p.x, ex, tol);
            assert_near((double)p.y, ey, tol);
        }
        /* after an advance of one step: drawn between where the step began and ends */
        if (advanced && steps == 1) {
            rg_vec2 ip;
            assert_ok(rg_body_get_interpolated_position(w, b, &ip));
            double ix = (double)p0[k].x + (double)alpha * ((double)p.x - (double)p0[k].x);
            double iy = (double)p0[k].y + (double)alpha * ((double)p.y - (double)p0[k].y);
            double tol = 8 * REAL_EPS * (fabs(ix) + fabs(iy) + fabs((double)p.x) + fabs((double)p.y) + 1);
            if (fabs((double)ip.x - ix) > tol || fabs((double)ip.y - iy) > tol) fail_msg("scene %d, step %d: drawn off its path", scene, i);
        }
    }
}

/* 100 scenes of 300 steps, half on two workers: after every step the springs the scene
 * made are the world's and tie their bodies' sleep, the speed limits hold, static bodies
 * stay, awake kinematic ones move at their velocity, and a body is drawn on its step's
 * path.  (On dd1af3b each of three fails: the drawing of a static body the mover carried,
 * then, that check aside, the speed limits, applied before the collisions, then, those
 * aside too, the spring ends: a spring made onto a sleeping body woke nothing.) */
static void test_random_scenes_with_every_change_keep_what_each_change_promises(void **state)
{
    (void)state;
    rg_task_system tasks;
    rg_thread_pool *pool = random_pool(&tasks);
    for (int scene = 0; scene < SCENES; scene++) {
        rscene r;
        rscene_begin(&r, scene, scene % 2 ? &tasks : NULL);
        for (int i = 0; i < STEPS; i++) {
            random_changes(r.w, &r.s, r.bodies, &r.nb, &r.e);
            rg_vec2 p0[MAXB], v0[MAXB];
            int32_t type[MAXB], awake[MAXB];
            for (int k = 0; k < r.nb; k++) {
                p0[k] = pos_of(r.w, r.bodies[k]);
                v0[k] = vel_of(r.w, r.bodies[k]);
                type[k] = body_type(r.w, r.bodies[k]);
                awake[k] = flag(rg_body_is_awake, r.w, r.bodies[k]);
            }
            int advanced;
            int32_t steps = random_step(r.w, &r.s, &advanced);
            rg_real alpha = 0;
            if (advanced) {
                assert_ok(rg_world_get_alpha(r.w, &alpha));
                assert_true(alpha >= 0 && alpha < 1);
            }
            check_step(&r, p0, v0, type, awake, steps, alpha, advanced, scene, i);
        }
        rg_world_destroy(r.w);
    }
    rg_thread_pool_destroy(pool);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_scenes_with_every_change_step_alike_on_one_and_two_workers),
        cmocka_unit_test(test_random_scenes_with_every_change_replay_alike_after_a_restore),
        cmocka_unit_test(test_random_scenes_with_every_change_keep_what_each_change_promises),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
