/* body.h: body storage: the dense structure of arrays, its partitions, and the one lookup
 * from handle to dense index.  Storage is used by the stages and the API; it calls none of
 * them. */
#ifndef RG_BODY_H
#define RG_BODY_H

#include <stdint.h>

#include "arg.h"
#include "state.h"



struct rg_world;

/* Dense index of a live body of this world, or -1: the one place handles are checked. */
int32_t body_lookup(const struct rg_world *w, rg_body body);
/* body_dense(w, slot) (state.h, inline): the dense index of the live body in pool slot. */

/* Declares the dense index `i` of `body` in an entry point that opened the world
 * (ERROR_BEGIN or WORLD_WRITABLE), or returns RG_ERR_STALE_HANDLE, the error naming it. */
#define BODY_LOOKUP(world, body, i)                                                 \
    int32_t i = arg_handle((world), __func__, #body, &(world)->body_pool, (body));  \
    if (i < 0) return RG_ERR_STALE_HANDLE

/* Looks up `body` at the top of an API call: declares the dense index `i`, or returns
 * RG_ERR_INVALID_ARGUMENT (NULL world) or RG_ERR_STALE_HANDLE. */
#define BODY_GET(world, body, i) \
    ERROR_BEGIN(world);          \
    BODY_LOOKUP(world, body, i)

/* BODY_GET for a call that changes the world: RG_ERR_LOCKED inside one of its callbacks. */
#define BODY_SET(world, body, i) \
    WORLD_WRITABLE(world);       \
    BODY_LOOKUP(world, body, i)

/* Grows storage so one more body fits; all-or-nothing. */
rg_status body_reserve(struct rg_world *w);
/* Grows storage so n bodies fit (restoring a snapshot); all-or-nothing. */
rg_status body_reserve_count(struct rg_world *w, int32_t n);
/* A new body (after a successful body_reserve) of a valid type, mass and position, placed in
 * its partition, every field at its default; returns its handle. */
rg_body body_add(struct rg_world *w, int32_t type, rg_real mass, rg_vec2 position);
/* Drops the live body `body` (its contacts, shape and springs already gone). */
void body_remove(struct rg_world *w, rg_body body);
/* Ensures the integrator scratch covers the body capacity; all-or-nothing. */
rg_status body_scratch_reserve(struct rg_world *w);
void body_store_release(struct rg_world *w);
/* Moves the body at dense index i into partition part; returns its new dense index. */
int32_t body_move_to_partition(struct rg_world *w, int32_t i, int part);
/* The BODY_F_COUNTED flags a body's settings give it; without branches (a restore computes
 * them for every body, in loops the compiler vectorises). */
static inline uint32_t body_flags_from(int32_t type, rg_real drag_lin, rg_real drag_quad, rg_real fric,
                                       rg_real min_speed, rg_real max_speed, rg_real gscale)
{
    uint32_t dynamic = type == RG_BODY_DYNAMIC, moving = type != RG_BODY_STATIC;
    uint32_t magnitude = (drag_quad > 0) | (fric > 0), dissipative = magnitude | (drag_lin > 0);
    uint32_t limited = (min_speed > 0) | (max_speed > 0);
    return (dynamic & dissipative) * BODY_F_DISSIPATIVE | (dynamic & magnitude) * BODY_F_MAGNITUDE |
           (dynamic & limited) * BODY_F_LIMITED | (moving & (gscale != 1)) * BODY_F_GSCALE;
}
/* Those of dense index i. */
static inline uint32_t body_flags_of(const body_store *b, int32_t i)
{
    return body_flags_from(b->type[i], b->drag_lin[i], b->drag_quad[i], b->fric[i], b->min_speed[i], b->max_speed[i],
                           b->gscale[i]);
}
/* Recomputes BODY_F_COUNTED of dense index i and the world's counts. */
void body_update_flags(struct rg_world *w, int32_t i);

#endif
