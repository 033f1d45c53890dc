/* test_slots.c: kept states (rg_world_save_slot, rg_world_restore_slot, rg_world_drop_slot):
 * a kept state brings the world back exactly as its snapshot would, slots are independent,
 * the rollback loop's memory holds, and a failure changes nothing. */
#include "snapshot_scene.h"

/* The world's snapshot now is the one given: its bytes are the whole state (snapshot.h). */
static void assert_same_state(rg_world *w, const void *snap, size_t size)
{
    size_t n;
    void *now = save(w, &n);
    assert_true(n == size);
    assert_memory_equal(now, snap, size);
    free(now);
}

/* For every integrator: keep the state at step 100 (and save its snapshot), run on, destroy
 * and create bodies; back to the slot: the world's snapshot is byte for byte the one saved
 * then, its handles name the same bodies, and the run after gives the same hash and events
 * at every step as the first run and as a restore of the snapshot. */
static void test_a_kept_state_restores_as_its_snapshot_would(void **state)
{
    (void)state;
    enum { K = 100, N = 120 };
    static uint64_t first[N], again[N], by_bytes[N];
    for (int32_t integ = 0; integ < 4; integ++) {
        rg_world *w;
        assert_ok(rg_world_create(&w));
        scene s;
        build(&s, w, integ);
        step_n(w, K, 1.0 / 60);
        assert_ok(rg_world_save_slot(w, 5));
        size_t size;
        void *snap = save(w, &size);
        run(w, N, first);
        assert_ok(rg_body_destroy(w, s.doomed));
        rg_body late;
        assert_ok(rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(0, 9), &late));
        assert_ok(rg_world_restore_slot(w, 5));
        assert_same_state(w, snap, size);
        assert_true(rg_body_is_valid(w, s.doomed));
        assert_false(rg_body_is_valid(w, late));
        run(w, N, again);
        assert_memory_equal(first, again, sizeof first);
        /* the slot keeps its state: once more, and against the snapshot's restore */
        assert_ok(rg_world_restore_slot(w, 5));
        assert_same_state(w, snap, size);
        assert_ok(rg_world_restore(w, snap, size));
        run(w, N, by_bytes);
        assert_memory_equal(first, by_bytes, sizeof first);
        free(snap);
        rg_world_destroy(w);
    }
}

/* Eight slots kept at eight frames, brought back in a scrambled order: each gives its own
 * frame's state; dropping one empties it and leaves the others. */
static void test_slots_are_independent(void **state)
{
    (void)state;
    enum { SLOTS = 8 };
    rg_world *w;
    assert_ok(rg_world_create(&w));
    scene s;
    build(&s, w, RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
    uint64_t h[SLOTS];
    for (int k = 0; k < SLOTS; k++) {
        step_n(w, 7, 1.0 / 60);
        assert_ok(rg_world_save_slot(w, RG_MAX_SLOTS - 1 - k));
        h[k] = hash_of(w);
    }
    for (int k = 0; k < SLOTS; k++) assert_true(k == 0 || h[k] != h[k - 1]); /* the frames differ */
    static const int order[SLOTS] = { 3, 0, 7, 5, 1, 6, 2, 4 };
    for (int j = 0; j < SLOTS; j++) {
        int k = order[j];
        assert_ok(rg_world_restore_slot(w, RG_MAX_SLOTS - 1 - k));
        assert_true(hash_of(w) == h[k]);
        step_n(w, 3, 1.0 / 60);
    }
    assert_ok(rg_world_drop_slot(w, RG_MAX_SLOTS - 1 - 2));
    assert_status(rg_world_restore_slot(w, RG_MAX_SLOTS - 1 - 2), RG_ERR_INVALID_ARGUMENT);
    assert_ok(rg_world_drop_slot(w, RG_MAX_SLOTS - 1 - 2)); /* an empty slot: no error */
    assert_ok(rg_world_restore_slot(w, RG_MAX_SLOTS - 1 - 3));
    assert_true(hash_of(w) == h[3]);
    rg_world_destroy(w);
}

/* A rollback loop of 10,000 frames back to one kept state (go back, step a frame, keep the
 * state gone back to): after the first the world's memory neither grows nor shrinks.  In a
 * loop that keeps an evolving state (keep, step two frames, go back, step one) the block
 * count stays the same, and a slot's block grows only when the state outgrows it, each time
 * to 9/8 of the state: from a first block of 9/8 of `first` bytes, g growths make one above
 * (9/8)^(g+1) first and at most 9/8 of the largest state, so g < log(largest / first) /
 * log(9/8).  Every slot's block goes with the world. */
static void test_ten_thousand_slot_rollbacks_hold_memory(void **state)
{
    (void)state;
    test_alloc ta;
    scene s;
    rg_world *w = counted_scene(&s, &ta);
    assert_ok(rg_world_save_slot(w, 0));
    uint64_t h0 = hash_of(w);
    size_t first = 0, largest = 0; /* the first keep's block: 9/8 of first */
    assert_ok(rg_world_save(w, NULL, 0, &first));
    step_n(w, 2, 1.0 / 60);
    assert_ok(rg_world_restore_slot(w, 0));
    step_n(w, 1, 1.0 / 60);
    long long bytes = ta.live_bytes;
    long blocks = ta.live_blocks;
    for (int k = 0; k < 10000; k++) {
        assert_ok(rg_world_restore_slot(w, 0));
        if (k % 1000 == 0) {
            assert_true(hash_of(w) == h0);
            assert_ok(rg_world_save_slot(w, 0));
        }
        step_n(w, 1, 1.0 / 60);
        assert_memory_held(&ta, bytes, blocks, k);
    }
    int growths = 0;
    for (int k = 0; k < 2000; k++) {
        size_t n = 0;
        assert_ok(rg_world_save(w, NULL, 0, &n));
        largest = n > largest ? n : largest;
        long long before = ta.live_bytes;
        assert_ok(rg_world_save_slot(w, 0));
        growths += ta.live_bytes != before;
        step_n(w, 2, 1.0 / 60);
        assert_ok(rg_world_restore_slot(w, 0));
        step_n(w, 1, 1.0 / 60);
        assert_true(ta.live_blocks == blocks);
    }
    assert_true(growths < log((double)largest / (double)first) / log(9.0 / 8.0) || growths == 0);
    assert_ok(rg_world_save_slot(w, 9));
    assert_true(ta.live_blocks == blocks + 1);
    assert_ok(rg_world_drop_slot(w, 9));
    assert_true(ta.live_blocks == blocks);
    assert_ok(rg_world_save_slot(w, 9));
    rg_world_destroy(w);
    assert_int_equal(ta.live_blocks, 0);
}

/* With the allocator failing from its k-th call on: a restore into a world that must grow
 * (from a small state to a bigger one) returns RG_ERR_OUT_OF_MEMORY and the world is as it
 * was; a keep whose slot's block must grow returns it too and the slot holds what it held. */
static void test_out_of_memory_on_a_slot_changes_nothing(void **state)
{
    (void)state;
    int failed_restore = 0, failed_keep = 0;
    for (long fail = 1; fail < 40; fail++) {
        test_alloc ta;
        memset(&ta, 0, sizeof ta);
        rg_world *w;
        assert_ok(rg_world_create_with_allocator(test_alloc_fn, &ta, &w));
        rg_body b = make_body(w, 1, 1, 1);
        assert_ok(rg_world_save_slot(w, 1));
        uint64_t small = hash_of(w);
        scene s;
        build(&s, w, RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
        step_n(w, 20, 1.0 / 60);
        uint64_t big = hash_of(w);
        assert_ok(rg_world_save_slot(w, 2));
        assert_ok(rg_world_restore_slot(w, 1));
        assert_true(hash_of(w) == small);
        ta.fail_at = ta.calls + fail;
        rg_status st = rg_world_restore_slot(w, 2);
        ta.fail_at = 0;
        if (st == RG_OK) {
            assert_true(hash_of(w) == big);
        } else {
            assert_int_equal(st, RG_ERR_OUT_OF_MEMORY);
            assert_true(hash_of(w) == small && rg_body_is_valid(w, b));
            failed_restore++;
            assert_ok(rg_world_restore_slot(w, 2));
        }
        /* the big state into slot 1, whose block holds the small one */
        ta.fail_at = ta.calls + fail;
        st = rg_world_save_slot(w, 1);
        ta.fail_at = 0;
        assert_true(st == RG_OK || st == RG_ERR_OUT_OF_MEMORY);
        failed_keep += st != RG_OK;
        assert_true(hash_of(w) == big);
        assert_ok(rg_world_restore_slot(w, 1));
        assert_true(hash_of(w) == (st == RG_OK ? big : small));
        rg_world_destroy(w);
        assert_int_equal(ta.live_blocks, 0);
    }
    /* the failures happened: the first allocation of each call fails at fail = 1 */
    assert_true(failed_restore > 0 && failed_keep > 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_kept_state_restores_as_its_snapshot_would),
        cmocka_unit_test(test_slots_are_independent),
        cmocka_unit_test(test_ten_thousand_slot_rollbacks_hold_memory),
        cmocka_unit_test(test_out_of_memory_on_a_slot_changes_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
