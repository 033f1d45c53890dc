/* pairs.h: fat boxes, the collision filter and the pair search over the broadphase.
 *
 * Every shaped body has a fat box in the broadphase (its box grown by a margin, the path of
 * its last step and a look-ahead of four steps of motion).  A body whose swept box leaves
 * its fat box gets a new one and joins the move buffer; only moved bodies query the
 * broadphase, and a query creates a contact for each new overlapping fat box that the
 * filter admits.  A contact lives while the two fat boxes overlap, so a settled pile finds
 * no pairs at all. */
#ifndef RG_PAIRS_H
#define RG_PAIRS_H

#include <stdint.h>

#include "state.h"

/* Whether dense bodies i and j may collide: the filter both ways, and at least one dynamic
 * body unless a sensor meets a kinematic body. */
static inline int pairs_admitted(const rg_world *w, int32_t i, int32_t j)
{
    const body_store *b = &w->b;
    int32_t ti = b->type[i], tj = b->type[j];
    int sensor = ((b->cflags[i] | b->cflags[j]) & CF_SENSOR) != 0;
    if (ti != RG_BODY_DYNAMIC && tj != RG_BODY_DYNAMIC) {
        if (!sensor || (ti == RG_BODY_STATIC && tj == RG_BODY_STATIC)) return 0;
    }
    return (b->cat[i] & b->mask[j]) != 0 && (b->cat[j] & b->mask[i]) != 0;
}

/* Refreshes the fat box of active body i (slot s, broadphase entry e) from its box [l, u],
 * its displacement (mx, my) and that displacement's change over the last step (ax, ay) to
 * look ahead by, and marks it moved.  pairs_refresh calls it only when the box [l, u] left
 * the fat box, or when the body's pairs are to be searched anyway (new, teleported). */
void pairs_refresh_now(struct rg_world *w, int32_t i, rg_real lx, rg_real ly, rg_real ux, rg_real uy,
                       rg_real mx, rg_real my, rg_real ax, rg_real ay);

/* Whether box (lx, ly, ux, uy) lies in entry e's fat box and e need not be searched anyway:
 * no refresh (pairs_refresh_now) is due. */
static inline int pairs_inside(const bp_entry *e, const rg_real *box)
{
    return !e->moved && box[0] >= e->lx && box[1] >= e->ly && box[2] <= e->ux && box[3] <= e->uy;
}

/* The test inline, the refresh out of line: most bodies stay inside their fat box. */
static inline void pairs_refresh(struct rg_world *w, const bp_entry *e, int32_t i, rg_real lx,
                                 rg_real ly, rg_real ux, rg_real uy, rg_real mx, rg_real my,
                                 rg_real ax, rg_real ay)
{
    const rg_real box[4] = { lx, ly, ux, uy };
    if (pairs_inside(e, box)) return;
    pairs_refresh_now(w, i, lx, ly, ux, uy, mx, my, ax, ay);
}

/* Searches the pairs of the moved bodies; returns 1 when that woke sleeping bodies. */
int pairs_find(struct rg_world *w);
/* After the solve: the fat boxes of the awake shaped bodies hold their final boxes, for
 * queries and the next step (x->na: those that were awake when the stage started). */
void pairs_refit(struct rg_world *w, const collide_step *x, rg_real dt);

/* A body's shape was just given (slot not in the broadphase yet; room reserved): its fat box
 * at rest enters the broadphase, among the moving members unless it is static. */
void pairs_insert(struct rg_world *w, int32_t slot);
/* The body in slot was placed by the API or its shape changed: its fat box becomes its box at
 * rest, its pairs are searched at the next step, and what rested on it wakes. */
void pairs_teleported(struct rg_world *w, int32_t slot);

#endif
