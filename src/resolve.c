/* resolve.c: the solve driver (see resolve.h). */
#include <string.h>

#include "bands.h"
#include "body.h"
#include "continuous.h"
#include "dispatch.h"
#include "inline.h"
#include "order.h"
#include "resolve.h"
#include "state.h"
#include "task.h"
#include "vec2.h"
#if RG_AVX2_PATHS
#include "avx2.h"
#endif

/* The step's timers (step.h, -DRG_STEP_PROFILE): the solve's parts on one thread, the order
 * by height, the colouring and the shock sweeps, each in seconds. */
#ifdef RG_STEP_PROFILE
#include <time.h>
double step_prof_solve[3];
static double resolve_prof_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}
#define RESOLVE_PROF(k, call)                                 \
    do {                                                      \
        double t_ = resolve_prof_now();                       \
        call;                                                 \
        step_prof_solve[(k)] += resolve_prof_now() - t_;      \
    } while (0)
#else
#define RESOLVE_PROF(k, call) call
#endif

void resolve_layout(mem_layout *l, resolve_state *s, int32_t n)
{
    s->sv = mem_take(l, (size_t)n, 2 * sizeof(rg_real));
    s->spv = mem_take(l, (size_t)n, 2 * sizeof(rg_real));
    s->stoi = mem_take(l, (size_t)n, sizeof(rg_real));
    s->spush = mem_take(l, (size_t)n, sizeof(uint8_t));
    s->spn = mem_take(l, (size_t)n, 2 * sizeof(rg_real));
    s->sstamp = mem_take(l, (size_t)n, sizeof(uint32_t));
    s->cmask = mem_take(l, (size_t)n, sizeof(uint32_t));
    s->sbody = mem_take(l, (size_t)n, sizeof(int32_t));
    s->sband = mem_take(l, (size_t)n, BANDS_MAX);
}

void resolve_next_gen(resolve_state *s, int32_t n)
{
    if (++s->gen == 0) {
        memset(s->sstamp, 0, (size_t)n * sizeof *s->sstamp);
        s->gen = 1;
    }
}

/* Rows staged again from the contacts flagged CT_SOLVE, after the narrowphase woke bodies
 * (their indices and the ground index changed). */
static void resolve_restage(rg_world *w, collide_step *x)
{
    collide_world *cw = &w->coll;
    contact_store *cs = &cw->contacts;
    const body_store *b = &w->b;
    int32_t n = b->n_active;
    x->nimp = 0;
    x->nc = 0;
    x->n = n;
    x->ns = n;
    solver_dest d = resolve_rows_dest(&cw->rows, x);
    for (int32_t k = 0; k < cs->n_awake; k++) {
        int32_t id = cs->awake[k];
        contact *c = &cs->c[id];
        if (!(c->flags & CT_SOLVE)) continue;
        int32_t ia = body_dense(w, c->sa), ib = body_dense(w, c->sb);
        rg_real ima = ia < n ? b->inv_mass[ia] : 0, imb = ib < n ? b->inv_mass[ib] : 0;
        if (!(ima + imb > 0)) {
            c->flags &= ~CT_SOLVE;
            c->pn = c->pt = 0;
            continue;
        }
        resolve_stage(w, x, &d, id, ia, ib, ima, imb);
    }
}

/* The solve's passes over rows and over solver bodies, split over the task system: each
 * item writes only its own row or body (the wide rows: colour by colour, a colour's rows
 * sharing no movable body); colours and passes in order. */
enum {
    RESOLVE_WARM, RESOLVE_VELOCITY, RESOLVE_POSITION, /* wide rows of a colour */
    RESOLVE_LOAD, RESOLVE_MOVE, RESOLVE_PUSH,         /* solver bodies 1..ns */
    RESOLVE_PREPARE, RESOLVE_KEEP,                    /* rows of c */
    RESOLVE_PACK_LANES,                               /* all wide rows */
    RESOLVE_UNPACK, RESOLVE_UNPACK_POSITION, RESOLVE_PACK_POSITION, /* all wide rows, light */
    RESOLVE_PACK                                      /* blocks of the solving order */
};

typedef struct resolve_task {
    rg_world *w;
    collide_step *x; /* read only, but for x->late's call */
    solver_batch *sb;
    solver_constraint *con;
    rg_real *v, *pv;
    int32_t r0;
    int what, timed;
    int placed;     /* the integrator is not semi-implicit Euler (resolve_body): 1 explicit Euler,
                     * 2 Verlet or RK4 */
    int listed;     /* the body passes walk the list of the bodies the rows meet (solver_rows_few) */
    int32_t nbody;  /* listed: how many (rs->sbody) */
    int32_t bands;  /* the colour passes run in bands (bands.h) when above 1 */
    int32_t last;   /* bands: the first phase of the last sweep, whose rows unpack as they end */
    int ncol;       /* the colours that have rows, in order */
    int cols[32];
    int32_t nedge[BANDS_MAX][32]; /* bands: the edge rows of band b's slice of colour cols[k] */
    int32_t pushing[RG_MAX_WORKERS];
    int32_t pressed[RG_MAX_WORKERS], press0[RG_MAX_WORKERS], press1[RG_MAX_WORKERS];
} resolve_task;

/* Solver body q (1-based) that a row meets: one of the body passes. */
static FORCE_INLINE void resolve_body(const resolve_task *t, int what, int32_t q)
{
    body_store *b = &t->w->b;
    const resolve_state *rs = &t->w->coll.resolve;
    rg_real *v = t->v, dt = t->x->p.dt;
    int32_t i = q - 1;
    if (what == RESOLVE_LOAD) {
        /* an immovable body's zero velocity as +0: the rows store it back unchanged, in
         * whatever order they run (solver.h) */
        rg_real z = b->inv_mass[i] > 0 ? -RG_R(0.0) : 0;
        v[2 * q] = b->vx[i] + z;
        v[2 * q + 1] = b->vy[i] + z;
    } else if (what == RESOLVE_PUSH) {
        b->x[i] += t->pv[2 * q] * dt;
        b->y[i] += t->pv[2 * q + 1] * dt;
    } else {
        /* positions move with the solved velocities.  A timed body's velocity changes
         * at its impact, t into the step; v then holds the velocity of its whole step's
         * motion, for the position pass to see where the step leaves it. */
        rg_real dvx = v[2 * q] - b->vx[i], dvy = v[2 * q + 1] - b->vy[i];
        rg_real ti = t->timed ? rs->stoi[q] : 0;
        if (ti > 0) {
            rg_real after = 1 - ti, fx = b->vx[i], fy = b->vy[i];
            if (t->placed) {
                /* Explicit Euler, Verlet, RK4: the impact is timed on the integrator's own
                 * motion (narrow_decide), and the body ends where that motion, from the
                 * surface at t on, takes it: x0 + v dt + (v_solved - v) (1 - t) dt plus the
                 * integrator's term o = dx - v dt (Verlet, RK4: exact under a constant
                 * force; explicit Euler: keeps its invariant v^2/2 - a y - a dt v / 2 with
                 * solver_vout's stagger, as semi-implicit Euler keeps its own, the impact
                 * timed on its motion v0 dt).  Landing without a bounce (resolve_pushed's
                 * 8), or where o takes it toward what it meets (4: a jump into a ceiling),
                 * only the part that brings it to the surface: (2 t - t^2) o, or t o. */
                int four = (rs->spush[q] & 12) != 0, euler = t->placed == 1;
                rg_real keep = four ? (euler ? ti : ti * (2 - ti)) : 1;
                rg_real drop = 1 - keep;
                b->x[i] -= drop * (b->dx[i] - fx * dt);
                b->y[i] -= drop * (b->dy[i] - fy * dt);
            }
            b->x[i] += dvx * after * dt;
            b->y[i] += dvy * after * dt;
            b->vx[i] = v[2 * q];
            b->vy[i] = v[2 * q + 1];
            v[2 * q] = fx + dvx * after;
            v[2 * q + 1] = fy + dvy * after;
        } else if (t->placed && (rs->spush[q] & 3)) {
            /* The rows hold semi-implicit Euler's positions, x0 + v dt.  Another integrator's
             * free motion (dx: views_build) ends a term o = dx - v_free dt off it (a*dt^2 for
             * explicit Euler, a*dt^2 / 2 for Verlet and RK4) that the rows never saw: a body
             * the rows push moves from where the step began, x0 + v dt, along their normal
             * (so a body resting on the ground stays where it is, at rest), and keeps o
             * across it (a force pushing it along the ground keeps the integrator's order).
             * Pushed along several normals, or held by friction (o across would creep), it
             * moves by x0 + v dt alone; a row that does not push drops o along its normal
             * where o takes the body toward the other one (a jump into a ceiling, which the
             * row held only x0 + v dt away from).  A body no row pushes keeps its own motion;
             * a timed body: above. */
            rg_real ox = b->dx[i] - b->vx[i] * dt, oy = b->dy[i] - b->vy[i] * dt;
            rg_real kx = 0, ky = 0; /* o along (-ny, nx); spn is written only along one normal */
            if ((rs->spush[q] & 3) == 1) {
                rg_real nx = rs->spn[2 * q], ny = rs->spn[2 * q + 1], across = nx * oy - ny * ox;
                kx = -(across * ny);
                ky = across * nx;
            }
            b->x[i] = (b->x[i] - b->dx[i]) + v[2 * q] * dt + kx;
            b->y[i] = (b->y[i] - b->dy[i]) + v[2 * q + 1] * dt + ky;
            b->vx[i] = v[2 * q];
            b->vy[i] = v[2 * q + 1];
        } else {
            b->x[i] += dvx * dt;
            b->y[i] += dvy * dt;
            b->vx[i] = v[2 * q];
            b->vy[i] = v[2 * q + 1];
        }
    }
}

#if RG_AVX2_PATHS
/* The pairs (x, y) of p[0 .. 16) as eight x and eight y, and back. */
AVX2_FN static inline void resolve_pairs_load(const float *p, __m256 *x, __m256 *y)
{
    __m256 lo = _mm256_loadu_ps(p), hi = _mm256_loadu_ps(p + 8);
    __m256 xs = _mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(2, 0, 2, 0)),
           ys = _mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(3, 1, 3, 1));
    *x = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(xs), _MM_SHUFFLE(3, 1, 2, 0)));
    *y = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(ys), _MM_SHUFFLE(3, 1, 2, 0)));
}

AVX2_FN static inline void resolve_pairs_store(float *p, __m256 x, __m256 y)
{
    __m256 lo = _mm256_unpacklo_ps(x, y), hi = _mm256_unpackhi_ps(x, y);
    _mm256_storeu_ps(p, _mm256_permute2f128_ps(lo, hi, 0x20));
    _mm256_storeu_ps(p + 8, _mm256_permute2f128_ps(lo, hi, 0x31));
}

/* resolve_body of solver bodies q .. q + 7 (all met by rows): the same operations, eight at
 * once; a timed body's lanes take the timed branch's results. */
AVX2_FN static void resolve_eight(const resolve_task *t, int what, int32_t q)
{
    body_store *b = &t->w->b;
    const resolve_state *rs = &t->w->coll.resolve;
    float *v = t->v + 2 * q;
    int32_t i = q - 1;
    __m256 dt = _mm256_set1_ps(t->x->p.dt);
    if (what == RESOLVE_LOAD) {
        __m256 movable = _mm256_cmp_ps(_mm256_loadu_ps(b->inv_mass + i), _mm256_setzero_ps(), _CMP_GT_OQ);
        __m256 z = _mm256_and_ps(movable, _mm256_set1_ps(-0.0f));
        resolve_pairs_store(v, _mm256_add_ps(_mm256_loadu_ps(b->vx + i), z),
                            _mm256_add_ps(_mm256_loadu_ps(b->vy + i), z));
        return;
    }
    __m256 px, py;
    if (what == RESOLVE_PUSH) {
        resolve_pairs_load(t->pv + 2 * q, &px, &py);
        _mm256_storeu_ps(b->x + i, _mm256_add_ps(_mm256_loadu_ps(b->x + i), _mm256_mul_ps(px, dt)));
        _mm256_storeu_ps(b->y + i, _mm256_add_ps(_mm256_loadu_ps(b->y + i), _mm256_mul_ps(py, dt)));
        return;
    }
    __m256 wx, wy;
    resolve_pairs_load(v, &wx, &wy);
    __m256 fx = _mm256_loadu_ps(b->vx + i), fy = _mm256_loadu_ps(b->vy + i);
    __m256 dvx = _mm256_sub_ps(wx, fx), dvy = _mm256_sub_ps(wy, fy);
    __m256 mx = _mm256_mul_ps(dvx, dt), my = _mm256_mul_ps(dvy, dt);
    if (t->timed) {
        __m256 ti = _mm256_loadu_ps(rs->stoi + q);
        __m256 timed = _mm256_cmp_ps(ti, _mm256_setzero_ps(), _CMP_GT_OQ);
        __m256 after = _mm256_sub_ps(_mm256_set1_ps(1.0f), ti);
        __m256 ax = _mm256_mul_ps(dvx, after), ay = _mm256_mul_ps(dvy, after);
        mx = _mm256_blendv_ps(mx, _mm256_mul_ps(ax, dt), timed);
        my = _mm256_blendv_ps(my, _mm256_mul_ps(ay, dt), timed);
        resolve_pairs_store(v, _mm256_blendv_ps(wx, _mm256_add_ps(fx, ax), timed),
                            _mm256_blendv_ps(wy, _mm256_add_ps(fy, ay), timed));
    }
    _mm256_storeu_ps(b->x + i, _mm256_add_ps(_mm256_loadu_ps(b->x + i), mx));
    _mm256_storeu_ps(b->y + i, _mm256_add_ps(_mm256_loadu_ps(b->y + i), my));
    _mm256_storeu_ps(b->vx + i, wx);
    _mm256_storeu_ps(b->vy + i, wy);
}

/* Whether the rows meet each of solver bodies q .. q + 7. */
AVX2_FN static inline int resolve_met8(const resolve_state *rs, int32_t q)
{
    __m256i s = _mm256_loadu_si256((const __m256i *)(const void *)(rs->sstamp + q - 1));
    return _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(s, _mm256_set1_epi32((int)rs->gen)))) == 0xFF;
}
#endif

/* Items [k0, k1) of a body pass: places in the list of the bodies the rows meet (t->listed),
 * or solver bodies k0..k1-1 (1-based), those no row meets skipped; eight at a time
 * (resolve_eight) where the rows meet eight in a row and the CPU has AVX2. */
static FORCE_INLINE void resolve_bodies_as(const resolve_task *t, int what, int32_t k0, int32_t k1)
{
    const resolve_state *rs = &t->w->coll.resolve;
    if (t->listed) {
        for (int32_t k = k0; k < k1; k++) resolve_body(t, what, rs->sbody[k]);
        return;
    }
    int32_t q = k0;
#if RG_AVX2_PATHS
    if (__builtin_cpu_supports("avx2") && !(what == RESOLVE_MOVE && t->placed)) {
        for (; k1 - q >= 8; q += 8) {
            if (resolve_met8(rs, q)) {
                resolve_eight(t, what, q);
                continue;
            }
            for (int32_t e = q; e < q + 8; e++)
                if (rs->sstamp[e - 1] == rs->gen) resolve_body(t, what, e);
        }
    }
#endif
    for (; q < k1; q++)
        if (rs->sstamp[q - 1] == rs->gen) resolve_body(t, what, q);
}

/* resolve_bodies_as, each pass's loop of its own. */
static void resolve_bodies(const resolve_task *t, int what, int32_t k0, int32_t k1)
{
    if (what == RESOLVE_LOAD)
        resolve_bodies_as(t, RESOLVE_LOAD, k0, k1);
    else if (what == RESOLVE_PUSH)
        resolve_bodies_as(t, RESOLVE_PUSH, k0, k1);
    else
        resolve_bodies_as(t, RESOLVE_MOVE, k0, k1);
}

static void resolve_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    resolve_task *t = context;
    int32_t b0 = t->r0 + begin, b1 = t->r0 + end;
    switch (t->what) {
    case RESOLVE_WARM: solver_wide_warm_start(t->sb, b0, b1, t->v); break;
    case RESOLVE_VELOCITY: solver_wide_iterate(t->sb, b0, b1, t->v); break;
    case RESOLVE_POSITION: solver_wide_iterate_position(t->sb, b0, b1, t->pv); break;
    case RESOLVE_PACK_LANES: solver_pack_lanes(t->sb, t->con, b0, b1); break;
    case RESOLVE_UNPACK: solver_unpack_wide(t->sb, t->con, b0, b1, 0); break;
    case RESOLVE_UNPACK_POSITION: solver_unpack_wide(t->sb, t->con, b0, b1, 1); break;
    case RESOLVE_PACK_POSITION: solver_pack_position(t->sb, t->con, b0, b1); break;
    case RESOLVE_PACK:
        solver_pack_rows(t->con, t->w->coll.rows.ord, t->x->nc, t->w->coll.rows.color, t->w->coll.rows.lanes, b0,
                         b1, t->sb);
        break;
    case RESOLVE_PREPARE:
        t->pushing[worker] += solver_prepare_position(t->con + b0, b1 - b0, t->v, &t->x->p);
        break;
    case RESOLVE_KEEP: {
        int32_t pressed = 0, p0 = b1, p1 = b0;
        for (int32_t k = b0; k < b1; k++) {
            contact *c = &t->w->coll.contacts.c[t->con[k].cid];
            c->pn = rg_min(t->con[k].pn, CONTACT_MAX_IMPULSE);
            c->pt = rg_max(rg_min(t->con[k].pt, CONTACT_MAX_IMPULSE), -CONTACT_MAX_IMPULSE);
            /* a pair apart at the start, not touching (toi -1: it did not touch before, and
             * the free motion does not close it), that the solve pressed together: it ends
             * the step in contact, and narrow_press makes it touch now */
            if (c->toi < 0 && c->pn > 0 && !(c->flags & CT_TOUCHING)) {
                c->flags |= CT_PRESSED;
                pressed++;
                if (p0 > k) p0 = k;
                p1 = k + 1;
            }
        }
        if (pressed > 0) {
            t->pressed[worker] += pressed;
            if (t->press0[worker] > p0) t->press0[worker] = p0;
            if (t->press1[worker] < p1) t->press1[worker] = p1;
        }
        break;
    }
    default: resolve_bodies(t, t->what, b0, b1); break;
    }
}

/* Items per range: wide rows (64 lanes; for the copies, 512), rows and bodies, or packing
 * blocks. */
#define RESOLVE_WIDE_RANGE 8
#define RESOLVE_COPY_RANGE 64
#define RESOLVE_RANGE 512
#define RESOLVE_PACK_RANGE 2

#ifdef RG_STEP_PROFILE
/* The step's timers name each pass, in the order of the enum. */
static const char *const resolve_pass_names[] = {
    "resolve_range warm",    "resolve_range velocity", "resolve_range position",         "resolve_range load",
    "resolve_range move",    "resolve_range push",     "resolve_range prepare",          "resolve_range keep",
    "resolve_range lanes",   "resolve_range unpack",   "resolve_range unpack position", "resolve_range pack position",
    "resolve_range pack"};
typedef char resolve_pass_names_fit[sizeof resolve_pass_names / sizeof resolve_pass_names[0] == RESOLVE_PACK + 1 ? 1 : -1];
#endif

/* One pass: `count` items from r0 (wide rows, rows of c, or solver bodies). */
static void resolve_pass(resolve_task *t, int what, int32_t r0, int32_t count)
{
    t->what = what;
    t->r0 = r0;
    int wide = what <= RESOLVE_POSITION || what == RESOLVE_PACK_LANES;
    int copy = what == RESOLVE_UNPACK || what == RESOLVE_UNPACK_POSITION || what == RESOLVE_PACK_POSITION;
    int32_t min_range = what == RESOLVE_PACK ? RESOLVE_PACK_RANGE
                      : wide                 ? RESOLVE_WIDE_RANGE
                      : copy                 ? RESOLVE_COPY_RANGE
                                             : RESOLVE_RANGE;
#ifdef RG_STEP_PROFILE
    task_for_named(t->w, resolve_range, resolve_pass_names[what], count, min_range, t);
#else
    task_for(t->w, resolve_range, count, min_range, t);
#endif
}

/* A pass over the wide rows, colour by colour. */
static void resolve_wide(resolve_task *t, int what)
{
    for (int col = 0; col < 32; col++)
        resolve_pass(t, what, t->sb->cstart[col], t->sb->cstart[col + 1] - t->sb->cstart[col]);
}

/* ---- the colour passes in bands (bands.h) */

/* Wide rows per band at least: below it the colours run as passes (each colour's pass a
 * task of its own).  Bands pay from some 500 rows on two workers: a band's phases wait on
 * one line of the other band, a pass on the task system's hand-over (make bench-ab-threads:
 * README, Performance); at 250 rows they paid nothing. */
#define RESOLVE_BAND_ROWS 24

/* Where band b begins among colour col's wide rows: each colour is split evenly, and its rows
 * keep their order along gravity (solver_pack), so band b holds about the same slice of the
 * scene in every colour and few bodies are met by two bands. */
static int32_t resolve_band_at(const solver_batch *sb, int col, int32_t b, int32_t bands)
{
    int32_t n = sb->cstart[col + 1] - sb->cstart[col];
    return sb->cstart[col] + (int32_t)((int64_t)n * b / bands);
}

/* How many bands the colour passes run in (one per worker, at most BANDS_MAX, each of at
 * least RESOLVE_BAND_ROWS wide rows; below 2: passes, as also with rows in the overflow list,
 * which the calling thread solves between the sweeps); lists the colours that have rows. */
static int32_t resolve_bands_for(const rg_world *w, resolve_task *t)
{
    const solver_batch *sb = t->sb;
    t->ncol = 0;
    for (int col = 0; col < 32; col++)
        if (sb->cstart[col + 1] > sb->cstart[col]) t->cols[t->ncol++] = col;
    if (!bands_available() || sb->nover > 0) return 0;
    int32_t bands = task_workers(w);
    if (bands > BANDS_MAX) bands = BANDS_MAX;
    if (bands > sb->nrows / RESOLVE_BAND_ROWS) bands = sb->nrows / RESOLVE_BAND_ROWS;
    return bands;
}

/* Items are bands: each fills its wide rows where solver_pack_lanes does (so that the thread
 * that solves a band's rows is likely the one that wrote them), then stamps the movable
 * bodies its rows meet, in a byte of its own. */
static void resolve_band_stamp(int32_t begin, int32_t end, int32_t worker, void *context)
{
    const resolve_task *t = context;
    solver_batch *sb = t->sb;
    resolve_state *rs = &t->w->coll.resolve;
    int fill = solver_pack_wide();
    (void)worker;
    for (int32_t b = begin; b < end; b++)
        for (int k = 0; k < t->ncol; k++) {
            int32_t r0 = resolve_band_at(sb, t->cols[k], b, t->bands), r1 = resolve_band_at(sb, t->cols[k], b + 1, t->bands);
            if (fill) solver_pack_lanes(sb, t->con, r0, r1);
            for (int32_t r = r0; r < r1; r++) {
                const solver_wide *q = &sb->rows[r];
                for (int l = 0; l < SOLVER_LANES; l++) {
                    if (q->ima[l] > 0) rs->sband[(size_t)q->a[l] * BANDS_MAX + (size_t)b] = rs->bgen;
                    if (q->imb[l] > 0) rs->sband[(size_t)q->b[l] * BANDS_MAX + (size_t)b] = rs->bgen;
                }
            }
        }
}

/* resolve_band_flag reads a body's bytes as one 64-bit word */
typedef char resolve_bands_fill_a_word[BANDS_MAX == 8 ? 1 : -1];

/* Items are bands: each lists the wide rows of its slices that meet a body another band
 * stamped (its edge rows, rows.edge from each slice's start, t->nedge).  Only movable bodies
 * are stamped, so every lane may be tested: eight bands' bytes at once, those of the other
 * bands compared with the generation (a byte of x is zero where they match). */
static void resolve_band_flag(int32_t begin, int32_t end, int32_t worker, void *context)
{
    resolve_task *t = context;
    const solver_batch *sb = t->sb;
    const resolve_state *rs = &t->w->coll.resolve;
    int32_t *edge = t->w->coll.rows.edge;
    const uint64_t ones = 0x0101010101010101u, lows = 0x7F7F7F7F7F7F7F7Fu;
    (void)worker;
    for (int32_t b = begin; b < end; b++) {
        /* 0xFF in the bytes not compared: band b's own and those past the last band */
        uint8_t skip[8];
        for (int u = 0; u < 8; u++) skip[u] = (uint8_t)(u == b || u >= t->bands ? 0xFF : 0);
        uint64_t ignore, gen = ones * rs->bgen;
        memcpy(&ignore, skip, sizeof ignore);
        for (int k = 0; k < t->ncol; k++) {
            int32_t r0 = resolve_band_at(sb, t->cols[k], b, t->bands), r1 = resolve_band_at(sb, t->cols[k], b + 1, t->bands);
            int32_t n = 0;
            for (int32_t r = r0; r < r1; r++) {
                const solver_wide *q = &sb->rows[r];
                uint64_t zero = 0;
                for (int l = 0; l < SOLVER_LANES; l++) {
                    uint64_t x, y;
                    memcpy(&x, rs->sband + (size_t)q->a[l] * BANDS_MAX, sizeof x);
                    memcpy(&y, rs->sband + (size_t)q->b[l] * BANDS_MAX, sizeof y);
                    x = (x ^ gen) | ignore;
                    y = (y ^ gen) | ignore;
                    zero |= ~(((x & lows) + lows) | x) | ~(((y & lows) + lows) | y); /* the high bit of each zero byte */
                }
                edge[r0 + n] = r; /* written always, kept (n grows) for an edge row */
                n += (zero & ~lows) != 0;
            }
            t->nedge[b][k] = n;
        }
    }
}

/* Solves wide rows [r, e) of a band's phase: a run of its edge rows or of its inner rows. */
static void resolve_band_run(const resolve_task *t, int what, int32_t phase, int32_t r, int32_t e)
{
    if (what == RESOLVE_WARM)
        solver_wide_warm_start(t->sb, r, e, t->v);
    else if (what == RESOLVE_VELOCITY)
        solver_wide_iterate(t->sb, r, e, t->v);
    else
        solver_wide_iterate_position(t->sb, r, e, t->pv);
    if (phase >= t->last) solver_unpack_wide(t->sb, t->con, r, e, what == RESOLVE_POSITION);
}

/* The bands' phases (bands_fn): t->what's colours in order (RESOLVE_WARM: the warm start's,
 * then the velocity iterations'), each band's edge rows or its inner rows (the runs between
 * them), in runs.  In the last sweep each run's impulses go back to their rows of c at once
 * (the pass RESOLVE_UNPACK or RESOLVE_UNPACK_POSITION would do after the sweeps), read where
 * they were just written. */
static void resolve_band_phase(int32_t band, int32_t phase, int edge, void *context)
{
    const resolve_task *t = context;
    int k = phase % t->ncol;
    int what = t->what == RESOLVE_WARM && phase >= t->ncol ? RESOLVE_VELOCITY : t->what;
    int32_t r0 = resolve_band_at(t->sb, t->cols[k], band, t->bands), r1 = resolve_band_at(t->sb, t->cols[k], band + 1, t->bands);
    const int32_t *list = t->w->coll.rows.edge + r0;
    int32_t n = t->nedge[band][k];
    if (edge) {
        for (int32_t i = 0; i < n;) {
            int32_t j = i + 1;
            while (j < n && list[j] == list[j - 1] + 1) j++;
            resolve_band_run(t, what, phase, list[i], list[j - 1] + 1);
            i = j;
        }
        return;
    }
    int32_t r = r0;
    for (int32_t i = 0; i <= n; i++) {
        int32_t e = i < n ? list[i] : r1;
        if (e > r) resolve_band_run(t, what, phase, r, e);
        r = e + 1;
    }
}

/* Row r's two solver bodies for the stamps: its movable bodies (rows.ab, beside it) but where
 * it is against an immovable one (solver_row_bodies: a body with inverse mass > 0 is not the
 * ground, 0), which only then is read for them; returns whether it is (solver_row_fixed). */
static inline int resolve_row_met(const solver_rows *rows, int32_t r, int32_t *qa, int32_t *qb)
{
    *qa = rows->ab[2 * r];
    *qb = rows->ab[2 * r + 1];
    if (*qa != 0 && *qb != 0) return 0;
    *qa = rows->stage[r].a;
    *qb = rows->stage[r].b;
    return 1;
}

/* The solve's first part in two halves that share nothing, so that they may run at once:
 * item 0 the solving order and the colours; item 1 what the narrowphase left (x->late), the
 * bodies the rows meet (stamped), their velocities loaded, and the rows against an immovable
 * body listed. */
typedef struct resolve_head {
    resolve_task *t;
    int32_t nfixed; /* rows against an immovable body (rows.fixed) */
} resolve_head;

static void resolve_head_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    resolve_head *h = context;
    resolve_task *t = h->t;
    rg_world *w = t->w;
    collide_step *x = t->x;
    collide_world *cw = &w->coll;
    resolve_state *rs = &cw->resolve;
    solver_rows *rows = &cw->rows;
    int32_t nc = x->nc;
    (void)worker;
    for (int32_t k = begin; k < end; k++) {
        if (k == 0) {
            RESOLVE_PROF(0, order_rows(rows, nc, x->down));
            RESOLVE_PROF(1, solver_pack(rows->ab, rows->ord, nc, x->ns + 1, rs->cmask, rows->color, rows->lanes,
                                        &rows->batch));
            continue;
        }
        if (x->late != NULL) x->late(w, x);
        /* the solver's bodies: 0 is the ground, 1..ns the awake bodies; stamped, those the
         * rows meet; in the same walk, the rows against an immovable body listed.  The
         * rows are read only where listed (resolve_row_met): the others stay in the caches
         * of the workers that staged them, which write their impulses back at the end of the
         * bands (a row read here would be shared with this thread, and each such write would
         * wait for this core to let go of it). */
        resolve_next_gen(rs, cw->scap);
        int32_t met = 0, nfixed = 0, *fixed = rows->fixed;
        int listed = t->listed = solver_rows_few(nc, x->ns);
        for (int32_t r = 0; r < nc && listed; r++) {
            int32_t qa, qb;
            if (resolve_row_met(rows, r, &qa, &qb)) fixed[nfixed++] = r;
            if (qa > 0 && rs->sstamp[qa - 1] != rs->gen) {
                rs->sstamp[qa - 1] = rs->gen;
                rs->sbody[met++] = qa;
            }
            if (qb > 0 && rs->sstamp[qb - 1] != rs->gen) {
                rs->sstamp[qb - 1] = rs->gen;
                rs->sbody[met++] = qb;
            }
        }
        for (int32_t r = 0; r < nc && !listed; r++) {
            int32_t qa, qb;
            if (resolve_row_met(rows, r, &qa, &qb)) fixed[nfixed++] = r;
            if (qa > 0) rs->sstamp[qa - 1] = rs->gen;
            if (qb > 0) rs->sstamp[qb - 1] = rs->gen;
        }
        h->nfixed = nfixed;
        t->nbody = met;
        t->v[0] = t->v[1] = 0;
        resolve_bodies(t, RESOLVE_LOAD, listed ? 0 : 1, listed ? met : x->ns + 1);
    }
}

/* Where the rows push each movable body they meet (rs->spush, spn): under the integrators
 * other than semi-implicit Euler, for resolve_body's move. */
static void resolve_pushed(resolve_state *rs, const body_store *b, const rg_real *v, rg_real dt,
                           rg_real slop, const solver_constraint *con, int32_t nc)
{
    for (int32_t k = 0; k < nc; k++) rs->spush[con[k].a] = rs->spush[con[k].b] = 0;
    for (int32_t k = 0; k < nc; k++) {
        int pushes = con[k].pn > 0;
        if (con[k].toi > 0 && !(con[k].vmin > 0)) {
            /* an impact that leaves no bounce (solver_vout 0): a timed body ends on the
             * surface (bit 8, resolve_body) */
            rs->spush[con[k].a] |= 8;
            rs->spush[con[k].b] |= 8;
        }
        /* friction holds the pair (its impulse within the cone, and the pair no longer
         * slides along it: of two rows of one sliding body, across a seam, one may end within
         * its cone): the bodies it pushes move by x0 + v dt outright, which the friction row
         * stopped (o across would creep) */
        int held = 0;
        if (pushes && rg_fabs(con[k].pt) < con[k].mu * con[k].pn) {
            const rg_real *va = v + 2 * con[k].a, *vb = v + 2 * con[k].b;
            rg_real vt = (vb[1] - va[1]) * con[k].nx - (vb[0] - va[0]) * con[k].ny;
            held = rg_fabs(vt) * dt <= RG_R(1e-3) * slop;
        }
        int32_t ab[2] = {con[k].ima > 0 ? con[k].a : 0, con[k].imb > 0 ? con[k].b : 0};
        for (int e = 0; e < 2; e++) {
            int32_t q = ab[e];
            if (q == 0) continue; /* the ground, or a kinematic body: the rows never move it */
            /* o takes the body toward the other one (bit 4): the row held only x0 + v dt
             * apart (a jump into a ceiling) */
            int32_t i = q - 1;
            rg_real on = (b->dx[i] - b->vx[i] * dt) * con[k].nx + (b->dy[i] - b->vy[i] * dt) * con[k].ny;
            int closes = e == 0 ? on > 0 : on < 0;
            if (!pushes && !closes) continue; /* a row that does not push: the body keeps o */
            if (closes) rs->spush[q] |= 4;
            rg_real *n = rs->spn + 2 * q;
            if (held) {
                rs->spush[q] = (uint8_t)((rs->spush[q] & 12) | 2);
            } else if ((rs->spush[q] & 3) == 0) {
                n[0] = con[k].nx;
                n[1] = con[k].ny;
                rs->spush[q] |= 1;
            } else if ((rs->spush[q] & 3) == 1 && rg_fabs(n[0] * con[k].ny - n[1] * con[k].nx) > RG_R(1e-3)) {
                /* another direction (parallel ones, opposite too, are one) */
                rs->spush[q] = (uint8_t)((rs->spush[q] & 12) | 2);
            }
        }
    }
}

void resolve_run(rg_world *w, collide_step *x)
{
    collide_world *cw = &w->coll;
    resolve_state *rs = &cw->resolve;
    solver_rows *rows = &cw->rows;
    if (x->woke) resolve_restage(w, x);
    int32_t nc = x->nc;
    x->pressed = 0;
    if (nc == 0) {
        if (x->late != NULL) x->late(w, x);
        x->late = NULL;
        return;
    }
    solver_constraint *con = rows->stage;
    int32_t ns = x->ns;
    rg_real *v = rs->sv;
    solver_batch *sb = &rows->batch;
    resolve_task t;
    t.w = w;
    t.x = x;
    t.sb = sb;
    t.con = con;
    t.v = v;
    t.pv = rs->spv;
    t.timed = continuous_time_impacts(w, x);
    t.placed = w->integrator == RG_INTEGRATOR_EXPLICIT_EULER        ? 1
             : w->integrator != RG_INTEGRATOR_SEMI_IMPLICIT_EULER ? 2
                                                                  : 0;
    resolve_head h;
    h.t = &t;
    task_for(w, resolve_head_range, 2, 1, &h);
    x->late = NULL;
    rg_real gx = x->ux, gy = x->uy;
    int shock = x->down;
    const int32_t *ord = rows->ord;
    resolve_pass(&t, RESOLVE_PACK, 0, SOLVER_PACK_BLOCKS(nc));
    t.bands = resolve_bands_for(w, &t);
    if (t.bands > 1) {
        if (++rs->bgen == 0) {
            memset(rs->sband, 0, (size_t)cw->scap * BANDS_MAX);
            rs->bgen = 1;
        }
        rs->banded++;
        task_for(w, resolve_band_stamp, t.bands, 1, &t);
        task_for(w, resolve_band_flag, t.bands, 1, &t);
        t.what = RESOLVE_WARM;
        t.last = t.ncol * cw->iterations;
        bands_run(w, t.bands, t.ncol * (1 + cw->iterations), resolve_band_phase, &t);
    } else {
        if (solver_pack_wide()) resolve_pass(&t, RESOLVE_PACK_LANES, 0, sb->nrows);
        resolve_wide(&t, RESOLVE_WARM);
        solver_warm_start(con, sb->over, sb->nover, v);
        for (int32_t it = 0; it < cw->iterations; it++) {
            resolve_wide(&t, RESOLVE_VELOCITY);
            solver_iterate(con, sb->over, sb->nover, v);
        }
    }
    if (t.bands < 2) resolve_pass(&t, RESOLVE_UNPACK, 0, sb->nrows);
    if (shock) RESOLVE_PROF(2, solver_shock(con, ord, nc, v, gx, gy));
    solver_fixed_rows(con, rows->fixed, h.nfixed, v, 0);
    /* positions move with the solved velocities, then by the pseudo-velocities of the
     * position pass, which leave the velocities alone */
    if (t.placed) resolve_pushed(rs, &w->b, v, x->p.dt, x->p.slop, con, nc);
    /* the body passes: the list of the bodies the rows meet, or every awake body */
    int32_t first = t.listed ? 0 : 1, bodies = t.listed ? t.nbody : ns;
    resolve_pass(&t, RESOLVE_MOVE, first, bodies);
    int32_t pushing = 0, workers = task_workers(w);
    if (cw->position > 0) {
        for (int32_t k = 0; k < workers; k++) t.pushing[k] = 0;
        resolve_pass(&t, RESOLVE_PREPARE, 0, nc);
        for (int32_t k = 0; k < workers; k++) pushing += t.pushing[k];
    }
    if (pushing > 0) {
        rg_real *pv = rs->spv;
        if (t.listed) { /* the ground's (the padding lanes act on it) and the met bodies' */
            pv[0] = pv[1] = 0;
            for (int32_t k = 0; k < t.nbody; k++) pv[2 * rs->sbody[k]] = pv[2 * rs->sbody[k] + 1] = 0;
        } else {
            memset(pv, 0, (size_t)(2 * ns + 2) * sizeof *pv);
        }
        resolve_pass(&t, RESOLVE_PACK_POSITION, 0, sb->nrows);
        if (t.bands > 1) {
            t.what = RESOLVE_POSITION;
            t.last = t.ncol * (cw->position - 1);
            bands_run(w, t.bands, t.ncol * cw->position, resolve_band_phase, &t);
        } else {
            for (int32_t it = 0; it < cw->position; it++) {
                resolve_wide(&t, RESOLVE_POSITION);
                solver_iterate_position(con, sb->over, sb->nover, pv);
            }
        }
        if (t.bands < 2) resolve_pass(&t, RESOLVE_UNPACK_POSITION, 0, sb->nrows);
        if (shock) RESOLVE_PROF(2, solver_shock_position(con, ord, nc, pv, gx, gy));
        solver_fixed_rows(con, rows->fixed, h.nfixed, pv, 1);
        rs->pv_valid = 1;
        resolve_pass(&t, RESOLVE_PUSH, first, bodies);
    }
    for (int32_t k = 0; k < workers; k++) {
        t.pressed[k] = 0;
        t.press0[k] = nc;
        t.press1[k] = 0;
    }
    resolve_pass(&t, RESOLVE_KEEP, 0, nc);
    x->pressed = 0;
    x->press0 = nc;
    x->press1 = 0;
    for (int32_t k = 0; k < workers; k++) {
        x->pressed += t.pressed[k];
        if (x->press0 > t.press0[k]) x->press0 = t.press0[k];
        if (x->press1 < t.press1[k]) x->press1 = t.press1[k];
    }
}
