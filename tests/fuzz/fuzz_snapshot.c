/* fuzz_snapshot.c: libFuzzer harness for the snapshot reader, rg_world_restore.
 *
 * The input is a mode byte and a snapshot.  Unless the mode says otherwise the harness first
 * makes the checksum (bytes 24 to 31) right for the bytes the fuzzer made, so that the reader's
 * structure checks are what is fuzzed, not the checksum (mode & 3 == 0 keeps the bytes as they
 * are); mode & 4 keeps the size field (bytes 16 to 23) as it is, else it is set to the input's
 * size; mode & 8 gives the world an allocator that fails from the (mode >> 4)-th call of the
 * restore.  The snapshot goes to rg_world_restore on a world that holds a scene (bodies, a
 * spring, contacts, events), and then:
 *   - refused: the status is RG_ERR_INVALID_ARGUMENT (or RG_ERR_OUT_OF_MEMORY when its
 *     allocator fails), rg_world_last_error names rg_world_restore and the reason, and the
 *     world's hash and a save of it are what they were, byte for byte;
 *   - accepted: the error is cleared, a fresh world accepts the same bytes and hashes alike,
 *     the world's own save restores into a fresh world that hashes alike and saves the same
 *     bytes, and the restored state steps safely: a few steps in every integrator (with the
 *     queries and the debug draw after each) leave every coordinate the draw shows finite, and
 *     the same steps with a task system (the shuffler of tests/shuffler.h) hash alike;
 *   - either way (the allocator not failing), a fresh world with the shuffler as its task
 *     system decides alike, with the same reason, and an accepted state hashes alike.
 * Any sanitizer report on the way is a finding too.  The seeds are snapshots of varied scenes
 * written by snapshot_seeds.c (make fuzz runs it). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_alloc.h"
#include "rigid.h"
#include "shuffler.h"
#include "snapshot.h"

#define FAIL(...)                                      \
    do {                                               \
        fprintf(stderr, "fuzz_snapshot: violation: "); \
        fprintf(stderr, __VA_ARGS__);                  \
        fputc('\n', stderr);                           \
        abort();                                       \
    } while (0)

/* Worlds with more bodies step less (an accepted snapshot may hold a thousand bodies in one
 * place, whose pairs are a million): every integrator up to STEP_ALL, one step up to STEP_ONE. */
#define STEP_ALL 128
#define STEP_ONE 1024
#define STEPS    3

typedef struct buf {
    unsigned char *p;
    size_t n;
} buf;

static rg_vec2 vec(double x, double y)
{
    rg_vec2 v;
    v.x = (rg_real)x;
    v.y = (rg_real)y;
    return v;
}

static buf save(const rg_world *w)
{
    buf b = { NULL, 0 };
    if (rg_world_save(w, NULL, 0, &b.n) != RG_OK) FAIL("save: no size");
    b.p = (unsigned char *)malloc(b.n);
    if (b.p == NULL) abort();
    if (rg_world_save(w, b.p, b.n, &b.n) != RG_OK) FAIL("save into its own size");
    return b;
}

static uint64_t hash(const rg_world *w)
{
    uint64_t h = 0;
    if (rg_world_hash(w, &h) != RG_OK) FAIL("hash failed");
    return h;
}

/* The world the snapshot is given to: a pile on a floor, a spring, a sensor, 20 steps. */
static void scene(rg_world *w)
{
    rg_body b, prev = 0;
    uint64_t s;
    (void)rg_world_set_gravity(w, vec(0, -9.81));
    if (rg_body_create(w, RG_BODY_STATIC, 0, vec(0, -0.5), &b) == RG_OK) (void)rg_body_set_aabb(w, b, 5, 0.5);
    if (rg_body_create(w, RG_BODY_STATIC, 0, vec(2, 0.5), &b) == RG_OK) {
        (void)rg_body_set_circle(w, b, 0.5);
        (void)rg_body_set_sensor(w, b, 1);
    }
    for (int i = 0; i < 6; i++) {
        if (rg_body_create(w, RG_BODY_DYNAMIC, 1, vec(-1 + (i % 3) * 0.9, 0.4 + (i / 3) * 0.9), &b) != RG_OK) continue;
        if (i % 2) (void)rg_body_set_circle(w, b, 0.4);
        else (void)rg_body_set_aabb(w, b, 0.4, 0.4);
        if (prev != 0) (void)rg_spring_create(w, b, prev, vec(0, 0), 1, 20, 0.5, &s);
        prev = b;
    }
    for (int k = 0; k < 20; k++) (void)rg_world_step(w, (rg_real)(1.0 / 60));
}

/* ---- the restored state steps safely: every coordinate the debug draw shows is finite */

static void need_finite(rg_vec2 v, const char *what)
{
    if (!(isfinite(v.x) && isfinite(v.y))) FAIL("after a step, a %s at (%g, %g)", what, (double)v.x, (double)v.y);
}

static void on_circle(rg_body body, rg_vec2 c, rg_real r, uint32_t rgba, void *user)
{
    (void)body;
    (void)rgba;
    (void)user;
    need_finite(c, "circle");
    if (!(r > 0 && isfinite(r))) FAIL("a circle of radius %g", (double)r);
}

static void on_box(rg_body body, rg_vec2 lo, rg_vec2 hi, uint32_t rgba, void *user)
{
    (void)body;
    (void)rgba;
    (void)user;
    need_finite(lo, "box");
    need_finite(hi, "box");
    if (!(lo.x <= hi.x && lo.y <= hi.y)) FAIL("a box with lower > upper");
}

static void on_segment(rg_vec2 a, rg_vec2 b, uint32_t rgba, void *user)
{
    (void)rgba;
    (void)user;
    need_finite(a, "segment (spring, velocity or contact normal)");
    need_finite(b, "segment (spring, velocity or contact normal)");
}

static void on_point(rg_vec2 p, uint32_t rgba, void *user)
{
    (void)rgba;
    (void)user;
    need_finite(p, "point (body without a shape or contact)");
}

static void check_state(const rg_world *w)
{
    static const rg_debug_draw draw = { on_circle, on_box, on_segment, on_point, 31u, NULL };
    static rg_body out[STEP_ONE];
    static rg_contact_event ev[256];
    rg_ray_hit hits[16];
    int32_t n = rg_world_body_count(w);
    if (rg_world_draw(w, &draw) != RG_OK) FAIL("draw failed");
    if (rg_world_awake_body_count(w) > n || rg_world_touching_count(w) < 0) FAIL("counts");
    int32_t q = rg_world_query_aabb(w, vec(-1e12, -1e12), vec(1e12, 1e12), 0xFFFFFFFFu, out, STEP_ONE);
    if (q < 0 || q > n) FAIL("query_aabb found %d of %d bodies", q, n);
    for (int32_t k = 0; k < q && k < STEP_ONE; k++)
        if (!rg_body_is_valid(w, out[k]) || (k > 0 && !(out[k - 1] < out[k]))) FAIL("query_aabb results");
    int32_t r = rg_world_raycast_all(w, vec(-1e6, 0.25), vec(2e6, 0), 0xFFFFFFFFu, hits, 16);
    for (int32_t k = 0; k < r && k < 16; k++)
        if (!rg_body_is_valid(w, hits[k].body) || !(hits[k].fraction >= 0 && hits[k].fraction <= 1)) FAIL("raycast_all hit");
    int32_t e = rg_world_get_contact_events(w, ev, 256);
    for (int32_t k = 0; k < e && k < 256; k++)
        if (!(ev[k].a < ev[k].b) || (ev[k].kind != RG_CONTACT_BEGIN && ev[k].kind != RG_CONTACT_END)) FAIL("event %d", k);
    int32_t s = rg_world_get_stopped(w, out, STEP_ONE);
    if (s < 0 || s > n) FAIL("%d stopped of %d bodies", s, n);
}

/* Steps the restored state in every integrator (one when it is large), each from the start,
 * with and without a task system: both must hash alike after every step. */
static void step_safely(const buf *state)
{
    rg_world *w, *t;
    if (rg_world_create(&w) != RG_OK || rg_world_create(&t) != RG_OK) abort();
    if (rg_world_restore(w, state->p, state->n) != RG_OK) FAIL("a saved state does not restore");
    int32_t bodies = rg_world_body_count(w), own = 0;
    (void)rg_world_get_integrator(w, &own);
    int integrators = bodies <= STEP_ALL ? 4 : bodies <= STEP_ONE ? 1 : 0;
    shuffler sh;
    rg_task_system ts;
    shuffler_init(&sh, 0x9E3779B97F4A7C15ull, 3, 0);
    shuffler_tasks(&sh, &ts);
    if (rg_world_set_task_system(t, &ts) != RG_OK) FAIL("set_task_system");
    for (int k = 0; k < integrators; k++) {
        int32_t integrator = (own + k) % 4;
        if (rg_world_restore(w, state->p, state->n) != RG_OK || rg_world_restore(t, state->p, state->n) != RG_OK)
            FAIL("a saved state does not restore");
        if (rg_world_set_integrator(w, integrator) != RG_OK || rg_world_set_integrator(t, integrator) != RG_OK)
            FAIL("set_integrator");
        for (int s = 0; s < (integrators == 4 ? STEPS : 1); s++) {
            rg_status st = rg_world_step(w, (rg_real)(1.0 / 60));
            if (st != RG_OK) FAIL("a step of a restored state failed: status %d (%s)", st, rg_world_last_error(w));
            if (rg_world_step(t, (rg_real)(1.0 / 60)) != RG_OK) FAIL("a step with a task system failed");
            check_state(w);
            if (hash(w) != hash(t)) FAIL("integrator %d step %d: a task system changed the result", integrator, s + 1);
            if (sh.misuse != 0) FAIL("the world misused its task system");
        }
    }
    rg_world_destroy(t);
    rg_world_destroy(w);
}

/* ---- the input */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) return 0;
    uint8_t mode = data[0];
    size_t n = size - 1;
    unsigned char *snap = (unsigned char *)malloc(n > 0 ? n : 1);
    if (snap == NULL) abort();
    if (n > 0) memcpy(snap, data + 1, n);
    if (n >= SNAP_HEADER) {
        if (!(mode & 4)) snap_put64(snap + 16, (uint64_t)n);
        if (mode & 3) snap_put64(snap + 24, snap_hash(snap + SNAP_HEADER, n - SNAP_HEADER));
    }

    fz_alloc al = { 0, -1, 0, 0, 0 };
    rg_world *w;
    if (rg_world_create_with_allocator(fz_allocf, &al, &w) != RG_OK) abort();
    scene(w);
    uint64_t h0 = hash(w);
    buf before = save(w);
    if (rg_world_restore(NULL, snap, n) != RG_ERR_INVALID_ARGUMENT) FAIL("restore into NULL");
    if (rg_world_restore(w, NULL, n) != RG_ERR_INVALID_ARGUMENT) FAIL("restore of NULL");
    if (mode & 8) al.fail_at = al.calls + (mode >> 4);

    rg_status st = rg_world_restore(w, snap, n);
    al.fail_at = -1;
    const char *why = rg_world_last_error(w);
    if (!(mode & 8)) { /* spread over a task system: the same decision, reason and state */
        rg_world *t;
        shuffler sh;
        rg_task_system ts;
        if (rg_world_create(&t) != RG_OK) abort();
        shuffler_init(&sh, 0x2545F4914F6CDD1Dull ^ n, 3, mode & 1);
        shuffler_tasks(&sh, &ts);
        if (rg_world_set_task_system(t, &ts) != RG_OK) FAIL("set_task_system");
        rg_status tst = rg_world_restore(t, snap, n);
        if (tst != st || strcmp(rg_world_last_error(t), why) != 0)
            FAIL("with a task system the restore says %d \"%s\", without %d \"%s\"", tst, rg_world_last_error(t), st, why);
        if (st == RG_OK && hash(t) != hash(w)) FAIL("with a task system the restore loads another state");
        if (sh.misuse != 0) FAIL("the restore misused its task system");
        rg_world_destroy(t);
    }
    if (st != RG_OK) {
        if (st != RG_ERR_INVALID_ARGUMENT && !(st == RG_ERR_OUT_OF_MEMORY && al.refused > 0))
            FAIL("restore refused with status %d", st);
        if (why == NULL || strstr(why, "rg_world_restore") == NULL) FAIL("restore refused without a reason: \"%s\"", why);
        buf after = save(w);
        if (hash(w) != h0 || after.n != before.n || memcmp(after.p, before.p, before.n) != 0)
            FAIL("a refused restore changed the world (%s)", why);
        free(after.p);
    } else {
        if (why == NULL || why[0] != 0) FAIL("an accepted restore left an error: \"%s\"", why);
        uint64_t h1 = hash(w);
        buf state = save(w);
        rg_world *f;
        if (rg_world_create(&f) != RG_OK) abort();
        if (rg_world_restore(f, snap, n) != RG_OK) FAIL("a fresh world refuses what a world with a scene took");
        if (hash(f) != h1) FAIL("the same snapshot restores to other states in two worlds");
        if (rg_world_restore(f, state.p, state.n) != RG_OK) FAIL("an accepted state's save does not restore");
        buf again = save(f);
        if (hash(f) != h1 || again.n != state.n || memcmp(again.p, state.p, state.n) != 0)
            FAIL("save -> restore -> save of an accepted state changes it");
        free(again.p);
        rg_world_destroy(f);
        step_safely(&state);
        free(state.p);
    }
    free(before.p);
    rg_world_destroy(w);
    if (al.live_blocks != 0 || al.live_bytes != 0) FAIL("a destroyed world left %ld blocks", al.live_blocks);
    free(snap);
    return 0;
}
