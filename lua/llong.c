/* llong.c: the live long strings of a Lua state by size class (see llong.h). */
#include <stdlib.h>
#include <string.h>

#include "llong.h"

static char llong_deleted;   /* its address marks a deleted slot */
#define DELETED ((void *)&llong_deleted)

static int llong_class(size_t n)
{
    int k = 0;
    while (n > 1 && k < LLONG_NCLASS - 1) {
        n >>= 1;
        k++;
    }
    return k;
}

/* The class of the second longest live string (the longest itself if it has company). */
static void llong_rebound(llong *s)
{
    int k = LLONG_NCLASS - 1, seen = 0;
    for (; k >= 0; k--) {
        seen += s->count[k];
        if (seen >= 2) break;
    }
    s->bound = k >= 0 ? (size_t)2 << k : 0;
    if (s->bound > s->peak) s->peak = s->bound;
}

static size_t llong_hash(const llong *s, const void *p)
{
    return (size_t)(((uint64_t)(uintptr_t)p >> 4) * 0x9E3779B97F4A7C15u) & (s->cap - 1);
}

static int llong_rehash(llong *s, size_t cap, size_t room)
{
    size_t bytes = cap * (sizeof(void *) + 1), i;
    void **key, **old_key = s->key;
    unsigned char *cls, *old_cls = s->cls;
    size_t old_cap = s->cap;
    if (bytes > s->bytes && bytes - s->bytes > room) return 0;
    key = (void **)calloc(cap, sizeof *key);
    cls = (unsigned char *)malloc(cap);
    if (key == NULL || cls == NULL) {
        free(key);
        free(cls);
        return 0;
    }
    s->key = key;
    s->cls = cls;
    s->cap = cap;
    s->used = 0;
    s->bytes = bytes;
    for (i = 0; i < old_cap; i++)
        if (old_key[i] != NULL && old_key[i] != DELETED) {
            size_t h = llong_hash(s, old_key[i]);
            while (key[h] != NULL) h = (h + 1) & (cap - 1);
            key[h] = old_key[i];
            cls[h] = old_cls[i];
            s->used++;
        }
    free(old_key);
    free(old_cls);
    return 1;
}

int llong_add(llong *s, void *block, size_t size, size_t room)
{
    size_t h;
    int k = llong_class(size);
    if ((s->used + 1) * 4 > s->cap * 3 && !llong_rehash(s, s->cap < 64 ? 64 : s->cap * 2, room))
        return 0;
    h = llong_hash(s, block);
    while (s->key[h] != NULL && s->key[h] != DELETED) h = (h + 1) & (s->cap - 1);
    if (s->key[h] == NULL) s->used++;
    s->key[h] = block;
    s->cls[h] = (unsigned char)k;
    s->count[k]++;
    llong_rebound(s);
    return 1;
}

void llong_forget(llong *s, const void *block, size_t size)
{
    size_t h;
    if (s->cap == 0 || size < LLONG_MIN_BLOCK) return;
    for (h = llong_hash(s, block); s->key[h] != NULL; h = (h + 1) & (s->cap - 1))
        if (s->key[h] == block) {
            s->key[h] = DELETED;
            s->count[s->cls[h]]--;
            llong_rebound(s);
            return;
        }
}

size_t llong_take_peak(llong *s)
{
    size_t p = s->peak;
    s->peak = s->bound;
    return p;
}

void llong_free(llong *s)
{
    free(s->key);
    free(s->cls);
    memset(s, 0, sizeof *s);
}
