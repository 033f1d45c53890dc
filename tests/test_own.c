/* test_own.c: a world knows its own saves again (own.h) by a keyed hash (keyed.h): the hash
 * is the one its definition gives, in any pieces; a save is known byte for byte and no
 * other bytes are; only a world that restores tags its saves; and a restore of a known save
 * skips the checks yet leaves the world exactly as the checked restore does. */
#include "keyed.h"
#include "own.h"
#include "snapshot.h"
#include "state.h"

#include "snapshot_scene.h"

/* ---------------------------------------------------------------- the hash, by definition */

/* a b modulo p by doubling and adding: plainly right, and slow. */
static uint64_t ref_mulmod(uint64_t a, uint64_t b)
{
    uint64_t r = 0;
    for (int bit = 63; bit >= 0; bit--) {
        r = r >= KEYED_P - r ? r - (KEYED_P - r) : r + r;
        if ((b >> bit) & 1) r = r >= KEYED_P - a ? r - (KEYED_P - a) : r + a;
    }
    return r;
}

static uint64_t lcg(uint64_t *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return *s >> 11;
}

static void test_mulmod_is_the_product_modulo_the_prime(void **state)
{
    (void)state;
    static const uint64_t edge[] = { 0, 1, 2, 3, 0xFFFFFFFFull, 0x100000000ull, (1ull << 60), (1ull << 61) - 2,
                                     (1ull << 61) - 3, 0x1FFFFFFF00000000ull, 0x0000000FFFFFFFFFull };
    enum { E = sizeof edge / sizeof edge[0] };
    for (int i = 0; i < E; i++)
        for (int j = 0; j < E; j++) assert_true(keyed_mulmod(edge[i], edge[j]) == ref_mulmod(edge[i], edge[j]));
    uint64_t s = 7;
    for (int k = 0; k < 100000; k++) {
        uint64_t a = lcg(&s) % KEYED_P, b = lcg(&s) % KEYED_P;
        if (keyed_mulmod(a, b) != ref_mulmod(a, b)) fail_msg("%llx * %llx", (unsigned long long)a, (unsigned long long)b);
    }
}

/* keyed.h's definition, word by word: NH per chunk of the zero-padded words, each sum's two
 * halves and then the length into Horner's rule modulo p. */
static void ref_tags(const keyed_key *k, const uint8_t *p, size_t n, uint64_t tag[2])
{
    size_t words = (n + 7) / 8;
    for (int t = 0; t < 2; t++) {
        uint64_t poly = 0;
        for (size_t c = 0; c * KEYED_WORDS < words; c++) {
            uint64_t nh = 0;
            for (size_t i = 0; i < KEYED_WORDS && c * KEYED_WORDS + i < words; i++) {
                uint8_t w8[8] = { 0 };
                size_t at = 8 * (c * KEYED_WORDS + i);
                memcpy(w8, p + at, n - at < 8 ? n - at : 8);
                uint64_t w;
                memcpy(&w, w8, 8);
                uint32_t lo = (uint32_t)w + k->nh[t][2 * i], hi = (uint32_t)(w >> 32) + k->nh[t][2 * i + 1];
                nh += (uint64_t)lo * hi;
            }
            poly = (ref_mulmod(poly, k->r[t]) + (nh & 0xFFFFFFFFu)) % KEYED_P;
            poly = (ref_mulmod(poly, k->r[t]) + (nh >> 32)) % KEYED_P;
        }
        poly = (ref_mulmod(poly, k->r[t]) + ((uint64_t)n & 0xFFFFFFFFu)) % KEYED_P;
        poly = (ref_mulmod(poly, k->r[t]) + ((uint64_t)n >> 32)) % KEYED_P;
        tag[t] = poly;
    }
}

/* The tags of bytes given whole, and in pieces cut at pseudo-random places (1 byte to a few
 * chunks, so that every path of keyed.c, vector and scalar, takes some), are the
 * definition's, at lengths around the word and chunk boundaries. */
static void test_tags_follow_the_definition_in_any_pieces(void **state)
{
    (void)state;
    static keyed_key key;
    keyed_key_init(&key, 0x1234567887654321ull);
    for (int t = 0; t < 2; t++) assert_true(key.r[t] >= 2 && key.r[t] < KEYED_P);
    enum { MAX = 3 * KEYED_CHUNK + 100 };
    uint8_t *p = malloc(MAX);
    assert_non_null(p);
    uint64_t s = 99;
    for (size_t i = 0; i < MAX; i++) p[i] = (uint8_t)lcg(&s);
    static const size_t lengths[] = { 0, 1, 7, 8, 9, 31, 64, 65, KEYED_CHUNK - 1, KEYED_CHUNK, KEYED_CHUNK + 1,
                                      2 * KEYED_CHUNK + 24, 3 * KEYED_CHUNK + 100 };
    for (size_t li = 0; li < sizeof lengths / sizeof lengths[0]; li++) {
        size_t n = lengths[li];
        uint64_t want[2], whole[2], cut[2];
        ref_tags(&key, p, n, want);
        keyed_hasher h;
        keyed_init(&h, &key);
        keyed_bytes(&h, p, n);
        keyed_final(&h, whole);
        assert_memory_equal(whole, want, sizeof want);
        for (int trial = 0; trial < 20; trial++) {
            keyed_init(&h, &key);
            for (size_t at = 0; at < n;) {
                size_t piece = 1 + (size_t)(lcg(&s) % (trial % 2 ? 9 : 2 * KEYED_CHUNK));
                if (piece > n - at) piece = n - at;
                keyed_bytes(&h, p + at, piece);
                at += piece;
            }
            keyed_final(&h, cut);
            assert_memory_equal(cut, want, sizeof want);
        }
    }
    free(p);
}

/* Each vector path the CPU has gives the scalar loop's sums, at every length up to a chunk
 * and at every place in the chunk's key (the sums are taken modulo 2^64 in another order). */
static void test_every_path_gives_the_scalar_sums(void **state)
{
    (void)state;
#if KEYED_VECTOR
    static keyed_key key;
    keyed_key_init(&key, 77);
    uint8_t *p = malloc(KEYED_CHUNK);
    assert_non_null(p);
    uint64_t s = 3;
    for (size_t i = 0; i < KEYED_CHUNK; i++) p[i] = (uint8_t)lcg(&s);
    int paths = 0;
    for (int path = 0; path < 2; path++) {
        if (!(path ? __builtin_cpu_supports("avx512f") : __builtin_cpu_supports("avx2"))) {
            print_message("no %s on this CPU: that path is not run\n", path ? "AVX-512" : "AVX2");
            continue;
        }
        paths++;
        for (size_t at = 0; at < KEYED_WORDS; at += 37)
            for (size_t words = 0; at + words <= KEYED_WORDS; words += 1 + words / 3) {
                uint64_t want[2] = { 11, 22 }, got[2] = { 11, 22 };
                const uint32_t *k0 = key.nh[0] + 2 * at, *k1 = key.nh[1] + 2 * at;
                keyed_nh_scalar(want, p + 8 * at, words, k0, k1);
                if (path)
                    keyed_nh_avx512(got, p + 8 * at, words, k0, k1);
                else
                    keyed_nh_avx2(got, p + 8 * at, words, k0, k1);
                assert_memory_equal(got, want, sizeof want);
            }
    }
    print_message("vector paths run: %d of 2\n", paths);
    free(p);
#else
    skip();
#endif
}

/* Any one bit of three chunks flipped changes both tags.  Per flip each tag stays with
 * chance 2^-32 + n 2^-61 at most (keyed.h), both with about 2^-64: over 98,304 flips a
 * miss is a fault, not chance. */
static void test_every_flipped_bit_changes_both_tags(void **state)
{
    (void)state;
    static keyed_key key;
    keyed_key_init(&key, 42);
    enum { N = 3 * KEYED_CHUNK };
    uint8_t *p = malloc(N);
    assert_non_null(p);
    uint64_t s = 5, base[2], now[2];
    for (size_t i = 0; i < N; i++) p[i] = (uint8_t)lcg(&s);
    keyed_hasher h;
    keyed_init(&h, &key);
    keyed_bytes(&h, p, N);
    keyed_final(&h, base);
    for (size_t i = 0; i < N; i++)
        for (int bit = 0; bit < 8; bit++) {
            p[i] ^= (uint8_t)(1u << bit);
            keyed_init(&h, &key);
            keyed_bytes(&h, p, N);
            keyed_final(&h, now);
            p[i] ^= (uint8_t)(1u << bit);
            if (now[0] == base[0] || now[1] == base[1]) fail_msg("byte %lu bit %d left a tag", (unsigned long)i, bit);
        }
    free(p);
}

/* ---------------------------------------------------------------- worlds */

/* Whether w knows the size bytes at p as one of its own saves (as rg_world_restore asks). */
static int knows(const rg_world *w, const uint8_t *p, size_t size)
{
    return own_knows(w->own, p, size, snap_get64(p + OWN_HEAD));
}

static rg_world *scene_world(scene *s)
{
    rg_world *w;
    assert_ok(rg_world_create(&w));
    build(s, w, RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
    step_n(w, 30, 1.0 / 60);
    return w;
}

/* A restore of the world's own state: from here on its saves are tagged. */
static void arm(rg_world *w)
{
    size_t size;
    void *now = save(w, &size);
    assert_ok(rg_world_restore(w, now, size));
    free(now);
}

/* A world that never restored tags no save; a refused restore does not change that; a
 * restore does, for the next OWN_SAVES saves; then saves go untagged again. */
static void test_only_a_world_that_restores_tags_its_saves(void **state)
{
    (void)state;
    scene s;
    rg_world *w = scene_world(&s);
    size_t asize, size;
    uint8_t *a = save(w, &asize);
    assert_false(knows(w, a, asize));
    uint8_t junk[64] = { 0 };
    assert_status(rg_world_restore(w, junk, sizeof junk), RG_ERR_INVALID_ARGUMENT);
    uint8_t *b = save(w, &size);
    assert_false(knows(w, b, size));
    free(b);
    assert_ok(rg_world_restore(w, a, asize)); /* checked: a was not tagged */
    uint8_t *last = NULL;
    size_t last_size = 0;
    for (int k = 0; k < OWN_SAVES; k++) {
        assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
        free(last);
        last = save(w, &last_size);
        assert_true(knows(w, last, last_size));
    }
    assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
    uint8_t *after = save(w, &size);
    assert_false(knows(w, after, size));
    assert_true(knows(w, last, last_size)); /* still remembered */
    free(after);
    free(last);
    free(a);
    rg_world_destroy(w);
}

/* A known save with any one byte changed is not known (the checksum, compared itself, or a
 * tag, which covers every other byte, differs); nor is it when its checksum alone matches a
 * remembered one (a forger's checksum collision, made here by writing the remembered
 * checksum over); nor in another world, whose key differs; and a save is forgotten after
 * OWN_SAVES saves more. */
static void test_a_save_is_known_byte_for_byte_and_nowhere_else(void **state)
{
    (void)state;
    scene s;
    rg_world *w = scene_world(&s);
    arm(w);
    size_t size;
    uint8_t *b = save(w, &size);
    assert_true(knows(w, b, size));
    uint8_t *c = malloc(size);
    assert_non_null(c);
    memcpy(c, b, size);
    assert_true(knows(w, c, size)); /* the bytes, wherever they lie */
    for (size_t i = 0; i < size; i++) {
        c[i] ^= 0x01;
        if (knows(w, c, size)) fail_msg("byte %lu of %lu flipped, still known", (unsigned long)i, (unsigned long)size);
        c[i] ^= 0x01;
    }
    /* a changed body position, resealed: only the remembered checksum made to match passes
     * the first test, and the tags refuse it */
    c[SNAP_HEADER + 100] ^= 0x10;
    reseal(c, size);
    assert_false(knows(w, c, size));
    int entry = (int)((w->own->next + OWN_SAVES - 1) % OWN_SAVES);
    assert_true(w->own->save[entry].size == size);
    uint64_t kept_sum = w->own->save[entry].sum;
    w->own->save[entry].sum = snap_get64(c + OWN_HEAD);
    assert_false(knows(w, c, size));
    w->own->save[entry].sum = kept_sum;
    /* another world of the same scene, restoring too */
    scene s2;
    rg_world *w2 = scene_world(&s2);
    arm(w2);
    assert_false(knows(w2, b, size));
    /* OWN_SAVES saves of other states, each followed by a restore that keeps the world
     * tagging: b is forgotten */
    for (int k = 0; k < OWN_SAVES; k++) {
        assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
        arm(w);
    }
    assert_false(knows(w, b, size));
    free(c);
    free(b);
    rg_world_destroy(w2);
    rg_world_destroy(w);
}

/* Bytes allocated by the calls made (a restore's scratch among them). */
typedef struct sum_alloc {
    long long bytes;
} sum_alloc;

static void *sum_alloc_fn(void *user, void *ptr, size_t old_size, size_t new_size)
{
    sum_alloc *t = user;
    if (new_size == 0) {
        free(ptr);
        return NULL;
    }
    if (new_size > old_size) t->bytes += (long long)(new_size - old_size);
    return realloc(ptr, new_size);
}

/* For every integrator: a known save restored (the world's own) and the same bytes restored
 * once the world has forgotten them (checked), from the same state: the first takes less
 * scratch (the checks' is not made), and both leave the state byte for byte the one saved,
 * with the same handles and the same run after; and a world restored from those bytes from
 * outside does too. */
static void test_a_known_save_restores_unchecked_as_the_checked_restore_does(void **state)
{
    (void)state;
    enum { N = 90 };
    static uint64_t first[N], own_run[N], checked_run[N], outside_run[N];
    for (int32_t integ = 0; integ < 4; integ++) {
        sum_alloc ta = { 0 };
        rg_world *w;
        assert_ok(rg_world_create_with_allocator(sum_alloc_fn, &ta, &w));
        scene s;
        build(&s, w, integ);
        step_n(w, 40, 1.0 / 60);
        arm(w);
        size_t size, csize;
        uint8_t *b = save(w, &size);
        run(w, N, first);
        assert_ok(rg_body_destroy(w, s.doomed));
        rg_body late;
        assert_ok(rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(0, 9), &late));
        uint8_t *c = save(w, &csize); /* the state both restores start from */
        assert_true(knows(w, b, size) && knows(w, c, csize));
        long long before = ta.bytes;
        assert_ok(rg_world_restore(w, b, size));
        long long own_bytes = ta.bytes - before;
        assert_true(rg_body_is_valid(w, s.doomed));
        assert_false(rg_body_is_valid(w, late));
        uint8_t *again = save(w, &size);
        assert_memory_equal(again, b, size);
        free(again);
        run(w, N, own_run);
        assert_memory_equal(first, own_run, sizeof first);
        /* forget b and c: saves of other states, each restored */
        for (int k = 0; k < OWN_SAVES; k++) {
            assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
            arm(w);
        }
        assert_false(knows(w, b, size) || knows(w, c, csize));
        assert_ok(rg_world_restore(w, c, csize)); /* checked, back to where the first began */
        before = ta.bytes;
        assert_ok(rg_world_restore(w, b, size));
        long long checked_bytes = ta.bytes - before;
        if (!(own_bytes < checked_bytes))
            fail_msg("the own restore allocated %lld bytes, the checked %lld", own_bytes, checked_bytes);
        again = save(w, &size);
        assert_memory_equal(again, b, size);
        free(again);
        run(w, N, checked_run);
        assert_memory_equal(first, checked_run, sizeof first);
        rg_world *w2;
        assert_ok(rg_world_create(&w2));
        assert_ok(rg_world_restore(w2, b, size));
        run(w2, N, outside_run);
        assert_memory_equal(first, outside_run, sizeof first);
        rg_world_destroy(w2);
        free(c);
        free(b);
        rg_world_destroy(w);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mulmod_is_the_product_modulo_the_prime),
        cmocka_unit_test(test_tags_follow_the_definition_in_any_pieces),
        cmocka_unit_test(test_every_path_gives_the_scalar_sums),
        cmocka_unit_test(test_every_flipped_bit_changes_both_tags),
        cmocka_unit_test(test_only_a_world_that_restores_tags_its_saves),
        cmocka_unit_test(test_a_save_is_known_byte_for_byte_and_nowhere_else),
        cmocka_unit_test(test_a_known_save_restores_unchecked_as_the_checked_restore_does),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
