/* query.c: raycasts, shape casts, box and point queries over the broadphase, as bodies are
 * now. */
#include <string.h>

#include "arg.h"
#include "collision.h"
#include "query.h"
#include "vec2.h"
#include "state.h"

typedef struct ray_query {
    const rg_world *w;
    rg_vec2 o, d;
    uint32_t mask;
    int hit;
    rg_real t;
    rg_vec2 n;
    rg_body body;
} ray_query;

static rg_real ray_visit(void *p, int32_t slot, rg_real max_t)
{
    ray_query *q = p;
    const body_store *b = &q->w->b;
    int32_t i = pool_dense(&q->w->body_pool, slot);
    if ((b->cat[i] & q->mask) == 0) return max_t;
    /* a circle is the rounded box of core 0 and radius r; a box has radius 0 */
    int circle = b->shape[i] == RG_SHAPE_CIRCLE;
    rg_vec2 core = circle ? rg_v2(0, 0) : rg_v2(b->hx[i], b->hy[i]);
    rg_real t;
    rg_vec2 n;
    if (coll_ray_rounded_box(rg_v2(b->x[i], b->y[i]), core, circle ? b->hx[i] : 0, q->o, q->d, &t, &n) != 1)
        return max_t;
    rg_body h = pool_handle(&q->w->body_pool, slot);
    if (!q->hit || t < q->t || (t == q->t && h < q->body)) {
        q->hit = 1;
        q->t = t;
        q->n = n;
        q->body = h;
    }
    return q->t;
}

RG_API int32_t rg_world_raycast(const rg_world *world, rg_vec2 origin, rg_vec2 translation,
                                uint32_t mask, rg_ray_hit *out_hit)
{
    ERROR_BEGIN(world);
    ARG_VEC(world, origin, RG_MAX_QUERY_COORD);
    ARG_VEC(world, translation, RG_MAX_QUERY_COORD);
    ARG_PTR(world, out_hit);
    ray_query q;
    q.w = world;
    q.o = origin;
    q.d = translation;
    q.mask = mask;
    q.hit = 0;
    q.t = 1;
    q.n = rg_v2(0, 0);
    q.body = 0;
    broadphase_raycast(&world->coll.bp, origin, translation, ray_visit, &q);
    if (!q.hit) return 0;
    query_hit(out_hit, q.body, rg_v2(origin.x + translation.x * q.t, origin.y + translation.y * q.t), q.n, q.t);
    return 1;
}

typedef struct box_query {
    const rg_world *w;
    rg_real lx, ly, ux, uy;
    uint32_t mask;
    query_handles hs;
} box_query;

static void heap_down(rg_body *h, int32_t root, int32_t n)
{
    for (;;) {
        int32_t c = 2 * root + 1;
        if (c >= n) return;
        if (c + 1 < n && h[c] < h[c + 1]) c++;
        if (!(h[root] < h[c])) return;
        rg_body t = h[root];
        h[root] = h[c];
        h[c] = t;
        root = c;
    }
}

static void box_visit(void *p, int32_t slot)
{
    box_query *q = p;
    const body_store *b = &q->w->b;
    int32_t i = pool_dense(&q->w->body_pool, slot);
    if ((b->cat[i] & q->mask) == 0) return;
    if (!(b->x[i] - b->hx[i] <= q->ux && q->lx <= b->x[i] + b->hx[i] &&
          b->y[i] - b->hy[i] <= q->uy && q->ly <= b->y[i] + b->hy[i]))
        return;
    query_keep(&q->hs, pool_handle(&q->w->body_pool, slot));
}

void query_hit(rg_ray_hit *h, rg_body body, rg_vec2 point, rg_vec2 normal, rg_real fraction)
{
    memset(h, 0, sizeof *h);
    h->body = body;
    h->point = point;
    h->normal = normal;
    h->fraction = fraction;
}

void query_keep(query_handles *q, rg_body h)
{
    int32_t n = q->count < q->cap ? q->count : q->cap;
    q->count++;
    if (q->cap == 0) return;
    if (n < q->cap) {
        /* push and sift up */
        int32_t k = n;
        q->out[k] = h;
        while (k > 0 && q->out[(k - 1) / 2] < q->out[k]) {
            rg_body t = q->out[k];
            q->out[k] = q->out[(k - 1) / 2];
            q->out[(k - 1) / 2] = t;
            k = (k - 1) / 2;
        }
    } else if (h < q->out[0]) {
        q->out[0] = h;
        heap_down(q->out, 0, n);
    }
}

RG_API int32_t rg_world_query_aabb(const rg_world *world, rg_vec2 lower, rg_vec2 upper, uint32_t mask,
                                   rg_body *out, int32_t capacity)
{
    ERROR_BEGIN(world);
    ARG_VEC(world, lower, RG_MAX_QUERY_COORD);
    ARG_VEC(world, upper, RG_MAX_QUERY_COORD);
    if (lower.x > upper.x || lower.y > upper.y)
        return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "lower (%g, %g) is not <= upper (%g, %g)",
                       (double)lower.x, (double)lower.y, (double)upper.x, (double)upper.y);
    ARG_BUFFER(world, out, capacity);
    box_query q;
    q.w = world;
    q.lx = lower.x;
    q.ly = lower.y;
    q.ux = upper.x;
    q.uy = upper.y;
    q.mask = mask;
    q.hs.out = out;
    q.hs.cap = capacity;
    q.hs.count = 0;
    broadphase_query(&world->coll.bp, lower.x, lower.y, upper.x, upper.y, box_visit, &q);
    return query_sorted(&q.hs);
}

int32_t query_sorted(query_handles *q)
{
    /* heapsort the kept handles into ascending order */
    int32_t n = q->count < q->cap ? q->count : q->cap;
    for (int32_t k = n - 1; k > 0; k--) {
        rg_body t = q->out[0];
        q->out[0] = q->out[k];
        q->out[k] = t;
        heap_down(q->out, 0, k);
    }
    return q->count;
}

/* ---------------------------------------------------------------- points */

static void point_visit(void *p, int32_t slot)
{
    box_query *q = p;
    const body_store *b = &q->w->b;
    int32_t i = body_dense(q->w, slot);
    if ((b->cat[i] & q->mask) == 0) return;
    rg_real dx = q->lx - b->x[i], dy = q->ly - b->y[i];
    int in = b->shape[i] == RG_SHAPE_CIRCLE ? dx * dx + dy * dy <= b->hx[i] * b->hx[i]
                                            : rg_fabs(dx) <= b->hx[i] && rg_fabs(dy) <= b->hy[i];
    if (in) query_keep(&q->hs, pool_handle(&q->w->body_pool, slot));
}

RG_API int32_t rg_world_query_point(const rg_world *world, rg_vec2 point, uint32_t mask,
                                    rg_body *out, int32_t capacity)
{
    ERROR_BEGIN(world);
    ARG_VEC(world, point, RG_MAX_QUERY_COORD);
    ARG_BUFFER(world, out, capacity);
    box_query q;
    q.w = world;
    q.lx = q.ux = point.x;
    q.ly = q.uy = point.y;
    q.mask = mask;
    q.hs.out = out;
    q.hs.cap = capacity;
    q.hs.count = 0;
    broadphase_query(&world->coll.bp, point.x, point.y, point.x, point.y, point_visit, &q);
    return query_sorted(&q.hs);
}

/* ---------------------------------------------------------------- every hit along a ray */

typedef struct ray_all {
    const rg_world *w;
    rg_vec2 o, d;
    uint32_t mask;
    rg_ray_hit *out;    /* a max-heap by (fraction, handle) of the first hits, [0, min(count, cap)) */
    int32_t cap, count;
} ray_all;

static int hit_less(const rg_ray_hit *a, const rg_ray_hit *b)
{
    return a->fraction < b->fraction || (a->fraction == b->fraction && a->body < b->body);
}

static void hit_down(rg_ray_hit *h, int32_t root, int32_t n)
{
    for (;;) {
        int32_t c = 2 * root + 1;
        if (c >= n) return;
        if (c + 1 < n && hit_less(&h[c], &h[c + 1])) c++;
        if (!hit_less(&h[root], &h[c])) return;
        rg_ray_hit t = h[root];
        h[root] = h[c];
        h[c] = t;
        root = c;
    }
}

static rg_real ray_all_visit(void *p, int32_t slot, rg_real max_t)
{
    ray_all *q = p;
    const body_store *b = &q->w->b;
    int32_t i = body_dense(q->w, slot);
    if ((b->cat[i] & q->mask) == 0) return max_t;
    int circle = b->shape[i] == RG_SHAPE_CIRCLE;
    rg_vec2 core = circle ? rg_v2(0, 0) : rg_v2(b->hx[i], b->hy[i]);
    rg_real t;
    rg_vec2 n;
    if (coll_ray_rounded_box(rg_v2(b->x[i], b->y[i]), core, circle ? b->hx[i] : 0, q->o, q->d, &t, &n) != 1)
        return max_t;
    rg_ray_hit h;
    query_hit(&h, pool_handle(&q->w->body_pool, slot), rg_v2(q->o.x + q->d.x * t, q->o.y + q->d.y * t), n, t);
    int32_t k = q->count < q->cap ? q->count : q->cap;
    q->count++;
    if (q->cap == 0) return max_t;
    if (k < q->cap) {
        q->out[k] = h;
        while (k > 0 && hit_less(&q->out[(k - 1) / 2], &q->out[k])) {
            rg_ray_hit tmp = q->out[k];
            q->out[k] = q->out[(k - 1) / 2];
            q->out[(k - 1) / 2] = tmp;
            k = (k - 1) / 2;
        }
    } else if (hit_less(&h, &q->out[0])) {
        q->out[0] = h;
        hit_down(q->out, 0, k);
    }
    return max_t;
}

RG_API int32_t rg_world_raycast_all(const rg_world *world, rg_vec2 origin, rg_vec2 translation,
                                    uint32_t mask, rg_ray_hit *out, int32_t capacity)
{
    ERROR_BEGIN(world);
    ARG_VEC(world, origin, RG_MAX_QUERY_COORD);
    ARG_VEC(world, translation, RG_MAX_QUERY_COORD);
    ARG_BUFFER(world, out, capacity);
    ray_all q;
    q.w = world;
    q.o = origin;
    q.d = translation;
    q.mask = mask;
    q.out = out;
    q.cap = capacity;
    q.count = 0;
    broadphase_sweep(&world->coll.bp, origin, translation, 0, 0, 1, ray_all_visit, &q);
    int32_t n = q.count < capacity ? q.count : capacity;
    for (int32_t k = n - 1; k > 0; k--) {
        rg_ray_hit t = out[0];
        out[0] = out[k];
        out[k] = t;
        hit_down(out, 0, k);
    }
    return q.count;
}

/* ---------------------------------------------------------------- shape casts */

int query_sweep(int32_t ka, rg_vec2 pa, rg_vec2 ha, int32_t kb, rg_vec2 pb, rg_vec2 hb, rg_vec2 r,
                rg_real *t, coll_manifold *m)
{
    coll_manifold_of(ka, pa, ha, kb, pb, hb, m);
    if (m->depth >= 0) {
        *t = 0;
        return 1;
    }
    return coll_sweep(ka, pa, ha, kb, pb, hb, r, t, m);
}

typedef struct cast_query {
    const rg_world *w;
    int32_t kind;
    rg_vec2 o, d, h;
    uint32_t mask;
    int hit;
    rg_ray_hit best;
} cast_query;

static rg_real cast_visit(void *p, int32_t slot, rg_real max_t)
{
    cast_query *q = p;
    const body_store *b = &q->w->b;
    int32_t i = body_dense(q->w, slot);
    if ((b->cat[i] & q->mask) == 0) return max_t;
    rg_real t;
    coll_manifold m;
    if (!query_sweep(b->shape[i], rg_v2(b->x[i], b->y[i]), rg_v2(b->hx[i], b->hy[i]), q->kind, q->o, q->h,
                     q->d, &t, &m))
        return max_t;
    /* overlapping at the start: a hit only when the cast goes into the shape */
    if (t == 0 && !(q->d.x * m.normal.x + q->d.y * m.normal.y < 0)) return max_t;
    rg_body h = pool_handle(&q->w->body_pool, slot);
    if (q->hit && (t > q->best.fraction || (t == q->best.fraction && h > q->best.body))) return max_t;
    q->hit = 1;
    query_hit(&q->best, h, m.point, m.normal, t);
    return t;
}

RG_API int32_t rg_world_cast_shape(const rg_world *world, int32_t shape, rg_vec2 size,
                                   rg_vec2 origin, rg_vec2 translation, uint32_t mask,
                                   rg_ray_hit *out_hit)
{
    ERROR_BEGIN(world);
    ARG_INT(world, shape, RG_SHAPE_CIRCLE, RG_SHAPE_AABB, "RG_SHAPE_CIRCLE (1) or RG_SHAPE_AABB (2)");
    /* size: (radius, any finite number) or half extents */
    if (!arg_real(world, __func__, "size", ".x", size.x,
                  ARG_RULE(RG_MIN_SHAPE_SIZE, RG_MAX_SHAPE_SIZE, "RG_MIN_SHAPE_SIZE", "RG_MAX_SHAPE_SIZE", 0)) ||
        !arg_real(world, __func__, "size", ".y", size.y,
                  shape == RG_SHAPE_CIRCLE ? NULL
                  : ARG_RULE(RG_MIN_SHAPE_SIZE, RG_MAX_SHAPE_SIZE, "RG_MIN_SHAPE_SIZE", "RG_MAX_SHAPE_SIZE", 0)))
        return RG_ERR_INVALID_ARGUMENT;
    ARG_VEC(world, origin, RG_MAX_QUERY_COORD);
    ARG_VEC(world, translation, RG_MAX_QUERY_COORD);
    ARG_PTR(world, out_hit);
    rg_vec2 h = shape == RG_SHAPE_CIRCLE ? rg_v2(size.x, size.x) : size;
    cast_query q;
    q.w = world;
    q.kind = shape;
    q.o = origin;
    q.d = translation;
    q.h = h;
    q.mask = mask;
    q.hit = 0;
    broadphase_sweep(&world->coll.bp, origin, translation, h.x, h.y, 0, cast_visit, &q);
    if (!q.hit) return 0;
    *out_hit = q.best;
    return 1;
}
