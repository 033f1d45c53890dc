/* spring.h: spring storage (damped springs between two bodies or a body and a point) and
 * what the body API needs of it.  The force springs apply is in force.c. */
#ifndef RG_SPRING_H
#define RG_SPRING_H

#include <stdint.h>

#include "state.h"


struct rg_world;

/* Room for n springs; all-or-nothing. */
rg_status spring_reserve(struct rg_world *w, int32_t n);
/* Destroys the springs attached to body slot `slot`, waking the bodies at their other ends. */
void spring_detach_body(struct rg_world *w, int32_t slot);
void spring_release(struct rg_world *w);

#endif
