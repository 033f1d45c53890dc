/* speed_limits.c: speed limits after integration. */
#include "speed_limits.h"
#include "vec2.h"
#include "state.h"

void speed_limits_apply(rg_world *w)
{
    body_store *b = &w->b;
    int32_t n = b->n_active;
    if (w->limit_count == 0) return;
    for (int32_t i = 0; i < n; i++) {
        if (!(b->flags[i] & BODY_F_LIMITED)) continue;
        rg_real vx = b->vx[i], vy = b->vy[i];
        rg_real s2 = vx * vx + vy * vy;
        rg_real lo = b->min_speed[i], hi = b->max_speed[i];
        if (s2 < lo * lo) {
            b->vx[i] = 0;
            b->vy[i] = 0;
        } else if (hi > 0 && s2 > hi * hi) {
            rg_real k = hi / rg_sqrt(s2);
            b->vx[i] = vx * k;
            b->vy[i] = vy * k;
        }
    }
}
