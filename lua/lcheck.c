/* lcheck.c: the Lua binding's argument and option checks, and the errors they raise.
 *
 * Numbers must be numbers (not numeric strings) and finite, and fit rg_real; option tables
 * accept only the names listed, so a misspelt option is an error, not a silent default. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "lrigid_int.h"

const char *const lcheck_integrator_names[] = { "explicit", "semi_implicit", "verlet", "rk4",
                                                NULL };
const char *const lcheck_type_names[] = { "static", "kinematic", "dynamic", NULL };

/* ---------------------------------------------------------------- arguments */

void *lcheck_self(lua_State *L, int i, const char *tname)
{
    void *p = lua_touserdata(L, i);
    if (p != NULL && lua_getmetatable(L, i)) {
        int same = lua_rawequal(L, -1, lua_upvalueindex(1));
        lua_pop(L, 1);
        if (same) return p;
    }
    luaL_typeerror(L, i, tname);
    return NULL;
}

lua_Number lcheck_finite(lua_State *L, int i)
{
    lua_Number v;
    if (lua_type(L, i) != LUA_TNUMBER) luaL_typeerror(L, i, "number");
    v = lua_tonumber(L, i);
    if (!isfinite(v)) luaL_argerror(L, i, v != v ? "finite number expected, got nan"
                                                 : "finite number expected, got inf");
    return v;
}

static int lcheck_fits(lua_Number v)
{
#ifdef RG_DOUBLE
    (void)v;
    return 1;
#else
    return fabs(v) <= (lua_Number)FLT_MAX;
#endif
}

rg_real lcheck_real(lua_State *L, int i)
{
    lua_Number v = lcheck_finite(L, i);
    if (!lcheck_fits(v)) luaL_argerror(L, i, "number out of range for rg_real (float)");
    return (rg_real)v;
}

rg_vec2 lcheck_vec2(lua_State *L, int i)
{
    rg_vec2 v;
    v.x = lcheck_real(L, i);
    v.y = lcheck_real(L, i + 1);
    return v;
}

rg_real lcheck_optreal(lua_State *L, int i, rg_real def)
{
    return lua_isnoneornil(L, i) ? def : lcheck_real(L, i);
}

uint32_t lcheck_mask(lua_State *L, int i)
{
    int ok = 0;
    lua_Integer v = 0;
    if (lua_type(L, i) == LUA_TNUMBER) v = lua_tointegerx(L, i, &ok);
    if (!ok || v < 0 || v > 0xFFFFFFFF)
        luaL_argerror(L, i, "integer in [0, 0xFFFFFFFF] expected");
    return (uint32_t)v;
}

uint32_t lcheck_optmask(lua_State *L, int i)
{
    return lua_isnoneornil(L, i) ? 0xFFFFFFFFu : lcheck_mask(L, i);
}

/* luaL_checkinteger takes a string of digits too ("3"), and reads all of it in C: one a
 * script made may be megabytes long, so it is charged first, a unit a byte (as tonumber is,
 * lua/lcount.c; 0.9 ns a byte). */
lua_Integer lcheck_integer(lua_State *L, int i)
{
    if (lua_type(L, i) == LUA_TSTRING) lworld_charge(L, (double)lua_rawlen(L, i));
    return luaL_checkinteger(L, i);
}

int32_t lcheck_int32(lua_State *L, int i, int32_t lo, int32_t hi, const char *msg)
{
    lua_Integer v = lcheck_integer(L, i);
    luaL_argcheck(L, v >= lo && v <= hi, i, msg);
    return (int32_t)v;
}

int lcheck_boolean(lua_State *L, int i)
{
    luaL_checktype(L, i, LUA_TBOOLEAN);
    return lua_toboolean(L, i);
}

/* Pushes "a, b, c" for the NULL-terminated list names. */
static const char *lcheck_pushnames(lua_State *L, const char *const names[])
{
    luaL_Buffer b;
    int i;
    luaL_buffinit(L, &b);
    for (i = 0; names[i] != NULL; i++) {
        if (i > 0) luaL_addstring(&b, ", ");
        luaL_addstring(&b, names[i]);
    }
    luaL_pushresult(&b);
    return lua_tostring(L, -1);
}

int lcheck_enum(lua_State *L, int i, const char *const names[], const char *what)
{
    const char *s;
    int k;
    if (lua_type(L, i) != LUA_TSTRING) luaL_typeerror(L, i, "string");
    s = lua_tostring(L, i);
    for (k = 0; names[k] != NULL; k++)
        if (strcmp(names[k], s) == 0) return k;
    return luaL_argerror(L, i, lua_pushfstring(L, "invalid %s '%s' (%s)", what, s,
                                               lcheck_pushnames(L, names)));
}

void lcheck_pushreal(lua_State *L, rg_real v)
{
    lua_pushnumber(L, (lua_Number)v);
}

void lcheck_pushvec2(lua_State *L, rg_vec2 v)
{
    lua_pushnumber(L, (lua_Number)v.x);
    lua_pushnumber(L, (lua_Number)v.y);
}

/* The library's reason names the C function first ("rg_body_set_circle: radius ..."); the
 * binding's message names the Lua call instead, so that prefix is left out. */
const char *lcheck_reason(const rg_world *w, rg_status s)
{
    const char *why = w != NULL ? rg_world_last_error(w) : "";
    const char *colon = strstr(why, ": ");
    if (why[0] == '\0') return rg_status_string(s);
    if (strncmp(why, "rg_", 3) == 0 && colon != NULL) why = colon + 2;
    return why;
}

void lcheck_copyreason(const rg_world *w, rg_status s, char *out, size_t size)
{
    size_t n = strlen(lcheck_reason(w, s));
    if (n >= size) n = size - 1;
    memcpy(out, lcheck_reason(w, s), n);
    out[n] = '\0';
}

int lcheck_status(lua_State *L, const rg_world *w, rg_status s, const char *what)
{
    if (s == RG_ERR_STALE_HANDLE) return luaL_error(L, "attempt to use a destroyed body");
    return luaL_error(L, "%s: %s", what, lcheck_reason(w, s));
}

/* ---------------------------------------------------------------- option tables */

void lcheck_option_names(lua_State *L, int t, const char *const names[], const char *what)
{
    lua_pushnil(L);
    while (lua_next(L, t) != 0) {
        const char *k;
        int i, found = 0;
        lua_pop(L, 1);
        if (lua_type(L, -1) != LUA_TSTRING)
            luaL_error(L, "%s: option names must be strings (got a %s key)", what,
                       luaL_typename(L, -1));
        k = lua_tostring(L, -1);
        for (i = 0; names[i] != NULL; i++)
            if (strcmp(names[i], k) == 0) found = 1;
        if (!found)
            luaL_error(L, "%s: unknown option '%s' (known: %s)", what, k,
                       lcheck_pushnames(L, names));
    }
}

/* Without metamethods; pushes nothing when absent. */
int lcheck_getoption(lua_State *L, int t, const char *key)
{
    lua_pushstring(L, key);
    if (lua_rawget(L, t) == LUA_TNIL) {
        lua_pop(L, 1);
        return 0;
    }
    return 1;
}

/* The option's value is on top of the stack. */
int lcheck_option_error(lua_State *L, const char *what, const char *key, const char *expected)
{
    return luaL_error(L, "%s: option '%s' must be %s (got %s)", what, key, expected,
                      luaL_typename(L, -1));
}

/* v as a message shows it: a NaN without its sign, which 0/0 sets on x86 and the C library
 * prints ("-nan"), as LuaJIT's binding words it ("nan"). */
static lua_Number lcheck_shown(lua_Number v)
{
    return v != v ? fabs(v) : v;
}

int lcheck_option_real(lua_State *L, int t, const char *key, const char *what, rg_real *out)
{
    lua_Number v;
    if (!lcheck_getoption(L, t, key)) return 0;
    if (lua_type(L, -1) != LUA_TNUMBER) lcheck_option_error(L, what, key, "a number");
    v = lua_tonumber(L, -1);
    if (!isfinite(v) || !lcheck_fits(v))
        luaL_error(L, "%s: option '%s' must be a finite number (got %f)", what, key, lcheck_shown(v));
    *out = (rg_real)v;
    lua_pop(L, 1);
    return 1;
}

int lcheck_option_integer(lua_State *L, int t, const char *key, const char *what,
                          lua_Integer lo, lua_Integer hi, lua_Integer *out)
{
    int ok = 0;
    lua_Integer v = 0;
    if (!lcheck_getoption(L, t, key)) return 0;
    if (lua_type(L, -1) == LUA_TNUMBER) v = lua_tointegerx(L, -1, &ok);
    if (!ok || v < lo || v > hi) {
        if (lua_type(L, -1) != LUA_TNUMBER) lcheck_option_error(L, what, key, "an integer");
        luaL_error(L, "%s: option '%s' must be an integer in [%I, %I]", what, key, lo, hi);
    }
    *out = v;
    lua_pop(L, 1);
    return 1;
}

/* A pair {a, b} of finite numbers: vectors, drag coefficients, box half sizes. */
int lcheck_option_pair(lua_State *L, int t, const char *key, const char *what, rg_real out[2])
{
    int i, n = 0, tab;
    if (!lcheck_getoption(L, t, key)) return 0;
    if (lua_type(L, -1) != LUA_TTABLE)
        lcheck_option_error(L, what, key, "a table {a, b} of two numbers");
    tab = lua_gettop(L);
    lua_pushnil(L);
    while (lua_next(L, tab) != 0) {
        lua_pop(L, 1);
        n++;
        if (!lua_isinteger(L, -1) || lua_tointeger(L, -1) < 1 || lua_tointeger(L, -1) > 2)
            luaL_error(L, "%s: option '%s' must be a table {a, b} of two numbers (it has key %s)",
                       what, key, luaL_tolstring(L, -1, NULL));
    }
    if (n != 2) luaL_error(L, "%s: option '%s' must be a table {a, b} of two numbers", what, key);
    for (i = 0; i < 2; i++) {
        lua_Number v;
        lua_rawgeti(L, tab, i + 1);
        if (lua_type(L, -1) != LUA_TNUMBER)
            luaL_error(L, "%s: option '%s' must be a table {a, b} of two numbers (item %d is a %s)",
                       what, key, i + 1, luaL_typename(L, -1));
        v = lua_tonumber(L, -1);
        if (!isfinite(v) || !lcheck_fits(v))
            luaL_error(L, "%s: option '%s' must hold finite numbers (item %d is %f)", what, key,
                       i + 1, lcheck_shown(v));
        out[i] = (rg_real)v;
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    return 1;
}

int lcheck_option_boolean(lua_State *L, int t, const char *key, const char *what, int *out)
{
    if (!lcheck_getoption(L, t, key)) return 0;
    if (lua_type(L, -1) != LUA_TBOOLEAN) lcheck_option_error(L, what, key, "a boolean");
    *out = lua_toboolean(L, -1);
    lua_pop(L, 1);
    return 1;
}

int lcheck_option_enum(lua_State *L, int t, const char *key, const char *what,
                       const char *const names[], int *out)
{
    const char *s;
    int i;
    if (!lcheck_getoption(L, t, key)) return 0;
    if (lua_type(L, -1) != LUA_TSTRING) lcheck_option_error(L, what, key, "a string");
    s = lua_tostring(L, -1);
    for (i = 0; names[i] != NULL; i++) {
        if (strcmp(names[i], s) == 0) {
            *out = i;
            lua_pop(L, 1);
            return 1;
        }
    }
    return luaL_error(L, "%s: option '%s' has no value '%s' (%s)", what, key, s,
                      lcheck_pushnames(L, names));
}
