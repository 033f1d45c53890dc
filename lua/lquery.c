/* lquery.c: what the Lua binding reads out of a world after a step: contact events
 * (world:events) and queries (world:raycast, raycast_all, query_aabb, query_point,
 * cast_circle, cast_box, stopped).  Bodies come back as the values scripts hold (lbody_push); the
 * bodies visited are charged to the host. */
#include "lrigid_int.h"

static void lquery_setreal(lua_State *L, rg_real v, const char *field)
{
    lcheck_pushreal(L, v);
    lua_setfield(L, -2, field);
}

/* Pushes the events of the last step, or of every step of the last advance, of the open
 * world at idx as an array of tables. */
void lquery_pushevents(lua_State *L, int idx)
{
    lworld *lw = lworld_test(L, idx);
    rg_world *w = lw != NULL ? lw->w : NULL;
    int32_t n, i;
    rg_contact_event *ev;
    if (w == NULL) luaL_error(L, "attempt to use a closed world");
    idx = lua_absindex(L, idx);
    n = rg_world_get_contact_events(w, NULL, 0);
    if (n < 0) lcheck_status(L, w, n, "events");
    ev = (rg_contact_event *)lua_newuserdatauv(L, (size_t)(n > 0 ? n : 1) * sizeof *ev, 0);
    if (n > 0) n = rg_world_get_contact_events(w, ev, n);
    lworld_charge(L, n);
    lua_createtable(L, n, 0);
    for (i = 0; i < n; i++) {
        const rg_contact_event *e = &ev[i];
        lua_createtable(L, 0, 10);
        lua_pushstring(L, e->kind == RG_CONTACT_BEGIN ? "begin" : "end");
        lua_setfield(L, -2, "kind");
        lbody_push(L, idx, e->a);
        lua_setfield(L, -2, "a");
        lbody_push(L, idx, e->b);
        lua_setfield(L, -2, "b");
        lquery_setreal(L, e->normal.x, "nx");
        lquery_setreal(L, e->normal.y, "ny");
        lquery_setreal(L, e->point.x, "x");
        lquery_setreal(L, e->point.y, "y");
        lquery_setreal(L, e->depth, "depth");
        lquery_setreal(L, e->speed, "speed");
        lua_pushboolean(L, e->sensor != 0);
        lua_setfield(L, -2, "sensor");
        lua_rawseti(L, -2, i + 1);
    }
    lua_remove(L, -2);   /* the scratch buffer */
}

static int lquery_events(lua_State *L)
{
    lworld_checkopen(L, 1);
    lua_settop(L, 1);
    lquery_pushevents(L, 1);
    return 1;
}

/* The returns of world:raycast, cast_circle and cast_box for a query that returned r:
 * body, x, y, nx, ny, fraction, or nil. */
static int lquery_returnhit(lua_State *L, int32_t r, const rg_ray_hit *hit)
{
    if (r == 0) {
        lua_pushnil(L);
        return 1;
    }
    lbody_push(L, 1, hit->body);
    lcheck_pushvec2(L, hit->point);
    lcheck_pushvec2(L, hit->normal);
    lcheck_pushreal(L, hit->fraction);
    return 6;
}

static int lquery_raycast(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    rg_vec2 o = lcheck_vec2(L, 2), d = lcheck_vec2(L, 4);
    uint32_t mask = lcheck_optmask(L, 6);
    rg_ray_hit hit;
    int32_t r = rg_world_raycast(w, o, d, mask, &hit);
    if (r < 0) return lcheck_status(L, w, r, "raycast");
    lworld_charge(L, rg_world_body_count(w));
    return lquery_returnhit(L, r, &hit);
}

static int lquery_aabb(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    rg_vec2 lo = lcheck_vec2(L, 2), hi = lcheck_vec2(L, 4);
    uint32_t mask = lcheck_optmask(L, 6);
    int32_t n = rg_world_query_aabb(w, lo, hi, mask, NULL, 0), i;
    rg_body *out;
    lua_settop(L, 1);
    if (n < 0) return lcheck_status(L, w, n, "query_aabb");
    out = (rg_body *)lua_newuserdatauv(L, (size_t)(n > 0 ? n : 1) * sizeof *out, 0);
    if (n > 0) n = rg_world_query_aabb(w, lo, hi, mask, out, n);
    lworld_charge(L, rg_world_body_count(w));
    lua_createtable(L, n, 0);
    for (i = 0; i < n; i++) {
        lbody_push(L, 1, out[i]);
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

void lquery_pushhit(lua_State *L, int world_idx, const rg_ray_hit *hit)
{
    world_idx = lua_absindex(L, world_idx);
    lua_createtable(L, 0, 6);
    lbody_push(L, world_idx, hit->body);
    lua_setfield(L, -2, "body");
    lquery_setreal(L, hit->point.x, "x");
    lquery_setreal(L, hit->point.y, "y");
    lquery_setreal(L, hit->normal.x, "nx");
    lquery_setreal(L, hit->normal.y, "ny");
    lquery_setreal(L, hit->fraction, "fraction");
}

static int lquery_raycast_all(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    rg_vec2 o = lcheck_vec2(L, 2), d = lcheck_vec2(L, 4);
    uint32_t mask = lcheck_optmask(L, 6);
    int32_t n = rg_world_raycast_all(w, o, d, mask, NULL, 0), i;
    rg_ray_hit *out;
    lua_settop(L, 1);
    if (n < 0) return lcheck_status(L, w, n, "raycast_all");
    out = (rg_ray_hit *)lua_newuserdatauv(L, (size_t)(n > 0 ? n : 1) * sizeof *out, 0);
    if (n > 0) n = rg_world_raycast_all(w, o, d, mask, out, n);
    lworld_charge(L, rg_world_body_count(w));
    lua_createtable(L, n, 0);
    for (i = 0; i < n; i++) {
        lquery_pushhit(L, 1, &out[i]);
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

static int lquery_point(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    rg_vec2 p = lcheck_vec2(L, 2);
    uint32_t mask = lcheck_optmask(L, 4);
    int32_t n = rg_world_query_point(w, p, mask, NULL, 0), i;
    rg_body *out;
    lua_settop(L, 1);
    if (n < 0) return lcheck_status(L, w, n, "query_point");
    out = (rg_body *)lua_newuserdatauv(L, (size_t)(n > 0 ? n : 1) * sizeof *out, 0);
    if (n > 0) n = rg_world_query_point(w, p, mask, out, n);
    lworld_charge(L, n);
    lua_createtable(L, n, 0);
    for (i = 0; i < n; i++) {
        lbody_push(L, 1, out[i]);
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

/* world:stopped(): the bodies the last stepping call stopped at the edge of the range. */
static int lquery_stopped(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    int32_t n = rg_world_get_stopped(w, NULL, 0), i;
    rg_body *out;
    lua_settop(L, 1);
    if (n < 0) return lcheck_status(L, w, n, "stopped");
    out = (rg_body *)lua_newuserdatauv(L, (size_t)(n > 0 ? n : 1) * sizeof *out, 0);
    if (n > 0) n = rg_world_get_stopped(w, out, n);
    lworld_charge(L, n);
    lua_createtable(L, n, 0);
    for (i = 0; i < n; i++) {
        lbody_push(L, 1, out[i]);
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

/* world:cast_circle(r, x, y, dx, dy [, mask]) and world:cast_box(hw, hh, x, y, dx, dy
 * [, mask]): the returns of world:raycast. */
static int lquery_cast(lua_State *L, int32_t shape, rg_vec2 size, int at, const char *what)
{
    rg_world *w = lworld_checkopen(L, 1);
    rg_vec2 o = lcheck_vec2(L, at), d = lcheck_vec2(L, at + 2);
    uint32_t mask = lcheck_optmask(L, at + 4);
    rg_ray_hit hit;
    int32_t r = rg_world_cast_shape(w, shape, size, o, d, mask, &hit);
    if (r < 0) return lcheck_status(L, w, r, what);
    lworld_charge(L, rg_world_body_count(w));
    return lquery_returnhit(L, r, &hit);
}

static int lquery_cast_circle(lua_State *L)
{
    rg_vec2 size = { lcheck_real(L, 2), 0 };
    return lquery_cast(L, RG_SHAPE_CIRCLE, size, 3, "cast_circle");
}

static int lquery_cast_box(lua_State *L)
{
    rg_vec2 size = lcheck_vec2(L, 2);
    return lquery_cast(L, RG_SHAPE_AABB, size, 4, "cast_box");
}

const luaL_Reg lquery_world_methods[] = {
    { "events", lquery_events },
    { "raycast", lquery_raycast },
    { "raycast_all", lquery_raycast_all },
    { "query_aabb", lquery_aabb },
    { "query_point", lquery_point },
    { "stopped", lquery_stopped },
    { "cast_circle", lquery_cast_circle },
    { "cast_box", lquery_cast_box },
    { NULL, NULL }
};
