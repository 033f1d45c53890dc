/* test_contact_api.c: a body's contacts with the impulses of the last step, and the
 * pre-solve hook: skipping pairs, the locked world, a fixed call order. */
#include "testutil.h"

#define G 10.0

/* ---------------------------------------------------------------- contacts */

/* A 2 kg unit box on a floor, sleeping off, after `steps` steps. */
static rg_world *box_on_floor(rg_body *floor, rg_body *box, int steps)
{
    rg_world *w = gravity_world(-G);
    *floor = floor_of(w);
    *box = box_body(w, RG_BODY_DYNAMIC, 2, 0, 0.5, 0.5, 0.5);
    assert_ok(rg_world_set_sleeping(w, 0));
    step_n(w, steps, DT);
    return w;
}

/* At rest on the floor the solve gives the impulse that cancels what gravity adds in a step:
 * J = m g dt along the normal, no friction.  The solver converges on one row exactly up to
 * rounding (warm start and 8 sweeps), so the tolerance is a few ulps of J. */
static void test_a_resting_body_has_one_contact_carrying_m_g_dt(void **state)
{
    (void)state;
    rg_body floor, b;
    rg_world *w = box_on_floor(&floor, &b, 120);
    rg_contact c[4];
    assert_int_equal(rg_body_get_contacts(w, b, c, 4), 1);
    assert_true(c[0].other == floor);
    assert_near(c[0].normal.x, 0, 1e-6);
    assert_near(c[0].normal.y, -1, 1e-6); /* from the body toward the floor */
    assert_true(c[0].separation <= 0 && (double)c[0].separation >= -0.005);
    assert_near(c[0].point.y, 0, 0.005);
    double j = 2 * G * DT;
    assert_near(c[0].normal_impulse, j, 64 * REAL_EPS * j);
    assert_near(c[0].tangent_impulse, 0, 64 * REAL_EPS * j);
    assert_int_equal(c[0].sensor, 0);
    /* the floor sees the same contact from its side */
    assert_int_equal(rg_body_get_contacts(w, floor, c, 4), 1);
    assert_true(c[0].other == b);
    assert_near(c[0].normal.y, 1, 1e-6);
    assert_near(c[0].normal_impulse, j, 64 * REAL_EPS * j);
    rg_world_destroy(w);
}

/* A box pushed along the floor by F > mu m g slides; Coulomb friction then takes exactly
 * mu * (normal impulse) = mu m g dt per step, against the motion. */
static void test_a_box_pushed_along_the_floor_shows_the_friction_impulse(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-G);
    floor_of(w);
    rg_body b = box_body(w, RG_BODY_DYNAMIC, 2, 0, 0.5, 0.5, 0.5);
    double mu = 0.5; /* the floor's 0.6 and the box's mu mix as sqrt(0.6 mu_b) */
    assert_ok(rg_body_set_friction(w, b, (rg_real)(mu * mu / 0.6)));
    step_n(w, 30, DT);
    for (int k = 0; k < 30; k++) {
        assert_ok(rg_body_apply_force(w, b, v2(25, 0))); /* > mu m g = 10 N */
        step_n(w, 1, DT);
    }
    assert_true(VX(w, b) > 0.5);
    rg_contact c;
    assert_int_equal(rg_body_get_contacts(w, b, &c, 1), 1);
    double j = 2 * G * DT;
    assert_near(c.normal_impulse, j, 1e-4 * j);
    /* the tangent of the normal (0, -1) is (1, 0): friction on the box points to -x */
    assert_near(c.tangent_impulse, -mu * (double)c.normal_impulse, 1e-4 * j);
    /* and the velocity gained per step is (F dt - mu m g dt) / m */
    double v0 = VX(w, b);
    assert_ok(rg_body_apply_force(w, b, v2(25, 0)));
    step_n(w, 1, DT);
    assert_near(VX(w, b) - v0, (25 * DT - mu * j) / 2, 1e-4);
    rg_world_destroy(w);
}

static void test_contacts_are_sorted_by_handle_with_sensors_and_capacity(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-G);
    rg_body floor = floor_of(w);
    rg_body coin = circle_body(w, RG_BODY_STATIC, 0, 0, 1.5, 0.3);
    assert_ok(rg_body_set_sensor(w, coin, 1));
    rg_body b = box_body(w, RG_BODY_DYNAMIC, 1, 0, 1.2, 0.5, 1.2); /* spans y 0 .. 2.4 */
    rg_body top = box_body(w, RG_BODY_DYNAMIC, 1, 0, 2.9, 0.5, 0.5);
    step_n(w, 30, DT);
    rg_contact c[3];
    assert_int_equal(rg_body_get_contacts(w, b, NULL, 0), 3);
    assert_int_equal(rg_body_get_contacts(w, b, c, 3), 3);
    assert_true(c[0].other < c[1].other && c[1].other < c[2].other);
    rg_body want[3] = { floor, coin, top };
    for (int k = 0; k < 3; k++) assert_true(c[k].other == want[k]);
    assert_int_equal(c[1].sensor, 1);
    assert_true(c[1].normal_impulse == 0 && c[1].tangent_impulse == 0);
    /* capacity 1 copies the first in order, and still counts all */
    rg_contact one;
    assert_int_equal(rg_body_get_contacts(w, b, &one, 1), 3);
    assert_true(one.other == floor);
    /* bad input */
    assert_int_equal(rg_body_get_contacts(NULL, b, c, 3), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_body_get_contacts(w, b, NULL, 1), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_body_get_contacts(w, b, c, -1), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_body_get_contacts(w, 77, c, 3), RG_ERR_STALE_HANDLE);
    /* a body in the air has none */
    rg_body air = circle_body(w, RG_BODY_DYNAMIC, 1, 20, 20, 0.5);
    assert_int_equal(rg_body_get_contacts(w, air, c, 3), 0);
    rg_world_destroy(w);
}

/* Whether the bytes of p from `from` to `size` (a record's padding after its last field)
 * are all 0. */
static int zero_after(const void *p, size_t from, size_t size)
{
    const unsigned char *c = p;
    for (size_t k = from; k < size; k++)
        if (c[k] != 0) return 0;
    return 1;
}

/* The records the library writes into the caller's memory carry no byte of its own stack:
 * into buffers filled with 0xAA, every contact's padding after its last field (4 bytes in
 * the double build) and every hit's pad and padding (4 more in the double build) end 0, from
 * each call that writes them.  (Until 2026-12-07 the double build's padding held stack bytes,
 * which changed from call to call on s390x.) */
static void test_contacts_and_hits_come_with_their_padding_zeroed(void **state)
{
    (void)state;
    rg_body floor, b;
    rg_world *w = box_on_floor(&floor, &b, 60);
    const size_t contact_end = offsetof(rg_contact, sensor) + sizeof(int32_t);
    const size_t hit_end = offsetof(rg_ray_hit, pad);
    rg_contact c[2];
    memset(c, 0xAA, sizeof c);
    assert_int_equal(rg_body_get_contacts(w, b, c, 2), 1);
    assert_true(c[0].other == floor && zero_after(&c[0], contact_end, sizeof c[0]));
    rg_ray_hit h[4];
    memset(h, 0xAA, sizeof h);
    assert_int_equal(rg_world_raycast(w, v2(3, 5), v2(0, -10), 0xFFFFFFFFu, &h[0]), 1);
    assert_int_equal(rg_world_raycast_all(w, v2(0, 5), v2(0, -10), 0xFFFFFFFFu, &h[1], 1), 2);
    assert_int_equal(rg_world_cast_shape(w, RG_SHAPE_CIRCLE, v2(0.25, 0.25), v2(3, 5), v2(0, -10), 0xFFFFFFFFu,
                                         &h[2]), 1);
    int32_t n = 0;
    assert_ok(rg_body_move(w, b, v2(0, -2), 0xFFFFFFFFu, RG_MOVE_TOUCH, NULL, &h[3], 1, &n));
    assert_int_equal(n, 1);
    for (int k = 0; k < 4; k++) assert_true(zero_after(&h[k], hit_end, sizeof h[k]));
    rg_world_destroy(w);
}

/* ---------------------------------------------------------------- pre-solve */

typedef struct hook_log {
    rg_world *w;
    rg_body skip;          /* pairs with this body are skipped */
    int calls;
    uint64_t hash;         /* of the (a, b) sequence, as creation indices */
    const rg_body *bodies;
    int n;
    int bad_order;
    int locked_ok;         /* every mutating call returned RG_ERR_LOCKED */
    int getters_ok;
} hook_log;

static int32_t index_in(const hook_log *l, rg_body h)
{
    for (int i = 0; i < l->n; i++)
        if (l->bodies[i] == h) return i;
    return -1;
}

static int32_t skip_hook(rg_body a, rg_body b, rg_vec2 normal, rg_real separation, void *user)
{
    hook_log *l = user;
    l->calls++;
    if (!(a < b)) l->bad_order++;
    if (fabs((double)normal.x * (double)normal.x + (double)normal.y * (double)normal.y - 1) > 1e-5) l->bad_order++;
    (void)separation;
    if (l->bodies != NULL) {
        int32_t ab[2] = { index_in(l, a), index_in(l, b) };
        l->hash = fnv(l->hash, ab, 2, sizeof ab[0]);
    }
    return a != l->skip && b != l->skip;
}

static void test_returning_zero_lets_a_pair_pass(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-G);
    floor_of(w);
    rg_body ghost = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 1, 0.25);
    rg_body solid = circle_body(w, RG_BODY_DYNAMIC, 1, 3, 1, 0.25);
    hook_log l;
    memset(&l, 0, sizeof l);
    l.skip = ghost;
    assert_ok(rg_world_set_pre_solve(w, skip_hook, &l));
    rg_contact_event ev[16];
    for (int k = 0; k < 90; k++) {
        step_n(w, 1, DT);
        /* the skipped pair never touches: no event names the ghost */
        int32_t n = get_events(w, ev, 16);
        for (int32_t e = 0; e < n; e++) assert_true(ev[e].a != ghost && ev[e].b != ghost);
        assert_int_equal(flag(rg_body_is_grounded, w, ghost), 0);
    }
    assert_true(PY(w, ghost) < -1);                 /* fell through the floor */
    assert_true(fabs(PY(w, solid) - 0.25) <= 0.005); /* rests on it */
    assert_true(l.calls > 0);
    assert_int_equal(l.bad_order, 0);
    /* NULL removes the hook: no more calls */
    assert_ok(rg_world_set_pre_solve(w, NULL, &l));
    int before = l.calls;
    step_n(w, 10, DT);
    assert_int_equal(l.calls, before);
    assert_status(rg_world_set_pre_solve(NULL, skip_hook, &l), RG_ERR_INVALID_ARGUMENT);
    rg_world_destroy(w);
}

/* A pair the hook skips is skipped by the post-solve sweep too: a box sent at 2-128 m/s at a
 * static wall (1 m or 4 cm thick) the hook lets it through keeps its velocity and ends past
 * the wall at the distance its free motion gives, and a box the hook does not skip stops at
 * the wall.  (Until 2026-12-07 the sweep stopped every box that moved more than half its size
 * in a step, from 8 m/s, at a wall the hook had let it pass.) */
static void test_a_pair_the_hook_skips_is_not_stopped_by_the_sweep(void **state)
{
    (void)state;
    for (int thin = 0; thin < 2; thin++) {
        for (double speed = 2; speed <= 128; speed *= 2) {
            for (int skipped = 0; skipped < 2; skipped++) {
                rg_world *w = gravity_world(0);
                rg_body wall = box_body(w, RG_BODY_STATIC, 0, 2, 0, thin ? 0.02 : 0.5, 2);
                rg_body b = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0, 0.25, 0.25);
                hook_log l;
                memset(&l, 0, sizeof l);
                l.skip = skipped ? wall : 0; /* 0 is never a handle */
                assert_ok(rg_world_set_pre_solve(w, skip_hook, &l));
                assert_ok(rg_body_set_velocity(w, b, v2((rg_real)speed, 0)));
                int steps = (int)(60 * 8 / speed) + 10;
                step_n(w, steps, DT);
                if (skipped) {
                    assert_near(VX(w, b), speed, 1e-6 * speed);
                    assert_near(PX(w, b), speed * steps * DT, 1e-5 * speed * steps * DT);
                } else {
                    assert_true(PX(w, b) < 2 - (thin ? 0.02 : 0.5) - 0.25 + 0.005);
                }
                rg_world_destroy(w);
            }
        }
    }
}

/* A ball asleep on the floor, then a hook installed that skips its pair with the floor: the
 * installation changes nothing (the world hashes as before: a restored world given its hook
 * steps as the saved one did), and the sleeping pair is not asked until the ball is woken;
 * then it is, and the ball falls through. */
static void test_a_sleeping_pair_is_asked_once_a_body_of_it_is_woken(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-G);
    floor_of(w);
    rg_body ball = circle_body(w, RG_BODY_DYNAMIC, 1, 0, 0.25, 0.25);
    step_n(w, 120, DT);
    assert_int_equal(flag(rg_body_is_awake, w, ball), 0);
    hook_log l;
    memset(&l, 0, sizeof l);
    l.skip = ball;
    uint64_t before, after;
    assert_ok(rg_world_hash(w, &before));
    assert_ok(rg_world_set_pre_solve(w, skip_hook, &l));
    assert_ok(rg_world_hash(w, &after));
    assert_true(before == after);
    step_n(w, 10, DT);
    assert_int_equal(l.calls, 0);
    assert_int_equal(flag(rg_body_is_awake, w, ball), 0);
    assert_ok(rg_body_wake(w, ball));
    step_n(w, 30, DT);
    assert_true(l.calls > 0);
    assert_true(PY(w, ball) < -0.5); /* some 1 m down after 0.5 s */
    rg_world_destroy(w);
}

/* Inside the hook every call that changes the world returns RG_ERR_LOCKED and changes
 * nothing; getters and queries answer. */
static int32_t locked_hook(rg_body a, rg_body b, rg_vec2 normal, rg_real separation, void *user)
{
    hook_log *l = user;
    rg_world *w = l->w;
    (void)normal;
    (void)separation;
    l->calls++;
    rg_vec2 p0 = pos_of(w, a), v0 = vel_of(w, a);
    rg_body nb = 0;
    uint64_t sp = 0;
    int32_t steps = 0;
    rg_status st[] = {
        rg_world_step(w, (rg_real)DT), rg_world_advance(w, (rg_real)DT, &steps),
        rg_world_set_gravity(w, v2(0, 1)), rg_world_set_wind(w, v2(1, 0)),
        rg_world_set_integrator(w, RG_INTEGRATOR_RK4), rg_world_set_fixed_step(w, 0.1f, 2),
        rg_world_set_sleeping(w, 0), rg_world_set_sleep_thresholds(w, 1, 1),
        rg_world_set_solver_iterations(w, 2, 2), rg_world_set_contact_tuning(w, 0.1f, 0.5f, 1, 1),
        rg_world_set_continuous(w, 0), rg_world_set_pre_solve(w, NULL, NULL),
        rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(0, 0), &nb), rg_body_destroy(w, a),
        rg_body_set_mass(w, a, 3), rg_body_set_position(w, a, v2(9, 9)),
        rg_body_set_velocity(w, a, v2(9, 9)), rg_body_apply_force(w, a, v2(9, 9)),
        rg_body_apply_impulse(w, a, v2(9, 9)), rg_body_set_gravity_scale(w, a, 2),
        rg_body_set_drag(w, a, 1, 1), rg_body_set_surface_friction(w, a, 1, 1),
        rg_body_set_speed_limits(w, a, 0, 1), rg_body_set_user_data(w, a, 7),
        rg_spring_create(w, a, b, v2(0, 0), 1, 1, 0, &sp), rg_body_set_circle(w, a, 1),
        rg_body_set_aabb(w, a, 1, 1), rg_body_clear_shape(w, a), rg_body_set_restitution(w, a, 1),
        rg_body_set_friction(w, a, 0), rg_body_set_sensor(w, a, 1), rg_body_set_filter(w, a, 2, 2),
        rg_body_wake(w, a), rg_body_set_one_way(w, a, v2(0, 1)), rg_body_pass_through(w, a, b),
        rg_body_move(w, a, v2(5, 5), 0xFFFFFFFFu, RG_MOVE_SLIDE, NULL, NULL, 0, NULL),
    };
    int ok = 1;
    for (size_t k = 0; k < sizeof st / sizeof st[0]; k++) ok &= st[k] == RG_ERR_LOCKED;
    ok &= nb == 0 && sp == 0;
    rg_vec2 p1 = pos_of(w, a), v1 = vel_of(w, a);
    ok &= p0.x == p1.x && p0.y == p1.y && v0.x == v1.x && v0.y == v1.y;
    rg_world_destroy(w); /* a no-op inside the step */
    l->locked_ok &= ok;
    /* getters and queries work */
    rg_body hits[4];
    rg_ray_hit rh;
    int32_t kind;
    l->getters_ok &= rg_body_get_shape(w, a, &kind, NULL) == RG_OK && rg_body_is_valid(w, b) &&
                     rg_world_query_aabb(w, v2(-1, -1), v2(1, 1), 0xFFFFFFFFu, hits, 4) >= 0 &&
                     rg_world_raycast(w, v2(0, 5), v2(0, -10), 0xFFFFFFFFu, &rh) >= 0 &&
                     rg_world_body_count(w) == 2;
    return 1;
}

static void test_the_world_is_locked_inside_the_hook(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-G);
    floor_of(w);
    circle_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5);
    hook_log l;
    memset(&l, 0, sizeof l);
    l.w = w;
    l.locked_ok = l.getters_ok = 1;
    assert_ok(rg_world_set_pre_solve(w, locked_hook, &l));
    step_n(w, 3, DT);
    assert_true(l.calls >= 3);
    assert_int_equal(l.locked_ok, 1);
    assert_int_equal(l.getters_ok, 1);
    /* unlocked again after the step */
    assert_ok(rg_world_set_gravity(w, v2(0, -1)));
    rg_world_destroy(w);
}

/* The calls come in a fixed order: the sequence of pairs over 120 steps of a small pile,
 * hashed by the creation indices of the bodies, matches a pinned constant (the order of
 * the awake contacts, which the same history always gives). */
static void test_the_hook_is_called_in_a_fixed_order(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-G);
    rg_body bodies[41];
    bodies[0] = floor_of(w);
    for (int i = 0; i < 40; i++) {
        double x = (i % 8) * 1.1 - 4 + 0.01 * (i % 3), y = 1 + (i / 8) * 1.1;
        bodies[1 + i] = i % 2 ? circle_body(w, RG_BODY_DYNAMIC, 1, x, y, 0.5)
                              : box_body(w, RG_BODY_DYNAMIC, 1, x, y, 0.5, 0.5);
    }
    hook_log l;
    memset(&l, 0, sizeof l);
    l.hash = 1469598103934665603ull;
    l.bodies = bodies;
    l.n = 41;
    assert_ok(rg_world_set_pre_solve(w, skip_hook, &l));
    step_n(w, 120, DT);
    printf("  pre-solve calls %d, order hash 0x%016llxull\n", l.calls, (unsigned long long)l.hash);
#ifdef RG_DOUBLE
    assert_true(l.hash == 0x896a81a50867a903ull);
#else
    assert_true(l.hash == 0x80fd8c7c62176bcbull);
#endif
    rg_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_resting_body_has_one_contact_carrying_m_g_dt),
        cmocka_unit_test(test_a_box_pushed_along_the_floor_shows_the_friction_impulse),
        cmocka_unit_test(test_contacts_are_sorted_by_handle_with_sensors_and_capacity),
        cmocka_unit_test(test_contacts_and_hits_come_with_their_padding_zeroed),
        cmocka_unit_test(test_returning_zero_lets_a_pair_pass),
        cmocka_unit_test(test_a_pair_the_hook_skips_is_not_stopped_by_the_sweep),
        cmocka_unit_test(test_a_sleeping_pair_is_asked_once_a_body_of_it_is_woken),
        cmocka_unit_test(test_the_world_is_locked_inside_the_hook),
        cmocka_unit_test(test_the_hook_is_called_in_a_fixed_order),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
