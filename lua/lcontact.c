/* lcontact.c: the gameplay methods of a body: its contacts, one-way shapes, passing through
 * another body, and the character mover (body:move). */
#include "lrigid_int.h"

static void lcontact_setreal(lua_State *L, rg_real v, const char *field)
{
    lcheck_pushreal(L, v);
    lua_setfield(L, -2, field);
}

/* body:contacts() --> { { other, nx, ny, x, y, separation, normal_impulse,
 * tangent_impulse, sensor }... } after the last step, in ascending order of other. */
static int lcontact_contacts(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    rg_world *w = lbody_world_of(L, b);
    int32_t n = rg_body_get_contacts(w, b->h, NULL, 0), i;
    rg_contact *c;
    lua_settop(L, 1);
    if (n < 0) return lcheck_status(L, w, n, "contacts");
    lua_getiuservalue(L, 1, LBODY_UV_WORLD);   /* 2: the world value */
    c = (rg_contact *)lua_newuserdatauv(L, (size_t)(n > 0 ? n : 1) * sizeof *c, 0);
    if (n > 0) n = rg_body_get_contacts(w, b->h, c, n);
    lworld_charge(L, n);
    lua_createtable(L, n, 0);
    for (i = 0; i < n; i++) {
        lua_createtable(L, 0, 9);
        lbody_push(L, 2, c[i].other);
        lua_setfield(L, -2, "other");
        lcontact_setreal(L, c[i].normal.x, "nx");
        lcontact_setreal(L, c[i].normal.y, "ny");
        lcontact_setreal(L, c[i].point.x, "x");
        lcontact_setreal(L, c[i].point.y, "y");
        lcontact_setreal(L, c[i].separation, "separation");
        lcontact_setreal(L, c[i].normal_impulse, "normal_impulse");
        lcontact_setreal(L, c[i].tangent_impulse, "tangent_impulse");
        lua_pushboolean(L, c[i].sensor != 0);
        lua_setfield(L, -2, "sensor");
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

static int lcontact_set_one_way(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    rg_vec2 n = lcheck_vec2(L, 2);
    rg_world *w = lbody_world_of(L, b);
    LCHECK(L, w, rg_body_set_one_way(w, b->h, n), "set_one_way");
    return 0;
}

static int lcontact_one_way(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    rg_world *w = lbody_world_of(L, b);
    rg_vec2 n;
    LCHECK(L, w, rg_body_get_one_way(w, b->h, &n), "one_way");
    lcheck_pushvec2(L, n);
    return 2;
}

static int lcontact_pass_through(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    lbody *o = lbody_test(L, 2);
    if (o == NULL) return luaL_typeerror(L, 2, LBODY_MT);
    if (o->world != b->world) return luaL_argerror(L, 2, "a body of the same world");
    rg_world *w = lbody_world_of(L, b);
    LCHECK(L, w, rg_body_pass_through(w, b->h, lbody_handle(L, o)), "pass_through");
    return 0;
}

static const char *const lcontact_responses[] = { "slide", "touch", "cross", NULL };
static const char *const lcontact_move_options[] = { "mask", "response", NULL };

/* Room for the hits of one move: SLIDE meets at most 8 surfaces and TOUCH one; a CROSS that
 * crosses more is made again with room for all. */
#define LCONTACT_HITS 16

/* body:move(tx, ty [, { mask =, response = "slide" | "touch" | "cross" }]) --> x, y, hits.
 * A CROSS lands on its target exactly, so one back to the start restores the position bit
 * for bit before the second try, and keeps the position rendering interpolates from
 * (rg_body_set_position would not). */
static int lcontact_move(lua_State *L)
{
    const char *what = "move";
    lbody *b = lbody_check(L, 1);
    rg_world *w = lbody_world_of(L, b);
    rg_vec2 target = lcheck_vec2(L, 2), start, end;
    lua_Integer mask = 0xFFFFFFFF;
    int response = RG_MOVE_SLIDE;
    int32_t n = 0, cap = LCONTACT_HITS, i;
    rg_ray_hit room[LCONTACT_HITS], *hits = room;
    if (!lua_isnoneornil(L, 4)) {
        luaL_checktype(L, 4, LUA_TTABLE);
        lcheck_option_names(L, 4, lcontact_move_options, what);
        lcheck_option_integer(L, 4, "mask", what, 0, 0xFFFFFFFF, &mask);
        lcheck_option_enum(L, 4, "response", what, lcontact_responses, &response);
    }
    lua_settop(L, 1);
    lua_getiuservalue(L, 1, LBODY_UV_WORLD);   /* 2: the world value */
    LCHECK(L, w, rg_body_get_position(w, b->h, &start), what);
    LCHECK(L, w, rg_body_move(w, b->h, target, (uint32_t)mask, response, &end, hits, cap, &n),
           what);
    if (n > cap) {
        LCHECK(L, w, rg_body_move(w, b->h, start, 0, RG_MOVE_CROSS, NULL, NULL, 0, NULL), what);
        hits = (rg_ray_hit *)lua_newuserdatauv(L, (size_t)n * sizeof *hits, 0);
        cap = n;
        LCHECK(L, w, rg_body_move(w, b->h, target, (uint32_t)mask, response, &end, hits, cap, &n),
               what);
        if (n > cap) n = cap;   /* the same path crosses the same shapes */
    }
    lworld_charge(L, rg_world_body_count(w));
    lcheck_pushvec2(L, end);
    lua_createtable(L, n, 0);
    for (i = 0; i < n; i++) {
        lquery_pushhit(L, 2, &hits[i]);
        lua_rawseti(L, -2, i + 1);
    }
    return 3;
}

const luaL_Reg lcontact_methods[] = {
    { "contacts", lcontact_contacts },
    { "set_one_way", lcontact_set_one_way },
    { "one_way", lcontact_one_way },
    { "pass_through", lcontact_pass_through },
    { "move", lcontact_move },
    { NULL, NULL }
};
