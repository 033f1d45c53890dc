/* contact.h: contact storage (its structures in state.h): creation and destruction, each
 * body's list of contacts, and the awake set.  The storage grows all-or-nothing together
 * with what is sized by the contact count: the event buffer (events.h) and the solver rows
 * (solver.h). */
#ifndef RG_CONTACT_H
#define RG_CONTACT_H

#include <stdint.h>

#include "collision.h"
#include "state.h"


struct rg_world;

static inline int32_t contact_other(const contact *c, int32_t slot) { return c->sa == slot ? c->sb : c->sa; }
static inline int32_t contact_next(const contact *c, int32_t slot) { return c->sa == slot ? c->na : c->nb; }

void contact_init(contact_store *cs);
void contact_release(struct rg_world *w);
/* A new contact between body slots s and t (materials mixed, linked, awake when either body
 * is), or -1 when memory runs out. */
int32_t contact_create(struct rg_world *w, int32_t s, int32_t t);
/* Grows the storage (as contact_create does when it is full): RG_OK, RG_ERR_OUT_OF_MEMORY or
 * RG_ERR_CAPACITY, changing nothing. */
rg_status contact_reserve(struct rg_world *w);
/* Unlinks and frees contact id; a touching one reports its end (events.h). */
void contact_destroy(struct rg_world *w, int32_t id);
/* Mixes the materials of the contacts of body slot s again. */
void contact_refresh_materials(struct rg_world *w, int32_t s);
/* Sets CT_ONEWAY of the contacts of body slot s again (its one-way normal changed). */
void contact_refresh_flags(struct rg_world *w, int32_t s);
/* The contact between body slots s and t, or -1. */
int32_t contact_find(const struct rg_world *w, int32_t s, int32_t t);
/* The manifold of dense bodies i and j as they are now, normal from i toward j: what the
 * public calls report (a stored contact point is where the narrowphase last computed it). */
void contact_manifold_now(const struct rg_world *w, int32_t i, int32_t j, coll_manifold *m);
/* Contact storage of an exact capacity with room for n_ev events, made aside (restoring a
 * snapshot) and taken by contact_block_adopt, which frees what it replaces and leaves the
 * contents to the caller.  Nothing is allocated when the world's storage already fits. */
typedef struct contact_block {
    contact *c;
    int32_t *awake;
    solver_rows rows;
    event_store ev;
    int32_t cap;
    int new_contacts, new_events;
} contact_block;
rg_status contact_block_alloc(contact_block *b, const struct rg_world *w, int32_t cap, int32_t n_ev, int32_t n_pend);
void contact_block_adopt(struct rg_world *w, contact_block *b);
void contact_block_free(contact_block *b, const rg_mem *m);

void contact_awake_add(contact_store *cs, int32_t id);
void contact_awake_remove(contact_store *cs, int32_t id);

#endif
