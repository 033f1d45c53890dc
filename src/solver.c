/* solver.c: sequential impulses over one-point, translation-only contacts (see solver.h). */
#include <string.h>

#include "dispatch.h"
#include "inline.h"
#include "solver.h"
#include "vec2.h"
#if RG_AVX2_PATHS
#include "avx2.h"
#endif

void solver_warm_start(const solver_constraint *c, const int32_t *list, int32_t k, rg_real *v)
{
    for (int32_t i = 0; i < k; i++) {
        const solver_constraint *q = &c[list != NULL ? list[i] : i];
        /* P = pn n + pt t with t = (-ny, nx) */
        rg_real px = q->pn * q->nx - q->pt * q->ny;
        rg_real py = q->pn * q->ny + q->pt * q->nx;
        rg_real *va = SOLVER_PAIR(v, q->a), *vb = SOLVER_PAIR(v, q->b);
        va[0] -= px * q->ima;
        va[1] -= py * q->ima;
        vb[0] += px * q->imb;
        vb[1] += py * q->imb;
    }
}

void solver_iterate(solver_constraint *c, const int32_t *list, int32_t k, rg_real *v)
{
    for (int32_t i = 0; i < k; i++) {
        solver_constraint *q = &c[list != NULL ? list[i] : i];
        rg_real *va = SOLVER_PAIR(v, q->a), *vb = SOLVER_PAIR(v, q->b);
        rg_real vax = va[0], vay = va[1], vbx = vb[0], vby = vb[1];
        rg_real nx = q->nx, ny = q->ny, m = q->m, ima = q->ima, imb = q->imb;
        rg_real pn0 = q->pn, pt0 = q->pt;
        rg_real dvx = vbx - vax, dvy = vby - vay;
        rg_real vn = dvx * nx + dvy * ny;
        rg_real vt = dvy * nx - dvx * ny;
        /* normal: reach vn = vmin, keep the total push >= 0 */
        rg_real pn = solver_smax(pn0 + m * (q->vmin - vn), 0);
        /* friction: stop the sliding, within the Coulomb cone of the new normal impulse */
        rg_real maxf = q->mu * pn;
        rg_real pt = solver_smin(solver_smax(pt0 - m * vt, -maxf), maxf);
        q->pn = pn;
        q->pt = pt;
        rg_real ln = pn - pn0, lt = pt - pt0;
        rg_real px = ln * nx - lt * ny;
        rg_real py = ln * ny + lt * nx;
        va[0] = vax - px * ima;
        va[1] = vay - py * ima;
        vb[0] = vbx + px * imb;
        vb[1] = vby + py * imb;
    }
}

/* How many rows ahead of the one it solves a shock sweep asks for (PREFETCH): the rows come
 * in solving order, scattered over the staged rows, and with workers half of them were last
 * written by the other core (its figures: commit d05123f; the sweep's time a step: step.h's
 * timers). */
#define SOLVER_SHOCK_AHEAD 16

void solver_shock(solver_constraint *c, const int32_t *order, int32_t n, rg_real *v, rg_real gx,
                  rg_real gy)
{
    for (int32_t k = 0; k < n; k++) {
        if (k + SOLVER_SHOCK_AHEAD < n) PREFETCH(&c[order[k + SOLVER_SHOCK_AHEAD]]);
        solver_constraint *q = &c[order[k]];
        rg_real ng = q->nx * gx + q->ny * gy; /* > 0: the normal a -> b points down, a is upper */
        if (rg_fabs(ng) < RG_R(0.5)) continue;
        rg_real im = ng > 0 ? q->ima : q->imb;
        if (!(im > 0)) continue;
        rg_real m = 1 / im;
        rg_real *va = SOLVER_PAIR(v, q->a), *vb = SOLVER_PAIR(v, q->b);
        rg_real dvx = vb[0] - va[0], dvy = vb[1] - va[1];
        rg_real vn = dvx * q->nx + dvy * q->ny;
        rg_real vt = dvy * q->nx - dvx * q->ny;
        rg_real pn = rg_max(q->pn + m * (q->vmin - vn), 0);
        rg_real ln = pn - q->pn;
        q->pn = pn;
        rg_real maxf = q->mu * pn;
        rg_real pt = rg_clamp(q->pt - m * vt, -maxf, maxf);
        rg_real lt = pt - q->pt;
        q->pt = pt;
        rg_real px = (ln * q->nx - lt * q->ny) * im;
        rg_real py = (ln * q->ny + lt * q->nx) * im;
        if (ng > 0) {
            va[0] -= px;
            va[1] -= py;
        } else {
            vb[0] += px;
            vb[1] += py;
        }
    }
}

void solver_shock_position(solver_constraint *c, const int32_t *order, int32_t n, rg_real *pv,
                           rg_real gx, rg_real gy)
{
    for (int32_t k = 0; k < n; k++) {
        if (k + SOLVER_SHOCK_AHEAD < n) PREFETCH(&c[order[k + SOLVER_SHOCK_AHEAD]]);
        solver_constraint *q = &c[order[k]];
        rg_real ng = q->nx * gx + q->ny * gy;
        if (rg_fabs(ng) < RG_R(0.5)) continue;
        rg_real im = ng > 0 ? q->ima : q->imb;
        if (!(im > 0)) continue;
        rg_real *va = SOLVER_PAIR(pv, q->a), *vb = SOLVER_PAIR(pv, q->b);
        rg_real vn = (vb[0] - va[0]) * q->nx + (vb[1] - va[1]) * q->ny;
        rg_real pp = solver_smax(q->pp + (q->pmin - vn) / im, 0);
        rg_real l = (pp - q->pp) * im;
        q->pp = pp;
        if (ng > 0) {
            va[0] -= l * q->nx;
            va[1] -= l * q->ny;
        } else {
            vb[0] += l * q->nx;
            vb[1] += l * q->ny;
        }
    }
}

void solver_fixed_rows(solver_constraint *c, const int32_t *list, int32_t k, rg_real *v, int position)
{
    if (position)
        solver_iterate_position(c, list, k, v);
    else
        solver_iterate(c, list, k, v);
}

void solver_iterate_position(solver_constraint *c, const int32_t *list, int32_t k, rg_real *pv)
{
    for (int32_t i = 0; i < k; i++) {
        solver_constraint *q = &c[list != NULL ? list[i] : i];
        rg_real *va = SOLVER_PAIR(pv, q->a), *vb = SOLVER_PAIR(pv, q->b);
        rg_real vn = (vb[0] - va[0]) * q->nx + (vb[1] - va[1]) * q->ny;
        rg_real pp = solver_smax(q->pp + q->m * (q->pmin - vn), 0);
        rg_real l = pp - q->pp;
        q->pp = pp;
        rg_real px = l * q->nx, py = l * q->ny;
        va[0] -= px * q->ima;
        va[1] -= py * q->ima;
        vb[0] += px * q->imb;
        vb[1] += py * q->imb;
    }
}

/* ---------------------------------------------------------------- eight lanes */

void solver_pack(const int32_t *ab, const int32_t *order, int32_t n, int32_t nbodies, uint32_t *mask,
                 int32_t *color, int32_t *lanes, solver_batch *out)
{
    const int32_t ground = 0;
    int32_t count[33];
    memset(count, 0, sizeof count);
    /* the masks of the bodies the rows meet, which alone are read (solver_rows_few) */
    if (solver_rows_few(n, nbodies)) {
        mask[ground] = 0; /* read for an immovable body, never written */
        for (int32_t j = 0; j < n; j++) mask[ab[2 * j]] = mask[ab[2 * j + 1]] = 0;
    } else {
        memset(mask, 0, (size_t)nbodies * sizeof *mask);
    }
    out->nover = 0;
    /* greedy: the first colour neither movable body is in yet; at the start of each block,
     * how many rows of each colour came before it */
    for (int32_t blk = 0; blk < SOLVER_PACK_BLOCKS(n); blk++) {
        memcpy(lanes + blk * 32, count, 32 * sizeof *count);
        int32_t j1 = (blk + 1) * SOLVER_PACK_BLOCK < n ? (blk + 1) * SOLVER_PACK_BLOCK : n;
        for (int32_t j = blk * SOLVER_PACK_BLOCK; j < j1; j++) {
            int32_t k = order[j], qa = ab[2 * k], qb = ab[2 * k + 1];
            uint32_t used = mask[qa] | mask[qb];
            int col = 32;
            if (used != 0xFFFFFFFFu) {
#ifdef __GNUC__
                col = __builtin_ctz(~used);
#else
                col = 0;
                while (used & (1u << col)) col++;
#endif
                if (qa != ground) mask[qa] |= 1u << col;
                if (qb != ground) mask[qb] |= 1u << col;
            } else {
                out->over[out->nover++] = k;
            }
            color[k] = col;
            count[col]++;
        }
    }
    /* each colour takes whole wide rows; the lanes it leaves over are padding that acts on
     * the ground with zero mass */
    int32_t start[32];
    int32_t rows = 0;
    for (int col = 0; col < 32; col++) {
        start[col] = rows;
        out->cstart[col] = rows;
        rows += (count[col] + SOLVER_LANES - 1) / SOLVER_LANES;
    }
    out->cstart[32] = rows;
    out->nrows = rows;
    /* a block's first slot in each colour */
    for (int32_t blk = 0; blk < SOLVER_PACK_BLOCKS(n); blk++)
        for (int col = 0; col < 32; col++) lanes[blk * 32 + col] += start[col] * SOLVER_LANES;
    solver_wide *w = out->rows;
    /* padding: the lanes after the last row of each colour (every other lane is filled by
     * solver_pack_rows; pmin and pp are set by solver_pack_position) */
    for (int col = 0; col < 32; col++) {
        int used = count[col] % SOLVER_LANES;
        if (used == 0) continue;
        solver_wide *q = &w[start[col] + count[col] / SOLVER_LANES];
        for (int l = used; l < SOLVER_LANES; l++) {
            out->row_of[(start[col] + count[col] / SOLVER_LANES) * SOLVER_LANES + l] = -1;
            q->a[l] = q->b[l] = ground;
            q->nx[l] = q->ny[l] = q->m[l] = q->mu[l] = q->ima[l] = q->imb[l] = 0;
            q->vmin[l] = q->pn[l] = q->pt[l] = q->pmin[l] = q->pp[l] = 0;
        }
    }
}

int solver_pack_wide(void)
{
#if RG_AVX2_PATHS
    return __builtin_cpu_supports("avx2");
#else
    return 0;
#endif
}

void solver_pack_rows(const solver_constraint *c, const int32_t *order, int32_t n, int32_t *color,
                      const int32_t *lanes, int32_t blk0, int32_t blk1, solver_batch *out)
{
    solver_wide *w = out->rows;
    int place_only = solver_pack_wide(); /* solver_pack_lanes copies */
    for (int32_t blk = blk0; blk < blk1; blk++) {
        int32_t next[32];
        memcpy(next, lanes + blk * 32, sizeof next);
        int32_t j1 = (blk + 1) * SOLVER_PACK_BLOCK < n ? (blk + 1) * SOLVER_PACK_BLOCK : n;
        for (int32_t j = blk * SOLVER_PACK_BLOCK; j < j1; j++) {
            int32_t k = order[j];
            int col = color[k];
            if (col == 32) continue; /* the overflow list (solver_pack) */
            int32_t slot = next[col]++;
            out->row_of[slot] = k;
            color[k] = slot; /* (solver.h: the line becomes this thread's) */
            if (place_only) continue;
            solver_wide *q = &w[(uint32_t)slot / SOLVER_LANES]; /* slot >= 0: a shift, not a division */
            int l = (int)((uint32_t)slot % SOLVER_LANES);
            const solver_constraint *r = &c[k];
            q->a[l] = r->a;
            q->b[l] = r->b;
            q->nx[l] = r->nx;
            q->ny[l] = r->ny;
            q->m[l] = r->m;
            q->mu[l] = r->mu;
            q->ima[l] = r->ima;
            q->imb[l] = r->imb;
            q->vmin[l] = r->vmin;
            q->pn[l] = r->pn;
            q->pt[l] = r->pt;
        }
    }
}

#if RG_AVX2_PATHS
/* solver_pack_rows's copies for wide rows [r0, r1): each lane's row of c (a padding lane's a
 * zero row on the ground, as solver_pack wrote it) in two halves, transposed. */
AVX2_FN static void pack_lanes_avx2(solver_batch *out, const solver_constraint *c, int32_t r0, int32_t r1)
{
    static const solver_constraint pad; /* a = b = 0, the ground; every value 0 */
    for (int32_t r = r0; r < r1; r++) {
        const int32_t *k = out->row_of + (size_t)r * SOLVER_LANES;
        __m256 f[8], h[8];
        for (int l = 0; l < 8; l++) {
            const solver_constraint *q = k[l] >= 0 ? &c[k[l]] : &pad;
            f[l] = _mm256_loadu_ps((const float *)(const void *)q);
            h[l] = _mm256_loadu_ps(&q->vmin);
        }
        avx2_transpose8(f); /* a, b, ima, imb, nx, ny, m, mu */
        avx2_transpose8(h); /* vmin, s0, pmin, pn, pt, pp, toi, cid */
        solver_wide *w = &out->rows[r];
        _mm256_storeu_ps((float *)(void *)w->a, f[0]);
        _mm256_storeu_ps((float *)(void *)w->b, f[1]);
        _mm256_storeu_ps(w->ima, f[2]);
        _mm256_storeu_ps(w->imb, f[3]);
        _mm256_storeu_ps(w->nx, f[4]);
        _mm256_storeu_ps(w->ny, f[5]);
        _mm256_storeu_ps(w->m, f[6]);
        _mm256_storeu_ps(w->mu, f[7]);
        _mm256_storeu_ps(w->vmin, h[0]);
        _mm256_storeu_ps(w->pn, h[3]);
        _mm256_storeu_ps(w->pt, h[4]);
    }
}
#endif

void solver_pack_lanes(solver_batch *out, const solver_constraint *c, int32_t r0, int32_t r1)
{
#if RG_AVX2_PATHS
    pack_lanes_avx2(out, c, r0, r1);
#else
    (void)out;
    (void)c;
    (void)r0;
    (void)r1;
#endif
}

void solver_unpack_wide(const solver_batch *s, solver_constraint *c, int32_t r0, int32_t r1, int position)
{
    for (int32_t r = r0; r < r1; r++) {
        const solver_wide *q = &s->rows[r];
        const int32_t *k = s->row_of + (size_t)r * SOLVER_LANES;
        for (int l = 0; l < SOLVER_LANES; l++) {
            if (k[l] < 0) continue;
            if (position) {
                c[k[l]].pp = q->pp[l];
            } else {
                c[k[l]].pn = q->pn[l];
                c[k[l]].pt = q->pt[l];
            }
        }
    }
}

void solver_pack_position(solver_batch *s, const solver_constraint *c, int32_t r0, int32_t r1)
{
    for (int32_t r = r0; r < r1; r++) {
        const int32_t *k = s->row_of + (size_t)r * SOLVER_LANES;
        solver_wide *q = &s->rows[r];
        for (int l = 0; l < SOLVER_LANES; l++) {
            q->pmin[l] = k[l] >= 0 ? c[k[l]].pmin : 0;
            q->pp[l] = 0;
        }
    }
}

/* ---------------------------------------------------------------- row storage */

static void solver_rows_layout(mem_layout *l, void *ctx)
{
    solver_rows *r = ctx;
    size_t n = (size_t)r->cap;
    /* the wide rows first: the block's own alignment */
    r->batch.rows = mem_take(l, (size_t)SOLVER_WIDE_ROWS(r->cap), sizeof(solver_wide));
    r->stage = mem_take(l, n, sizeof(solver_constraint));
    r->hgt = mem_take(l, n, sizeof(rg_real));
    r->ab = mem_take(l, n, 2 * sizeof(int32_t));
    r->ord = mem_take(l, n, sizeof(int32_t));
    r->tord = mem_take(l, n, sizeof(int32_t));
    r->batch.row_of = mem_take(l, (size_t)SOLVER_WIDE_ROWS(r->cap) * SOLVER_LANES, sizeof(int32_t));
    r->batch.over = mem_take(l, n, sizeof(int32_t));
    r->color = mem_take(l, n, sizeof(int32_t));
    r->imp = mem_take(l, n, sizeof(int32_t));
    r->fixed = mem_take(l, n, sizeof(int32_t));
    r->late = mem_take(l, 3 * n + 2 * (size_t)SOLVER_STAGE_BLOCKS(r->cap), sizeof(int32_t));
    r->lanes = mem_take(l, (size_t)SOLVER_PACK_BLOCKS(r->cap) * 32, sizeof(int32_t));
    r->edge = mem_take(l, (size_t)SOLVER_WIDE_ROWS(r->cap), sizeof(int32_t));
    r->key = mem_take(l, n, sizeof(uint16_t));
    r->tkey = mem_take(l, n, sizeof(uint16_t));
}

rg_status solver_rows_alloc(solver_rows *fresh, const rg_mem *m, int32_t cap)
{
    memset(fresh, 0, sizeof *fresh);
    fresh->cap = cap;
    fresh->block = mem_block(m, solver_rows_layout, fresh, &fresh->block_size);
    return fresh->block != NULL ? RG_OK : RG_ERR_OUT_OF_MEMORY;
}

static void solver_rows_spare_layout(mem_layout *l, void *ctx)
{
    solver_rows *r = ctx;
    size_t n = (size_t)r->cap;
    r->spare.stage = mem_take(l, n, sizeof(solver_constraint));
    r->spare.hgt = mem_take(l, n, sizeof(rg_real));
    r->spare.ab = mem_take(l, n, 2 * sizeof(int32_t));
    r->spare.imp = mem_take(l, n, sizeof(int32_t));
    r->mean = mem_take(l, (size_t)SOLVER_STAGE_BLOCKS(r->cap), sizeof(int32_t));
    r->handed = mem_take(l, (size_t)SOLVER_STAGE_BLOCKS(r->cap), sizeof(int32_t));
}

int solver_rows_spare(solver_rows *r, const rg_mem *m)
{
    if (r->spare_block == NULL) r->spare_block = mem_block(m, solver_rows_spare_layout, r, &r->spare_size);
    return r->spare_block != NULL;
}

void solver_rows_release(solver_rows *r, const rg_mem *m)
{
    mem_free(m, r->block, r->block_size);
    mem_free(m, r->spare_block, r->spare_size);
    memset(r, 0, sizeof *r);
}
