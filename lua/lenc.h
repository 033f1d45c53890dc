/* lenc.h: the byte encodings of a recording: a growable buffer, varints, deflate, base64
 * and JSON strings.  Memory comes from malloc and is bounded by the caller's cap. */
#ifndef LENC_H
#define LENC_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* A byte buffer that grows up to `cap` bytes; past it (or when malloc fails) `failed` is
 * set and every later write is dropped, so a writer checks once at the end. */
typedef struct lenc_buf {
    unsigned char *data;
    size_t len, room, cap;
    int failed;
} lenc_buf;

/* Grows the array *p of elements of size sz (room of them now) to hold n; the new elements
 * are zero.  0 when out of memory or past 2^28 elements (nothing changes then). */
int lenc_grow(void **p, int32_t *room, int32_t n, size_t sz);

void lenc_init(lenc_buf *b, size_t cap);
void lenc_free(lenc_buf *b);
void lenc_bytes(lenc_buf *b, const void *p, size_t n);
/* Unsigned LEB128: 7 bits a byte, low bits first, the top bit set on all but the last. */
void lenc_uv(lenc_buf *b, uint64_t v);
/* Signed values zigzag-mapped first (0, -1, 1, -2, ... -> 0, 1, 2, 3, ...). */
void lenc_sv(lenc_buf *b, int64_t v);

/* A zlib (RFC 1950) stream into `out`: lenc_deflate_feed compresses and empties `in`,
 * lenc_deflate_end flushes.  0 on success; on failure out->failed is set. */
typedef struct lenc_deflate {
    void *z;
    lenc_buf out;
} lenc_deflate;

int lenc_deflate_begin(lenc_deflate *d, size_t cap);
int lenc_deflate_feed(lenc_deflate *d, lenc_buf *in);
int lenc_deflate_end(lenc_deflate *d);
void lenc_deflate_free(lenc_deflate *d);

/* Base64 (RFC 4648, padded) of p[0..n) to f, in lines of 1024 characters. */
void lenc_base64(FILE *f, const unsigned char *p, size_t n);
/* s[0..n) as a JSON string literal, quotes included: valid UTF-8 passes, other bytes become
 * U+FFFD, controls and '<' '>' '&' are escaped (safe inside an HTML <script> element). */
void lenc_json_string(FILE *f, const char *s, size_t n);

#endif
