/* solver.c: sequential impulses over one-point, translation-only contacts (see solver.h). */
#include <string.h>

#include "dispatch.h"
#include "inline.h"
#include "solver.h"
#include "vec2.h"

/* The velocity sweep (the hot loop), the warm start and the position pass's preparation also
 * have AVX2 versions (dispatch.h's RG_AVX2_PATHS), picked per call from the CPU (so the
 * library stays portable x86-64); RG_NO_DISPATCH builds SSE2 only. */
#if RG_AVX2_PATHS
#define SOLVER_AVX2 1
#include "avx2.h"

/* The velocity pairs of solver bodies idx[0..8) in eight lanes, and back (every address
 * computed before the stores: they may alias idx as far as the compiler knows). */
AVX2_INLINE void solver_gather8(const float *v, const int32_t *idx, __m256 *x, __m256 *y)
{
    const float *p[8] = {SOLVER_PAIR(v, idx[0]), SOLVER_PAIR(v, idx[1]), SOLVER_PAIR(v, idx[2]), SOLVER_PAIR(v, idx[3]),
                         SOLVER_PAIR(v, idx[4]), SOLVER_PAIR(v, idx[5]), SOLVER_PAIR(v, idx[6]), SOLVER_PAIR(v, idx[7])};
    avx2_pairs_at(p, x, y);
}

AVX2_INLINE void solver_scatter8(float *v, const int32_t *idx, __m256 x, __m256 y)
{
    float *p[8] = {SOLVER_PAIR(v, idx[0]), SOLVER_PAIR(v, idx[1]), SOLVER_PAIR(v, idx[2]), SOLVER_PAIR(v, idx[3]),
                   SOLVER_PAIR(v, idx[4]), SOLVER_PAIR(v, idx[5]), SOLVER_PAIR(v, idx[6]), SOLVER_PAIR(v, idx[7])};
    avx2_pairs_put(p, x, y);
}
#else
#define SOLVER_AVX2 0
#endif

/* max and min without branches (x86 SSE: one instruction each; elsewhere plain C).  Both
 * return b when a is NaN, like the C expression. */
#if defined(__SSE2__)
#include <emmintrin.h>
#ifdef RG_DOUBLE
static inline rg_real smax(rg_real a, rg_real b) { return _mm_cvtsd_f64(_mm_max_sd(_mm_set_sd(a), _mm_set_sd(b))); }
static inline rg_real smin(rg_real a, rg_real b) { return _mm_cvtsd_f64(_mm_min_sd(_mm_set_sd(a), _mm_set_sd(b))); }
#else
static inline rg_real smax(rg_real a, rg_real b) { return _mm_cvtss_f32(_mm_max_ss(_mm_set_ss(a), _mm_set_ss(b))); }
static inline rg_real smin(rg_real a, rg_real b) { return _mm_cvtss_f32(_mm_min_ss(_mm_set_ss(a), _mm_set_ss(b))); }
#endif
#else
static inline rg_real smax(rg_real a, rg_real b) { return a > b ? a : b; }
static inline rg_real smin(rg_real a, rg_real b) { return a < b ? a : b; }
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
        rg_real pn = smax(pn0 + m * (q->vmin - vn), 0);
        /* friction: stop the sliding, within the Coulomb cone of the new normal impulse */
        rg_real maxf = q->mu * pn;
        rg_real pt = smin(smax(pt0 - m * vt, -maxf), maxf);
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
        rg_real pp = smax(q->pp + (q->pmin - vn) / im, 0);
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

#if SOLVER_AVX2
static int32_t prepare_position_avx2(solver_constraint *c, int32_t n, const float *v, const solver_params *p);
#endif

int32_t solver_prepare_position(solver_constraint *c, int32_t n, const rg_real *v,
                                const solver_params *p)
{
    int32_t pushing = 0, k = 0;
#if SOLVER_AVX2
    if (__builtin_cpu_supports("avx2")) {
        k = n - n % 8;
        pushing = prepare_position_avx2(c, k, v, p);
    }
#endif
    for (; k < n; k++) {
        solver_constraint *q = &c[k];
        const rg_real *va = SOLVER_PAIR(v, q->a), *vb = SOLVER_PAIR(v, q->b);
        rg_real vn = (vb[0] - va[0]) * q->nx + (vb[1] - va[1]) * q->ny;
        rg_real s1 = q->s0 + vn * p->dt; /* separation after the velocity pass */
        rg_real push = p->bias_rate * (-s1 - p->slop) * p->inv_dt;
        /* a gap left may close, a penetration beyond the slop is pushed out */
        q->pmin = s1 > 0 ? -s1 * p->inv_dt : (push > 0 ? rg_min(push, p->max_push) : 0);
        q->pp = 0;
        pushing += push > 0;
    }
    return pushing;
}

void solver_iterate_position(solver_constraint *c, const int32_t *list, int32_t k, rg_real *pv)
{
    for (int32_t i = 0; i < k; i++) {
        solver_constraint *q = &c[list != NULL ? list[i] : i];
        rg_real *va = SOLVER_PAIR(pv, q->a), *vb = SOLVER_PAIR(pv, q->b);
        rg_real vn = (vb[0] - va[0]) * q->nx + (vb[1] - va[1]) * q->ny;
        rg_real pp = smax(q->pp + q->m * (q->pmin - vn), 0);
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
#if SOLVER_AVX2
    return __builtin_cpu_supports("avx2");
#else
    return 0;
#endif
}

void solver_pack_rows(const solver_constraint *c, const int32_t *order, int32_t n, const int32_t *color,
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

#if SOLVER_AVX2
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
#if SOLVER_AVX2
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

#if defined(__SSE2__) && !defined(RG_DOUBLE)

/* The lanes in SSE registers.  Velocities are pairs (x, y): two lanes' pairs load into one
 * register and shuffle into x and y vectors; the stores undo it.  Lanes of one row never
 * share a movable body, so the scattered stores never collide; lanes on the ground or a
 * kinematic body store back the value they loaded. */
static inline void gather(const float *v, const int32_t *idx, __m128 *x, __m128 *y)
{
    __m128 p01 = _mm_loadl_pi(_mm_setzero_ps(), (const __m64 *)(const void *)SOLVER_PAIR(v, idx[0]));
    p01 = _mm_loadh_pi(p01, (const __m64 *)(const void *)SOLVER_PAIR(v, idx[1]));
    __m128 p23 = _mm_loadl_pi(_mm_setzero_ps(), (const __m64 *)(const void *)SOLVER_PAIR(v, idx[2]));
    p23 = _mm_loadh_pi(p23, (const __m64 *)(const void *)SOLVER_PAIR(v, idx[3]));
    *x = _mm_shuffle_ps(p01, p23, _MM_SHUFFLE(2, 0, 2, 0));
    *y = _mm_shuffle_ps(p01, p23, _MM_SHUFFLE(3, 1, 3, 1));
}

static inline void scatter(float *v, const int32_t *idx, __m128 x, __m128 y)
{
    __m128 p01 = _mm_unpacklo_ps(x, y), p23 = _mm_unpackhi_ps(x, y);
    /* the addresses first: the stores may alias idx as far as the compiler knows */
    float *p[4] = {SOLVER_PAIR(v, idx[0]), SOLVER_PAIR(v, idx[1]), SOLVER_PAIR(v, idx[2]), SOLVER_PAIR(v, idx[3])};
    _mm_storel_pi((__m64 *)(void *)p[0], p01);
    _mm_storeh_pi((__m64 *)(void *)p[1], p01);
    _mm_storel_pi((__m64 *)(void *)p[2], p23);
    _mm_storeh_pi((__m64 *)(void *)p[3], p23);
}

/* Four lanes of a row, from lane h: the loads, the arithmetic and the stores of a row are
 * those of one lane at a time, so any grouping of a row's lanes gives the same results. */
static inline void warm_start4(const solver_wide *q, int h, float *v)
{
    __m128 vax, vay, vbx, vby;
    gather(v, q->a + h, &vax, &vay);
    __m128 nx = _mm_loadu_ps(q->nx + h), ny = _mm_loadu_ps(q->ny + h);
    __m128 pn = _mm_loadu_ps(q->pn + h), pt = _mm_loadu_ps(q->pt + h);
    __m128 px = _mm_sub_ps(_mm_mul_ps(pn, nx), _mm_mul_ps(pt, ny));
    __m128 py = _mm_add_ps(_mm_mul_ps(pn, ny), _mm_mul_ps(pt, nx));
    __m128 ima = _mm_loadu_ps(q->ima + h), imb = _mm_loadu_ps(q->imb + h);
    scatter(v, q->a + h, _mm_sub_ps(vax, _mm_mul_ps(px, ima)), _mm_sub_ps(vay, _mm_mul_ps(py, ima)));
    gather(v, q->b + h, &vbx, &vby);
    scatter(v, q->b + h, _mm_add_ps(vbx, _mm_mul_ps(px, imb)), _mm_add_ps(vby, _mm_mul_ps(py, imb)));
}

static inline void iterate4(solver_wide *q, int h, float *v)
{
    const __m128 zero = _mm_setzero_ps();
    __m128 vax, vay, vbx, vby;
    gather(v, q->a + h, &vax, &vay);
    gather(v, q->b + h, &vbx, &vby);
    __m128 nx = _mm_loadu_ps(q->nx + h), ny = _mm_loadu_ps(q->ny + h), m = _mm_loadu_ps(q->m + h);
    __m128 pn0 = _mm_loadu_ps(q->pn + h), pt0 = _mm_loadu_ps(q->pt + h);
    __m128 dvx = _mm_sub_ps(vbx, vax), dvy = _mm_sub_ps(vby, vay);
    __m128 vn = _mm_add_ps(_mm_mul_ps(dvx, nx), _mm_mul_ps(dvy, ny));
    __m128 vt = _mm_sub_ps(_mm_mul_ps(dvy, nx), _mm_mul_ps(dvx, ny));
    __m128 pn = _mm_max_ps(_mm_add_ps(pn0, _mm_mul_ps(m, _mm_sub_ps(_mm_loadu_ps(q->vmin + h), vn))), zero);
    __m128 maxf = _mm_mul_ps(_mm_loadu_ps(q->mu + h), pn);
    __m128 pt = _mm_min_ps(_mm_max_ps(_mm_sub_ps(pt0, _mm_mul_ps(m, vt)), _mm_sub_ps(zero, maxf)), maxf);
    _mm_storeu_ps(q->pn + h, pn);
    _mm_storeu_ps(q->pt + h, pt);
    __m128 ln = _mm_sub_ps(pn, pn0), lt = _mm_sub_ps(pt, pt0);
    __m128 px = _mm_sub_ps(_mm_mul_ps(ln, nx), _mm_mul_ps(lt, ny));
    __m128 py = _mm_add_ps(_mm_mul_ps(ln, ny), _mm_mul_ps(lt, nx));
    __m128 ima = _mm_loadu_ps(q->ima + h), imb = _mm_loadu_ps(q->imb + h);
    scatter(v, q->a + h, _mm_sub_ps(vax, _mm_mul_ps(px, ima)), _mm_sub_ps(vay, _mm_mul_ps(py, ima)));
    scatter(v, q->b + h, _mm_add_ps(vbx, _mm_mul_ps(px, imb)), _mm_add_ps(vby, _mm_mul_ps(py, imb)));
}

static inline void iterate_position4(solver_wide *q, int h, float *pv)
{
    const __m128 zero = _mm_setzero_ps();
    __m128 vax, vay, vbx, vby;
    gather(pv, q->a + h, &vax, &vay);
    gather(pv, q->b + h, &vbx, &vby);
    __m128 nx = _mm_loadu_ps(q->nx + h), ny = _mm_loadu_ps(q->ny + h), m = _mm_loadu_ps(q->m + h);
    __m128 pp0 = _mm_loadu_ps(q->pp + h);
    __m128 vn = _mm_add_ps(_mm_mul_ps(_mm_sub_ps(vbx, vax), nx), _mm_mul_ps(_mm_sub_ps(vby, vay), ny));
    __m128 pp = _mm_max_ps(_mm_add_ps(pp0, _mm_mul_ps(m, _mm_sub_ps(_mm_loadu_ps(q->pmin + h), vn))), zero);
    _mm_storeu_ps(q->pp + h, pp);
    __m128 l = _mm_sub_ps(pp, pp0);
    __m128 px = _mm_mul_ps(l, nx), py = _mm_mul_ps(l, ny);
    __m128 ima = _mm_loadu_ps(q->ima + h), imb = _mm_loadu_ps(q->imb + h);
    scatter(pv, q->a + h, _mm_sub_ps(vax, _mm_mul_ps(px, ima)), _mm_sub_ps(vay, _mm_mul_ps(py, ima)));
    scatter(pv, q->b + h, _mm_add_ps(vbx, _mm_mul_ps(px, imb)), _mm_add_ps(vby, _mm_mul_ps(py, imb)));
}

#if SOLVER_AVX2
/* All eight lanes in AVX registers: the same operations on each lane as iterate4, so the same
 * results. */
AVX2_FN static void wide_iterate_avx2(solver_batch *s, int32_t r0, int32_t r1, float *v)
{
    const __m256 zero = _mm256_setzero_ps();
    for (int32_t r = r0; r < r1; r++) {
        solver_wide *q = &s->rows[r];
        __m256 vax, vay, vbx, vby;
        solver_gather8(v, q->a, &vax, &vay);
        solver_gather8(v, q->b, &vbx, &vby);
        __m256 nx = _mm256_loadu_ps(q->nx), ny = _mm256_loadu_ps(q->ny), m = _mm256_loadu_ps(q->m);
        __m256 pn0 = _mm256_loadu_ps(q->pn), pt0 = _mm256_loadu_ps(q->pt);
        __m256 dvx = _mm256_sub_ps(vbx, vax), dvy = _mm256_sub_ps(vby, vay);
        __m256 vn = _mm256_add_ps(_mm256_mul_ps(dvx, nx), _mm256_mul_ps(dvy, ny));
        __m256 vt = _mm256_sub_ps(_mm256_mul_ps(dvy, nx), _mm256_mul_ps(dvx, ny));
        __m256 pn =
            _mm256_max_ps(_mm256_add_ps(pn0, _mm256_mul_ps(m, _mm256_sub_ps(_mm256_loadu_ps(q->vmin), vn))), zero);
        __m256 maxf = _mm256_mul_ps(_mm256_loadu_ps(q->mu), pn);
        __m256 pt =
            _mm256_min_ps(_mm256_max_ps(_mm256_sub_ps(pt0, _mm256_mul_ps(m, vt)), _mm256_sub_ps(zero, maxf)), maxf);
        _mm256_storeu_ps(q->pn, pn);
        _mm256_storeu_ps(q->pt, pt);
        __m256 ln = _mm256_sub_ps(pn, pn0), lt = _mm256_sub_ps(pt, pt0);
        __m256 px = _mm256_sub_ps(_mm256_mul_ps(ln, nx), _mm256_mul_ps(lt, ny));
        __m256 py = _mm256_add_ps(_mm256_mul_ps(ln, ny), _mm256_mul_ps(lt, nx));
        __m256 ima = _mm256_loadu_ps(q->ima), imb = _mm256_loadu_ps(q->imb);
        solver_scatter8(v, q->a, _mm256_sub_ps(vax, _mm256_mul_ps(px, ima)),
                           _mm256_sub_ps(vay, _mm256_mul_ps(py, ima)));
        solver_scatter8(v, q->b, _mm256_add_ps(vbx, _mm256_mul_ps(px, imb)),
                           _mm256_add_ps(vby, _mm256_mul_ps(py, imb)));
    }
}
#endif

#if SOLVER_AVX2
/* warm_start4's operations on all eight lanes (a's velocities stored before b's are read,
 * as there: lanes of a row share no movable body, and the ground's velocity, +0, stays +0). */
AVX2_FN static void wide_warm_start_avx2(const solver_batch *s, int32_t r0, int32_t r1,
                                                                 float *v)
{
    for (int32_t r = r0; r < r1; r++) {
        const solver_wide *q = &s->rows[r];
        __m256 vax, vay, vbx, vby;
        solver_gather8(v, q->a, &vax, &vay);
        __m256 nx = _mm256_loadu_ps(q->nx), ny = _mm256_loadu_ps(q->ny);
        __m256 pn = _mm256_loadu_ps(q->pn), pt = _mm256_loadu_ps(q->pt);
        __m256 px = _mm256_sub_ps(_mm256_mul_ps(pn, nx), _mm256_mul_ps(pt, ny));
        __m256 py = _mm256_add_ps(_mm256_mul_ps(pn, ny), _mm256_mul_ps(pt, nx));
        __m256 ima = _mm256_loadu_ps(q->ima), imb = _mm256_loadu_ps(q->imb);
        solver_scatter8(v, q->a, _mm256_sub_ps(vax, _mm256_mul_ps(px, ima)),
                           _mm256_sub_ps(vay, _mm256_mul_ps(py, ima)));
        solver_gather8(v, q->b, &vbx, &vby);
        solver_scatter8(v, q->b, _mm256_add_ps(vbx, _mm256_mul_ps(px, imb)),
                           _mm256_add_ps(vby, _mm256_mul_ps(py, imb)));
    }
}
#endif

#if SOLVER_AVX2
/* solver_prepare_position's operations for rows c[0 .. n), n a multiple of 8, eight at once:
 * the rows' first halves (a, b, ima, imb, nx, ny, m, mu) and second halves (vmin, s0, ...)
 * through 8x8 transposes, the velocities through gather8. */
AVX2_FN static int32_t prepare_position_avx2(solver_constraint *c, int32_t n, const float *v,
                                                                      const solver_params *p)
{
    const __m256 zero = _mm256_setzero_ps(), dt = _mm256_set1_ps(p->dt), inv_dt = _mm256_set1_ps(p->inv_dt);
    const __m256 bias = _mm256_set1_ps(p->bias_rate), slop = _mm256_set1_ps(p->slop),
                 max_push = _mm256_set1_ps(p->max_push);
    int32_t pushing = 0;
    for (int32_t k = 0; k < n; k += 8) {
        solver_constraint *q = c + k;
        __m256 r[8], h[8];
        for (int l = 0; l < 8; l++) {
            r[l] = _mm256_loadu_ps((const float *)(const void *)&q[l]);
            h[l] = _mm256_loadu_ps(&q[l].vmin);
        }
        avx2_transpose8(r);
        avx2_transpose8(h);
        int32_t ia[8], ib[8];
        _mm256_storeu_si256((__m256i *)(void *)ia, _mm256_castps_si256(r[0]));
        _mm256_storeu_si256((__m256i *)(void *)ib, _mm256_castps_si256(r[1]));
        __m256 vax, vay, vbx, vby;
        solver_gather8(v, ia, &vax, &vay);
        solver_gather8(v, ib, &vbx, &vby);
        __m256 vn =
            _mm256_add_ps(_mm256_mul_ps(_mm256_sub_ps(vbx, vax), r[4]), _mm256_mul_ps(_mm256_sub_ps(vby, vay), r[5]));
        __m256 s1 = _mm256_add_ps(h[1], _mm256_mul_ps(vn, dt));
        __m256 neg_s1 = _mm256_xor_ps(s1, _mm256_set1_ps(-0.0f));
        __m256 push = _mm256_mul_ps(_mm256_mul_ps(bias, _mm256_sub_ps(neg_s1, slop)), inv_dt);
        __m256 pushes = _mm256_cmp_ps(push, zero, _CMP_GT_OQ);
        __m256 pmin = _mm256_and_ps(pushes, _mm256_min_ps(push, max_push)); /* push > 0 ? min : 0 */
        pmin = _mm256_blendv_ps(pmin, _mm256_mul_ps(neg_s1, inv_dt), _mm256_cmp_ps(s1, zero, _CMP_GT_OQ));
        float out[8];
        _mm256_storeu_ps(out, pmin);
        for (int l = 0; l < 8; l++) {
            q[l].pmin = out[l];
            q[l].pp = 0;
        }
        pushing += __builtin_popcount((unsigned)_mm256_movemask_ps(pushes));
    }
    return pushing;
}
#endif

void solver_wide_warm_start(const solver_batch *s, int32_t r0, int32_t r1, rg_real *v)
{
#if SOLVER_AVX2
    if (__builtin_cpu_supports("avx2")) {
        wide_warm_start_avx2(s, r0, r1, v);
        return;
    }
#endif
    for (int32_t r = r0; r < r1; r++)
        for (int h = 0; h < SOLVER_LANES; h += 4) warm_start4(&s->rows[r], h, v);
}

void solver_wide_iterate(solver_batch *s, int32_t r0, int32_t r1, rg_real *v)
{
#if SOLVER_AVX2
    if (__builtin_cpu_supports("avx2")) {
        wide_iterate_avx2(s, r0, r1, v);
        return;
    }
#endif
    for (int32_t r = r0; r < r1; r++)
        for (int h = 0; h < SOLVER_LANES; h += 4) iterate4(&s->rows[r], h, v);
}

void solver_wide_iterate_position(solver_batch *s, int32_t r0, int32_t r1, rg_real *pv)
{
    for (int32_t r = r0; r < r1; r++)
        for (int h = 0; h < SOLVER_LANES; h += 4) iterate_position4(&s->rows[r], h, pv);
}
#else
/* The same arithmetic lane by lane: all loads of a row before its stores, as in SSE. */
void solver_wide_warm_start(const solver_batch *s, int32_t r0, int32_t r1, rg_real *v)
{
    for (int32_t r = r0; r < r1; r++) {
        const solver_wide *q = &s->rows[r];
        rg_real px[SOLVER_LANES], py[SOLVER_LANES];
        for (int l = 0; l < SOLVER_LANES; l++) {
            px[l] = q->pn[l] * q->nx[l] - q->pt[l] * q->ny[l];
            py[l] = q->pn[l] * q->ny[l] + q->pt[l] * q->nx[l];
        }
        for (int l = 0; l < SOLVER_LANES; l++) {
            rg_real *va = SOLVER_PAIR(v, q->a[l]);
            va[0] -= px[l] * q->ima[l];
            va[1] -= py[l] * q->ima[l];
        }
        for (int l = 0; l < SOLVER_LANES; l++) {
            rg_real *vb = SOLVER_PAIR(v, q->b[l]);
            vb[0] += px[l] * q->imb[l];
            vb[1] += py[l] * q->imb[l];
        }
    }
}

void solver_wide_iterate(solver_batch *s, int32_t r0, int32_t r1, rg_real *v)
{
    for (int32_t r = r0; r < r1; r++) {
        solver_wide *q = &s->rows[r];
        rg_real ax[SOLVER_LANES], ay[SOLVER_LANES], bx[SOLVER_LANES], by[SOLVER_LANES];
        for (int l = 0; l < SOLVER_LANES; l++) {
            ax[l] = v[2 * q->a[l]];
            ay[l] = v[2 * q->a[l] + 1];
            bx[l] = v[2 * q->b[l]];
            by[l] = v[2 * q->b[l] + 1];
        }
        for (int l = 0; l < SOLVER_LANES; l++) {
            rg_real nx = q->nx[l], ny = q->ny[l], m = q->m[l];
            rg_real pn0 = q->pn[l], pt0 = q->pt[l];
            rg_real dvx = bx[l] - ax[l], dvy = by[l] - ay[l];
            rg_real vn = dvx * nx + dvy * ny, vt = dvy * nx - dvx * ny;
            rg_real pn = smax(pn0 + m * (q->vmin[l] - vn), 0);
            rg_real maxf = q->mu[l] * pn;
            rg_real pt = smin(smax(pt0 - m * vt, 0 - maxf), maxf);
            q->pn[l] = pn;
            q->pt[l] = pt;
            rg_real ln = pn - pn0, lt = pt - pt0;
            rg_real px = ln * nx - lt * ny, py = ln * ny + lt * nx;
            ax[l] -= px * q->ima[l];
            ay[l] -= py * q->ima[l];
            bx[l] += px * q->imb[l];
            by[l] += py * q->imb[l];
        }
        for (int l = 0; l < SOLVER_LANES; l++) {
            v[2 * q->a[l]] = ax[l];
            v[2 * q->a[l] + 1] = ay[l];
        }
        for (int l = 0; l < SOLVER_LANES; l++) {
            v[2 * q->b[l]] = bx[l];
            v[2 * q->b[l] + 1] = by[l];
        }
    }
}

void solver_wide_iterate_position(solver_batch *s, int32_t r0, int32_t r1, rg_real *pv)
{
    for (int32_t r = r0; r < r1; r++) {
        solver_wide *q = &s->rows[r];
        rg_real ax[SOLVER_LANES], ay[SOLVER_LANES], bx[SOLVER_LANES], by[SOLVER_LANES];
        for (int l = 0; l < SOLVER_LANES; l++) {
            ax[l] = pv[2 * q->a[l]];
            ay[l] = pv[2 * q->a[l] + 1];
            bx[l] = pv[2 * q->b[l]];
            by[l] = pv[2 * q->b[l] + 1];
        }
        for (int l = 0; l < SOLVER_LANES; l++) {
            rg_real vn = (bx[l] - ax[l]) * q->nx[l] + (by[l] - ay[l]) * q->ny[l];
            rg_real pp = smax(q->pp[l] + q->m[l] * (q->pmin[l] - vn), 0);
            rg_real d = pp - q->pp[l];
            q->pp[l] = pp;
            rg_real px = d * q->nx[l], py = d * q->ny[l];
            ax[l] -= px * q->ima[l];
            ay[l] -= py * q->ima[l];
            bx[l] += px * q->imb[l];
            by[l] += py * q->imb[l];
        }
        for (int l = 0; l < SOLVER_LANES; l++) {
            pv[2 * q->a[l]] = ax[l];
            pv[2 * q->a[l] + 1] = ay[l];
        }
        for (int l = 0; l < SOLVER_LANES; l++) {
            pv[2 * q->b[l]] = bx[l];
            pv[2 * q->b[l] + 1] = by[l];
        }
    }
}
#endif

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
