/* bands.h: a sequence of phases run over bands of work at once, each band's phases in order,
 * with one wait where one thread's order demands it and no barrier between phases.
 *
 * The solver's colour passes (resolve.c) are phases: each phase's rows share no movable body,
 * and a body's rows must meet it in phase order.  Split each phase's rows into bands (band b
 * holding the same region of the scene in every phase), and most bodies are met by one band
 * only: those a band may run ahead of the others.  The rows that meet a body of another band
 * (the band's edge) are the only ones that must wait: band b runs the edge rows of phase s
 * once every other band has run its edge rows of phase s - 1, then publishes, then runs the
 * rest of phase s, its inner rows, which give the other bands the time to publish theirs.  A
 * body met by two bands is thus met in phase order; a body of one band is met in that band's
 * order; rows of one phase share no body.  So every row sees exactly the velocities it sees
 * when one thread runs the phases one after the other, whatever runs where and when.
 *
 * Nothing waits on a thread that is not there: a thread whose band cannot go on runs a phase
 * of the band furthest behind (which can always go on, unless another thread is running it),
 * so one thread alone, or a task system that runs the bands one after the other, completes
 * them all.  Where the compiler has no __atomic builtins (bands_available() is 0), the caller
 * runs the phases as passes of their own instead. */
#ifndef RG_BANDS_H
#define RG_BANDS_H

#include <stdint.h>

struct rg_world;

/* Most bands a run splits into (a task system with more workers leaves the others idle in
 * the phases). */
#define BANDS_MAX 8

/* Runs phase `phase` of band `band`: its edge rows (edge 1), or its inner rows (edge 0). */
typedef void bands_fn(int32_t band, int32_t phase, int edge, void *context);

/* Whether bands_run can run at once here (the compiler has the atomics it needs). */
int bands_available(void);

/* Runs phases [0, phases) of bands [0, bands) (1 <= bands <= BANDS_MAX) on the world's task
 * system as the opening comment says; returns when all have run. */
void bands_run(struct rg_world *w, int32_t bands, int32_t phases, bands_fn *fn, void *context);

#endif
