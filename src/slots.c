/* slots.c: kept states (rg_world_save_slot, rg_world_restore_slot, rg_world_drop_slot): the
 * world's own snapshots, written unsealed with a tail of what a restore would derive into
 * blocks of its allocator, and loaded without the checks a snapshot from outside needs
 * (snapshot.h: snap_write_planned, snap_kept_tail_size, restore_kept). */
#include "error.h"
#include "snapshot.h"

#define SLOT_VALID(world, slot)                                                                      \
    if ((slot) < 0 || (slot) >= RG_MAX_SLOTS)                                                        \
    return RG_FAIL((world), RG_ERR_INVALID_ARGUMENT, "slot %ld is outside [0, %d)", (long)(slot), \
                   (int)RG_MAX_SLOTS)

RG_API rg_status rg_world_save_slot(rg_world *world, int32_t slot)
{
    WORLD_WRITABLE(world);
    SLOT_VALID(world, slot);
    snap_plan plan;
    snap_plan_of(world, &plan);
    uint8_t *p = world->kept[slot].p;
    size_t need = plan.size + snap_kept_tail_size(&plan); /* the snapshot and its tail */
    if (need > world->kept[slot].cap) {
        /* an eighth more than now, so that a state that grows a little does not grow the
         * block at every save (the size itself where that would wrap) */
        size_t cap = need + need / 8;
        if (cap < need) cap = need;
        p = mem_alloc(&world->mem, cap);
        if (p == NULL)
            return error_alloc(world, "rg_world_save_slot", RG_ERR_OUT_OF_MEMORY, "the kept state", "RG_MAX_BODIES");
        if (world->kept[slot].p != NULL) mem_free(&world->mem, world->kept[slot].p, world->kept[slot].cap);
        world->kept[slot].p = p;
        world->kept[slot].cap = cap;
    }
    snap_write_planned(world, &plan, p, 0);
    world->kept[slot].size = plan.size;
    return RG_OK;
}

RG_API rg_status rg_world_restore_slot(rg_world *world, int32_t slot)
{
    WORLD_WRITABLE(world);
    SLOT_VALID(world, slot);
    if (world->kept[slot].size == 0) return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "slot %ld is empty", (long)slot);
    WORLD_LOCK(world); /* the allocator and the task system may call on it */
    rg_status st = restore_kept(world, world->kept[slot].p, world->kept[slot].size);
    WORLD_UNLOCK(world);
    if (st == RG_OK) ERROR_CLEAR(world); /* a callback's failed call is not this call's */
    return st;
}

RG_API rg_status rg_world_drop_slot(rg_world *world, int32_t slot)
{
    WORLD_WRITABLE(world);
    SLOT_VALID(world, slot);
    if (world->kept[slot].p != NULL) mem_free(&world->mem, world->kept[slot].p, world->kept[slot].cap);
    world->kept[slot].p = NULL;
    world->kept[slot].size = world->kept[slot].cap = 0;
    return RG_OK;
}
