/* fuzz_lua.c: libFuzzer harness for the sandboxed Lua host: each input is a script, run as
 * the host runs one (lua/lsandbox.c with the rigid binding, a small instruction budget and
 * memory cap): its main chunk, then, when it defines update(world, dt) and contact(world,
 * event), three frames of a host-made world, each frame's update and contact calls under one
 * budget.  Any crash or sanitizer report is a finding, and so is an input that takes more
 * than FUZZ_LUA_CPU seconds of CPU: the budget must stop every runaway script long before
 * (BUDGET units are well under a millisecond of VM work).  Each entry also has the host's
 * backstop, a time limit (ENTRY_SECONDS, at most 5 entries; the clock is read every 1,000
 * instructions, at most some 50 ms apart: 1,000 lookups through 2,000 __index tables),
 * which stops work the units undercharge call after call (a next() scanning empty slots);
 * what it cannot stop, one call or instruction that runs long, is what the CPU guard finds.
 */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include <lauxlib.h>
#include <lua.h>

#include "lrigid.h"
#include "lsandbox.h"

#define BUDGET       200000
#define MEMORY       (16u << 20)
#define FRAMES       3
#define FUZZ_LUA_CPU 0.5
#define ENTRY_SECONDS 0.02

static void charge(lua_State *L, void *ud, double units)
{
    lsandbox_charge(L, (lsandbox *)ud, units);
}

static int quiet(lua_State *L)
{
    (void)L;
    return 0;
}

/* update(world, dt), one fixed step, then contact(world, event) for each event. */
static void frames(lua_State *L, lsandbox *sb)
{
    int world;
    lua_getglobal(L, "rigid");
    if (lua_type(L, -1) != LUA_TTABLE) return;
    lua_getfield(L, -1, "world");
    if (lsandbox_call(L, sb, 0, 1) != LUA_OK) return;
    world = lua_gettop(L);
    for (int f = 0; f < FRAMES; f++) {
        rg_world *w = lrigid_toworld(L, world);
        int fresh = 1;
        if (lsandbox_getfunction(L, "update")) {
            lua_pushvalue(L, world);
            lua_pushnumber(L, 1.0 / 60);
            if (lsandbox_call(L, sb, 2, 0) != LUA_OK) return;
            fresh = 0;
        }
        w = lrigid_toworld(L, world);   /* update may have closed it */
        if (w == NULL || rg_world_advance(w, (rg_real)(1.0 / 60), NULL) != RG_OK) return;
        lrigid_pushevents(L, world);
        int events = lua_gettop(L);
        for (lua_Integer i = 1; i <= (lua_Integer)lua_rawlen(L, events); i++) {
            if (!lsandbox_getfunction(L, "contact")) break;
            lua_pushvalue(L, world);
            lua_rawgeti(L, events, i);
            int st = fresh ? lsandbox_call(L, sb, 2, 0) : lsandbox_continue(L, sb, 2, 0);
            fresh = 0;
            if (st != LUA_OK) return;
        }
        lua_settop(L, world);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static lrigid_hooks hooks;
    lsandbox *sb = NULL;
    clock_t t0 = clock();
    lua_State *L = lsandbox_new(MEMORY, BUDGET, &sb);
    if (L == NULL) return 0;
    lsandbox_set_time_limit(sb, ENTRY_SECONDS);
    lsandbox_provide(L, "rigid", luaopen_rigid);
    lua_pushcfunction(L, quiet);
    lua_setglobal(L, "print");
    hooks.charge = charge;
    hooks.after_step = NULL;
    hooks.ud = sb;
    lrigid_sethooks(L, &hooks);
    if (luaL_loadbufferx(L, (const char *)data, size, "=fuzz", "t") == LUA_OK &&
        lsandbox_call(L, sb, 0, 0) == LUA_OK)
        frames(L, sb);
    lua_settop(L, 0);
    lrigid_sethooks(L, NULL);
    lsandbox_close(L, sb);
    double cpu = (double)(clock() - t0) / CLOCKS_PER_SEC;
    if (cpu > FUZZ_LUA_CPU) {
        fprintf(stderr, "fuzz_lua: an input ran %.2f s of CPU under a budget of %d units\n", cpu, BUDGET);
        abort();
    }
    return 0;
}
