/* contact.h: the collide stage of the step: persistent contacts, narrowphase, the solver
 * call, continuous collision, events, grounded flags and sleeping islands.
 *
 * Who pays: only bodies with a shape are in the broadphase, and only the awake ones among
 * them (the broadphase's active list) are visited per step; static and sleeping bodies and
 * bodies without shapes cost nothing.  A world with no shape skips the stage.
 *
 * Pairs: every shaped body has a fat box in the broadphase (its box grown by a margin, the
 * path of its last step and a look-ahead of four steps of motion).  A body whose swept box
 * leaves its fat box gets a new one and joins the move buffer; only moved bodies query the
 * broadphase, and a query creates a contact for each new overlapping fat box that the
 * filter admits.  A contact lives while the two fat boxes overlap, so a settled pile finds
 * no pairs at all.
 *
 * Narrowphase: the manifold is taken at the start of the step (positions minus the step's
 * displacement) and extrapolated linearly: s0 is the start separation along the normal and
 * the solver keeps s0 + vn*dt >= 0 (speculative contacts), so a body moving less than its
 * size stops exactly at a surface.  A pair whose relative motion exceeds half the smaller
 * shape uses the time of impact instead (continuous collision).  A pair is solved when it
 * could close within the step, counting each body's own motion toward the other (the solver
 * may stop either).  Touching (events, grounded, islands) means the step's free motion ends
 * in contact, with a slop of hysteresis.
 *
 * Solve: rows are staged in the narrowphase, ordered bottom-up along gravity (radix sort of
 * the contact heights) and handed to the solver (solver.h); then a post-solve sweep stops
 * any body the step moved by more than half its size at the first static, kinematic or
 * sleeping shape its path crosses.
 *
 * Timed impacts: an impact is a pair apart after the last step whose free motion closes the
 * gap s0 > 0 within this one, at the fraction t = s0 / (approach distance) of the step.  A
 * body whose rows are impacts at one t (one, or several at once: a box landing across a
 * tile seam) and rows with immovable bodies that stay apart moves freely until t and with
 * its solved velocity after it: it ends at x_free + (1 - t) dt (v - v_free), so a bounce turns
 * at the surface and leaves at solver_vout for the rest of the step, and a landing ends on
 * the surface with no velocity into it.  It may share a row with one other movable body if
 * that row is an impact timed at both ends (two balls colliding).  Every other body (in
 * contact with something, near another body, meeting two things at different moments)
 * keeps the speculative rows, which stop it at the surface from where the step began, and
 * shares no row with a timed one but with immovable bodies, so it solves as without timing.
 *
 * Contacts are identified by an id into `c`; the awake ones (at least one body awake) are
 * listed in `awake`, in a deterministic order; each body heads a doubly linked list of its
 * contacts (`chead` in the body fields). */
#ifndef RG_CONTACT_H
#define RG_CONTACT_H

#include <stdint.h>

#include "broadphase.h"
#include "rigid.h"
#include "solver.h"

/* body cflags */
#define CF_SENSOR   1u
#define CF_GROUNDED 2u
#define CF_TELEPORTED 4u /* placed by the API since its last pair search */

/* contact flags */
#define CT_TOUCHING 1u
#define CT_SENSOR   2u
#define CT_SOLVE    4u  /* solved in this step */
#define CT_CLOSING  8u  /* the step's free motion would make the pair overlap */

typedef struct contact {
    int32_t sa, sb;           /* body slots; a has the lower handle */
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
} contact;

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

typedef struct contact_world {
    broadphase bp;

    contact *c;               /* [0, cap) by id */
    int32_t cap, live, free_head;
    int32_t *awake;           /* ids of awake contacts, [0, n_awake) */
    int32_t n_awake;
    int32_t n_touching;
    solver_constraint *stage; /* [0, cap): rows in contact order, before sorting */
    rg_real *hgt, *hgx;       /* [0, cap): their contact points, then heights along gravity */
    int32_t *ord, *tord;      /* [0, cap): staged rows in solving order, radix scratch */
    uint16_t *key, *tkey;     /* [0, cap): their sort keys, radix scratch */
    int32_t *color;           /* [0, cap): colouring scratch */
    int32_t *imp;             /* [0, cap): staged rows that are impacts (toi > 0) */
    solver_batch batch;       /* the rows eight at a time (rows: SOLVER_WIDE_ROWS(cap)) */

    rg_contact_event *ev;     /* events of the last step, or of every step of the last advance */
    int32_t n_ev, ev_cap;     /* held, room (>= ev_base + 3 * cap during a step) */
    int32_t ev_base;          /* where the current step's events start */
    rg_contact_event *pend;   /* ends between steps, reported with the next step (cap) */
    int32_t n_pend;
    int32_t in_step;

    /* per-body scratch, body capacity + 1: indexed by place in the broadphase's active list
     * (k), by dense body index (i) or by solver body (q) */
    cbody *cb;                /* i: the step's view of the awake shaped bodies */
    rg_real *sx0, *sy0;       /* k: positions before integration */
    rg_real *svx0, *svy0;     /* k: velocities before integration */
    int32_t *adense;          /* k: dense index during the step */
    rg_real *umin;            /* k: island minimum rest time */
    int32_t *uf;              /* k: union-find parents */
    int32_t *ihead, *itail;   /* k: island member lists while falling asleep */
    int32_t *list;            /* slots of bodies falling asleep */
    int32_t *sidx;            /* i: solver index, valid when sstamp[i] == gen */
    uint32_t *sstamp;         /* i */
    uint32_t gen;             /* solver index generation (one per step, or more) */
    int32_t *sbody;           /* q: dense index of solver body q (q >= 1; 0 is the ground) */
    rg_real *sv;              /* q: solver velocities, pairs */
    rg_real *spv;             /* q: pseudo-velocities of the position pass, pairs */
    rg_real *stoi;            /* q: fraction of the step at which its velocity changes */
    int32_t pv_valid;         /* spv holds this step's position pass */
    uint32_t *cmask;          /* q: colouring, the colours each body is in */
    int32_t scap;

    /* what the scene uses */
    int32_t shape_count;

    /* settings */
    int32_t iterations, position;
    int32_t sleeping;
    int32_t near_sleep;       /* a body will reach sleep_time within two steps */
    rg_real sleep_speed, sleep_time;
    int32_t continuous;
    rg_real slop, bias_rate, max_push, restitution_threshold;
} contact_world;

struct rg_world;

void contact_init(struct rg_world *w);
void contact_release(struct rg_world *w);
/* Scratch a step needs; call before anything changes. */
rg_status contact_prepare(struct rg_world *w);
/* Whether the step must run the collide stage (shapes, or ended contacts to report). */
int contact_stage_needed(const struct rg_world *w);
/* The events readable so far are dropped: a step or an advance begins. */
void contact_events_clear(struct rg_world *w);
/* Room for one more step's events after those held (a later step of one advance);
 * RG_ERR_OUT_OF_MEMORY changes nothing. */
rg_status contact_events_reserve(struct rg_world *w);
/* Before integration: remembers where the awake bodies start. */
void contact_begin(struct rg_world *w);
/* After integration: the collide stage. */
void contact_step(struct rg_world *w, rg_real dt);

/* Hooks for the body API.  Dense indices in, new dense indices out where bodies move. */
void contact_body_init(struct rg_world *w, int32_t i);
/* Wakes the body's island if it sleeps and restarts its rest timer; returns its index. */
int32_t contact_body_wake(struct rg_world *w, int32_t i);
/* The body was teleported: refresh its fat box, wake what rested on it. */
void contact_body_moved(struct rg_world *w, int32_t i);
/* The body is about to be destroyed: end its contacts, leave the broadphase.  Returns its
 * (possibly new) dense index. */
int32_t contact_body_destroy(struct rg_world *w, int32_t i);

#endif
