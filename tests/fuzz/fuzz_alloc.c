/* fuzz_alloc.c: the harnesses' allocator (rg_alloc_fn): it fails from its Nth call and
 * checks that every block is resized and freed with the size it was allocated with. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_alloc.h"

typedef struct fz_block {
    size_t size;
    size_t magic;
} fz_block;   /* before each block: 16 bytes, so the block stays aligned as malloc's */
#define FZ_MAGIC ((size_t)0x5a17b10c)

static void fz_alloc_misuse(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("fuzz: the library misused its allocator: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    abort();
}

void *fz_allocf(void *user, void *ptr, size_t old_size, size_t new_size)
{
    fz_alloc *a = (fz_alloc *)user;
    fz_block *h = ptr != NULL ? (fz_block *)ptr - 1 : NULL;
    if (h != NULL && (h->magic != FZ_MAGIC || h->size != old_size))
        fz_alloc_misuse("told old_size %zu for a block of %zu", old_size, h->magic == FZ_MAGIC ? h->size : 0);
    if (h == NULL && old_size != 0) fz_alloc_misuse("told old_size %zu for a NULL block", old_size);
    if (new_size == 0) {
        if (h != NULL) {
            a->live_bytes -= h->size;
            a->live_blocks--;
            h->magic = 0;
            free(h);
        }
        return NULL;
    }
    a->calls++;
    if (a->fail_at >= 0 && a->calls >= a->fail_at) {
        a->refused++;
        return NULL;
    }
    if (new_size > ((size_t)1 << 31)) return NULL;   /* nothing the harness does needs more */
    fz_block *n = (fz_block *)malloc(sizeof *n + new_size);
    if (n == NULL) return NULL;
    n->size = new_size;
    n->magic = FZ_MAGIC;
    if (h != NULL) {
        memcpy(n + 1, h + 1, old_size < new_size ? old_size : new_size);
        a->live_bytes -= h->size;
        a->live_blocks--;
        h->magic = 0;
        free(h);
    }
    a->live_bytes += new_size;
    a->live_blocks++;
    return n + 1;
}
