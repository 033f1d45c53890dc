/* pattern_fuzz.c: runs tests/lua/pattern_fuzz.lua in a stock Lua state that also has the
 * metered matcher as global `bounded` (and `metered`, whose meter counts units). */
#include <stdio.h>

#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>

#include "lpattern.h"

static size_t units;

static void count(lua_State *L, void *ud, size_t n)
{
    (void)L;
    (void)ud;
    units += n;
}

static int l_units(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)units);
    return 1;
}

int main(int argc, char **argv)
{
    static const lpattern_meter meter = { count, NULL };
    const char *script = argc > 1 ? argv[1] : "tests/lua/pattern_fuzz.lua";
    lua_State *L = luaL_newstate();
    int rc;
    if (L == NULL) return 1;
    luaL_openlibs(L);
    lua_newtable(L);
    lpattern_open(L, -1, NULL);
    lua_setglobal(L, "bounded");
    lua_newtable(L);
    lpattern_open(L, -1, &meter);
    lua_pushcfunction(L, l_units);
    lua_setfield(L, -2, "units");
    lua_setglobal(L, "metered");
    rc = luaL_dofile(L, script);
    if (rc != LUA_OK) fprintf(stderr, "%s\n", lua_tostring(L, -1));
    lua_close(L);
    return rc == LUA_OK ? 0 : 1;
}
