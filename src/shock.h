/* shock.h: the shock sweeps (solver.c) on two workers at once, with the one-thread bits.
 *
 * A shock sweep solves its rows one after the other in the solving order, each row reading
 * its two bodies' velocities and writing its upper body's.  Any order in which every body
 * meets its rows in the solving order gives the same numbers, bit for bit (rows that share
 * no body commute).  So the rows are split into two chains by where their first movable body
 * lies across gravity (left or right of a line: a pile's columns share few bodies across
 * it), each chain in the solving order, and each row is given its need: how many rows of
 * the other chain must have run before it, up to the last one earlier in the solving order
 * that meets one of its bodies (the rows of its own chain before it see to the rest).  Two
 * workers run a chain each, a row waiting until the other chain's published progress covers
 * its need.
 *
 * Nothing waits on a thread that is not there: a worker whose chain cannot go on runs the
 * other chain while no thread holds it (of the two chains' next rows, the one earlier in the
 * solving order can always run), so one thread alone, or a task system that runs the two
 * chains one after the other, completes both.  Where the compiler has no __atomic builtins
 * (shock_available() is 0), the sweeps run on one thread. */
#ifndef RG_SHOCK_H
#define RG_SHOCK_H

#include <stdint.h>

#include "solver.h"

struct rg_world;

/* Rows in the solving order [0, n) of which a sweep is worth two chains: below it, the
 * planning and the hand-overs cost more than half a sweep on one thread saves. */
#define SHOCK_MIN_ROWS 1024

/* The two chains: chain s holds rows row[s][0, n[s]), each to run after need[s][k] rows
 * of chain 1 - s. */
typedef struct shock_chains {
    int32_t n[2];
    int32_t *row[2], *need[2];
} shock_chains;

/* Whether shock_run can run the chains at once here (the compiler has the atomics). */
int shock_available(void);

/* Splits rows ord[0, nc) (their movable solver bodies ab[2 r], ab[2 r + 1], 0 for none;
 * solver body q is dense body q - 1, at x[q - 1], y[q - 1]) into chains at `split` across
 * gravity (ux, uy) (unit): a row goes to chain 1 where its first movable body lies at
 * x uy - y ux >= split.  last holds one int32_t per solver body [0, bodies) (scratch);
 * *lo and *hi get the least and the greatest of those coordinates (for the next split). */
void shock_plan(shock_chains *ch, const int32_t *ord, int32_t nc, const int32_t *ab, const rg_real *x,
                const rg_real *y, rg_real ux, rg_real uy, rg_real split, int32_t *last, int32_t bodies,
                rg_real *lo, rg_real *hi);

/* Runs solver_shock (position 0: velocities v) or solver_shock_position (position 1:
 * pseudo-velocities) over the chains on the world's task system, as the opening comment
 * says; returns when every row has run. */
void shock_run(struct rg_world *w, const shock_chains *ch, solver_constraint *c, rg_real *v, rg_real gx,
               rg_real gy, int position);

/* Runs fn(context) once for those who call it with the same *state (0 before the first):
 * the first runs it, the others wait until it has ended (on the thread running it).  Only
 * where shock_available(). */
void shock_once(int32_t *state, void (*fn)(void *), void *context);

#endif
