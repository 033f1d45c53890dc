/* collide.h: the state of the collide stage, shared by its modules: pairs.c (fat boxes and
 * the pair search), narrow.c (manifolds, touching, grounded), resolve.c (the solve driver),
 * continuous.c (timed impacts and the post-solve sweep), island.c (islands and sleeping),
 * contact.c and events.c (storage); collide.c holds its settings, scratch and lifetime.
 *
 * Who pays: only bodies with a shape are in the broadphase, and only the awake ones among
 * them (the broadphase's active list) are visited per step; static and sleeping bodies and
 * bodies without shapes cost nothing.  A world with no shape skips the stage.
 *
 * The stage, step by step (step.c calls them in this order):
 *   narrow_record_start  before integration: where the awake shaped bodies start
 *   narrow_views         the step's view of each (displacement, velocity, size); fat boxes
 *   pairs_find           new pairs for the bodies that left their fat boxes
 *   narrow_run           manifolds, touching and events, grounded flags, solver rows
 *   resolve_run          the solve, timed impacts (continuous_time_impacts)
 *   continuous_sweep     the post-solve safety net
 *   pairs_refit          fat boxes hold the final boxes
 *   island_sleep         islands at rest fall asleep */
#ifndef RG_COLLIDE_H
#define RG_COLLIDE_H

#include <stdint.h>

#include "broadphase.h"
#include "contact.h"
#include "events.h"
#include "rigid.h"
#include "solver.h"

/* The step's view of a body, cached once per step for the awake ones (one cache line's worth
 * for the narrowphase instead of a dozen arrays). */
typedef struct cbody {
    rg_real sx, sy;   /* position at the start of the step, m */
    rg_real dx, dy;   /* displacement of the integration, m */
    rg_real vx, vy;   /* velocity at the start of the step, m/s */
    rg_real hx, hy;   /* half extents, m */
    rg_real gs;       /* gravity scale (0 unless dynamic) */
    rg_real im;       /* inverse mass (0 unless dynamic) */
    int32_t kind;     /* RG_SHAPE_* */
    int32_t pad;
} cbody;

/* Per-body scratch, body capacity + 1, indexed by place in the broadphase's active list (k),
 * by dense body index (i) or by solver body (q). */
typedef struct narrow_state {
    cbody *cb;                /* i: the step's view of the awake shaped bodies */
    rg_real *sx0, *sy0;       /* k: positions before integration */
    rg_real *svx0, *svy0;     /* k: velocities before integration */
    int32_t *adense;          /* k: dense index during the step */
} narrow_state;

typedef struct island_state {
    rg_real *umin;            /* k: island minimum rest time */
    int32_t *uf;              /* k: union-find parents */
    int32_t *ihead, *itail;   /* k: island member lists while falling asleep */
    int32_t *list;            /* slots of bodies falling asleep */
    int32_t near_sleep;       /* a body will reach sleep_time within two steps */
} island_state;

typedef struct resolve_state {
    int32_t *sidx;            /* i: solver index, valid when sstamp[i] == gen */
    uint32_t *sstamp;         /* i */
    uint32_t gen;             /* solver index generation (one per step, or more) */
    int32_t *sbody;           /* q: dense index of solver body q (q >= 1; 0 is the ground) */
    rg_real *sv;              /* q: solver velocities, pairs */
    rg_real *spv;             /* q: pseudo-velocities of the position pass, pairs */
    rg_real *stoi;            /* q: fraction of the step at which its velocity changes */
    int32_t pv_valid;         /* spv holds this step's position pass */
    uint32_t *cmask;          /* q: colouring, the colours each body is in */
} resolve_state;

typedef struct collide_world {
    broadphase bp;
    contact_store contacts;
    event_store events;
    solver_rows rows;         /* sized with the contacts */

    narrow_state narrow;      /* the per-body scratch, one block of scap bodies */
    island_state island;
    resolve_state resolve;
    void *scratch;
    size_t scratch_size;
    int32_t scap;

    /* what the scene uses */
    int32_t shape_count;

    /* settings */
    int32_t iterations, position;
    int32_t sleeping;
    rg_real sleep_speed, sleep_time;
    int32_t continuous;
    rg_real slop, bias_rate, max_push, restitution_threshold;
} collide_world;

/* What one step's collide stage hands from module to module: solver rows staged by the
 * narrowphase in contact order with their sort keys, and what it woke. */
typedef struct collide_step {
    int32_t n;          /* active bodies when the stage started (those with a body view) */
    int32_t na;         /* awake shaped bodies then (the island list's range) */
    int32_t nc;         /* staged rows */
    int32_t ns;         /* solver bodies, 0 being the ground */
    int32_t nimp;       /* staged impact rows (rows.imp) */
    int woke;           /* the pair search or the narrowphase woke bodies: rows restaged */
    int unite;          /* join islands in the narrowphase (sleeping is near) */
    solver_params p;
} collide_step;

struct rg_world;

void collide_init(struct rg_world *w);
void collide_release(struct rg_world *w);
/* Scratch a step needs; call before anything changes. */
rg_status collide_prepare(struct rg_world *w);
/* Whether the step must run the collide stage (shapes, or ended contacts to report). */
int collide_needed(const struct rg_world *w);
/* The step's solver parameters and counters, before narrow_views. */
void collide_step_begin(struct rg_world *w, collide_step *x, rg_real dt);

#endif
