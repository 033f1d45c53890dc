/* snapshot_scene.h: the scene the snapshot tests (test_snapshot.c, test_slots.c) save and
 * restore, and what they read of a world. */
#ifndef RG_SNAPSHOT_SCENE_H
#define RG_SNAPSHOT_SCENE_H

#include "testutil.h"

typedef struct scene {
    rg_world *w;
    rg_body b[128];
    int n;
    rg_body plat, coin, doomed;
} scene;

static inline rg_body add(scene *s, int32_t type, double m, double x, double y)
{
    rg_body h;
    assert_ok(rg_body_create(s->w, type, (rg_real)m, v2(x, y), &h));
    s->b[s->n++] = h;
    return h;
}

/* A pile on a floor between walls, a kinematic platform, a sensor, springs, drag, bullets
 * fast enough for continuous collision; sleeping on. */
static inline void build(scene *s, rg_world *w, int32_t integrator)
{
    s->w = w;
    s->n = 0;
    assert_ok(rg_world_set_gravity(w, v2(0, -9.81)));
    assert_ok(rg_world_set_integrator(w, integrator));
    rg_body floor = add(s, RG_BODY_STATIC, 0, 0, -0.5);
    assert_ok(rg_body_set_aabb(w, floor, 10, 0.5));
    for (int side = -1; side <= 1; side += 2) {
        rg_body wall = add(s, RG_BODY_STATIC, 0, side * 10.5, 5);
        assert_ok(rg_body_set_aabb(w, wall, 0.5, 6));
    }
    s->plat = add(s, RG_BODY_KINEMATIC, 0, -5, 3);
    assert_ok(rg_body_set_aabb(w, s->plat, 1.5, 0.2));
    assert_ok(rg_body_set_velocity(w, s->plat, v2(1, 0)));
    s->coin = add(s, RG_BODY_STATIC, 0, 3, 1);
    assert_ok(rg_body_set_circle(w, s->coin, 0.5));
    assert_ok(rg_body_set_sensor(w, s->coin, 1));
    for (int i = 0; i < 60; i++) {
        rg_body b = add(s, RG_BODY_DYNAMIC, 0.5 + 0.2 * (i % 4), -6 + (i % 10) * 1.2 + 0.01 * (i % 3),
                        4 + (i / 10) * 1.2);
        if (i % 3)
            assert_ok(rg_body_set_circle(w, b, 0.4f));
        else
            assert_ok(rg_body_set_aabb(w, b, 0.4f, 0.35f));
        if (i % 5 == 0) assert_ok(rg_body_set_drag(w, b, 0.1f, 0.05f));
        if (i % 7 == 0) assert_ok(rg_body_set_restitution(w, b, 0.5f));
        if (i > 0 && i % 9 == 0) {
            uint64_t sp;
            assert_ok(rg_spring_create(w, b, s->b[s->n - 2], v2(0, 0), 1.2f, 30, 0.4f, &sp));
        }
    }
    for (int i = 0; i < 4; i++) {
        rg_body bullet = add(s, RG_BODY_DYNAMIC, 0.1, -8 + i, 8);
        assert_ok(rg_body_set_circle(w, bullet, 0.05f));
        assert_ok(rg_body_set_velocity(w, bullet, v2(i % 2 ? 120 : -90, -150)));
    }
    s->doomed = s->b[20];
}

static inline uint64_t hash_of(rg_world *w)
{
    uint64_t h = 0;
    assert_ok(rg_world_hash(w, &h));
    return h;
}

/* The step trace: every step's hash and event count. */
static inline void run(rg_world *w, int steps, uint64_t *trace)
{
    for (int k = 0; k < steps; k++) {
        assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
        trace[k] = hash_of(w) ^ (uint64_t)rg_world_get_contact_events(w, NULL, 0);
    }
}

static inline void *save(rg_world *w, size_t *size)
{
    assert_ok(rg_world_save(w, NULL, 0, size));
    void *buf = malloc(*size);
    assert_non_null(buf);
    size_t again = 0;
    assert_ok(rg_world_save(w, buf, *size, &again));
    assert_true(again == *size);
    return buf;
}

/* Forged: the checksum made right after changing what it covers (needs snapshot.h). */
#ifdef RG_SNAPSHOT_H
static inline void reseal(uint8_t *p, size_t size) { snap_put64(p + 24, snap_hash(p + SNAP_HEADER, size - SNAP_HEADER)); }

/* Every 4-byte word of snap set to a few hostile values in turn (those it does not hold
 * already), resealed, in bad (size bytes), each given to forged. */
static inline void forge_words(const uint8_t *snap, size_t size, uint8_t *bad, void (*forged)(uint8_t *, size_t, void *),
                               void *context)
{
    static const uint32_t hostile[] = { 0xFFFFFFFFu, 0x7FFFFFFFu, 0x80000000u, 0x7FC00000u, 0x7F800000u, 0, 1, 3 };
    for (size_t at = SNAP_HEADER; at + 4 <= size; at += 4) {
        for (size_t v = 0; v < sizeof hostile / sizeof hostile[0]; v++) {
            memcpy(bad, snap, size);
            if (snap_get32(bad + at) == hostile[v]) continue;
            snap_put32(bad + at, hostile[v]);
            reseal(bad, size);
            forged(bad, size, context);
        }
    }
}
#endif

/* The scene in a world whose memory ta counts, 30 steps on: where the rollback loops start. */
static inline rg_world *counted_scene(scene *s, test_alloc *ta)
{
    rg_world *w;
    memset(ta, 0, sizeof *ta);
    assert_ok(rg_world_create_with_allocator(test_alloc_fn, ta, &w));
    build(s, w, RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
    step_n(w, 30, 1.0 / 60);
    return w;
}

/* Rollback k of a loop holds the memory it started with. */
static inline void assert_memory_held(const test_alloc *ta, long long bytes, long blocks, int k)
{
    if (ta->live_bytes != bytes || ta->live_blocks != blocks)
        fail_msg("rollback %d: %lld bytes in %ld blocks, was %lld in %ld", k, ta->live_bytes, ta->live_blocks, bytes,
                 blocks);
}

#endif
