/* llong.h: the live long strings of a Lua state, and what one comparison of two may cost. */
#ifndef LLONG_H
#define LLONG_H

#include <stddef.h>
#include <stdint.h>

/* Lua compares long strings (over 40 bytes; short ones are interned and compare by
 * address) byte by byte inside one VM instruction: == with memcmp, < and <= with strcoll,
 * rawequal and table lookups too.  Such a comparison reads at most the shorter string, so
 * at most the second longest live long string.  The allocator reports every string block
 * it makes and frees; this keeps them by size class (block size in [2^k, 2^(k+1))) in an
 * open-addressing table of their addresses. */
#define LLONG_NCLASS 64

typedef struct llong {
    int32_t count[LLONG_NCLASS];
    size_t bound;            /* 2^(k+1) for the class of the second longest, or 0 */
    size_t peak;             /* the largest bound since llong_take_peak */
    void **key;
    unsigned char *cls;
    size_t cap, used;        /* slots, slots taken (live or deleted) */
    size_t bytes;            /* what the table itself takes */
} llong;

/* The smallest block of a long string: Lua 5.4's TString header (24 bytes) + 41 + 1. */
#define LLONG_MIN_BLOCK 66

/* Records a new string block of `size` bytes (>= LLONG_MIN_BLOCK).  0 when the table cannot
 * grow: within `room` more bytes, or at all. */
int llong_add(llong *s, void *block, size_t size, size_t room);
/* Forgets a freed block of `size` bytes if it is a recorded string. */
void llong_forget(llong *s, const void *block, size_t size);
/* The largest bound since the last call, then restarts it at the current bound. */
size_t llong_take_peak(llong *s);
void llong_free(llong *s);

#endif
