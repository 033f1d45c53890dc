/* test_pool.c: the handle pool — generations, retirement, tags, capacity. */
#include "testutil.h"

#include "pool.h"

static rg_mem heap(void)
{
    rg_mem m;
    m.fn = mem_default_alloc;
    m.user = NULL;
    m.locked = NULL; /* no world */
    m.err = NULL;
    return m;
}

static void test_handle_round_trips_and_is_never_zero(void **state)
{
    (void)state;
    rg_mem m = heap();
    pool p;
    pool_init(&p, 0, 0, 0); /* tag 0: the generation alone keeps handles non-zero */
    for (int32_t i = 0; i < 100; i++) {
        assert_ok(pool_reserve(&p, &m));
        uint64_t h = pool_alloc(&p, i);
        assert_true(h != 0);
        assert_int_equal(pool_lookup(&p, h), i);
    }
    assert_int_equal(p.live, 100);
    pool_release_memory(&p, &m);
}

static void test_freed_handle_is_stale_and_slot_reuse_gets_new_generation(void **state)
{
    (void)state;
    rg_mem m = heap();
    pool p;
    pool_init(&p, 5, 0, 0);
    assert_ok(pool_reserve(&p, &m));
    uint64_t a = pool_alloc(&p, 0);
    pool_free(&p, a);
    assert_int_equal(pool_lookup(&p, a), -1);
    assert_ok(pool_reserve(&p, &m));
    uint64_t b = pool_alloc(&p, 0);
    assert_int_equal(pool_slot(a), pool_slot(b)); /* the slot is reused ... */
    assert_true(a != b);                          /* ... under a new generation */
    assert_int_equal(pool_lookup(&p, a), -1);
    assert_int_equal(pool_lookup(&p, b), 0);
    pool_release_memory(&p, &m);
}

static void test_slot_retires_instead_of_wrapping_its_generation(void **state)
{
    (void)state;
    rg_mem m = heap();
    pool p;
    pool_init(&p, 1, 4, 0); /* generations 1..4, then the slot retires */
    uint64_t seen[16];
    for (int k = 0; k < 12; k++) {
        assert_ok(pool_reserve(&p, &m));
        seen[k] = pool_alloc(&p, 0);
        for (int j = 0; j < k; j++) assert_true(seen[j] != seen[k]);
        pool_free(&p, seen[k]);
    }
    /* 12 uses at 4 generations per slot: exactly 3 slots used, all old handles stale */
    assert_int_equal(p.slot_count, 3);
    for (int k = 0; k < 12; k++) assert_int_equal(pool_lookup(&p, seen[k]), -1);
    pool_release_memory(&p, &m);
}

static void test_foreign_tag_and_forged_handles_are_rejected(void **state)
{
    (void)state;
    rg_mem m = heap();
    pool p, q;
    pool_init(&p, 7, 0, 0);
    pool_init(&q, 8, 0, 0);
    assert_ok(pool_reserve(&p, &m));
    assert_ok(pool_reserve(&q, &m));
    uint64_t hp = pool_alloc(&p, 0), hq = pool_alloc(&q, 0);
    assert_true(pool_slot(hp) == pool_slot(hq));
    assert_int_equal(pool_lookup(&p, hq), -1);
    assert_int_equal(pool_lookup(&q, hp), -1);
    assert_int_equal(pool_lookup(&p, 0), -1);
    assert_int_equal(pool_lookup(&p, hp + 1), -1);                 /* slot never used */
    assert_int_equal(pool_lookup(&p, hp + (1u << POOL_SLOT_BITS)), -1); /* next generation */
    assert_int_equal(pool_lookup(&p, hp & ~((uint64_t)POOL_MAX_GEN << POOL_SLOT_BITS)), -1); /* gen 0 */
    assert_int_equal(pool_lookup(&p, UINT64_MAX), -1);
    pool_release_memory(&p, &m);
    pool_release_memory(&q, &m);
}

static void test_capacity_limit_is_reported_and_changes_nothing(void **state)
{
    (void)state;
    rg_mem m = heap();
    pool p;
    pool_init(&p, 0, 0, 20);
    for (int32_t i = 0; i < 20; i++) {
        assert_ok(pool_reserve(&p, &m));
        (void)pool_alloc(&p, i);
    }
    assert_status(pool_reserve(&p, &m), RG_ERR_CAPACITY);
    assert_int_equal(p.slot_count, 20);
    assert_int_equal(p.live, 20);
    pool_release_memory(&p, &m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_handle_round_trips_and_is_never_zero),
        cmocka_unit_test(test_freed_handle_is_stale_and_slot_reuse_gets_new_generation),
        cmocka_unit_test(test_slot_retires_instead_of_wrapping_its_generation),
        cmocka_unit_test(test_foreign_tag_and_forged_handles_are_rejected),
        cmocka_unit_test(test_capacity_limit_is_reported_and_changes_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
