/* mem.c: the default allocator, and the world's allocator called with its lock taken. */
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "mem.h"

void *mem_default_alloc(void *user, void *ptr, size_t old_size, size_t new_size)
{
    (void)user;
    (void)old_size;
    if (new_size == 0) {
        free(ptr);
        return NULL;
    }
    return realloc(ptr, new_size);
}

void *mem_call_locked(const rg_mem *m, void *p, size_t old_size, size_t new_size)
{
    char kept[ERROR_SIZE];
    int had = m->err[0] != '\0';
    if (had) memcpy(kept, m->err, ERROR_SIZE);
    *m->locked = 1;
    void *r = m->fn(m->user, p, old_size, new_size);
    *m->locked = 0;
    /* a call the allocator made on the world and that was refused is not the caller's */
    if (had)
        memcpy(m->err, kept, ERROR_SIZE);
    else
        m->err[0] = '\0';
    return r;
}
