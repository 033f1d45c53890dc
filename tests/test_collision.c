/* test_collision.c: the pure shape tests of src/collision.c (manifolds, rays, time of impact). */
#include "testutil.h"

#include "collision.h"

/* rounding of one or two operations on numbers of order 1..10 */
#define TOL (64 * REAL_EPS)

static void assert_vec(rg_vec2 v, double x, double y, double tol)
{
    assert_near(v.x, x, tol);
    assert_near(v.y, y, tol);
}

/* ---------------------------------------------------------------- circle-circle */

static void test_circle_circle_overlap_gives_normal_depth_and_midpoint(void **state)
{
    (void)state;
    coll_manifold m;
    /* centres 1.5 apart along x, radii 1 and 1: depth 0.5 */
    assert_int_equal(coll_circle_circle(v2(0, 0), 1, v2(1.5, 0), 1, &m), 1);
    assert_vec(m.normal, 1, 0, TOL);
    assert_near(m.depth, 0.5, TOL);
    /* surfaces at x = 1 (a) and x = 0.5 (b): halfway 0.75 */
    assert_vec(m.point, 0.75, 0, TOL);
}

static void test_circle_circle_separated_reports_the_gap_as_negative_depth(void **state)
{
    (void)state;
    coll_manifold m;
    /* 3-4-5 triangle: centres 5 apart, radii 1 + 2: gap 2 */
    assert_int_equal(coll_circle_circle(v2(1, 1), 1, v2(4, 5), 2, &m), 0);
    assert_vec(m.normal, 0.6, 0.8, TOL);
    assert_near(m.depth, -2, TOL);
}

static void test_circle_circle_is_antisymmetric_in_its_arguments(void **state)
{
    (void)state;
    coll_manifold m1, m2;
    coll_circle_circle(v2(0.3, -0.2), 0.7, v2(1.1, 0.4), 0.5, &m1);
    coll_circle_circle(v2(1.1, 0.4), 0.5, v2(0.3, -0.2), 0.7, &m2);
    assert_vec(m2.normal, -(double)m1.normal.x, -(double)m1.normal.y, TOL);
    assert_near(m2.depth, m1.depth, TOL);
    assert_vec(m2.point, (double)m1.point.x, (double)m1.point.y, TOL);
}

static void test_circle_circle_coincident_centres_push_along_plus_y(void **state)
{
    (void)state;
    coll_manifold m;
    assert_int_equal(coll_circle_circle(v2(2, 3), 0.5, v2(2, 3), 0.25, &m), 1);
    assert_vec(m.normal, 0, 1, 0);
    assert_near(m.depth, 0.75, TOL);
}

static void test_circle_circle_exact_touch_counts_as_touching(void **state)
{
    (void)state;
    coll_manifold m;
    assert_int_equal(coll_circle_circle(v2(0, 0), 1, v2(0, 2), 1, &m), 1);
    assert_near(m.depth, 0, 0);
}

/* ---------------------------------------------------------------- box-box */

static void test_aabb_aabb_uses_the_axis_of_least_penetration(void **state)
{
    (void)state;
    coll_manifold m;
    /* overlap 0.2 in x, 1.5 in y: x axis, b to the right */
    assert_int_equal(coll_aabb_aabb(v2(0, 0), v2(1, 1), v2(1.8, 0.5), v2(1, 1), &m), 1);
    assert_vec(m.normal, 1, 0, 0);
    assert_near(m.depth, 0.2, TOL);
    /* the point: halfway between the faces x = 1 and x = 0.8, mid of y overlap [-0.5, 1] */
    assert_vec(m.point, 0.9, 0.25, TOL);
    /* overlap 1.9 in x, 0.3 in y, b below: -y */
    assert_int_equal(coll_aabb_aabb(v2(0, 0), v2(1, 1), v2(0.1, -1.7), v2(1, 1), &m), 1);
    assert_vec(m.normal, 0, -1, 0);
    assert_near(m.depth, 0.3, TOL);
}

static void test_aabb_aabb_tie_goes_to_the_y_axis(void **state)
{
    (void)state;
    coll_manifold m;
    coll_aabb_aabb(v2(0, 0), v2(1, 1), v2(1.5, 1.5), v2(1, 1), &m);
    assert_vec(m.normal, 0, 1, 0);
    assert_near(m.depth, 0.5, TOL);
}

static void test_aabb_aabb_separated_gives_the_most_separating_axis(void **state)
{
    (void)state;
    coll_manifold m;
    /* gap 3 in x, 0.5 in y: x separates most; depth -3 is a valid separating distance */
    assert_int_equal(coll_aabb_aabb(v2(0, 0), v2(1, 1), v2(5, 2.5), v2(1, 0.5), &m), 0);
    assert_vec(m.normal, 1, 0, 0);
    assert_near(m.depth, -3, TOL);
}

/* ---------------------------------------------------------------- circle-box */

static void test_circle_aabb_face_contact(void **state)
{
    (void)state;
    coll_manifold m;
    /* circle r 0.5 above a box of half extents (2, 1): centre 1.4 above its centre */
    assert_int_equal(coll_circle_aabb(v2(0.3, 1.4), 0.5, v2(0, 0), v2(2, 1), &m), 1);
    assert_vec(m.normal, 0, -1, TOL); /* circle -> box */
    assert_near(m.depth, 0.1, TOL);
    assert_vec(m.point, 0.3, 0.95, TOL);
}

static void test_circle_aabb_corner_contact_uses_the_corner_distance(void **state)
{
    (void)state;
    coll_manifold m;
    /* box corner (1, 1); circle centre (1.3, 1.4): distance 0.5 */
    assert_int_equal(coll_circle_aabb(v2(1.3, 1.4), 0.6, v2(0, 0), v2(1, 1), &m), 1);
    assert_vec(m.normal, -0.6, -0.8, TOL);
    assert_near(m.depth, 0.1, TOL);
    /* beyond the corner reach: a gap, still measured from the corner */
    assert_int_equal(coll_circle_aabb(v2(1.3, 1.4), 0.4, v2(0, 0), v2(1, 1), &m), 0);
    assert_near(m.depth, -0.1, TOL);
}

static void test_circle_aabb_centre_inside_is_pushed_out_through_the_nearest_face(void **state)
{
    (void)state;
    coll_manifold m;
    /* centre 0.2 inside the right face (x = 1): depth r + 0.2 */
    assert_int_equal(coll_circle_aabb(v2(0.8, 0.1), 0.5, v2(0, 0), v2(1, 2), &m), 1);
    assert_vec(m.normal, -1, 0, 0); /* the box lies to the circle's left */
    assert_near(m.depth, 0.7, TOL);
}

static void test_circle_aabb_centre_on_a_corner_region_boundary(void **state)
{
    (void)state;
    coll_manifold m;
    /* centre level with the top face, outside the side: the side face, not a corner */
    assert_int_equal(coll_circle_aabb(v2(1.25, 1), 0.5, v2(0, 0), v2(1, 1), &m), 1);
    assert_vec(m.normal, -1, 0, TOL);
    assert_near(m.depth, 0.25, TOL);
}

static void test_manifold_of_dispatches_and_flips_the_box_circle_order(void **state)
{
    (void)state;
    coll_manifold m1, m2;
    rg_vec2 hc = v2(0.5, 0.5), hb = v2(2, 1);
    coll_manifold_of(RG_SHAPE_CIRCLE, v2(0.3, 1.4), hc, RG_SHAPE_AABB, v2(0, 0), hb, &m1);
    coll_manifold_of(RG_SHAPE_AABB, v2(0, 0), hb, RG_SHAPE_CIRCLE, v2(0.3, 1.4), hc, &m2);
    assert_vec(m1.normal, 0, -1, TOL);
    assert_vec(m2.normal, 0, 1, TOL); /* from a (the box) toward b (the circle) */
    assert_near(m1.depth, m2.depth, 0);
    coll_manifold_of(RG_SHAPE_CIRCLE, v2(0, 0), hc, RG_SHAPE_CIRCLE, v2(0, 0.8), hc, &m1);
    assert_near(m1.depth, 0.2, TOL);
    coll_manifold_of(RG_SHAPE_AABB, v2(0, 0), hc, RG_SHAPE_AABB, v2(0.9, 0), hc, &m1);
    assert_near(m1.depth, 0.1, TOL);
}

/* ---------------------------------------------------------------- grazing */

static void test_a_box_sliding_onto_a_flush_tile_grazes_its_corner(void **state)
{
    (void)state;
    coll_manifold m;
    rg_vec2 tile = v2(0.5, 0.5), body = v2(0.4, 0.4);
    /* the box rests at the tiles' top level (y 0.4 over a tile centred at y -0.5), 5 cm left
     * of the next tile, moving right by 13 cm */
    rg_vec2 pb = v2(-0.95, 0.4), r = v2(0.133, 0);
    /* the plain test sees a gap along x: the side of the tile */
    coll_manifold_of(RG_SHAPE_AABB, v2(0, -0.5), tile, RG_SHAPE_AABB, pb, body, &m);
    assert_vec(m.normal, -1, 0, 0);
    /* grazing: the top face's contact */
    coll_contact(RG_SHAPE_AABB, v2(0, -0.5), tile, RG_SHAPE_AABB, pb, body, r, 0.005f, &m);
    assert_vec(m.normal, 0, 1, 0);
    assert_near(m.depth, 0, TOL);
    /* moving away (off a ledge): the plain contact, which lets it fall */
    coll_contact(RG_SHAPE_AABB, v2(0, -0.5), tile, RG_SHAPE_AABB, pb, body, v2(-0.133, 0), 0.005f, &m);
    assert_vec(m.normal, -1, 0, 0);
    /* sliding down along a wall of tiles: the side face */
    coll_contact(RG_SHAPE_AABB, v2(0, 0), tile, RG_SHAPE_AABB, v2(0.9, 1.0), body, v2(0, -0.2), 0.005f, &m);
    assert_vec(m.normal, 1, 0, 0);
    /* too far below the top to graze: it hits the side */
    coll_contact(RG_SHAPE_AABB, v2(0, -0.5), tile, RG_SHAPE_AABB, v2(-0.95, 0.35), body, r, 0.005f, &m);
    assert_vec(m.normal, -1, 0, 0);
    /* level with the top but 5 cm off, moving 4.5 cm toward it: the step cannot close the
     * gap (its 4.5 cm and the 5 mm of slop fall short), so the tile's top plane does not hold
     * it where the tile is not: the plain contact, 5 cm apart along x */
    coll_contact(RG_SHAPE_AABB, v2(0, -0.5), tile, RG_SHAPE_AABB, pb, body, v2(0.045, 0), 0.005f, &m);
    assert_vec(m.normal, -1, 0, 0);
    assert_near(m.depth, -0.05, TOL);
    /* the same with 5.5 cm of motion, which closes it within the slop: grazing */
    coll_contact(RG_SHAPE_AABB, v2(0, -0.5), tile, RG_SHAPE_AABB, pb, body, v2(0.055, 0), 0.005f, &m);
    assert_vec(m.normal, 0, 1, 0);
    /* flush with the tile's side, 30 cm above its top, falling 2 cm: the side's plane does
     * not reach up to it; the plain contact, 30 cm apart along y */
    coll_contact(RG_SHAPE_AABB, v2(0, 0), tile, RG_SHAPE_AABB, v2(0.9, 1.2), body, v2(0, -0.02), 0.005f, &m);
    assert_vec(m.normal, 0, 1, 0);
    assert_near(m.depth, -0.3, TOL);
}

static void test_a_circle_sliding_onto_a_flush_tile_grazes_its_corner(void **state)
{
    (void)state;
    coll_manifold m;
    rg_vec2 tile = v2(0.5, 0.5), ball = v2(0.4, 0.4);
    rg_vec2 pc = v2(-0.7, 0.4); /* on the tiles' top level, 20 cm left of the corner */
    /* plain: the corner, a tilted normal */
    coll_manifold_of(RG_SHAPE_CIRCLE, pc, ball, RG_SHAPE_AABB, v2(0, -0.5), tile, &m);
    assert_true(m.normal.x > (rg_real)0.4);
    /* moving toward the tile along its top: the top face, from circle to box */
    coll_contact(RG_SHAPE_CIRCLE, pc, ball, RG_SHAPE_AABB, v2(0, -0.5), tile, v2(-0.133, 0), 0.005f, &m);
    assert_vec(m.normal, 0, -1, 0);
    assert_near(m.depth, 0, TOL);
    /* the same with the box first */
    coll_contact(RG_SHAPE_AABB, v2(0, -0.5), tile, RG_SHAPE_CIRCLE, pc, ball, v2(0.133, 0), 0.005f, &m);
    assert_vec(m.normal, 0, 1, 0);
    /* moving away: the corner */
    coll_contact(RG_SHAPE_CIRCLE, pc, ball, RG_SHAPE_AABB, v2(0, -0.5), tile, v2(0.133, 0), 0.005f, &m);
    assert_true(m.normal.x > (rg_real)0.4);
    /* moving toward it by less than the gap to the corner (sqrt(0.2^2 + 0.4^2) - 0.4 = 4.7 cm)
     * less the slop: the corner, at that gap; the top's plane would hold the ball 4.7 cm off */
    coll_contact(RG_SHAPE_CIRCLE, pc, ball, RG_SHAPE_AABB, v2(0, -0.5), tile, v2(-0.04, 0), 0.005f, &m);
    assert_true(m.normal.x > (rg_real)0.4);
    assert_near(m.depth, 0.4 - sqrt(0.2), TOL);
    /* beside the tile's side, 20 cm above its top, settling by a millimetre: the corner */
    coll_contact(RG_SHAPE_CIRCLE, v2(-0.9, 0.2), ball, RG_SHAPE_AABB, v2(0, -0.5), tile, v2(0, 0.001), 0.005f, &m);
    assert_true(m.normal.y < (rg_real)-0.4);
    assert_near(m.depth, 0.4 - sqrt(0.2), TOL);
    /* circle pairs are never changed */
    coll_contact(RG_SHAPE_CIRCLE, v2(0, 0), ball, RG_SHAPE_CIRCLE, v2(0.6, 0.3), ball, v2(1, 0), 0.005f, &m);
    assert_near(m.depth, 0.8 - sqrt(0.45), TOL);
}

/* ---------------------------------------------------------------- rays */

static void test_ray_hits_a_circle_at_the_entry_fraction(void **state)
{
    (void)state;
    rg_real t;
    rg_vec2 n;
    /* from (-5, 0) along +x by 10 toward a unit circle at the origin: enters at x = -1 */
    assert_int_equal(coll_ray_rounded_box(v2(0, 0), v2(0, 0), 1, v2(-5, 0), v2(10, 0), &t, &n), 1);
    assert_near(t, 0.4, TOL);
    assert_vec(n, -1, 0, TOL);
    /* off-centre: y = 0.6 enters at x = -0.8 */
    assert_int_equal(coll_ray_rounded_box(v2(0, 0), v2(0, 0), 1, v2(-5, 0.6), v2(10, 0), &t, &n), 1);
    assert_near(t, 0.42, TOL);
    assert_vec(n, -0.8, 0.6, TOL);
}

static void test_ray_hits_a_box_face_with_its_normal(void **state)
{
    (void)state;
    rg_real t;
    rg_vec2 n;
    assert_int_equal(coll_ray_rounded_box(v2(0, 0), v2(1, 2), 0, v2(0.5, 10), v2(0, -20), &t, &n), 1);
    assert_near(t, 0.4, TOL);
    assert_vec(n, 0, 1, 0);
}

static void test_ray_misses_short_far_and_parallel(void **state)
{
    (void)state;
    rg_real t = -1;
    rg_vec2 n;
    /* too short */
    assert_int_equal(coll_ray_rounded_box(v2(0, 0), v2(1, 1), 0, v2(-5, 0), v2(3, 0), &t, &n), 0);
    /* passes beside */
    assert_int_equal(coll_ray_rounded_box(v2(0, 0), v2(1, 1), 0, v2(-5, 1.5), v2(10, 0), &t, &n), 0);
    /* pointing away */
    assert_int_equal(coll_ray_rounded_box(v2(0, 0), v2(0, 0), 1, v2(-5, 0), v2(-10, 0), &t, &n), 0);
    /* zero translation outside */
    assert_int_equal(coll_ray_rounded_box(v2(0, 0), v2(1, 1), 0.5, v2(3, 3), v2(0, 0), &t, &n), 0);
    assert_near(t, -1, 0); /* untouched */
}

static void test_ray_from_inside_reports_minus_one(void **state)
{
    (void)state;
    rg_real t = 7;
    rg_vec2 n = v2(3, 3);
    assert_int_equal(coll_ray_rounded_box(v2(0, 0), v2(1, 1), 0, v2(0.2, 0.3), v2(5, 0), &t, &n), -1);
    assert_int_equal(coll_ray_rounded_box(v2(0, 0), v2(0, 0), 1, v2(0.2, 0.3), v2(5, 0), &t, &n), -1);
    assert_near(t, 7, 0);
}

static void test_ray_against_a_rounded_corner_hits_the_corner_circle(void **state)
{
    (void)state;
    rg_real t;
    rg_vec2 n;
    /* core (1, 1), radius 0.5: the corner arc is centred at (1, 1).  A ray along y = 1.3
     * from the right enters the arc at x = 1 + sqrt(0.25 - 0.09) = 1.4 */
    assert_int_equal(coll_ray_rounded_box(v2(0, 0), v2(1, 1), 0.5, v2(5, 1.3), v2(-10, 0), &t, &n), 1);
    assert_near(t, (5 - 1.4) / 10, TOL);
    assert_vec(n, 0.8, 0.6, TOL);
    /* a ray through the corner square that misses the arc misses the shape */
    assert_int_equal(coll_ray_rounded_box(v2(0, 0), v2(1, 1), 0.5, v2(5, 1.45), v2(-10, 2), &t, &n), 0);
}

static void test_ray_from_a_corner_square_outside_the_arc_can_still_hit_it(void **state)
{
    (void)state;
    rg_real t;
    rg_vec2 n;
    /* origin (1.45, 1.45) is inside the expanded box but outside the arc (distance 0.636) */
    assert_int_equal(coll_ray_rounded_box(v2(0, 0), v2(1, 1), 0.5, v2(1.45, 1.45), v2(-1, -1), &t, &n), 1);
    double d0 = sqrt(2.0) * 0.45; /* distance to the arc centre along the diagonal */
    assert_near(t, (d0 - 0.5) / sqrt(2.0), TOL);
    assert_vec(n, sqrt(0.5), sqrt(0.5), TOL);
}

/* ---------------------------------------------------------------- time of impact */

static void test_sweep_circle_circle_gives_the_exact_time_of_impact(void **state)
{
    (void)state;
    rg_real t;
    coll_manifold m;
    rg_vec2 h = v2(0.5, 0.5);
    /* b starts 10 to the right and moves -20: touches when 1 apart, t = 9/20 */
    assert_int_equal(coll_sweep(RG_SHAPE_CIRCLE, v2(0, 0), h, RG_SHAPE_CIRCLE, v2(10, 0), h, v2(-20, 0), &t, &m), 1);
    assert_near(t, 0.45, TOL);
    assert_vec(m.normal, 1, 0, TOL);
    assert_near(m.depth, 0, 0);
    assert_vec(m.point, 0.5, 0, TOL);
}

static void test_sweep_circle_against_a_box_corner(void **state)
{
    (void)state;
    rg_real t;
    coll_manifold m;
    /* box (1, 1) at the origin; circle r 0.5 moving left along y = 1.3: hits the corner arc
     * when its centre is at x = 1.4 */
    assert_int_equal(coll_sweep(RG_SHAPE_AABB, v2(0, 0), v2(1, 1), RG_SHAPE_CIRCLE, v2(5, 1.3),
                                v2(0.5, 0.5), v2(-10, 0), &t, &m), 1);
    assert_near(t, 0.36, TOL);
    assert_vec(m.normal, 0.8, 0.6, TOL);
    /* and the other way round: normal from the circle toward the box */
    assert_int_equal(coll_sweep(RG_SHAPE_CIRCLE, v2(5, 1.3), v2(0.5, 0.5), RG_SHAPE_AABB, v2(0, 0),
                                v2(1, 1), v2(10, 0), &t, &m), 1);
    assert_near(t, 0.36, TOL);
    assert_vec(m.normal, -0.8, -0.6, TOL);
}

static void test_sweep_box_box_enters_through_the_right_face(void **state)
{
    (void)state;
    rg_real t;
    coll_manifold m;
    /* b (0.5, 0.5) falls onto a (2, 0.5) from 3 above: touches after 2 of its 4 m */
    assert_int_equal(coll_sweep(RG_SHAPE_AABB, v2(0, 0), v2(2, 0.5), RG_SHAPE_AABB, v2(0.5, 3),
                                v2(0.5, 0.5), v2(0, -4), &t, &m), 1);
    assert_near(t, 0.5, TOL);
    assert_vec(m.normal, 0, 1, 0);
}

static void test_sweep_overlapping_at_the_start_reports_time_zero(void **state)
{
    (void)state;
    rg_real t = -1;
    coll_manifold m;
    rg_vec2 h = v2(0.5, 0.5);
    assert_int_equal(coll_sweep(RG_SHAPE_CIRCLE, v2(0, 0), h, RG_SHAPE_CIRCLE, v2(0.8, 0), h, v2(5, 0), &t, &m), 1);
    assert_near(t, 0, 0);
    assert_near(m.depth, 0.2, TOL);
}

static void test_sweep_that_passes_beside_misses(void **state)
{
    (void)state;
    rg_real t;
    coll_manifold m;
    rg_vec2 h = v2(0.5, 0.5);
    assert_int_equal(coll_sweep(RG_SHAPE_CIRCLE, v2(0, 0), h, RG_SHAPE_CIRCLE, v2(-5, 1.01), h, v2(10, 0), &t, &m), 0);
    assert_int_equal(coll_sweep(RG_SHAPE_AABB, v2(0, 0), h, RG_SHAPE_AABB, v2(-5, 0), h, v2(3, 0), &t, &m), 0);
}

/* The thin wall: a 10 cm ball (r = 0.05) at 300 m/s meets a 1 cm wall at 60 Hz.  It
 * moves 5 m per step, 50 times what it would need to overlap the wall in one sample: a check
 * of where each step leaves it sees it on one side, then on the other, never overlapping;
 * the sweep over the step finds the impact. */
static void test_naive_discrete_check_misses_a_thin_wall_the_sweep_catches_it(void **state)
{
    (void)state;
    const double dt = 1.0 / 60, speed = 300, r = 0.05;
    rg_vec2 wall_h = v2(0.005, 1), ball_h = v2(r, r);
    int missed = 0, swept = 0, trials = 0;
    for (int k = 0; k < 100; k++) {
        /* start positions spread over one step's travel before the wall */
        double x0 = -1 - (k / 100.0) * speed * dt;
        double x1 = x0 + speed * dt;
        coll_manifold m;
        int start = coll_manifold_of(RG_SHAPE_CIRCLE, v2(x0, 0), ball_h, RG_SHAPE_AABB, v2(0, 0), wall_h, &m);
        int end = coll_manifold_of(RG_SHAPE_CIRCLE, v2(x1, 0), ball_h, RG_SHAPE_AABB, v2(0, 0), wall_h, &m);
        if (x1 <= -r - 0.005) continue; /* this step does not reach the wall */
        trials++;
        missed += !start && !end;
        rg_real t;
        if (coll_sweep(RG_SHAPE_AABB, v2(0, 0), wall_h, RG_SHAPE_CIRCLE, v2(x0, 0), ball_h,
                       v2(speed * dt, 0), &t, &m)) {
            swept++;
            /* the impact point: ball surface at the wall face x = -0.005 */
            assert_near(x0 + (double)t * speed * dt, -0.005 - r, 1e-4);
            assert_vec(m.normal, -1, 0, 0); /* from the wall toward the ball */
        }
    }
    assert_true(trials > 0);
    /* theory: overlap in a sample needs |x| < 0.055, a window of 0.11 m out of 5 m */
    assert_true(missed >= trials * 9 / 10);
    assert_int_equal(swept, trials);
}

static void test_a_small_fast_box_is_caught_by_the_sweep_too(void **state)
{
    (void)state;
    rg_real t;
    coll_manifold m;
    rg_vec2 wall_h = v2(0.005, 1), box_h = v2(0.05, 0.05);
    int end = coll_manifold_of(RG_SHAPE_AABB, v2(3, 0), box_h, RG_SHAPE_AABB, v2(0, 0), wall_h, &m);
    assert_int_equal(end, 0);
    assert_int_equal(coll_sweep(RG_SHAPE_AABB, v2(0, 0), wall_h, RG_SHAPE_AABB, v2(-2, 0.3), box_h,
                                v2(5, 0), &t, &m), 1);
    assert_near(t, (2 - 0.055) / 5, TOL);
    assert_vec(m.normal, -1, 0, 0);
}

static void test_non_finite_inputs_give_no_contact_and_no_crash(void **state)
{
    (void)state;
    coll_manifold m;
    rg_real t;
    rg_vec2 n, h = v2(0.5, 0.5), bad = v2(NAN, 0), inf = v2(INFINITY, 0);
    assert_int_equal(coll_circle_circle(bad, 1, v2(0, 0), 1, &m), 0);
    assert_int_equal(coll_aabb_aabb(bad, h, v2(0, 0), h, &m), 0);
    coll_circle_aabb(inf, 1, v2(0, 0), h, &m);
    assert_int_equal(m.depth >= 0, 0);
    assert_int_not_equal(coll_ray_rounded_box(v2(0, 0), h, 0, bad, v2(1, 0), &t, &n), 1);
    assert_int_equal(coll_sweep(RG_SHAPE_CIRCLE, v2(0, 0), h, RG_SHAPE_CIRCLE, bad, h, v2(1, 0), &t, &m) &&
                         m.depth >= 0 && t > 0,
                     0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_circle_circle_overlap_gives_normal_depth_and_midpoint),
        cmocka_unit_test(test_circle_circle_separated_reports_the_gap_as_negative_depth),
        cmocka_unit_test(test_circle_circle_is_antisymmetric_in_its_arguments),
        cmocka_unit_test(test_circle_circle_coincident_centres_push_along_plus_y),
        cmocka_unit_test(test_circle_circle_exact_touch_counts_as_touching),
        cmocka_unit_test(test_aabb_aabb_uses_the_axis_of_least_penetration),
        cmocka_unit_test(test_aabb_aabb_tie_goes_to_the_y_axis),
        cmocka_unit_test(test_aabb_aabb_separated_gives_the_most_separating_axis),
        cmocka_unit_test(test_circle_aabb_face_contact),
        cmocka_unit_test(test_circle_aabb_corner_contact_uses_the_corner_distance),
        cmocka_unit_test(test_circle_aabb_centre_inside_is_pushed_out_through_the_nearest_face),
        cmocka_unit_test(test_circle_aabb_centre_on_a_corner_region_boundary),
        cmocka_unit_test(test_manifold_of_dispatches_and_flips_the_box_circle_order),
        cmocka_unit_test(test_a_box_sliding_onto_a_flush_tile_grazes_its_corner),
        cmocka_unit_test(test_a_circle_sliding_onto_a_flush_tile_grazes_its_corner),
        cmocka_unit_test(test_ray_hits_a_circle_at_the_entry_fraction),
        cmocka_unit_test(test_ray_hits_a_box_face_with_its_normal),
        cmocka_unit_test(test_ray_misses_short_far_and_parallel),
        cmocka_unit_test(test_ray_from_inside_reports_minus_one),
        cmocka_unit_test(test_ray_against_a_rounded_corner_hits_the_corner_circle),
        cmocka_unit_test(test_ray_from_a_corner_square_outside_the_arc_can_still_hit_it),
        cmocka_unit_test(test_sweep_circle_circle_gives_the_exact_time_of_impact),
        cmocka_unit_test(test_sweep_circle_against_a_box_corner),
        cmocka_unit_test(test_sweep_box_box_enters_through_the_right_face),
        cmocka_unit_test(test_sweep_overlapping_at_the_start_reports_time_zero),
        cmocka_unit_test(test_sweep_that_passes_beside_misses),
        cmocka_unit_test(test_naive_discrete_check_misses_a_thin_wall_the_sweep_catches_it),
        cmocka_unit_test(test_a_small_fast_box_is_caught_by_the_sweep_too),
        cmocka_unit_test(test_non_finite_inputs_give_no_contact_and_no_crash),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
