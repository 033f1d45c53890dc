/* mem.h: the per-world allocator every module allocates through (no global state). */
#ifndef RG_MEM_H
#define RG_MEM_H

#include <stddef.h>
#include <stdint.h>

#include "rigid.h"

typedef struct rg_mem {
    rg_alloc_fn fn;
    void *user;
    int32_t *locked; /* the world's lock (state.h), held while the allocator runs; NULL: none */
    char *err;       /* the world's last error, which the allocator's own calls leave alone */
} rg_mem;

/* The allocator, with the world's lock taken and its last error kept (mem.c). */
void *mem_call_locked(const rg_mem *m, void *p, size_t old_size, size_t new_size);

/* The allocator called with the world locked, so that a call it makes on the world that
 * would change it returns RG_ERR_LOCKED.  Inside a step or a restore the world is locked
 * already (and tasks may allocate on workers): the lock is then only read. */
static inline void *mem_call(const rg_mem *m, void *p, size_t old_size, size_t new_size)
{
    if (m->locked == NULL || *m->locked) return m->fn(m->user, p, old_size, new_size);
    return mem_call_locked(m, p, old_size, new_size);
}

/* A fresh block of size bytes (> 0), or NULL. */
static inline void *mem_alloc(const rg_mem *m, size_t size) { return mem_call(m, NULL, 0, size); }
/* Frees a block of size bytes; NULL is a no-op. */
static inline void mem_free(const rg_mem *m, void *p, size_t size)
{
    if (p != NULL) (void)mem_call(m, p, size, 0);
}

/* count * size, or 0 when it would overflow SIZE_MAX (callers treat 0 as out of memory). */
static inline size_t mem_array_size(size_t count, size_t size)
{
    return (size != 0 && count > (size_t)-1 / size) ? 0 : count * size;
}

/* The default allocator: malloc/realloc/free. */
void *mem_default_alloc(void *user, void *ptr, size_t old_size, size_t new_size);

/* Many arrays in one block, each on a cache line of its own, so that growing them is
 * all-or-nothing and costs one allocation.  A layout function makes the same sequence of
 * mem_take calls twice (mem_block): over a layout without a base, which only adds up the
 * size, then over the block, which sets the pointers.  A size that would overflow makes the
 * layout's size SIZE_MAX, which no allocator gives. */
typedef struct mem_layout {
    char *base;     /* NULL while measuring */
    size_t size;    /* bytes used so far */
} mem_layout;

static inline mem_layout mem_layout_measure(void)
{
    mem_layout l = { NULL, 0 };
    return l;
}

static inline mem_layout mem_layout_at(void *block)
{
    mem_layout l = { (char *)block, 0 };
    return l;
}

/* Room for count elements of elem bytes, 64-byte aligned from the block's start; NULL while
 * measuring. */
static inline void *mem_take(mem_layout *l, size_t count, size_t elem)
{
    size_t bytes = mem_array_size(count, elem);
    size_t at = (l->size + 63u) & ~(size_t)63u;
    if ((bytes == 0 && count != 0 && elem != 0) || at < l->size || at > (size_t)-1 - bytes) {
        l->size = (size_t)-1;
        return NULL;
    }
    l->size = at + bytes;
    return l->base != NULL ? l->base + at : NULL;
}

typedef void (*mem_layout_fn)(mem_layout *l, void *ctx);

/* Measures layout(ctx), allocates a block of that size and lays ctx out over it: returns
 * the block and its size in *size, or NULL when the allocator fails (ctx's pointers are
 * then NULL: lay out a copy, and commit it on success). */
static inline void *mem_block(const rg_mem *m, mem_layout_fn layout, void *ctx, size_t *size)
{
    mem_layout l = mem_layout_measure();
    layout(&l, ctx);
    if (l.size == 0) l.size = 1; /* an empty layout is still a block */
    void *block = mem_alloc(m, l.size);
    if (block == NULL) return NULL;
    *size = l.size;
    l = mem_layout_at(block);
    layout(&l, ctx);
    return block;
}

#endif
