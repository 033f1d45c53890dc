/* lenc.c: buffers, varints, deflate (zlib), base64 and JSON strings for the recorder. */
#include <stdlib.h>
#include <string.h>

#include <zlib.h>

#include "lenc.h"

int lenc_grow(void **p, int32_t *room, int32_t n, size_t sz)
{
    int32_t k = *room < 64 ? 64 : *room;
    void *q;
    if (n <= *room) return 1;
    while (k < n) {
        if (k > (1 << 27)) return 0;
        k *= 2;
    }
    if ((q = realloc(*p, (size_t)k * sz)) == NULL) return 0;
    memset((char *)q + (size_t)*room * sz, 0, (size_t)(k - *room) * sz);
    *p = q;
    *room = k;
    return 1;
}

void lenc_init(lenc_buf *b, size_t cap)
{
    memset(b, 0, sizeof *b);
    b->cap = cap;
}

void lenc_free(lenc_buf *b)
{
    free(b->data);
    memset(b, 0, sizeof *b);
}

static int reserve(lenc_buf *b, size_t n)
{
    size_t room;
    unsigned char *p;
    if (b->failed) return 0;
    if (n <= b->room - b->len) return 1;
    if (n > b->cap - b->len) {
        b->failed = 1;
        return 0;
    }
    room = b->room < 4096 ? 4096 : b->room;
    while (room - b->len < n) room = room > b->cap / 2 ? b->cap : room * 2;
    p = (unsigned char *)realloc(b->data, room);
    if (p == NULL) {
        b->failed = 1;
        return 0;
    }
    b->data = p;
    b->room = room;
    return 1;
}

void lenc_bytes(lenc_buf *b, const void *p, size_t n)
{
    if (n == 0 || !reserve(b, n)) return;
    memcpy(b->data + b->len, p, n);
    b->len += n;
}

void lenc_uv(lenc_buf *b, uint64_t v)
{
    unsigned char tmp[10];
    size_t n = 0;
    do {
        tmp[n] = (unsigned char)(v & 127u);
        v >>= 7;
        if (v != 0) tmp[n] |= 128u;
        n++;
    } while (v != 0);
    lenc_bytes(b, tmp, n);
}

void lenc_sv(lenc_buf *b, int64_t v)
{
    /* (v << 1) ^ (v >> 63) without shifting a negative value. */
    lenc_uv(b, v < 0 ? ((uint64_t)(-(v + 1)) << 1) | 1u : (uint64_t)v << 1);
}

/* ---------------------------------------------------------------- deflate */

int lenc_deflate_begin(lenc_deflate *d, size_t cap)
{
    z_stream *z = (z_stream *)calloc(1, sizeof *z);
    lenc_init(&d->out, cap);
    d->z = z;
    if (z == NULL || deflateInit(z, 6) != Z_OK) {
        free(z);
        d->z = NULL;
        d->out.failed = 1;
        return -1;
    }
    return 0;
}

static int pump(lenc_deflate *d, const unsigned char *p, size_t n, int flush)
{
    z_stream *z = (z_stream *)d->z;
    int st;
    if (z == NULL || d->out.failed) return -1;
    z->next_in = (Bytef *)(uintptr_t)p;   /* zlib does not write through next_in */
    z->avail_in = (uInt)n;
    do {
        if (!reserve(&d->out, 65536)) return -1;
        z->next_out = d->out.data + d->out.len;
        z->avail_out = (uInt)(d->out.room - d->out.len);
        st = deflate(z, flush);
        d->out.len = d->out.room - z->avail_out;
        if (st == Z_STREAM_ERROR) {
            d->out.failed = 1;
            return -1;
        }
    } while (z->avail_out == 0 || z->avail_in != 0 || (flush == Z_FINISH && st != Z_STREAM_END));
    return 0;
}

int lenc_deflate_feed(lenc_deflate *d, lenc_buf *in)
{
    int st = 0;
    size_t off = 0;
    if (in->failed) d->out.failed = 1;
    while (st == 0 && off < in->len) {   /* avail_in is an unsigned int */
        size_t n = in->len - off > (1u << 30) ? (1u << 30) : in->len - off;
        st = pump(d, in->data + off, n, Z_NO_FLUSH);
        off += n;
    }
    in->len = 0;
    return d->out.failed ? -1 : st;
}

int lenc_deflate_end(lenc_deflate *d)
{
    return pump(d, NULL, 0, Z_FINISH);
}

void lenc_deflate_free(lenc_deflate *d)
{
    if (d->z != NULL) deflateEnd((z_stream *)d->z);
    free(d->z);
    d->z = NULL;
    lenc_free(&d->out);
}

/* ---------------------------------------------------------------- text */

void lenc_base64(FILE *f, const unsigned char *p, size_t n)
{
    static const char abc[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    char line[1025];
    size_t i, k = 0;
    for (i = 0; i < n; i += 3) {
        uint32_t v = (uint32_t)p[i] << 16;
        if (i + 1 < n) v |= (uint32_t)p[i + 1] << 8;
        if (i + 2 < n) v |= p[i + 2];
        line[k++] = abc[(v >> 18) & 63];
        line[k++] = abc[(v >> 12) & 63];
        line[k++] = i + 1 < n ? abc[(v >> 6) & 63] : '=';
        line[k++] = i + 2 < n ? abc[v & 63] : '=';
        if (k == 1024 || i + 3 >= n) {
            line[k++] = '\n';
            fwrite(line, 1, k, f);
            k = 0;
        }
    }
}

/* Length of the valid UTF-8 sequence at s (at most n bytes), 0 when it is not one:
 * no overlong forms, no surrogates, nothing past U+10FFFF. */
static size_t utf8_len(const unsigned char *s, size_t n)
{
    size_t len, i;
    uint32_t c;
    if (s[0] < 0x80) return 1;
    if (s[0] >= 0xC2 && s[0] <= 0xDF) len = 2, c = s[0] & 0x1Fu;
    else if (s[0] >= 0xE0 && s[0] <= 0xEF) len = 3, c = s[0] & 0x0Fu;
    else if (s[0] >= 0xF0 && s[0] <= 0xF4) len = 4, c = s[0] & 0x07u;
    else return 0;
    if (len > n) return 0;
    for (i = 1; i < len; i++) {
        if ((s[i] & 0xC0) != 0x80) return 0;
        c = (c << 6) | (s[i] & 0x3Fu);
    }
    if ((len == 3 && (c < 0x800 || (c >= 0xD800 && c <= 0xDFFF))) || (len == 4 && (c < 0x10000 || c > 0x10FFFF)))
        return 0;
    return len;
}

void lenc_json_string(FILE *f, const char *str, size_t n)
{
    const unsigned char *s = (const unsigned char *)str;
    size_t i = 0;
    fputc('"', f);
    while (i < n) {
        unsigned char c = s[i];
        size_t len;
        if (c == '"' || c == '\\') {
            fputc('\\', f);
            fputc(c, f);
            i++;
        } else if (c < 0x20 || c == '<' || c == '>' || c == '&' || c == 0x7F) {
            if (c == '\n') fputs("\\n", f);
            else if (c == '\t') fputs("\\t", f);
            else fprintf(f, "\\u%04x", c);
            i++;
        } else if ((len = utf8_len(s + i, n - i)) != 0) {
            fwrite(s + i, 1, len, f);
            i += len;
        } else {
            fputs("\\ufffd", f);
            i++;
        }
    }
    fputc('"', f);
}
