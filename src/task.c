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
