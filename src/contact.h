/* contact.h: contact storage: persistent contacts between pairs of bodies whose fat boxes
 * overlap, each body's list of them, and the awake set.
 *
 * Contacts are identified by an id into `c`; the awake ones (at least one body awake) are
 * listed in `awake`, in a deterministic order; each body heads a doubly linked list of its
 * contacts (`chead` in the body fields, id + 1).  The storage grows all-or-nothing together
 * with what is sized by the contact count: the event buffer (events.h) and the solver rows
 * (solver.h). */
#ifndef RG_CONTACT_H
#define RG_CONTACT_H

#include <stdint.h>

#include "rigid.h"

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

typedef struct contact_store {
    contact *c;               /* [0, cap) by id */
    int32_t cap, live, free_head;
    int32_t *awake;           /* ids of awake contacts, [0, n_awake) */
    int32_t n_awake;
    int32_t n_touching;       /* contacts with CT_TOUCHING */
} contact_store;

struct rg_world;

static inline int32_t contact_other(const contact *c, int32_t slot) { return c->sa == slot ? c->sb : c->sa; }
static inline int32_t contact_next(const contact *c, int32_t slot) { return c->sa == slot ? c->na : c->nb; }

void contact_init(contact_store *cs);
void contact_release(struct rg_world *w);
/* A new contact between body slots s and t (materials mixed, linked, awake when either body
 * is), or -1 when memory runs out. */
int32_t contact_create(struct rg_world *w, int32_t s, int32_t t);
/* Unlinks and frees contact id; a touching one reports its end (events.h). */
void contact_destroy(struct rg_world *w, int32_t id);
/* Mixes the materials of the contacts of body slot s again. */
void contact_refresh_materials(struct rg_world *w, int32_t s);
void contact_awake_add(contact_store *cs, int32_t id);
void contact_awake_remove(contact_store *cs, int32_t id);

#endif
