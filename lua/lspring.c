/* lspring.c: Lua spring values: world:spring{...}, spring:destroy(), spring:is_valid(). */
#include "lrigid_int.h"

#define LSPRING_UV_WORLD 1   /* the world value, which keeps the world alive */

typedef struct lspring {
    uint64_t h;
    lworld *world;
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
    luaL_setmetatable(L, LSPRING_MT);
    lua_pushvalue(L, 1);
    lua_setiuservalue(L, -2, LSPRING_UV_WORLD);
    LCHECK(L, rg_spring_create(w, a->h, b != NULL ? b->h : 0, (rg_vec2){ anchor[0], anchor[1] },
                               rest, k, damping, &h),
           what,
           "rest_length, stiffness and damping must be >= 0, and a and b distinct live bodies");
    s->h = h;
    return 1;
}

static lspring *lspring_check(lua_State *L, int i)
{
    return (lspring *)luaL_checkudata(L, i, LSPRING_MT);
}

static int lspring_live(const lspring *s)
{
    return s->world->w != NULL && rg_spring_is_valid(s->world->w, s->h);
}

static int lspring_destroy(lua_State *L)
{
    lspring *s = lspring_check(L, 1);
    lua_pushboolean(L, s->world->w != NULL && rg_spring_destroy(s->world->w, s->h) == RG_OK);
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
