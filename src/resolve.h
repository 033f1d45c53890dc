/* resolve.h: the solve driver: rows staged by the narrowphase, ordered bottom-up along
 * gravity (a radix sort of the contact heights) and handed to the solver (solver.h) in
 * lanes; timed impacts (continuous.h); the solved velocities and the position pass applied
 * to the bodies; the impulses kept on the contacts for the next step's warm start. */
#ifndef RG_RESOLVE_H
#define RG_RESOLVE_H

#include <stdint.h>

#include "collide.h"
#include "mem.h"

struct rg_world;

/* The solver scratch arrays for n bodies. */
void resolve_layout(mem_layout *l, resolve_state *s, int32_t n);
/* A new generation of solver indices (the stamps of the old one no longer match). */
void resolve_next_gen(resolve_state *s, int32_t n);
/* Stages the row of contact id (its normal, point, s0, vn0, toi and flags set for this step)
 * between dense bodies ia and ib of inverse masses ima, imb (ima + imb > 0). */
void resolve_stage(struct rg_world *w, collide_step *x, int32_t id, int32_t ia, int32_t ib,
                   rg_real ima, rg_real imb);
/* Solves the staged rows (restaged first when bodies woke) and moves the bodies. */
void resolve_run(struct rg_world *w, collide_step *x);

#endif
