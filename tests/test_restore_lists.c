/* test_restore_lists.c: a snapshot whose linked lists are forged with their links kept
 * consistent link by link (every next a member of the same list that links back), resealed,
 * is refused when a list runs round a cycle or leaves a member out: what no check of a link
 * where it lies finds (restore_acyclic, and the counts of links and heads: the islands in
 * src/restore_check.c, each body's contacts, the bucket chains and the level lists in
 * src/restore_links.c). */
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

/* The world's snapshot, read where it lies (in), and a buffer of its size for forgeries. */
static uint8_t *saved_and_read(rg_world *w, size_t *size, uint8_t **bad, snap_in *in)
{
    uint8_t *snap = save_of(w, size);
    *bad = malloc(*size);
    assert_non_null(*bad);
    memset(in, 0, sizeof *in);
    assert_true(restore_check_header(w, in, snap, *size, 1));
    assert_true(restore_check_scalars(in));
    return snap;
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

static void test_an_island_forged_into_a_cycle_or_leaving_a_body_out_is_refused(void **state)
{
    (void)state;
    rg_world *w = sleeping_stack();
    size_t size;
    snap_in in;
    uint8_t *bad, *snap = saved_and_read(w, &size, &bad, &in);
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
    /* a -> c and b -> c: b linked from nothing, c from two (as many links as bodies that
     * head no list, and no cycle); then b -> nothing as well (no body linked from two) */
    memcpy(bad, snap, size);
    snap_put32(island_at(&in, bad, SNAP_F_isl_next, order[0]), (uint32_t)BF_I(&in, slot, order[2]) + 1);
    for (int way = 0; way < 2; way++) {
        if (way == 1) snap_put32(island_at(&in, bad, SNAP_F_isl_next, order[1]), 0);
        reseal(bad, size);
        assert_status(rg_world_restore(w, bad, size), RG_ERR_INVALID_ARGUMENT);
        assert_true(world_hash(w) == h0);
    }
    /* c -> a -> b: a link that leads to the head (c heads the chain, but not the list) */
    memcpy(bad, snap, size);
    snap_put32(island_at(&in, bad, SNAP_F_isl_next, order[1]), 0);
    snap_put32(island_at(&in, bad, SNAP_F_isl_next, order[2]), (uint32_t)BF_I(&in, slot, order[0]) + 1);
    reseal(bad, size);
    assert_status(rg_world_restore(w, bad, size), RG_ERR_INVALID_ARGUMENT);
    assert_true(world_hash(w) == h0);
    /* c names b, which heads nothing, as its head; then a, b and c all name b */
    memcpy(bad, snap, size);
    for (int way = 0; way < 2; way++) {
        for (int k = way ? 0 : 2; k < 3; k++)
            snap_put32(island_at(&in, bad, SNAP_F_isl_head, order[k]), b_link);
        reseal(bad, size);
        assert_status(rg_world_restore(w, bad, size), RG_ERR_INVALID_ARGUMENT);
        assert_true(world_hash(w) == h0);
    }
    /* and the world steps on as before */
    step_n(w, 10, DT);
    assert_int_equal(rg_world_awake_body_count(w), 0);
    free(bad);
    free(snap);
    rg_world_destroy(w);
}

/* ---- the doubly linked lists: a body's contacts, a bucket chain, a level list */

/* A list of a snapshot: where node k's next and prev links lie (as the link values, which
 * name the nodes: contact ids, or member slots). */
typedef struct dlist {
    int32_t n;
    int32_t value[64];   /* what a link to node k holds */
    size_t next[64], prev[64]; /* offsets in the snapshot */
} dlist;

/* The contact record with id `id`, as an offset. */
static size_t contact_at(const snap_in *in, int32_t id)
{
    for (int32_t k = 0; k < in->s.clive; k++) {
        const uint8_t *q = rec(in, in->l.contacts, SNAP_CONTACT, k);
        if ((int32_t)snap_get32(q) == id) return (size_t)(q - in->p);
    }
    fail_msg("no contact %d", id);
    return 0;
}

/* Dense body i's contacts in list order (record: id, sa, sb, na, pa, nb, pb, flags). */
static void contact_list(const snap_in *in, int32_t i, dlist *d)
{
    int32_t slot = BF_I(in, slot, i), id = BF_I(in, chead, i) - 1;
    for (d->n = 0; id >= 0 && d->n < 64; d->n++) {
        size_t at = contact_at(in, id);
        int side = (int32_t)snap_get32(in->p + at + 4) == slot ? 0 : 1;
        d->value[d->n] = id;
        d->next[d->n] = at + SNAP_CONTACT_LINKS + 8 + 8 * (size_t)side; /* after sa, sb: na, pa, nb, pb */
        d->prev[d->n] = d->next[d->n] + 4;
        id = (int32_t)snap_get32(in->p + d->next[d->n]);
    }
}

/* The member list (level 0: bucket chain, 1: level list) that member k heads. */
static void member_list(const snap_in *in, int32_t k, int level, dlist *d)
{
    size_t links = SNAP_MEMBER_LINKS + 8 * (size_t)level;
    for (d->n = 0; k >= 0 && d->n < 64; d->n++) {
        size_t at = (size_t)(rec(in, in->l.members, SNAP_MEMBER, k) - in->p);
        d->value[d->n] = (int32_t)snap_get32(in->p + at);
        d->next[d->n] = at + links;
        d->prev[d->n] = at + links + 4;
        int32_t slot = (int32_t)snap_get32(in->p + d->next[d->n]);
        k = -1;
        for (int32_t m = 0; slot >= 0 && m < in->s.members; m++)
            if ((int32_t)snap_get32(rec(in, in->l.members, SNAP_MEMBER, m)) == slot) k = m;
    }
}

/* The longest list of a kind: 0 a body's contacts, 1 a bucket chain, 2 a level list. */
static void longest_list(const snap_in *in, int kind, dlist *best)
{
    dlist d;
    best->n = 0;
    int32_t n = kind == 0 ? in->s.count : in->s.members;
    for (int32_t k = 0; k < n; k++) {
        if (kind == 0) {
            contact_list(in, k, &d);
        } else {
            const uint8_t *q = rec(in, in->l.members, SNAP_MEMBER, k) + SNAP_MEMBER_LINKS + 8 * (size_t)(kind - 1);
            if ((int32_t)snap_get32(q + 4) != -1 || (int32_t)snap_get32(q) < -1) continue; /* not a head */
            member_list(in, k, kind - 1, &d);
        }
        if (d.n > best->n) *best = d;
    }
}

/* Forges list d (at least 3 nodes) in bad, each link consistent with the next's way back:
 * way 0 takes nodes 1 and 2 out into a cycle of their own (1 -> 2 -> 1), way 1 takes node 1
 * out into a cycle of one (1 -> 1), way 2 takes node 1 out as a list of one that no link
 * leads to and no head starts (its prev still the head's); the list goes on without them. */
static void forge_list(const dlist *d, uint8_t *bad, int way)
{
    int32_t out = way == 0 ? 2 : 1, after = 1 + out; /* the node the head links to now */
    snap_put32(bad + d->next[0], (uint32_t)(after < d->n ? d->value[after] : -1));
    if (after < d->n) snap_put32(bad + d->prev[after], (uint32_t)d->value[0]);
    if (way == 2) {
        snap_put32(bad + d->next[1], (uint32_t)-1);
        return;
    }
    snap_put32(bad + d->next[out], (uint32_t)d->value[1]); /* node 1 .. out, round */
    snap_put32(bad + d->prev[1], (uint32_t)d->value[out]);
}

/* Three boxes resting on a floor (the floor's list holds three contacts), three static
 * boxes in one place (a bucket chain of three), all of one size but the floor (a level list
 * of six). */
static rg_world *crowded(void)
{
    rg_world *w = gravity_world(-10);
    floor_of(w);
    for (int i = 0; i < 3; i++) box_body(w, RG_BODY_DYNAMIC, 1, 2.0 * i, 0.5, 0.5, 0.5);
    for (int i = 0; i < 3; i++) box_body(w, RG_BODY_STATIC, 0, 20, 5, 0.5, 0.5);
    step_n(w, 30, DT);
    return w;
}

static void test_contact_and_broadphase_lists_forged_into_cycles_or_leaving_a_node_out_are_refused(void **state)
{
    (void)state;
    rg_world *w = crowded();
    size_t size;
    snap_in in;
    uint8_t *bad, *snap = saved_and_read(w, &size, &bad, &in);
    uint64_t h0 = world_hash(w);
    memcpy(bad, snap, size);
    reseal(bad, size);
    assert_ok(rg_world_restore(w, bad, size));
    for (int kind = 0; kind < 3; kind++) { /* a body's contacts, a chain, a level list */
        dlist d;
        longest_list(&in, kind, &d);
        assert_true(d.n >= 3);
        for (int way = 0; way < 3; way++) {
            memcpy(bad, snap, size);
            forge_list(&d, bad, way);
            reseal(bad, size);
            if (rg_world_restore(w, bad, size) != RG_ERR_INVALID_ARGUMENT)
                fail_msg("list kind %d of %d nodes, forged way %d: accepted", kind, d.n, way);
            assert_true(world_hash(w) == h0);
        }
    }
    step_n(w, 10, DT); /* and the world steps on as before */
    free(bad);
    free(snap);
    rg_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_an_island_forged_into_a_cycle_or_leaving_a_body_out_is_refused),
        cmocka_unit_test(test_contact_and_broadphase_lists_forged_into_cycles_or_leaving_a_node_out_are_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
