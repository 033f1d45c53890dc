/* solver_wide.c: the rows eight at a time (solver.h's solver_wide): sequential impulses in
 * SIMD lanes, AVX2 or SSE2 in the float build on x86-64 and plain C elsewhere, the same
 * arithmetic lane by lane; and the position pass's preparation (solver_prepare_position),
 * eight rows at a time in AVX2. */
#include "dispatch.h"
#include "solver.h"
#include "vec2.h"

/* The velocity sweep (the hot loop), the warm start and the position pass's preparation also
 * have AVX2 versions (dispatch.h's RG_AVX2_PATHS), picked per call from the CPU (so the
 * library stays portable x86-64); RG_NO_DISPATCH builds SSE2 only. */
#if RG_AVX2_PATHS
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
#endif

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

#if RG_AVX2_PATHS
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

#if RG_AVX2_PATHS
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

#if RG_AVX2_PATHS
/* solver_prepare_position's operations for rows c[0 .. n), n a multiple of 8, eight at once:
 * the rows' first halves (a, b, ima, imb, nx, ny, m, mu) and second halves (vmin, s0, ...)
 * through 8x8 transposes, the velocities through gather8. */
AVX2_FN static int32_t prepare_position8(solver_constraint *c, int32_t n, const float *v,
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
#if RG_AVX2_PATHS
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
#if RG_AVX2_PATHS
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
            rg_real pn = solver_smax(pn0 + m * (q->vmin[l] - vn), 0);
            rg_real maxf = q->mu[l] * pn;
            rg_real pt = solver_smin(solver_smax(pt0 - m * vt, 0 - maxf), maxf);
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
            rg_real pp = solver_smax(q->pp[l] + q->m[l] * (q->pmin[l] - vn), 0);
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

/* (solver.h) */
int32_t solver_prepare_position(solver_constraint *c, int32_t n, const rg_real *v,
                                const solver_params *p)
{
    int32_t pushing = 0, k = 0;
#if RG_AVX2_PATHS
    if (__builtin_cpu_supports("avx2")) {
        k = n - n % 8;
        pushing = prepare_position8(c, k, v, p);
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
