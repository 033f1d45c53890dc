/* lutf8.c: utf8.len, codepoint, offset and codes charged by the bytes they scan.
 *
 * The stock functions loop over a string in C with no instruction to count, so a loop of
 * utf8.len over a long string costs its length per call and one unit to the budget.  These
 * wrappers call the stock function and then charge what it scanned: the range asked for
 * (len, codepoint), the distance moved (offset, and each step of the codes iterator; a run
 * of continuation bytes the iterator skips counts as moved). */
#include <lauxlib.h>
#include <lua.h>

#include "lutf8.h"

#define SCAN_BYTES_PER_UNIT 1   /* utf8.len decodes 1 byte in 1.7 ns, an instruction takes 1.8 */

static void charge_bytes(lua_State *L, lua_Integer bytes)
{
    const lpattern_meter *m = (const lpattern_meter *)lua_touserdata(L, lua_upvalueindex(2));
    if (bytes > 0) m->charge(L, m->ud, (size_t)bytes / SCAN_BYTES_PER_UNIT + 1);
}

/* Calls the stock function (upvalue 1) with the arguments; leaves its results. */
static int call_stock(lua_State *L, int base)
{
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, base);
    lua_call(L, lua_gettop(L) - base, LUA_MULTRET);
    return lua_gettop(L) - base + 1;
}

/* A position as the stock library reads it: negative from the end, clamped at 0. */
static lua_Integer posrelat(lua_Integer pos, size_t len)
{
    if (pos >= 0) return pos;
    if ((size_t)-pos > len) return 0;
    return (lua_Integer)len + pos + 1;
}

/* len(s [, i [, j [, lax]]]) and codepoint(s [, i [, j [, lax]]]) scan bytes i..j. */
static int range_call(lua_State *L, int j_defaults_to_i)
{
    size_t len;
    luaL_checklstring(L, 1, &len);
    lua_Integer i = posrelat(luaL_optinteger(L, 2, 1), len);
    lua_Integer j = posrelat(luaL_optinteger(L, 3, j_defaults_to_i ? i : -1), len);
    if (j > (lua_Integer)len) j = (lua_Integer)len;
    int n = call_stock(L, 1);
    charge_bytes(L, j - i + 1);
    return n;
}

static int m_len(lua_State *L) { return range_call(L, 0); }
static int m_codepoint(lua_State *L) { return range_call(L, 1); }

/* offset(s, n [, i]) moves from i over |n| characters (or to the boundary). */
static int m_offset(lua_State *L)
{
    size_t len;
    luaL_checklstring(L, 1, &len);
    lua_Integer n = luaL_checkinteger(L, 2);
    lua_Integer i = posrelat(luaL_optinteger(L, 3, n >= 0 ? 1 : (lua_Integer)len + 1), len);
    int r = call_stock(L, 1);
    lua_Integer to = lua_isinteger(L, -r) ? lua_tointeger(L, -r) : (n > 0 ? (lua_Integer)len + 1 : 0);
    charge_bytes(L, to > i ? to - i : i - to);
    return r;
}

/* The codes iterator: iter(s, pos) -> next pos, code; charged by the distance moved. */
static int m_codes_step(lua_State *L)
{
    size_t len;
    luaL_checklstring(L, 1, &len);
    lua_Integer from = luaL_optinteger(L, 2, 0);
    int r = call_stock(L, 1);
    lua_Integer to = r > 0 && lua_isinteger(L, -r) ? lua_tointeger(L, -r) : (lua_Integer)len;
    charge_bytes(L, to > from ? to - from : 1);
    return r;
}

/* codes(s [, lax]) -> the metered iterator, s, 0. */
static int m_codes(lua_State *L)
{
    int r = call_stock(L, 1);
    if (r >= 1 && lua_type(L, -r) == LUA_TFUNCTION) {
        lua_pushvalue(L, -r);
        lua_pushvalue(L, lua_upvalueindex(2));
        lua_pushcclosure(L, m_codes_step, 2);
        lua_replace(L, -r - 1);
    }
    return r;
}

void lutf8_open(lua_State *L, int idx, const lpattern_meter *meter)
{
    static const luaL_Reg fns[] = {
        { "len", m_len }, { "codepoint", m_codepoint }, { "offset", m_offset },
        { "codes", m_codes }, { NULL, NULL },
    };
    union { const lpattern_meter *c; void *p; } u;   /* stored, never written through */
    u.c = meter;
    idx = lua_absindex(L, idx);
    for (const luaL_Reg *f = fns; f->name != NULL; f++) {
        lua_getfield(L, idx, f->name);
        lua_pushlightuserdata(L, u.p);
        lua_pushcclosure(L, f->func, 2);
        lua_setfield(L, idx, f->name);
    }
}
