/* state.h: the state of a world: struct rg_world and the structures of every module it
 * holds, in one place so that no module's header depends on another's.  Data only (and the
 * inline slot-to-index lookup); the functions that work on it are declared by the modules'
 * own headers. */
#ifndef RG_STATE_H
#define RG_STATE_H

#include <stdint.h>

#include "broadphase.h"
#include "error.h"
#include "mem.h"
#include "own.h"
#include "pool.h"
#include "rigid.h"
#include "solver.h"

/* ---------------------------------------------------------------- bodies (body.c) */

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
    X(int32_t, isl_head) X(int32_t, isl_next) /* sleeping island list: slot + 1 */    \
    X(rg_real, owx) X(rg_real, owy)      /* one-way normal; (0, 0): two-way */

#define BODY_F_DISSIPATIVE 1u /* has drag or surface friction (and is dynamic) */
#define BODY_F_LIMITED     2u /* has a speed limit (and is dynamic) */
#define BODY_F_STOPPED     4u /* the last stepping call stopped it at the range's edge (bounds.c) */
#define BODY_F_MAGNITUDE   8u /* has quadratic drag or surface friction (and is dynamic) */
#define BODY_F_GSCALE     16u /* moves (dynamic or kinematic) with a gravity scale other than 1 */
/* the flags a body's settings give it (body_flags_of), the rest are the step's */
#define BODY_F_COUNTED (BODY_F_DISSIPATIVE | BODY_F_LIMITED | BODY_F_MAGNITUDE | BODY_F_GSCALE)

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

/* ---------------------------------------------------------------- springs (spring.c) */

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

/* ---------------------------------------------------------------- contacts (contact.c)
 *
 * Persistent contacts between pairs of bodies whose fat boxes overlap.  Contacts are
 * identified by an id into `c`; the awake ones (at least one body awake) are listed in
 * `awake`, in a deterministic order; each body heads a doubly linked list of its contacts
 * (`chead` in the body fields, id + 1). */

/* contact flags */
#define CT_TOUCHING 1u
#define CT_SENSOR   2u
#define CT_SOLVE    4u  /* solved in this step */
#define CT_CLOSING  8u  /* the step's free motion would make the pair overlap */
#define CT_ONEWAY  16u  /* a body of the pair is one-way (narrow.c decides when it blocks) */
#define CT_PASS    32u  /* passing: neither solved nor touching until a step ends apart */
#define CT_ACTIVE  64u  /* scratch within the narrowphase: the pair meets within the step (narrow.c) */
#define CT_PRESSED 128u /* scratch from the solve's keep pass to narrow_press: apart, pressed together */
#define CT_SKIPPED 256u /* scratch from the narrowphase to the post-solve sweep: the pre-solve hook
                         * skipped the pair this step (narrow_unskip clears it) */
/* A pair is solved when its free motion over the step leaves it less than SPECULATIVE * slop
 * apart (narrow.c); a body the solve moves further than that off its free motion may meet a
 * pair that was not (continuous.c's sweep). */
#define SPECULATIVE RG_R(4)

/* The accumulated impulses a contact keeps for the next step's warm start stay within
 * [0, CONTACT_MAX_IMPULSE] (normal) and +-CONTACT_MAX_IMPULSE (friction), N*s: the solve
 * stores them clamped (resolve.c), and a snapshot beyond them is refused (restore_check.c).
 * The bound is far above the impulses of game scenes (the heaviest body stopped from the
 * highest speed takes 2e15 N*s; only a tall stack of the heaviest bodies under the strongest
 * gravity could need more, and there the clamp weakens the warm start, never the step's
 * finiteness), and low enough that the warm start of the lightest body and the solve's
 * products stay finite in float (1e20 N*s on 1e-6 kg is 1e26 m/s, times the largest
 * effective mass 1e9 kg is 1e35). */
#define CONTACT_MAX_IMPULSE RG_R(1e20)

typedef struct contact {
    int32_t sa, sb;           /* body slots; a has the lower handle; -1 when the id is free */
    int32_t na, pa, nb, pb;   /* next/prev contact ids in a's and b's lists (-1 ends) */
    int32_t awake;            /* index in awake[], -1 while both bodies rest */
    uint32_t flags;           /* CT_* */
    rg_real mu, e;            /* mixed friction and restitution */
    rg_real nx, ny;           /* last normal, from a to b */
    rg_real px, py;           /* last contact point, m */
    rg_real s0;               /* last start separation, m */
    rg_real vn0;              /* last relative normal velocity at the start of the step, m/s */
    rg_real depth, speed;     /* at the begin, for the events */
    rg_real pn, pt;           /* accumulated impulses, N*s (warm start) */
    rg_real toi;              /* its solver row's toi (solver.h) */
    uint32_t decided;         /* scratch within the narrowphase: what it decided (narrow.c) */
} contact;

typedef struct contact_store {
    contact *c;               /* [0, cap) by id */
    int32_t cap, live, free_head;
    int32_t *awake;           /* ids of awake contacts, [0, n_awake) */
    int32_t n_awake;
    int32_t n_touching;       /* contacts with CT_TOUCHING */
} contact_store;

/* ---------------------------------------------------------------- events (events.c) */

typedef struct event_store {
    rg_contact_event *ev;     /* events of the last step, or of every step of the last advance */
    int32_t n, cap;           /* held, room (>= base + EVENTS_PER_STEP(contacts) in a step) */
    int32_t base;             /* where the current step's events start */
    rg_contact_event *pend;   /* ends between steps, reported with the next step */
    int32_t n_pend, pend_cap; /* pend_cap: the contact capacity (one end per contact at most) */
    int32_t in_step;
} event_store;

/* ---------------------------------------------------------------- the collide stage (collide.h) */

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
typedef struct views_state {
    cbody *cb;                /* i: the step's view of the awake shaped bodies */
    rg_real *sx0, *sy0;       /* k: positions before integration */
    rg_real *svx0, *svy0;     /* k: velocities before integration */
    int32_t *adense;          /* k: dense index during the step */
    uint8_t *refresh;         /* k: the fat box must be refreshed (views_build) */
} views_state;

/* The parallel pair search's candidates (pairs.c): count per moved body (scap + 1, in the
 * scratch block), cand grown as needed and kept. */
typedef struct pairs_state {
    int32_t *count;
    int32_t *cand;
    int32_t cand_cap;
} pairs_state;

typedef struct island_state {
    rg_real *umin;            /* k: island minimum rest time */
    int32_t *uf;              /* k: union-find parents */
    int32_t *ihead, *itail;   /* k: island member lists while falling asleep */
    int32_t *list;            /* slots of bodies falling asleep */
    int32_t near_sleep;       /* a body will reach sleep_time within two steps */
} island_state;

/* The solver's bodies: q = 0 is the ground, q = i + 1 awake body i (resolve_index). */
typedef struct resolve_state {
    uint32_t *sstamp;         /* i: == gen when a row of this step meets awake body i */
    uint32_t gen;             /* stamp generation (one per solve) */
    rg_real *sv;              /* q: solver velocities, pairs */
    rg_real *spv;             /* q: pseudo-velocities of the position pass, pairs */
    rg_real *stoi;            /* q: fraction of the step at which its velocity changes */
    uint8_t *spush;           /* q: the rows that push it (pn > 0) in this solve, or whose
                                 normal the integrator's term o goes along into the other
                                 body: (& 3) 0 none, 1 along one normal (spn), 2 along
                                 several or held by friction; 4: o goes into one; 8: an
                                 impact row without a bounce (vmin 0) meets it; written
                                 for the bodies the rows meet, under the integrators other
                                 than semi-implicit Euler only (resolve.c) */
    rg_real *spn;             /* q: that normal, pairs */
    int32_t pv_valid;         /* spv holds this step's position pass */
    uint32_t *cmask;          /* q: colouring, the colours each body is in */
    int32_t *sbody;           /* the solver bodies the rows meet, each once (stamping order),
                                 listed where the rows are few (resolve.c) */
    uint8_t *sband;           /* q * BANDS_MAX + b: == bgen when band b's rows meet q */
    uint8_t bgen;             /* their generation (one per solve in bands) */
    int64_t banded;           /* solves whose colours ran in bands (test_bands.c reads it) */
} resolve_state;

/* The post-solve sweep's stops at sleeping bodies (continuous.c), k: the slot of the one a
 * body stopped at (-1: none) and the normal from it toward the body. */
typedef struct sweep_state {
    int32_t *stop;
    rg_real *nx, *ny;
} sweep_state;

typedef struct collide_world {
    broadphase bp;
    contact_store contacts;
    event_store events;
    solver_rows rows;         /* sized with the contacts */

    views_state views;        /* the per-body scratch, one block of scap bodies */
    pairs_state pairs;
    island_state island;
    resolve_state resolve;
    sweep_state sweep;
    void *scratch;
    size_t scratch_size;
    int32_t scap;
    /* A pair search ran out of contact storage (pairs.c): its bodies search again in the
     * next step, which first grows the storage, or fails changing nothing (step.c). */
    int32_t pairs_short;

    /* what the scene uses */
    int32_t shape_count;

    /* settings */
    int32_t iterations, position;
    int32_t sleeping;
    rg_real sleep_speed, sleep_time;
    int32_t continuous;
    rg_real slop, bias_rate, max_push, restitution_threshold;
    /* this step's integrator term (narrow.c): a body's own motion ends o = -offk (D - v0 dt)
     * off the v dt = D its view holds (v0 its velocity at the step's start); offk 1 under
     * explicit Euler, 1/2 under Verlet and RK4, 0 under semi-implicit Euler */
    rg_real offk, offdt;
} collide_world;

/* What one step's collide stage hands from module to module: solver rows staged by the
 * narrowphase in contact order with their sort keys, and what it woke. */
typedef struct collide_step {
    int32_t n;          /* active bodies when the stage started (those with a body view);
                         * after a restage (woke), the active bodies then */
    int32_t nv;         /* those with a body view: n when the stage started (views_of) */
    int32_t na;         /* awake shaped bodies then (the island list's range) */
    int32_t nc;         /* staged rows */
    int32_t ns;         /* solver bodies after the ground: the awake bodies, 1..n */
    int32_t nimp;       /* staged impact rows (rows.imp) */
    int32_t nblock;     /* the parallel staging's blocks (their bodies to ground and contacts
                         * with an event: narrow.c) */
    int woke;           /* the pair search or the narrowphase woke bodies: rows restaged */
    int sensed;         /* the narrowphase met a sensor pair (sense.h decides them) */
    int32_t pressed;    /* rows the solve pressed together though the free motion left them
                         * apart (CT_PRESSED), all within rows [press0, press1) */
    int32_t press0, press1;
    int unite;          /* join islands in the narrowphase (sleeping is near) */
    /* What the narrowphase left to do after the rows are staged, which neither reads nor
     * writes what the solve's first serial part does (events, grounded flags, islands): the
     * solve runs it beside that part (resolve_run), or NULL */
    void (*late)(struct rg_world *w, struct collide_step *x);
    solver_params p;
    int down;           /* gravity is finite and not zero: the rows are solved bottom-up */
    rg_real ux, uy;     /* then its unit direction; a row's height is -(contact point . u) */
} collide_step;

/* ---------------------------------------------------------------- the world */

struct rg_world {
    rg_mem mem;
    char *err;             /* the last error (error.h): ERROR_SIZE bytes allocated with the world */
    own_saves *own;        /* its last saves (own.h), allocated with the world after err */
    pool body_pool;
    body_store b;          /* dense structure-of-arrays body storage */
    spring_store springs;

    rg_vec2 gravity;       /* m/s^2 */
    rg_vec2 wind;          /* N */
    int32_t integrator;    /* RG_INTEGRATOR_* */

    /* What the scene uses, so a stage nobody uses costs nothing. */
    int32_t dissipative_count; /* dynamic bodies with drag or surface friction */
    int32_t limit_count;       /* dynamic bodies with speed limits */
    int32_t gscale_count;      /* bodies with BODY_F_GSCALE */
    int32_t magnitude_count;   /* bodies with BODY_F_MAGNITUDE (quadratic drag or friction) */
    int32_t stopped_any;       /* some body may carry BODY_F_STOPPED (bounds.c) */
    int32_t forces_applied;    /* some dynamic body may hold an applied force (fx, fy other than
                                  +0): set by rg_body_apply_force and a restore, cleared with
                                  the forces at the end of a step */

    /* Fixed-step accumulator (double, so that long runs do not drift). */
    double fixed_dt;
    int32_t max_steps;
    double accumulator;
    int32_t prev_valid;    /* b.px/b.py hold the positions before the last advance step */
    uint64_t step_count;

    /* Per-body scratch for the integrators, grown with the body capacity when first needed. */
    scratch_store scratch;

    /* Collision: broadphase, contacts, events, islands, settings. */
    collide_world coll;

    /* The pre-solve hook (narrow.c), and whether the world is locked: set through a step, an
     * advance, a restore and a draw, and while its allocator runs (mem.h), whose callbacks
     * (the hook, the task system, the allocator, the draw) may call on the world; calls that
     * would change it return RG_ERR_LOCKED and rg_world_destroy does nothing. */
    rg_pre_solve_fn *pre_solve;
    void *pre_solve_user;
    int32_t locked;

    /* The task system the stages spread over (task.c); tasks_on 0: one thread. */
    rg_task_system tasks;
    int32_t tasks_on;

    /* Kept states (slots.c): unsealed snapshots of this world, size bytes in blocks of cap
     * (0: the slot is empty) from its allocator. */
    struct {
        uint8_t *p;
        size_t size, cap;
    } kept[RG_MAX_SLOTS];
};

/* At the top of every call that changes the world: ERROR_BEGIN, and RG_ERR_LOCKED inside one
 * of the world's callbacks. */
#define WORLD_WRITABLE(world) \
    ERROR_BEGIN(world);       \
    if ((world)->locked)      \
        return RG_FAIL((world), RG_ERR_LOCKED, "locked: called from inside one of the world's callbacks")

/* A call that runs the world's callbacks holds its lock from here to its return; `locked`
 * is 0 at both ends (WORLD_WRITABLE refused the call otherwise). */
#define WORLD_LOCK(world) ((world)->locked = 1)
#define WORLD_UNLOCK(world) ((world)->locked = 0)

/* Partition (BODY_PART_*) of dense index i. */
static inline int body_partition(const struct rg_world *w, int32_t i)
{
    if (i < w->b.n_active) return BODY_PART_ACTIVE;
    if (i < w->b.n_moving) return BODY_PART_ASLEEP;
    return BODY_PART_STATIC;
}

/* Dense index of the live body in pool slot `slot`.  Slots never move; dense indices move
 * whenever a body changes partition (falls asleep, wakes, is created or destroyed), so code
 * that keeps a body across such a change keeps its slot. */
static inline int32_t body_dense(const struct rg_world *w, int32_t slot)
{
    return pool_dense(&w->body_pool, slot);
}

#endif
