/* pairs.c: fat boxes, the collision filter and the pair search (see pairs.h). */
#include "body.h"
#include "contact.h"
#include "dispatch.h"
#include "island.h"
#include "pairs.h"
#include "state.h"
#include "task.h"
#include "vec2.h"

/* Fat boxes grow by a margin of FAT_FRACTION of the shape's larger half extent, at least the
 * slop (so that two touching shapes held apart by up to the slop keep their contact) and at
 * most FAT_MARGIN.  A small margin keeps pairs few: neighbours a tenth of their size apart
 * (a settled pile, a spawn grid) are no contact until the look-ahead of their motion brings
 * them closer; it costs more refreshes only for bodies that drift without moving, which
 * sleep. */
#ifndef FAT_MARGIN
#define FAT_MARGIN       RG_R(0.1)  /* m */
#endif
#ifndef FAT_FRACTION
#define FAT_FRACTION     RG_R(0.02)
#endif
#ifndef LOOKAHEAD
#define LOOKAHEAD        RG_R(4)    /* fat boxes reach this many steps of motion ahead */
#endif

static inline rg_real pairs_margin(const collide_world *cw, const body_store *b, int32_t i)
{
    return rg_min(FAT_MARGIN, rg_max(cw->slop, FAT_FRACTION * rg_max(b->hx[i], b->hy[i])));
}

/* The fat box of a body at rest: its box grown by the margin. */
static void pairs_rest_box(const collide_world *cw, const body_store *b, int32_t i, rg_real box[4])
{
    rg_real m = pairs_margin(cw, b, i);
    box[0] = b->x[i] - b->hx[i] - m;
    box[1] = b->y[i] - b->hy[i] - m;
    box[2] = b->x[i] + b->hx[i] + m;
    box[3] = b->y[i] + b->hy[i] + m;
}

void pairs_refresh_now(rg_world *w, int32_t i, rg_real lx, rg_real ly, rg_real ux, rg_real uy,
                       rg_real mx, rg_real my, rg_real ax, rg_real ay)
{
    broadphase *bp = &w->coll.bp;
    int32_t slot = w->b.slot[i];
    rg_real m = pairs_margin(&w->coll, &w->b, i);
    mx *= LOOKAHEAD;
    my *= LOOKAHEAD;
    ax = mx + ax * (LOOKAHEAD * (LOOKAHEAD + 1) / 2);
    ay = my + ay * (LOOKAHEAD * (LOOKAHEAD + 1) / 2);
    rg_real flx = rg_min(lx, rg_min(lx + mx, lx + ax)) - m, fly = rg_min(ly, rg_min(ly + my, ly + ay)) - m;
    rg_real fux = rg_max(ux, rg_max(ux + mx, ux + ax)) + m, fuy = rg_max(uy, rg_max(uy + my, uy + ay)) + m;
    broadphase_move(bp, slot, flx, fly, fux, fuy);
    broadphase_mark_moved(bp, slot);
}

typedef struct pairs_query {
    rg_world *w;
    int32_t s, is;
    uint32_t mark;    /* the bodies s has a contact with carry it */
    int teleported;
    int failed;
    int *grow_failed; /* a contact grow failed in this search: every later try would too */
    int woke;
} pairs_query;

/* Whether the query of moved body s (dense is) meets t as a new pair candidate: not itself,
 * not a moved body before it (t's own query finds the pair), and admitted by the filter. */
static inline int pairs_candidate(const rg_world *w, int32_t s, int32_t is, int32_t t)
{
    if (t == s) return 0;
    const bp_entry *et = &w->coll.bp.e[t];
    if (et->moved && t < s) return 0;
    return pairs_admitted(w, is, body_dense(w, t));
}

/* A candidate t of the query: a contact unless s has one with t already. */
static void pairs_meet(pairs_query *q, int32_t t)
{
    rg_world *w = q->w;
    collide_world *cw = &w->coll;
    bp_entry *et = &cw->bp.e[t];
    if (et->mark == q->mark) return; /* s has a contact with t */
    /* Out of memory, the search asks once: trying the same allocations again for every
     * remaining pair would cost a failed grow per pair (44,850 for 300 overlapping bodies). */
    if ((cw->contacts.free_head < 0 && *q->grow_failed) || contact_create(w, q->s, t) < 0) {
        *q->grow_failed = 1;
        q->failed = 1;
        return;
    }
    et->mark = q->mark;
    /* a teleported body landing on a sleeping one wakes it */
    int32_t it = body_dense(w, t);
    if (q->teleported && body_partition(w, it) == BODY_PART_ASLEEP) {
        island_wake(w, t);
        q->is = body_dense(w, q->s);
        q->woke = 1;
    }
}

static void pairs_visit(void *p, int32_t t)
{
    pairs_query *q = p;
    if (pairs_candidate(q->w, q->s, q->is, t)) pairs_meet(q, t);
}

/* The queries of the move buffer in parallel: each moved body's candidates, in the order
 * its query visits them, counted (fill 0: count[k]) or written at offset count[k] of cand.
 * The broadphase does not change during the search, so these are the candidates the serial
 * walk would meet. */
typedef struct find_task {
    const rg_world *w;
    int32_t *count, *cand;
    int fill;
} find_task;

typedef struct find_visit {
    const rg_world *w;
    int32_t s, is, n;
    int32_t *out;
} find_visit;

static void pairs_collect(void *p, int32_t t)
{
    find_visit *f = p;
    if (!pairs_candidate(f->w, f->s, f->is, t)) return;
    if (f->out != NULL) f->out[f->n] = t;
    f->n++;
}

static void pairs_find_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    const find_task *t = context;
    const broadphase *bp = &t->w->coll.bp;
    (void)worker;
    for (int32_t k = begin; k < end; k++) {
        int32_t s = bp->moved[k];
        const bp_entry *e = &bp->e[s];
        find_visit f = { t->w, s, body_dense(t->w, s), 0, t->fill ? t->cand + t->count[k] : NULL };
        broadphase_query(bp, e->lx, e->ly, e->ux, e->uy, pairs_collect, &f);
        if (!t->fill) t->count[k] = f.n;
    }
}

/* Moved bodies per query range. */
#define PAIRS_RANGE 64

/* Collects every moved body's candidates in parallel into cw->pairs (count[k] .. count[k+1]
 * of cand); 0 when the search runs serially (no task system, few moved bodies, or no memory
 * for the candidates: the same pairs either way). */
static int pairs_collect_all(rg_world *w)
{
    collide_world *cw = &w->coll;
    pairs_state *ps = &cw->pairs;
    int32_t n = cw->bp.n_moved;
    if (task_workers(w) < 2 || n < 2 * PAIRS_RANGE) return 0;
    find_task t = { w, ps->count, ps->cand, 0 };
    task_for(w, pairs_find_range, n, PAIRS_RANGE, &t);
    int64_t total = 0;
    for (int32_t k = 0; k < n; k++) {
        int32_t c = ps->count[k];
        ps->count[k] = (int32_t)total;
        total += c;
    }
    ps->count[n] = (int32_t)total;
    if (total == 0) return 1; /* nothing to fill (and maybe no buffer yet) */
    if (total > ps->cand_cap) {
        if (total > INT32_MAX / 2) return 0;
        int32_t cap = (int32_t)(total + total / 2 + 64);
        int32_t *cand = mem_alloc(&w->mem, (size_t)cap * sizeof *cand);
        if (cand == NULL) return 0;
        mem_free(&w->mem, ps->cand, (size_t)ps->cand_cap * sizeof *ps->cand);
        ps->cand = cand;
        ps->cand_cap = cap;
    }
    t.cand = ps->cand;
    t.fill = 1;
    task_for(w, pairs_find_range, n, PAIRS_RANGE, &t);
    return 1;
}

int pairs_find(rg_world *w)
{
    collide_world *cw = &w->coll;
    contact_store *cs = &cw->contacts;
    broadphase *bp = &cw->bp;
    int32_t n = bp->n_moved, kept = 0;
    int woke = 0, grow_failed = 0;
    int collected = pairs_collect_all(w);
    for (int32_t k = 0; k < n; k++) {
        int32_t s = bp->moved[k];
        const bp_entry *e = &bp->e[s];
        /* contacts whose fat boxes no longer overlap end; the others' bodies are marked,
         * so the query knows its existing pairs in O(1) */
        uint32_t mark = broadphase_new_mark(bp);
        for (int32_t id = w->b.chead[body_dense(w, s)] - 1; id >= 0;) {
            int32_t next = contact_next(&cs->c[id], s), t = contact_other(&cs->c[id], s);
            if (!broadphase_overlap(bp, s, t))
                contact_destroy(w, id);
            else
                bp->e[t].mark = mark;
            id = next;
        }
        pairs_query q;
        q.w = w;
        q.s = s;
        q.mark = mark;
        q.is = body_dense(w, s);
        q.teleported = (w->b.cflags[q.is] & CF_TELEPORTED) != 0;
        q.failed = 0;
        q.grow_failed = &grow_failed;
        q.woke = 0;
        if (collected) {
            const pairs_state *ps = &cw->pairs;
            for (int32_t j = ps->count[k]; j < ps->count[k + 1]; j++) pairs_meet(&q, ps->cand[j]);
        } else {
            broadphase_query(bp, e->lx, e->ly, e->ux, e->uy, pairs_visit, &q);
        }
        woke |= q.woke;
        cw->pairs_short |= q.failed;
        if (q.failed)
            bp->e[s].moved = 2; /* out of memory: search again next step */
        else
            w->b.cflags[body_dense(w, s)] &= ~CF_TELEPORTED;
    }
    for (int32_t k = 0; k < n; k++) {
        int32_t s = bp->moved[k];
        if (bp->e[s].moved == 2) {
            bp->e[s].moved = 1;
            bp->moved[kept++] = s;
        } else {
            bp->e[s].moved = 0;
        }
    }
    bp->n_moved = kept;
    return woke;
}

typedef struct refit_task {
    rg_world *w;
    const collide_step *x;
    rg_real dt;
} refit_task;

/* The final box of active member k (dense i) and its motion for the look-ahead. */
static inline void pairs_final_box(const rg_world *w, const collide_step *x, int32_t k, int32_t i, rg_real dt,
                                   rg_real *box, rg_real *mo)
{
    const views_state *ns = &w->coll.views;
    const body_store *b = &w->b;
    rg_real x1 = b->x[i], y1 = b->y[i], hx = b->hx[i], hy = b->hy[i];
    box[0] = x1 - hx;
    box[1] = y1 - hy;
    box[2] = x1 + hx;
    box[3] = y1 + hy;
    mo[0] = b->vx[i] * dt;
    mo[1] = b->vy[i] * dt;
    /* bodies woken during the step (k >= na) have no start velocity: no trend */
    mo[2] = k < x->na ? (b->vx[i] - ns->svx0[k]) * dt : 0;
    mo[3] = k < x->na ? (b->vy[i] - ns->svy0[k]) * dt : 0;
}

#if RG_AVX2_PATHS
#include "avx2.h"

/* pairs_refit_range's test for members k .. k + 7, the consecutive bodies from dense i: the
 * final boxes (pairs_final_box's) against their fat boxes, eight at once. */
AVX2_FN static void pairs_refit8(const rg_world *w, int32_t k, int32_t i)
{
    const body_store *b = &w->b;
    __m256 x1 = _mm256_loadu_ps(b->x + i), y1 = _mm256_loadu_ps(b->y + i);
    __m256 hx = _mm256_loadu_ps(b->hx + i), hy = _mm256_loadu_ps(b->hy + i);
    uint32_t out = avx2_outside8(w->coll.bp.e, b->slot + i, _mm256_sub_ps(x1, hx), _mm256_sub_ps(y1, hy),
                                 _mm256_add_ps(x1, hx), _mm256_add_ps(y1, hy));
    avx2_bytes8(w->coll.views.refresh + k, out);
}
#endif

/* Members [begin, end): whether each final box left its fat box (ns->refresh[k]); eight
 * members of consecutive bodies at a time (pairs_refit8) where the CPU has AVX2. */
static void pairs_refit_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    const refit_task *t = context;
    const rg_world *w = t->w;
    const broadphase *bp = &w->coll.bp;
    uint8_t *refresh = w->coll.views.refresh;
    (void)worker;
    int32_t k = begin;
#if RG_AVX2_PATHS
    if (__builtin_cpu_supports("avx2")) {
        while (end - k >= 8) {
            int32_t i0 = body_dense(w, bp->active[k]), run = 1;
            for (int l = 1; l < 8; l++) run &= body_dense(w, bp->active[k + l]) == i0 + l;
            if (!run) break;
            pairs_refit8(w, k, i0);
            k += 8;
        }
    }
#endif
    for (; k < end; k++) {
        int32_t s = bp->active[k];
        rg_real box[4], mo[4];
        pairs_final_box(w, t->x, k, body_dense(w, s), t->dt, box, mo);
        refresh[k] = (uint8_t)!pairs_inside(&bp->e[s], box);
    }
}

/* Members per refit range. */
#define REFIT_RANGE 256

void pairs_refit(rg_world *w, const collide_step *x, rg_real dt)
{
    broadphase *bp = &w->coll.bp;
    const uint8_t *refresh = w->coll.views.refresh;
    refit_task t = { w, x, dt };
    task_for(w, pairs_refit_range, bp->n_active, REFIT_RANGE, &t);
    /* the broadphase changes in order, on this thread */
    for (int32_t k = 0; k < bp->n_active; k++) {
        if (!refresh[k]) continue;
        int32_t i = body_dense(w, bp->active[k]);
        rg_real box[4], mo[4];
        pairs_final_box(w, x, k, i, dt, box, mo);
        pairs_refresh_now(w, i, box[0], box[1], box[2], box[3], mo[0], mo[1], mo[2], mo[3]);
    }
}

void pairs_insert(rg_world *w, int32_t slot)
{
    collide_world *cw = &w->coll;
    int32_t i = body_dense(w, slot);
    rg_real box[4];
    pairs_rest_box(cw, &w->b, i, box);
    broadphase_insert(&cw->bp, slot, box[0], box[1], box[2], box[3]);
    if (w->b.type[i] != RG_BODY_STATIC) broadphase_activate(&cw->bp, slot);
}

void pairs_teleported(rg_world *w, int32_t slot)
{
    body_store *b = &w->b;
    int32_t i = body_dense(w, slot);
    if (b->shape[i] == RG_SHAPE_NONE) return;
    rg_real box[4];
    pairs_rest_box(&w->coll, b, i, box);
    broadphase_move(&w->coll.bp, slot, box[0], box[1], box[2], box[3]);
    broadphase_mark_moved(&w->coll.bp, slot);
    b->cflags[i] |= CF_TELEPORTED;
    island_wake_touching(w, slot);
}
