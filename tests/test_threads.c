/* test_threads.c: the step spread over a task system gives bit-identical results at any
 * number of workers, and the same as the step on one thread: a scene large enough that every
 * stage splits (3000 bodies: circles and boxes in a container, springs, drag, a kinematic
 * platform, a sensor, a one-way ledge, bullets, sleeping), hashed every 20 steps and
 * compared across
 *   - no task system (one thread),
 *   - the shuffler (shuffler.h): a task system of 1 to 4 workers that splits each task into
 *     ranges of random lengths (at least min_range), runs them in a random order with random
 *     worker indices, and defers them to finish (it exercises what threads would do to the
 *     split and the order, deterministically),
 *   - rg_thread_pool with 1 to 4 threads (real threads; this machine may have fewer cores).
 * And the pool's and the task system's bad input, and the pool's own promises: every item of
 * every task runs once, inside its task, in ranges of at least min_range. */
#include "testutil.h"
#include "shuffler.h"

/* ---------------------------------------------------------------- the scene */

enum { N_BODIES = 3000, STEPS = 120 };

typedef struct big_scene {
    rg_world *w;
    rg_body b[N_BODIES + 64];
    int n;
} big_scene;

static rg_body big_add(big_scene *s, int32_t type, double m, double x, double y)
{
    rg_body b;
    assert_true(s->n < N_BODIES + 64);
    assert_ok(rg_body_create(s->w, type, (rg_real)m, v2(x, y), &b));
    s->b[s->n++] = b;
    return b;
}

/* Every body's position, velocity, grounded and awake flags, the step's events and the
 * counts; rg_world_hash on top (the whole state, contacts and accumulated impulses included). */
static uint64_t big_hash(const big_scene *s, uint64_t h)
{
    h = hash_bodies(s->w, s->b, s->n, h);
    /* each call its own buffer: two worlds may be hashed at once from two threads */
    rg_contact_event *ev = malloc(65536 * sizeof *ev);
    assert_non_null(ev);
    int32_t n = rg_world_get_contact_events(s->w, ev, 65536);
    assert_true(n >= 0 && n <= 65536);
    /* field by field (no padding), handles without their world's random tag (the top bits) */
    const uint64_t untagged = (1ull << 44) - 1;
    for (int32_t k = 0; k < n; k++) {
        uint64_t who[2] = { ev[k].a & untagged, ev[k].b & untagged };
        int32_t kind[2] = { ev[k].kind, ev[k].sensor };
        rg_real r[6] = { ev[k].normal.x, ev[k].normal.y, ev[k].point.x, ev[k].point.y, ev[k].depth, ev[k].speed };
        h = fnv(h, who, 2, sizeof who[0]);
        h = fnv(h, kind, 2, sizeof kind[0]);
        h = fnv(h, r, 6, sizeof r[0]);
    }
    free(ev);
    int32_t counts[3] = { n, rg_world_touching_count(s->w), rg_world_awake_body_count(s->w) };
    h = fnv(h, counts, 3, sizeof counts[0]);
    uint64_t whole;
    assert_ok(rg_world_hash(s->w, &whole));
    return fnv(h, &whole, 1, sizeof whole);
}

/* plain: without the one-way ledge and with sleeping off, so that no contact is decided in
 * order and no body can wake: the narrowphase's commits (events, grounded flags) then run
 * beside the solve's first part (narrow.c, resolve.c). */
static uint64_t run_big(int32_t integrator, const rg_task_system *tasks, int plain)
{
    big_scene *s = calloc(1, sizeof *s);
    assert_non_null(s);
    assert_ok(rg_world_create(&s->w));
    assert_ok(rg_world_set_task_system(s->w, tasks));
    assert_ok(rg_world_set_gravity(s->w, v2(0, -9.81)));
    assert_ok(rg_world_set_integrator(s->w, integrator));
    if (plain) assert_ok(rg_world_set_sleeping(s->w, 0));
    rg_body floor = big_add(s, RG_BODY_STATIC, 0, 0, -0.5);
    assert_ok(rg_body_set_aabb(s->w, floor, 40, 0.5));
    for (int side = -1; side <= 1; side += 2) {
        rg_body wall = big_add(s, RG_BODY_STATIC, 0, side * 40.5, 20);
        assert_ok(rg_body_set_aabb(s->w, wall, 0.5, 21));
    }
    if (!plain) {
        rg_body ledge = big_add(s, RG_BODY_STATIC, 0, 20, 6);
        assert_ok(rg_body_set_aabb(s->w, ledge, 6, 0.2));
        assert_ok(rg_body_set_one_way(s->w, ledge, v2(0, 1)));
    }
    rg_body plat = big_add(s, RG_BODY_KINEMATIC, 0, -30, 4);
    assert_ok(rg_body_set_aabb(s->w, plat, 3, 0.2));
    assert_ok(rg_body_set_velocity(s->w, plat, v2(2, 0)));
    rg_body coin = big_add(s, RG_BODY_STATIC, 0, 0, 3);
    assert_ok(rg_body_set_circle(s->w, coin, 2));
    assert_ok(rg_body_set_sensor(s->w, coin, 1));
    for (int i = 0; i < N_BODIES; i++) {
        double x = -39 + (i % 100) * 0.78 + 0.011 * (i % 7), y = 1 + (i / 100) * 0.9;
        rg_body b = big_add(s, RG_BODY_DYNAMIC, 0.5 + 0.25 * (i % 5), x, y);
        double size = 0.25 + 0.03 * (i % 4);
        if (i % 3 == 0)
            assert_ok(rg_body_set_aabb(s->w, b, (rg_real)size, (rg_real)(size * 0.8)));
        else
            assert_ok(rg_body_set_circle(s->w, b, (rg_real)size));
        if (i % 4 == 1) assert_ok(rg_body_set_restitution(s->w, b, 0.4f));
        if (i % 5 == 2) assert_ok(rg_body_set_friction(s->w, b, 0.2f));
        if (i % 7 == 3) assert_ok(rg_body_set_drag(s->w, b, 0.1f, 0.02f));
        if (i % 11 == 5) assert_ok(rg_body_set_surface_friction(s->w, b, 0.2f, 1));
        assert_ok(rg_body_set_velocity(s->w, b, v2((i % 5) - 2, -(i % 3))));
        if (i % 50 == 49) {
            uint64_t sp;
            assert_ok(rg_spring_create(s->w, b, s->b[s->n - 2], v2(0, 0), 0.8f, 30, 0.5f, &sp));
        }
        if (i % 400 == 7) assert_ok(rg_body_set_velocity(s->w, b, v2(120, -40))); /* bullets */
    }
    uint64_t h = 1469598103934665603ull;
    for (int k = 1; k <= STEPS; k++) {
        if (k == 120) assert_ok(rg_body_set_velocity(s->w, plat, v2(-2, 0)));
        assert_ok(rg_world_step(s->w, (rg_real)(1.0 / 60)));
        if (k % 20 == 0) h = big_hash(s, h);
    }
    rg_world_destroy(s->w);
    free(s);
    return h;
}

/* ---------------------------------------------------------------- tests */

static int compare(const char *name, uint64_t got, uint64_t want)
{
    printf("  %-34s 0x%016llxull%s\n", name, (unsigned long long)got, got == want ? "" : "  MISMATCH");
    return got != want;
}

/* workers_max 0: 2 and 3 workers only (the shuffler at 3, the pool at 2). */
static void check_integrator(int32_t integrator, int workers_max, int plain)
{
    uint64_t one = run_big(integrator, NULL, plain);
    printf("  integrator %d%s, one thread   0x%016llxull\n", (int)integrator, plain ? ", plain" : "",
           (unsigned long long)one);
    int bad = 0;
    char name[64];
    for (int k = workers_max > 0 ? 1 : 2; k <= (workers_max > 0 ? workers_max : 3); k++) {
        shuffler sh;
        rg_task_system ts;
        shuffler_init(&sh, 0x9E3779B97F4A7C15ull * (uint64_t)k, k, 0);
        shuffler_tasks(&sh, &ts);
        if (workers_max > 0 || k == 3) {
            snprintf(name, sizeof name, "shuffler, %d workers", k);
            bad += compare(name, run_big(integrator, &ts, plain), one);
            assert_int_equal(sh.misuse, 0);
            /* the scene is large enough that stages do split */
            if (k > 1) assert_true(sh.ranges > sh.tasks);
        }
        if (workers_max == 0 && k != 2) continue;
        rg_thread_pool *pool;
        assert_ok(rg_thread_pool_create(k, &pool));
        assert_ok(rg_thread_pool_task_system(pool, &ts));
        snprintf(name, sizeof name, "thread pool, %d threads", k);
        bad += compare(name, run_big(integrator, &ts, plain), one);
        rg_thread_pool_destroy(pool);
    }
    assert_int_equal(bad, 0);
}

static void test_the_default_integrator_is_identical_at_1_to_4_workers(void **state)
{
    (void)state;
    check_integrator(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, 4, 0);
    check_integrator(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, 4, 1);
}

static void test_the_other_integrators_are_identical_with_more_workers(void **state)
{
    (void)state;
    check_integrator(RG_INTEGRATOR_EXPLICIT_EULER, 0, 0);
    check_integrator(RG_INTEGRATOR_VELOCITY_VERLET, 0, 0);
    check_integrator(RG_INTEGRATOR_RK4, 0, 0);
}

static void *never(rg_task_fn *fn, int32_t count, int32_t min_range, void *context, void *user)
{
    (void)fn;
    (void)count;
    (void)min_range;
    (void)context;
    (void)user;
    fail_msg("a refused task system was called");
    return NULL;
}

static void never_finish(void *task, void *user)
{
    (void)task;
    (void)user;
}

static void test_bad_task_systems_and_pools_are_refused(void **state)
{
    (void)state;
    rg_world *w;
    assert_ok(rg_world_create(&w));
    rg_task_system ts = { 0, never, never_finish, NULL };
    assert_status(rg_world_set_task_system(w, &ts), RG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(rg_world_last_error(w), "workers 0"));
    ts.workers = RG_MAX_WORKERS + 1;
    assert_status(rg_world_set_task_system(w, &ts), RG_ERR_INVALID_ARGUMENT);
    ts.workers = 2;
    ts.enqueue = NULL;
    assert_status(rg_world_set_task_system(w, &ts), RG_ERR_INVALID_ARGUMENT);
    ts.enqueue = never;
    ts.finish = NULL;
    assert_status(rg_world_set_task_system(w, &ts), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_task_system(NULL, NULL), RG_ERR_INVALID_ARGUMENT);
    /* none took: the world steps on one thread (never would fail) */
    for (int i = 0; i < 3000; i++) circle_body(w, RG_BODY_DYNAMIC, 1, i % 60, i / 60, 0.4);
    step_n(w, 3, DT);
    assert_ok(rg_world_set_task_system(w, NULL));
    rg_world_destroy(w);

    rg_thread_pool *pool = (rg_thread_pool *)&ts;
    assert_status(rg_thread_pool_create(0, &pool), RG_ERR_INVALID_ARGUMENT);
    assert_null(pool);
    assert_status(rg_thread_pool_create(RG_MAX_WORKERS + 1, &pool), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_thread_pool_create(2, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_thread_pool_task_system(NULL, &ts), RG_ERR_INVALID_ARGUMENT);
    assert_ok(rg_thread_pool_create(3, &pool));
    assert_status(rg_thread_pool_task_system(pool, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_ok(rg_thread_pool_task_system(pool, &ts));
    assert_int_equal(ts.workers, 3);
    rg_thread_pool_destroy(pool);
    rg_thread_pool_destroy(NULL);
}

/* Two worlds stepped at once from two threads share one pool: their tasks take turns, and
 * each world's results are its one-thread results. */
#include <pthread.h>

typedef struct twin {
    const rg_task_system *ts;
    uint64_t h;
} twin;

static void *twin_main(void *p)
{
    twin *t = p;
    t->h = run_big(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, t->ts, 1);
    return NULL;
}

static void test_two_worlds_on_two_threads_share_a_pool(void **state)
{
    (void)state;
    uint64_t one = run_big(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, NULL, 1);
    rg_thread_pool *pool;
    rg_task_system ts;
    assert_ok(rg_thread_pool_create(3, &pool));
    assert_ok(rg_thread_pool_task_system(pool, &ts));
    twin a = { &ts, 0 }, b = { &ts, 0 };
    pthread_t ta, tb;
    assert_int_equal(pthread_create(&ta, NULL, twin_main, &a), 0);
    assert_int_equal(pthread_create(&tb, NULL, twin_main, &b), 0);
    pthread_join(ta, NULL);
    pthread_join(tb, NULL);
    rg_thread_pool_destroy(pool);
    assert_true(a.h == one && b.h == one);
}

/* The pool runs every item of every task exactly once, and only inside its task: tasks of
 * alternating sizes back to back (the next task's count larger than where the last one's
 * ranges ran out), each item counting its runs in its own task's record (POOL_ITEMS bytes
 * per task).  A thread late from
 * one task must find no range of it left, never run a range of the next task under the last
 * one's claim (which ran those items twice, and let the task end before they were done). */
enum { POOL_TASKS = 200000, POOL_ITEMS = 64 };

static void count_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    uint8_t *runs = context;
    (void)worker;
    for (int32_t i = begin; i < end; i++) __atomic_fetch_add(&runs[i], 1, __ATOMIC_RELAXED);
}

/* Task k's items: 3, then 64, in turn: a late thread of a small task sees its ranges run out
 * at 3, below the next task's count. */
static int32_t pool_task_items(int32_t k) { return (k & 1) ? POOL_ITEMS : 3; }

static void test_the_pool_runs_each_item_of_each_task_once(void **state)
{
    (void)state;
    uint8_t *runs = malloc((size_t)POOL_TASKS * POOL_ITEMS);
    assert_non_null(runs);
    for (int32_t threads = 2; threads <= 3; threads++) {
        rg_thread_pool *pool;
        rg_task_system ts;
        assert_ok(rg_thread_pool_create(threads, &pool));
        assert_ok(rg_thread_pool_task_system(pool, &ts));
        memset(runs, 0, (size_t)POOL_TASKS * POOL_ITEMS);
        long early = 0, wrong = 0;   /* early: items not yet run when their task returned */
        for (int32_t k = 0; k < POOL_TASKS; k++) {
            int32_t count = pool_task_items(k);   /* in ranges of 1 */
            uint8_t *r = runs + (size_t)k * POOL_ITEMS;
            void *h = ts.enqueue(count_range, count, 1, r, ts.user);
            if (h != NULL) ts.finish(h, ts.user);
            for (int32_t i = 0; i < count; i++) early += __atomic_load_n(&r[i], __ATOMIC_RELAXED) == 0;
        }
        rg_thread_pool_destroy(pool);
        for (int32_t k = 0; k < POOL_TASKS; k++)
            for (int32_t i = 0; i < POOL_ITEMS; i++)
                wrong += runs[(size_t)k * POOL_ITEMS + i] != (i < pool_task_items(k));
        printf("  %d threads: %d tasks, %ld items run other than once, %ld not yet run when their task returned\n",
               (int)threads, (int)POOL_TASKS, wrong, early);
        assert_int_equal(wrong, 0);
        assert_int_equal(early, 0);
    }
    free(runs);
}

/* The task system's promise on ranges (rigid.h: "in ranges of at least min_range"): every
 * range the pool hands out holds at least min_range items, but where the task itself is
 * smaller, and the ranges cover [0, count) once; counts 1-300 against min_range 1-17, at 2,
 * 3 and 4 threads (a part per thread, fewer when a part would be short of min_range). */
typedef struct range_log {
    int32_t min_range, count;
    int32_t short_ranges;  /* atomic */
    uint8_t runs[300];
} range_log;

static void log_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    range_log *l = context;
    (void)worker;
    int32_t least = l->min_range < l->count ? l->min_range : l->count;
    if (end - begin < least) __atomic_fetch_add(&l->short_ranges, 1, __ATOMIC_RELAXED);
    for (int32_t i = begin; i < end; i++) __atomic_fetch_add(&l->runs[i], 1, __ATOMIC_RELAXED);
}

static void test_the_pool_keeps_ranges_at_least_min_range(void **state)
{
    (void)state;
    for (int32_t threads = 2; threads <= 4; threads++) {
        rg_thread_pool *pool;
        rg_task_system ts;
        assert_ok(rg_thread_pool_create(threads, &pool));
        assert_ok(rg_thread_pool_task_system(pool, &ts));
        long short_ranges = 0, wrong = 0;
        for (int32_t count = 1; count <= 300; count++) {
            for (int32_t min_range = 1; min_range <= 17; min_range++) {
                range_log l;
                memset(&l, 0, sizeof l);
                l.min_range = min_range;
                l.count = count;
                void *h = ts.enqueue(log_range, count, min_range, &l, ts.user);
                if (h != NULL) ts.finish(h, ts.user);
                short_ranges += l.short_ranges;
                for (int32_t i = 0; i < count; i++) wrong += l.runs[i] != 1;
            }
        }
        rg_thread_pool_destroy(pool);
        assert_int_equal(short_ranges, 0);
        assert_int_equal(wrong, 0);
    }
}

/* An allocator that, armed, refuses the first block of 64 kB or more asked of it. */
typedef struct refusing {
    int armed;
    long refused, big; /* blocks refused, big blocks given */
} refusing;

static void *refusing_fn(void *user, void *ptr, size_t old_size, size_t new_size)
{
    refusing *r = user;
    if (new_size >= ((size_t)64 << 10)) {
        if (r->armed) {
            r->armed = 0;
            r->refused++;
            return NULL;
        }
        r->big++;
    }
    if (new_size == 0) {
        free(ptr);
        return NULL;
    }
    (void)old_size;
    return realloc(ptr, new_size);
}

/* The first step with workers lays out the parallel staging's spare rows (narrow.c: 160 kB
 * for this pile's contacts in the float build, more in the double; the pair search's own
 * blocks for workers are 3 kB); where the allocator refuses them, that step stages its rows
 * on the stepping thread instead, with the results of one thread, and the next step lays
 * them out. */
static void test_workers_whose_spare_rows_are_refused_step_as_one_thread(void **state)
{
    (void)state;
    enum { N = 1200 };
    refusing ref = { 0, 0, 0 };
    rg_world *w[2];
    rg_body b[2][N];
    assert_ok(rg_world_create(&w[0]));
    assert_ok(rg_world_create_with_allocator(refusing_fn, &ref, &w[1]));
    for (int k = 0; k < 2; k++) {
        assert_ok(rg_world_set_gravity(w[k], v2(0, -10)));
        assert_ok(rg_world_set_sleeping(w[k], 0));
        floor_of(w[k]);
        for (int i = 0; i < N; i++) /* columns 1.1 m apart of boxes 1.05 m apart: every box rests */
            b[k][i] = box_body(w[k], RG_BODY_DYNAMIC, 1, -16.5 + 1.1 * (i % 30), 0.5 + 1.05 * (i / 30), 0.5, 0.5);
        step_n(w[k], 30, DT);
    }
    shuffler sh;
    rg_task_system ts;
    shuffler_init(&sh, 11, 2, 0);
    shuffler_tasks(&sh, &ts);
    assert_ok(rg_world_set_task_system(w[1], &ts));
    long big = ref.big;
    ref.armed = 1;
    for (int k = 0; k < 2; k++) assert_ok(rg_world_step(w[k], DT));
    assert_int_equal(ref.refused, 1);
    assert_int_equal(ref.big, big);
    assert_true(hash_bodies(w[0], b[0], N, 0) == hash_bodies(w[1], b[1], N, 0));
    for (int k = 0; k < 2; k++) assert_ok(rg_world_step(w[k], DT));
    assert_int_equal(ref.big, big + 1); /* laid out now */
    for (int k = 0; k < 2; k++) step_n(w[k], 20, DT);
    assert_int_equal(ref.big, big + 1);
    assert_true(hash_bodies(w[0], b[0], N, 0) == hash_bodies(w[1], b[1], N, 0));
    uint64_t h[2];
    for (int k = 0; k < 2; k++) assert_ok(rg_world_hash(w[k], &h[k]));
    assert_true(h[0] == h[1]);
    assert_true(sh.ranges > sh.tasks);
    assert_int_equal(sh.misuse, 0);
    for (int k = 0; k < 2; k++) rg_world_destroy(w[k]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_the_default_integrator_is_identical_at_1_to_4_workers),
        cmocka_unit_test(test_the_other_integrators_are_identical_with_more_workers),
        cmocka_unit_test(test_bad_task_systems_and_pools_are_refused),
        cmocka_unit_test(test_two_worlds_on_two_threads_share_a_pool),
        cmocka_unit_test(test_the_pool_runs_each_item_of_each_task_once),
        cmocka_unit_test(test_the_pool_keeps_ranges_at_least_min_range),
        cmocka_unit_test(test_workers_whose_spare_rows_are_refused_step_as_one_thread),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
