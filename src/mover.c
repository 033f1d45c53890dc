/* mover.c: the character mover, rg_body_move: a body's shape swept toward a target against
 * the shapes around it, sliding along what it meets (or stopping, or crossing). */
#include "arg.h"
#include "body.h"
#include "collision.h"
#include "island.h"
#include "pairs.h"
#include "query.h"
#include "state.h"
#include "vec2.h"

#define MOVER_LEGS 8

typedef struct mover {
    const rg_world *w;
    int32_t self;           /* the moving body's slot */
    int32_t kind;           /* its shape */
    rg_vec2 h;              /* its half extents */
    uint32_t mask;
    int32_t response;
    rg_real tol;            /* grazing tolerance, m */
    rg_vec2 p, r;           /* this leg: start and motion */
    /* SLIDE, TOUCH: the first blocking hit of the leg */
    int hit;
    rg_real t;
    rg_ray_hit best;
    /* CROSS: every hit, a max-heap by (fraction, handle) of the first cap */
    rg_ray_hit *out;
    int32_t cap, count;
} mover;

/* Whether a one-way body i blocks a hit whose normal n points from i toward the mover. */
static int mover_one_way_blocks(const body_store *b, int32_t i, rg_vec2 n, rg_real t)
{
    rg_real ox = b->owx[i], oy = b->owy[i];
    if (ox == 0 && oy == 0) return 1;
    return t > 0 && n.x * ox + n.y * oy > 0; /* an overlap at the start passes */
}

static void mover_keep(mover *q, const rg_ray_hit *h)
{
    int32_t k = q->count < q->cap ? q->count : q->cap;
    q->count++;
    if (q->cap == 0) return;
    rg_ray_hit *o = q->out;
#define MOVER_LESS(a, b) ((a)->fraction < (b)->fraction || ((a)->fraction == (b)->fraction && (a)->body < (b)->body))
    if (k < q->cap) {
        o[k] = *h;
        while (k > 0 && MOVER_LESS(&o[(k - 1) / 2], &o[k])) {
            rg_ray_hit t = o[k];
            o[k] = o[(k - 1) / 2];
            o[(k - 1) / 2] = t;
            k = (k - 1) / 2;
        }
        return;
    }
    if (!MOVER_LESS(h, &o[0])) return;
    o[0] = *h;
    for (int32_t root = 0;;) {
        int32_t c = 2 * root + 1;
        if (c >= k) break;
        if (c + 1 < k && MOVER_LESS(&o[c], &o[c + 1])) c++;
        if (!MOVER_LESS(&o[root], &o[c])) break;
        rg_ray_hit t = o[root];
        o[root] = o[c];
        o[c] = t;
        root = c;
    }
}

static void mover_sort(mover *q)
{
    rg_ray_hit *o = q->out;
    int32_t n = q->count < q->cap ? q->count : q->cap;
    for (int32_t k = n - 1; k > 0; k--) {
        rg_ray_hit t = o[0];
        o[0] = o[k];
        o[k] = t;
        for (int32_t root = 0;;) {
            int32_t c = 2 * root + 1;
            if (c >= k) break;
            if (c + 1 < k && MOVER_LESS(&o[c], &o[c + 1])) c++;
            if (!MOVER_LESS(&o[root], &o[c])) break;
            rg_ray_hit u = o[root];
            o[root] = o[c];
            o[c] = u;
            root = c;
        }
    }
#undef MOVER_LESS
}

static rg_real mover_visit(void *p, int32_t slot, rg_real max_t)
{
    mover *q = p;
    const body_store *b = &q->w->b;
    if (slot == q->self) return max_t;
    int32_t i = body_dense(q->w, slot);
    if ((b->cat[i] & q->mask) == 0) return max_t;
    int sensor = (b->cflags[i] & CF_SENSOR) != 0;
    if (sensor && q->response != RG_MOVE_CROSS) return max_t;
    rg_vec2 c = rg_v2(b->x[i], b->y[i]), hb = rg_v2(b->hx[i], b->hy[i]);
    rg_real t;
    coll_manifold m;
    if (!query_sweep(b->shape[i], c, hb, q->kind, q->p, q->h, q->r, &t, &m)) return max_t;
    rg_vec2 n = m.normal;
    if (b->shape[i] == RG_SHAPE_AABB && t > 0)
        n = coll_graze_normal(c, hb, rg_v2(q->p.x + q->r.x * t, q->p.y + q->r.y * t), q->h, q->r, n, q->tol);
    rg_real into = q->r.x * n.x + q->r.y * n.y, len = rg_v2_len(q->r);
    if (!(into < -COLL_INTO * len)) return max_t; /* along or away from it */
    rg_ray_hit h;
    query_hit(&h, pool_handle(&q->w->body_pool, slot), m.point, n, t);
    if (q->response == RG_MOVE_CROSS) {
        mover_keep(q, &h);
        return max_t;
    }
    if (!mover_one_way_blocks(b, i, n, t)) return max_t;
    if (q->hit && (t > q->t || (t == q->t && h.body > q->best.body))) return max_t;
    q->hit = 1;
    q->t = t;
    q->best = h;
    return t;
}

/* Where a leg p + r * t, t in [0, 1], takes the body's centre past +-RG_MAX_COORD (the range
 * of every position, as bounds.c keeps it): the t at which it reaches the edge, and in
 * *axes the edges it meets there (1 x, 2 y); 1 and 0 when the leg ends in range.  p is in
 * range, so r's component toward an edge it crosses is not 0. */
static rg_real mover_edge(rg_vec2 p, rg_vec2 r, int *axes)
{
    const rg_real c = (rg_real)RG_MAX_COORD;
    rg_vec2 e = rg_v2_add(p, r); /* as the leg's end is computed */
    rg_real tx = 1, ty = 1;
    *axes = 0;
    if (rg_fabs(e.x) <= c && rg_fabs(e.y) <= c) return 1;
    if (rg_fabs(e.x) > c) tx = rg_clamp(((r.x > 0 ? c : -c) - p.x) / r.x, 0, 1);
    if (rg_fabs(e.y) > c) ty = rg_clamp(((r.y > 0 ? c : -c) - p.y) / r.y, 0, 1);
    rg_real t = rg_min(tx, ty);
    *axes = (rg_fabs(e.x) > c && tx == t ? 1 : 0) | (rg_fabs(e.y) > c && ty == t ? 2 : 0);
    return t;
}

/* p with each component within +-RG_MAX_COORD: p itself when it is in range, as every
 * position is but where rounding takes a leg that ends on the edge past it. */
static rg_vec2 mover_clamp(rg_vec2 p)
{
    const rg_real c = (rg_real)RG_MAX_COORD;
    return rg_v2(rg_clamp(p.x, -c, c), rg_clamp(p.y, -c, c));
}

RG_API rg_status rg_body_move(rg_world *world, rg_body body, rg_vec2 target, uint32_t mask,
                              int32_t response, rg_vec2 *out_position, rg_ray_hit *out_hits,
                              int32_t capacity, int32_t *out_count)
{
    BODY_SET(world, body, i);
    body_store *b = &world->b;
    ARG_VEC(world, target, RG_MAX_COORD);
    ARG_INT(world, response, RG_MOVE_SLIDE, RG_MOVE_CROSS, "one of RG_MOVE_* (0..2)");
    ARG_BUFFER(world, out_hits, capacity);
    if (b->shape[i] == RG_SHAPE_NONE) return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "body has no shape");
    rg_vec2 start = rg_v2(b->x[i], b->y[i]), total = rg_v2_sub(target, start);
    rg_real length = rg_v2_len(total);
    if (!rg_finite(length)) /* defensive: within the ranges a path is always finite */
        return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "target: the path from the body at (%g, %g) is too long",
                       (double)start.x, (double)start.y);
    mover q;
    q.w = world;
    q.self = b->slot[i];
    q.kind = b->shape[i];
    q.h = rg_v2(b->hx[i], b->hy[i]);
    q.mask = mask;
    q.response = response;
    q.tol = world->coll.slop + 64 * RG_EPSILON * (rg_fabs(start.x) + rg_fabs(start.y) + q.h.x + q.h.y);
    q.out = out_hits;
    q.cap = capacity;
    q.count = 0;
    rg_vec2 pos = start;
    if (response == RG_MOVE_CROSS) {
        q.p = start;
        q.r = total;
        broadphase_sweep(&world->coll.bp, start, total, q.h.x, q.h.y, 1, mover_visit, &q);
        mover_sort(&q);
        pos = target;
    } else {
        rg_vec2 rem = total;
        rg_real travelled = 0;
        for (int leg = 0; leg < MOVER_LEGS && (rem.x != 0 || rem.y != 0); leg++) {
            int axes;
            rg_real edge = mover_edge(pos, rem, &axes);
            q.p = pos;
            q.r = rem;
            q.hit = 0;
            broadphase_sweep(&world->coll.bp, pos, rem, q.h.x, q.h.y, 0, mover_visit, &q);
            rg_real len = rg_v2_len(rem);
            if (!q.hit && axes == 0) {
                pos = rg_v2_add(pos, rem);
                break;
            }
            if (!q.hit || q.t > edge) {
                /* the centre meets the range's edge first: it stops on it and goes on along
                 * it, as along a wall that reports no hit (the target is in range: only a
                 * turn of the slide, or rounding, takes a leg past the edge) */
                const rg_real c = (rg_real)RG_MAX_COORD;
                pos = mover_clamp(rg_v2(pos.x + rem.x * edge, pos.y + rem.y * edge));
                if (axes & 1) pos.x = rem.x > 0 ? c : -c;
                if (axes & 2) pos.y = rem.y > 0 ? c : -c;
                travelled += len * edge;
                rem = rg_v2_scale(rem, 1 - edge);
                if (axes & 1) rem.x = 0;
                if (axes & 2) rem.y = 0;
                continue;
            }
            /* stop where it meets the surface; what is left goes on along it (slide) */
            pos = mover_clamp(rg_v2(pos.x + rem.x * q.t, pos.y + rem.y * q.t));
            travelled += len * q.t;
            q.best.fraction = length > 0 ? rg_min(travelled / length, 1) : 0;
            if (q.count < q.cap) out_hits[q.count] = q.best;
            q.count++;
            if (response == RG_MOVE_TOUCH) break;
            rg_vec2 n = q.best.normal;
            rem = rg_v2_scale(rem, 1 - q.t);
            rg_real into = rem.x * n.x + rem.y * n.y;
            rem = rg_v2(rem.x - n.x * into, rem.y - n.y * into);
        }
    }
    b->x[i] = pos.x;
    b->y[i] = pos.y;
    if (b->type[i] == RG_BODY_STATIC) {
        /* no step brings a static body's previous position along: drawn where it ends */
        b->px[i] = pos.x;
        b->py[i] = pos.y;
    }
    int32_t s = b->slot[i];
    island_touch(world, s);
    pairs_teleported(world, s);
    if (out_position != NULL) *out_position = pos;
    if (out_count != NULL) *out_count = q.count;
    return RG_OK;
}
