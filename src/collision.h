/* collision.h: pure shape tests (no world): manifolds, time of impact, rays.
 *
 * Shapes are circles and axis-aligned boxes, each given by its kind (RG_SHAPE_*), its
 * centre p and its half extents h (a circle of radius r has h = (r, r)).  Every function
 * here is a pure function of its arguments. */
#ifndef RG_COLLISION_H
#define RG_COLLISION_H

#include "inline.h"
#include "rigid.h"
#include "vec2.h"

/* The contact between two shapes a and b.  normal is a unit vector from a toward b; depth
 * is the penetration along it (negative: the gap between them, a separating distance
 * along normal); point is the world point halfway between the two surfaces. */
typedef struct coll_manifold {
    rg_vec2 normal;
    rg_vec2 point;
    rg_real depth;
} coll_manifold;

/* Circle-circle, from squared distances; coincident centres push along +y.  Returns 1 when
 * the shapes touch or overlap (depth >= 0), else 0; *m is filled either way. */
int coll_circle_circle(rg_vec2 pa, rg_real ra, rg_vec2 pb, rg_real rb, coll_manifold *m);
/* Box-box: the axis of least penetration (most separation); ties go to the y axis. */
int coll_aabb_aabb(rg_vec2 pa, rg_vec2 ha, rg_vec2 pb, rg_vec2 hb, coll_manifold *m);
/* Circle (a) against box (b): the closest point of the box to the centre; a centre inside
 * the box is pushed out through the nearest face.  Corners included. */
int coll_circle_aabb(rg_vec2 pc, rg_real r, rg_vec2 pb, rg_vec2 hb, coll_manifold *m);
/* Any pair of kinds, normal from a to b. */
int coll_manifold_of(int32_t ka, rg_vec2 pa, rg_vec2 ha, int32_t kb, rg_vec2 pb, rg_vec2 hb,
                     coll_manifold *m);

/* The contact a step starts with: coll_manifold_of, except for grazing.  A body whose side
 * is flush with a box's face plane (within tol) and that moves onto the box along that
 * plane slides over its corner instead of catching on it: the contact is that face's, with
 * its normal.  So a box or a circle sliding along a row of flush boxes (a tile floor, a tile
 * wall) keeps its speed at the seams, while one moving off the end of a ledge still falls.
 * r is b's motion relative to a over the step. */
int coll_contact(int32_t ka, rg_vec2 pa, rg_vec2 ha, int32_t kb, rg_vec2 pb, rg_vec2 hb, rg_vec2 r,
                 rg_real tol, coll_manifold *m);

/* The box-box cases inline, for the narrowphase's loop over contacts (coll_aabb_aabb and
 * coll_contact call these: the same operations, so the same results). */
static inline rg_real coll_sign(rg_real v) { return v < 0 ? RG_R(-1) : RG_R(1); }

/* coll_aabb_aabb's manifold. */
static inline void coll_boxes(rg_vec2 pa, rg_vec2 ha, rg_vec2 pb, rg_vec2 hb, coll_manifold *m)
{
    rg_vec2 d = rg_v2_sub(pb, pa);
    /* overlap of the projections on each axis (negative: the gap) */
    rg_real ox = (ha.x + hb.x) - rg_fabs(d.x);
    rg_real oy = (ha.y + hb.y) - rg_fabs(d.y);
    if (!(ox >= oy)) {
        rg_real s = coll_sign(d.x);
        rg_real lo = rg_max(pa.y - ha.y, pb.y - hb.y), hi = rg_min(pa.y + ha.y, pb.y + hb.y);
        m->normal = rg_v2(s, 0);
        m->depth = ox;
        m->point = rg_v2(((pa.x + s * ha.x) + (pb.x - s * hb.x)) * RG_R(0.5), (lo + hi) * RG_R(0.5));
    } else {
        rg_real s = coll_sign(d.y);
        rg_real lo = rg_max(pa.x - ha.x, pb.x - hb.x), hi = rg_min(pa.x + ha.x, pb.x + hb.x);
        m->normal = rg_v2(0, s);
        m->depth = oy;
        m->point = rg_v2((lo + hi) * RG_R(0.5), ((pa.y + s * ha.y) + (pb.y - s * hb.y)) * RG_R(0.5));
    }
    if (oy != oy) m->depth = oy; /* NaN in, NaN out: never touching */
}

/* Which face two grazing candidates give (coll_graze_boxes, the circle's): overlapping on
 * both axes (by ox and oy), the one of least penetration; else the one along the motion r.
 * (A box pressed against a tile wall and sliding up it across a seam grazes the wall; one
 * resting across a floor seam, the floor.)  1: the face across y (normal along y). */
static inline int coll_graze_y(rg_real ox, rg_real oy, rg_vec2 r)
{
    return ox > 0 && oy > 0 ? ox >= oy : rg_fabs(r.x) >= rg_fabs(r.y);
}

/* Box-box grazing (coll_contact): separation along one axis within tol of zero while the
 * other axis overlaps, or closes by enough to overlap within the step (its gap at most tol
 * plus the motion r along it): the contact is along the touching axis (both: coll_graze_y).
 * (A gap the step cannot close would leave the face's plane holding a box beside the other,
 * apart from it.)  0 when the boxes do not graze (*m untouched). */
static inline int coll_graze_boxes(rg_vec2 pa, rg_vec2 ha, rg_vec2 pb, rg_vec2 hb, rg_vec2 r, rg_real tol,
                                   coll_manifold *m)
{
    rg_vec2 d = rg_v2_sub(pb, pa);
    rg_real ox = (ha.x + hb.x) - rg_fabs(d.x), oy = (ha.y + hb.y) - rg_fabs(d.y);
    int y_can = rg_fabs(oy) <= tol && (ox > 0 || (d.x * r.x < 0 && -ox <= tol + rg_fabs(r.x)));
    int x_can = rg_fabs(ox) <= tol && (oy > 0 || (d.y * r.y < 0 && -oy <= tol + rg_fabs(r.y)));
    int y_face = y_can && (!x_can || coll_graze_y(ox, oy, r));
    int x_face = x_can && !y_face;
    if (!y_face && !x_face) return 0;
    if (y_face) {
        rg_real sy = coll_sign(d.y);
        m->normal = rg_v2(0, sy);
        m->depth = oy;
        m->point = rg_v2(pb.x - coll_sign(d.x) * rg_min(hb.x, rg_fabs(d.x)), pa.y + sy * ha.y);
    } else {
        rg_real sx = coll_sign(d.x);
        m->normal = rg_v2(sx, 0);
        m->depth = ox;
        m->point = rg_v2(pa.x + sx * ha.x, pb.y - coll_sign(d.y) * rg_min(hb.y, rg_fabs(d.y)));
    }
    return 1;
}

/* A swept hit blocks when the motion goes into the surface by more than this fraction of its
 * length (rounding of a motion along a surface does not stop it). */
#define COLL_INTO RG_R(1e-5)

/* The normal a swept hit on box B (centre c, half extents hb) really has, the moving shape
 * (a box, or a circle: half extents r, r) at pm when it meets B moving by r.  A shape whose
 * side lies within tol of one of B's face planes, outside B, when it meets B grazes that face
 * (a tile seam, a corner met tangentially, a step lower than the tolerance): the face's
 * normal replaces the sweep's n, which at a corner is tilted by rounding or by the tolerance.
 * When it lies within tol of two faces (corner to corner) the face along the motion r wins.
 * (The mover's legs and the step's post-solve sweep.) */
static inline rg_vec2 coll_graze_normal(rg_vec2 c, rg_vec2 hb, rg_vec2 pm, rg_vec2 hm, rg_vec2 r, rg_vec2 n,
                                        rg_real tol)
{
    int top = pm.y - hm.y >= c.y + hb.y - tol, bottom = pm.y + hm.y <= c.y - hb.y + tol;
    int right = pm.x - hm.x >= c.x + hb.x - tol, left = pm.x + hm.x <= c.x - hb.x + tol;
    int vertical = top || bottom, horizontal = right || left;
    if (vertical && (!horizontal || rg_fabs(r.x) >= rg_fabs(r.y))) return rg_v2(0, top ? RG_R(1) : RG_R(-1));
    if (horizontal) return rg_v2(right ? RG_R(1) : RG_R(-1), 0);
    return n;
}

/* coll_contact's manifold of two boxes. */
static FORCE_INLINE void coll_contact_boxes(rg_vec2 pa, rg_vec2 ha, rg_vec2 pb, rg_vec2 hb, rg_vec2 r,
                                            rg_real tol, coll_manifold *m)
{
    if (!coll_graze_boxes(pa, ha, pb, hb, r, tol, m)) coll_boxes(pa, ha, pb, hb, m);
}

/* Ray p(t) = origin + t * d, t in [0, 1], against the rounded box {q : dist(q, box(c, h))
 * <= radius} (a circle when h = 0, a box when radius = 0).  Returns 1 and the entry
 * fraction *t and outward unit normal *n on a hit, 0 on a miss, -1 when the origin lies
 * inside or on the boundary within rounding (then *t and *n are untouched). */
int coll_ray_rounded_box(rg_vec2 c, rg_vec2 h, rg_real radius, rg_vec2 origin, rg_vec2 d,
                         rg_real *t, rg_vec2 *n);

/* Time of impact: shape b moves by r (relative to a) over t in [0, 1].  Returns 1 with the
 * first fraction of contact *t and the manifold at that moment (normal from the ray test,
 * depth 0), or 1 with *t = 0 and the discrete manifold when they already overlap at t = 0;
 * 0 when they never touch within the step. */
int coll_sweep(int32_t ka, rg_vec2 pa, rg_vec2 ha, int32_t kb, rg_vec2 pb, rg_vec2 hb,
               rg_vec2 r, rg_real *t, coll_manifold *m);

#endif
