/* solver.c: sequential impulses over one-point, translation-only contacts (see solver.h). */
#include "solver.h"
#include "vec2.h"

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

void solver_warm_start(const solver_constraint *c, int32_t n, rg_real *v)
{
    for (int32_t k = 0; k < n; k++) {
        const solver_constraint *q = &c[k];
        /* P = pn n + pt t with t = (-ny, nx) */
        rg_real px = q->pn * q->nx - q->pt * q->ny;
        rg_real py = q->pn * q->ny + q->pt * q->nx;
        rg_real *va = v + 2 * q->a, *vb = v + 2 * q->b;
        va[0] -= px * q->ima;
        va[1] -= py * q->ima;
        vb[0] += px * q->imb;
        vb[1] += py * q->imb;
    }
}

void solver_iterate(solver_constraint *c, int32_t n, rg_real *v)
{
    for (int32_t k = 0; k < n; k++) {
        solver_constraint *q = &c[k];
        rg_real *va = v + 2 * q->a, *vb = v + 2 * q->b;
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

void solver_shock(solver_constraint *c, int32_t n, rg_real *v, rg_real gx, rg_real gy)
{
    for (int32_t k = 0; k < n; k++) {
        solver_constraint *q = &c[k];
        rg_real ng = q->nx * gx + q->ny * gy; /* > 0: the normal a -> b points down, a is upper */
        if (rg_fabs(ng) < RG_R(0.5)) continue;
        rg_real im = ng > 0 ? q->ima : q->imb;
        if (!(im > 0)) continue;
        rg_real m = 1 / im;
        rg_real *va = v + 2 * q->a, *vb = v + 2 * q->b;
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

void solver_shock_position(solver_constraint *c, int32_t n, rg_real *pv, rg_real gx, rg_real gy)
{
    for (int32_t k = 0; k < n; k++) {
        solver_constraint *q = &c[k];
        rg_real ng = q->nx * gx + q->ny * gy;
        if (rg_fabs(ng) < RG_R(0.5)) continue;
        rg_real im = ng > 0 ? q->ima : q->imb;
        if (!(im > 0)) continue;
        rg_real *va = pv + 2 * q->a, *vb = pv + 2 * q->b;
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

int32_t solver_prepare_position(solver_constraint *c, int32_t n, const rg_real *v,
                                const solver_params *p)
{
    int32_t pushing = 0;
    for (int32_t k = 0; k < n; k++) {
        solver_constraint *q = &c[k];
        const rg_real *va = v + 2 * q->a, *vb = v + 2 * q->b;
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

void solver_iterate_position(solver_constraint *c, int32_t n, rg_real *pv)
{
    for (int32_t k = 0; k < n; k++) {
        solver_constraint *q = &c[k];
        rg_real *va = pv + 2 * q->a, *vb = pv + 2 * q->b;
        rg_real vn = (vb[0] - va[0]) * q->nx + (vb[1] - va[1]) * q->ny;
        rg_real pp = rg_max(q->pp + q->m * (q->pmin - vn), 0);
        rg_real l = pp - q->pp;
        q->pp = pp;
        rg_real px = l * q->nx, py = l * q->ny;
        va[0] -= px * q->ima;
        va[1] -= py * q->ima;
        vb[0] += px * q->imb;
        vb[1] += py * q->imb;
    }
}
