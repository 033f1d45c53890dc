/* fuzz_alloc.h: the harnesses' allocator, failing from its Nth call (fuzz_alloc.c). */
#ifndef FUZZ_ALLOC_H
#define FUZZ_ALLOC_H

#include <stddef.h>

/* Fails every call from its fail_at-th on (-1: never), counting the refusals; aborts when the
 * library gives a block back with another size than it was allocated with.  A destroyed
 * world must leave live_blocks and live_bytes at 0. */
typedef struct fz_alloc {
    long calls, fail_at, refused;
    size_t live_bytes;
    long live_blocks;
} fz_alloc;

void *fz_allocf(void *user, void *ptr, size_t old_size, size_t new_size);

#endif
