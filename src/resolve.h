/* resolve.h: the solve driver: rows staged by the narrowphase, ordered bottom-up along
 * gravity (a radix sort of the contact heights, or the last step's order repaired) and
 * handed to the solver (solver.h) in lanes; timed impacts (continuous.h); the solved
 * velocities and the position pass applied to the bodies; the impulses kept on the contacts
 * for the next step's warm start. */
#ifndef RG_RESOLVE_H
#define RG_RESOLVE_H

#include <stdint.h>

#include "state.h"

/* The solver scratch arrays for n bodies. */
void resolve_layout(mem_layout *l, resolve_state *s, int32_t n);
/* A new generation of stamps (the old one's no longer match). */
void resolve_next_gen(resolve_state *s, int32_t n);
/* Solver index of dense body i: the ground (0) unless it is awake (dense below n, the awake
 * count when the stage began), then i + 1.  It depends on the body alone, so rows are staged
 * in any order, in parallel (narrow.c); the solve's passes skip the bodies no row meets
 * (resolve_run stamps them). */
static inline int32_t resolve_index(int32_t i, int32_t n) { return i < n ? i + 1 : 0; }

/* Stages the next row of d: contact id's (its normal, point, s0, vn0, toi and flags set for
 * this step) between dense bodies ia and ib of inverse masses ima, imb (ima + imb > 0), and
 * lists it as an impact when toi > 0. */
static inline void resolve_stage(const rg_world *w, const collide_step *x, const solver_dest *d, int32_t id,
                                 int32_t ia, int32_t ib, rg_real ima, rg_real imb)
{
    const contact *c = &w->coll.contacts.c[id];
    int32_t k = (*d->nc)++;
    solver_constraint *q = &d->stage[k];
    d->hgt[k] = -(c->px * x->ux + c->py * x->uy); /* the height along gravity (0 without) */
    q->a = resolve_index(ia, x->n);
    q->b = resolve_index(ib, x->n);
    q->ima = ima;
    q->imb = imb;
    q->nx = c->nx;
    q->ny = c->ny;
    q->m = 1 / (ima + imb);
    q->mu = c->mu;
    q->s0 = c->s0;
    q->vmin = solver_vmin(c->s0, c->vn0, c->e, (c->flags & CT_CLOSING) != 0, &x->p);
    q->toi = c->toi;
    q->pn = c->pn;
    q->pt = c->pt;
    q->cid = id;
    solver_row_bodies(q, d->ab + 2 * (size_t)k);
    if (c->toi > 0) d->imp[(*d->nimp)++] = k;
}

/* The step's own rows as a destination: staged at x->nc. */
static inline solver_dest resolve_rows_dest(solver_rows *rows, collide_step *x)
{
    solver_dest d = {rows->stage, rows->hgt, rows->ab, rows->imp, &x->nc, &x->nimp};
    return d;
}

#ifdef RG_STEP_PROFILE
/* The step's timers of the solve's parts on one thread (step.h): the order by height, the
 * colouring, the shock sweeps, in seconds since the last report. */
extern double step_prof_solve[3];
#endif

/* Solves the staged rows (restaged first when bodies woke) and moves the bodies. */
void resolve_run(struct rg_world *w, collide_step *x);

#endif
