/* task.c: the world's task system and task_for. */
#include "arg.h"
#include "state.h"
#include "task.h"

RG_API rg_status rg_world_set_task_system(rg_world *world, const rg_task_system *tasks)
{
    WORLD_WRITABLE(world);
    if (tasks == NULL) {
        world->tasks_on = 0;
        return RG_OK;
    }
    if (tasks->workers < 1 || tasks->workers > RG_MAX_WORKERS)
        return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "tasks->workers %d is not in [1, RG_MAX_WORKERS (%d)]",
                       (int)tasks->workers, RG_MAX_WORKERS);
    if (tasks->enqueue == NULL || tasks->finish == NULL)
        return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "tasks->%s is NULL", tasks->enqueue == NULL ? "enqueue" : "finish");
    world->tasks = *tasks;
    world->tasks_on = 1;
    return RG_OK;
}

#ifdef RG_STEP_PROFILE
#undef task_for
#include <time.h>

/* Tasks told apart, workers timed (each worker's sums on lines of its own). */
#define TASK_PROF_MAX 48
#define TASK_PROF_WORKERS 8

typedef struct task_prof {
    const char *name;
    double wall;   /* s from the call to its return */
    long calls, items;
} task_prof;

static task_prof task_prof_row[TASK_PROF_MAX];
static int task_prof_n;
static struct {
    double busy[TASK_PROF_MAX];
    char pad[64]; /* no line shared with the next worker's */
} task_prof_busy[TASK_PROF_WORKERS];

static double task_prof_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

/* A named task's ranges, each timed on the worker that runs it. */
typedef struct task_prof_call {
    rg_task_fn *fn;
    void *context;
    int row;
} task_prof_call;

static void task_prof_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    const task_prof_call *c = context;
    double t0 = task_prof_now();
    c->fn(begin, end, worker, c->context);
    if (c->row >= 0 && worker >= 0 && worker < TASK_PROF_WORKERS)
        task_prof_busy[worker].busy[c->row] += task_prof_now() - t0;
}

void task_for_named(rg_world *w, rg_task_fn *fn, const char *name, int32_t count, int32_t min_range, void *context)
{
    int row = -1;
    for (int k = 0; k < task_prof_n && row < 0; k++)
        if (task_prof_row[k].name == name) row = k;
    if (row < 0 && task_prof_n < TASK_PROF_MAX) {
        row = task_prof_n++;
        task_prof_row[row].name = name;
    }
    task_prof_call c = { fn, context, row };
    double t0 = task_prof_now();
    task_for(w, task_prof_range, count, min_range, &c);
    if (row >= 0) {
        task_prof_row[row].wall += task_prof_now() - t0;
        task_prof_row[row].calls++;
        task_prof_row[row].items += count;
    }
}

void task_prof_report(FILE *out, int steps)
{
    fprintf(out, "tasks over the last %d steps, us a step: the task's time, then each worker's inside its ranges\n", steps);
    for (int k = 0; k < task_prof_n; k++) {
        task_prof *r = &task_prof_row[k];
        if (r->calls == 0) continue;
        fprintf(out, "  %-32s calls %5.2f items %7.0f  time %7.1f  workers", r->name, (double)r->calls / steps,
                (double)r->items / (double)r->calls, r->wall * 1e6 / steps);
        for (int u = 0; u < TASK_PROF_WORKERS; u++)
            if (task_prof_busy[u].busy[k] > 0) fprintf(out, " %7.1f", task_prof_busy[u].busy[k] * 1e6 / steps);
        fprintf(out, "\n");
        r->wall = 0;
        r->calls = r->items = 0;
        for (int u = 0; u < TASK_PROF_WORKERS; u++) task_prof_busy[u].busy[k] = 0;
    }
}
#endif

void task_for(rg_world *w, rg_task_fn *fn, int32_t count, int32_t min_range, void *context)
{
    if (count <= 0) return;
    if (!w->tasks_on || w->tasks.workers < 2 || count < 2 * min_range) {
        fn(0, count, 0, context);
        return;
    }
    void *t = w->tasks.enqueue(fn, count, min_range, context, w->tasks.user);
    if (t != NULL) w->tasks.finish(t, w->tasks.user);
}

int32_t task_workers(const rg_world *w) { return w->tasks_on ? w->tasks.workers : 1; }
