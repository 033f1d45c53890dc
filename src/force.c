/* force.c: the force generators: gravity, wind and applied forces (force_sum), drag and
 * surface friction, springs. */
#include <string.h>

#include "body.h"
#include "force.h"
#include "state.h"
#include "vec2.h"

void force_springs(const rg_world *w, rg_real *sax, rg_real *say)
{
    const body_store *b = &w->b;
    int32_t n = b->n_active;
    if (n > 0) {
        memset(sax, 0, (size_t)n * sizeof *sax);
        memset(say, 0, (size_t)n * sizeof *say);
    }
    for (int32_t s = 0; s < w->springs.count; s++) {
        const spring *sp = &w->springs.items[s];
        int32_t ia = body_dense(w, sp->slot_a);
        int32_t ib = sp->slot_b >= 0 ? body_dense(w, sp->slot_b) : -1;
        rg_real bx = ib >= 0 ? b->x[ib] : sp->anchor.x;
        rg_real by = ib >= 0 ? b->y[ib] : sp->anchor.y;
        rg_real bvx = ib >= 0 ? b->vx[ib] : 0;
        rg_real bvy = ib >= 0 ? b->vy[ib] : 0;
        rg_real dx = b->x[ia] - bx, dy = b->y[ia] - by;
        rg_real dvx = b->vx[ia] - bvx, dvy = b->vy[ia] - bvy;
        rg_real d2 = dx * dx + dy * dy;
        /* Hooke: F = -k (|d| - L) d/|d| = -k (1 - L/|d|) d, exactly -k d when L = 0.
         * Damping: F = -c (dv . d) d / |d|^2, the relative velocity along the spring. */
        rg_real s_k = sp->k;
        rg_real s_c = 0;
        if (d2 > 0) {
            if (sp->rest > 0) s_k = sp->k * (1 - sp->rest / rg_sqrt(d2));
            s_c = sp->c * (dvx * dx + dvy * dy) / d2;
        } else if (sp->rest > 0) {
            s_k = 0; /* no direction to push along */
        }
        rg_real fx = -(s_k + s_c) * dx, fy = -(s_k + s_c) * dy;
        if (ia < n) {
            sax[ia] += fx * b->inv_mass[ia];
            say[ia] += fy * b->inv_mass[ia];
        }
        if (ib >= 0 && ib < n) {
            sax[ib] -= fx * b->inv_mass[ib];
            say[ib] -= fy * b->inv_mass[ib];
        }
    }
}

void force_begin(rg_world *w)
{
    if (w->springs.count > 0) force_springs(w, w->scratch.sax, w->scratch.say);
}

void force_eval(rg_world *w, rg_real *ax, rg_real *ay, int springs_ready)
{
    const body_store *b = &w->b;
    int32_t n = b->n_active;
    rg_real gx = w->gravity.x, gy = w->gravity.y, wx = w->wind.x, wy = w->wind.y;
    for (int32_t i = 0; i < n; i++) {
        ax[i] = force_sum(gx, b->gscale[i], wx, b->fx[i], b->inv_mass[i]);
        ay[i] = force_sum(gy, b->gscale[i], wy, b->fy[i], b->inv_mass[i]);
    }
    if (w->dissipative_count > 0) {
        for (int32_t i = 0; i < n; i++) {
            if (!(b->flags[i] & BODY_F_DISSIPATIVE)) continue;
            rg_real vx = b->vx[i], vy = b->vy[i];
            rg_real speed = rg_sqrt(vx * vx + vy * vy);
            if (speed <= 0) continue;
            /* drag -(l + q|v|) v and friction -muN v/|v|, divided by m */
            rg_real k = (b->drag_lin[i] + b->drag_quad[i] * speed + b->fric[i] / speed) * b->inv_mass[i];
            ax[i] -= k * vx;
            ay[i] -= k * vy;
        }
    }
    if (w->springs.count > 0) {
        scratch_store *s = &w->scratch;
        if (!springs_ready) force_springs(w, s->sax, s->say);
        for (int32_t i = 0; i < n; i++) {
            ax[i] += s->sax[i];
            ay[i] += s->say[i];
        }
    }
}
