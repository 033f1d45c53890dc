/* query.c: raycast and box queries over the broadphase, as bodies are now. */
#include "collision.h"
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
    if (world == NULL || out_hit == NULL || !rg_vec2_finite(origin) || !rg_vec2_finite(translation))
        return RG_ERR_INVALID_ARGUMENT;
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
    out_hit->body = q.body;
    out_hit->point = rg_v2(origin.x + translation.x * q.t, origin.y + translation.y * q.t);
    out_hit->normal = q.n;
    out_hit->fraction = q.t;
    out_hit->pad = 0;
    return 1;
}

typedef struct box_query {
    const rg_world *w;
    rg_real lx, ly, ux, uy;
    uint32_t mask;
    rg_body *out;       /* a max-heap of the smallest handles, [0, min(count, cap)) */
    int32_t cap, count;
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
    rg_body h = pool_handle(&q->w->body_pool, slot);
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
    if (world == NULL || !rg_vec2_finite(lower) || !rg_vec2_finite(upper) || lower.x > upper.x ||
        lower.y > upper.y || capacity < 0 || (out == NULL && capacity > 0))
        return RG_ERR_INVALID_ARGUMENT;
    box_query q;
    q.w = world;
    q.lx = lower.x;
    q.ly = lower.y;
    q.ux = upper.x;
    q.uy = upper.y;
    q.mask = mask;
    q.out = out;
    q.cap = capacity;
    q.count = 0;
    broadphase_query(&world->coll.bp, lower.x, lower.y, upper.x, upper.y, box_visit, &q);
    /* heapsort the kept handles into ascending order */
    int32_t n = q.count < capacity ? q.count : capacity;
    for (int32_t k = n - 1; k > 0; k--) {
        rg_body t = out[0];
        out[0] = out[k];
        out[k] = t;
        heap_down(out, 0, k);
    }
    return q.count;
}
