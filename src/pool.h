/* pool.h: handle pool.  A handle packs a slot index, the slot's generation and the owner's
 * tag; one lookup function checks all three.  A slot whose generation would wrap is retired,
 * so a destroyed handle never becomes valid again. */
#ifndef RG_POOL_H
#define RG_POOL_H

#include <stdint.h>

#include "mem.h"

#define POOL_SLOT_BITS 24
#define POOL_GEN_BITS  20
#define POOL_TAG_BITS  20
#define POOL_MAX_SLOTS ((1 << POOL_SLOT_BITS) - 1)
#define POOL_MAX_GEN   ((1u << POOL_GEN_BITS) - 1u)
#define POOL_TAG_MASK  ((1u << POOL_TAG_BITS) - 1u)

typedef struct pool {
    uint32_t *gen;      /* per slot: generation of the live or next handle; 0 = retired */
    int32_t *index;     /* per slot: dense index when live (>= 0), -(next free + 2) when free */
    int32_t slot_count; /* slots ever used */
    int32_t capacity;   /* slots allocated */
    int32_t free_head;  /* first free slot, -1 when none */
    int32_t live;       /* live handles */
    uint32_t tag;       /* owner tag in the handle's top bits */
    uint32_t max_gen;   /* retire a slot after this generation (tests lower it) */
    int32_t max_slots;  /* capacity limit */
} pool;

void pool_init(pool *p, uint32_t tag, uint32_t max_gen, int32_t max_slots);
void pool_release_memory(pool *p, const rg_mem *m);
/* Makes room so that the next pool_alloc cannot fail.  RG_ERR_CAPACITY or
 * RG_ERR_OUT_OF_MEMORY, changing nothing, when it cannot. */
rg_status pool_reserve(pool *p, const rg_mem *m);
/* Room for `slots` slots (restoring a snapshot); all-or-nothing. */
rg_status pool_reserve_slots(pool *p, const rg_mem *m, int32_t slots);
/* Takes a slot (after a successful pool_reserve) mapped to dense index `dense`. */
uint64_t pool_alloc(pool *p, int32_t dense);
/* Frees the slot of a live handle; its generation moves on (or the slot retires). */
void pool_free(pool *p, uint64_t handle);
/* Slot of a handle (no check). */
static inline int32_t pool_slot(uint64_t handle) { return (int32_t)(handle & ((1u << POOL_SLOT_BITS) - 1u)); }
/* Dense index of a live handle of this pool, or -1 (inline: every entry point calls it). */
static inline int32_t pool_lookup(const pool *p, uint64_t handle)
{
    uint32_t tag = (uint32_t)(handle >> (POOL_SLOT_BITS + POOL_GEN_BITS));
    uint32_t gen = (uint32_t)(handle >> POOL_SLOT_BITS) & POOL_MAX_GEN;
    int32_t slot = pool_slot(handle);
    if (tag != p->tag || gen == 0 || slot >= p->slot_count) return -1;
    if (p->gen[slot] != gen || p->index[slot] < 0) return -1;
    return p->index[slot];
}
/* Dense index of a live slot. */
static inline int32_t pool_dense(const pool *p, int32_t slot) { return p->index[slot]; }
static inline void pool_set_dense(pool *p, int32_t slot, int32_t dense) { p->index[slot] = dense; }
/* The live handle of a slot. */
uint64_t pool_handle(const pool *p, int32_t slot);

#endif
