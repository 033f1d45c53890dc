/* test_restore_threads.c: rg_world_restore spread over a task system (its checks of the
 * contacts and the broadphase, the checksum beside the other checks, the load of the
 * contacts and members) decides and loads exactly as on one thread:
 *   - every 4-byte word of a snapshot set to a few hostile values and the checksum made
 *     right again (forged), and every byte flipped (damaged): the same status and the same
 *     reason (rg_world_last_error) with the shuffler (shuffler.h: random ranges, random
 *     order, deferred) and with rg_thread_pool as without a task system, and for an accepted
 *     forgery the same state (rg_world_hash);
 *   - a pile of 1200 bodies, saved as it falls and once it lies, restored by a world with
 *     the pool, the shuffler and none: the same hash, and the same 60 steps after.
 * make tsan runs it under ThreadSanitizer: a forged snapshot must not make two threads write
 * one place. */
#include <string.h>

#include "snapshot.h"
#include "shuffler.h"
#include "snapshot_scene.h"

enum { N_WORLDS = 3 }; /* none, the shuffler, the pool */

typedef struct trio {
    rg_world *w[N_WORLDS];
    shuffler sh;
    rg_task_system ts[N_WORLDS];
    rg_thread_pool *pool;
} trio;

static void trio_open(trio *t)
{
    for (int k = 0; k < N_WORLDS; k++) assert_ok(rg_world_create(&t->w[k]));
    shuffler_init(&t->sh, 0x2545F4914F6CDD1Dull, 3, 0);
    shuffler_tasks(&t->sh, &t->ts[1]);
    assert_ok(rg_thread_pool_create(2, &t->pool));
    assert_ok(rg_thread_pool_task_system(t->pool, &t->ts[2]));
    assert_ok(rg_world_set_task_system(t->w[1], &t->ts[1]));
    assert_ok(rg_world_set_task_system(t->w[2], &t->ts[2]));
}

static void trio_close(trio *t)
{
    assert_int_equal(t->sh.misuse, 0);
    for (int k = 0; k < N_WORLDS; k++) rg_world_destroy(t->w[k]);
    rg_thread_pool_destroy(t->pool);
}

/* The three worlds restore data: the same status, reason and (accepted) hash; returns the
 * status. */
static rg_status restore_alike(trio *t, const uint8_t *data, size_t size)
{
    rg_status st[N_WORLDS];
    char why[N_WORLDS][256];
    uint64_t h[N_WORLDS];
    for (int k = 0; k < N_WORLDS; k++) {
        st[k] = rg_world_restore(t->w[k], data, size);
        snprintf(why[k], sizeof why[k], "%s", st[k] == RG_OK ? "" : rg_world_last_error(t->w[k]));
        h[k] = st[k] == RG_OK ? hash_of(t->w[k]) : 0;
    }
    for (int k = 1; k < N_WORLDS; k++) {
        if (st[k] != st[0] || strcmp(why[k], why[0]) != 0 || h[k] != h[0])
            printf("  world %d: status %d '%s' hash %016llx; without tasks: %d '%s' %016llx\n", k, (int)st[k], why[k],
                   (unsigned long long)h[k], (int)st[0], why[0], (unsigned long long)h[0]);
        assert_int_equal(st[k], st[0]);
        assert_string_equal(why[k], why[0]);
        assert_true(h[k] == h[0]);
    }
    return st[0];
}

typedef struct tally {
    trio *t;
    int refused, accepted;
} tally;

static void restore_forged(uint8_t *bad, size_t size, void *context)
{
    tally *c = context;
    if (restore_alike(c->t, bad, size) == RG_OK)
        c->accepted++;
    else
        c->refused++;
}

static void test_forged_and_damaged_snapshots_are_decided_alike_with_workers(void **state)
{
    (void)state;
    trio t;
    trio_open(&t);
    rg_world *src;
    assert_ok(rg_world_create(&src));
    scene s;
    build(&s, src, RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
    step_n(src, 40, 1.0 / 60);
    size_t size;
    uint8_t *snap = save(src, &size);
    uint8_t *bad = malloc(size);
    assert_non_null(bad);
    assert_int_equal(restore_alike(&t, snap, size), RG_OK);
    tally c = { &t, 0, 0 };
    forge_words(snap, size, bad, restore_forged, &c);
    for (size_t k = SNAP_HEADER; k < size; k += 3) {
        memcpy(bad, snap, size);
        bad[k] ^= (uint8_t)(1u << (k % 8));
        assert_int_equal(restore_alike(&t, bad, size), RG_ERR_INVALID_ARGUMENT);
    }
    printf("  forged words: %d refused, %d accepted, alike with and without workers\n", c.refused, c.accepted);
    assert_true(c.refused > 0);
    /* the shuffler did split the passes */
    assert_true(t.sh.ranges > t.sh.tasks);
    free(bad);
    free(snap);
    rg_world_destroy(src);
    trio_close(&t);
}

/* A pile large enough that every pass splits into many ranges. */
static void pile(rg_world *w)
{
    assert_ok(rg_world_set_gravity(w, v2(0, -9.81)));
    rg_body b;
    assert_ok(rg_body_create(w, RG_BODY_STATIC, 0, v2(0, -0.5), &b));
    assert_ok(rg_body_set_aabb(w, b, 30, 0.5));
    for (int side = -1; side <= 1; side += 2) {
        assert_ok(rg_body_create(w, RG_BODY_STATIC, 0, v2(side * 30.5, 15), &b));
        assert_ok(rg_body_set_aabb(w, b, 0.5, 16));
    }
    for (int i = 0; i < 1200; i++) {
        assert_ok(rg_body_create(w, RG_BODY_DYNAMIC, (rg_real)(0.5 + 0.25 * (i % 5)),
                                 v2(-29 + (i % 60) * 0.97 + 0.013 * (i % 7), 1 + (i / 60) * 0.9), &b));
        if (i % 3 == 0)
            assert_ok(rg_body_set_aabb(w, b, 0.35f, 0.3f));
        else
            assert_ok(rg_body_set_circle(w, b, (rg_real)(0.3 + 0.04 * (i % 4))));
        if (i % 4 == 1) assert_ok(rg_body_set_restitution(w, b, 0.3f));
        if (i % 5 == 2) assert_ok(rg_body_set_friction(w, b, 0.2f));
    }
}

static void test_a_large_pile_restores_alike_with_workers(void **state)
{
    (void)state;
    trio t;
    trio_open(&t);
    rg_world *src;
    assert_ok(rg_world_create(&src));
    pile(src);
    for (int when = 0; when < 2; when++) {
        step_n(src, when == 0 ? 30 : 400, 1.0 / 60); /* falling, then at rest (asleep) */
        size_t size;
        uint8_t *snap = save(src, &size);
        long ranges = t.sh.ranges;
        assert_int_equal(restore_alike(&t, snap, size), RG_OK);
        assert_true(t.sh.ranges > ranges + 20);
        assert_true(hash_of(t.w[0]) == hash_of(src));
        for (int k = 0; k < 60; k++) {
            assert_ok(rg_world_step(src, (rg_real)(1.0 / 60)));
            for (int j = 0; j < N_WORLDS; j++) assert_ok(rg_world_step(t.w[j], (rg_real)(1.0 / 60)));
        }
        for (int j = 0; j < N_WORLDS; j++) assert_true(hash_of(t.w[j]) == hash_of(src));
        free(snap);
    }
    rg_world_destroy(src);
    trio_close(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_forged_and_damaged_snapshots_are_decided_alike_with_workers),
        cmocka_unit_test(test_a_large_pile_restores_alike_with_workers),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
