/* views.c: the step's view of each awake shaped body (start, displacement, velocity,
 * size), and the fat boxes that left their box after integration (see views.h). */
#include "dispatch.h"
#include "pairs.h"
#include "state.h"
#include "task.h"
#include "vec2.h"
#include "views.h"

void views_layout(mem_layout *l, views_state *s, int32_t n)
{
    s->cb = mem_take(l, (size_t)n, sizeof(cbody));
    s->sx0 = mem_take(l, (size_t)n, sizeof(rg_real));
    s->sy0 = mem_take(l, (size_t)n, sizeof(rg_real));
    s->svx0 = mem_take(l, (size_t)n, sizeof(rg_real));
    s->svy0 = mem_take(l, (size_t)n, sizeof(rg_real));
    s->adense = mem_take(l, (size_t)n, sizeof(int32_t));
    s->refresh = mem_take(l, (size_t)n, sizeof(uint8_t));
}

/* Awake shaped bodies [begin, end) of the broadphase's list: each writes its own start. */
static void views_start_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    rg_world *w = context;
    views_state *ns = &w->coll.views;
    const broadphase *bp = &w->coll.bp;
    const body_store *b = &w->b;
    (void)worker;
    for (int32_t k = begin; k < end; k++) {
        int32_t i = body_dense(w, bp->active[k]);
        ns->adense[k] = i;
        ns->sx0[k] = b->x[i];
        ns->sy0[k] = b->y[i];
        ns->svx0[k] = b->vx[i];
        ns->svy0[k] = b->vy[i];
    }
}

/* Bodies per range of the cheap per-body passes (a few ns each). */
#define VIEWS_START_RANGE 1024

void views_record_start(rg_world *w)
{
    if (w->coll.shape_count == 0) return;
    task_for(w, views_start_range, w->coll.bp.n_active, VIEWS_START_RANGE, w);
}

typedef struct views_task {
    rg_world *w;
    collide_step *x;
    int vdt; /* the narrowphase sees the free motion as v dt (views_build) */
} views_task;

/* The fat box of a body at (x1, y1) with half extents (hx, hy) that moved by (mx, my) this
 * step: its box, swept back over the motion when the collision is continuous. */
static inline void views_box(rg_real x1, rg_real y1, rg_real hx, rg_real hy, rg_real mx, rg_real my,
                             int continuous, rg_real *box)
{
    rg_real lx = x1 - hx, ly = y1 - hy, ux = x1 + hx, uy = y1 + hy;
    if (continuous) {
        lx = rg_min(lx, lx - mx);
        ly = rg_min(ly, ly - my);
        ux = rg_max(ux, ux - mx);
        uy = rg_max(uy, uy - my);
    }
    box[0] = lx;
    box[1] = ly;
    box[2] = ux;
    box[3] = uy;
}

#if RG_AVX2_PATHS
#include "avx2.h"

/* views_range's loop body for the eight bodies of places k .. k + 7, dense i .. i + 7 (the
 * places hold consecutive bodies): the same operations, eight at once; the cbody records and
 * the fat boxes pass through 8x8 and 4x8 transposes. */
AVX2_FN static void views_eight(const views_task *t, int32_t k, int32_t i)
{
    rg_world *w = t->w;
    collide_world *cw = &w->coll;
    views_state *ns = &cw->views;
    body_store *b = &w->b;
    __m256 x1 = _mm256_loadu_ps(b->x + i), y1 = _mm256_loadu_ps(b->y + i);
    __m256 h0 = _mm256_loadu_ps(b->hx + i), h1 = _mm256_loadu_ps(b->hy + i);
    __m256 sx = _mm256_loadu_ps(ns->sx0 + k), sy = _mm256_loadu_ps(ns->sy0 + k);
    __m256 mx = _mm256_sub_ps(x1, sx), my = _mm256_sub_ps(y1, sy);
    /* views_box */
    __m256 lx = _mm256_sub_ps(x1, h0), ly = _mm256_sub_ps(y1, h1), ux = _mm256_add_ps(x1, h0),
           uy = _mm256_add_ps(y1, h1);
    if (cw->continuous) {
        lx = _mm256_min_ps(lx, _mm256_sub_ps(lx, mx));
        ly = _mm256_min_ps(ly, _mm256_sub_ps(ly, my));
        ux = _mm256_max_ps(ux, _mm256_sub_ps(ux, mx));
        uy = _mm256_max_ps(uy, _mm256_sub_ps(uy, my));
    }
    _mm256_storeu_ps(b->dx + i, mx);
    _mm256_storeu_ps(b->dy + i, my);
    __m256i *cf = (__m256i *)(void *)(b->cflags + i);
    _mm256_storeu_si256(cf, _mm256_andnot_si256(_mm256_set1_epi32((int)CF_GROUNDED), _mm256_loadu_si256(cf)));
    /* the records: sx sy dx dy vx vy hx hy, then gs im kind pad */
    __m256 r[8] = { sx, sy, mx, my, _mm256_loadu_ps(ns->svx0 + k), _mm256_loadu_ps(ns->svy0 + k), h0, h1 };
    if (t->vdt) {
        __m256 dt = _mm256_set1_ps(t->x->p.dt);
        r[2] = _mm256_mul_ps(_mm256_loadu_ps(b->vx + i), dt);
        r[3] = _mm256_mul_ps(_mm256_loadu_ps(b->vy + i), dt);
    }
    avx2_transpose8(r);
    __m256i type = _mm256_loadu_si256((const __m256i *)(const void *)(b->type + i));
    __m256 dyn = _mm256_castsi256_ps(_mm256_cmpeq_epi32(type, _mm256_set1_epi32(RG_BODY_DYNAMIC)));
    __m256 gs = _mm256_and_ps(dyn, _mm256_loadu_ps(b->gscale + i)); /* type == dynamic ? gscale : 0 */
    __m256 im = _mm256_loadu_ps(b->inv_mass + i);
    __m256 kind = _mm256_castsi256_ps(_mm256_loadu_si256((const __m256i *)(const void *)(b->shape + i)));
    __m256 gi_lo = _mm256_unpacklo_ps(gs, im), gi_hi = _mm256_unpackhi_ps(gs, im);
    __m256 kp_lo = _mm256_unpacklo_ps(kind, _mm256_setzero_ps());
    __m256 kp_hi = _mm256_unpackhi_ps(kind, _mm256_setzero_ps());
    __m256 q[4] = {_mm256_shuffle_ps(gi_lo, kp_lo, _MM_SHUFFLE(1, 0, 1, 0)),
                   _mm256_shuffle_ps(gi_lo, kp_lo, _MM_SHUFFLE(3, 2, 3, 2)),
                   _mm256_shuffle_ps(gi_hi, kp_hi, _MM_SHUFFLE(1, 0, 1, 0)),
                   _mm256_shuffle_ps(gi_hi, kp_hi, _MM_SHUFFLE(3, 2, 3, 2))};
    cbody *cb = ns->cb + i;
    for (int l = 0; l < 8; l++) {
        _mm256_storeu_ps(&cb[l].sx, r[l]);
        /* lane l's (gs, im, kind, 0): lanes 0-3 in the low halves of q[0..3], 4-7 in the high */
        __m256 ql = q[l & 3];
        _mm_storeu_ps(&cb[l].gs, l < 4 ? _mm256_castps256_ps128(ql) : _mm256_extractf128_ps(ql, 1));
    }
    /* pairs_inside of each body's entry */
    avx2_bytes8(ns->refresh + k, avx2_outside8(cw->bp.e, b->slot + i, lx, ly, ux, uy));
    if (t->x->unite) {
        int32_t *uf = cw->island.uf + k;
        _mm256_storeu_si256((__m256i *)(void *)uf,
                            _mm256_add_epi32(_mm256_set1_epi32(k), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
    }
}
#endif

/* Awake bodies [begin, end): views, displacements and whether the fat box must be refreshed
 * (ns->refresh[k]), each body's own; eight at a time (views_eight) where eight places hold
 * consecutive bodies and the CPU has AVX2. */
static void views_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    const views_task *t = context;
    rg_world *w = t->w;
    collide_world *cw = &w->coll;
    views_state *ns = &cw->views;
    body_store *b = &w->b;
    /* the arrays in locals: the stores below cannot move them, so they are read once */
    cbody *cb = ns->cb;
    const int32_t *adense = ns->adense;
    const rg_real *sx0 = ns->sx0, *sy0 = ns->sy0, *svx0 = ns->svx0, *svy0 = ns->svy0;
    const rg_real *x = b->x, *y = b->y, *hx = b->hx, *hy = b->hy;
    const rg_real *gscale = b->gscale, *inv_mass = b->inv_mass;
    const int32_t *type = b->type, *shape = b->shape, *slot = b->slot;
    rg_real *dx = b->dx, *dy = b->dy;
    uint32_t *cflags = b->cflags;
    uint8_t *refresh = ns->refresh;
    int32_t *uf = t->x->unite ? cw->island.uf : NULL;
    const bp_entry *e = cw->bp.e;
    int continuous = cw->continuous;
    (void)worker;
#if RG_AVX2_PATHS
    int wide = __builtin_cpu_supports("avx2");
#endif
    for (int32_t k = begin; k < end;) {
        int32_t stop = end; /* the bodies up to stop one by one */
#if RG_AVX2_PATHS
        if (wide && end - k >= 8) {
            int32_t i0 = adense[k], run = 1;
            for (int l = 1; l < 8; l++) run &= adense[k + l] == i0 + l;
            if (run) {
                views_eight(t, k, i0);
                k += 8;
                continue;
            }
            stop = k + 8;
        }
#endif
        for (; k < stop; k++) {
            int32_t i = adense[k];
            rg_real x1 = x[i], y1 = y[i], h0 = hx[i], h1 = hy[i];
            rg_real mx = x1 - sx0[k], my = y1 - sy0[k], box[4];
            views_box(x1, y1, h0, h1, mx, my, continuous, box);
            dx[i] = mx;
            dy[i] = my;
            cflags[i] &= ~CF_GROUNDED; /* set again by the touching contacts */
            cbody v;
            v.sx = sx0[k];
            v.sy = sy0[k];
            v.dx = t->vdt ? b->vx[i] * t->x->p.dt : mx;
            v.dy = t->vdt ? b->vy[i] * t->x->p.dt : my;
            v.vx = svx0[k];
            v.vy = svy0[k];
            v.hx = h0;
            v.hy = h1;
            v.gs = type[i] == RG_BODY_DYNAMIC ? gscale[i] : 0;
            v.im = inv_mass[i];
            v.kind = shape[i];
            v.pad = 0;
            cb[i] = v;
            refresh[k] = (uint8_t)!pairs_inside(&e[slot[i]], box);
            if (uf != NULL) uf[k] = k;
        }
    }
}

/* Bodies per views range. */
#define VIEWS_RANGE 256

void views_build(rg_world *w, collide_step *x, rg_real dt)
{
    /* The narrowphase sees each body move by v dt, its velocity after integration: the
     * motion the solver's rows hold (x0 + v dt), semi-implicit Euler's.  Another integrator's
     * own motion (b->dx, mx above) ends an a*dt^2 term off it; with it the narrowphase would
     * find a pair apart at the end of the step that the rows stop at the surface (landing
     * with no impact, its velocity into the surface, to bounce off it in the next step). */
    views_task t = { w, x, w->integrator != RG_INTEGRATOR_SEMI_IMPLICIT_EULER };
    views_state *ns = &w->coll.views;
    const body_store *b = &w->b;
    task_for(w, views_range, x->na, VIEWS_RANGE, &t);
    /* the broadphase changes in order, on this thread */
    for (int32_t k = 0; k < x->na; k++) {
        if (!ns->refresh[k]) continue;
        int32_t i = ns->adense[k];
        rg_real mx = b->x[i] - ns->sx0[k], my = b->y[i] - ns->sy0[k], box[4];
        views_box(b->x[i], b->y[i], b->hx[i], b->hy[i], mx, my, w->coll.continuous, box);
        pairs_refresh_now(w, i, box[0], box[1], box[2], box[3], mx, my, (b->vx[i] - ns->svx0[k]) * dt,
                          (b->vy[i] - ns->svy0[k]) * dt);
    }
}

void views_woken(rg_world *w, const collide_step *x)
{
    views_state *ns = &w->coll.views;
    const broadphase *bp = &w->coll.bp;
    const body_store *b = &w->b;
    for (int32_t k = x->na; k < bp->n_active; k++) {
        int32_t i = body_dense(w, bp->active[k]);
        ns->adense[k] = i;
        ns->sx0[k] = b->x[i];
        ns->sy0[k] = b->y[i];
    }
}
