/* spring.c: spring storage and the spring API. */
#include <string.h>

#include "body.h"
#include "spring.h"
#include "state.h"
#include "vec2.h"

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

rg_status spring_reserve(rg_world *w, int32_t n)
{
    spring_store *ss = &w->springs;
    if (n <= ss->capacity) return RG_OK;
    if (n > RG_MAX_SPRINGS) return RG_ERR_CAPACITY;
    int32_t cap = ss->capacity < 8 ? 8 : ss->capacity;
    while (cap < n) cap = cap > RG_MAX_SPRINGS / 2 ? RG_MAX_SPRINGS : cap * 2;
    spring *items = mem_alloc(&w->mem, (size_t)cap * sizeof *items);
    if (items == NULL) return RG_ERR_OUT_OF_MEMORY;
    if (ss->count > 0) memcpy(items, ss->items, (size_t)ss->count * sizeof *items);
    mem_free(&w->mem, ss->items, (size_t)ss->capacity * sizeof *items);
    ss->items = items;
    ss->capacity = cap;
    return RG_OK;
}

RG_API rg_status rg_spring_create(rg_world *world, rg_body a, rg_body b, rg_vec2 anchor,
                                  rg_real rest_length, rg_real stiffness, rg_real damping,
                                  uint64_t *out_spring)
{
    WORLD_WRITABLE(world);
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
    if (st == RG_OK) st = spring_reserve(world, ss->count + 1);
    if (st != RG_OK) return st;
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
    WORLD_WRITABLE(world);
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

void spring_detach_body(rg_world *w, int32_t slot)
{
    spring_store *ss = &w->springs;
    for (int32_t s = ss->count - 1; s >= 0; s--) {
        if (ss->items[s].slot_a == slot || ss->items[s].slot_b == slot) spring_remove_dense(w, s);
    }
}

void spring_release(rg_world *w)
{
    spring_store *ss = &w->springs;
    mem_free(&w->mem, ss->items, (size_t)ss->capacity * sizeof *ss->items);
    ss->items = NULL;
    ss->capacity = ss->count = 0;
    pool_release_memory(&ss->pool, &w->mem);
}
