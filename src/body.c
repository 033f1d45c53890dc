/* body.c: body storage: the structure of arrays in one block, partitions, lookup. */
#include <string.h>

#include "body.h"
#include "state.h"

int32_t body_lookup(const rg_world *w, rg_body body)
{
    return pool_lookup(&w->body_pool, body);
}

/* Every field array of a store of b->capacity bodies. */
static void body_layout(mem_layout *l, void *ctx)
{
    body_store *b = ctx;
#define RG_FIELD_TAKE(T, name) b->name = (T *)mem_take(l, (size_t)b->capacity, sizeof(T));
    RG_BODY_FIELDS(RG_FIELD_TAKE)
#undef RG_FIELD_TAKE
}

rg_status body_reserve(rg_world *w)
{
    rg_status st = pool_reserve(&w->body_pool, &w->mem);
    if (st != RG_OK) return st;
    return body_reserve_count(w, w->b.count + 1);
}

rg_status body_reserve_count(rg_world *w, int32_t n)
{
    body_store *b = &w->b;
    if (n <= b->capacity) return RG_OK;
    if (n > RG_MAX_BODIES) return RG_ERR_CAPACITY;
    body_store grown = *b;
    grown.capacity = b->capacity < 64 ? 64 : b->capacity;
    while (grown.capacity < n) grown.capacity = grown.capacity > RG_MAX_BODIES / 2 ? RG_MAX_BODIES : grown.capacity * 2;
    grown.block = mem_block(&w->mem, body_layout, &grown, &grown.block_size);
    if (grown.block == NULL) return RG_ERR_OUT_OF_MEMORY;
    if (b->count > 0) {
#define RG_FIELD_COPY(T, name) memcpy(grown.name, b->name, (size_t)b->count * sizeof(T));
        RG_BODY_FIELDS(RG_FIELD_COPY)
#undef RG_FIELD_COPY
    }
    mem_free(&w->mem, b->block, b->block_size);
    *b = grown;
    return RG_OK;
}

static void body_scratch_layout(mem_layout *l, void *ctx)
{
    scratch_store *s = ctx;
#define RG_FIELD_TAKE(T, name) s->name = (T *)mem_take(l, (size_t)s->capacity, sizeof(T));
    RG_SCRATCH_FIELDS(RG_FIELD_TAKE)
#undef RG_FIELD_TAKE
}

rg_status body_scratch_reserve(rg_world *w)
{
    scratch_store *s = &w->scratch;
    if (s->capacity >= w->b.capacity) return RG_OK;
    scratch_store grown = *s;
    grown.capacity = w->b.capacity;
    grown.block = mem_block(&w->mem, body_scratch_layout, &grown, &grown.block_size);
    if (grown.block == NULL) return RG_ERR_OUT_OF_MEMORY;
    mem_free(&w->mem, s->block, s->block_size);
    *s = grown;
    return RG_OK;
}

void body_store_release(rg_world *w)
{
    mem_free(&w->mem, w->b.block, w->b.block_size);
    mem_free(&w->mem, w->scratch.block, w->scratch.block_size);
    memset(&w->b, 0, sizeof w->b);
    memset(&w->scratch, 0, sizeof w->scratch);
    pool_release_memory(&w->body_pool, &w->mem);
}

/* Swaps dense places i and j, fields and slot map. */
static void body_swap(rg_world *w, int32_t i, int32_t j)
{
    body_store *b = &w->b;
    if (i == j) return;
#define RG_FIELD_SWAP(T, name) { T t = b->name[i]; b->name[i] = b->name[j]; b->name[j] = t; }
    RG_BODY_FIELDS(RG_FIELD_SWAP)
#undef RG_FIELD_SWAP
    pool_set_dense(&w->body_pool, b->slot[i], i);
    pool_set_dense(&w->body_pool, b->slot[j], j);
}

/* Partitions are contiguous: moving a body one partition boundary is one swap with the
 * boundary element and a shift of the boundary. */
int32_t body_move_to_partition(rg_world *w, int32_t i, int part)
{
    body_store *b = &w->b;
    int cur = body_partition(w, i);
    while (cur < part) { /* move right: swap with the last of its partition */
        int32_t *end = cur == BODY_PART_ACTIVE ? &b->n_active : &b->n_moving;
        int32_t last = *end - 1;
        body_swap(w, i, last);
        i = last;
        (*end)--;
        cur++;
    }
    while (cur > part) { /* move left: swap with the first of its partition */
        int32_t *begin = cur == BODY_PART_STATIC ? &b->n_moving : &b->n_active;
        int32_t first = *begin;
        body_swap(w, i, first);
        i = first;
        (*begin)++;
        cur--;
    }
    return i;
}

void body_update_flags(rg_world *w, int32_t i)
{
    body_store *b = &w->b;
    uint32_t old = b->flags[i];
    uint32_t f = (old & ~BODY_F_COUNTED) | body_flags_of(b, i);
    w->dissipative_count += (int32_t)((f & BODY_F_DISSIPATIVE) != 0) - (int32_t)((old & BODY_F_DISSIPATIVE) != 0);
    w->limit_count += (int32_t)((f & BODY_F_LIMITED) != 0) - (int32_t)((old & BODY_F_LIMITED) != 0);
    w->gscale_count += (int32_t)((f & BODY_F_GSCALE) != 0) - (int32_t)((old & BODY_F_GSCALE) != 0);
    w->magnitude_count += (int32_t)((f & BODY_F_MAGNITUDE) != 0) - (int32_t)((old & BODY_F_MAGNITUDE) != 0);
    b->flags[i] = f;
}

rg_body body_add(rg_world *w, int32_t type, rg_real mass, rg_vec2 position)
{
    body_store *b = &w->b;
    int32_t i = b->count++;
    uint64_t h = pool_alloc(&w->body_pool, i);
#define RG_FIELD_ZERO(T, name) b->name[i] = (T)0;
    RG_BODY_FIELDS(RG_FIELD_ZERO)
#undef RG_FIELD_ZERO
    b->x[i] = b->px[i] = position.x;
    b->y[i] = b->py[i] = position.y;
    b->slot[i] = pool_slot(h);
    b->type[i] = type;
    b->mu[i] = BODY_DEFAULT_FRICTION;
    b->cat[i] = BODY_DEFAULT_CATEGORY;
    b->mask[i] = BODY_DEFAULT_MASK;
    if (type == RG_BODY_DYNAMIC) {
        b->mass[i] = mass;
        b->inv_mass[i] = 1 / mass;
        b->gscale[i] = 1;
    }
    body_update_flags(w, i);
    /* The new body sits in the static partition (the last place); move it where it goes. */
    if (type != RG_BODY_STATIC) body_move_to_partition(w, i, BODY_PART_ACTIVE);
    return h;
}

void body_remove(rg_world *w, rg_body body)
{
    body_store *b = &w->b;
    int32_t i = body_lookup(w, body);
    /* Clear its counted flags, move it to the end of the static partition, drop it. */
    b->type[i] = RG_BODY_STATIC;
    body_update_flags(w, i);
    i = body_move_to_partition(w, i, BODY_PART_STATIC);
    body_swap(w, i, b->count - 1);
    b->count--;
    pool_free(&w->body_pool, body);
}
