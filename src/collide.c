/* collide.c: the collide stage's settings, per-step scratch and lifetime, and its settings
 * API (solver iterations, contact tuning, continuous collision). */
#include <string.h>

#include "arg.h"
#include "bands.h"
#include "collide.h"
#include "contact.h"
#include "island.h"
#include "views.h"
#include "resolve.h"
#include "state.h"
#include "vec2.h"

void collide_init(rg_world *w)
{
    collide_world *cw = &w->coll;
    memset(cw, 0, sizeof *cw);
    contact_init(&cw->contacts);
    cw->iterations = 8;
    cw->position = 3;
    cw->sleeping = 1;
    cw->sleep_speed = RG_R(0.05);
    cw->sleep_time = RG_R(0.5);
    cw->continuous = 1;
    cw->slop = RG_R(0.005);
    cw->bias_rate = RG_R(0.2);
    cw->max_push = RG_R(2);
    cw->restitution_threshold = RG_R(1);
}

/* The per-body scratch of the stages, for cw->scap bodies. */
static void collide_layout(mem_layout *l, void *ctx)
{
    collide_world *cw = ctx;
    views_layout(l, &cw->views, cw->scap);
    cw->pairs.count = mem_take(l, (size_t)cw->scap + 1, sizeof(int32_t));
    island_layout(l, &cw->island, cw->scap);
    resolve_layout(l, &cw->resolve, cw->scap);
    cw->sweep.stop = mem_take(l, (size_t)cw->scap, sizeof(int32_t));
    cw->sweep.nx = mem_take(l, (size_t)cw->scap, sizeof(rg_real));
    cw->sweep.ny = mem_take(l, (size_t)cw->scap, sizeof(rg_real));
}

void collide_release(rg_world *w)
{
    collide_world *cw = &w->coll;
    broadphase_release(&cw->bp, &w->mem);
    contact_release(w);
    mem_free(&w->mem, cw->pairs.cand, (size_t)cw->pairs.cand_cap * sizeof *cw->pairs.cand);
    cw->pairs.cand = NULL;
    cw->pairs.cand_cap = 0;
    mem_free(&w->mem, cw->scratch, cw->scratch_size);
    cw->scratch = NULL;
    cw->scratch_size = 0;
    cw->scap = 0;
}

rg_status collide_prepare(rg_world *w)
{
    collide_world *cw = &w->coll;
    if (cw->shape_count == 0) return RG_OK;
    int32_t n = w->b.capacity + 1;
    if (cw->scap >= n) return RG_OK;
    collide_world grown = *cw;
    grown.scap = n;
    grown.scratch = mem_block(&w->mem, collide_layout, &grown, &grown.scratch_size);
    if (grown.scratch == NULL) return RG_ERR_OUT_OF_MEMORY;
    mem_free(&w->mem, cw->scratch, cw->scratch_size);
    cw->views = grown.views;
    cw->pairs.count = grown.pairs.count;
    cw->island.umin = grown.island.umin;
    cw->island.uf = grown.island.uf;
    cw->island.ihead = grown.island.ihead;
    cw->island.itail = grown.island.itail;
    cw->island.list = grown.island.list;
    cw->resolve = grown.resolve;
    cw->sweep = grown.sweep;
    cw->scratch = grown.scratch;
    cw->scratch_size = grown.scratch_size;
    cw->scap = n;
    memset(cw->resolve.sstamp, 0, (size_t)n * sizeof *cw->resolve.sstamp);
    cw->resolve.gen = 0;
    memset(cw->resolve.sband, 0, (size_t)n * BANDS_MAX);
    cw->resolve.bgen = 0;
    return RG_OK;
}

int collide_needed(const rg_world *w)
{
    const collide_world *cw = &w->coll;
    return cw->shape_count > 0 || cw->events.n_pend > 0;
}

void collide_step_begin(rg_world *w, collide_step *x, rg_real dt)
{
    collide_world *cw = &w->coll;
    cw->resolve.pv_valid = 0;
    x->n = x->nv = w->b.n_active;
    x->na = cw->bp.n_active;
    x->nc = 0;
    x->ns = x->n;
    x->nimp = 0;
    x->nblock = 0;
    x->woke = 0;
    x->sensed = 0;
    x->pressed = 0;
    x->unite = cw->sleeping && cw->island.near_sleep;
    x->late = NULL;
    x->p.dt = dt;
    x->p.inv_dt = 1 / dt;
    x->p.slop = cw->slop;
    x->p.bias_rate = cw->bias_rate;
    x->p.max_push = cw->max_push;
    x->p.restitution_threshold = cw->restitution_threshold;
    /* where the integrator's velocities sit in time (solver_vout) */
    x->p.stagger = w->integrator == RG_INTEGRATOR_SEMI_IMPLICIT_EULER ? RG_R(0.5)
                 : w->integrator == RG_INTEGRATOR_EXPLICIT_EULER     ? RG_R(-0.5)
                                                                     : 0;
    cw->offk = RG_R(0.5) - x->p.stagger;
    if (w->integrator == RG_INTEGRATOR_SEMI_IMPLICIT_EULER) cw->offk = 0;
    cw->offdt = dt;
    /* the direction the staging measures the rows' heights along (resolve.c orders them) */
    rg_real gx = w->gravity.x, gy = w->gravity.y, gl = rg_sqrt(gx * gx + gy * gy);
    x->down = gl > 0 && rg_finite(gl);
    x->ux = x->down ? gx / gl : 0;
    x->uy = x->down ? gy / gl : 0;
}

/* ---------------------------------------------------------------- API */

RG_API int32_t rg_world_touching_count(const rg_world *world)
{
    if (world == NULL) return 0;
    ERROR_CLEAR(world);
    return world->coll.contacts.n_touching;
}

RG_API rg_status rg_world_set_solver_iterations(rg_world *world, int32_t velocity, int32_t position)
{
    WORLD_WRITABLE(world);
    ARG_INT(world, velocity, 1, 64, "in 1..64");
    ARG_INT(world, position, 0, 64, "in 0..64");
    world->coll.iterations = velocity;
    world->coll.position = position;
    return RG_OK;
}

RG_API rg_status rg_world_get_solver_iterations(const rg_world *world, int32_t *out_velocity,
                                                int32_t *out_position)
{
    ERROR_BEGIN(world);
    ARG_PTR(world, out_velocity);
    ARG_PTR(world, out_position);
    *out_velocity = world->coll.iterations;
    *out_position = world->coll.position;
    return RG_OK;
}

RG_API rg_status rg_world_set_contact_tuning(rg_world *world, rg_real slop, rg_real bias_rate,
                                             rg_real max_push, rg_real restitution_threshold)
{
    WORLD_WRITABLE(world);
    ARG_IN(world, slop, 0, RG_MAX_SHAPE_SIZE);
    ARG_ABOVE(world, bias_rate, 0, 1);
    ARG_ABOVE(world, max_push, 0, RG_MAX_SPEED);
    ARG_IN(world, restitution_threshold, 0, RG_MAX_SPEED);
    collide_world *cw = &world->coll;
    cw->slop = slop;
    cw->bias_rate = bias_rate;
    cw->max_push = max_push;
    cw->restitution_threshold = restitution_threshold;
    return RG_OK;
}

RG_API rg_status rg_world_get_contact_tuning(const rg_world *world, rg_real *out_slop,
                                             rg_real *out_bias_rate, rg_real *out_max_push,
                                             rg_real *out_restitution_threshold)
{
    ERROR_BEGIN(world);
    ARG_PTR(world, out_slop);
    ARG_PTR(world, out_bias_rate);
    ARG_PTR(world, out_max_push);
    ARG_PTR(world, out_restitution_threshold);
    const collide_world *cw = &world->coll;
    *out_slop = cw->slop;
    *out_bias_rate = cw->bias_rate;
    *out_max_push = cw->max_push;
    *out_restitution_threshold = cw->restitution_threshold;
    return RG_OK;
}

RG_API rg_status rg_world_set_continuous(rg_world *world, int32_t enabled)
{
    WORLD_WRITABLE(world);
    ARG_INT(world, enabled, 0, 1, "0 or 1");
    world->coll.continuous = enabled;
    return RG_OK;
}

RG_API rg_status rg_world_get_continuous(const rg_world *world, int32_t *out_enabled)
{
    ERROR_BEGIN(world);
    ARG_PTR(world, out_enabled);
    *out_enabled = world->coll.continuous;
    return RG_OK;
}
