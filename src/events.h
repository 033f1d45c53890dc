/* events.h: the contact event buffer: begin and end events of the steps of the last
 * rg_world_step or rg_world_advance, each step's sorted by (a, b), an end before a begin;
 * and the ends reported between steps (a body destroyed, a shape, sensor flag or filter
 * changed), held until the next step reports them first. */
#ifndef RG_EVENTS_H
#define RG_EVENTS_H

#include <stdint.h>

#include "state.h"


/* Events one step can produce with contact capacity cap: ends of the contacts touching when
 * it starts (found gone or updated), ends reported between steps (at most cap) and begins
 * of the contacts touching when it ends. */
#define EVENTS_PER_STEP(cap) (3 * (int64_t)(cap))

struct rg_world;

/* Buffers sized for contact capacity `contacts` after those of `cur` (its held events and
 * the current step's room), into *fresh; RG_ERR_CAPACITY or RG_ERR_OUT_OF_MEMORY, with
 * nothing allocated, when it cannot.  events_adopt then moves what cur holds into them and
 * frees cur's; events_discard frees them instead. */
rg_status events_alloc(event_store *fresh, const event_store *cur, const rg_mem *m, int32_t contacts);
void events_adopt(event_store *cur, event_store *fresh, const rg_mem *m);
void events_discard(event_store *fresh, const rg_mem *m);
void events_release(event_store *es, const rg_mem *m);

/* The events readable so far are dropped: a step or an advance begins. */
void events_clear(event_store *es);
/* Room for one more step's events after those held (a later step of one advance);
 * RG_ERR_OUT_OF_MEMORY changes nothing. */
rg_status events_reserve(struct rg_world *w);
/* Contact c's event of this kind (RG_CONTACT_*): into the step's events inside a step, held
 * for the next step outside one. */
void events_emit(struct rg_world *w, const contact *c, int32_t kind);
/* The events stage: a step's events start with the ends held since the last one ... */
void events_begin_step(event_store *es);
/* ... and end sorted. */
void events_end_step(event_store *es);

#endif
