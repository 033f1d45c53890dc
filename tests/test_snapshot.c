/* test_snapshot.c: save, restore and hash: resimulation to the same bytes, clones, the
 * rollback loop's memory, corrupt, truncated and forged snapshots. */
#include "testutil.h"

#include "snapshot.h"

#include "snapshot_scene.h"

/* Save at step 100, run on to 260; restore and run again; restore into a fresh world and
 * run; through a file.  Every step gives the same hash and events, and the end the same
 * positions and velocities, for every integrator. */
static void test_resimulation_after_restore_gives_identical_bytes(void **state)
{
    (void)state;
    enum { K = 100, N = 160 };
    static uint64_t first[N], again[N], fresh[N], filed[N];
    for (int32_t integ = 0; integ < 4; integ++) {
        rg_world *w;
        assert_ok(rg_world_create(&w));
        scene s;
        build(&s, w, integ);
        for (int k = 0; k < K; k++) {
            if (k == 40) assert_ok(rg_body_apply_impulse(w, s.b[30], v2(3, 2)));
            assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
        }
        size_t size;
        void *snap = save(w, &size);
        uint64_t h0 = hash_of(w);
        run(w, N, first);
        rg_vec2 p_end = pos_of(w, s.b[40]), v_end = vel_of(w, s.b[40]);
        /* back: the same hash at once, the same run after */
        assert_ok(rg_world_restore(w, snap, size));
        assert_true(hash_of(w) == h0);
        run(w, N, again);
        assert_memory_equal(first, again, sizeof first);
        rg_vec2 p2 = pos_of(w, s.b[40]), v2_ = vel_of(w, s.b[40]);
        assert_memory_equal(&p_end, &p2, sizeof p2);
        assert_memory_equal(&v_end, &v2_, sizeof v2_);
        /* into a fresh world: it answers the saving world's handles */
        rg_world *w2;
        assert_ok(rg_world_create(&w2));
        assert_ok(rg_world_restore(w2, snap, size));
        assert_true(hash_of(w2) == h0);
        assert_true(rg_body_is_valid(w2, s.b[40]));
        run(w2, N, fresh);
        assert_memory_equal(first, fresh, sizeof first);
        /* through a file */
        FILE *f = tmpfile();
        assert_non_null(f);
        assert_true(fwrite(snap, 1, size, f) == size);
        rewind(f);
        void *back = malloc(size);
        assert_true(fread(back, 1, size, f) == size);
        fclose(f);
        rg_world *w3;
        assert_ok(rg_world_create(&w3));
        assert_ok(rg_world_restore(w3, back, size));
        run(w3, N, filed);
        assert_memory_equal(first, filed, sizeof first);
        /* something happened in the run: sleep, events, bullets stopped by the floor */
        assert_true(rg_world_awake_body_count(w3) < s.n - 5 || integ != RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
        free(back);
        free(snap);
        rg_world_destroy(w3);
        rg_world_destroy(w2);
        rg_world_destroy(w);
    }
}

/* Equal states hash alike in different worlds (other handle tags); a change of one bit of
 * one body's state changes the hash. */
/* What a snapshot leaves out, a restore derives: each body's inverse mass and the flags its
 * settings give it (drag, surface friction, speed limits, gravity scale), as the setters
 * make them.  The integrator's fast paths read the flags (src/integrator.c), so a body
 * restored without its flag moves as one without the setting: a restored world stepped
 * beside the saving one would part from it.  Each setting on a whole block of bodies, and
 * no applied force, so that each block may take a fast path. */
static void test_restore_derives_what_each_setting_gives_a_body(void **state)
{
    (void)state;
    enum { KINDS = 9, PER = 16, N = KINDS * PER };
    rg_world *w = gravity_world(-10), *w2;
    assert_ok(rg_world_set_sleeping(w, 0));
    rg_body b[N];
    for (int i = 0; i < N; i++) {
        b[i] = circle_body(w, RG_BODY_DYNAMIC, 0.5 + i % 7, 3.0 * i, 0, 0.5);
        assert_ok(rg_body_set_velocity(w, b[i], v2(4, 9)));
        switch (i / PER) {
        case 1: assert_ok(rg_body_set_drag(w, b[i], 0.5f, 0)); break;
        case 2: assert_ok(rg_body_set_drag(w, b[i], 0, 0.2f)); break;
        case 3: assert_ok(rg_body_set_surface_friction(w, b[i], 0.3f, 5)); break;
        case 4: assert_ok(rg_body_set_speed_limits(w, b[i], 12, 0)); break; /* held at rest */
        case 5: assert_ok(rg_body_set_speed_limits(w, b[i], 0, 2)); break;  /* falls at 2 m/s */
        case 6: assert_ok(rg_body_set_gravity_scale(w, b[i], 0.25f)); break;
        case 7: assert_ok(rg_body_set_gravity_scale(w, b[i], -1)); break;
        case 8: assert_ok(rg_body_set_mass(w, b[i], 0.125f)); break;
        default: break;
        }
    }
    step_n(w, 5, DT);
    size_t size;
    void *snap = save(w, &size);
    assert_ok(rg_world_create(&w2));
    assert_ok(rg_world_restore(w2, snap, size));
    step_n(w, 60, DT);
    step_n(w2, 60, DT);
    for (int i = 0; i < N; i++) {
        rg_vec2 p = pos_of(w, b[i]), p2 = pos_of(w2, b[i]), v = vel_of(w, b[i]), v2_ = vel_of(w2, b[i]);
        assert_memory_equal(&p, &p2, sizeof p);
        assert_memory_equal(&v, &v2_, sizeof v);
    }
    /* and each setting but the mass (which free flight does not feel) made its bodies move
     * otherwise than the plain ones */
    for (int i = PER; i < N - PER; i++) assert_true(VY(w, b[i]) != VY(w, b[0]) || VX(w, b[i]) != VX(w, b[0]));
    free(snap);
    rg_world_destroy(w2);
    rg_world_destroy(w);
}

static void test_equal_states_give_equal_hashes(void **state)
{
    (void)state;
    rg_world *a, *b;
    assert_ok(rg_world_create(&a));
    assert_ok(rg_world_create(&b));
    scene sa, sb;
    build(&sa, a, RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
    build(&sb, b, RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
    assert_true(sa.b[0] != sb.b[0]); /* different tags */
    step_n(a, 50, 1.0 / 60);
    step_n(b, 50, 1.0 / 60);
    assert_true(hash_of(a) == hash_of(b));
    rg_vec2 v = vel_of(b, sb.b[30]);
    rg_real bumped = v.x;
    uint32_t bits;
    memcpy(&bits, &bumped, sizeof bits < sizeof bumped ? sizeof bits : sizeof bumped);
    bits ^= 1u;
    memcpy(&bumped, &bits, sizeof bits < sizeof bumped ? sizeof bits : sizeof bumped);
    assert_ok(rg_body_set_velocity(b, sb.b[30], v2((double)bumped, (double)v.y)));
    assert_true(hash_of(a) != hash_of(b));
    rg_world_destroy(a);
    rg_world_destroy(b);
}

static void test_save_reports_its_size_and_respects_capacity(void **state)
{
    (void)state;
    rg_world *w;
    assert_ok(rg_world_create(&w));
    scene s;
    build(&s, w, RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
    step_n(w, 10, 1.0 / 60);
    size_t size = 0, got = 0;
    assert_ok(rg_world_save(w, NULL, 0, &size));
    assert_true(size > SNAP_HEADER && size % 8 == 0);
    uint8_t *buf = malloc(size + 16);
    memset(buf, 0xA5, size + 16);
    assert_status(rg_world_save(w, buf, size - 1, &got), RG_ERR_CAPACITY);
    assert_true(got == size);
    for (size_t k = 0; k < size + 16; k++) assert_int_equal(buf[k], 0xA5); /* nothing written */
    assert_ok(rg_world_save(w, buf, size + 16, &got));
    assert_true(got == size && buf[size] == 0xA5);
    assert_status(rg_world_save(NULL, buf, size, &got), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_save(w, buf, size, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_save(w, NULL, 10, &got), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_restore(NULL, buf, size), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_restore(w, NULL, size), RG_ERR_INVALID_ARGUMENT);
    uint64_t h;
    assert_status(rg_world_hash(NULL, &h), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_hash(w, NULL), RG_ERR_INVALID_ARGUMENT);
    /* an empty world saves, restores and hashes too */
    rg_world *e;
    assert_ok(rg_world_create(&e));
    size_t esize;
    void *es = save(e, &esize);
    assert_ok(rg_world_restore(w, es, esize));
    assert_int_equal(rg_world_body_count(w), 0);
    assert_true(hash_of(w) == hash_of(e));
    assert_false(rg_body_is_valid(w, s.b[0]));
    free(es);
    free(buf);
    rg_world_destroy(e);
    rg_world_destroy(w);
}

/* A flip of any byte, any truncation, any extension and random bytes: invalid, and the
 * world keeps its state (hash) and goes on as before. */
static void test_corrupt_truncated_and_random_snapshots_are_rejected(void **state)
{
    (void)state;
    rg_world *w, *src;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_create(&src));
    scene s, t;
    build(&s, w, RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
    build(&t, src, RG_INTEGRATOR_RK4);
    step_n(w, 30, 1.0 / 60);
    step_n(src, 60, 1.0 / 60);
    size_t size;
    uint8_t *snap = save(src, &size);
    uint64_t h0 = hash_of(w);
    uint8_t *bad = malloc(size + 64);
    for (size_t k = 0; k < size; k++) {
        memcpy(bad, snap, size);
        bad[k] ^= (uint8_t)(1u << (k % 8));
        assert_status(rg_world_restore(w, bad, size), RG_ERR_INVALID_ARGUMENT);
    }
    for (size_t n = 0; n < size; n += (n < 256 ? 1 : 37)) assert_status(rg_world_restore(w, snap, n), RG_ERR_INVALID_ARGUMENT);
    memcpy(bad, snap, size);
    memset(bad + size, 0, 64);
    assert_status(rg_world_restore(w, bad, size + 8), RG_ERR_INVALID_ARGUMENT);
    uint64_t x = 0x9E3779B97F4A7C15ull;
    for (int r = 0; r < 200; r++) {
        for (size_t k = 0; k < size; k++) {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            bad[k] = (uint8_t)x;
        }
        if (r % 2) memcpy(bad, snap, SNAP_HEADER); /* a good header over garbage */
        assert_status(rg_world_restore(w, bad, size), RG_ERR_INVALID_ARGUMENT);
    }
    assert_true(hash_of(w) == h0);
    /* and the world goes on exactly as an untouched twin */
    rg_world *twin;
    assert_ok(rg_world_create(&twin));
    scene u;
    build(&u, twin, RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
    step_n(twin, 30, 1.0 / 60);
    step_n(w, 30, 1.0 / 60);
    step_n(twin, 30, 1.0 / 60);
    assert_true(hash_of(w) == hash_of(twin));
    free(bad);
    free(snap);
    rg_world_destroy(twin);
    rg_world_destroy(src);
    rg_world_destroy(w);
}

/* Forged (snapshot_scene.h: forge_words): each forgery breaks one invariant the state
 * relies on; each is refused, or accepted only as a state that still checks out (then
 * stepped safely). */
typedef struct forgery {
    rg_world *w;
    const uint8_t *snap;
    size_t size;
    int refused, accepted;
} forgery;

static void restore_forged(uint8_t *bad, size_t size, void *context)
{
    forgery *f = context;
    rg_status st = rg_world_restore(f->w, bad, size);
    assert_true(st == RG_OK || st == RG_ERR_INVALID_ARGUMENT);
    if (st == RG_ERR_INVALID_ARGUMENT) {
        f->refused++;
        return;
    }
    f->accepted++;
    /* an accepted forgery is a valid state: stepping it must be safe */
    step_n(f->w, 2, 1.0 / 60);
    assert_ok(rg_world_restore(f->w, f->snap, f->size));
}

static void test_forged_snapshots_with_a_valid_checksum_are_rejected(void **state)
{
    (void)state;
    rg_world *w;
    assert_ok(rg_world_create(&w));
    scene s;
    build(&s, w, RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
    step_n(w, 40, 1.0 / 60);
    size_t size;
    uint8_t *snap = save(w, &size);
    uint64_t h0 = hash_of(w);
    uint8_t *bad = malloc(size);
    memcpy(bad, snap, size);
    reseal(bad, size);
    assert_ok(rg_world_restore(w, bad, size)); /* resealing alone forges nothing */
    forgery f = { w, snap, size, 0, 0 };
    forge_words(snap, size, bad, restore_forged, &f);
    printf("  forged words: %d refused, %d accepted as valid states\n", f.refused, f.accepted);
    assert_true(f.refused > 0);
    assert_ok(rg_world_restore(w, snap, size));
    assert_true(hash_of(w) == h0);
    free(bad);
    free(snap);
    rg_world_destroy(w);
}

/* A rollback loop: 10,000 times restore and step a frame; memory in use stays what it was
 * after the first, bodies created after the save are gone, destroyed ones live again. */
static void test_ten_thousand_rollbacks_hold_memory_and_handles(void **state)
{
    (void)state;
    test_alloc ta;
    scene s;
    rg_world *w = counted_scene(&s, &ta);
    size_t size;
    void *snap = save(w, &size);
    uint64_t h0 = hash_of(w);
    assert_ok(rg_body_destroy(w, s.doomed));
    rg_body late;
    assert_ok(rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(0, 9), &late));
    assert_ok(rg_world_restore(w, snap, size));
    assert_true(rg_body_is_valid(w, s.doomed));
    assert_false(rg_body_is_valid(w, late));
    step_n(w, 1, 1.0 / 60);
    long long bytes = ta.live_bytes;
    long blocks = ta.live_blocks;
    for (int k = 0; k < 10000; k++) {
        assert_ok(rg_world_restore(w, snap, size));
        if (k % 1000 == 0) assert_true(hash_of(w) == h0);
        step_n(w, 1, 1.0 / 60);
        assert_memory_held(&ta, bytes, blocks, k);
    }
    /* a new body after a restore never takes a handle that was live in the snapshot's
     * future: handles of the saving world's bodies still name them */
    assert_ok(rg_world_restore(w, snap, size));
    rg_body again;
    assert_ok(rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(0, 9), &again));
    for (int i = 0; i < s.n; i++) assert_true(again != s.b[i]);
    free(snap);
    rg_world_destroy(w);
    assert_int_equal(ta.live_blocks, 0);
}

/* Restoring with too little memory: RG_ERR_OUT_OF_MEMORY, the world unchanged. */
static void test_out_of_memory_on_restore_changes_nothing(void **state)
{
    (void)state;
    rg_world *big;
    assert_ok(rg_world_create(&big));
    scene s;
    build(&s, big, RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
    step_n(big, 20, 1.0 / 60);
    size_t size;
    void *snap = save(big, &size);
    for (long fail = 1; fail < 40; fail++) {
        test_alloc ta;
        memset(&ta, 0, sizeof ta);
        rg_world *w;
        assert_ok(rg_world_create_with_allocator(test_alloc_fn, &ta, &w));
        rg_body b = make_body(w, 1, 1, 1);
        uint64_t h0 = hash_of(w);
        ta.fail_at = ta.calls + fail;
        rg_status st = rg_world_restore(w, snap, size);
        ta.fail_at = 0;
        if (st == RG_OK) {
            assert_true(hash_of(w) == hash_of(big));
        } else {
            assert_int_equal(st, RG_ERR_OUT_OF_MEMORY);
            assert_true(hash_of(w) == h0 && rg_body_is_valid(w, b));
        }
        rg_world_destroy(w);
        assert_int_equal(ta.live_blocks, 0);
    }
    free(snap);
    rg_world_destroy(big);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_resimulation_after_restore_gives_identical_bytes),
        cmocka_unit_test(test_restore_derives_what_each_setting_gives_a_body),
        cmocka_unit_test(test_equal_states_give_equal_hashes),
        cmocka_unit_test(test_save_reports_its_size_and_respects_capacity),
        cmocka_unit_test(test_corrupt_truncated_and_random_snapshots_are_rejected),
        cmocka_unit_test(test_forged_snapshots_with_a_valid_checksum_are_rejected),
        cmocka_unit_test(test_ten_thousand_rollbacks_hold_memory_and_handles),
        cmocka_unit_test(test_out_of_memory_on_restore_changes_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
