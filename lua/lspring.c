/* lspring.c: Lua spring values: world:spring{...}, spring:destroy(), spring:is_valid().
 *
 * The world's `springs` uservalue maps handles to spring values weakly, for one case: a
 * restore can take the world back to before a spring was made, and the world then gives
 * that handle out again; the old value is retired then (destroyed for good), so that it
 * never names the new spring. */
#include "lrigid_int.h"

#define LSPRING_UV_WORLD 1   /* the world value, which keeps the world alive */

typedef struct lspring {
    uint64_t h;
    lworld *world;
    int retired;
} lspring;

static const char *const lspring_options[] = { "a", "b", "anchor", "rest_length", "stiffness",
                                               "damping", NULL };

static lbody *lspring_option_body(lua_State *L, int t, const char *key, const char *what,
                                  const lworld *lw)
{
    lbody *b;
    if (!lcheck_getoption(L, t, key)) return NULL;
    b = lbody_test(L, -1);
    if (b == NULL) lcheck_option_error(L, what, key, "a body");
    if (b->world != lw) luaL_error(L, "%s: option '%s' is a body of another world", what, key);
    lbody_handle(L, b);
    lua_pop(L, 1);
    return b;
}

static int lspring_create(lua_State *L)
{
    const char *what = "world:spring";
    rg_world *w = lworld_checkopen(L, 1);
    const lworld *lw = (const lworld *)lua_touserdata(L, 1);
    rg_real anchor[2] = { 0, 0 }, rest = 0, k = 0, damping = 0;
    lbody *a, *b;
    lspring *s;
    uint64_t h = 0;
    luaL_checktype(L, 2, LUA_TTABLE);
    lua_settop(L, 2);
    lcheck_option_names(L, 2, lspring_options, what);
    a = lspring_option_body(L, 2, "a", what, lw);
    b = lspring_option_body(L, 2, "b", what, lw);
    if (a == NULL) luaL_error(L, "%s: option 'a' (a body) is required", what);
    if (!lcheck_option_pair(L, 2, "anchor", what, anchor) && b == NULL)
        luaL_error(L, "%s: option 'anchor' {x, y} is required when there is no body 'b'", what);
    lcheck_option_real(L, 2, "rest_length", what, &rest);
    if (!lcheck_option_real(L, 2, "stiffness", what, &k))
        luaL_error(L, "%s: option 'stiffness' is required", what);
    lcheck_option_real(L, 2, "damping", what, &damping);
    s = (lspring *)lua_newuserdatauv(L, sizeof *s, 1);
    s->h = 0;
    s->world = (lworld *)lua_touserdata(L, 1);
    s->retired = 0;
    luaL_setmetatable(L, LSPRING_MT);
    lua_pushvalue(L, 1);
    lua_setiuservalue(L, -2, LSPRING_UV_WORLD);
    lua_getiuservalue(L, 1, LWORLD_UV_SPRINGS);   /* 4 */
    lua_pushcfunction(L, lworld_rawset3);
    lua_pushvalue(L, 4);
    LCHECK(L, w, rg_spring_create(w, a->h, b != NULL ? b->h : 0,
                                  (rg_vec2){ anchor[0], anchor[1] }, rest, k, damping, &h),
           what);
    /* The value that had this handle before is retired (see the top).  The insert may fail
     * under a memory cap, and then the spring must not stay behind. */
    lua_pushinteger(L, (lua_Integer)h);
    if (lua_rawget(L, 4) == LUA_TUSERDATA) ((lspring *)lua_touserdata(L, -1))->retired = 1;
    lua_pop(L, 1);
    lua_pushinteger(L, (lua_Integer)h);
    lua_pushvalue(L, 3);
    if (lua_pcall(L, 3, 0, 0) != LUA_OK) {
        rg_spring_destroy(w, h);
        return lua_error(L);
    }
    s->h = h;
    lua_settop(L, 3);
    return 1;
}

static lspring *lspring_check(lua_State *L, int i)
{
    return (lspring *)luaL_checkudata(L, i, LSPRING_MT);
}

static int lspring_live(const lspring *s)
{
    return s->world->w != NULL && !s->retired && rg_spring_is_valid(s->world->w, s->h);
}

static int lspring_destroy(lua_State *L)
{
    lspring *s = lspring_check(L, 1);
    lua_pushboolean(L, lspring_live(s) && rg_spring_destroy(s->world->w, s->h) == RG_OK);
    return 1;
}

static int lspring_is_valid(lua_State *L)
{
    lua_pushboolean(L, lspring_live(lspring_check(L, 1)));
    return 1;
}

static int lspring_tostring(lua_State *L)
{
    int live = lspring_live(lspring_check(L, 1));
    lua_pushfstring(L, "rigid.spring (%s)", live ? "live" : "destroyed");
    return 1;
}

const luaL_Reg lspring_world_methods[] = {
    { "spring", lspring_create },
    { NULL, NULL }
};

const luaL_Reg lspring_methods[] = {
    { "destroy", lspring_destroy },
    { "is_valid", lspring_is_valid },
    { NULL, NULL }
};

const luaL_Reg lspring_meta[] = {
    { "__tostring", lspring_tostring },
    { "__close", lspring_destroy },
    { NULL, NULL }
};
