/* pool.c: slot + generation handles with a free list and retirement. */
#include <string.h>

#include "pool.h"

void pool_init(pool *p, uint32_t tag, uint32_t max_gen, int32_t max_slots)
{
    memset(p, 0, sizeof *p);
    p->free_head = -1;
    p->tag = tag & POOL_TAG_MASK;
    p->max_gen = (max_gen == 0 || max_gen > POOL_MAX_GEN) ? POOL_MAX_GEN : max_gen;
    p->max_slots = (max_slots <= 0 || max_slots > POOL_MAX_SLOTS) ? POOL_MAX_SLOTS : max_slots;
}

void pool_release_memory(pool *p, const rg_mem *m)
{
    mem_free(m, p->gen, (size_t)p->capacity * sizeof *p->gen);
    mem_free(m, p->index, (size_t)p->capacity * sizeof *p->index);
    p->gen = NULL;
    p->index = NULL;
    p->capacity = 0;
}

rg_status pool_reserve(pool *p, const rg_mem *m)
{
    if (p->free_head >= 0 || p->slot_count < p->capacity) return RG_OK;
    if (p->slot_count >= p->max_slots) return RG_ERR_CAPACITY;
    int32_t cap = p->capacity < 16 ? 16 : (p->capacity > p->max_slots / 2 ? p->max_slots : p->capacity * 2);
    uint32_t *gen = mem_alloc(m, (size_t)cap * sizeof *gen);
    int32_t *index = mem_alloc(m, (size_t)cap * sizeof *index);
    if (gen == NULL || index == NULL) {
        mem_free(m, gen, (size_t)cap * sizeof *gen);
        mem_free(m, index, (size_t)cap * sizeof *index);
        return RG_ERR_OUT_OF_MEMORY;
    }
    if (p->slot_count > 0) {
        memcpy(gen, p->gen, (size_t)p->slot_count * sizeof *gen);
        memcpy(index, p->index, (size_t)p->slot_count * sizeof *index);
    }
    pool_release_memory(p, m);
    p->gen = gen;
    p->index = index;
    p->capacity = cap;
    return RG_OK;
}

rg_status pool_reserve_slots(pool *p, const rg_mem *m, int32_t slots)
{
    if (slots > p->max_slots) return RG_ERR_CAPACITY;
    if (slots <= p->capacity) return RG_OK;
    int32_t cap = p->capacity < 16 ? 16 : p->capacity;
    while (cap < slots) cap = cap > p->max_slots / 2 ? p->max_slots : cap * 2;
    uint32_t *gen = mem_alloc(m, (size_t)cap * sizeof *gen);
    int32_t *index = mem_alloc(m, (size_t)cap * sizeof *index);
    if (gen == NULL || index == NULL) {
        mem_free(m, gen, (size_t)cap * sizeof *gen);
        mem_free(m, index, (size_t)cap * sizeof *index);
        return RG_ERR_OUT_OF_MEMORY;
    }
    if (p->slot_count > 0) {
        memcpy(gen, p->gen, (size_t)p->slot_count * sizeof *gen);
        memcpy(index, p->index, (size_t)p->slot_count * sizeof *index);
    }
    pool_release_memory(p, m);
    p->gen = gen;
    p->index = index;
    p->capacity = cap;
    return RG_OK;
}

static uint64_t make_handle(const pool *p, int32_t slot)
{
    return ((uint64_t)p->tag << (POOL_SLOT_BITS + POOL_GEN_BITS)) |
           ((uint64_t)p->gen[slot] << POOL_SLOT_BITS) | (uint64_t)slot;
}

uint64_t pool_alloc(pool *p, int32_t dense)
{
    int32_t slot;
    if (p->free_head >= 0) {
        slot = p->free_head;
        p->free_head = -p->index[slot] - 2;
    } else {
        slot = p->slot_count++;
        p->gen[slot] = 1;
    }
    p->index[slot] = dense;
    p->live++;
    return make_handle(p, slot);
}

void pool_free(pool *p, uint64_t handle)
{
    int32_t slot = pool_slot(handle);
    p->live--;
    if (p->gen[slot] >= p->max_gen) {
        /* Retire: generation 0 never matches a handle, and the slot never returns to the list. */
        p->gen[slot] = 0;
        p->index[slot] = -1;
        return;
    }
    p->gen[slot]++;
    p->index[slot] = -(p->free_head + 2);
    p->free_head = slot;
}

uint64_t pool_handle(const pool *p, int32_t slot)
{
    return make_handle(p, slot);
}
