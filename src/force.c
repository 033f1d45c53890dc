/* force.c: force generators and the spring API. */
#include <string.h>

#include "vec2.h"
#include "world.h"

void force_springs(const rg_world *w, rg_real *sax, rg_real *say)
{
    const body_store *b = &w->b;
    int32_t n = b->n_active;
    if (n > 0) {
        memset(sax, 0, (size_t)n * sizeof *sax);
        memset(say, 0, (size_t)n * sizeof *say);
    }
    for (int32_t s = 0; s < w->springs.count; s++) {
        const spring *sp = &w->springs.items[s];
        int32_t ia = pool_dense(&w->body_pool, sp->slot_a);
        int32_t ib = sp->slot_b >= 0 ? pool_dense(&w->body_pool, sp->slot_b) : -1;
        rg_real bx = ib >= 0 ? b->x[ib] : sp->anchor.x;
        rg_real by = ib >= 0 ? b->y[ib] : sp->anchor.y;
        rg_real bvx = ib >= 0 ? b->vx[ib] : 0;
        rg_real bvy = ib >= 0 ? b->vy[ib] : 0;
        rg_real dx = b->x[ia] - bx, dy = b->y[ia] - by;
        rg_real dvx = b->vx[ia] - bvx, dvy = b->vy[ia] - bvy;
        rg_real d2 = dx * dx + dy * dy;
        /* Hooke: F = -k (|d| - L) d/|d| = -k (1 - L/|d|) d, exactly -k d when L = 0.
         * Damping: F = -c (dv . d) d / |d|^2, the relative velocity along the spring. */
        rg_real s_k = sp->k;
        rg_real s_c = 0;
        if (d2 > 0) {
            if (sp->rest > 0) s_k = sp->k * (1 - sp->rest / rg_sqrt(d2));
            s_c = sp->c * (dvx * dx + dvy * dy) / d2;
        } else if (sp->rest > 0) {
            s_k = 0; /* no direction to push along */
        }
        rg_real fx = -(s_k + s_c) * dx, fy = -(s_k + s_c) * dy;
        if (ia < n) {
            sax[ia] += fx * b->inv_mass[ia];
            say[ia] += fy * b->inv_mass[ia];
        }
        if (ib >= 0 && ib < n) {
            sax[ib] -= fx * b->inv_mass[ib];
            say[ib] -= fy * b->inv_mass[ib];
        }
    }
}

void force_eval(rg_world *w, rg_real *ax, rg_real *ay)
{
    const body_store *b = &w->b;
    int32_t n = b->n_active;
    rg_real gx = w->gravity.x, gy = w->gravity.y, wx = w->wind.x, wy = w->wind.y;
    for (int32_t i = 0; i < n; i++) {
        ax[i] = gx * b->gscale[i] + (wx + b->fx[i]) * b->inv_mass[i];
        ay[i] = gy * b->gscale[i] + (wy + b->fy[i]) * b->inv_mass[i];
    }
    if (w->dissipative_count > 0) {
        for (int32_t i = 0; i < n; i++) {
            if (!(b->flags[i] & BODY_F_DISSIPATIVE)) continue;
            rg_real vx = b->vx[i], vy = b->vy[i];
            rg_real speed = rg_sqrt(vx * vx + vy * vy);
            if (speed <= 0) continue;
            /* drag -(l + q|v|) v and friction -muN v/|v|, divided by m */
            rg_real k = (b->drag_lin[i] + b->drag_quad[i] * speed + b->fric[i] / speed) * b->inv_mass[i];
            ax[i] -= k * vx;
            ay[i] -= k * vy;
        }
    }
    if (w->springs.count > 0) {
        scratch_store *s = &w->scratch;
        force_springs(w, s->sax, s->say);
        for (int32_t i = 0; i < n; i++) {
            ax[i] += s->sax[i];
            ay[i] += s->say[i];
        }
    }
}

/* ---------------------------------------------------------------- spring API */

static void spring_remove_dense(rg_world *w, int32_t s)
{
    spring_store *ss = &w->springs;
    pool_free(&ss->pool, pool_handle(&ss->pool, ss->items[s].self_slot));
    int32_t last = ss->count - 1;
    if (s != last) {
        ss->items[s] = ss->items[last];
        pool_set_dense(&ss->pool, ss->items[s].self_slot, s);
    }
    ss->count--;
}

RG_API rg_status rg_spring_create(rg_world *world, rg_body a, rg_body b, rg_vec2 anchor,
                                  rg_real rest_length, rg_real stiffness, rg_real damping,
                                  uint64_t *out_spring)
{
    if (world == NULL || out_spring == NULL) return RG_ERR_INVALID_ARGUMENT;
    if (!rg_finite(rest_length) || !rg_finite(stiffness) || !rg_finite(damping) ||
        rest_length < 0 || stiffness < 0 || damping < 0)
        return RG_ERR_INVALID_ARGUMENT;
    int32_t ia = body_lookup(world, a);
    if (ia < 0) return RG_ERR_STALE_HANDLE;
    int32_t slot_b = -1;
    if (b != 0) {
        if (b == a) return RG_ERR_INVALID_ARGUMENT;
        int32_t ib = body_lookup(world, b);
        if (ib < 0) return RG_ERR_STALE_HANDLE;
        slot_b = world->b.slot[ib];
    } else if (!rg_vec2_finite(anchor)) {
        return RG_ERR_INVALID_ARGUMENT;
    }
    spring_store *ss = &world->springs;
    rg_status st = pool_reserve(&ss->pool, &world->mem);
    if (st != RG_OK) return st;
    if (ss->count == ss->capacity) {
        int32_t cap = ss->capacity < 8 ? 8 : ss->capacity * 2;
        if (cap > RG_MAX_SPRINGS) cap = RG_MAX_SPRINGS;
        spring *items = mem_alloc(&world->mem, (size_t)cap * sizeof *items);
        if (items == NULL) return RG_ERR_OUT_OF_MEMORY;
        if (ss->count > 0) memcpy(items, ss->items, (size_t)ss->count * sizeof *items);
        mem_free(&world->mem, ss->items, (size_t)ss->capacity * sizeof *items);
        ss->items = items;
        ss->capacity = cap;
    }
    st = body_scratch_reserve(world);  /* springs are summed through the scratch arrays */
    if (st != RG_OK) return st;
    int32_t s = ss->count++;
    uint64_t h = pool_alloc(&ss->pool, s);
    spring *sp = &ss->items[s];
    sp->slot_a = world->b.slot[ia];
    sp->slot_b = slot_b;
    sp->self_slot = pool_slot(h);
    sp->anchor = b == 0 ? anchor : rg_v2(0, 0);
    sp->rest = rest_length;
    sp->k = stiffness;
    sp->c = damping;
    *out_spring = h;
    return RG_OK;
}

RG_API rg_status rg_spring_destroy(rg_world *world, uint64_t spring_handle)
{
    if (world == NULL) return RG_ERR_INVALID_ARGUMENT;
    int32_t s = pool_lookup(&world->springs.pool, spring_handle);
    if (s < 0) return RG_ERR_STALE_HANDLE;
    spring_remove_dense(world, s);
    return RG_OK;
}

RG_API int32_t rg_spring_is_valid(const rg_world *world, uint64_t spring_handle)
{
    return world != NULL && pool_lookup(&world->springs.pool, spring_handle) >= 0;
}

RG_API int32_t rg_world_spring_count(const rg_world *world)
{
    return world != NULL ? world->springs.count : 0;
}

void force_detach_body(rg_world *w, int32_t slot)
{
    spring_store *ss = &w->springs;
    for (int32_t s = ss->count - 1; s >= 0; s--) {
        if (ss->items[s].slot_a == slot || ss->items[s].slot_b == slot) spring_remove_dense(w, s);
    }
}

void force_release(rg_world *w)
{
    spring_store *ss = &w->springs;
    mem_free(&w->mem, ss->items, (size_t)ss->capacity * sizeof *ss->items);
    ss->items = NULL;
    ss->capacity = ss->count = 0;
    pool_release_memory(&ss->pool, &w->mem);
}
