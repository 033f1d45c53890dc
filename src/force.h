/* force.h: force generators (gravity, wind, applied, drag, surface friction, springs) as
 * functions of the state, so multi-stage integrators evaluate them at every stage. */
#ifndef RG_FORCE_H
#define RG_FORCE_H

#include <stdint.h>

#include "pool.h"
#include "rigid.h"

typedef struct spring {
    int32_t slot_a;     /* body pool slot of a */
    int32_t slot_b;     /* body pool slot of b, -1 when tied to the anchor */
    int32_t self_slot;  /* this spring's pool slot */
    rg_vec2 anchor;     /* m, world point when slot_b < 0 */
    rg_real rest;       /* m */
    rg_real k;          /* N/m */
    rg_real c;          /* N*s/m */
} spring;

typedef struct spring_store {
    pool pool;
    spring *items;      /* dense */
    int32_t count;
    int32_t capacity;
} spring_store;

struct rg_world;

/* Spring accelerations at the current state (b.x, b.y, b.vx, b.vy) into sax, say for the
 * active bodies [0, n_active); other bodies feel nothing. */
void force_springs(const struct rg_world *w, rg_real *sax, rg_real *say);
/* Total acceleration at the current state into ax, ay for [0, n_active):
 * gravity*scale + (wind + applied)/m + drag + surface friction + springs. */
void force_eval(struct rg_world *w, rg_real *ax, rg_real *ay);
/* Destroys the springs attached to body slot `slot`. */
void force_detach_body(struct rg_world *w, int32_t slot);
void force_release(struct rg_world *w);

#endif
