/* test_broadphase.c: the hierarchical hashed grid against brute force, and the world's
 * pair finding against brute force on random scenes. */
#include "testutil.h"

#include "broadphase.h"
#include "mem.h"

#define NB 600

typedef struct box {
    rg_real lx, ly, ux, uy;
    int live;
} box;

/* xorshift: deterministic scenes */
static uint32_t rng_state = 12345u;
static uint32_t rng(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}
static double unit(void) { return (rng() & 0xFFFFFF) / (double)0x1000000; }

/* A box of a random size from 1 mm to 50 m (log-uniform) somewhere in a 200 m field, a few
 * far away (1e6 m) or enormous (1e9 m, past the coarsest level). */
static box random_box(void)
{
    double size = 0.001 * pow(50000.0, unit());
    double cx = unit() * 200 - 100, cy = unit() * 200 - 100;
    uint32_t kind = rng() % 50;
    if (kind == 0) cx += 1e6;
    if (kind == 1) size = 1e9;
    double w = size * (0.2 + unit()), h = size * (0.2 + unit());
    box b;
    b.lx = (rg_real)(cx - w / 2);
    b.ux = (rg_real)(cx + w / 2);
    b.ly = (rg_real)(cy - h / 2);
    b.uy = (rg_real)(cy + h / 2);
    b.live = 1;
    return b;
}

static int overlap(const box *a, rg_real lx, rg_real ly, rg_real ux, rg_real uy)
{
    return a->lx <= ux && lx <= a->ux && a->ly <= uy && ly <= a->uy;
}

typedef struct hits {
    int count[NB];
    int total;
} hits;

static void record(void *p, int32_t slot)
{
    hits *h = p;
    assert_true(slot >= 0 && slot < NB);
    h->count[slot]++;
    h->total++;
}

/* Every query finds exactly the live boxes brute force finds, each once. */
static void check_queries(const broadphase *bp, const box *boxes, int nq)
{
    for (int q = 0; q < nq; q++) {
        box qb = q < NB && boxes[q].live ? boxes[q] : random_box();
        hits h;
        memset(&h, 0, sizeof h);
        broadphase_query(bp, qb.lx, qb.ly, qb.ux, qb.uy, record, &h);
        for (int s = 0; s < NB; s++) {
            int expect = boxes[s].live && overlap(&boxes[s], qb.lx, qb.ly, qb.ux, qb.uy);
            if (h.count[s] != expect)
                fail_msg("query %d: slot %d visited %d times, brute force says %d", q, s, h.count[s], expect);
        }
    }
}

static rg_mem test_mem(test_alloc *ta)
{
    rg_mem m;
    m.fn = test_alloc_fn;
    m.user = ta;
    m.locked = NULL; /* no world */
    m.err = NULL;
    return m;
}

static void test_queries_find_exactly_what_brute_force_finds(void **state)
{
    (void)state;
    test_alloc ta = {0, 0, 0, 0};
    rg_mem m = test_mem(&ta);
    broadphase bp;
    memset(&bp, 0, sizeof bp);
    static box boxes[NB];
    for (int s = 0; s < NB; s++) {
        boxes[s] = random_box();
        assert_ok(broadphase_reserve(&bp, &m, s + 1, bp.count + 1));
        broadphase_insert(&bp, s, boxes[s].lx, boxes[s].ly, boxes[s].ux, boxes[s].uy);
    }
    check_queries(&bp, boxes, 300);
    /* move a third, remove a sixth, and check again */
    for (int s = 0; s < NB; s += 3) {
        boxes[s] = random_box();
        broadphase_move(&bp, s, boxes[s].lx, boxes[s].ly, boxes[s].ux, boxes[s].uy);
    }
    for (int s = 1; s < NB; s += 6) {
        broadphase_remove(&bp, s);
        boxes[s].live = 0;
    }
    check_queries(&bp, boxes, 300);
    /* small moves that stay in the same cell, then everything back in */
    for (int s = 2; s < NB; s += 3) {
        rg_real e = (boxes[s].ux - boxes[s].lx) * (rg_real)0.001;
        boxes[s].lx += e;
        boxes[s].ux += e;
        broadphase_move(&bp, s, boxes[s].lx, boxes[s].ly, boxes[s].ux, boxes[s].uy);
    }
    for (int s = 1; s < NB; s += 6) {
        boxes[s] = random_box();
        broadphase_insert(&bp, s, boxes[s].lx, boxes[s].ly, boxes[s].ux, boxes[s].uy);
    }
    check_queries(&bp, boxes, 300);
    broadphase_release(&bp, &m);
    assert_int_equal(ta.live_blocks, 0);
}

static void test_boxes_at_a_point_and_far_beyond_the_clamp_are_found(void **state)
{
    (void)state;
    rg_mem m = {mem_default_alloc, NULL, NULL, NULL};
    broadphase bp;
    memset(&bp, 0, sizeof bp);
    static box boxes[NB];
    memset(boxes, 0, sizeof boxes);
    /* 40 tiny boxes stacked at one point, 40 beyond the clamped cell range on every side */
    for (int s = 0; s < 80; s++) {
        double c = s < 40 ? 0.5 : (s % 2 ? 3e10 : -3e10);
        double cy = s < 40 ? 0 : (s % 4 < 2 ? 3e10 : -3e10);
        box b;
        b.lx = (rg_real)(c - 0.01);
        b.ux = (rg_real)(c + 0.01 + s * 1e-3);
        b.ly = (rg_real)(cy - 0.01);
        b.uy = (rg_real)(cy + 0.01);
        b.live = 1;
        boxes[s] = b;
        assert_ok(broadphase_reserve(&bp, &m, s + 1, bp.count + 1));
        broadphase_insert(&bp, s, b.lx, b.ly, b.ux, b.uy);
    }
    check_queries(&bp, boxes, 80);
    broadphase_release(&bp, &m);
}

/* broadphase_locate_boxes (a snapshot's restore: eight boxes at a time where the CPU has
 * AVX2) gives every box the level and key that inserting it gives, bit for bit: on boxes at
 * the edges of the arithmetic (extents exactly at a level's fit and one ulp past it, powers
 * of two, subnormal, zero, negative, NaN and infinite extents; corners on cell boundaries,
 * negative ones, exactly at the clamp and past it) and on random ones, in a count that
 * leaves a tail of fewer than eight. */
#define LOCATE_N (8 * 40 + 5)
static void test_located_boxes_have_the_level_and_key_an_insert_gives(void **state)
{
    (void)state;
    rg_mem m = {mem_default_alloc, NULL, NULL, NULL};
    broadphase bp;
    memset(&bp, 0, sizeof bp);
    static rg_real boxes[4 * LOCATE_N];
    int16_t level[LOCATE_N];
    uint64_t key[LOCATE_N];
    rg_real ext[40];
    int ne = 0;
    for (int l = -12; l <= 21; l += 3) {
        rg_real fit = (rg_real)ldexp(0.99609375, l), pow2 = (rg_real)ldexp(1.0, l);
        ext[ne++] = fit;
#ifdef RG_DOUBLE
        ext[ne++] = nextafter(fit, INFINITY);
#else
        ext[ne++] = nextafterf(fit, INFINITY);
#endif
        ext[ne++] = pow2;
    }
    ext[ne - 3] = 0; /* past the top level's fit: huge, and below */
    ext[ne - 2] = (rg_real)1e-40; /* subnormal in float */
    ext[ne - 1] = -1;
    const rg_real corner[] = {0, -0.0f, 0.5f, -0.5f, -1, 3, -3e10f, 3e10f, 268435456.0f, -268435456.0f,
                              (rg_real)ldexp(1.0, 18), -(rg_real)ldexp(1.0, 18), 1e-3f, -1e-3f, 12345.678f};
    const int nc = (int)(sizeof corner / sizeof corner[0]);
    for (int k = 0; k < LOCATE_N; k++) {
        rg_real lx, ly, w, h;
        if (k < 200) {
            lx = corner[k % nc];
            ly = corner[(k / nc + k) % nc];
            w = ext[k % ne];
            h = ext[(k * 7) % ne];
        } else if (k < 210) {
            lx = k % 2 ? NAN : 0;
            ly = k % 3 ? -INFINITY : 1;
            w = k % 4 ? INFINITY : 1;
            h = 1;
        } else {
            box b = random_box();
            lx = b.lx;
            ly = b.ly;
            w = b.ux - b.lx;
            h = b.uy - b.ly;
        }
        boxes[4 * k] = lx;
        boxes[4 * k + 1] = ly;
        boxes[4 * k + 2] = lx + w;
        boxes[4 * k + 3] = ly + h;
    }
    broadphase_locate_boxes(boxes, LOCATE_N, level, key);
    assert_ok(broadphase_reserve(&bp, &m, LOCATE_N, LOCATE_N));
    int levels_seen = 0, huge = 0;
    for (int k = 0; k < LOCATE_N; k++) {
        broadphase_insert(&bp, k, boxes[4 * k], boxes[4 * k + 1], boxes[4 * k + 2], boxes[4 * k + 3]);
        if (level[k] != bp.e[k].level || key[k] != bp.e[k].key)
            fail_msg("box %d (%g %g %g %g): located at level %d key %llx, inserted at %d key %llx", k,
                     (double)boxes[4 * k], (double)boxes[4 * k + 1], (double)boxes[4 * k + 2], (double)boxes[4 * k + 3],
                     level[k], (unsigned long long)key[k], bp.e[k].level, (unsigned long long)bp.e[k].key);
        if (level[k] == BP_HUGE) huge++;
        else levels_seen |= 1 << (level[k] % 31);
    }
    /* the edges reached what they aim at: huge boxes, and boxes at many levels */
    assert_true(huge >= 10);
    int distinct = 0;
    for (int l = 0; l < 31; l++) distinct += (levels_seen >> l) & 1;
    assert_true(distinct >= 10);
    broadphase_release(&bp, &m);
}

static void test_non_finite_boxes_go_to_the_huge_list_and_match_nothing(void **state)
{
    (void)state;
    rg_mem m = {mem_default_alloc, NULL, NULL, NULL};
    broadphase bp;
    memset(&bp, 0, sizeof bp);
    assert_ok(broadphase_reserve(&bp, &m, 3, 3));
    broadphase_insert(&bp, 0, NAN, 0, NAN, 1);
    broadphase_insert(&bp, 1, -INFINITY, -1, INFINITY, 1);
    broadphase_insert(&bp, 2, 0, 0, 1, 1);
    assert_int_equal(bp.n_huge, 2);
    hits h;
    memset(&h, 0, sizeof h);
    broadphase_query(&bp, -1, -1, 2, 2, record, &h);
    assert_int_equal(h.count[0], 0); /* NaN never overlaps */
    assert_int_equal(h.count[1], 1); /* an infinite box overlaps what it spans */
    assert_int_equal(h.count[2], 1);
    broadphase_move(&bp, 0, 5, 5, 6, 6); /* back to a finite box: out of the huge list */
    assert_int_equal(bp.n_huge, 1);
    memset(&h, 0, sizeof h);
    broadphase_query(&bp, 4, 4, 5.5f, 5.5f, record, &h);
    assert_int_equal(h.count[0], 1);
    broadphase_remove(&bp, 1);
    assert_int_equal(bp.n_huge, 0);
    broadphase_release(&bp, &m);
}

typedef struct ray_hits {
    int seen[NB];
} ray_hits;

static rg_real ray_record(void *p, int32_t slot, rg_real max_t)
{
    ray_hits *r = p;
    r->seen[slot] = 1;
    return max_t; /* never prune: every candidate along the whole ray */
}

/* Segment against box, for brute force. */
static int segment_hits(const box *b, rg_vec2 o, rg_vec2 d)
{
    double t0 = 0, t1 = 1;
    double os[2] = {(double)o.x, (double)o.y}, ds[2] = {(double)d.x, (double)d.y};
    double lo[2] = {(double)b->lx, (double)b->ly}, hi[2] = {(double)b->ux, (double)b->uy};
    for (int k = 0; k < 2; k++) {
        if (ds[k] == 0) {
            if (os[k] < lo[k] || os[k] > hi[k]) return 0;
            continue;
        }
        double a = (lo[k] - os[k]) / ds[k], c = (hi[k] - os[k]) / ds[k];
        if (a > c) { double t = a; a = c; c = t; }
        if (a > t0) t0 = a;
        if (c < t1) t1 = c;
        if (t0 > t1) return 0;
    }
    return 1;
}

static void test_raycast_visits_every_box_the_segment_meets(void **state)
{
    (void)state;
    rg_mem m = {mem_default_alloc, NULL, NULL, NULL};
    broadphase bp;
    memset(&bp, 0, sizeof bp);
    static box boxes[NB];
    for (int s = 0; s < NB; s++) {
        boxes[s] = random_box();
        assert_ok(broadphase_reserve(&bp, &m, s + 1, bp.count + 1));
        broadphase_insert(&bp, s, boxes[s].lx, boxes[s].ly, boxes[s].ux, boxes[s].uy);
    }
    for (int q = 0; q < 200; q++) {
        rg_vec2 o = v2(unit() * 240 - 120, unit() * 240 - 120);
        double len = q % 4 == 0 ? 500 : unit() * 30;
        double ang = unit() * 6.2831853;
        rg_vec2 d = v2(len * cos(ang), len * sin(ang));
        if (q % 10 == 0) d = v2(len, 0); /* axis-aligned */
        static ray_hits r;
        memset(&r, 0, sizeof r);
        broadphase_raycast(&bp, o, d, ray_record, &r);
        for (int s = 0; s < NB; s++)
            if (segment_hits(&boxes[s], o, d) && !r.seen[s])
                fail_msg("ray %d missed box %d", q, s);
    }
    broadphase_release(&bp, &m);
}

static void test_reserve_that_fails_changes_nothing(void **state)
{
    (void)state;
    test_alloc ta = {0, 0, 0, 0};
    rg_mem m = test_mem(&ta);
    broadphase bp;
    memset(&bp, 0, sizeof bp);
    assert_ok(broadphase_reserve(&bp, &m, 10, 10));
    broadphase_insert(&bp, 3, 0, 0, 1, 1);
    broadphase before = bp;
    ta.fail_at = ta.calls + 1;
    assert_status(broadphase_reserve(&bp, &m, 100000, 100000), RG_ERR_OUT_OF_MEMORY);
    assert_memory_equal(&bp, &before, sizeof bp);
    ta.fail_at = ta.calls + 5; /* a later allocation of the same reserve fails */
    assert_status(broadphase_reserve(&bp, &m, 100000, 100000), RG_ERR_OUT_OF_MEMORY);
    assert_memory_equal(&bp, &before, sizeof bp);
    ta.fail_at = 0;
    hits h;
    memset(&h, 0, sizeof h);
    broadphase_query(&bp, 0, 0, 1, 1, record, &h);
    assert_int_equal(h.count[3], 1);
    broadphase_release(&bp, &m);
    assert_int_equal(ta.live_blocks, 0);
}

/* ---------------------------------------------------------------- the world's pairs */

typedef struct shape_rec {
    int32_t kind;
    double x, y, hx, hy;
    rg_body h;
} shape_rec;

/* The same tests the library makes, in its precision. */
static int shapes_touch(const shape_rec *a, const shape_rec *b)
{
    rg_real ax = (rg_real)a->x, ay = (rg_real)a->y, bx = (rg_real)b->x, by = (rg_real)b->y;
    if (a->kind == RG_SHAPE_CIRCLE && b->kind == RG_SHAPE_CIRCLE) {
        rg_real dx = bx - ax, dy = by - ay, r = (rg_real)a->hx + (rg_real)b->hx;
        return dx * dx + dy * dy <= r * r;
    }
    if (a->kind == RG_SHAPE_AABB && b->kind == RG_SHAPE_AABB)
        return fabs((double)(bx - ax)) <= a->hx + b->hx && fabs((double)(by - ay)) <= a->hy + b->hy;
    const shape_rec *c = a->kind == RG_SHAPE_CIRCLE ? a : b, *q = a->kind == RG_SHAPE_CIRCLE ? b : a;
    rg_real px = (rg_real)c->x - (rg_real)q->x, py = (rg_real)c->y - (rg_real)q->y;
    rg_real hx = (rg_real)q->hx, hy = (rg_real)q->hy;
    rg_real cx = px < -hx ? -hx : (px > hx ? hx : px), cy = py < -hy ? -hy : (py > hy ? hy : py);
    rg_real ex = px - cx, ey = py - cy, r = (rg_real)c->hx;
    return ex * ex + ey * ey <= r * r;
}

/* Random scenes of sensors at rest (no gravity): after one step the begin events are the
 * overlapping pairs, which brute force lists. */
static void test_world_pairs_match_brute_force_on_random_scenes(void **state)
{
    (void)state;
    enum { N = 300 };
    static shape_rec s[N];
    for (int scene = 0; scene < 6; scene++) {
        rg_world *w;
        assert_ok(rg_world_create(&w));
        double field = 10 + scene * 8;
        for (int i = 0; i < N; i++) {
            s[i].kind = rng() % 2 ? RG_SHAPE_CIRCLE : RG_SHAPE_AABB;
            double size = 0.05 * pow(40.0, unit());
            s[i].hx = size;
            s[i].hy = s[i].kind == RG_SHAPE_CIRCLE ? size : size * (0.3 + unit());
            s[i].x = (double)(rg_real)(unit() * field);
            s[i].y = (double)(rg_real)(unit() * field);
            s[i].hx = (double)(rg_real)s[i].hx;
            s[i].hy = (double)(rg_real)s[i].hy;
            int32_t type = i % 7 == 0 ? RG_BODY_STATIC : RG_BODY_DYNAMIC;
            assert_ok(rg_body_create(w, type, 1, v2(s[i].x, s[i].y), &s[i].h));
            if (s[i].kind == RG_SHAPE_CIRCLE)
                assert_ok(rg_body_set_circle(w, s[i].h, (rg_real)s[i].hx));
            else
                assert_ok(rg_body_set_aabb(w, s[i].h, (rg_real)s[i].hx, (rg_real)s[i].hy));
            assert_ok(rg_body_set_sensor(w, s[i].h, 1));
        }
        assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
        int32_t n = rg_world_get_contact_events(w, NULL, 0);
        rg_contact_event *ev = calloc((size_t)n + 1, sizeof *ev);
        assert_int_equal(rg_world_get_contact_events(w, ev, n), n);
        int expect = 0;
        for (int i = 0; i < N; i++) {
            for (int j = i + 1; j < N; j++) {
                int both_static = i % 7 == 0 && j % 7 == 0;
                if (both_static || !shapes_touch(&s[i], &s[j])) continue;
                expect++;
                rg_body a = s[i].h < s[j].h ? s[i].h : s[j].h, b = s[i].h < s[j].h ? s[j].h : s[i].h;
                int found = 0;
                for (int k = 0; k < n; k++) found += ev[k].a == a && ev[k].b == b && ev[k].kind == RG_CONTACT_BEGIN;
                if (found != 1) fail_msg("scene %d: pair %d-%d found %d times", scene, i, j, found);
            }
        }
        assert_int_equal(n, expect);
        assert_int_equal(rg_world_touching_count(w), expect);
        free(ev);
        rg_world_destroy(w);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_queries_find_exactly_what_brute_force_finds),
        cmocka_unit_test(test_boxes_at_a_point_and_far_beyond_the_clamp_are_found),
        cmocka_unit_test(test_non_finite_boxes_go_to_the_huge_list_and_match_nothing),
        cmocka_unit_test(test_located_boxes_have_the_level_and_key_an_insert_gives),
        cmocka_unit_test(test_raycast_visits_every_box_the_segment_meets),
        cmocka_unit_test(test_reserve_that_fails_changes_nothing),
        cmocka_unit_test(test_world_pairs_match_brute_force_on_random_scenes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
