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

/* BODY_GET for a call that changes the world: RG_ERR_LOCKED inside a step's callback. */
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
/* The BODY_F_COUNTED flags dense index i's settings give it. */
static inline uint32_t body_flags_of(const body_store *b, int32_t i)
{
    uint32_t f = 0;
    if (b->type[i] == RG_BODY_DYNAMIC) {
        if (b->drag_lin[i] > 0 || b->drag_quad[i] > 0 || b->fric[i] > 0) f |= BODY_F_DISSIPATIVE;
        if (b->drag_quad[i] > 0 || b->fric[i] > 0) f |= BODY_F_MAGNITUDE;
        if (b->min_speed[i] > 0 || b->max_speed[i] > 0) f |= BODY_F_LIMITED;
    }
    if (b->type[i] != RG_BODY_STATIC && b->gscale[i] != 1) f |= BODY_F_GSCALE;
    return f;
}
/* Recomputes BODY_F_COUNTED of dense index i and the world's counts. */
void body_update_flags(struct rg_world *w, int32_t i);

#endif
