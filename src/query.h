/* query.h: what the mover and the other handle lists share with the queries. */
#ifndef RG_QUERY_H
#define RG_QUERY_H

#include <stdint.h>

#include "collision.h"
#include "rigid.h"

/* A list call's output: the `cap` smallest handles counted so far, kept as a max-heap in
 * out[0, min(count, cap)) while the list is built. */
typedef struct query_handles {
    rg_body *out;
    int32_t cap, count;
} query_handles;

/* Counts handle h and keeps it if it is among the cap smallest so far. */
void query_keep(query_handles *q, rg_body h);
/* The kept handles in ascending order; returns the count. */
int32_t query_sorted(query_handles *q);

/* Sets *h to a hit, every byte of it: its pad and the padding after it (the double build's)
 * 0, so that no stack byte reaches the caller and equal hits are equal bytes. */
void query_hit(rg_ray_hit *h, rg_body body, rg_vec2 point, rg_vec2 normal, rg_real fraction);

/* The time of impact of shape b moving by r against shape a, as coll_sweep, except that
 * shapes that touch at the start (depth >= 0, their boundaries meeting included) count as
 * overlapping: *t = 0 and the manifold at the start. */
int query_sweep(int32_t ka, rg_vec2 pa, rg_vec2 ha, int32_t kb, rg_vec2 pb, rg_vec2 hb, rg_vec2 r,
                rg_real *t, coll_manifold *m);

#endif
