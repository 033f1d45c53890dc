/* solver.h: contact resolution for translation-only bodies by sequential impulses.
 *
 * One contact point per pair and no angular terms: the normal and the friction rows share
 * one effective mass m = 1 / (1/ma + 1/mb) and, being orthogonal, never disturb each other
 * within a contact.  Accumulated impulses are clamped (normal >= 0, |friction| <= mu *
 * normal) and kept across steps for warm starting.
 *
 * A step solves in two passes (split impulses):
 *   1. velocity iterations: vn >= vmin, where vmin = -s0/dt lets a pair that starts a gap
 *      s0 apart close it within the step and no further (a speculative contact), vmin = 0
 *      holds a touching pair, and vmin = -e * vn0 bounces an impact faster than the
 *      restitution threshold (vn0: the approach velocity at the start of the step); a timed
 *      impact (contact.h) aims at the velocity it leaves with instead, solver_vout.  No
 *      position error enters these rows, so the velocities that leave the step carry no
 *      push.
 *      Under gravity a final shock-propagation sweep (below) settles stacks at once.
 *   2. position iterations on pseudo-velocities that start at zero each step and only move
 *      positions: the penetration left after the velocity pass, s1 = s0 + vn*dt < -slop, is
 *      removed at bias_rate * (depth - slop) / dt (at most max_push).  Position correction
 *      therefore never adds kinetic energy. */
#ifndef RG_SOLVER_H
#define RG_SOLVER_H

#include <stddef.h>
#include <stdint.h>

#include "mem.h"
#include "rigid.h"

/* Solver body q's velocity pair (vx, vy) in v, an array of pairs with the ground at 0 (q >= 0:
 * as unsigned, the address needs no sign extension, which the wide loops paid on every
 * lane). */
#define SOLVER_PAIR(v, q) ((v) + 2 * (size_t)(uint32_t)(q))

/* max and min without branches (x86 SSE: one instruction each; elsewhere plain C).  Both
 * return b when a is NaN, like the C expression. */
#if defined(__SSE2__)
#include <emmintrin.h>
#ifdef RG_DOUBLE
static inline rg_real solver_smax(rg_real a, rg_real b) { return _mm_cvtsd_f64(_mm_max_sd(_mm_set_sd(a), _mm_set_sd(b))); }
static inline rg_real solver_smin(rg_real a, rg_real b) { return _mm_cvtsd_f64(_mm_min_sd(_mm_set_sd(a), _mm_set_sd(b))); }
#else
static inline rg_real solver_smax(rg_real a, rg_real b) { return _mm_cvtss_f32(_mm_max_ss(_mm_set_ss(a), _mm_set_ss(b))); }
static inline rg_real solver_smin(rg_real a, rg_real b) { return _mm_cvtss_f32(_mm_min_ss(_mm_set_ss(a), _mm_set_ss(b))); }
#endif
#else
static inline rg_real solver_smax(rg_real a, rg_real b) { return a > b ? a : b; }
static inline rg_real solver_smin(rg_real a, rg_real b) { return a < b ? a : b; }
#endif

typedef struct solver_constraint {
    int32_t a, b;      /* solver body indices (velocity pairs); 0 is the ground */
    rg_real ima, imb;  /* inverse masses, 1/kg */
    rg_real nx, ny;    /* unit normal from a to b */
    rg_real m;         /* effective mass, kg */
    rg_real mu;        /* friction coefficient */
    rg_real vmin;      /* velocity row: vn >= vmin, m/s */
    rg_real s0;        /* separation along n at the start of the step, m (< 0: depth) */
    rg_real pmin;      /* position row: pseudo vn >= pmin, m/s */
    rg_real pn, pt;    /* accumulated normal and friction impulses, N*s */
    rg_real pp;        /* accumulated pseudo impulse, N*s */
    rg_real toi;       /* the free motion closes the pair's gap at this fraction of the
                        * step, in (0, 1); 0 for a pair in contact; -1 for one apart that
                        * it does not close */
    int32_t cid;       /* the contact it came from */
} solver_constraint;

typedef struct solver_params {
    rg_real dt, inv_dt;
    rg_real slop;          /* m */
    rg_real bias_rate;     /* 1 */
    rg_real max_push;      /* m/s */
    rg_real restitution_threshold; /* m/s */
    rg_real stagger;       /* where the integrator's velocities sit in time (solver_vout) */
} solver_params;

/* The speculative velocity row of a contact that starts s0 apart (m) with relative normal
 * velocity vn0 (m/s, at the start of the step) and restitution e; `closing`: the step's free
 * motion would make the pair overlap.  The bounce turns the pair where the step began and
 * reverses the velocity it arrived with, vn0, not the one forces added during the step: with
 * e = 1 an impact then neither gains nor loses semi-implicit Euler's energy, whatever the
 * phase of the impact within the step. */
static inline rg_real solver_vmin(rg_real s0, rg_real vn0, rg_real e, int closing,
                                  const solver_params *p)
{
    rg_real vmin = s0 > 0 ? -s0 * p->inv_dt : 0;
    if (closing && e > 0 && vn0 < -p->restitution_threshold) {
        rg_real bounce = -e * vn0;
        if (bounce > vmin) vmin = bounce;
    }
    return vmin;
}

/* The relative normal velocity a pair leaves with when its free motion closes a gap at
 * fraction t of the step and the impact is timed: the bodies move freely until t and with the
 * solved velocity after it (contact.c places them so).  vn0 and vn1: the relative normal
 * velocity at the start of the step and after integration; dv = vn1 - vn0 is what the forces
 * add over the step.  An integrator's velocities sit at a time of their own: the true
 * velocity at the start of the step is vn0 + stagger * dv (semi-implicit Euler 1/2: its
 * velocity is that of the middle of the step it moved the body over; Verlet and RK4 0;
 * explicit Euler -1/2).  The pair meets at vi = vn0 + (stagger + t) dv, leaves at -e vi, and
 * the forces act on for the rest of the step:
 *     vout = -e vi + (1 - stagger - t) dv.
 * Under a constant acceleration a along the normal, semi-implicit Euler keeps
 * E = 1/2 v^2 - a y + 1/2 a dt v + a^2 dt^2 / 8 exactly in free flight (y the gap); with the
 * body ending the step at y = vout (1 - t) dt, this vout gives E' = e^2 E + (1 - e^2) a^2
 * dt^2 t (1 - t) / 2: an elastic bounce keeps E exactly, and a rebound rises to e^2 times the
 * drop height within a dt^2 / 8 (whatever the sign of a: floors and ceilings alike).  Without
 * a bounce (e = 0, an impact slower than the threshold, or one too weak to outlast the step)
 * the pair stays in contact: 0. */
static inline rg_real solver_vout(rg_real vn0, rg_real vn1, rg_real t, rg_real e,
                                  const solver_params *p)
{
    if (!(e > 0 && vn0 < -p->restitution_threshold)) return 0;
    rg_real dv = vn1 - vn0;
    rg_real vi = vn0 + (p->stagger + t) * dv;
    rg_real out = -e * vi + (1 - p->stagger - t) * dv;
    return out > 0 ? out : 0;
}

/* ---- rows one at a time.  `list` (k of them) selects rows by index; NULL takes c[0..k). */

/* Applies the accumulated impulses to the velocities v (pairs vx, vy per solver body). */
void solver_warm_start(const solver_constraint *c, const int32_t *list, int32_t k, rg_real *v);
/* One Gauss-Seidel sweep over the velocity rows. */
void solver_iterate(solver_constraint *c, const int32_t *list, int32_t k, rg_real *v);
/* Shock propagation (one sweep, rows ordered bottom-up along gravity): each row whose
 * normal lies within 60 degrees of gravity direction (gx, gy) (unit) is solved as if its
 * lower body were immovable, so only the upper body changes.  What the sweeps before it left
 * of a stack's compression is removed in one pass from the ground up; a light body under a
 * heavy one holds.  Dissipative: it only takes approach velocity out of upper bodies. */
void solver_shock(solver_constraint *c, const int32_t *order, int32_t n, rg_real *v, rg_real gx,
                  rg_real gy);
/* The same sweep over the position rows on pseudo-velocities pv: a stack pushed out of the
 * ground is pushed out as a whole, however heavy its top. */
void solver_shock_position(solver_constraint *c, const int32_t *order, int32_t n, rg_real *pv,
                           rg_real gx, rg_real gy);
/* Whether row q is against an immovable body (static, kinematic, sleeping). */
static inline int solver_row_fixed(const solver_constraint *q) { return !(q->ima > 0 && q->imb > 0); }
/* One last sweep over the rows against an immovable body, so that these win over what the
 * other rows left: a light body squeezed by a far heavier one may end inside it, but not
 * pushed through a wall.  `list` (k of them, in row order) holds those rows (the rows
 * solver_row_fixed says are).  Velocity rows on v, or position rows on pseudo-velocities pv. */
void solver_fixed_rows(solver_constraint *c, const int32_t *list, int32_t k, rg_real *v, int position);
/* Position rows from the penetration the velocities v leave; returns how many rows need a
 * push (0: the position pass can be skipped).  In solver_wide.c, beside its AVX2 path. */
int32_t solver_prepare_position(solver_constraint *c, int32_t n, const rg_real *v,
                                const solver_params *p);
/* One Gauss-Seidel sweep over the position rows on pseudo-velocities pv. */
void solver_iterate_position(solver_constraint *c, const int32_t *list, int32_t k, rg_real *pv);

/* ---- rows eight at a time.  A greedy graph colouring splits the rows into colours whose
 * rows share no movable body (inverse mass > 0; the ground and kinematic bodies, which no
 * row changes, may be shared); each colour is packed into groups of eight lanes solved
 * together (the velocity sweep in AVX2 where the CPU has it, else two halves in SSE2 in the
 * float build on x86, a plain loop over the lanes elsewhere: lanes of a colour touch
 * disjoint bodies and each lane does the same arithmetic, so every grouping gives the same
 * results).  Rows keep their bottom-up order within a colour.  Rows of bodies already in 32
 * colours overflow to a list solved one at a time. */

#define SOLVER_LANES 8

typedef struct solver_wide {
    int32_t a[SOLVER_LANES], b[SOLVER_LANES];
    rg_real nx[SOLVER_LANES], ny[SOLVER_LANES];
    rg_real m[SOLVER_LANES], mu[SOLVER_LANES];
    rg_real ima[SOLVER_LANES], imb[SOLVER_LANES];
    rg_real vmin[SOLVER_LANES], pn[SOLVER_LANES], pt[SOLVER_LANES];
    rg_real pmin[SOLVER_LANES], pp[SOLVER_LANES];
} solver_wide;

/* Most wide rows n rows can need. */
#define SOLVER_WIDE_ROWS(n) ((n) / SOLVER_LANES + 33)

typedef struct solver_batch {
    solver_wide *rows;   /* [0, nrows) */
    int32_t nrows;
    int32_t cstart[33];  /* colour c's rows: [cstart[c], cstart[c + 1]) */
    int32_t *row_of;     /* per wide slot: its row of c, -1 for padding */
    int32_t *over;       /* rows of c in the overflow list, [0, nover) */
    int32_t nover;
} solver_batch;

/* Row q's movable bodies, as the colouring reads them: ab[0] = a and ab[1] = b, each 0 (the
 * ground's index, whose colours stay none) for an immovable one.  Written with the row
 * (resolve.h), so that the colouring reads 8 bytes a row in its order, not the row. */
static inline void solver_row_bodies(const solver_constraint *q, int32_t *ab)
{
    ab[0] = q->ima > 0 ? q->a : 0;
    ab[1] = q->imb > 0 ? q->b : 0;
}

/* Colours rows order[0..n) (in that order; row k's movable bodies at ab[2k], ab[2k + 1]:
 * solver_row_bodies) over solver bodies [0, nbodies), body 0 being the ground (padding
 * lanes act on it with zero mass), lays out the wide rows, pads them and lists the
 * overflow; solver_pack_rows then copies the rows into their lanes, block by block of
 * SOLVER_PACK_BLOCK rows of `order` (blocks write disjoint lanes: they may run at once).
 * `mask` (nbodies words), `color` (n) and `lanes` (SOLVER_PACK_BLOCKS(n) * 32: each block's
 * first lane in each colour) are scratch kept from one call to the other; rows, row_of and
 * over must hold SOLVER_WIDE_ROWS(n), SOLVER_WIDE_ROWS(n) * SOLVER_LANES and n.  row_of
 * gives each lane its row of c (-1: padding); over holds rows of c.  solver_pack_rows
 * replaces each packed row's colour with its lane (row_of's inverse), so that the lines of
 * `color` it read are its thread's when solver_pack writes them next: writing a line that
 * another core has only read waits for that core to drop its copy, which on the README's
 * VM costs several times taking over a line the other core wrote. */
#define SOLVER_PACK_BLOCK 512
/* Whether rows are so few beside the solver bodies that what is kept per body is cleared, or
 * walked, row by row rather than whole: a world of many awake bodies of which few collide
 * (solver_pack's masks, the solve's body passes and pseudo-velocities, the impact times).
 * Only the bodies the rows meet are read, so either way gives the same results. */
static inline int solver_rows_few(int32_t rows, int32_t bodies) { return (int64_t)rows * 8 < bodies; }
#define SOLVER_PACK_BLOCKS(n) (((n) + SOLVER_PACK_BLOCK - 1) / SOLVER_PACK_BLOCK)
void solver_pack(const int32_t *ab, const int32_t *order, int32_t n, int32_t nbodies, uint32_t *mask,
                 int32_t *color, int32_t *lanes, solver_batch *out);
void solver_pack_rows(const solver_constraint *c, const int32_t *order, int32_t n, int32_t *color,
                      const int32_t *lanes, int32_t blk0, int32_t blk1, solver_batch *out);
/* Where the CPU has AVX2 (solver_pack_wide), solver_pack_rows only places the rows
 * (row_of), and solver_pack_lanes then fills wide rows [r0, r1) from them, eight rows of c at
 * a time through 8x8 transposes: the same lanes. */
int solver_pack_wide(void);
void solver_pack_lanes(solver_batch *out, const solver_constraint *c, int32_t r0, int32_t r1);
/* The wide calls take rows [r0, r1): within a colour the rows share no movable body, so its
 * rows may run in any split and order, at once on several threads, with the same results
 * (lanes on immovable bodies store back the velocity they loaded, which the caller makes
 * +0 where it is zero: resolve.c). */
void solver_wide_warm_start(const solver_batch *s, int32_t r0, int32_t r1, rg_real *v);
void solver_wide_iterate(solver_batch *s, int32_t r0, int32_t r1, rg_real *v);
/* Copies the accumulated impulses pn, pt (or the pseudo impulses pp) of the rows in wide
 * rows [r0, r1) (through row_of) back into their rows of c. */
void solver_unpack_wide(const solver_batch *s, solver_constraint *c, int32_t r0, int32_t r1, int position);
/* The position rows of wide rows [r0, r1): each lane's pmin from its row of c (0 for
 * padding), pp = 0.  Each wide row writes its own lanes. */
void solver_pack_position(solver_batch *s, const solver_constraint *c, int32_t r0, int32_t r1);
void solver_wide_iterate_position(solver_batch *s, int32_t r0, int32_t r1, rg_real *pv);

/* Where rows are staged (resolve.h's resolve_stage): row k in stage[k], its height hgt[k]
 * and movable bodies ab[2k], ab[2k + 1]; the impacts' rows listed in imp; *nc rows and
 * *nimp impacts there so far.  The rows themselves, counted by the step, or a block's place
 * in the parallel staging's spare arrays (solver_rows.spare). */
typedef struct solver_dest {
    solver_constraint *stage;
    rg_real *hgt;
    int32_t *ab, *imp;
    int32_t *nc, *nimp;
} solver_dest;

/* ---- the rows of a step and their scratch, sized by the contact capacity (one row per
 * contact at most), in one block. */
typedef struct solver_rows {
    solver_batch batch;       /* the rows eight at a time (rows: SOLVER_WIDE_ROWS(cap)) */
    solver_constraint *stage; /* [0, cap): rows in contact order, before sorting */
    rg_real *hgt;             /* [0, cap): their heights along gravity (resolve.h) */
    int32_t *ab;              /* [0, 2 cap): their movable bodies (solver_row_bodies) */
    int32_t *ord, *tord;      /* [0, cap): staged rows in solving order, radix scratch */
    int32_t nord;             /* rows ord held in order after the last solve (a hint only:
                               * resolve.c checks it), 0 when none */
    uint16_t *key, *tkey;     /* [0, cap): their sort keys, radix scratch */
    int32_t *color;           /* [0, cap): colouring scratch */
    int32_t *lanes;           /* [0, SOLVER_PACK_BLOCKS(cap) * 32): packing scratch */
    int32_t *imp;             /* [0, cap): staged rows that are impacts (toi > 0) */
    int32_t *fixed;           /* [0, cap): rows against an immovable body (solver_row_fixed) */
    int32_t *edge;            /* per wide row: when the colours run in bands (resolve.c), the
                               * wide rows of a band's slice of a colour that meet a body
                               * another band's rows meet, listed from the slice's start */
    int32_t *late;            /* what the parallel staging leaves for the commit (narrow.c):
                               * bodies to ground [0, 2 cap), contacts with an event [2 cap,
                               * 3 cap), two counts per block of contacts after that */
    void *block;
    size_t block_size;
    int32_t cap;
    /* The parallel staging's rows before their places are known (narrow.c): each block of
     * contacts stages at its first contact's index, and the rows are copied to their places
     * once every block is counted.  [0, cap) of stage, hgt, 2 cap of ab, cap of imp, in a
     * block of their own laid out by solver_rows_spare on the first step with workers (a
     * world on one thread never holds it); spare.nc and spare.nimp are NULL. */
    solver_dest spare;
    /* Which blocks of contacts the parallel staging's tasks hand out first (narrow.c): each
     * block's movable bodies' mean dense index in the last such step ([0, SOLVER_STAGE_BLOCKS
     * (cap)), -1 where it met none; `means` blocks have one), and the blocks in the order
     * given to the tasks.  In the spare block too. */
    int32_t *mean, *handed;
    int32_t means;
    void *spare_block;
    size_t spare_size;
} solver_rows;

/* The parallel staging's blocks of contacts (narrow.c), and how many cap contacts make. */
#define SOLVER_STAGE_BLOCK 256
#define SOLVER_STAGE_BLOCKS(cap) (((cap) + SOLVER_STAGE_BLOCK - 1) / SOLVER_STAGE_BLOCK)

/* Rows for cap contacts into *fresh (nothing allocated on failure: RG_ERR_OUT_OF_MEMORY). */
rg_status solver_rows_alloc(solver_rows *fresh, const rg_mem *m, int32_t cap);
/* Lays out r's spare arrays if they are not yet; returns 0 (holding none) if the allocator
 * fails. */
int solver_rows_spare(solver_rows *r, const rg_mem *m);
void solver_rows_release(solver_rows *r, const rg_mem *m);

#endif
