/* task.h: the stages' way onto the world's task system (rg_world_set_task_system). */
#ifndef RG_TASK_H
#define RG_TASK_H

#include "rigid.h"

struct rg_world;

/* Runs fn over [0, count) on the world's task system in ranges of at least min_range, or at
 * once on this thread (worker 0) when there is none or count is below two ranges.  Returns
 * when every range has run.  fn's results must not depend on the ranges or their order. */
void task_for(struct rg_world *w, rg_task_fn *fn, int32_t count, int32_t min_range, void *context);

/* Workers a stage may see (fn's worker index is below it): 1 without a task system. */
int32_t task_workers(const struct rg_world *w);

#ifdef RG_STEP_PROFILE
#include <stdio.h>

/* The step's timers (step.h) task by task: every task_for names its function, and each
 * task's time (from the call to its return) and each worker's time inside its ranges are
 * summed per function, printed and cleared by task_prof_report as means over `steps`. */
void task_for_named(struct rg_world *w, rg_task_fn *fn, const char *name, int32_t count, int32_t min_range,
                    void *context);
#define task_for(w, fn, count, min_range, context) task_for_named((w), (fn), #fn, (count), (min_range), (context))
void task_prof_report(FILE *out, int steps);
#endif

#endif
