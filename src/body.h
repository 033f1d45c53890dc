/* body.h: body storage: the dense structure of arrays, its partitions, and the one lookup
 * from handle to dense index.  Storage is used by the stages and the API; it calls none of
 * them. */
#ifndef RG_BODY_H
#define RG_BODY_H

#include <stdint.h>

#include "mem.h"
#include "rigid.h"

/* Every per-body array, in one list, so that growing, swapping and moving a body between
 * partitions is written once.  All arrays live in one block, so growth is all-or-nothing. */
#define RG_BODY_FIELDS(X)                                                              \
    X(rg_real, x) X(rg_real, y)          /* position, m */                             \
    X(rg_real, vx) X(rg_real, vy)        /* velocity, m/s */                           \
    X(rg_real, fx) X(rg_real, fy)        /* applied force for the next step, N */      \
    X(rg_real, ax) X(rg_real, ay)        /* acceleration at the start of the last step */ \
    X(rg_real, px) X(rg_real, py)        /* position before the last advance step */   \
    X(rg_real, mass) X(rg_real, inv_mass) /* kg, 1/kg; 0 for static and kinematic */   \
    X(rg_real, gscale)                   /* gravity scale; 0 for non-dynamic */        \
    X(rg_real, drag_lin)                 /* kg/s */                                    \
    X(rg_real, drag_quad)                /* kg/m */                                    \
    X(rg_real, fric)                     /* mu * normal force, N */                    \
    X(rg_real, min_speed) X(rg_real, max_speed) /* m/s; max 0 = none */                \
    X(uint64_t, user)                    /* caller's data */                           \
    X(int32_t, slot)                     /* pool slot of the body in this dense place */ \
    X(int32_t, type)                     /* RG_BODY_* */                               \
    X(uint32_t, flags)                   /* BODY_F_* */                                \
    /* collision (shape.c, pairs.c, narrow.c, island.c) */                             \
    X(int32_t, shape)                    /* RG_SHAPE_* */                              \
    X(rg_real, hx) X(rg_real, hy)        /* half extents, m ((r, r) for a circle) */   \
    X(rg_real, rest) X(rg_real, mu)      /* restitution, contact friction */           \
    X(uint32_t, cat) X(uint32_t, mask)   /* collision filter */                        \
    X(uint32_t, cflags)                  /* CF_* */                                    \
    X(int32_t, chead)                    /* first contact id + 1; 0: none */           \
    X(rg_real, dx) X(rg_real, dy)        /* displacement of the last integration, m */ \
    X(rg_real, sleep_t)                  /* s spent below the sleep speed */           \
    X(int32_t, isl_head) X(int32_t, isl_next) /* sleeping island list: slot + 1 */

#define BODY_F_DISSIPATIVE 1u /* has drag or surface friction (and is dynamic) */
#define BODY_F_LIMITED     2u /* has a speed limit (and is dynamic) */

/* cflags: collision state of a body */
#define CF_SENSOR     1u
#define CF_GROUNDED   2u
#define CF_TELEPORTED 4u /* placed by the API since its last pair search */

/* Dense order is partitioned: [0, n_active) moving and awake (dynamic and kinematic),
 * [n_active, n_moving) asleep, [n_moving, count) static.  Every stage loops over the
 * partition it needs, so static and sleeping bodies cost nothing per step. */
enum { BODY_PART_ACTIVE = 0, BODY_PART_ASLEEP = 1, BODY_PART_STATIC = 2 };

typedef struct body_store {
#define RG_FIELD_PTR(T, name) T *name;
    RG_BODY_FIELDS(RG_FIELD_PTR)
#undef RG_FIELD_PTR
    void *block;
    size_t block_size;
    int32_t count;
    int32_t capacity;
    int32_t n_active;
    int32_t n_moving;
} body_store;

/* Integrator scratch arrays (same capacity as the bodies). */
#define RG_SCRATCH_FIELDS(X) \
    X(rg_real, x0) X(rg_real, y0) X(rg_real, vx0) X(rg_real, vy0) \
    X(rg_real, kx) X(rg_real, ky) X(rg_real, kvx) X(rg_real, kvy) \
    X(rg_real, vfx) X(rg_real, vfy) X(rg_real, sax) X(rg_real, say) \
    X(rg_real, tax) X(rg_real, tay) X(int32_t, implicit)

typedef struct scratch_store {
#define RG_FIELD_PTR(T, name) T *name;
    RG_SCRATCH_FIELDS(RG_FIELD_PTR)
#undef RG_FIELD_PTR
    void *block;
    size_t block_size;
    int32_t capacity;
} scratch_store;

/* Defaults of a new body's collision fields (shape.c documents them). */
#define BODY_DEFAULT_FRICTION ((rg_real)0.6)
#define BODY_DEFAULT_CATEGORY 1u
#define BODY_DEFAULT_MASK     0xFFFFFFFFu

struct rg_world;

/* Dense index of a live body of this world, or -1: the one place handles are checked. */
int32_t body_lookup(const struct rg_world *w, rg_body body);
/* body_dense(w, slot) (world.h, inline): the dense index of the live body in pool slot
 * `slot`.  Slots never move; dense indices move whenever a body changes partition (falls
 * asleep, wakes, is created or destroyed), so code that keeps a body across such a change
 * keeps its slot. */

/* Looks up `body` at the top of an API call: declares the dense index `i`, or returns
 * RG_ERR_INVALID_ARGUMENT (NULL world) or RG_ERR_STALE_HANDLE. */
#define BODY_GET(world, body, i)                               \
    if ((world) == NULL) return RG_ERR_INVALID_ARGUMENT;       \
    int32_t i = body_lookup((world), (body));                  \
    if (i < 0) return RG_ERR_STALE_HANDLE

/* Grows storage so one more body fits; all-or-nothing. */
rg_status body_reserve(struct rg_world *w);
/* A new body (after a successful body_reserve) of a valid type, mass and position, placed in
 * its partition, every field at its default; returns its handle. */
rg_body body_add(struct rg_world *w, int32_t type, rg_real mass, rg_vec2 position);
/* Drops the live body `body` (its contacts, shape and springs already gone). */
void body_remove(struct rg_world *w, rg_body body);
/* Ensures the integrator scratch covers the body capacity; all-or-nothing. */
rg_status body_scratch_reserve(struct rg_world *w);
void body_store_release(struct rg_world *w);
/* Partition of dense index i. */
int body_partition(const struct rg_world *w, int32_t i);
/* Moves the body at dense index i into partition part; returns its new dense index. */
int32_t body_move_to_partition(struct rg_world *w, int32_t i, int part);
/* Recomputes BODY_F_* of dense index i and the world's counts. */
void body_update_flags(struct rg_world *w, int32_t i);

#endif
