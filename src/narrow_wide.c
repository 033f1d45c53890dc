/* narrow_wide.c: the narrowphase's measurement and decision of eight contacts at once (see
 * narrow_wide.h).  Each function mirrors its scalar original in narrow.c or collision.h, in
 * the same order of operations; comparisons keep C's answer for NaN (an ordered compare
 * where C's is true only for numbers, an unordered one where C negates one). */
#include "narrow_wide.h"
#include "vec2.h"

int narrow_wide_ready(const struct rg_world *w)
{
#if RG_AVX2_PATHS
    return w->coll.continuous && w->pre_solve == NULL && __builtin_cpu_supports("avx2");
#else
    (void)w;
    return 0;
#endif
}

#if RG_AVX2_PATHS
#include <float.h>
#include <stddef.h>

#include "avx2.h"

typedef struct narrow_wide_body {
    __m256 sx, sy, dx, dy, vx, vy, hx, hy, gs, im;
} narrow_wide_body;

/* The eight views' fields, lane l from v[l]: the first eight (sx .. hy) as an 8x8 transpose,
 * gs and im as pairs (they follow each other in a cbody). */
AVX2_INLINE void narrow_wide_gather(const cbody *const *v, narrow_wide_body *o)
{
    __m256 r[8] = {_mm256_loadu_ps(&v[0]->sx), _mm256_loadu_ps(&v[1]->sx), _mm256_loadu_ps(&v[2]->sx),
                   _mm256_loadu_ps(&v[3]->sx), _mm256_loadu_ps(&v[4]->sx), _mm256_loadu_ps(&v[5]->sx),
                   _mm256_loadu_ps(&v[6]->sx), _mm256_loadu_ps(&v[7]->sx)};
    avx2_transpose8(r);
    o->sx = r[0];
    o->sy = r[1];
    o->dx = r[2];
    o->dy = r[3];
    o->vx = r[4];
    o->vy = r[5];
    o->hx = r[6];
    o->hy = r[7];
    const float *gi[8] = {&v[0]->gs, &v[1]->gs, &v[2]->gs, &v[3]->gs, &v[4]->gs, &v[5]->gs, &v[6]->gs, &v[7]->gs};
    avx2_pairs_at(gi, &o->gs, &o->im);
}

AVX2_INLINE __m256 narrow_wide_abs(__m256 v) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), v); }
AVX2_INLINE __m256 narrow_wide_neg(__m256 v) { return _mm256_xor_ps(_mm256_set1_ps(-0.0f), v); }
/* coll_sign: v < 0 ? -1 : 1 */
AVX2_INLINE __m256 narrow_wide_sign(__m256 v)
{
    return _mm256_blendv_ps(_mm256_set1_ps(1.0f), _mm256_set1_ps(-1.0f),
                            _mm256_cmp_ps(v, _mm256_setzero_ps(), _CMP_LT_OQ));
}
/* m ? a : b */
AVX2_INLINE __m256 narrow_wide_pick(__m256 m, __m256 a, __m256 b) { return _mm256_blendv_ps(b, a, m); }
#define NARROW_WIDE_CMP(a, b, op) _mm256_cmp_ps((a), (b), (op))
#define NARROW_WIDE_AND(a, b) _mm256_and_ps((a), (b))
#define NARROW_WIDE_OR(a, b) _mm256_or_ps((a), (b))

/* narrow_far_apart, for the lanes whose pair is not touching (the caller masks it). */
AVX2_INLINE __m256 narrow_wide_far_apart(const narrow_wide_body *A, const narrow_wide_body *B, __m256 circles,
                                                __m256 slop)
{
    __m256 gx = _mm256_sub_ps(narrow_wide_abs(_mm256_sub_ps(B->sx, A->sx)), _mm256_add_ps(A->hx, B->hx));
    __m256 gy = _mm256_sub_ps(narrow_wide_abs(_mm256_sub_ps(B->sy, A->sy)), _mm256_add_ps(A->hy, B->hy));
    __m256 reach = _mm256_add_ps(
        _mm256_add_ps(_mm256_add_ps(narrow_wide_abs(A->dx), narrow_wide_abs(A->dy)), narrow_wide_abs(B->dx)),
        narrow_wide_abs(B->dy));
    __m256 u = _mm256_add_ps(
        _mm256_add_ps(_mm256_add_ps(narrow_wide_abs(A->sx), narrow_wide_abs(A->sy)), narrow_wide_abs(B->sx)),
        narrow_wide_abs(B->sy));
    u = _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_add_ps(u, reach), A->hx), A->hy), B->hx),
                      B->hy);
    __m256 ulps = _mm256_mul_ps(u, _mm256_set1_ps(64 * RG_EPSILON));
    __m256 need = _mm256_add_ps(_mm256_add_ps(reach, _mm256_mul_ps(_mm256_set1_ps(SPECULATIVE + 1), slop)), ulps);
    __m256 apart = NARROW_WIDE_CMP(_mm256_max_ps(gx, gy), need, _CMP_GE_OQ);
    __m256 no_graze = NARROW_WIDE_AND(NARROW_WIDE_CMP(narrow_wide_abs(gx), slop, _CMP_GT_OQ),
                                      NARROW_WIDE_CMP(narrow_wide_abs(gy), slop, _CMP_GT_OQ));
    return NARROW_WIDE_AND(apart, NARROW_WIDE_OR(circles, no_graze));
}

typedef struct narrow_wide_manifold {
    __m256 nx, ny, px, py, depth;
} narrow_wide_manifold;

/* coll_contact_boxes: the grazing faces first, else coll_boxes. */
AVX2_INLINE void narrow_wide_boxes(const narrow_wide_body *A, const narrow_wide_body *B, __m256 rx, __m256 ry,
                                          __m256 tol, narrow_wide_manifold *m)
{
    const __m256 zero = _mm256_setzero_ps(), half = _mm256_set1_ps(0.5f);
    __m256 dx = _mm256_sub_ps(B->sx, A->sx), dy = _mm256_sub_ps(B->sy, A->sy);
    __m256 adx = narrow_wide_abs(dx), ady = narrow_wide_abs(dy);
    __m256 ox = _mm256_sub_ps(_mm256_add_ps(A->hx, B->hx), adx);
    __m256 oy = _mm256_sub_ps(_mm256_add_ps(A->hy, B->hy), ady);
    __m256 sx = narrow_wide_sign(dx), sy = narrow_wide_sign(dy);
    /* coll_graze_boxes */
    __m256 x_closes = NARROW_WIDE_AND(NARROW_WIDE_CMP(_mm256_mul_ps(dx, rx), zero, _CMP_LT_OQ),
                                      NARROW_WIDE_CMP(narrow_wide_neg(ox), _mm256_add_ps(tol, narrow_wide_abs(rx)),
                                                      _CMP_LE_OQ));
    __m256 y_closes = NARROW_WIDE_AND(NARROW_WIDE_CMP(_mm256_mul_ps(dy, ry), zero, _CMP_LT_OQ),
                                      NARROW_WIDE_CMP(narrow_wide_neg(oy), _mm256_add_ps(tol, narrow_wide_abs(ry)),
                                                      _CMP_LE_OQ));
    __m256 y_can = NARROW_WIDE_AND(NARROW_WIDE_CMP(narrow_wide_abs(oy), tol, _CMP_LE_OQ),
                                   NARROW_WIDE_OR(NARROW_WIDE_CMP(ox, zero, _CMP_GT_OQ), x_closes));
    __m256 x_can = NARROW_WIDE_AND(NARROW_WIDE_CMP(narrow_wide_abs(ox), tol, _CMP_LE_OQ),
                                   NARROW_WIDE_OR(NARROW_WIDE_CMP(oy, zero, _CMP_GT_OQ), y_closes));
    /* coll_graze_y: both overlapping, the least penetration; else along the motion */
    __m256 both_over = NARROW_WIDE_AND(NARROW_WIDE_CMP(ox, zero, _CMP_GT_OQ), NARROW_WIDE_CMP(oy, zero, _CMP_GT_OQ));
    __m256 prefer_y = narrow_wide_pick(both_over, NARROW_WIDE_CMP(ox, oy, _CMP_GE_OQ),
                                       NARROW_WIDE_CMP(narrow_wide_abs(rx), narrow_wide_abs(ry), _CMP_GE_OQ));
    __m256 y_face = _mm256_andnot_ps(_mm256_andnot_ps(prefer_y, x_can), y_can);
    __m256 x_face = _mm256_andnot_ps(y_face, x_can);
    __m256 yf_px = _mm256_sub_ps(B->sx, _mm256_mul_ps(sx, _mm256_min_ps(B->hx, adx)));
    __m256 yf_py = _mm256_add_ps(A->sy, _mm256_mul_ps(sy, A->hy));
    __m256 xf_px = _mm256_add_ps(A->sx, _mm256_mul_ps(sx, A->hx));
    __m256 xf_py = _mm256_sub_ps(B->sy, _mm256_mul_ps(sy, _mm256_min_ps(B->hy, ady)));
    /* coll_boxes: along x when !(ox >= oy) */
    __m256 along_x = NARROW_WIDE_CMP(ox, oy, _CMP_NGE_UQ);
    __m256 ax_lo = _mm256_max_ps(_mm256_sub_ps(A->sy, A->hy), _mm256_sub_ps(B->sy, B->hy));
    __m256 ax_hi = _mm256_min_ps(_mm256_add_ps(A->sy, A->hy), _mm256_add_ps(B->sy, B->hy));
    __m256 ax_px = _mm256_mul_ps(
        _mm256_add_ps(_mm256_add_ps(A->sx, _mm256_mul_ps(sx, A->hx)), _mm256_sub_ps(B->sx, _mm256_mul_ps(sx, B->hx))),
        half);
    __m256 ax_py = _mm256_mul_ps(_mm256_add_ps(ax_lo, ax_hi), half);
    __m256 ay_lo = _mm256_max_ps(_mm256_sub_ps(A->sx, A->hx), _mm256_sub_ps(B->sx, B->hx));
    __m256 ay_hi = _mm256_min_ps(_mm256_add_ps(A->sx, A->hx), _mm256_add_ps(B->sx, B->hx));
    __m256 ay_px = _mm256_mul_ps(_mm256_add_ps(ay_lo, ay_hi), half);
    __m256 ay_py = _mm256_mul_ps(
        _mm256_add_ps(_mm256_add_ps(A->sy, _mm256_mul_ps(sy, A->hy)), _mm256_sub_ps(B->sy, _mm256_mul_ps(sy, B->hy))),
        half);
    __m256 b_nx = narrow_wide_pick(along_x, sx, zero), b_ny = narrow_wide_pick(along_x, zero, sy);
    __m256 b_depth = narrow_wide_pick(along_x, ox, oy);
    b_depth = narrow_wide_pick(NARROW_WIDE_CMP(oy, oy, _CMP_UNORD_Q), oy, b_depth); /* NaN in, NaN out */
    __m256 b_px = narrow_wide_pick(along_x, ax_px, ay_px), b_py = narrow_wide_pick(along_x, ax_py, ay_py);
    /* the grazing faces over the boxes' manifold */
    m->nx = narrow_wide_pick(y_face, zero, narrow_wide_pick(x_face, sx, b_nx));
    m->ny = narrow_wide_pick(y_face, sy, narrow_wide_pick(x_face, zero, b_ny));
    m->depth = narrow_wide_pick(y_face, oy, narrow_wide_pick(x_face, ox, b_depth));
    m->px = narrow_wide_pick(y_face, yf_px, narrow_wide_pick(x_face, xf_px, b_px));
    m->py = narrow_wide_pick(y_face, yf_py, narrow_wide_pick(x_face, xf_py, b_py));
}

/* narrow_measure's two circles at the start of the step; depth is -s0. */
AVX2_INLINE void narrow_wide_circles(const narrow_wide_body *A, const narrow_wide_body *B,
                                            narrow_wide_manifold *m)
{
    const __m256 zero = _mm256_setzero_ps();
    __m256 ex = _mm256_sub_ps(B->sx, A->sx), ey = _mm256_sub_ps(B->sy, A->sy);
    __m256 dist = _mm256_sqrt_ps(_mm256_add_ps(_mm256_mul_ps(ex, ex), _mm256_mul_ps(ey, ey)));
    __m256 pos = NARROW_WIDE_CMP(dist, zero, _CMP_GT_OQ);
    __m256 inv = _mm256_div_ps(_mm256_set1_ps(1.0f), dist);
    __m256 nx = narrow_wide_pick(pos, _mm256_mul_ps(ex, inv), zero);
    __m256 ny = narrow_wide_pick(pos, _mm256_mul_ps(ey, inv), _mm256_set1_ps(1.0f));
    __m256 s0 = _mm256_sub_ps(_mm256_sub_ps(dist, A->hx), B->hx);
    __m256 f = _mm256_add_ps(A->hx, _mm256_mul_ps(_mm256_set1_ps(0.5f), s0));
    m->nx = nx;
    m->ny = ny;
    m->px = _mm256_add_ps(A->sx, _mm256_mul_ps(nx, f));
    m->py = _mm256_add_ps(A->sy, _mm256_mul_ps(ny, f));
    m->depth = narrow_wide_neg(s0);
}

/* narrow_is_ground, for the lanes of mask `has` (gs != 0). */
AVX2_INLINE __m256 narrow_wide_ground(__m256 gx, __m256 gy, __m256 gs, __m256 nx, __m256 ny)
{
    const __m256 zero = _mm256_setzero_ps();
    __m256 ex = _mm256_mul_ps(gx, gs), ey = _mm256_mul_ps(gy, gs);
    __m256 up = narrow_wide_neg(_mm256_add_ps(_mm256_mul_ps(nx, ex), _mm256_mul_ps(ny, ey)));
    __m256 g2 = _mm256_add_ps(_mm256_mul_ps(ex, ex), _mm256_mul_ps(ey, ey));
    __m256 ok = NARROW_WIDE_AND(NARROW_WIDE_CMP(g2, zero, _CMP_GT_OQ), NARROW_WIDE_CMP(up, zero, _CMP_GT_OQ));
    ok = NARROW_WIDE_AND(
        ok, NARROW_WIDE_CMP(_mm256_mul_ps(up, up), _mm256_mul_ps(_mm256_set1_ps(COS45 * COS45), g2), _CMP_GE_OQ));
    return NARROW_WIDE_AND(ok, NARROW_WIDE_CMP(gs, zero, _CMP_NEQ_UQ));
}

/* rg_finite */
AVX2_INLINE __m256 narrow_wide_finite(__m256 v)
{
    return NARROW_WIDE_CMP(narrow_wide_abs(v), _mm256_set1_ps(FLT_MAX), _CMP_LE_OQ);
}

/* The eight values of two neighbouring fields of the lanes' contacts (mu and e, pn and pt). */
AVX2_INLINE void narrow_wide_fields(contact *const *c, size_t offset, __m256 *f0, __m256 *f1)
{
    const float *p[8];
    for (int l = 0; l < 8; l++) p[l] = (const float *)(const void *)((const char *)c[l] + offset);
    avx2_pairs_at(p, f0, f1);
}

/* resolve_stage (resolve.h) for the lanes of stage, in lane order, into st->d: each value
 * as there (resolve_index, the views' inverse masses of awake bodies, m = 1 / (ima + imb),
 * solver_vmin), a row's two halves through 8x8 transposes. */
AVX2_INLINE void narrow_wide_stage_rows(narrow_wide_stage *st, contact *const *c,
                                        uint32_t stage, __m256 ima, __m256 imb, __m256 nx, __m256 ny, __m256 px,
                                        __m256 py, __m256 s0, __m256 vn0, __m256 toi, __m256 closing)
{
    const collide_step *x = st->x;
    const solver_params *p = &x->p;
    const __m256 zero = _mm256_setzero_ps();
    __m256i n = _mm256_set1_epi32(x->n), one = _mm256_set1_epi32(1);
    __m256i ia = _mm256_loadu_si256((const __m256i *)(const void *)st->ia);
    __m256i ib = _mm256_loadu_si256((const __m256i *)(const void *)st->ib);
    __m256i awake_a = _mm256_cmpgt_epi32(n, ia), awake_b = _mm256_cmpgt_epi32(n, ib);
    ima = _mm256_and_ps(_mm256_castsi256_ps(awake_a), ima);
    imb = _mm256_and_ps(_mm256_castsi256_ps(awake_b), imb);
    __m256 mu, e, pn, pt;
    narrow_wide_fields(c, offsetof(contact, mu), &mu, &e);
    narrow_wide_fields(c, offsetof(contact, pn), &pn, &pt);
    __m256 vmin = _mm256_and_ps(NARROW_WIDE_CMP(s0, zero, _CMP_GT_OQ),
                                _mm256_mul_ps(narrow_wide_neg(s0), _mm256_set1_ps(p->inv_dt)));
    __m256 bounce = _mm256_mul_ps(narrow_wide_neg(e), vn0);
    __m256 bounces = NARROW_WIDE_AND(
        NARROW_WIDE_AND(closing, NARROW_WIDE_CMP(e, zero, _CMP_GT_OQ)),
        NARROW_WIDE_AND(NARROW_WIDE_CMP(vn0, _mm256_set1_ps(-p->restitution_threshold), _CMP_LT_OQ),
                        NARROW_WIDE_CMP(bounce, vmin, _CMP_GT_OQ)));
    vmin = narrow_wide_pick(bounces, bounce, vmin);
    /* resolve_index: the solver body of an awake body, else the ground */
    __m256i qa = _mm256_and_si256(awake_a, _mm256_add_epi32(ia, one));
    __m256i qb = _mm256_and_si256(awake_b, _mm256_add_epi32(ib, one));
    __m256 r[8] = {_mm256_castsi256_ps(qa),
                   _mm256_castsi256_ps(qb),
                   ima,
                   imb,
                   nx,
                   ny,
                   _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_add_ps(ima, imb)),
                   mu};
    __m256 h[8] = {vmin, s0, zero, pn, pt, zero, toi,
                   _mm256_castsi256_ps(_mm256_loadu_si256((const __m256i *)(const void *)st->id))};
    avx2_transpose8(r);
    avx2_transpose8(h);
    float o_toi[8];
    int32_t o_a[8], o_b[8]; /* solver_row_bodies: a movable body's index, else 0 */
    _mm256_storeu_ps(o_toi, toi);
    _mm256_storeu_si256((__m256i *)(void *)o_a,
                        _mm256_and_si256(_mm256_castps_si256(NARROW_WIDE_CMP(ima, zero, _CMP_GT_OQ)), qa));
    _mm256_storeu_si256((__m256i *)(void *)o_b,
                        _mm256_and_si256(_mm256_castps_si256(NARROW_WIDE_CMP(imb, zero, _CMP_GT_OQ)), qb));
    /* resolve_stage's height along gravity */
    float o_h[8];
    _mm256_storeu_ps(o_h, narrow_wide_neg(_mm256_add_ps(_mm256_mul_ps(px, _mm256_set1_ps(x->ux)),
                                                        _mm256_mul_ps(py, _mm256_set1_ps(x->uy)))));
    /* in locals: the stores could alias the counts and the arrays' pointers */
    solver_constraint *const out = st->d.stage;
    rg_real *const hgt = st->d.hgt;
    int32_t *const imp = st->d.imp, *const ab = st->d.ab;
    int32_t k = *st->d.nc, nimp = *st->d.nimp;
    for (uint32_t left = stage; left != 0; left &= left - 1, k++) {
        int l = __builtin_ctz(left);
        _mm256_storeu_ps((float *)(void *)&out[k], r[l]);
        _mm256_storeu_ps(&out[k].vmin, h[l]);
        hgt[k] = o_h[l];
        ab[2 * k] = o_a[l];
        ab[2 * k + 1] = o_b[l];
        if (o_toi[l] > 0) imp[nimp++] = k;
    }
    *st->d.nc = k;
    *st->d.nimp = nimp;
}

AVX2_FN uint32_t narrow_wide_decide(const struct rg_world *w, const narrow_lanes *in, contact *const *c,
                                             uint32_t *bits, narrow_wide_stage *st)
{
    const __m256i zero_i = _mm256_setzero_si256();
    __m256i F = _mm256_loadu_si256((const __m256i *)(const void *)in->flags);
    __m256i KA = _mm256_loadu_si256((const __m256i *)(const void *)in->kind_a);
    __m256i KB = _mm256_loadu_si256((const __m256i *)(const void *)in->kind_b);
    __m256i circle_i = _mm256_cmpeq_epi32(KA, _mm256_set1_epi32(RG_SHAPE_CIRCLE));
    __m256i kinds =
        _mm256_and_si256(_mm256_cmpeq_epi32(KA, KB),
                         _mm256_or_si256(circle_i, _mm256_cmpeq_epi32(KA, _mm256_set1_epi32(RG_SHAPE_AABB))));
    __m256i plain = _mm256_cmpeq_epi32(
        _mm256_and_si256(F, _mm256_set1_epi32(CT_ONEWAY | CT_PASS | CT_SENSOR | CT_ACTIVE)), zero_i);
    uint32_t fits = (uint32_t)_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_and_si256(kinds, plain))) & ~in->asleep;
    if (fits == 0) return 0;
    __m256i was_i =
        _mm256_cmpeq_epi32(_mm256_and_si256(F, _mm256_set1_epi32(CT_TOUCHING)), _mm256_set1_epi32(CT_TOUCHING));
    __m256 circle = _mm256_castsi256_ps(circle_i), was = _mm256_castsi256_ps(was_i);
    narrow_wide_body A, B;
    narrow_wide_gather(in->a, &A);
    narrow_wide_gather(in->b, &B);
    const __m256 zero = _mm256_setzero_ps();
    const __m256 slop = _mm256_set1_ps(w->coll.slop);
    uint32_t circles = fits & (uint32_t)_mm256_movemask_ps(circle);
    uint32_t was_m = (uint32_t)_mm256_movemask_ps(was);
    /* narrow_far: only a pair that is not touching */
    __m256 far = _mm256_setzero_ps();
    if ((fits & ~was_m) != 0) far = _mm256_andnot_ps(was, narrow_wide_far_apart(&A, &B, circle, slop));
    /* narrow_measure: the boxes' manifold, the circles', or both and each lane its own */
    __m256 rx = _mm256_sub_ps(B.dx, A.dx), ry = _mm256_sub_ps(B.dy, A.dy);
    narrow_wide_manifold m;
    if (circles == 0) {
        narrow_wide_boxes(&A, &B, rx, ry, slop, &m);
    } else if (circles == fits) {
        narrow_wide_circles(&A, &B, &m);
    } else {
        narrow_wide_manifold mb, mc;
        narrow_wide_boxes(&A, &B, rx, ry, slop, &mb);
        narrow_wide_circles(&A, &B, &mc);
        m.nx = narrow_wide_pick(circle, mc.nx, mb.nx);
        m.ny = narrow_wide_pick(circle, mc.ny, mb.ny);
        m.px = narrow_wide_pick(circle, mc.px, mb.px);
        m.py = narrow_wide_pick(circle, mc.py, mb.py);
        m.depth = narrow_wide_pick(circle, mc.depth, mb.depth);
    }
    __m256 nx = m.nx, ny = m.ny, px = m.px, py = m.py, s0 = narrow_wide_neg(m.depth);
    __m256 size = _mm256_min_ps(_mm256_min_ps(A.hx, A.hy), _mm256_min_ps(B.hx, B.hy));
    __m256 slow = NARROW_WIDE_CMP(_mm256_add_ps(_mm256_mul_ps(rx, rx), _mm256_mul_ps(ry, ry)),
                                  _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(0.25f), size), size), _CMP_LE_OQ);
    /* apart and fast: the time of impact, which the scalar code takes */
    __m256 sweep = _mm256_andnot_ps(far, _mm256_andnot_ps(slow, NARROW_WIDE_CMP(s0, slop, _CMP_GT_OQ)));
    uint32_t done = fits & ~(uint32_t)_mm256_movemask_ps(sweep);
    if (done == 0) return 0;
    /* narrow_decide, active */
    __m256 vn0 =
        _mm256_add_ps(_mm256_mul_ps(_mm256_sub_ps(B.vx, A.vx), nx), _mm256_mul_ps(_mm256_sub_ps(B.vy, A.vy), ny));
    __m256 d = _mm256_add_ps(_mm256_add_ps(s0, _mm256_mul_ps(rx, nx)), _mm256_mul_ps(ry, ny));
    __m256 now = NARROW_WIDE_OR(NARROW_WIDE_CMP(d, zero, _CMP_LE_OQ),
                                NARROW_WIDE_AND(was, NARROW_WIDE_CMP(d, slop, _CMP_LT_OQ)));
    __m256 closing = NARROW_WIDE_CMP(d, zero, _CMP_LT_OQ);
    __m256 reach = _mm256_add_ps(narrow_wide_abs(_mm256_add_ps(_mm256_mul_ps(A.dx, nx), _mm256_mul_ps(A.dy, ny))),
                                 narrow_wide_abs(_mm256_add_ps(_mm256_mul_ps(B.dx, nx), _mm256_mul_ps(B.dy, ny))));
    __m256 solve =
        NARROW_WIDE_CMP(_mm256_sub_ps(s0, reach), _mm256_mul_ps(_mm256_set1_ps(SPECULATIVE), slop), _CMP_LT_OQ);
    solve = NARROW_WIDE_AND(solve, NARROW_WIDE_AND(narrow_wide_finite(s0), narrow_wide_finite(vn0)));
    __m256 stage = NARROW_WIDE_AND(solve, NARROW_WIDE_CMP(_mm256_add_ps(A.im, B.im), zero, _CMP_GT_OQ));
    /* toi: was || s0 <= 0 ? 0 : -1, and where d < 0: s0 > 0 && !was ? s0 / (s0 - d) : 0 */
    __m256 toi =
        narrow_wide_pick(NARROW_WIDE_OR(was, NARROW_WIDE_CMP(s0, zero, _CMP_LE_OQ)), zero, _mm256_set1_ps(-1.0f));
    __m256 timed = _mm256_andnot_ps(was, NARROW_WIDE_CMP(s0, zero, _CMP_GT_OQ));
    toi = narrow_wide_pick(closing, narrow_wide_pick(timed, _mm256_div_ps(s0, _mm256_sub_ps(s0, d)), zero), toi);
    __m256 gx = _mm256_set1_ps(w->gravity.x), gy = _mm256_set1_ps(w->gravity.y);
    __m256 ground_a =
        NARROW_WIDE_AND(now, narrow_wide_ground(gx, gy, A.gs, narrow_wide_neg(nx), narrow_wide_neg(ny)));
    __m256 ground_b = NARROW_WIDE_AND(now, narrow_wide_ground(gx, gy, B.gs, nx, ny));
    /* the flags and the bits as narrow_decide leaves them: far apart, or solved */
    __m256i now_i = _mm256_castps_si256(now), flip = _mm256_xor_si256(now_i, was_i);
    __m256i fl = _mm256_andnot_si256(_mm256_set1_epi32(CT_SOLVE | CT_CLOSING), F);
    fl = _mm256_or_si256(fl, _mm256_and_si256(_mm256_castps_si256(closing), _mm256_set1_epi32(CT_CLOSING)));
    fl = _mm256_or_si256(fl, _mm256_and_si256(_mm256_castps_si256(stage), _mm256_set1_epi32(CT_SOLVE)));
    fl = _mm256_xor_si256(fl, _mm256_and_si256(flip, _mm256_set1_epi32(CT_TOUCHING)));
    __m256i far_i = _mm256_castps_si256(far);
    fl = _mm256_blendv_epi8(fl, _mm256_andnot_si256(_mm256_set1_epi32(CT_SOLVE | CT_CLOSING | CT_PASS), F), far_i);
    __m256i bi = _mm256_and_si256(_mm256_castps_si256(stage), _mm256_set1_epi32(ND_STAGE));
    bi = _mm256_or_si256(bi, _mm256_and_si256(_mm256_andnot_si256(was_i, now_i), _mm256_set1_epi32(ND_BEGIN)));
    bi = _mm256_or_si256(bi, _mm256_and_si256(_mm256_andnot_si256(now_i, was_i), _mm256_set1_epi32(ND_END)));
    bi = _mm256_or_si256(bi, _mm256_and_si256(now_i, _mm256_set1_epi32(ND_NOW)));
    bi = _mm256_or_si256(bi, _mm256_and_si256(was_i, _mm256_set1_epi32(ND_WAS)));
    bi = _mm256_or_si256(bi, _mm256_and_si256(_mm256_castps_si256(ground_a), _mm256_set1_epi32(ND_GROUND_A)));
    bi = _mm256_or_si256(bi, _mm256_and_si256(_mm256_castps_si256(ground_b), _mm256_set1_epi32(ND_GROUND_B)));
    bi = _mm256_andnot_si256(far_i, bi);
    uint32_t o_fl[8], o_bits[8];
    float o_nx[8], o_ny[8], o_px[8], o_py[8], o_s0[8], o_vn0[8], o_toi[8], o_depth[8], o_speed[8];
    _mm256_storeu_si256((__m256i *)(void *)o_fl, fl);
    _mm256_storeu_si256((__m256i *)(void *)o_bits, bi);
    _mm256_storeu_ps(o_nx, nx);
    _mm256_storeu_ps(o_ny, ny);
    _mm256_storeu_ps(o_px, px);
    _mm256_storeu_ps(o_py, py);
    _mm256_storeu_ps(o_s0, s0);
    _mm256_storeu_ps(o_vn0, vn0);
    _mm256_storeu_ps(o_toi, toi);
    _mm256_storeu_ps(o_depth, _mm256_max_ps(narrow_wide_neg(s0), zero));  /* rg_max(-s0, 0) */
    _mm256_storeu_ps(o_speed, _mm256_max_ps(narrow_wide_neg(vn0), zero)); /* rg_max(-vn0, 0) */
    uint32_t far_m = (uint32_t)_mm256_movemask_ps(far);
    for (uint32_t left = done; left != 0; left &= left - 1) {
        int l = __builtin_ctz(left);
        contact *q = c[l];
        uint32_t out = o_bits[l];
        q->flags = o_fl[l];
        bits[l] = out;
        if (!(out & ND_STAGE)) q->pn = q->pt = 0;
        if (far_m & (1u << l)) continue; /* narrow_decide's pair far apart: no measurement */
        q->nx = o_nx[l];
        q->ny = o_ny[l];
        q->px = o_px[l];
        q->py = o_py[l];
        q->s0 = o_s0[l];
        q->vn0 = o_vn0[l];
        if (out & ND_STAGE) q->toi = o_toi[l];
        if (out & ND_BEGIN) {
            q->depth = o_depth[l];
            q->speed = o_speed[l];
        }
    }
    if (st != NULL && done == 0xFFu) {
        uint32_t staging = (uint32_t)_mm256_movemask_ps(stage) & ~far_m;   /* bits[l] & ND_STAGE */
        narrow_wide_stage_rows(st, c, staging, A.im, B.im, nx, ny, px, py, s0, vn0, toi, closing);
        st->staged = 1;
    }
    return done;
}
#endif
