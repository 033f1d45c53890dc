/* speed_limits.h: the speed limits stage: min speed snaps to rest, max speed clamps. */
#ifndef RG_SPEED_LIMITS_H
#define RG_SPEED_LIMITS_H

struct rg_world;

/* After integration: |v| < min_speed -> v = 0 exactly; |v| > max_speed > 0 -> v scaled to
 * max_speed, for the active bodies that have limits (nothing when none has). */
void speed_limits_apply(struct rg_world *w);

#endif
