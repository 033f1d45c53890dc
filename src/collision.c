/* collision.c: pure shape tests: manifolds, rays against rounded boxes, time of impact. */
#include "collision.h"
#include "vec2.h"

int coll_circle_circle(rg_vec2 pa, rg_real ra, rg_vec2 pb, rg_real rb, coll_manifold *m)
{
    rg_vec2 d = rg_v2_sub(pb, pa);
    rg_real dist2 = rg_v2_len2(d);
    rg_real rr = ra + rb;
    rg_real dist = rg_sqrt(dist2);
    rg_vec2 n = dist > 0 ? rg_v2_scale(d, 1 / dist) : rg_v2(0, 1);
    m->normal = n;
    m->depth = rr - dist;
    /* halfway between a's surface pa + n ra and b's surface pb - n rb */
    m->point = rg_v2((pa.x + n.x * ra + pb.x - n.x * rb) * RG_R(0.5),
                     (pa.y + n.y * ra + pb.y - n.y * rb) * RG_R(0.5));
    return dist2 <= rr * rr;
}

int coll_aabb_aabb(rg_vec2 pa, rg_vec2 ha, rg_vec2 pb, rg_vec2 hb, coll_manifold *m)
{
    coll_boxes(pa, ha, pb, hb, m);
    return m->depth >= 0;
}

int coll_circle_aabb(rg_vec2 pc, rg_real r, rg_vec2 pb, rg_vec2 hb, coll_manifold *m)
{
    rg_vec2 q = rg_v2_sub(pc, pb); /* circle centre in the box frame */
    rg_vec2 cq = rg_v2(rg_clamp(q.x, -hb.x, hb.x), rg_clamp(q.y, -hb.y, hb.y));
    if (cq.x != q.x || cq.y != q.y) {
        /* centre outside: the closest box point cq (a face or a corner) */
        rg_vec2 d = rg_v2_sub(q, cq); /* box surface -> centre */
        rg_real dist = rg_v2_len(d);
        rg_vec2 u = dist > 0 ? rg_v2_scale(d, 1 / dist) : rg_v2(0, 1);
        m->normal = rg_v2_neg(u); /* circle -> box */
        m->depth = r - dist;
        m->point = rg_v2(pb.x + (cq.x + q.x - u.x * r) * RG_R(0.5),
                         pb.y + (cq.y + q.y - u.y * r) * RG_R(0.5));
    } else {
        /* centre inside: out through the nearest face */
        rg_real px = hb.x - rg_fabs(q.x), py = hb.y - rg_fabs(q.y);
        rg_vec2 u, face;
        rg_real pen;
        if (px < py) {
            rg_real s = coll_sign(q.x);
            u = rg_v2(s, 0);
            face = rg_v2(s * hb.x, q.y);
            pen = px;
        } else {
            rg_real s = coll_sign(q.y);
            u = rg_v2(0, s);
            face = rg_v2(q.x, s * hb.y);
            pen = py;
        }
        m->normal = rg_v2_neg(u);
        m->depth = r + pen;
        m->point = rg_v2(pb.x + (face.x + q.x - u.x * r) * RG_R(0.5),
                         pb.y + (face.y + q.y - u.y * r) * RG_R(0.5));
    }
    return m->depth >= 0;
}

int coll_manifold_of(int32_t ka, rg_vec2 pa, rg_vec2 ha, int32_t kb, rg_vec2 pb, rg_vec2 hb,
                     coll_manifold *m)
{
    if (ka == RG_SHAPE_CIRCLE) {
        if (kb == RG_SHAPE_CIRCLE) return coll_circle_circle(pa, ha.x, pb, hb.x, m);
        return coll_circle_aabb(pa, ha.x, pb, hb, m);
    }
    if (kb == RG_SHAPE_AABB) return coll_aabb_aabb(pa, ha, pb, hb, m);
    int hit = coll_circle_aabb(pb, hb.x, pa, ha, m);
    m->normal = rg_v2_neg(m->normal);
    return hit;
}

/* Circle-box grazing: the circle beside a corner with its edge within tol of a face plane,
 * moving toward the box along that plane, and near enough to meet the corner within the
 * step: the face's contact.  (Farther off, the face's plane would hold the circle where the
 * box is not: a ball at rest beside a crate's top corner, some centimetres from it.)  q is
 * the circle centre in the box frame, rc the circle's motion relative to the box; n_out from
 * circle to box. */
static int graze_circle(rg_vec2 q, rg_real rad, rg_vec2 hb, rg_vec2 rc, rg_real tol, rg_vec2 *n_out,
                        rg_real *depth)
{
    if (!(rg_fabs(q.x) > hb.x && rg_fabs(q.y) > hb.y)) return 0; /* not at a corner */
    rg_real dx = rg_fabs(q.x) - hb.x, dy = rg_fabs(q.y) - hb.y;
    if (rg_v2_len(rg_v2(dx, dy)) - rad > tol + rg_v2_len(rc)) return 0; /* the corner is out of reach */
    int y_can = rg_fabs(dy - rad) <= tol && q.x * rc.x < 0, x_can = rg_fabs(dx - rad) <= tol && q.y * rc.y < 0;
    if (y_can && (!x_can || coll_graze_y(rad - dx, rad - dy, rc))) {
        *n_out = rg_v2(0, -coll_sign(q.y));
        *depth = rad - dy;
        return 1;
    }
    if (x_can) {
        *n_out = rg_v2(-coll_sign(q.x), 0);
        *depth = rad - dx;
        return 1;
    }
    return 0;
}

int coll_contact(int32_t ka, rg_vec2 pa, rg_vec2 ha, int32_t kb, rg_vec2 pb, rg_vec2 hb, rg_vec2 r,
                 rg_real tol, coll_manifold *m)
{
    int hit = coll_manifold_of(ka, pa, ha, kb, pb, hb, m);
    if (ka == RG_SHAPE_CIRCLE && kb == RG_SHAPE_CIRCLE) return hit;
    if (ka == RG_SHAPE_AABB && kb == RG_SHAPE_AABB) {
        if (coll_graze_boxes(pa, ha, pb, hb, r, tol, m)) return m->depth >= 0;
        return hit;
    }
    /* circle against box, either order; normals from the circle toward the box */
    int circle_a = ka == RG_SHAPE_CIRCLE;
    rg_vec2 pc = circle_a ? pa : pb, pbox = circle_a ? pb : pa, hbox = circle_a ? hb : ha;
    rg_real rad = circle_a ? ha.x : hb.x;
    rg_vec2 rc = circle_a ? rg_v2_neg(r) : r; /* the circle's motion relative to the box */
    rg_vec2 n;
    rg_real depth;
    if (!graze_circle(rg_v2_sub(pc, pbox), rad, hbox, rc, tol, &n, &depth)) return hit;
    m->normal = circle_a ? n : rg_v2_neg(n);
    m->depth = depth;
    m->point = rg_v2(pc.x + n.x * (rad - RG_R(0.5) * depth), pc.y + n.y * (rad - RG_R(0.5) * depth));
    return depth >= 0;
}

/* Smallest t in [0, 1] with |o + t d - c| = r for a ray starting outside the circle.
 * a t^2 + 2 b t + k = 0 with a = d.d, b = (o - c).d, k = |o - c|^2 - r^2 > 0; the entry root
 * t = k / (-b + sqrt(b^2 - a k)) avoids cancellation. */
static int ray_circle(rg_vec2 c, rg_real r, rg_vec2 o, rg_vec2 d, rg_real *t)
{
    rg_vec2 f = rg_v2_sub(o, c);
    rg_real a = rg_v2_dot(d, d), b = rg_v2_dot(f, d), k = rg_v2_dot(f, f) - r * r;
    if (!(b < 0) || !(a > 0)) return 0;   /* moving away or not moving */
    rg_real disc = b * b - a * k;
    if (disc < 0) return 0;
    rg_real tt = k / (-b + rg_sqrt(disc));
    if (!(tt <= 1)) return 0;
    *t = tt < 0 ? 0 : tt;
    return 1;
}

int coll_ray_rounded_box(rg_vec2 c, rg_vec2 h, rg_real radius, rg_vec2 origin, rg_vec2 d,
                         rg_real *t, rg_vec2 *n)
{
    rg_vec2 q = rg_v2_sub(origin, c);
    /* inside test against the rounded box: distance from q to the core box <= radius */
    rg_vec2 out = rg_v2(rg_max(rg_fabs(q.x) - h.x, 0), rg_max(rg_fabs(q.y) - h.y, 0));
    if (rg_v2_len2(out) < radius * radius || (out.x == 0 && out.y == 0)) return -1;
    /* slab test against the box expanded by radius */
    rg_real ex = h.x + radius, ey = h.y + radius;
    rg_real tmin = 0, tmax = 1;
    int axis = -1;
    rg_real qs[2] = {q.x, q.y}, ds[2] = {d.x, d.y}, es[2] = {ex, ey};
    for (int k = 0; k < 2; k++) {
        if (ds[k] == 0) {
            if (qs[k] < -es[k] || qs[k] > es[k]) return 0;
            continue;
        }
        rg_real inv = 1 / ds[k];
        rg_real t1 = (-es[k] - qs[k]) * inv, t2 = (es[k] - qs[k]) * inv;
        if (t1 > t2) { rg_real tmp = t1; t1 = t2; t2 = tmp; }
        if (t1 > tmin) { tmin = t1; axis = k; }
        if (t2 < tmax) tmax = t2;
        if (!(tmin <= tmax)) return 0;
    }
    /* axis < 0: the origin is inside the expanded box, so (not being inside the rounded box)
     * it lies in a corner square, or on a face within rounding (below), and p = q */
    rg_vec2 p = rg_v2(q.x + d.x * tmin, q.y + d.y * tmin);
    if (radius > 0 && rg_fabs(p.x) > h.x && rg_fabs(p.y) > h.y) {
        /* entered through a corner square: the corner circle decides (missing it means
         * missing the rounded box, which is convex) */
        rg_vec2 corner = rg_v2(coll_sign(p.x) * h.x, coll_sign(p.y) * h.y);
        rg_real tc;
        if (!ray_circle(corner, radius, q, d, &tc)) return 0;
        rg_vec2 pc = rg_v2(q.x + d.x * tc - corner.x, q.y + d.y * tc - corner.y);
        *t = tc;
        *n = rg_v2_normalize(pc);
        if (n->x == 0 && n->y == 0) *n = rg_v2(coll_sign(corner.x), 0);
        return 1;
    }
    /* the origin inside the expanded box and in no corner square lies in a face band of
     * the rounded box, on its boundary within rounding (the inside test above, rounded the
     * other way, found it outside): touching at the start, as an overlap is */
    if (axis < 0) return -1;
    *t = tmin;
    *n = axis == 0 ? rg_v2(ds[0] > 0 ? RG_R(-1) : RG_R(1), 0)
                   : rg_v2(0, ds[1] > 0 ? RG_R(-1) : RG_R(1));
    return 1;
}

int coll_sweep(int32_t ka, rg_vec2 pa, rg_vec2 ha, int32_t kb, rg_vec2 pb, rg_vec2 hb,
               rg_vec2 r, rg_real *t, coll_manifold *m)
{
    /* b's centre moving by r against the Minkowski sum of a and b, a rounded box */
    rg_vec2 core;
    rg_real radius;
    if (ka == RG_SHAPE_CIRCLE && kb == RG_SHAPE_CIRCLE) {
        core = rg_v2(0, 0);
        radius = ha.x + hb.x;
    } else if (ka == RG_SHAPE_AABB && kb == RG_SHAPE_AABB) {
        core = rg_v2_add(ha, hb);
        radius = 0;
    } else if (ka == RG_SHAPE_CIRCLE) {
        core = hb;
        radius = ha.x;
    } else {
        core = ha;
        radius = hb.x;
    }
    rg_real tt;
    rg_vec2 n;
    int hit = coll_ray_rounded_box(pa, core, radius, pb, r, &tt, &n);
    if (hit < 0) { /* overlapping (or touching within rounding) at the start */
        coll_manifold_of(ka, pa, ha, kb, pb, hb, m);
        *t = 0;
        return 1;
    }
    if (hit == 0) return 0;
    coll_manifold_of(ka, pa, ha, kb, rg_v2(pb.x + r.x * tt, pb.y + r.y * tt), hb, m);
    m->normal = n;
    m->depth = 0;
    *t = tt;
    return 1;
}
