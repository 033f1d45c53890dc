/* lcount.c: library functions charged by the values they move and the strings they read.
 *
 * Each runs a loop in C that no instruction counts (a function that walks its arguments,
 * select or string.char, is charged them by the sandbox's call hook, as every call is: a
 * call may pass a million, from table.unpack): table.unpack and string.byte push
 * as many results as asked, table.sort without a comparator runs n log n comparisons,
 * table.concat appends (and formats) each element, string.format formats numbers (at some
 * 20 ns a digit), string.pack, unpack and packsize read each byte of their format,
 * collectgarbage walks the heap, and tonumber or arithmetic on a string
 * (the string metatable's __add and the rest) reads the whole string, and print writes it.
 * Each wrapper calls the stock function and charges the meter by that count: a value moved,
 * a comparison or a byte read is a unit; an element of table.concat is charged what it
 * costs as units (an instruction's 1.8 ns): a string 16, an integer 110 and a float 280
 * (lua/bench_sandbox.lua times them: 32, 205 and 446 ns an element on a Zen 5 VM), and 280
 * when the table has a metatable (its __index gives the values). */
#include <string.h>

#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>

#include "lcount.h"

enum { BY_RESULTS, BY_SORT, BY_STRINGS, BY_CONCAT, BY_FORMAT, BY_PACK, BY_GC };

/* string.format: a byte it writes that neither the format nor a string argument gave (a
 * digit it formatted, padding) -- string.format("%.99f", 1e308) writes 408, some 20 ns each
 * (lua/bench_sandbox.lua), some 12 units. */
#define FORMAT_BYTE 16

/* string.pack, unpack and packsize: a byte of their format (an item to read or write:
 * string.unpack of 200,000 "b" takes 10-33 ns each, lua/bench_sandbox.lua). */
#define PACK_FORMAT_BYTE 20

/* collectgarbage: a heap byte for a collection or a step (a step may finish the cycle), and
 * a change of mode (which walks every object): a full collection goes through some 4-5
 * bytes a ns (lua/bench_sandbox.lua). */
#define GC_BYTES_PER_UNIT 4

static double lcount_gc(lua_State *L)
{
    static const char *const work[] = { "collect", "step", "incremental", "generational", NULL };
    const char *opt = lua_type(L, 1) == LUA_TSTRING ? lua_tostring(L, 1) : lua_isnoneornil(L, 1) ? "collect" : NULL;
    if (opt == NULL) return 0;
    for (int i = 0; work[i] != NULL; i++)
        if (strcmp(opt, work[i]) == 0)
            return ((double)lua_gc(L, LUA_GCCOUNT, 0) * 1024 + (double)lua_gc(L, LUA_GCCOUNTB, 0)) / GC_BYTES_PER_UNIT;
    return 0;
}

#define CONCAT_STRING  16
#define CONCAT_INTEGER 110
#define CONCAT_FLOAT   280

/* table.concat(t [, sep [, i [, j]]]): what its elements i..j cost, read raw (the stock
 * function raises on a bad argument or element, after the charge). */
static double lcount_concat(lua_State *L)
{
    lua_Integer i, j;
    double units = 0;
    if (lua_type(L, 1) != LUA_TTABLE) return 0;
    i = luaL_optinteger(L, 3, 1);
    j = lua_isnoneornil(L, 4) ? (lua_Integer)lua_rawlen(L, 1) : luaL_checkinteger(L, 4);
    if (i > j) return 0;
    if (lua_getmetatable(L, 1)) {
        lua_pop(L, 1);
        return ((double)j - (double)i + 1) * CONCAT_FLOAT;
    }
    /* up to the first element that is neither string nor number, where the stock function
     * stops (so the walk is never longer than the table: j may be 2^62) */
    for (lua_Integer k = i;; k++) {
        int t = lua_rawgeti(L, 1, k);
        if (t != LUA_TNUMBER && t != LUA_TSTRING) {
            lua_pop(L, 1);
            break;
        }
        units += t == LUA_TSTRING ? CONCAT_STRING : lua_isinteger(L, -1) ? CONCAT_INTEGER : CONCAT_FLOAT;
        lua_pop(L, 1);
        if (k == j) break;
    }
    return units;
}

/* Charges units, at most half of size_t (past any budget: table.concat's j may be 2^63). */
static void lcount_charge(lua_State *L, double units)
{
    const lpattern_meter *m = (const lpattern_meter *)lua_touserdata(L, lua_upvalueindex(2));
    const double most = (double)((size_t)-1 / 2);
    if (units >= 1) m->charge(L, m->ud, units < most ? (size_t)units : (size_t)-1 / 2);
}

static int lcount_call(lua_State *L)
{
    int mode = (int)lua_tointeger(L, lua_upvalueindex(3));
    int nargs = lua_gettop(L), nres;
    double units = 0, strings = 0;
    if (mode == BY_STRINGS || mode == BY_FORMAT) /* the bytes they read or may copy */
        for (int i = 1; i <= nargs; i++)
            if (lua_type(L, i) == LUA_TSTRING) strings += (double)lua_rawlen(L, i);
    if (mode == BY_STRINGS) units = strings;
    if (mode == BY_SORT && lua_type(L, 1) == LUA_TTABLE) {
        double n = (double)lua_rawlen(L, 1), lg = 1;
        for (double k = n; k > 1; k /= 2) lg++;
        units = n * lg;
    }
    if (mode == BY_CONCAT) units = lcount_concat(L);
    if (mode == BY_PACK && lua_type(L, 1) == LUA_TSTRING) units = (double)lua_rawlen(L, 1) * PACK_FORMAT_BYTE;
    if (mode == BY_GC) units = lcount_gc(L);
    /* charged before the call: the stock function may raise, and its work is done by then */
    lcount_charge(L, units);
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, nargs, LUA_MULTRET);
    nres = lua_gettop(L);
    if (mode == BY_RESULTS) lcount_charge(L, nres);
    if (mode == BY_FORMAT && nres == 1 && lua_type(L, 1) == LUA_TSTRING)
        lcount_charge(L, ((double)lua_rawlen(L, 1) - strings) * FORMAT_BYTE);
    return nres;
}

/* Wraps table[name].  The stock function, called from C, has no name of its own for its
 * argument errors: luaL_argerror then looks for it in the registry's loaded-modules table,
 * where it is kept under `shown` ("string.format"), so the error names it as stock Lua
 * would, not '?'.  (Scripts cannot reach the registry, and the sandbox's require does not
 * read that table.) */
static void lcount_wrap(lua_State *L, int table, const char *name, const char *shown, int mode,
                        const lpattern_meter *meter)
{
    union { const lpattern_meter *c; void *p; } u;   /* stored, never written through */
    u.c = meter;
    lua_getfield(L, table, name);
    if (lua_type(L, -1) != LUA_TFUNCTION) {
        lua_pop(L, 1);
        return;
    }
    if (shown != NULL) {
        luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
        lua_pushvalue(L, -2);
        lua_setfield(L, -2, shown);
        lua_pop(L, 1);
    }
    lua_pushlightuserdata(L, u.p);
    lua_pushinteger(L, mode);
    lua_pushcclosure(L, lcount_call, 3);
    lua_setfield(L, table, name);
}

void lcount_open(lua_State *L, const lpattern_meter *meter)
{
    static const char *const arith[] = { "__add", "__sub", "__mul", "__div", "__mod",
                                         "__pow", "__unm", "__idiv", NULL };
    int top = lua_gettop(L);
    lua_pushglobaltable(L);
    lcount_wrap(L, top + 1, "tonumber", "tonumber", BY_STRINGS, meter);
    lcount_wrap(L, top + 1, "print", "print", BY_STRINGS, meter);   /* writes each string out */
    lcount_wrap(L, top + 1, "collectgarbage", "collectgarbage", BY_GC, meter);
    lua_getglobal(L, LUA_TABLIBNAME);
    lcount_wrap(L, top + 2, "unpack", "table.unpack", BY_RESULTS, meter);
    lcount_wrap(L, top + 2, "sort", "table.sort", BY_SORT, meter);
    lcount_wrap(L, top + 2, "concat", "table.concat", BY_CONCAT, meter);
    lua_getglobal(L, LUA_STRLIBNAME);
    lcount_wrap(L, top + 3, "byte", "string.byte", BY_RESULTS, meter);
    lcount_wrap(L, top + 3, "format", "string.format", BY_FORMAT, meter);
    lcount_wrap(L, top + 3, "pack", "string.pack", BY_PACK, meter);
    lcount_wrap(L, top + 3, "unpack", "string.unpack", BY_PACK, meter);
    lcount_wrap(L, top + 3, "packsize", "string.packsize", BY_PACK, meter);
    lua_settop(L, top);
    lua_pushliteral(L, "");
    if (lua_getmetatable(L, -1)) {
        int mt = lua_gettop(L);
        for (int i = 0; arith[i] != NULL; i++) lcount_wrap(L, mt, arith[i], NULL, BY_STRINGS, meter);
    }
    lua_settop(L, top);
}
