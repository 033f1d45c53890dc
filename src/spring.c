/* spring.c: spring storage and the spring API. */
#include <string.h>

#include "arg.h"
#include "body.h"
#include "island.h"
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

/* Wakes spring sp's bodies but slot `except` (-1: none; a static body never sleeps): a
 * spring made or removed changes the forces on them, which a sleeping body, not integrated,
 * would never feel (a body asleep on a rope that is cut would hang in the air). */
static void spring_wake_ends(rg_world *w, const spring *sp, int32_t except)
{
    const int32_t ends[2] = { sp->slot_a, sp->slot_b };
    for (int k = 0; k < 2; k++) {
        if (ends[k] < 0 || ends[k] == except) continue;
        if (w->b.type[body_dense(w, ends[k])] != RG_BODY_STATIC) island_touch(w, ends[k]);
    }
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
    ARG_PTR(world, out_spring);
    ARG_IN(world, rest_length, 0, RG_MAX_COORD);
    ARG_IN(world, stiffness, 0, RG_MAX_STIFFNESS);
    ARG_IN(world, damping, 0, RG_MAX_DAMPING);
    BODY_LOOKUP(world, a, ia);
    int32_t slot_b = -1;
    if (b != 0) {
        if (b == a) return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "b is a (a spring joins two bodies)");
        BODY_LOOKUP(world, b, ib);
        slot_b = world->b.slot[ib];
    } else {
        ARG_VEC(world, anchor, RG_MAX_COORD);
    }
    spring_store *ss = &world->springs;
    rg_status st = pool_reserve(&ss->pool, &world->mem);
    if (st != RG_OK) return error_alloc(world, __func__, st, "spring storage", "RG_MAX_SPRINGS");
    st = spring_reserve(world, ss->count + 1);
    if (st != RG_OK) return error_alloc(world, __func__, st, "spring storage", "RG_MAX_SPRINGS");
    st = body_scratch_reserve(world);  /* springs are summed through the scratch arrays */
    if (st != RG_OK) return error_alloc(world, __func__, st, "integrator scratch", "RG_MAX_BODIES");
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
    spring_wake_ends(world, sp, -1);
    *out_spring = h;
    return RG_OK;
}

RG_API rg_status rg_spring_destroy(rg_world *world, uint64_t spring_handle)
{
    WORLD_WRITABLE(world);
    int32_t s = arg_handle(world, __func__, "spring", &world->springs.pool, spring_handle);
    if (s < 0) return RG_ERR_STALE_HANDLE;
    spring_wake_ends(world, &world->springs.items[s], -1);
    spring_remove_dense(world, s);
    return RG_OK;
}

RG_API int32_t rg_spring_is_valid(const rg_world *world, uint64_t spring_handle)
{
    if (world == NULL) return 0;
    ERROR_CLEAR(world);
    return pool_lookup(&world->springs.pool, spring_handle) >= 0;
}

RG_API int32_t rg_world_spring_count(const rg_world *world)
{
    if (world == NULL) return 0;
    ERROR_CLEAR(world);
    return world->springs.count;
}

void spring_detach_body(rg_world *w, int32_t slot)
{
    spring_store *ss = &w->springs;
    for (int32_t s = ss->count - 1; s >= 0; s--) {
        if (ss->items[s].slot_a != slot && ss->items[s].slot_b != slot) continue;
        spring_wake_ends(w, &ss->items[s], slot);
        spring_remove_dense(w, s);
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
