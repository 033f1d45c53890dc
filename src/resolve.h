/* resolve.h: the solve driver: rows staged by the narrowphase, ordered bottom-up along
 * gravity (a radix sort of the contact heights) and handed to the solver (solver.h) in
 * lanes; timed impacts (continuous.h); the solved velocities and the position pass applied
 * to the bodies; the impulses kept on the contacts for the next step's warm start. */
#ifndef RG_RESOLVE_H
#define RG_RESOLVE_H

#include <stdint.h>

#include "state.h"

/* The solver scratch arrays for n bodies. */
void resolve_layout(mem_layout *l, resolve_state *s, int32_t n);
/* A new generation of solver indices (the stamps of the old one no longer match). */
void resolve_next_gen(resolve_state *s, int32_t n);
/* Stages the row of contact id (its normal, point, s0, vn0, toi and flags set for this step)
 * between dense bodies ia and ib of inverse masses ima, imb (ima + imb > 0); inline, for the
 * narrowphase stages most rows. */
/* Solver index of dense body i (for resolve_stage): the ground (0) unless it is awake; awake bodies get
 * consecutive indices in the order rows meet them, so the solver's arrays cover the bodies
 * in contact and nothing else. */
static inline int32_t resolve_index(resolve_state *rs, int32_t i, int32_t n, collide_step *x)
{
    if (i >= n) return 0;
    if (rs->sstamp[i] != rs->gen) {
        rs->sstamp[i] = rs->gen;
        rs->sidx[i] = ++x->ns;
        rs->sbody[x->ns] = i;
    }
    return rs->sidx[i];
}

static inline void resolve_stage(rg_world *w, collide_step *x, int32_t id, int32_t ia, int32_t ib,
                                 rg_real ima, rg_real imb)
{
    collide_world *cw = &w->coll;
    solver_rows *rows = &cw->rows;
    const contact *c = &cw->contacts.c[id];
    int32_t k = x->nc++;
    solver_constraint *q = &rows->stage[k];
    rows->hgt[k] = c->py; /* replaced by the height along gravity */
    rows->hgx[k] = c->px;
    q->a = resolve_index(&cw->resolve, ia, x->n, x);
    q->b = resolve_index(&cw->resolve, ib, x->n, x);
    q->ima = ima;
    q->imb = imb;
    q->nx = c->nx;
    q->ny = c->ny;
    q->m = 1 / (ima + imb);
    q->mu = c->mu;
    q->s0 = c->s0;
    q->vmin = solver_vmin(c->s0, c->vn0, c->e, (c->flags & CT_CLOSING) != 0, &x->p);
    q->toi = c->toi;
    if (q->toi > 0) rows->imp[x->nimp++] = k;
    q->pn = c->pn;
    q->pt = c->pt;
    q->cid = id;
}

/* Solves the staged rows (restaged first when bodies woke) and moves the bodies. */
void resolve_run(struct rg_world *w, collide_step *x);

#endif
