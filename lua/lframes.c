/* lframes.c: the frame stream (format in lframes.h): prediction, edit lists, deflate. */
#include <stdlib.h>
#include <string.h>

#include "lframes.h"

#define RAW_CAP ((size_t)1 << 31)   /* one frame's bytes before compression */

typedef struct history {
    int64_t q[LF_CHANNELS];   /* last values (the fat box: the last one the track had) */
    int64_t q2[4];            /* x, y, vx, vy before those */
    int32_t n;                /* samples since the track was born: 0, 1, 2 (= 2 or more) */
    int32_t pad;
} history;

typedef struct flist {
    lframes_prim *p;
    int32_t n, room;
} flist;

struct lframes {
    lenc_buf raw;
    lenc_deflate z;
    size_t raw_total, cap;
    int stopped;              /* no more frames: out of memory, or the stream is full */
    int32_t frames;
    int64_t t1, t2;
    history *hist;            /* by track */
    int32_t hist_room;
    int32_t *alive, nalive, alive_room;   /* live tracks of the last frame, ascending */
    int32_t *scratch, scratch_room;
    flist prev[LFRAMES_LISTS];             /* the last frame's lists as written */
    flist sorted[LFRAMES_LISTS];           /* and sorted */
    flist spare;
    int32_t *grid, grid_room;              /* match(): hash heads, chains, used flags */
    int32_t *order, order_room;            /* write_list(): (reference, index) pairs, refs */
};

static const int prim_coords[4] = { 2, 4, 3, 4 };

lframes *lframes_new(size_t cap)
{
    lframes *e = (lframes *)calloc(1, sizeof *e);
    if (e == NULL) return NULL;
    lenc_init(&e->raw, RAW_CAP);
    e->cap = cap;
    /* Room past the cap for the last frame's flush and the end of the stream. */
    if (lenc_deflate_begin(&e->z, cap + (4u << 20)) != 0) {
        lframes_free(e);
        return NULL;
    }
    return e;
}

void lframes_free(lframes *e)
{
    int i;
    if (e == NULL) return;
    lenc_free(&e->raw);
    lenc_deflate_free(&e->z);
    free(e->hist);
    free(e->alive);
    free(e->scratch);
    free(e->grid);
    free(e->order);
    free(e->spare.p);
    for (i = 0; i < LFRAMES_LISTS; i++) {
        free(e->prev[i].p);
        free(e->sorted[i].p);
    }
    free(e);
}

static int by_track(const void *a, const void *b)
{
    int32_t x = ((const lframes_body *)a)->track, y = ((const lframes_body *)b)->track;
    return (x > y) - (x < y);
}

static int prim_cmp(const lframes_prim *a, const lframes_prim *b)
{
    int k;
    if (a->kind != b->kind) return a->kind < b->kind ? -1 : 1;
    for (k = 0; k < 4; k++)
        if (a->q[k] != b->q[k]) return a->q[k] < b->q[k] ? -1 : 1;
    return (a->col > b->col) - (a->col < b->col);
}

static int prim_qsort(const void *a, const void *b)
{
    return prim_cmp((const lframes_prim *)a, (const lframes_prim *)b);
}

/* Births and deaths against the last frame's live tracks (both ascending). */
static int write_life(lframes *e, const lframes_body *B, int32_t n)
{
    int32_t i, j, nb = 0, nd = 0, last;
    if (!lenc_grow((void **)&e->scratch, &e->scratch_room, n + e->nalive, sizeof(int32_t))) return 0;
    for (i = 0, j = 0; j < n; j++) {        /* born: in B, not in alive */
        while (i < e->nalive && e->alive[i] < B[j].track) i++;
        if (i == e->nalive || e->alive[i] != B[j].track) e->scratch[nb++] = B[j].track;
    }
    for (i = 0, j = 0; i < e->nalive; i++) {   /* dead: in alive, not in B */
        while (j < n && B[j].track < e->alive[i]) j++;
        if (j == n || B[j].track != e->alive[i]) e->scratch[nb + nd++] = e->alive[i];
    }
    lenc_uv(&e->raw, (uint64_t)nb);
    for (i = 0, last = -1; i < nb; last = e->scratch[i++]) lenc_uv(&e->raw, (uint64_t)(e->scratch[i] - last));
    lenc_uv(&e->raw, (uint64_t)nd);
    for (i = 0, last = -1; i < nd; last = e->scratch[nb + i++])
        lenc_uv(&e->raw, (uint64_t)(e->scratch[nb + i] - last));
    for (i = 0; i < nb; i++) e->hist[e->scratch[i]].n = 0;
    if (!lenc_grow((void **)&e->alive, &e->alive_room, n, sizeof(int32_t))) return 0;
    for (j = 0; j < n; j++) e->alive[j] = B[j].track;
    e->nalive = n;
    return 1;
}

static void write_bodies(lframes *e, const lframes_body *B, int32_t n)
{
    int c;
    int32_t j;
    for (c = LF_X; c <= LF_VY; c++)
        for (j = 0; j < n; j++) {
            const history *h = &e->hist[B[j].track];
            int64_t pred = h->n == 0 ? 0 : h->n == 1 ? h->q[c] : 2 * h->q[c] - h->q2[c];
            lenc_sv(&e->raw, B[j].q[c] - pred);
        }
    for (c = LF_HX; c <= LF_COL; c++)
        for (j = 0; j < n; j++) {
            const history *h = &e->hist[B[j].track];
            lenc_sv(&e->raw, B[j].q[c] - (h->n == 0 ? 0 : h->q[c]));
        }
    for (j = 0; j < n; j++) lenc_uv(&e->raw, B[j].q[LF_BOUNDS] != 0);
    for (j = 0; j < n; j++) {
        history *h = &e->hist[B[j].track];
        if (B[j].q[LF_BOUNDS] != 0) {
            for (c = LF_BX0; c <= LF_BY1; c++) {
                lenc_sv(&e->raw, B[j].q[c] - (h->n == 0 ? 0 : h->q[c]));
                h->q[c] = B[j].q[c];
            }
        } else if (h->n == 0) {
            for (c = LF_BX0; c <= LF_BY1; c++) h->q[c] = 0;
        }
    }
    for (j = 0; j < n; j++) {
        history *h = &e->hist[B[j].track];
        for (c = LF_X; c <= LF_VY; c++) {
            h->q2[c] = h->q[c];
            h->q[c] = B[j].q[c];
        }
        for (c = LF_HX; c <= LF_BOUNDS; c++) h->q[c] = B[j].q[c];
        if (h->n < 2) h->n++;
    }
}

/* ---------------------------------------------------------------- free lists */

#define MATCH_BITS 5          /* a primitive matches one of the last frame within 2^5 quanta */
#define MATCH_DIST ((int64_t)1 << MATCH_BITS)

static int64_t cell(int64_t v)
{
    return v >= 0 ? v >> MATCH_BITS : -((-v + MATCH_DIST - 1) >> MATCH_BITS);
}

static uint32_t cell_hash(int64_t cx, int64_t cy, uint32_t mask)
{
    uint64_t h = (uint64_t)cx * 0x9E3779B97F4A7C15ULL ^ (uint64_t)cy * 0xC2B2AE3D27D4EB4FULL;
    return (uint32_t)(h >> 32) & mask;
}

static int64_t dist(const lframes_prim *a, const lframes_prim *b)
{
    int64_t d = 0;
    int k;
    for (k = 0; k < prim_coords[a->kind]; k++) d += a->q[k] > b->q[k] ? a->q[k] - b->q[k] : b->q[k] - a->q[k];
    return d;
}

static int by_ref(const void *a, const void *b)
{
    const int32_t *x = (const int32_t *)a, *y = (const int32_t *)b;
    if (x[0] != y[0]) return x[0] < y[0] ? -1 : 1;
    return (x[1] > y[1]) - (x[1] < y[1]);
}

/* For each primitive of C (sorted), the nearest unused one of the last frame's list P with
 * its kind and colour within MATCH_DIST per coordinate sum, through a hash grid of P's first
 * points; ref[j] = its index or -1.  0 when out of memory. */
static int match(lframes *f, const flist *P, const lframes_prim *C, int32_t nc, int32_t *ref)
{
    uint32_t mask = 1, i;
    int32_t *head, *next, *used, j;
    while (mask < 2u * (uint32_t)P->n) mask <<= 1;
    if (!lenc_grow((void **)&f->grid, &f->grid_room, (int32_t)mask + 2 * P->n, sizeof(int32_t))) return 0;
    head = f->grid;
    next = head + mask;
    used = next + P->n;
    mask--;
    for (i = 0; i <= mask; i++) head[i] = -1;
    for (j = 0; j < P->n; j++) {
        uint32_t h = cell_hash(cell(P->p[j].q[0]), cell(P->p[j].q[1]), mask);
        next[j] = head[h];
        head[h] = j;
        used[j] = 0;
    }
    for (j = 0; j < nc; j++) {
        int64_t cx = cell(C[j].q[0]), cy = cell(C[j].q[1]), best_d = MATCH_DIST;
        int32_t best = -1, dx, dy, k;
        for (dx = -1; dx <= 1; dx++)
            for (dy = -1; dy <= 1; dy++)
                for (k = head[cell_hash(cx + dx, cy + dy, mask)]; k >= 0; k = next[k]) {
                    const lframes_prim *q = &P->p[k];
                    int64_t d;
                    if (used[k] || q->kind != C[j].kind || q->col != C[j].col) continue;
                    d = dist(q, &C[j]);
                    if (d < best_d || (d == best_d && best >= 0 && k < best)) {
                        best_d = d;
                        best = k;
                    }
                }
        ref[j] = best;
        if (best >= 0) used[best] = 1;
    }
    return 1;
}

/* The list C (sorted) against the last frame's P: 0 when it is the same list; otherwise its
 * count + 1 and each primitive as a reference to one of P (moved by small differences) or
 * as a new one.  The references come first, in P's order. */
static int write_list(lframes *f, flist *P, flist *Psorted, lframes_prim *C, int32_t nc)
{
    int32_t j, n, *ord, last = -1;
    int64_t prev_new[4] = { 0, 0, 0, 0 };
    int k;
    if (nc == Psorted->n && (nc == 0 || memcmp(C, Psorted->p, (size_t)nc * sizeof *C) == 0)) {
        lenc_uv(&f->raw, 0);
        return 1;
    }
    lenc_uv(&f->raw, (uint64_t)nc + 1);
    if (!lenc_grow((void **)&f->order, &f->order_room, 3 * nc, sizeof(int32_t))) return 0;
    ord = f->order;
    if (!match(f, P, C, nc, ord + 2 * nc)) return 0;
    for (j = 0; j < nc; j++) {     /* (ref or P->n + j for a new one, j): sorted by ref */
        int32_t r = ord[2 * nc + j];
        ord[2 * j] = r >= 0 ? r : P->n + j;
        ord[2 * j + 1] = j;
    }
    if (nc > 1) qsort(ord, (size_t)nc, 2 * sizeof(int32_t), by_ref);
    if (!lenc_grow((void **)&f->spare.p, &f->spare.room, nc, sizeof *C)) return 0;
    for (n = 0; n < nc; n++) {
        const lframes_prim *c = &C[ord[2 * n + 1]];
        int32_t r = ord[2 * n];
        f->spare.p[n] = *c;
        if (r < P->n) {
            const lframes_prim *q = &P->p[r];
            lenc_uv(&f->raw, (uint64_t)(r - last));   /* >= 1: the gap from the last reference */
            last = r;
            for (k = 0; k < prim_coords[c->kind]; k++) {
                /* a second point moves with the first: its difference from the first's */
                int64_t d = c->q[k] - q->q[k];
                if (k >= 2 && c->kind != LFRAMES_CIRCLE) d -= c->q[k - 2] - q->q[k - 2];
                lenc_sv(&f->raw, d);
            }
        } else {
            lenc_uv(&f->raw, 0);
            lenc_uv(&f->raw, (uint64_t)c->kind);
            lenc_uv(&f->raw, (uint64_t)c->col);
            for (k = 0; k < prim_coords[c->kind]; k++) {
                lenc_sv(&f->raw, c->q[k] - prev_new[k]);
                prev_new[k] = c->q[k];
            }
        }
    }
    /* P becomes this list in the order written; Psorted, this list sorted. */
    {
        flist t = *P;
        *P = f->spare;
        P->n = nc;
        f->spare = t;
    }
    if (!lenc_grow((void **)&Psorted->p, &Psorted->room, nc, sizeof *C)) return 0;
    if (nc > 0) memcpy(Psorted->p, C, (size_t)nc * sizeof *C);
    Psorted->n = nc;
    return 1;
}

int lframes_add(lframes *e, int64_t t_us, lframes_body *B, int32_t n,
                lframes_prim *lists[LFRAMES_LISTS], const int32_t counts[LFRAMES_LISTS])
{
    int32_t j, m, maxtrack = -1;
    int l;
    if (e->stopped) return -1;
    if (n > 1) qsort(B, (size_t)n, sizeof *B, by_track);
    for (j = 0, m = 0; j < n; j++) {         /* one sample per track: the last given */
        if (m > 0 && B[m - 1].track == B[j].track) m--;
        B[m++] = B[j];
    }
    n = m;
    if (n > 0) maxtrack = B[n - 1].track;
    if (!lenc_grow((void **)&e->hist, &e->hist_room, maxtrack + 1, sizeof *e->hist)) goto fail;
    lenc_sv(&e->raw, e->frames == 0 ? t_us : e->frames == 1 ? t_us - e->t1 : t_us - 2 * e->t1 + e->t2);
    e->t2 = e->t1;
    e->t1 = t_us;
    if (!write_life(e, B, n)) goto fail;
    write_bodies(e, B, n);
    for (l = 0; l < LFRAMES_LISTS; l++) {
        if (counts[l] > 1) qsort(lists[l], (size_t)counts[l], sizeof *lists[l], prim_qsort);
        if (!write_list(e, &e->prev[l], &e->sorted[l], lists[l], counts[l])) goto fail;
    }
    /* A frame compresses to at most its size plus a little (deflate's stored blocks). */
    if (e->raw.failed || e->z.out.len + e->raw.len + e->raw.len / 64 + 65536 > e->cap) goto fail;
    e->raw_total += e->raw.len;
    if (lenc_deflate_feed(&e->z, &e->raw) != 0) goto fail;
    e->frames++;
    return 0;
fail:
    /* The frames before this one stay a valid stream. */
    e->raw.len = 0;
    e->raw.failed = 0;
    e->stopped = 1;
    return -1;
}

int32_t lframes_count(const lframes *e)
{
    return e->frames;
}

const unsigned char *lframes_finish(lframes *e, size_t *out_len)
{
    e->stopped = 1;
    if (e->z.out.failed || lenc_deflate_end(&e->z) != 0) return NULL;
    *out_len = e->z.out.len;
    return e->z.out.data;
}

size_t lframes_raw_bytes(const lframes *e)
{
    return e->raw_total;
}
