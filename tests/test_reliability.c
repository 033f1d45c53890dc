/* test_reliability.c: the header's promises that fuzzing (issue 15, tests/fuzz/fuzz_api.c)
 * found broken, one test each, named for the promise, each failing before its fix: no input
 * puts a NaN into the world (rigid.h, top), dissipation never reverses or grows a velocity,
 * a world can always restore its own snapshot, and another world's handle is rejected
 * (RG_ERR_STALE_HANDLE: "destroyed, forged, zero or another world's handle").  A comment
 * above each gives the root cause the finding had (file, function). */
#include "testutil.h"

#ifdef RG_DOUBLE
#define REAL_MIN DBL_MIN
#else
#define REAL_MIN FLT_MIN
#endif

static int finite_vec(rg_vec2 v) { return isfinite(v.x) && isfinite(v.y); }

/* Every observable of body b is finite: position, velocity, acceleration, interpolated. */
static void assert_body_finite(rg_world *w, rg_body b)
{
    rg_vec2 p, v, a, ip;
    assert_ok(rg_body_get_position(w, b, &p));
    assert_ok(rg_body_get_velocity(w, b, &v));
    assert_ok(rg_body_get_acceleration(w, b, &a));
    assert_ok(rg_body_get_interpolated_position(w, b, &ip));
    if (!finite_vec(p) || !finite_vec(v) || !finite_vec(a) || !finite_vec(ip))
        fail_msg("body state not finite: p (%g, %g) v (%g, %g) a (%g, %g) interpolated (%g, %g)",
                 (double)p.x, (double)p.y, (double)v.x, (double)v.y, (double)a.x, (double)a.y,
                 (double)ip.x, (double)ip.y);
}

/* A call that may refuse its input: either it fails (and the body reads as before) or the
 * state it leaves is finite.  Both keep the promise; a NaN or an inf breaks it. */
static void step_keeps_promise(rg_world *w, rg_body b, rg_real dt)
{
    rg_status st = rg_world_step(w, dt);
    if (st == RG_OK) assert_body_finite(w, b);
    else assert_status(st, RG_ERR_INVALID_ARGUMENT);
}

/* ---------------------------------------------------------------- NaN from accepted input */

/* Root cause: src/body_api.c, rg_body_create (and rg_body_set_mass) accept any mass > 0, so a
 * denormal passes; inv_mass = 1 / mass is then inf, and the first step's force sum in
 * src/integrator.c (euler_body: (wind + f) * inv_mass with f = 0) is 0 * inf = NaN.
 * Suggested fix: an accepted mass range stated in the header (e.g. [1e-6, 1e9] kg, or at
 * least 1/mass finite), checked where the mass enters. */
static void test_denormal_mass_never_puts_a_nan_into_the_world(void **state)
{
    (void)state;
    rg_world *w;
    rg_body b = 0;
    rg_real tiny = REAL_MIN / 1024;   /* a denormal */
    assert_true(tiny > 0 && tiny < REAL_MIN);
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_gravity(w, v2(0, -9.81f)));
    rg_status st = rg_body_create(w, RG_BODY_DYNAMIC, tiny, v2(0, 0), &b);
    if (st == RG_OK) {
        step_keeps_promise(w, b, (rg_real)(1.0 / 60));
    } else {
        assert_status(st, RG_ERR_INVALID_ARGUMENT);
        b = make_body(w, 1, 0, 0);
        st = rg_body_set_mass(w, b, tiny);
        if (st == RG_OK) step_keeps_promise(w, b, (rg_real)(1.0 / 60));
        else assert_status(st, RG_ERR_INVALID_ARGUMENT);
    }
    rg_world_destroy(w);
}

/* Root cause: no range is validated for positions and velocities (src/body_api.c,
 * rg_body_create / rg_body_set_position / rg_body_set_velocity take any finite value), and
 * the step is not total: src/integrator.c (euler_body) computes x + v * h, which overflows
 * to inf for a body near the float range, and nothing stops it.  Suggested fix: accepted
 * ranges in the header (|position| and |velocity| well inside the float range, e.g. 1e18),
 * and a step that stops and reports a body whose state would leave the finite range. */
static void test_state_near_the_float_range_stays_finite_after_a_step(void **state)
{
    (void)state;
    rg_world *w;
    assert_ok(rg_world_create(&w));
    rg_real big = REAL_MAX * (rg_real)0.75;
    rg_body b = 0;
    rg_status st = rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(big, 0), &b);
    if (st == RG_OK) st = rg_body_set_velocity(w, b, v2(big, 0));
    if (st == RG_OK) step_keeps_promise(w, b, 1);
    else assert_status(st, RG_ERR_INVALID_ARGUMENT);
    rg_world_destroy(w);
}

/* Root cause: src/step.c, rg_world_step accepts any finite dt > 0; with gravity, v = g * dt
 * and x = v * dt overflow (dt = 1e30: x ~ 1e61).  Suggested fix: a dt range in the header
 * (e.g. (0, 1] s or a few seconds), checked in rg_world_step and rg_world_set_fixed_step,
 * plus the total step above. */
static void test_huge_step_never_puts_an_inf_into_the_world(void **state)
{
    (void)state;
    rg_world *w;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_gravity(w, v2(0, -9.81f)));
    rg_body b = make_body(w, 1, 0, 0);
#ifdef RG_DOUBLE
    step_keeps_promise(w, b, (rg_real)1e200);
#else
    step_keeps_promise(w, b, (rg_real)1e30);
#endif
    rg_world_destroy(w);
}

/* Root cause: src/body_api.c, rg_body_get_interpolated_position computes
 * px + alpha * (x - px): once x is inf (the overflow above), alpha = 0 makes 0 * inf = NaN,
 * and x - px overflows by itself for positions of opposite signs near the float range.
 * Suggested fix: the ranges and total step above (x stays finite and within range, so the
 * difference cannot overflow), or a blend written as (1 - alpha) * px + alpha * x. */
static void test_interpolated_position_is_finite_after_an_advance(void **state)
{
    (void)state;
    rg_world *w;
    int32_t steps = 0;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_fixed_step(w, 1, 8));
    rg_real big = REAL_MAX * (rg_real)0.75;
    rg_body b = 0;
    rg_status st = rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(big, 0), &b);
    if (st == RG_OK) st = rg_body_set_velocity(w, b, v2(big, 0));
    if (st == RG_OK) st = rg_world_advance(w, 1, &steps);
    if (st == RG_OK) assert_body_finite(w, b);
    else assert_status(st, RG_ERR_INVALID_ARGUMENT);
    rg_world_destroy(w);
}

/* Root cause: src/force.c, force_springs: d2 = dx*dx + dy*dy overflows to inf for bodies
 * about 1e20 m apart (float); the bodies then reach speeds of about 1e20 m/s, dv . d
 * overflows too and the damping term c * (dv . d) / d2 is 0 * inf / inf = NaN even with
 * damping 0.  Suggested fix: a position range that keeps d2 finite, or the length by a
 * scaled hypot and the damping as c * (dv . n) with n = d / |d|. */
static void test_spring_between_far_bodies_stays_finite(void **state)
{
    (void)state;
    rg_world *w;
    uint64_t s;
#ifdef RG_DOUBLE
    double half = 1e160;
#else
    double half = 5e19;
#endif
    assert_ok(rg_world_create(&w));
    rg_body a = 0, b = 0;
    rg_status st = rg_body_create(w, RG_BODY_DYNAMIC, 1, v2((rg_real)-half, 0), &a);
    if (st == RG_OK) st = rg_body_create(w, RG_BODY_DYNAMIC, 1, v2((rg_real)half, 0), &b);
    if (st == RG_OK) st = rg_spring_create(w, a, b, v2(0, 0), 0, 1, 0, &s);
    if (st != RG_OK) {
        assert_status(st, RG_ERR_INVALID_ARGUMENT);   /* refusing the scene keeps the promise */
        rg_world_destroy(w);
        return;
    }
    for (int k = 0; k < 20; k++) {
        assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
        assert_body_finite(w, a);
        assert_body_finite(w, b);
    }
    rg_world_destroy(w);
}

/* Found by tests/fuzz/fuzz_api.c (create a world, one dynamic body of mass 1.4e-45, save).
 * Root cause: the denormal mass above (src/body_api.c, rg_body_create accepts it, inv_mass
 * = 1 / mass = inf), and rg_world_restore's state check refuses what rg_world_save wrote
 * (an inverse mass that is not finite), so a world cannot be rolled back to its own
 * snapshot.  Suggested fix: the mass range where the mass enters; the save and the restore
 * then agree on every state the API can make. */
static void test_a_saved_world_always_restores(void **state)
{
    (void)state;
    rg_world *w, *clone;
    rg_body b;
    size_t n = 0;
    assert_ok(rg_world_create(&w));
    rg_status st = rg_body_create(w, RG_BODY_DYNAMIC, REAL_MIN / 1024, v2(0, 0), &b);
    if (st != RG_OK) {
        assert_status(st, RG_ERR_INVALID_ARGUMENT);   /* refusing the mass keeps the promise */
        rg_world_destroy(w);
        return;
    }
    assert_ok(rg_world_save(w, NULL, 0, &n));
    void *buf = malloc(n);
    assert_non_null(buf);
    assert_ok(rg_world_save(w, buf, n, &n));
    assert_ok(rg_world_create(&clone));
    assert_ok(rg_world_restore(clone, buf, n));
    assert_ok(rg_world_restore(w, buf, n));
    free(buf);
    rg_world_destroy(clone);
    rg_world_destroy(w);
}

/* ---------------------------------------------------------------- dissipation */

/* Root cause: src/integrator.c, free_velocity / dissipation_explicit decide explicit or
 * implicit dissipation from the start state only: a body at rest has speed 0, so the
 * explicit branch is taken, and RK4's later stages then evaluate drag (1000 + 1000 |v|)
 * kg/s at dt = 0.1 s, where k * dt / m = 100 makes each stage overshoot and grow;
 * guard_dissipation (dissipation_overshoots) checks only that the result points the way of
 * the free velocity, not its size.  Suggested fix: decide per stage or bound every stage's
 * drag implicitly (k * h / m > 1 -> implicit), and guard |v_new| <= |v_free|.
 * The bound: drag only removes speed, so over a step from rest under gravity g the speed
 * can grow by at most g * dt (free fall), and never past the first step's free fall. */
static void test_rk4_with_strong_drag_never_grows_a_velocity(void **state)
{
    (void)state;
    rg_world *w;
    const double g = 9.81, dt = 0.1;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_gravity(w, v2(0, (rg_real)-g)));
    assert_ok(rg_world_set_integrator(w, RG_INTEGRATOR_RK4));
    rg_body b = make_body(w, 1, 0, 0);
    assert_ok(rg_body_set_drag(w, b, 1000, 1000));
    for (int k = 0; k < 10; k++) {
        assert_ok(rg_world_step(w, (rg_real)dt));
        rg_vec2 v = vel_of(w, b);
        double speed = hypot((double)v.x, (double)v.y);
        if (!(speed <= g * dt * (1 + 8 * REAL_EPS)))
            fail_msg("step %d: |v| = %g m/s, more than free fall adds in one step (%g)", k + 1,
                     speed, g * dt);
        if (!((double)v.y <= 0)) fail_msg("step %d: drag reversed the fall (vy = %g)", k + 1, (double)v.y);
    }
    rg_world_destroy(w);
}

/* ---------------------------------------------------------------- handles */

/* An allocator that keeps freed blocks and hands one out again for the next request of the
 * same size, as glibc does for a world destroyed and created again at once. */
#define CACHE_BLOCKS 64
typedef struct cache_alloc {
    void *block[CACHE_BLOCKS];
    size_t size[CACHE_BLOCKS];
    int n;
} cache_alloc;

static void *cache_allocf(void *user, void *ptr, size_t old_size, size_t new_size)
{
    cache_alloc *c = (cache_alloc *)user;
    if (new_size == 0) {
        if (ptr != NULL && c->n < CACHE_BLOCKS) {
            c->block[c->n] = ptr;
            c->size[c->n++] = old_size;
        } else {
            free(ptr);
        }
        return NULL;
    }
    if (ptr == NULL)
        for (int k = c->n - 1; k >= 0; k--)
            if (c->size[k] == new_size) {
                void *p = c->block[k];
                c->block[k] = c->block[--c->n];
                c->size[k] = c->size[c->n];
                return p;
            }
    return realloc(ptr, new_size);
}

/* Root cause: src/world.c, world_tag: the tag is 20 bits of the world's address, so a world
 * created where the last one was destroyed (a level reload) gets the same tag, and the old
 * world's handles (same slot, same generation) are valid in the new one.  Suggested fix: a
 * tag that a destroyed-and-recreated world cannot reuse without global state: e.g. a
 * per-world random tag from a seed the allocator cannot influence, or a generation kept in
 * the world block itself and bumped on destroy. */
static void test_handles_of_a_destroyed_world_are_rejected_by_the_next(void **state)
{
    (void)state;
    cache_alloc cache;
    memset(&cache, 0, sizeof cache);
    rg_world *w1, *w2;
    assert_ok(rg_world_create_with_allocator(cache_allocf, &cache, &w1));
    rg_body old = make_body(w1, 1, 0, 0);
    rg_world_destroy(w1);
    assert_ok(rg_world_create_with_allocator(cache_allocf, &cache, &w2));
    assert_true(w2 == w1);   /* the fixture: the same address again */
    rg_body fresh = make_body(w2, 1, 5, 0);
    assert_int_equal(rg_body_is_valid(w2, old), 0);
    assert_true(fresh != old);
    assert_status(rg_body_set_position(w2, old, v2(1, 1)), RG_ERR_STALE_HANDLE);
    assert_true(pos_of(w2, fresh).x == 5);
    rg_world_destroy(w2);
    for (int k = 0; k < cache.n; k++) free(cache.block[k]);
}

/* Places the first block asked for (the world itself) at a fixed address, the rest with
 * malloc: two worlds exactly 16 MiB apart, as a custom allocator's arena may put them. */
typedef struct arena_alloc {
    char *at;
    int used;
} arena_alloc;

static void *arena_allocf(void *user, void *ptr, size_t old_size, size_t new_size)
{
    arena_alloc *a = (arena_alloc *)user;
    (void)old_size;
    if ((char *)ptr == a->at) {
        if (new_size == 0) return NULL;   /* the arena is freed by the test */
        return NULL;                       /* the world block is never resized */
    }
    if (new_size == 0) {
        free(ptr);
        return NULL;
    }
    if (ptr == NULL && !a->used) {
        a->used = 1;
        return a->at;
    }
    return realloc(ptr, new_size);
}

/* Root cause: src/world.c, world_tag takes bits 4..23 of the address, so two live worlds
 * 16 MiB apart (2^24 bytes) share their tag: a handle of one is valid in the other and
 * rg_body_set_position(w2, handle_of_w1) moves w2's body.  Suggested fix: as above. */
static void test_worlds_16_mib_apart_reject_each_others_handles(void **state)
{
    (void)state;
    const size_t apart = (size_t)16 << 20, room = (size_t)1 << 20;
    char *arena = malloc(apart + room);   /* aligned as malloc's are, which the world needs */
    assert_non_null(arena);
    arena_alloc a1 = { arena, 0 }, a2 = { arena + apart, 0 };
    rg_world *w1, *w2;
    assert_ok(rg_world_create_with_allocator(arena_allocf, &a1, &w1));
    assert_ok(rg_world_create_with_allocator(arena_allocf, &a2, &w2));
    assert_true((char *)w2 - (char *)w1 == (ptrdiff_t)apart);
    rg_body b1 = make_body(w1, 1, 1, 0), b2 = make_body(w2, 1, 2, 0);
    assert_int_equal(rg_body_is_valid(w2, b1), 0);
    assert_int_equal(rg_body_is_valid(w1, b2), 0);
    assert_status(rg_body_set_position(w2, b1, v2(9, 9)), RG_ERR_STALE_HANDLE);
    assert_true(pos_of(w2, b2).x == 2);
    rg_world_destroy(w1);
    rg_world_destroy(w2);
    free(arena);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_denormal_mass_never_puts_a_nan_into_the_world),
        cmocka_unit_test(test_state_near_the_float_range_stays_finite_after_a_step),
        cmocka_unit_test(test_huge_step_never_puts_an_inf_into_the_world),
        cmocka_unit_test(test_interpolated_position_is_finite_after_an_advance),
        cmocka_unit_test(test_spring_between_far_bodies_stays_finite),
        cmocka_unit_test(test_a_saved_world_always_restores),
        cmocka_unit_test(test_rk4_with_strong_drag_never_grows_a_velocity),
        cmocka_unit_test(test_handles_of_a_destroyed_world_are_rejected_by_the_next),
        cmocka_unit_test(test_worlds_16_mib_apart_reject_each_others_handles),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
