/* test_draw.c: rg_world_draw against the state it draws. */
#include "testutil.h"

enum { MAXC = 512 };

typedef struct call {
    char kind;          /* 'c' circle, 'b' box, 's' segment, 'p' point */
    rg_body body;
    rg_vec2 a, b;       /* centre or lower corner or segment start; upper corner or end */
    rg_real r;
    uint32_t rgba;
} call;

typedef struct calls {
    call c[MAXC];
    int n;
} calls;

/* Member by member, so the padding stays zero and two lists compare with memcmp (a struct
 * copy may carry the stack's garbage in it, as clang's does). */
static void put(calls *l, call c)
{
    assert_true(l->n < MAXC);
    call *d = &l->c[l->n++];
    memset(d, 0, sizeof *d);
    d->kind = c.kind;
    d->body = c.body;
    d->a = c.a;
    d->b = c.b;
    d->r = c.r;
    d->rgba = c.rgba;
}

static void on_circle(rg_body body, rg_vec2 center, rg_real radius, uint32_t rgba, void *user)
{
    call c = { 'c', body, center, center, radius, rgba };
    put(user, c);
}

static void on_box(rg_body body, rg_vec2 lower, rg_vec2 upper, uint32_t rgba, void *user)
{
    call c = { 'b', body, lower, upper, 0, rgba };
    put(user, c);
}

static void on_segment(rg_vec2 a, rg_vec2 b, uint32_t rgba, void *user)
{
    call c = { 's', 0, a, b, 0, rgba };
    put(user, c);
}

static void on_point(rg_vec2 p, uint32_t rgba, void *user)
{
    call c = { 'p', 0, p, p, 0, rgba };
    put(user, c);
}

static int draw(rg_world *w, uint32_t flags, calls *l)
{
    rg_debug_draw d = { on_circle, on_box, on_segment, on_point, flags, l };
    l->n = 0;
    return rg_world_draw(w, &d);
}

typedef struct fixture {
    rg_world *w;
    rg_body floor, plat, coin, ball, crate, dot, sleeper;
} fixture;

/* A floor, a kinematic platform, a sensor coin, a falling ball and crate, a body without a
 * shape, and a box that has fallen asleep on the floor far from the rest. */
static void make_fixture(fixture *f)
{
    f->w = gravity_world(-10);
    f->floor = box_body(f->w, RG_BODY_STATIC, 0, 0, -0.5, 20, 0.5);
    f->plat = box_body(f->w, RG_BODY_KINEMATIC, 0, -5, 2, 1, 0.1);
    assert_ok(rg_body_set_velocity(f->w, f->plat, v2(1, 0)));
    f->coin = circle_body(f->w, RG_BODY_STATIC, 0, 3, 1, 0.3);
    assert_ok(rg_body_set_sensor(f->w, f->coin, 1));
    f->sleeper = box_body(f->w, RG_BODY_DYNAMIC, 1, 15, 0.5, 0.5, 0.5);
    for (int k = 0; k < 90; k++) assert_ok(rg_world_step(f->w, (rg_real)(1.0 / 60)));
    int32_t awake;
    assert_ok(rg_body_is_awake(f->w, f->sleeper, &awake));
    assert_int_equal(awake, 0);
    f->ball = circle_body(f->w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5);
    f->crate = box_body(f->w, RG_BODY_DYNAMIC, 2, 3, 3, 0.4, 0.4);
    f->dot = make_body(f->w, 1, -8, 8);
    assert_ok(rg_world_step(f->w, (rg_real)(1.0 / 60)));
}

static const call *find(const calls *l, char kind, rg_body body, int *count)
{
    const call *hit = NULL;
    *count = 0;
    for (int k = 0; k < l->n; k++)
        if (l->c[k].kind == kind && l->c[k].body == body) {
            hit = &l->c[k];
            (*count)++;
        }
    return hit;
}

static void test_every_shape_is_drawn_once_with_its_body_and_state_colour(void **state)
{
    (void)state;
    fixture f;
    make_fixture(&f);
    calls *l = calloc(1, sizeof *l);
    assert_ok(draw(f.w, RG_DRAW_SHAPES, l));
    struct { rg_body b; char kind; uint32_t col; } want[] = {
        { f.floor, 'b', RG_COLOR_STATIC },   { f.plat, 'b', RG_COLOR_KINEMATIC },
        { f.coin, 'c', RG_COLOR_SENSOR },    { f.sleeper, 'b', RG_COLOR_SLEEPING },
        { f.ball, 'c', RG_COLOR_AWAKE },     { f.crate, 'b', RG_COLOR_AWAKE },
    };
    for (size_t k = 0; k < sizeof want / sizeof want[0]; k++) {
        int n;
        const call *c = find(l, want[k].kind, want[k].b, &n);
        assert_int_equal(n, 1);
        assert_int_equal(c->rgba, want[k].col);
        rg_vec2 p = pos_of(f.w, want[k].b), h;
        int32_t kind;
        assert_ok(rg_body_get_shape(f.w, want[k].b, &kind, &h));
        if (kind == RG_SHAPE_CIRCLE) {
            assert_true(c->a.x == p.x && c->a.y == p.y && c->r == h.x);
        } else {
            assert_true(c->a.x == p.x - h.x && c->a.y == p.y - h.y);
            assert_true(c->b.x == p.x + h.x && c->b.y == p.y + h.y);
        }
    }
    /* six shapes and the shapeless body as one point at its position */
    assert_int_equal(l->n, 7);
    assert_int_equal(l->c[6].kind, 'p');
    rg_vec2 dp = pos_of(f.w, f.dot);
    assert_true(l->c[6].a.x == dp.x && l->c[6].a.y == dp.y);
    assert_int_equal(l->c[6].rgba, RG_COLOR_AWAKE);
    free(l);
    rg_world_destroy(f.w);
}

/* The points are where the events put the touching contacts, the normals of unit direction
 * and RG_DRAW_NORMAL_LENGTH long, from a toward b. */
static void test_contacts_match_the_touching_contacts_of_the_events(void **state)
{
    (void)state;
    fixture f;
    make_fixture(&f);
    calls *l = calloc(1, sizeof *l);
    rg_contact_event ev[64];
    /* the ball starts on the floor: its contact begins in the first step and stays */
    int32_t n = rg_world_get_contact_events(f.w, ev, 64);
    int begins = 0;
    for (int32_t k = 0; k < n; k++) begins += ev[k].kind == RG_CONTACT_BEGIN && !ev[k].sensor;
    assert_int_equal(rg_world_touching_count(f.w), 2); /* ball and sleeper on the floor */
    assert_int_equal(begins, 1);
    assert_ok(draw(f.w, RG_DRAW_CONTACTS, l));
    assert_int_equal(l->n, 2 * rg_world_touching_count(f.w));
    int matched = 0;
    for (int k = 0; k + 1 < l->n; k += 2) {
        const call *pt = &l->c[k], *nm = &l->c[k + 1];
        assert_int_equal(pt->kind, 'p');
        assert_int_equal(nm->kind, 's');
        assert_true(nm->a.x == pt->a.x && nm->a.y == pt->a.y);
        double dx = (double)(nm->b.x - nm->a.x), dy = (double)(nm->b.y - nm->a.y);
        assert_near(sqrt(dx * dx + dy * dy), RG_DRAW_NORMAL_LENGTH, 1e-5);
        for (int32_t e = 0; e < n; e++) {
            if (ev[e].kind != RG_CONTACT_BEGIN || ev[e].sensor) continue;
            if (ev[e].point.x == pt->a.x && ev[e].point.y == pt->a.y) {
                assert_near(dx / RG_DRAW_NORMAL_LENGTH, ev[e].normal.x, 1e-5);
                assert_near(dy / RG_DRAW_NORMAL_LENGTH, ev[e].normal.y, 1e-5);
                matched++;
            }
        }
    }
    assert_int_equal(matched, 1);
    free(l);
    rg_world_destroy(f.w);
}

/* A contact that persists while its box slides is drawn where the shapes touch now, as
 * rg_body_get_contacts reports it (it was drawn where the narrowphase first stored it: 0.45 m
 * behind a box sliding at 3 m/s for 10 steps). */
static void test_a_sliding_contact_is_drawn_where_it_is_now(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-20);
    rg_body floor = box_body(w, RG_BODY_STATIC, 0, 0, -0.5, 10, 0.5);
    rg_body box = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.4, 0.4, 0.4);
    assert_ok(rg_body_set_friction(w, box, 0));
    assert_ok(rg_body_set_friction(w, floor, 0));
    for (int k = 0; k < 30; k++) assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
    assert_ok(rg_body_set_velocity(w, box, v2(-3, 0)));
    for (int k = 0; k < 10; k++) assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
    rg_contact c[4];
    assert_int_equal(rg_body_get_contacts(w, box, c, 4), 1);
    calls *l = calloc(1, sizeof *l);
    assert_ok(draw(w, RG_DRAW_CONTACTS, l));
    assert_int_equal(l->n, 2);
    assert_true(l->c[0].a.x == c[0].point.x && l->c[0].a.y == c[0].point.y);
    /* and under the box: within its half width of its centre */
    assert_true(fabs((double)(l->c[0].a.x - pos_of(w, box).x)) <= 0.4);
    free(l);
    rg_world_destroy(w);
}

static void test_bounds_contain_their_shapes_and_velocities_point_along_v(void **state)
{
    (void)state;
    fixture f;
    make_fixture(&f);
    calls *l = calloc(1, sizeof *l);
    assert_ok(draw(f.w, RG_DRAW_BOUNDS, l));
    assert_int_equal(l->n, 6); /* the six shaped bodies */
    for (int k = 0; k < l->n; k++) {
        const call *c = &l->c[k];
        assert_int_equal(c->kind, 'b');
        assert_int_equal(c->rgba, RG_COLOR_BOUNDS);
        rg_vec2 p = pos_of(f.w, c->body), h;
        assert_ok(rg_body_get_shape(f.w, c->body, NULL, &h));
        assert_true(c->a.x <= p.x - h.x && c->a.y <= p.y - h.y);
        assert_true(c->b.x >= p.x + h.x && c->b.y >= p.y + h.y);
    }
    assert_ok(draw(f.w, RG_DRAW_VELOCITIES, l));
    /* moving: the platform, the crate (falling) and the dot; the ball rests, the sleeper sleeps */
    assert_int_equal(l->n, 3);
    for (int k = 0; k < l->n; k++) assert_int_equal(l->c[k].rgba, RG_COLOR_VELOCITY);
    rg_vec2 v = vel_of(f.w, f.plat), p = pos_of(f.w, f.plat);
    assert_true(l->c[0].a.x == p.x && l->c[0].a.y == p.y);
    assert_near(l->c[0].b.x - l->c[0].a.x, (double)v.x * RG_DRAW_VELOCITY_SCALE, 1e-6);
    free(l);
    rg_world_destroy(f.w);
}

static void test_springs_are_drawn_between_their_ends(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body a = make_body(w, 1, 0, 0), b = make_body(w, 1, 2, 0);
    uint64_t s1, s2;
    assert_ok(rg_spring_create(w, a, b, v2(0, 0), 1, 10, 0, &s1));
    assert_ok(rg_spring_create(w, b, 0, v2(5, 5), 1, 10, 0, &s2));
    calls *l = calloc(1, sizeof *l);
    assert_ok(draw(w, RG_DRAW_SPRINGS, l));
    assert_int_equal(l->n, 2);
    assert_true(l->c[0].a.x == 0 && l->c[0].b.x == 2);
    assert_true(l->c[1].a.x == 2 && l->c[1].b.x == 5 && l->c[1].b.y == 5);
    assert_int_equal(l->c[1].rgba, RG_COLOR_SPRING);
    free(l);
    rg_world_destroy(w);
}

static void test_order_is_fixed_and_null_callbacks_are_skipped(void **state)
{
    (void)state;
    fixture f;
    make_fixture(&f);
    calls *l1 = calloc(1, sizeof *l1), *l2 = calloc(1, sizeof *l2);
    uint32_t all = RG_DRAW_SHAPES | RG_DRAW_CONTACTS | RG_DRAW_VELOCITIES | RG_DRAW_BOUNDS | RG_DRAW_SPRINGS;
    assert_ok(draw(f.w, all, l1));
    assert_ok(draw(f.w, all, l2));
    assert_int_equal(l1->n, l2->n);
    assert_memory_equal(l1->c, l2->c, (size_t)l1->n * sizeof(call));
    /* layers: every shape before any bound, contacts last */
    assert_int_equal(l1->c[0].body, f.floor);
    assert_int_equal(l1->c[l1->n - 1].kind, 's');
    rg_debug_draw d = { NULL, on_box, NULL, NULL, RG_DRAW_SHAPES | RG_DRAW_CONTACTS | RG_DRAW_VELOCITIES, l1 };
    l1->n = 0;
    assert_ok(rg_world_draw(f.w, &d));
    assert_int_equal(l1->n, 4); /* the boxes alone */
    for (int k = 0; k < l1->n; k++) assert_int_equal(l1->c[k].kind, 'b');
    rg_debug_draw none = { NULL, NULL, NULL, NULL, all, NULL };
    assert_ok(rg_world_draw(f.w, &none));
    free(l1);
    free(l2);
    rg_world_destroy(f.w);
}

static void test_bad_arguments_are_rejected(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    calls *l = calloc(1, sizeof *l);
    rg_debug_draw d = { on_circle, on_box, on_segment, on_point, RG_DRAW_SHAPES, l };
    assert_status(rg_world_draw(NULL, &d), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_draw(w, NULL), RG_ERR_INVALID_ARGUMENT);
    d.flags = 32u;
    assert_status(rg_world_draw(w, &d), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(l->n, 0);
    d.flags = 0; /* nothing asked: nothing drawn */
    make_body(w, 1, 0, 0);
    assert_ok(rg_world_draw(w, &d));
    assert_int_equal(l->n, 0);
    free(l);
    rg_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_shape_is_drawn_once_with_its_body_and_state_colour),
        cmocka_unit_test(test_contacts_match_the_touching_contacts_of_the_events),
        cmocka_unit_test(test_a_sliding_contact_is_drawn_where_it_is_now),
        cmocka_unit_test(test_bounds_contain_their_shapes_and_velocities_point_along_v),
        cmocka_unit_test(test_springs_are_drawn_between_their_ends),
        cmocka_unit_test(test_order_is_fixed_and_null_callbacks_are_skipped),
        cmocka_unit_test(test_bad_arguments_are_rejected),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
