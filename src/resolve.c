/* resolve.c: the solve driver (see resolve.h). */
#include <string.h>

#include "body.h"
#include "continuous.h"
#include "resolve.h"
#include "state.h"
#include "task.h"
#include "vec2.h"

void resolve_layout(mem_layout *l, resolve_state *s, int32_t n)
{
    s->sv = mem_take(l, (size_t)n, 2 * sizeof(rg_real));
    s->spv = mem_take(l, (size_t)n, 2 * sizeof(rg_real));
    s->stoi = mem_take(l, (size_t)n, sizeof(rg_real));
    s->sidx = mem_take(l, (size_t)n, sizeof(int32_t));
    s->sstamp = mem_take(l, (size_t)n, sizeof(uint32_t));
    s->sbody = mem_take(l, (size_t)n, sizeof(int32_t));
    s->cmask = mem_take(l, (size_t)n, sizeof(uint32_t));
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
    resolve_next_gen(&cw->resolve, cw->scap);
    x->ns = 0;
    x->nimp = 0;
    x->nc = 0;
    x->n = n;
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
        resolve_stage(w, x, id, ia, ib, ima, imb);
    }
}

/* LSD radix sort of n (key, value) pairs by 16-bit key, two passes of 8 bits; stable. */
static void resolve_radix_sort16(uint16_t *key, int32_t *val, uint16_t *tkey, int32_t *tval, int32_t n)
{
    for (int shift = 0; shift < 16; shift += 8) {
        int32_t count[257];
        memset(count, 0, sizeof count);
        for (int32_t i = 0; i < n; i++) count[((key[i] >> shift) & 255) + 1]++;
        for (int d = 0; d < 256; d++) count[d + 1] += count[d];
        for (int32_t i = 0; i < n; i++) {
            int32_t at = count[(key[i] >> shift) & 255]++;
            tkey[at] = key[i];
            tval[at] = val[i];
        }
        uint16_t *kt = key;
        key = tkey;
        tkey = kt;
        int32_t *vt = val;
        val = tval;
        tval = vt;
    }
}

/* Under gravity, rows bottom-up by the height of the contact point: Gauss-Seidel then
 * carries support up a stack within a sweep, and the shock sweep needs the order.  Returns
 * whether there is gravity, with its unit direction in *ux, *uy. */
static int resolve_order(rg_world *w, int32_t nc, rg_real *ux, rg_real *uy)
{
    solver_rows *rows = &w->coll.rows;
    rg_real gx = w->gravity.x, gy = w->gravity.y, gl = rg_sqrt(gx * gx + gy * gy);
    int shock = gl > 0 && rg_finite(gl);
    if (shock) {
        gx /= gl;
        gy /= gl;
        rg_real *h = rows->hgt;
        rg_real hmin = RG_HUGE, hmax = -RG_HUGE;
        for (int32_t k = 0; k < nc; k++) {
            h[k] = -(rows->hgx[k] * gx + h[k] * gy);
            hmin = rg_min(hmin, h[k]);
            hmax = rg_max(hmax, h[k]);
        }
        rg_real scale = hmax > hmin ? RG_R(65535) / (hmax - hmin) : 0;
        if (!rg_finite(scale)) scale = 0;
        for (int32_t k = 0; k < nc; k++) {
            rg_real q = (h[k] - hmin) * scale;
            rows->key[k] = (uint16_t)(q >= 0 && q <= RG_R(65535) ? q : 0);
            rows->ord[k] = k;
        }
        resolve_radix_sort16(rows->key, rows->ord, rows->tkey, rows->tord, nc);
    } else {
        for (int32_t k = 0; k < nc; k++) rows->ord[k] = k;
    }
    *ux = gx;
    *uy = gy;
    return shock;
}

/* The wide rows colour by colour, each colour's rows split over the task system (its rows
 * share no movable body); the colours in order. */
enum { RESOLVE_WARM, RESOLVE_VELOCITY, RESOLVE_POSITION };

typedef struct resolve_task {
    solver_batch *sb;
    rg_real *v;
    int32_t r0;
    int what;
} resolve_task;

static void resolve_rows(int32_t begin, int32_t end, int32_t worker, void *context)
{
    const resolve_task *t = context;
    (void)worker;
    if (t->what == RESOLVE_WARM) solver_wide_warm_start(t->sb, t->r0 + begin, t->r0 + end, t->v);
    else if (t->what == RESOLVE_VELOCITY) solver_wide_iterate(t->sb, t->r0 + begin, t->r0 + end, t->v);
    else solver_wide_iterate_position(t->sb, t->r0 + begin, t->r0 + end, t->v);
}

/* Wide rows per range: 64 lanes. */
#define RESOLVE_RANGE 8

static void resolve_wide(rg_world *w, solver_batch *sb, rg_real *v, int what)
{
    resolve_task t = { sb, v, 0, what };
    for (int col = 0; col < 32; col++) {
        t.r0 = sb->cstart[col];
        task_for(w, resolve_rows, sb->cstart[col + 1] - t.r0, RESOLVE_RANGE, &t);
    }
}

void resolve_run(rg_world *w, collide_step *x)
{
    collide_world *cw = &w->coll;
    resolve_state *rs = &cw->resolve;
    solver_rows *rows = &cw->rows;
    body_store *b = &w->b;
    if (x->woke) resolve_restage(w, x);
    int32_t nc = x->nc;
    if (nc == 0) return;
    rg_real dt = x->p.dt;
    solver_constraint *con = rows->stage;
    rg_real gx, gy;
    int shock = resolve_order(w, nc, &gx, &gy);
    const int32_t *ord = rows->ord;
    int timed = continuous_time_impacts(w, x);
    /* the solver's bodies: 0 is the ground, 1..ns the awake bodies the rows meet */
    int32_t ns = x->ns;
    const int32_t *sbody = rs->sbody;
    rg_real *v = rs->sv;
    v[0] = v[1] = 0;
    for (int32_t q = 1; q <= ns; q++) {
        /* an immovable body's zero velocity as +0: the rows store it back unchanged, in
         * whatever order they run (solver.h) */
        rg_real z = b->inv_mass[sbody[q]] > 0 ? -RG_R(0.0) : 0;
        v[2 * q] = b->vx[sbody[q]] + z;
        v[2 * q + 1] = b->vy[sbody[q]] + z;
    }
    solver_batch *sb = &rows->batch;
    solver_pack(con, ord, nc, ns + 1, rs->cmask, rows->color, sb);
    resolve_wide(w, sb, v, RESOLVE_WARM);
    solver_warm_start(con, sb->over, sb->nover, v);
    for (int32_t it = 0; it < cw->iterations; it++) {
        resolve_wide(w, sb, v, RESOLVE_VELOCITY);
        solver_iterate(con, sb->over, sb->nover, v);
    }
    solver_unpack(sb, con, nc, 0);
    if (shock) solver_shock(con, ord, nc, v, gx, gy);
    solver_fixed_rows(con, nc, v, 0);
    /* positions move with the solved velocities, then by the pseudo-velocities of the
     * position pass, which leave the velocities alone.  A timed body's velocity changes at
     * its impact, t into the step; v then holds the velocity of its whole step's motion, for
     * the position pass to see where the step leaves it. */
    for (int32_t q = 1; q <= ns; q++) {
        int32_t i = sbody[q];
        rg_real dvx = v[2 * q] - b->vx[i], dvy = v[2 * q + 1] - b->vy[i];
        rg_real t = timed ? rs->stoi[q] : 0;
        if (t > 0) {
            rg_real after = 1 - t, fx = b->vx[i], fy = b->vy[i];
            b->x[i] += dvx * after * dt;
            b->y[i] += dvy * after * dt;
            b->vx[i] = v[2 * q];
            b->vy[i] = v[2 * q + 1];
            v[2 * q] = fx + dvx * after;
            v[2 * q + 1] = fy + dvy * after;
        } else {
            b->x[i] += dvx * dt;
            b->y[i] += dvy * dt;
            b->vx[i] = v[2 * q];
            b->vy[i] = v[2 * q + 1];
        }
    }
    if (cw->position > 0 && solver_prepare_position(con, nc, v, &x->p) > 0) {
        rg_real *pv = rs->spv;
        memset(pv, 0, (size_t)(2 * ns + 2) * sizeof *pv);
        solver_pack_position(sb, con, nc);
        for (int32_t it = 0; it < cw->position; it++) {
            resolve_wide(w, sb, pv, RESOLVE_POSITION);
            solver_iterate_position(con, sb->over, sb->nover, pv);
        }
        solver_unpack(sb, con, nc, 1);
        if (shock) solver_shock_position(con, ord, nc, pv, gx, gy);
        solver_fixed_rows(con, nc, pv, 1);
        rs->pv_valid = 1;
        for (int32_t q = 1; q <= ns; q++) {
            b->x[sbody[q]] += pv[2 * q] * dt;
            b->y[sbody[q]] += pv[2 * q + 1] * dt;
        }
    }
    for (int32_t k = 0; k < nc; k++) {
        contact *c = &cw->contacts.c[con[k].cid];
        c->pn = con[k].pn;
        c->pt = con[k].pt;
    }
}
