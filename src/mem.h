/* mem.h: the per-world allocator every module allocates through (no global state). */
#ifndef RG_MEM_H
#define RG_MEM_H

#include <stddef.h>

#include "rigid.h"

typedef struct rg_mem {
    rg_alloc_fn fn;
    void *user;
} rg_mem;

/* A fresh block of size bytes (> 0), or NULL. */
static inline void *mem_alloc(const rg_mem *m, size_t size) { return m->fn(m->user, NULL, 0, size); }
/* Frees a block of size bytes; NULL is a no-op. */
static inline void mem_free(const rg_mem *m, void *p, size_t size)
{
    if (p != NULL) (void)m->fn(m->user, p, size, 0);
}

/* count * size, or 0 when it would overflow SIZE_MAX (callers treat 0 as out of memory). */
static inline size_t mem_array_size(size_t count, size_t size)
{
    return (size != 0 && count > (size_t)-1 / size) ? 0 : count * size;
}

/* The default allocator: malloc/realloc/free. */
void *mem_default_alloc(void *user, void *ptr, size_t old_size, size_t new_size);

#endif
