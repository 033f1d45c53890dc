/* island.h: islands, sleeping and waking.
 *
 * Islands are dynamic bodies joined by touching solid contacts and springs.  An island whose
 * every body rested (speed below sleep_speed) for sleep_time falls asleep as a whole: its
 * bodies move to the asleep partition and leave the broadphase's active list, so they cost
 * nothing per step, and a linked list of its members (isl_head, isl_next in the body fields)
 * wakes it as a whole.  Waking moves bodies between partitions, so their dense indices
 * change: every function here takes a body's pool slot, which does not. */
#ifndef RG_ISLAND_H
#define RG_ISLAND_H

#include <stdint.h>

#include "state.h"

struct rg_world;

/* The island scratch arrays for n bodies. */
void island_layout(mem_layout *l, island_state *s, int32_t n);
/* Wakes the island of the body in `slot` if it sleeps. */
void island_wake(struct rg_world *w, int32_t slot);
/* island_wake, and the body's rest timer starts again (it was pushed, moved or changed).
 * Inline: most calls find the body awake. */
static inline void island_touch(struct rg_world *w, int32_t slot)
{
    int32_t i = body_dense(w, slot);
    if (body_partition(w, i) == BODY_PART_ASLEEP) {
        island_wake(w, slot);
        i = body_dense(w, slot);
    }
    w->b.sleep_t[i] = 0;
}
/* Wakes the sleeping bodies that touch slot's body (it moved, changed or goes away). */
void island_wake_touching(struct rg_world *w, int32_t slot);
void island_wake_all(struct rg_world *w);

/* Union-find over places in the broadphase's active list (inline: the narrowphase unites
 * every touching pair while sleep is near). */
static inline int32_t island_root(int32_t *uf, int32_t i)
{
    while (uf[i] != i) {
        uf[i] = uf[uf[i]];
        i = uf[i];
    }
    return i;
}

static inline void island_unite(int32_t *uf, int32_t a, int32_t b)
{
    a = island_root(uf, a);
    b = island_root(uf, b);
    /* the lower index becomes the root: deterministic */
    if (a < b) uf[b] = a; else if (b < a) uf[a] = b;
}

/* The sleep stage: rest timers, and the islands that rested long enough fall asleep.
 * `united`: the narrowphase already joined this step's islands in island.uf. */
void island_sleep(struct rg_world *w, rg_real dt, int united);

#endif
