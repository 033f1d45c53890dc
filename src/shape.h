/* shape.h: a body's shape and collision properties, and what the body API needs of them. */
#ifndef RG_SHAPE_H
#define RG_SHAPE_H

#include <stdint.h>

struct rg_world;

/* The body in slot goes away: its contacts end (reported with the next step), what rested
 * on it wakes, and its shape leaves the broadphase.  No effect without a shape. */
void shape_remove(struct rg_world *w, int32_t slot);

#endif
