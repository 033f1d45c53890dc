/* collision.h: pure shape tests (no world): manifolds, time of impact, rays.
 *
 * Shapes are circles and axis-aligned boxes, each given by its kind (RG_SHAPE_*), its
 * centre p and its half extents h (a circle of radius r has h = (r, r)).  Every function
 * here is a pure function of its arguments. */
#ifndef RG_COLLISION_H
#define RG_COLLISION_H

#include "rigid.h"

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

/* Ray p(t) = origin + t * d, t in [0, 1], against the rounded box {q : dist(q, box(c, h))
 * <= radius} (a circle when h = 0, a box when radius = 0).  Returns 1 and the entry
 * fraction *t and outward unit normal *n on a hit, 0 on a miss, -1 when the origin lies
 * inside (then *t and *n are untouched). */
int coll_ray_rounded_box(rg_vec2 c, rg_vec2 h, rg_real radius, rg_vec2 origin, rg_vec2 d,
                         rg_real *t, rg_vec2 *n);

/* Time of impact: shape b moves by r (relative to a) over t in [0, 1].  Returns 1 with the
 * first fraction of contact *t and the manifold at that moment (normal from the ray test,
 * depth 0), or 1 with *t = 0 and the discrete manifold when they already overlap at t = 0;
 * 0 when they never touch within the step. */
int coll_sweep(int32_t ka, rg_vec2 pa, rg_vec2 ha, int32_t kb, rg_vec2 pb, rg_vec2 hb,
               rg_vec2 r, rg_real *t, coll_manifold *m);

#endif
