/* test_reliability.c (pending): library findings of the fuzzers awaiting their fix, one test
 * each, named for the promise it checks; each fails today.  `make pending` runs them against
 * the library built by clang under ASan + UBSan; they move into tests/ with their fixes (the
 * first ones are in tests/test_reliability.c).  A comment above each gives the root cause
 * found (file, function) and a suggested fix. */
#include "testutil.h"

/* ---------------------------------------------------------------- NaN from accepted input */

/* Found by tests/fuzz/fuzz_api.c on the ranges' fix (one body of 1 kg, a spring to an anchor
 * 1e7 m away with stiffness 1e7 N/m and damping 1e7 N*s/m, all within range; three steps of
 * 1/60 s: inf, then NaN).  Root cause: src/force.c, force_springs is explicit in every
 * integrator, unstable once k*dt^2/m > 4 (here 2 800) or c*dt/m > 2 (here 1.7e5): each step
 * multiplies the state until it overflows, and nothing stops a body leaving the ranges
 * (RG_MAX_COORD, RG_MAX_SPEED).  Suggested fix: springs treated implicitly when stiff (as
 * dissipation is, k*h >= 1), or the step made total: a body whose state would leave the
 * ranges is stopped there and reported. */
static void test_a_stiff_damped_spring_never_puts_a_nan_into_the_world(void **state)
{
    (void)state;
    rg_world *w;
    uint64_t s;
    assert_ok(rg_world_create(&w));
    rg_body b = make_body(w, 1, -0.25, -1);
    assert_ok(rg_body_set_circle(w, b, 1));
    assert_ok(rg_spring_create(w, b, 0, v2(0, 1e7f), 0, 1e7f, 1e7f, &s));
    for (int k = 0; k < 10; k++) {
        rg_status st = rg_world_step(w, (rg_real)(1.0 / 60));
        rg_vec2 p = pos_of(w, b), v = vel_of(w, b);
        if (!(isfinite(p.x) && isfinite(p.y) && isfinite(v.x) && isfinite(v.y)))
            fail_msg("step %d (status %d): x (%g, %g) v (%g, %g)", k + 1, st, (double)p.x,
                     (double)p.y, (double)v.x, (double)v.y);
    }
    rg_world_destroy(w);
}

/* ---------------------------------------------------------------- snapshots */

/* Found by tests/fuzz/fuzz_api.c on the ranges' fix (two 1-kg circles 0.25 m apart, a spring
 * between them of rest length 1e6 m, stiffness and damping 1e6, all within range; one step,
 * save, restore into a fresh world: the hashes differ, and so do the two worlds' own
 * snapshots, from the checksum at byte 24 on).  With the same scene at stiffness 10 the
 * velocities stay under RG_MAX_SPEED and the round trip is exact; here one step leaves them
 * at 1.7e10 m/s.  Root cause: the step that is not total (above); a state outside the
 * ranges does not survive save and restore unchanged (something restore.c derives or checks
 * differs, e.g. a body flag derived from the state).  Suggested fix: the total step (the
 * state stays within the ranges), or a restore that refuses rather than alters. */
static void test_a_restored_clone_hashes_like_its_original(void **state)
{
    (void)state;
    rg_world *w, *clone;
    uint64_t s, h1 = 0, h2 = 0;
    size_t n = 0;
    assert_ok(rg_world_create(&w));
    rg_body a = make_body(w, 1, -0.25, -1), b = make_body(w, 1, 0, -1);
    assert_ok(rg_body_set_circle(w, a, 1));
    assert_ok(rg_body_set_circle(w, b, 1));
    assert_ok(rg_spring_create(w, a, b, v2(0, 0), 1e6f, 1e6f, 1e6f, &s));
    assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
    assert_ok(rg_world_save(w, NULL, 0, &n));
    void *buf = malloc(n);
    assert_non_null(buf);
    assert_ok(rg_world_save(w, buf, n, &n));
    assert_ok(rg_world_create(&clone));
    assert_ok(rg_world_restore(clone, buf, n));
    assert_ok(rg_world_hash(w, &h1));
    assert_ok(rg_world_hash(clone, &h2));
    free(buf);
    if (h1 != h2) fail_msg("hash %016llx, its clone's %016llx", (unsigned long long)h1, (unsigned long long)h2);
    rg_world_destroy(clone);
    rg_world_destroy(w);
}

/* ---------------------------------------------------------------- out of memory */

/* Refuses every allocation once `limit` bytes are live; counts the refusals. */
typedef struct capped_alloc {
    size_t live, limit;
    long refused;
} capped_alloc;

static void *capped_allocf(void *user, void *ptr, size_t old_size, size_t new_size)
{
    capped_alloc *c = (capped_alloc *)user;
    if (new_size == 0) {
        if (ptr != NULL) c->live -= old_size;
        free(ptr);
        return NULL;
    }
    if (new_size > old_size && c->live + (new_size - old_size) > c->limit) {
        c->refused++;
        return NULL;
    }
    void *p = realloc(ptr, new_size);
    if (p != NULL) c->live = c->live - old_size + new_size;
    return p;
}

/* Found by tests/fuzz/fuzz_lua.c (300 overlapping circles under a 16 MiB cap: one step took
 * 39 s under ASan).  Root cause: src/contact.c, contact_create calls contact_grow whenever
 * the free list is empty, and when the grow fails the pair search (src/pairs.c, pairs_visit)
 * goes on to the next pair, which tries again: one failing grow, several allocations of
 * megabytes each, per remaining pair.  Suggested fix: remember the failure for the rest of
 * the step (stop creating contacts, or end the step with RG_ERR_OUT_OF_MEMORY changing
 * nothing).  The bound: a step that cannot grow needs to learn it once, so the refusals of
 * one step are at most the few blocks of one grow, not one per pair (300 bodies overlapping
 * are 44 850 pairs). */
static void test_a_step_out_of_memory_gives_up_growing_at_once(void **state)
{
    (void)state;
    capped_alloc cap = { 0, (size_t)2 << 20, 0 };
    rg_world *w;
    assert_ok(rg_world_create_with_allocator(capped_allocf, &cap, &w));
    for (int i = 0; i < 300; i++) {
        rg_body b = make_body(w, 1, i * 0.01, 0);
        assert_ok(rg_body_set_circle(w, b, 10));
    }
    cap.refused = 0;
    (void)rg_world_step(w, (rg_real)(1.0 / 60));
    if (cap.refused > 16) fail_msg("one step had %ld allocations refused", cap.refused);
    rg_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_stiff_damped_spring_never_puts_a_nan_into_the_world),
        cmocka_unit_test(test_a_restored_clone_hashes_like_its_original),
        cmocka_unit_test(test_a_step_out_of_memory_gives_up_growing_at_once),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
