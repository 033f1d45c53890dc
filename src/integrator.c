/* integrator.c: the four integrators over the dense arrays of the active partition, with
 * dissipation that never reverses or grows a velocity. */
#include <string.h>

#include "body.h"
#include "bounds.h"
#include "dispatch.h"
#include "force.h"
#include "integrator.h"
#include "state.h"
#include "task.h"
#include "vec2.h"

/* Backward-Euler dissipation for one body: given the velocity v_free the other forces give
 * over h, solve v' = v_free - h/m * (muN + lin*|v'| + quad*|v'|^2) * v'/|v'| for v' along
 * v_free.  Friction that exceeds |v_free| stops the body exactly (static friction);
 * otherwise a*s^2 + b*s - (|v_free| - h*muN/m) = 0 with a = h*quad/m, b = 1 + h*lin/m,
 * taken in the cancellation-free form s = 2c / (b + sqrt(b^2 + 4ac)).  |v'| <= |v_free|, so
 * it can never reverse or grow the velocity. */
static inline void dissipate_implicit(rg_real vfx, rg_real vfy, rg_real lin, rg_real quad,
                                      rg_real fric, rg_real inv_m, rg_real h,
                                      rg_real *out_vx, rg_real *out_vy)
{
    rg_real s = rg_sqrt(vfx * vfx + vfy * vfy);
    rg_real c = s - h * inv_m * fric;
    if (!(c > 0)) {
        *out_vx = 0;
        *out_vy = 0;
        return;
    }
    rg_real a = h * inv_m * quad, bb = 1 + h * inv_m * lin;
    rg_real s1 = 2 * c / (bb + rg_sqrt(bb * bb + 4 * a * c));
    rg_real k = s1 / s;
    *out_vx = vfx * k;
    *out_vy = vfy * k;
}

/* The explicit step is kept unless it would carry the velocity through zero (the new
 * velocity no longer points along v_free), or a body with surface friction starts at rest,
 * where friction has no direction and acts as static friction.  (Drag vanishes smoothly at
 * rest, so a body with drag alone keeps the explicit step there and the integrator keeps
 * its order from rest.)  NaN compares false, so it falls back too. */
static inline int dissipation_overshoots(rg_real v0x, rg_real v0y, rg_real nvx, rg_real nvy,
                                         rg_real vfx, rg_real vfy, rg_real fric)
{
    return (fric > 0 && v0x == 0 && v0y == 0) || !(nvx * vfx + nvy * vfy > 0);
}

/* The explicit (Euler) dissipation check of body i from v0, given v_free: returns 1 when the
 * step must treat dissipation implicitly, else 0 and the explicit velocity in *nvx, *nvy and
 * the dissipative acceleration added to *ax, *ay.  Every integrator makes this decision
 * from the start state: a multi-stage method evaluated past the stop sees friction flip
 * between stages, cancel, and creep forever instead of stopping.
 *
 * Besides the overshoot, the step is stiff when the dissipation rate k (1/s: drag and
 * friction per unit speed over the mass) reaches 1/h anywhere the step can go: explicit
 * Euler then takes more than the whole velocity away along v0 (its factor 1 - kh <= 0) even
 * when the other forces keep the result pointing along v_free, and RK4's and Verlet's
 * stages overshoot and grow (their factors 1 - z + z^2/2 - ... stay in (0, 1) only for
 * z = kh < 1).  `reach` bounds how far the speed can rise within the step (0 for Euler,
 * h |a_free| for the multi-stage methods), so quadratic drag is judged at its largest. */
static inline int dissipation_explicit(const body_store *b, int32_t i, rg_real v0x, rg_real v0y,
                                       rg_real vfx, rg_real vfy, rg_real h, rg_real reach,
                                       rg_real *ax, rg_real *ay, rg_real *nvx, rg_real *nvy)
{
    rg_real speed = rg_sqrt(v0x * v0x + v0y * v0y);
    rg_real im = b->inv_mass[i], lin = b->drag_lin[i], quad = b->drag_quad[i];
    rg_real dax = 0, day = 0, kmax = (lin + quad * reach) * im;
    if (speed > 0) {
        rg_real k = (lin + quad * speed + b->fric[i] / speed) * im;
        dax = -k * v0x;
        day = -k * v0y;
        kmax = (lin + quad * (speed + reach) + b->fric[i] / speed) * im;
    }
    *ax += dax;
    *ay += day;
    *nvx = vfx + dax * h;
    *nvy = vfy + day * h;
    return !(kmax * h < 1) || dissipation_overshoots(v0x, v0y, *nvx, *nvy, vfx, vfy, b->fric[i]);
}

/* Explicit and semi-implicit Euler in one fused pass: one force evaluation at the start
 * state, so drag and friction are evaluated inline and springs come from one spring pass. */
typedef struct euler_env {
    rg_real h, gx, gy, wx, wy;
    const rg_real *sax, *say;
    int springs, dissipative, explicit_euler;
    int forces; /* some body may have an applied force (rg_world.forces_applied) */
    int wind;    /* the wind is not zero */
    int gscaled; /* some body has BODY_F_GSCALE */
    int linear;  /* every moving body has BODY_F_DISSIPATIVE, none BODY_F_MAGNITUDE or
                  * BODY_F_GSCALE: every block's flags are known without reading them */
    /* the one acceleration of a uniform block (euler_in): force_sum with the gravity scale
     * 1, (wind + f) = +0 times an inverse mass of +0, and the spring term -0 */
    rg_real ax0, ay0;
    int plain; /* no wind, applied forces or springs: a block without BODY_F_GSCALE is uniform */
} euler_env;

/* One body of the pass, exactly as specified; the blocked loop below runs it wherever its
 * fast path does not apply.  Returns 1 when the body's new state is out of range
 * (bounds.h). */
static inline int32_t euler_body(body_store *b, const euler_env *e, int32_t i)
{
    rg_real h = e->h;
    rg_real im = b->inv_mass[i];
    rg_real ax = force_sum(e->gx, b->gscale[i], e->wx, b->fx[i], im);
    rg_real ay = force_sum(e->gy, b->gscale[i], e->wy, b->fy[i], im);
    if (e->springs) {
        ax += e->sax[i];
        ay += e->say[i];
    }
    rg_real v0x = b->vx[i], v0y = b->vy[i];
    rg_real vfx = v0x + ax * h, vfy = v0y + ay * h; /* without dissipation */
    rg_real nvx = vfx, nvy = vfy;
    if (e->dissipative && (b->flags[i] & BODY_F_DISSIPATIVE) &&
        dissipation_explicit(b, i, v0x, v0y, vfx, vfy, h, 0, &ax, &ay, &nvx, &nvy))
        dissipate_implicit(vfx, vfy, b->drag_lin[i], b->drag_quad[i], b->fric[i], im, h, &nvx, &nvy);
    b->ax[i] = ax;
    b->ay[i] = ay;
    if (e->explicit_euler) {
        b->x[i] += v0x * h;
        b->y[i] += v0y * h;
    } else {
        b->x[i] += nvx * h;
        b->y[i] += nvy * h;
    }
    b->vx[i] = nvx;
    b->vy[i] = nvy;
    return bounds_out(b->x[i], b->y[i], nvx, nvy);
}

/* Blocks of a constant length, so the compiler vectorises them at -O2 without an epilogue;
 * restrict parameters spare it alias checks. */
#define EULER_BLOCK 64

/* The commit of a block whose bodies all took the fast path: positions from the old
 * (explicit) or new (semi-implicit) velocities, then the new velocities.  Returns 1 when a
 * body's new state is out of range (bounds.h), checked here while it is in registers. */
static DISPATCH_INLINE int32_t euler_commit(rg_real *restrict x, rg_real *restrict y, rg_real *restrict vx,
                                   rg_real *restrict vy, const rg_real *restrict nvx,
                                   const rg_real *restrict nvy, rg_real h, int explicit_euler)
{
    int32_t out = 0;
    if (explicit_euler) {
        for (int j = 0; j < EULER_BLOCK; j++) {
            rg_real px = x[j] + vx[j] * h, py = y[j] + vy[j] * h;
            x[j] = px;
            y[j] = py;
            vx[j] = nvx[j];
            vy[j] = nvy[j];
            out |= bounds_out(px, py, nvx[j], nvy[j]);
        }
    } else {
        for (int j = 0; j < EULER_BLOCK; j++) {
            rg_real ux = nvx[j], uy = nvy[j];
            rg_real px = x[j] + ux * h, py = y[j] + uy * h;
            x[j] = px;
            y[j] = py;
            vx[j] = ux;
            vy[j] = uy;
            out |= bounds_out(px, py, ux, uy);
        }
    }
    return out;
}

/* The pass runs in blocks: a branch-free first loop computes every body's new velocity into
 * block-local arrays (and its acceleration, an output only, in place), and a second loop
 * commits the block unless one of its bodies needs what the fast path leaves out (quadratic
 * drag or surface friction, BODY_F_MAGNITUDE; a body at rest or with a huge speed, a
 * dissipation overshoot or a stiff step, kh >= 1): then the block runs body by body.  The
 * fast path does the same IEEE operations in the same order, so results are bit-identical
 * either way: with quad and fric both +-0 and 0 < |v|^2 < HUGE, quad*|v| == quad and
 * fric/|v| == fric exactly, so k = (lin + quad + fric) * im needs no square root, and where
 * a body is dissipative without BODY_F_MAGNITUDE it has lin > 0 and k = lin * im exactly;
 * the rest is dissipation_explicit's arithmetic and dissipation_overshoots' test.  Without
 * springs the spring term is -0, the exact identity of addition.
 *
 * What every body of a block would read as the same value comes from the block-sized
 * constants of `c` instead of memory: the gravity scale 1 where no body of the block has
 * BODY_F_GSCALE (g * 1 == g), and, with no wind and no applied force, an inverse mass of 0
 * in force_sum: there (wind + f) is +0, and +0 times any inverse mass (finite, >= 0) is +0.
 * Returns 1 when the block must run body by body. */
typedef struct euler_const {
    rg_real no_spring[EULER_BLOCK]; /* -0 */
    rg_real zero[EULER_BLOCK];      /* +0: what a step's clearing leaves in fx and fy */
    rg_real one[EULER_BLOCK];
} euler_const;

/* A block's inputs.  A block is uniform when no body has BODY_F_GSCALE and there are no
 * wind, applied forces or springs: every body of it then feels euler_env's ax0, ay0, the
 * same operations on the same values as each body's. */
typedef struct euler_in {
    const rg_real *gs, *imf, *fx, *fy, *spx, *spy;
} euler_in;

/* The accelerations of body j of the block other than dissipation; with `uniform` a
 * constant at the call, so the loops below are built once for each case. */
#define EULER_ACC(in, uniform, j, a0, g, w, f, sp) \
    ((uniform) ? e->a0 : force_sum(e->g, (in)->gs[j], e->w, (in)->f[j], (in)->imf[j]) + (in)->sp[j])

/* No dissipation in the block. */
static DISPATCH_INLINE void euler_free(const body_store *b, int32_t i0, const euler_env *e,
                                       const euler_in *in, int uniform, rg_real *restrict nvx,
                                       rg_real *restrict nvy, rg_real *restrict oax, rg_real *restrict oay)
{
    const rg_real *restrict vx = b->vx + i0, *restrict vy = b->vy + i0;
    const rg_real h = e->h;
    for (int j = 0; j < EULER_BLOCK; j++) {
        rg_real ax = EULER_ACC(in, uniform, j, ax0, gx, wx, fx, spx);
        rg_real ay = EULER_ACC(in, uniform, j, ay0, gy, wy, fy, spy);
        oax[j] = ax;
        oay[j] = ay;
        nvx[j] = vx[j] + ax * h;
        nvy[j] = vy[j] + ay * h;
    }
}

/* Linear drag on every body of the block; returns nonzero when a body needs the slow path. */
static DISPATCH_INLINE int32_t euler_linear(const body_store *b, int32_t i0, const euler_env *e,
                                            const euler_in *in, int uniform, rg_real *restrict nvx,
                                            rg_real *restrict nvy, rg_real *restrict oax, rg_real *restrict oay)
{
    const rg_real *restrict im = b->inv_mass + i0, *restrict lin = b->drag_lin + i0;
    const rg_real *restrict vx = b->vx + i0, *restrict vy = b->vy + i0;
    const rg_real h = e->h;
    int32_t slow = 0;
    for (int j = 0; j < EULER_BLOCK; j++) {
        rg_real ax = EULER_ACC(in, uniform, j, ax0, gx, wx, fx, spx);
        rg_real ay = EULER_ACC(in, uniform, j, ay0, gy, wy, fy, spy);
        rg_real v0x = vx[j], v0y = vy[j];
        rg_real vfx = v0x + ax * h, vfy = v0y + ay * h;
        rg_real s2 = v0x * v0x + v0y * v0y;
        rg_real k = lin[j] * im[j];
        rg_real dax = -k * v0x, day = -k * v0y;
        rg_real dvx = vfx + dax * h, dvy = vfy + day * h;
        slow |= !((s2 > 0) & (s2 < RG_HUGE) & (k * h < 1) & (dvx * vfx + dvy * vfy > 0));
        oax[j] = ax + dax;
        oay[j] = ay + day;
        nvx[j] = dvx;
        nvy[j] = dvy;
    }
    return slow;
}

/* A block of dissipative and other bodies; returns nonzero when a body needs the slow path. */
static DISPATCH_INLINE int32_t euler_mixed(const body_store *b, int32_t i0, const euler_env *e,
                                           const euler_in *in, rg_real *restrict nvx,
                                           rg_real *restrict nvy, rg_real *restrict oax, rg_real *restrict oay)
{
    const rg_real *restrict im = b->inv_mass + i0, *restrict lin = b->drag_lin + i0;
    const rg_real *restrict vx = b->vx + i0, *restrict vy = b->vy + i0;
    const uint32_t *restrict fl = b->flags + i0;
    const rg_real h = e->h;
    int32_t slow = 0;
    for (int j = 0; j < EULER_BLOCK; j++) {
        rg_real ax = EULER_ACC(in, 0, j, ax0, gx, wx, fx, spx);
        rg_real ay = EULER_ACC(in, 0, j, ay0, gy, wy, fy, spy);
        rg_real v0x = vx[j], v0y = vy[j];
        rg_real vfx = v0x + ax * h, vfy = v0y + ay * h;
        rg_real s2 = v0x * v0x + v0y * v0y;
        rg_real k = lin[j] * im[j]; /* exact where it is used: d and no magnitude */
        rg_real dax = -k * v0x, day = -k * v0y;
        rg_real dvx = vfx + dax * h, dvy = vfy + day * h;
        rg_real tax = ax + dax, tay = ay + day;
        /* The flag bits moved to the sign bit: a 32-bit compare the vectoriser takes. */
        int32_t d = (int32_t)(fl[j] * (0x80000000u / BODY_F_DISSIPATIVE)) < 0;
        int32_t m = (int32_t)(fl[j] * (0x80000000u / BODY_F_MAGNITUDE)) < 0;
        /* The finiteness test of tax, tay also keeps their adds out of the selects
         * below (an add there may trap under -ftrapping-math and would keep a branch). */
        int32_t ok = !m & (s2 > 0) & (s2 < RG_HUGE) & (k * h < 1) & (dvx * vfx + dvy * vfy > 0) &
                     (tax - tax == 0) & (tay - tay == 0);
        slow |= d & !ok;
        oax[j] = d ? tax : ax;
        oay[j] = d ? tay : ay;
        nvx[j] = d ? dvx : vfx;
        nvy[j] = d ? dvy : vfy;
    }
    return slow;
}

/* Returns 1 when the block must run body by body. */
static DISPATCH_INLINE int euler_block(const body_store *b, int32_t i0, const euler_env *e,
                                       const euler_const *c, rg_real *restrict nvx, rg_real *restrict nvy)
{
    const uint32_t *restrict fl = b->flags + i0;
    uint32_t all = ~0u, any = 0;
    if (e->linear) {
        all = any = BODY_F_DISSIPATIVE;
    } else if (e->dissipative || e->gscaled) {
        for (int j = 0; j < EULER_BLOCK; j++) {
            all &= fl[j];
            any |= fl[j];
        }
    }
    euler_in in;
    in.gs = (any & BODY_F_GSCALE) ? b->gscale + i0 : c->one;
    in.imf = e->wind || e->forces ? b->inv_mass + i0 : c->zero;
    in.fx = e->forces ? b->fx + i0 : c->zero;
    in.fy = e->forces ? b->fy + i0 : c->zero;
    in.spx = e->springs ? e->sax + i0 : c->no_spring;
    in.spy = e->springs ? e->say + i0 : c->no_spring;
    int uniform = e->plain && !(any & BODY_F_GSCALE);
    /* A slow block's accelerations are written again by euler_body. */
    rg_real *oax = b->ax + i0, *oay = b->ay + i0;
    if (!(any & BODY_F_DISSIPATIVE)) {
        if (uniform)
            euler_free(b, i0, e, &in, 1, nvx, nvy, oax, oay);
        else
            euler_free(b, i0, e, &in, 0, nvx, nvy, oax, oay);
        return 0;
    }
    if ((all & BODY_F_DISSIPATIVE) && !(any & BODY_F_MAGNITUDE))
        return (uniform ? euler_linear(b, i0, e, &in, 1, nvx, nvy, oax, oay)
                        : euler_linear(b, i0, e, &in, 0, nvx, nvy, oax, oay)) != 0;
    if (all & BODY_F_DISSIPATIVE) return 1; /* quadratic drag or friction: square roots, body by body */
    return euler_mixed(b, i0, e, &in, nvx, nvy, oax, oay) != 0;
}

/* The pass over blocks [begin, end) of EULER_BLOCK bodies (the last one short), as a task
 * (task.h): each block's bodies are its own, so any split gives the same results.  The
 * worker's slot of `out` records a body out of range. */
typedef struct euler_task {
    body_store *b;
    euler_env e;
    int32_t n;
    int32_t out[RG_MAX_WORKERS];
} euler_task;

/* The pass over the active bodies [begin, end), built for SSE2 and AVX2 (dispatch.h). */
DISPATCH static void euler_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    euler_task *t = context;
    body_store *b = t->b;
    const euler_env *e = &t->e;
    euler_const c;
    for (int j = 0; j < EULER_BLOCK; j++) {
        c.no_spring[j] = -RG_R(0.0);
        c.zero[j] = 0;
        c.one[j] = 1;
    }
    int32_t out = 0;
    for (int32_t k = begin; k < end; k++) {
        int32_t i0 = k * EULER_BLOCK;
        if (i0 + EULER_BLOCK > t->n) { /* the short last block */
            for (int32_t i = i0; i < t->n; i++) out |= euler_body(b, e, i);
            continue;
        }
        rg_real nvx[EULER_BLOCK], nvy[EULER_BLOCK];
        if (euler_block(b, i0, e, &c, nvx, nvy)) {
            for (int j = 0; j < EULER_BLOCK; j++) out |= euler_body(b, e, i0 + j);
            continue;
        }
        out |= euler_commit(b->x + i0, b->y + i0, b->vx + i0, b->vy + i0, nvx, nvy, e->h, e->explicit_euler);
    }
    t->out[worker] |= out;
}

/* Blocks per task range: some 1000 bodies, so a range outweighs handing it out. */
#define EULER_RANGE 16

/* Returns 1 when a body's new state is out of range. */
static int32_t euler_step(rg_world *w, rg_real h, int explicit_euler)
{
    euler_task t;
    euler_env *e = &t.e;
    t.b = &w->b;
    t.n = w->b.n_active;
    e->h = h;
    e->gx = w->gravity.x;
    e->gy = w->gravity.y;
    e->wx = w->wind.x;
    e->wy = w->wind.y;
    e->springs = w->springs.count > 0;
    e->dissipative = w->dissipative_count > 0;
    e->explicit_euler = explicit_euler;
    e->forces = w->forces_applied;
    e->wind = e->wx != 0 || e->wy != 0;
    e->gscaled = w->gscale_count > 0;
    /* dissipative bodies are dynamic, so as many as the moving ones means every one */
    e->linear = w->dissipative_count == w->b.n_moving && w->magnitude_count == 0 && !e->gscaled;
    e->plain = !e->wind && !e->forces && !e->springs;
    e->ax0 = force_sum(e->gx, 1, e->wx, 0, 0) + -RG_R(0.0);
    e->ay0 = force_sum(e->gy, 1, e->wy, 0, 0) + -RG_R(0.0);
    /* the springs at the start state come from the forces stage (force_begin) */
    e->sax = w->scratch.sax;
    e->say = w->scratch.say;
    int32_t workers = task_workers(w), out = 0;
    for (int32_t k = 0; k < workers; k++) t.out[k] = 0;
    task_for(w, euler_range, (t.n + EULER_BLOCK - 1) / EULER_BLOCK, EULER_RANGE, &t);
    for (int32_t k = 0; k < workers; k++) out |= t.out[k];
    return out;
}

static void save_start(rg_world *w, int32_t n)
{
    scratch_store *s = &w->scratch;
    const body_store *b = &w->b;
    if (n == 0) return; /* no arrays yet: memcpy(NULL, NULL, 0) is undefined */
    memcpy(s->x0, b->x, (size_t)n * sizeof *b->x);
    memcpy(s->y0, b->y, (size_t)n * sizeof *b->y);
    memcpy(s->vx0, b->vx, (size_t)n * sizeof *b->vx);
    memcpy(s->vy0, b->vy, (size_t)n * sizeof *b->vy);
}

/* v_free = v0 + h * (gravity, wind, applied, springs at the start, from the forces stage):
 * what the step would
 * give without dissipation, the reference the guard compares against; and the start-state
 * decision whether this body's dissipation is treated implicitly this step. */
static void free_velocity(rg_world *w, rg_real h)
{
    body_store *b = &w->b;
    scratch_store *s = &w->scratch;
    int32_t n = b->n_active;
    for (int32_t i = 0; i < n; i++) {
        if (!(b->flags[i] & BODY_F_DISSIPATIVE)) continue;
        rg_real im = b->inv_mass[i];
        rg_real ax = force_sum(w->gravity.x, b->gscale[i], w->wind.x, b->fx[i], im);
        rg_real ay = force_sum(w->gravity.y, b->gscale[i], w->wind.y, b->fy[i], im);
        if (w->springs.count > 0) {
            ax += s->sax[i];
            ay += s->say[i];
        }
        rg_real vfx = b->vx[i] + ax * h, vfy = b->vy[i] + ay * h, nvx, nvy;
        s->vfx[i] = vfx;
        s->vfy[i] = vfy;
        /* a_free now holds the other forces only (the call below adds the dissipation) */
        rg_real reach = h * rg_sqrt(ax * ax + ay * ay);
        s->implicit[i] = dissipation_explicit(b, i, b->vx[i], b->vy[i], vfx, vfy, h, reach, &ax, &ay,
                                              &nvx, &nvy);
    }
}

static void guard_dissipation(rg_world *w, rg_real h)
{
    body_store *b = &w->b;
    scratch_store *s = &w->scratch;
    int32_t n = b->n_active;
    for (int32_t i = 0; i < n; i++) {
        if (!(b->flags[i] & BODY_F_DISSIPATIVE)) continue;
        if (!s->implicit[i] &&
            !dissipation_overshoots(s->vx0[i], s->vy0[i], b->vx[i], b->vy[i], s->vfx[i], s->vfy[i],
                                    b->fric[i]))
            continue;
        rg_real vx, vy;
        dissipate_implicit(s->vfx[i], s->vfy[i], b->drag_lin[i], b->drag_quad[i], b->fric[i],
                           b->inv_mass[i], h, &vx, &vy);
        b->vx[i] = vx;
        b->vy[i] = vy;
        b->x[i] = s->x0[i] + vx * h;
        b->y[i] = s->y0[i] + vy * h;
    }
}

/* Velocity Verlet; velocity-dependent forces see the predicted velocity v0 + h*a0:
 *   x1 = x0 + h v0 + h^2/2 a0,  a1 = a(x1, v0 + h a0),  v1 = v0 + h/2 (a0 + a1). */
static void verlet_step(rg_world *w, rg_real h)
{
    body_store *b = &w->b;
    scratch_store *s = &w->scratch;
    int32_t n = b->n_active;
    rg_real hh = h * h / 2, h2 = h / 2;
    force_eval(w, b->ax, b->ay, 1);
    for (int32_t i = 0; i < n; i++) {
        b->x[i] += h * b->vx[i] + hh * b->ax[i];
        b->y[i] += h * b->vy[i] + hh * b->ay[i];
        b->vx[i] = s->vx0[i] + h * b->ax[i];
        b->vy[i] = s->vy0[i] + h * b->ay[i];
    }
    force_eval(w, s->tax, s->tay, 0);
    for (int32_t i = 0; i < n; i++) {
        b->vx[i] = s->vx0[i] + h2 * (b->ax[i] + s->tax[i]);
        b->vy[i] = s->vy0[i] + h2 * (b->ay[i] + s->tay[i]);
    }
}

/* Classic RK4 on (x, v): k1 at the start, k2 and k3 at the midpoint, k4 at the end,
 * weights 1, 2, 2, 1.  kx/kvx accumulate the weighted derivatives. */
static void rk4_step(rg_world *w, rg_real h)
{
    body_store *b = &w->b;
    scratch_store *s = &w->scratch;
    int32_t n = b->n_active;
    rg_real h2 = h / 2;
    force_eval(w, b->ax, b->ay, 1);
    for (int32_t i = 0; i < n; i++) {
        s->kx[i] = s->vx0[i];
        s->ky[i] = s->vy0[i];
        s->kvx[i] = b->ax[i];
        s->kvy[i] = b->ay[i];
        b->x[i] = s->x0[i] + h2 * s->vx0[i];
        b->y[i] = s->y0[i] + h2 * s->vy0[i];
        b->vx[i] = s->vx0[i] + h2 * b->ax[i];
        b->vy[i] = s->vy0[i] + h2 * b->ay[i];
    }
    for (int stage = 2; stage <= 3; stage++) {
        rg_real hs = stage == 2 ? h2 : h;
        force_eval(w, s->tax, s->tay, 0);
        for (int32_t i = 0; i < n; i++) {
            rg_real vx = b->vx[i], vy = b->vy[i];
            s->kx[i] += 2 * vx;
            s->ky[i] += 2 * vy;
            s->kvx[i] += 2 * s->tax[i];
            s->kvy[i] += 2 * s->tay[i];
            b->x[i] = s->x0[i] + hs * vx;
            b->y[i] = s->y0[i] + hs * vy;
            b->vx[i] = s->vx0[i] + hs * s->tax[i];
            b->vy[i] = s->vy0[i] + hs * s->tay[i];
        }
    }
    force_eval(w, s->tax, s->tay, 0);
    rg_real h6 = h / 6;
    for (int32_t i = 0; i < n; i++) {
        rg_real kx = s->kx[i] + b->vx[i], ky = s->ky[i] + b->vy[i];
        rg_real kvx = s->kvx[i] + s->tax[i], kvy = s->kvy[i] + s->tay[i];
        b->x[i] = s->x0[i] + h6 * kx;
        b->y[i] = s->y0[i] + h6 * ky;
        b->vx[i] = s->vx0[i] + h6 * kvx;
        b->vy[i] = s->vy0[i] + h6 * kvy;
    }
}

rg_status integrator_prepare(rg_world *w)
{
    int multi_stage = w->integrator == RG_INTEGRATOR_VELOCITY_VERLET ||
                      w->integrator == RG_INTEGRATOR_RK4;
    if (multi_stage || w->springs.count > 0) return body_scratch_reserve(w);
    return RG_OK;
}

int integrator_step(rg_world *w, rg_real h)
{
    switch (w->integrator) {
    case RG_INTEGRATOR_EXPLICIT_EULER:
        return euler_step(w, h, 1);
    case RG_INTEGRATOR_SEMI_IMPLICIT_EULER:
        return euler_step(w, h, 0);
    default: {
        int32_t n = w->b.n_active;
        save_start(w, n);
        if (w->dissipative_count > 0) free_velocity(w, h);
        if (w->integrator == RG_INTEGRATOR_VELOCITY_VERLET)
            verlet_step(w, h);
        else
            rk4_step(w, h);
        if (w->dissipative_count > 0) guard_dissipation(w, h);
        return 1; /* four or two force passes: the range guard's own pass costs little */
    }
    }
}
