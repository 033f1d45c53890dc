/* query.h: what the mover shares with the queries. */
#ifndef RG_QUERY_H
#define RG_QUERY_H

#include <stdint.h>

#include "collision.h"

/* The time of impact of shape b moving by r against shape a, as coll_sweep, except that
 * shapes that touch at the start (depth >= 0, their boundaries meeting included) count as
 * overlapping: *t = 0 and the manifold at the start. */
int query_sweep(int32_t ka, rg_vec2 pa, rg_vec2 ha, int32_t kb, rg_vec2 pb, rg_vec2 hb, rg_vec2 r,
                rg_real *t, coll_manifold *m);

#endif
