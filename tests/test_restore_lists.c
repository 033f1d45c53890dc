/* test_restore_lists.c: a snapshot whose linked lists are forged with their links kept
 * consistent link by link (every next a member of the same list), resealed, is refused when
 * a list runs round a cycle or leaves a member out: what only the walks from the heads find
 * (src/restore_check.c, restore_check_islands). */
#include "testutil.h"
#include "snapshot.h"
#include "restore_check.h"
#include "snapshot_scene.h"

/* A stack of three boxes on a floor, asleep: one island of three. */
static rg_world *sleeping_stack(void)
{
    rg_world *w = gravity_world(-10);
    floor_of(w);
    for (int i = 0; i < 3; i++) box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5 + i, 0.5, 0.5);
    step_n(w, 240, DT);
    assert_int_equal(rg_world_awake_body_count(w), 0);
    return w;
}

static uint8_t *save_of(rg_world *w, size_t *size)
{
    assert_ok(rg_world_save(w, NULL, 0, size));
    uint8_t *p = malloc(*size);
    assert_non_null(p);
    assert_ok(rg_world_save(w, p, *size, size));
    return p;
}

/* Where island field f of dense body i lies in the snapshot. */
static uint8_t *island_at(const snap_in *in, uint8_t *p, int f, int32_t i)
{
    assert_true(in->l.stride[f] != 0); /* the bodies differ in it */
    return p + in->l.field[f] + in->l.stride[f] * (size_t)i;
}

static uint64_t world_hash(rg_world *w)
{
    uint64_t h;
    assert_ok(rg_world_hash(w, &h));
    return h;
}

/* The island's bodies in list order, as dense indices: order[0] the head. */
static void island_order(const snap_in *in, uint8_t *p, int32_t order[3])
{
    const snap_scalars *s = &in->s;
    assert_int_equal(s->n_moving - s->n_active, 3);
    int32_t head = -1;
    for (int32_t i = s->n_active; i < s->n_moving; i++)
        if ((int32_t)snap_get32(island_at(in, p, SNAP_F_isl_head, i)) == BF_I(in, slot, i) + 1) head = i;
    assert_true(head >= 0);
    order[0] = head;
    for (int k = 1; k < 3; k++) {
        int32_t next = (int32_t)snap_get32(island_at(in, p, SNAP_F_isl_next, order[k - 1]));
        assert_true(next > 0);
        order[k] = rd_i32(in, in->l.bindex, next - 1);
    }
    assert_int_equal((int32_t)snap_get32(island_at(in, p, SNAP_F_isl_next, order[2])), 0);
}

static void test_an_island_forged_into_a_cycle_is_refused(void **state)
{
    (void)state;
    rg_world *w = sleeping_stack();
    size_t size;
    uint8_t *snap = save_of(w, &size), *bad = malloc(size);
    assert_non_null(bad);
    snap_in in;
    memset(&in, 0, sizeof in);
    assert_true(restore_check_header(w, &in, snap, size, 1));
    assert_true(restore_check_scalars(&in));
    int32_t order[3]; /* head a, then b, then c */
    island_order(&in, snap, order);
    uint32_t b_link = (uint32_t)BF_I(&in, slot, order[1]) + 1;
    uint64_t h0 = world_hash(w);
    /* resealed as it is: accepted (the forgeries below differ in the links alone) */
    memcpy(bad, snap, size);
    reseal(bad, size);
    assert_ok(rg_world_restore(w, bad, size));
    /* a -> b -> c -> b ...: a cycle the walk from the head runs into */
    memcpy(bad, snap, size);
    snap_put32(island_at(&in, bad, SNAP_F_isl_next, order[2]), b_link);
    reseal(bad, size);
    assert_status(rg_world_restore(w, bad, size), RG_ERR_INVALID_ARGUMENT);
    assert_true(world_hash(w) == h0);
    /* a alone, and b -> c -> b apart: every link still within the list, but no walk from a
     * head reaches b or c */
    snap_put32(island_at(&in, bad, SNAP_F_isl_next, order[0]), 0);
    reseal(bad, size);
    assert_status(rg_world_restore(w, bad, size), RG_ERR_INVALID_ARGUMENT);
    assert_true(world_hash(w) == h0);
    /* and the world steps on as before */
    step_n(w, 10, DT);
    assert_int_equal(rg_world_awake_body_count(w), 0);
    free(bad);
    free(snap);
    rg_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_an_island_forged_into_a_cycle_is_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
