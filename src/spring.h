/* spring.h: spring storage (damped springs between two bodies or a body and a point) and
 * what the body API needs of it.  The force springs apply is in force.c. */
#ifndef RG_SPRING_H
#define RG_SPRING_H

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

/* Destroys the springs attached to body slot `slot`. */
void spring_detach_body(struct rg_world *w, int32_t slot);
void spring_release(struct rg_world *w);

#endif
