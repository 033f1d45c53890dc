/* lrigid.c: the Lua 5.4 binding of rigid: worlds, bodies and springs as userdata.
 *
 * The contract is shared/ABI.md (section Lua); this is all of it, extensions included.
 * Units are SI.  Numbers must be numbers (not numeric strings) and finite; option tables
 * accept only the names listed; a destroyed body raises "attempt to use a destroyed body".
 *
 *   rigid.version, rigid.real_size (4 or 8), rigid.collision (boolean)
 *   rigid.world{ gravity = {x, y}, wind = {x, y}, integrator = "explicit" | "semi_implicit"
 *                | "verlet" | "rk4", dt = 1/60, max_steps = 8 }          -- all optional
 *   world:body{ type = "static" | "kinematic" | "dynamic", mass, x, y, vx, vy, gravity_scale,
 *               drag = {linear, quadratic}, surface_friction = {mu, normal_force},
 *               min_speed, max_speed, user_data (integer), name (string, for pictures),
 *               circle = r | aabb = {hw, hh}, restitution, friction, sensor (boolean),
 *               category, mask }                                        --> body
 *   world:spring{ a = body, b = body | anchor = {x, y}, rest_length, stiffness, damping }
 *   world:step(dt)  world:advance(frame_time) --> steps  world:alpha()
 *   world:gravity() / set_gravity(x, y)   world:wind() / set_wind(x, y)
 *   world:integrator() / set_integrator(name)   world:fixed_step() / set_fixed_step(dt [, max])
 *   world:bodies() --> live bodies in creation order   world:body_count()  world:spring_count()
 *   world:events() --> { kind = "begin" | "end", a, b, nx, ny, x, y, depth, speed, sensor }...
 *                      (of the last world:step, or of every step of the last world:advance)
 *   world:raycast(x, y, dx, dy [, mask]) --> body, hit_x, hit_y, nx, ny, fraction | nil
 *   world:query_aabb(x0, y0, x1, y1 [, mask]) --> { body... }
 *   world:set_sleeping(on) / sleeping()  set_sleep_thresholds(speed, time)
 *   world:set_solver_iterations(velocity [, relax])  set_contact_tuning(slop, bias_rate,
 *   max_push, restitution_threshold)  set_continuous(on)  awake_body_count()  touching_count()
 *   world:close() (also <close> and garbage collection)  world:is_open()
 *   body:position() / set_position(x, y)   body:velocity() / set_velocity(vx, vy)
 *   body:apply_force(fx, fy)  body:apply_impulse(ix, iy)  body:acceleration()
 *   body:interpolated_position()  body:type()  body:mass() / set_mass(m)
 *   body:set_gravity_scale(s)  set_drag(linear [, quadratic])  set_surface_friction(mu, n)
 *   body:set_speed_limits(min [, max])  user_data() / set_user_data(i)  name()  world()  id()
 *   body:set_circle(r)  set_aabb(hw, hh)  clear_shape()  shape() --> "circle", r | "aabb",
 *   hw, hh | "none"   restitution() / set_restitution(e)  friction() / set_friction(mu)
 *   is_sensor() / set_sensor(on)  filter() / set_filter(category, mask)  grounded()
 *   is_awake()  wake()  is_valid()  destroy() (also <close>)
 *   spring:destroy()  spring:is_valid()
 * Collision methods exist when rigid.collision is true.  A body is one Lua value wherever it
 * appears (world:body, world:bodies, events, queries), also after it is destroyed, for as
 * long as anyone holds it; a world stays alive while any of its bodies is held. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lauxlib.h>
#include <lua.h>

#include "lrigid.h"

#define WORLD_MT  "rigid.world"
#define BODY_MT   "rigid.body"
#define SPRING_MT "rigid.spring"

/* Uservalues of a world: the bodies created through Lua, by handle.  `live` holds every live
 * one strongly (a body lives in its world whether or not a script keeps its value), `dead`
 * holds destroyed ones weakly, so a body keeps its identity for as long as anyone holds it. */
#define UV_LIVE 1
#define UV_DEAD 2
/* Uservalues of a body: its world value (which keeps the world alive) and its name. */
#define UV_WORLD 1
#define UV_NAME  2

typedef struct lworld {
    rg_world *w;             /* NULL once closed */
    lua_Integer next_serial;
} lworld;

typedef struct lbody {
    rg_body h;
    lworld *world;           /* kept alive by uservalue UV_WORLD */
    lua_Integer serial;
    int32_t type;
    int32_t shape;
    double size[2];
    int32_t sensor;
} lbody;

typedef struct lspring {
    uint64_t h;
    lworld *world;
} lspring;

static const char hooks_key = 'h';

/* ---------------------------------------------------------------- helpers */

static const lrigid_hooks *gethooks(lua_State *L)
{
    const lrigid_hooks *h;
    lua_rawgetp(L, LUA_REGISTRYINDEX, &hooks_key);
    h = (const lrigid_hooks *)lua_touserdata(L, -1);
    lua_pop(L, 1);
    return h;
}

void lrigid_sethooks(lua_State *L, const lrigid_hooks *hooks)
{
    if (hooks != NULL) {
        /* The registry holds a pointer to the caller's struct; lightuserdata of a pointer
         * to const needs the const dropped, and the binding never writes through it. */
        union { const lrigid_hooks *c; void *p; } u;
        u.c = hooks;
        lua_pushlightuserdata(L, u.p);
    } else {
        lua_pushnil(L);
    }
    lua_rawsetp(L, LUA_REGISTRYINDEX, &hooks_key);
}

static void charge(lua_State *L, double units)
{
    const lrigid_hooks *h = gethooks(L);
    if (h != NULL && h->charge != NULL) h->charge(L, h->ud, units);
}

/* Handles are Lua integer keys; the conversion wraps modulo 2^64 on every two's complement
 * target, which is all that matters here (it is a bijection). */
static lua_Integer handle_key(uint64_t h)
{
    return (lua_Integer)h;
}

/* A number argument that is finite (numeric strings are refused: scripts get told). */
static lua_Number checkfinite(lua_State *L, int i)
{
    lua_Number v;
    if (lua_type(L, i) != LUA_TNUMBER) luaL_typeerror(L, i, "number");
    v = lua_tonumber(L, i);
    if (!isfinite(v)) luaL_argerror(L, i, v != v ? "finite number expected, got nan"
                                                 : "finite number expected, got inf");
    return v;
}

static int real_fits(lua_Number v)
{
#ifdef RG_DOUBLE
    (void)v;
    return 1;
#else
    return fabs(v) <= (lua_Number)FLT_MAX;
#endif
}

static rg_real checkreal(lua_State *L, int i)
{
    lua_Number v = checkfinite(L, i);
    if (!real_fits(v)) luaL_argerror(L, i, "number out of range for rg_real (float)");
    return (rg_real)v;
}

static rg_real optreal(lua_State *L, int i, rg_real def)
{
    return lua_isnoneornil(L, i) ? def : checkreal(L, i);
}

#ifdef LRIGID_COLLISION
static uint32_t checkmask(lua_State *L, int i)
{
    int ok = 0;
    lua_Integer v = 0;
    if (lua_type(L, i) == LUA_TNUMBER) v = lua_tointegerx(L, i, &ok);
    if (!ok || v < 0 || v > 0xFFFFFFFF)
        luaL_argerror(L, i, "integer in [0, 0xFFFFFFFF] expected");
    return (uint32_t)v;
}
#endif

static void pushreal(lua_State *L, rg_real v)
{
    lua_pushnumber(L, (lua_Number)v);
}

/* Raises for a failed call: names the call and says what was wrong. */
static int status_error(lua_State *L, rg_status s, const char *what, const char *hint)
{
    if (s == RG_ERR_STALE_HANDLE) return luaL_error(L, "attempt to use a destroyed body");
    if (s == RG_ERR_OUT_OF_MEMORY) return luaL_error(L, "%s: not enough memory", what);
    if (s == RG_ERR_INVALID_ARGUMENT && hint != NULL)
        return luaL_error(L, "%s: invalid argument (%s)", what, hint);
    return luaL_error(L, "%s: %s", what, rg_status_string(s));
}

#define CHECK(L, call, what, hint)                                              \
    do {                                                                        \
        rg_status st_ = (call);                                                 \
        if (st_ != RG_OK) status_error((L), st_, (what), (hint));               \
    } while (0)

static int checkoption(lua_State *L, int i, const char *const names[], const char *what)
{
    const char *s;
    int k;
    if (lua_type(L, i) != LUA_TSTRING) luaL_typeerror(L, i, "string");
    s = lua_tostring(L, i);
    for (k = 0; names[k] != NULL; k++)
        if (strcmp(names[k], s) == 0) return k;
    return luaL_argerror(L, i, lua_pushfstring(L, "invalid %s '%s'", what, s));
}

static const char *const integrator_names[] = { "explicit", "semi_implicit", "verlet", "rk4",
                                                NULL };
static const char *const type_names[] = { "static", "kinematic", "dynamic", NULL };

/* ---------------------------------------------------------------- option tables */

/* Every key of the table at t must be one of names: a misspelt option is an error, not a
 * silent default. */
static void check_option_names(lua_State *L, int t, const char *const names[], const char *what)
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
        if (!found) {
            luaL_Buffer b;
            luaL_buffinit(L, &b);
            for (i = 0; names[i] != NULL; i++) {
                if (i > 0) luaL_addstring(&b, ", ");
                luaL_addstring(&b, names[i]);
            }
            luaL_pushresult(&b);
            luaL_error(L, "%s: unknown option '%s' (known: %s)", what, k, lua_tostring(L, -1));
        }
    }
}

/* Pushes t[key] without metamethods; returns 0 (and pushes nothing) when absent. */
static int getoption(lua_State *L, int t, const char *key)
{
    lua_pushstring(L, key);
    if (lua_rawget(L, t) == LUA_TNIL) {
        lua_pop(L, 1);
        return 0;
    }
    return 1;
}

static int option_error(lua_State *L, const char *what, const char *key, const char *expected)
{
    return luaL_error(L, "%s: option '%s' must be %s (got %s)", what, key, expected,
                      luaL_typename(L, -1));
}

static int option_real(lua_State *L, int t, const char *key, const char *what, rg_real *out)
{
    lua_Number v;
    if (!getoption(L, t, key)) return 0;
    if (lua_type(L, -1) != LUA_TNUMBER) option_error(L, what, key, "a number");
    v = lua_tonumber(L, -1);
    if (!isfinite(v) || !real_fits(v))
        luaL_error(L, "%s: option '%s' must be a finite number (got %f)", what, key, v);
    *out = (rg_real)v;
    lua_pop(L, 1);
    return 1;
}

static int option_integer(lua_State *L, int t, const char *key, const char *what,
                          lua_Integer lo, lua_Integer hi, lua_Integer *out)
{
    int ok = 0;
    lua_Integer v = 0;
    if (!getoption(L, t, key)) return 0;
    if (lua_type(L, -1) == LUA_TNUMBER) v = lua_tointegerx(L, -1, &ok);
    if (!ok || v < lo || v > hi) {
        if (lua_type(L, -1) != LUA_TNUMBER) option_error(L, what, key, "an integer");
        luaL_error(L, "%s: option '%s' must be an integer in [%I, %I]", what, key, lo, hi);
    }
    *out = v;
    lua_pop(L, 1);
    return 1;
}

/* A pair {a, b} of finite numbers: vectors, drag coefficients, box half sizes. */
static int option_pair(lua_State *L, int t, const char *key, const char *what, rg_real out[2])
{
    int i, n = 0, tab;
    if (!getoption(L, t, key)) return 0;
    if (lua_type(L, -1) != LUA_TTABLE) option_error(L, what, key, "a table {a, b} of two numbers");
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
        if (!isfinite(v) || !real_fits(v))
            luaL_error(L, "%s: option '%s' must hold finite numbers (item %d is %f)", what, key,
                       i + 1, v);
        out[i] = (rg_real)v;
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    return 1;
}

#ifdef LRIGID_COLLISION
static int option_boolean(lua_State *L, int t, const char *key, const char *what, int *out)
{
    if (!getoption(L, t, key)) return 0;
    if (lua_type(L, -1) != LUA_TBOOLEAN) option_error(L, what, key, "a boolean");
    *out = lua_toboolean(L, -1);
    lua_pop(L, 1);
    return 1;
}
#endif

static int option_name(lua_State *L, int t, const char *key, const char *what,
                       const char *const names[], int *out)
{
    const char *s;
    int i;
    if (!getoption(L, t, key)) return 0;
    if (lua_type(L, -1) != LUA_TSTRING) option_error(L, what, key, "a string");
    s = lua_tostring(L, -1);
    for (i = 0; names[i] != NULL; i++) {
        if (strcmp(names[i], s) == 0) {
            *out = i;
            lua_pop(L, 1);
            return 1;
        }
    }
    return luaL_error(L, "%s: option '%s' has no value '%s'", what, key, s);
}

/* ---------------------------------------------------------------- worlds */

static lworld *toworld(lua_State *L, int i)
{
    lworld *lw = (lworld *)luaL_testudata(L, i, WORLD_MT);
    return lw;
}

/* Methods carry the world metatable as upvalue 1: a pointer compare, no registry lookup. */
static lworld *checkworld(lua_State *L, int i)
{
    lworld *lw = (lworld *)lua_touserdata(L, i);
    if (lw != NULL && lua_getmetatable(L, i)) {
        int same = lua_rawequal(L, -1, lua_upvalueindex(1));
        lua_pop(L, 1);
        if (same) return lw;
    }
    luaL_typeerror(L, i, WORLD_MT);
    return NULL;
}

static rg_world *checkopenworld(lua_State *L, int i)
{
    lworld *lw = checkworld(L, i);
    if (lw->w == NULL) luaL_error(L, "attempt to use a closed world");
    return lw->w;
}

rg_world *lrigid_toworld(lua_State *L, int idx)
{
    lworld *lw = toworld(L, idx);
    return lw != NULL ? lw->w : NULL;
}

void lrigid_pushbodies(lua_State *L, int idx)
{
    lua_getiuservalue(L, idx, UV_LIVE);
}

static void world_after_step(lua_State *L, int idx, rg_world *w, int steps)
{
    const lrigid_hooks *h;
    if (steps <= 0) return;
    h = gethooks(L);
    if (h == NULL) return;
    if (h->charge != NULL)
        h->charge(L, h->ud, (double)steps * (double)(rg_world_body_count(w) + 1));
    if (h->after_step != NULL) h->after_step(L, h->ud, idx, steps);
}

static const char *const world_options[] = { "gravity", "wind", "integrator", "dt", "max_steps",
                                             NULL };

static int l_world(lua_State *L)
{
    const char *what = "rigid.world";
    rg_real gravity[2], wind[2], dt = 0;
    int has_gravity = 0, has_wind = 0, has_integrator = 0, has_dt = 0, has_max = 0;
    int integrator = RG_INTEGRATOR_SEMI_IMPLICIT_EULER;
    lua_Integer max_steps = 8;
    lworld *lw;
    rg_world *w = NULL;
    rg_status st;
    void *alloc_ud;
    lua_Alloc alloc;

    if (!lua_isnoneornil(L, 1)) {
        luaL_checktype(L, 1, LUA_TTABLE);
        check_option_names(L, 1, world_options, what);
        has_gravity = option_pair(L, 1, "gravity", what, gravity);
        has_wind = option_pair(L, 1, "wind", what, wind);
        has_integrator = option_name(L, 1, "integrator", what, integrator_names, &integrator);
        has_dt = option_real(L, 1, "dt", what, &dt);
        has_max = option_integer(L, 1, "max_steps", what, 1, 0x7FFFFFFF, &max_steps);
        if (has_dt && !(dt > 0)) luaL_error(L, "%s: option 'dt' must be > 0", what);
    }
    /* Everything that allocates on the Lua side comes first, so that a memory error cannot
     * leave a world nobody owns. */
    lw = (lworld *)lua_newuserdatauv(L, sizeof *lw, 2);
    lw->w = NULL;
    lw->next_serial = 1;
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_setmetatable(L, -2);
    lua_newtable(L);
    lua_setiuservalue(L, -2, UV_LIVE);
    lua_newtable(L);
    lua_newtable(L);
    lua_pushliteral(L, "v");
    lua_setfield(L, -2, "__mode");
    lua_setmetatable(L, -2);
    lua_setiuservalue(L, -2, UV_DEAD);

    /* The world allocates through the state's allocator, so a host's memory cap counts it. */
    alloc = lua_getallocf(L, &alloc_ud);
    st = rg_world_create_with_allocator(alloc, alloc_ud, &w);
    if (st != RG_OK) return status_error(L, st, what, NULL);
    if (st == RG_OK && has_gravity) st = rg_world_set_gravity(w, (rg_vec2){ gravity[0], gravity[1] });
    if (st == RG_OK && has_wind) st = rg_world_set_wind(w, (rg_vec2){ wind[0], wind[1] });
    if (st == RG_OK && has_integrator) st = rg_world_set_integrator(w, integrator);
    if (st == RG_OK && (has_dt || has_max)) {
        rg_real cur_dt;
        int32_t cur_max;
        st = rg_world_get_fixed_step(w, &cur_dt, &cur_max);
        if (st == RG_OK)
            st = rg_world_set_fixed_step(w, has_dt ? dt : cur_dt,
                                         has_max ? (int32_t)max_steps : cur_max);
    }
    if (st != RG_OK) {
        rg_world_destroy(w);
        return status_error(L, st, what, NULL);
    }
    lw->w = w;
    return 1;
}

static int world_close(lua_State *L)
{
    lworld *lw = checkworld(L, 1);
    rg_world_destroy(lw->w);
    lw->w = NULL;
    return 0;
}

static int world_gc(lua_State *L)
{
    lworld *lw = (lworld *)lua_touserdata(L, 1);
    if (lw != NULL) {
        rg_world_destroy(lw->w);
        lw->w = NULL;
    }
    return 0;
}

static int world_tostring(lua_State *L)
{
    lworld *lw = checkworld(L, 1);
    if (lw->w == NULL) lua_pushliteral(L, "rigid.world (closed)");
    else
        lua_pushfstring(L, "rigid.world (%d bodies, %d springs)", (int)rg_world_body_count(lw->w),
                        (int)rg_world_spring_count(lw->w));
    return 1;
}

static int world_is_open(lua_State *L)
{
    lua_pushboolean(L, checkworld(L, 1)->w != NULL);
    return 1;
}

static int world_step(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    rg_real dt = checkreal(L, 2);
    CHECK(L, rg_world_step(w, dt), "step", "dt must be > 0");
    world_after_step(L, 1, w, 1);
    return 0;
}

static int world_advance(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    rg_real frame_time = checkreal(L, 2);
    int32_t steps = 0;
    CHECK(L, rg_world_advance(w, frame_time, &steps), "advance", "frame_time must be >= 0");
    world_after_step(L, 1, w, steps);
    lua_pushinteger(L, steps);
    return 1;
}

static int world_alpha(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    rg_real a = 0;
    CHECK(L, rg_world_get_alpha(w, &a), "alpha", NULL);
    pushreal(L, a);
    return 1;
}

static int world_gravity(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    rg_vec2 g;
    CHECK(L, rg_world_get_gravity(w, &g), "gravity", NULL);
    pushreal(L, g.x);
    pushreal(L, g.y);
    return 2;
}

static int world_set_gravity(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    rg_vec2 g = { checkreal(L, 2), checkreal(L, 3) };
    CHECK(L, rg_world_set_gravity(w, g), "set_gravity", NULL);
    return 0;
}

static int world_wind(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    rg_vec2 f;
    CHECK(L, rg_world_get_wind(w, &f), "wind", NULL);
    pushreal(L, f.x);
    pushreal(L, f.y);
    return 2;
}

static int world_set_wind(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    rg_vec2 f = { checkreal(L, 2), checkreal(L, 3) };
    CHECK(L, rg_world_set_wind(w, f), "set_wind", NULL);
    return 0;
}

static int world_integrator(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    int32_t i = 0;
    CHECK(L, rg_world_get_integrator(w, &i), "integrator", NULL);
    if (i < 0 || i > 3) return luaL_error(L, "integrator: unknown integrator %d", (int)i);
    lua_pushstring(L, integrator_names[i]);
    return 1;
}

static int world_set_integrator(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    int i = checkoption(L, 2, integrator_names, "integrator");
    CHECK(L, rg_world_set_integrator(w, i), "set_integrator", NULL);
    return 0;
}

static int world_fixed_step(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    rg_real dt = 0;
    int32_t max = 0;
    CHECK(L, rg_world_get_fixed_step(w, &dt, &max), "fixed_step", NULL);
    pushreal(L, dt);
    lua_pushinteger(L, max);
    return 2;
}

static int world_set_fixed_step(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    rg_real dt = checkreal(L, 2), cur_dt;
    int32_t max;
    CHECK(L, rg_world_get_fixed_step(w, &cur_dt, &max), "set_fixed_step", NULL);
    if (!lua_isnoneornil(L, 3)) {
        lua_Integer m = luaL_checkinteger(L, 3);
        luaL_argcheck(L, m >= 1 && m <= 0x7FFFFFFF, 3, "max_steps must be >= 1");
        max = (int32_t)m;
    }
    CHECK(L, rg_world_set_fixed_step(w, dt, max), "set_fixed_step", "dt must be > 0");
    return 0;
}

static int world_body_count(lua_State *L)
{
    lua_pushinteger(L, rg_world_body_count(checkopenworld(L, 1)));
    return 1;
}

static int world_spring_count(lua_State *L)
{
    lua_pushinteger(L, rg_world_spring_count(checkopenworld(L, 1)));
    return 1;
}

/* ---------------------------------------------------------------- bodies */

static lbody *checkbody(lua_State *L, int i)
{
    lbody *b = (lbody *)lua_touserdata(L, i);
    if (b != NULL && lua_getmetatable(L, i)) {
        int same = lua_rawequal(L, -1, lua_upvalueindex(1));
        lua_pop(L, 1);
        if (same) return b;
    }
    luaL_typeerror(L, i, BODY_MT);
    return NULL;
}

static rg_world *bodyworld(lua_State *L, const lbody *b)
{
    if (b->world->w == NULL) luaL_error(L, "attempt to use a body of a closed world");
    return b->world->w;
}

int lrigid_tobody(lua_State *L, int idx, lrigid_body_info *out)
{
    lbody *b = (lbody *)luaL_testudata(L, idx, BODY_MT);
    if (b == NULL) return 0;
    out->handle = b->h;
    out->serial = b->serial;
    out->type = b->type;
    out->shape = b->shape;
    out->size[0] = b->size[0];
    out->size[1] = b->size[1];
    out->sensor = b->sensor;
#ifdef LRIGID_COLLISION
    {
        int32_t kind, sensor;
        rg_vec2 half;
        if (b->world->w != NULL && rg_body_get_shape(b->world->w, b->h, &kind, &half) == RG_OK &&
            rg_body_is_sensor(b->world->w, b->h, &sensor) == RG_OK) {
            out->shape = kind == RG_SHAPE_CIRCLE ? LRIGID_SHAPE_CIRCLE
                         : kind == RG_SHAPE_AABB ? LRIGID_SHAPE_AABB : LRIGID_SHAPE_NONE;
            out->size[0] = (double)half.x;
            out->size[1] = (double)half.y;
            out->sensor = sensor;
        }
    }
#endif
    lua_getiuservalue(L, idx, UV_NAME);
    out->name = lua_tostring(L, -1);   /* the body value holds the string */
    lua_pop(L, 1);
    return 1;
}

/* A new body value for handle h of the world at world_idx; the body metatable is pushed by
 * the caller and stays below. */
static lbody *newbody(lua_State *L, int world_idx, rg_body h)
{
    lworld *lw = (lworld *)lua_touserdata(L, world_idx);
    lbody *b = (lbody *)lua_newuserdatauv(L, sizeof *b, 2);
    memset(b, 0, sizeof *b);
    b->h = h;
    b->world = lw;
    b->type = -1;
    luaL_setmetatable(L, BODY_MT);
    lua_pushvalue(L, world_idx);
    lua_setiuservalue(L, -2, UV_WORLD);
    return b;
}

void lrigid_pushbody(lua_State *L, int world_idx, rg_body h)
{
    lworld *lw;
    world_idx = lua_absindex(L, world_idx);
    lw = (lworld *)lua_touserdata(L, world_idx);
    lua_getiuservalue(L, world_idx, UV_LIVE);
    if (lua_rawgeti(L, -1, handle_key(h)) != LUA_TNIL) {
        lua_remove(L, -2);
        return;
    }
    lua_pop(L, 2);
    lua_getiuservalue(L, world_idx, UV_DEAD);
    if (lua_rawgeti(L, -1, handle_key(h)) != LUA_TNIL) {
        lua_remove(L, -2);
        return;
    }
    lua_pop(L, 1);
    /* Met for the first time: a destroyed body nobody held any more. */
    {
        lbody *b = newbody(L, world_idx, h);
        int32_t type;
        if (lw->w != NULL && rg_body_get_type(lw->w, h, &type) == RG_OK) b->type = type;
        lua_pushvalue(L, -1);
        lua_rawseti(L, -3, handle_key(h));
        lua_remove(L, -2);
    }
}

/* Inserts t[k] = v for (t, k, v) on the stack, under lua_pcall. */
static int rawset3(lua_State *L)
{
    lua_rawset(L, 1);
    return 0;
}

static const char *const body_options[] = {
    "type", "mass", "x", "y", "vx", "vy", "gravity_scale", "drag", "surface_friction",
    "min_speed", "max_speed", "user_data", "name",
#ifdef LRIGID_COLLISION
    "circle", "aabb", "restitution", "friction", "sensor", "category", "mask",
#endif
    NULL
};

static int world_body(lua_State *L)
{
    const char *what = "world:body";
    rg_world *w = checkopenworld(L, 1);
    lworld *lw = (lworld *)lua_touserdata(L, 1);
    int type = RG_BODY_DYNAMIC;
    rg_real mass = 1, x = 0, y = 0, vx = 0, vy = 0, gscale = 1, min_speed = 0, max_speed = 0;
    rg_real drag[2], sfric[2];
    int has_v, has_gscale, has_drag, has_sfric, has_limits, has_ud;
    lua_Integer user_data = 0;
#ifdef LRIGID_COLLISION
    rg_real circle = 0, aabb[2], restitution = 0, friction = 0;
    int has_circle, has_aabb, has_rest, has_fric, has_sensor, has_filter, sensor = 0;
    lua_Integer category = 1, mask = 0xFFFFFFFF;
#endif
    rg_body h = 0;
    rg_status st;
    lbody *b;
    const char *failed = NULL, *hint = NULL;

    if (lua_isnoneornil(L, 2)) {
        lua_settop(L, 1);
        lua_newtable(L);
    }
    luaL_checktype(L, 2, LUA_TTABLE);
    lua_settop(L, 2);
    check_option_names(L, 2, body_options, what);
    option_name(L, 2, "type", what, type_names, &type);
    option_real(L, 2, "mass", what, &mass);
    option_real(L, 2, "x", what, &x);
    option_real(L, 2, "y", what, &y);
    has_v = option_real(L, 2, "vx", what, &vx);
    has_v |= option_real(L, 2, "vy", what, &vy);
    has_gscale = option_real(L, 2, "gravity_scale", what, &gscale);
    has_drag = option_pair(L, 2, "drag", what, drag);
    has_sfric = option_pair(L, 2, "surface_friction", what, sfric);
    has_limits = option_real(L, 2, "min_speed", what, &min_speed);
    has_limits |= option_real(L, 2, "max_speed", what, &max_speed);
    has_ud = option_integer(L, 2, "user_data", what, LUA_MININTEGER, LUA_MAXINTEGER, &user_data);
    if (getoption(L, 2, "name")) {
        if (lua_type(L, -1) != LUA_TSTRING) option_error(L, what, "name", "a string");
    } else {
        lua_pushnil(L);
    }
#ifdef LRIGID_COLLISION
    has_circle = option_real(L, 2, "circle", what, &circle);
    has_aabb = option_pair(L, 2, "aabb", what, aabb);
    has_rest = option_real(L, 2, "restitution", what, &restitution);
    has_fric = option_real(L, 2, "friction", what, &friction);
    has_sensor = option_boolean(L, 2, "sensor", what, &sensor);
    has_filter = option_integer(L, 2, "category", what, 0, 0xFFFFFFFF, &category);
    has_filter |= option_integer(L, 2, "mask", what, 0, 0xFFFFFFFF, &mask);
    if (has_circle && has_aabb) luaL_error(L, "%s: options 'circle' and 'aabb' exclude each other", what);
#endif
    /* Stack: world, options, name.  The value first, so that nothing after the body exists
     * needs Lua memory except the table insert, which runs protected. */
    b = newbody(L, 1, 0);
    lua_pushvalue(L, 3);
    lua_setiuservalue(L, -2, UV_NAME);
    b->type = type;

    st = rg_body_create(w, type, mass, (rg_vec2){ x, y }, &h);
    if (st != RG_OK)
        return status_error(L, st, what,
                            type == RG_BODY_DYNAMIC ? "a dynamic body needs a finite mass > 0" : NULL);
#define TRY(cond, call, opt, why)                                               \
    if (st == RG_OK && (cond)) {                                                \
        st = (call);                                                            \
        if (st != RG_OK) { failed = (opt); hint = (why); }                      \
    }
    TRY(has_v, rg_body_set_velocity(w, h, (rg_vec2){ vx, vy }), "vx/vy",
        "a static body cannot move")
    TRY(has_gscale, rg_body_set_gravity_scale(w, h, gscale), "gravity_scale", NULL)
    TRY(has_drag, rg_body_set_drag(w, h, drag[0], drag[1]), "drag",
        "linear and quadratic must be >= 0")
    TRY(has_sfric, rg_body_set_surface_friction(w, h, sfric[0], sfric[1]), "surface_friction",
        "mu and normal_force must be >= 0")
    TRY(has_limits, rg_body_set_speed_limits(w, h, min_speed, max_speed), "min_speed/max_speed",
        "both >= 0, and max_speed >= min_speed unless max_speed is 0")
    TRY(has_ud, rg_body_set_user_data(w, h, (uint64_t)user_data), "user_data", NULL)
#ifdef LRIGID_COLLISION
    TRY(has_circle, rg_body_set_circle(w, h, circle), "circle", "radius must be > 0")
    TRY(has_aabb, rg_body_set_aabb(w, h, aabb[0], aabb[1]), "aabb",
        "half sizes must be > 0")
    TRY(has_rest, rg_body_set_restitution(w, h, restitution), "restitution",
        "restitution must be in [0, 1]")
    TRY(has_fric, rg_body_set_friction(w, h, friction), "friction", "friction must be >= 0")
    TRY(has_sensor, rg_body_set_sensor(w, h, sensor), "sensor", NULL)
    TRY(has_filter, rg_body_set_filter(w, h, (uint32_t)category, (uint32_t)mask),
        "category/mask", NULL)
#endif
#undef TRY
    if (st != RG_OK) {
        rg_body_destroy(w, h);
        lua_pushfstring(L, "%s: option '%s'", what, failed);
        return status_error(L, st, lua_tostring(L, -1), hint);
    }
#ifdef LRIGID_COLLISION
    if (has_circle) {
        b->shape = LRIGID_SHAPE_CIRCLE;
        b->size[0] = (double)circle;
    } else if (has_aabb) {
        b->shape = LRIGID_SHAPE_AABB;
        b->size[0] = (double)aabb[0];
        b->size[1] = (double)aabb[1];
    }
    b->sensor = sensor;
#endif
    b->h = h;
    b->serial = lw->next_serial++;
    /* live[h] = body, protected: under a memory cap the insert may fail, and then the body
     * must not stay behind in the world. */
    lua_pushcfunction(L, rawset3);
    lua_getiuservalue(L, 1, UV_LIVE);
    lua_pushinteger(L, handle_key(h));
    lua_pushvalue(L, -4);
    if (lua_pcall(L, 3, 0, 0) != LUA_OK) {
        rg_body_destroy(w, h);
        b->h = 0;
        return lua_error(L);
    }
    return 1;
}

static int body_destroy(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_world *w = b->world->w;
    if (w == NULL || rg_body_destroy(w, b->h) != RG_OK) {
        lua_pushboolean(L, 0);
        return 1;
    }
    /* Move the value from live to dead; setting an existing key to nil never allocates. */
    lua_getiuservalue(L, 1, UV_WORLD);
    lua_getiuservalue(L, -1, UV_LIVE);
    lua_pushnil(L);
    lua_rawseti(L, -2, handle_key(b->h));
    lua_pop(L, 1);
    lua_getiuservalue(L, -1, UV_DEAD);
    lua_pushvalue(L, 1);
    lua_rawseti(L, -2, handle_key(b->h));
    lua_pushboolean(L, 1);
    return 1;
}

static int body_is_valid(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    lua_pushboolean(L, b->world->w != NULL && rg_body_is_valid(b->world->w, b->h));
    return 1;
}

static int body_position(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_vec2 p;
    rg_status st = rg_body_get_position(bodyworld(L, b), b->h, &p);
    if (st != RG_OK) return status_error(L, st, "position", NULL);
    lua_pushnumber(L, (lua_Number)p.x);
    lua_pushnumber(L, (lua_Number)p.y);
    return 2;
}

static int body_velocity(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_vec2 v;
    CHECK(L, rg_body_get_velocity(bodyworld(L, b), b->h, &v), "velocity", NULL);
    pushreal(L, v.x);
    pushreal(L, v.y);
    return 2;
}

static int body_interpolated_position(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_vec2 p;
    CHECK(L, rg_body_get_interpolated_position(bodyworld(L, b), b->h, &p),
          "interpolated_position", NULL);
    pushreal(L, p.x);
    pushreal(L, p.y);
    return 2;
}

static int body_acceleration(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_vec2 a;
    CHECK(L, rg_body_get_acceleration(bodyworld(L, b), b->h, &a), "acceleration", NULL);
    pushreal(L, a.x);
    pushreal(L, a.y);
    return 2;
}

static int body_set_position(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_vec2 p = { checkreal(L, 2), checkreal(L, 3) };
    CHECK(L, rg_body_set_position(bodyworld(L, b), b->h, p), "set_position", NULL);
    return 0;
}

static int body_set_velocity(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_vec2 v = { checkreal(L, 2), checkreal(L, 3) };
    CHECK(L, rg_body_set_velocity(bodyworld(L, b), b->h, v), "set_velocity",
          "a static body cannot move");
    return 0;
}

static int body_apply_force(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_vec2 f = { checkreal(L, 2), checkreal(L, 3) };
    rg_status st = rg_body_apply_force(bodyworld(L, b), b->h, f);
    if (st != RG_OK) return status_error(L, st, "apply_force", NULL);
    return 0;
}

static int body_apply_impulse(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_vec2 j = { checkreal(L, 2), checkreal(L, 3) };
    CHECK(L, rg_body_apply_impulse(bodyworld(L, b), b->h, j), "apply_impulse", NULL);
    return 0;
}

static int body_type(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    int32_t t = 0;
    CHECK(L, rg_body_get_type(bodyworld(L, b), b->h, &t), "type", NULL);
    lua_pushstring(L, type_names[t >= 0 && t <= 2 ? t : 0]);
    return 1;
}

static int body_mass(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_real m = 0;
    CHECK(L, rg_body_get_mass(bodyworld(L, b), b->h, &m), "mass", NULL);
    pushreal(L, m);
    return 1;
}

static int body_set_mass(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_real m = checkreal(L, 2);
    CHECK(L, rg_body_set_mass(bodyworld(L, b), b->h, m), "set_mass",
          "mass must be > 0, and only a dynamic body has one");
    return 0;
}

static int body_set_gravity_scale(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_real s = checkreal(L, 2);
    CHECK(L, rg_body_set_gravity_scale(bodyworld(L, b), b->h, s), "set_gravity_scale", NULL);
    return 0;
}

static int body_set_drag(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_real lin = checkreal(L, 2), quad = optreal(L, 3, 0);
    CHECK(L, rg_body_set_drag(bodyworld(L, b), b->h, lin, quad), "set_drag",
          "linear and quadratic must be >= 0");
    return 0;
}

static int body_set_surface_friction(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_real mu = checkreal(L, 2), n = checkreal(L, 3);
    CHECK(L, rg_body_set_surface_friction(bodyworld(L, b), b->h, mu, n), "set_surface_friction",
          "mu and normal_force must be >= 0");
    return 0;
}

static int body_set_speed_limits(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_real lo = checkreal(L, 2), hi = optreal(L, 3, 0);
    CHECK(L, rg_body_set_speed_limits(bodyworld(L, b), b->h, lo, hi), "set_speed_limits",
          "both >= 0, and max_speed >= min_speed unless max_speed is 0");
    return 0;
}

static int body_user_data(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    uint64_t u = 0;
    CHECK(L, rg_body_get_user_data(bodyworld(L, b), b->h, &u), "user_data", NULL);
    lua_pushinteger(L, (lua_Integer)u);
    return 1;
}

static int body_set_user_data(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    lua_Integer u = luaL_checkinteger(L, 2);
    CHECK(L, rg_body_set_user_data(bodyworld(L, b), b->h, (uint64_t)u), "set_user_data", NULL);
    return 0;
}

static int body_name(lua_State *L)
{
    checkbody(L, 1);
    lua_getiuservalue(L, 1, UV_NAME);
    return 1;
}

static int body_world(lua_State *L)
{
    checkbody(L, 1);
    lua_getiuservalue(L, 1, UV_WORLD);
    return 1;
}

static int body_id(lua_State *L)
{
    lua_pushinteger(L, handle_key(checkbody(L, 1)->h));
    return 1;
}

#ifdef LRIGID_COLLISION
static int body_grounded(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    int32_t g = 0;
    CHECK(L, rg_body_is_grounded(bodyworld(L, b), b->h, &g), "grounded", NULL);
    lua_pushboolean(L, g != 0);
    return 1;
}

static int body_set_circle(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_real r = checkreal(L, 2);
    CHECK(L, rg_body_set_circle(bodyworld(L, b), b->h, r), "set_circle", "radius must be > 0");
    b->shape = LRIGID_SHAPE_CIRCLE;
    b->size[0] = (double)r;
    return 0;
}

static int body_set_aabb(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_real hw = checkreal(L, 2), hh = checkreal(L, 3);
    CHECK(L, rg_body_set_aabb(bodyworld(L, b), b->h, hw, hh), "set_aabb",
          "half sizes must be > 0");
    b->shape = LRIGID_SHAPE_AABB;
    b->size[0] = (double)hw;
    b->size[1] = (double)hh;
    return 0;
}

static int body_set_restitution(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_real e = checkreal(L, 2);
    CHECK(L, rg_body_set_restitution(bodyworld(L, b), b->h, e), "set_restitution",
          "restitution must be in [0, 1]");
    return 0;
}

static int body_set_friction(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_real mu = checkreal(L, 2);
    CHECK(L, rg_body_set_friction(bodyworld(L, b), b->h, mu), "set_friction",
          "friction must be >= 0");
    return 0;
}

static int body_set_sensor(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    int s;
    luaL_checktype(L, 2, LUA_TBOOLEAN);
    s = lua_toboolean(L, 2);
    CHECK(L, rg_body_set_sensor(bodyworld(L, b), b->h, s), "set_sensor", NULL);
    b->sensor = s;
    return 0;
}

static int body_set_filter(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    uint32_t category = checkmask(L, 2), mask = checkmask(L, 3);
    CHECK(L, rg_body_set_filter(bodyworld(L, b), b->h, category, mask), "set_filter", NULL);
    return 0;
}

static int body_filter(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    uint32_t category = 0, mask = 0;
    CHECK(L, rg_body_get_filter(bodyworld(L, b), b->h, &category, &mask), "filter", NULL);
    lua_pushinteger(L, (lua_Integer)category);
    lua_pushinteger(L, (lua_Integer)mask);
    return 2;
}

static int body_clear_shape(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    CHECK(L, rg_body_clear_shape(bodyworld(L, b), b->h), "clear_shape", NULL);
    b->shape = LRIGID_SHAPE_NONE;
    return 0;
}

/* "circle", r | "aabb", half_width, half_height | "none" */
static int body_shape(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    int32_t kind = 0;
    rg_vec2 half;
    CHECK(L, rg_body_get_shape(bodyworld(L, b), b->h, &kind, &half), "shape", NULL);
    if (kind == RG_SHAPE_CIRCLE) {
        lua_pushliteral(L, "circle");
        pushreal(L, half.x);
        return 2;
    }
    if (kind == RG_SHAPE_AABB) {
        lua_pushliteral(L, "aabb");
        pushreal(L, half.x);
        pushreal(L, half.y);
        return 3;
    }
    lua_pushliteral(L, "none");
    return 1;
}

static int body_restitution(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_real e = 0;
    CHECK(L, rg_body_get_restitution(bodyworld(L, b), b->h, &e), "restitution", NULL);
    pushreal(L, e);
    return 1;
}

static int body_friction(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    rg_real mu = 0;
    CHECK(L, rg_body_get_friction(bodyworld(L, b), b->h, &mu), "friction", NULL);
    pushreal(L, mu);
    return 1;
}

static int body_is_sensor(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    int32_t s = 0;
    CHECK(L, rg_body_is_sensor(bodyworld(L, b), b->h, &s), "is_sensor", NULL);
    lua_pushboolean(L, s != 0);
    return 1;
}

static int body_is_awake(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    int32_t a = 0;
    CHECK(L, rg_body_is_awake(bodyworld(L, b), b->h, &a), "is_awake", NULL);
    lua_pushboolean(L, a != 0);
    return 1;
}

static int body_wake(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    CHECK(L, rg_body_wake(bodyworld(L, b), b->h), "wake", NULL);
    return 0;
}

static int checkboolean(lua_State *L, int i)
{
    luaL_checktype(L, i, LUA_TBOOLEAN);
    return lua_toboolean(L, i);
}

static int world_set_sleeping(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    CHECK(L, rg_world_set_sleeping(w, checkboolean(L, 2)), "set_sleeping", NULL);
    return 0;
}

static int world_sleeping(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    int32_t on = 0;
    CHECK(L, rg_world_get_sleeping(w, &on), "sleeping", NULL);
    lua_pushboolean(L, on != 0);
    return 1;
}

static int world_set_sleep_thresholds(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    rg_real speed = checkreal(L, 2), time = checkreal(L, 3);
    CHECK(L, rg_world_set_sleep_thresholds(w, speed, time), "set_sleep_thresholds",
          "speed >= 0 and time > 0");
    return 0;
}

static int world_set_solver_iterations(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    lua_Integer v = luaL_checkinteger(L, 2), r = luaL_optinteger(L, 3, 2);
    luaL_argcheck(L, v >= -0x7FFFFFFF && v <= 0x7FFFFFFF, 2, "out of range");
    luaL_argcheck(L, r >= -0x7FFFFFFF && r <= 0x7FFFFFFF, 3, "out of range");
    CHECK(L, rg_world_set_solver_iterations(w, (int32_t)v, (int32_t)r), "set_solver_iterations",
          "velocity in 1..64, relax in 0..64");
    return 0;
}

static int world_set_contact_tuning(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    rg_real slop = checkreal(L, 2), bias = checkreal(L, 3), push = checkreal(L, 4);
    rg_real threshold = checkreal(L, 5);
    CHECK(L, rg_world_set_contact_tuning(w, slop, bias, push, threshold), "set_contact_tuning",
          "slop >= 0, bias_rate in (0, 1], max_push > 0, restitution_threshold >= 0");
    return 0;
}

static int world_set_continuous(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    CHECK(L, rg_world_set_continuous(w, checkboolean(L, 2)), "set_continuous", NULL);
    return 0;
}

static int world_awake_body_count(lua_State *L)
{
    lua_pushinteger(L, rg_world_awake_body_count(checkopenworld(L, 1)));
    return 1;
}

static int world_touching_count(lua_State *L)
{
    lua_pushinteger(L, rg_world_touching_count(checkopenworld(L, 1)));
    return 1;
}
#endif

static int body_tostring(lua_State *L)
{
    lbody *b = checkbody(L, 1);
    int valid = b->world->w != NULL && rg_body_is_valid(b->world->w, b->h);
    const char *state = !valid ? "destroyed"
                        : b->type >= 0 && b->type <= 2 ? type_names[b->type] : "?";
    lua_getiuservalue(L, 1, UV_NAME);
    if (lua_isstring(L, -1))
        lua_pushfstring(L, "rigid.body #%I \"%s\" (%s)", b->serial, lua_tostring(L, -1), state);
    else
        lua_pushfstring(L, "rigid.body #%I (%s)", b->serial, state);
    return 1;
}

/* Two values of one body are the same body (the binding keeps one value per body, so this
 * only matters for a value made after the first was collected). */
static int body_eq(lua_State *L)
{
    const lbody *a = (const lbody *)luaL_testudata(L, 1, BODY_MT);
    const lbody *b = (const lbody *)luaL_testudata(L, 2, BODY_MT);
    lua_pushboolean(L, a != NULL && b != NULL && a->h == b->h && a->world == b->world);
    return 1;
}

static int body_close(lua_State *L)
{
    lua_settop(L, 1);
    body_destroy(L);
    return 0;
}

/* Bodies of the world in creation order. */
typedef struct bodyref {
    lua_Integer serial;
    lua_Integer key;
} bodyref;

static int bodyref_cmp(const void *x, const void *y)
{
    const bodyref *a = (const bodyref *)x, *b = (const bodyref *)y;
    return (a->serial > b->serial) - (a->serial < b->serial);
}

static int world_bodies(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    int n = 0, i, cap = rg_world_body_count(w);
    bodyref *refs;
    lua_settop(L, 1);
    lua_getiuservalue(L, 1, UV_LIVE);   /* 2 */
    refs = (bodyref *)lua_newuserdatauv(L, (size_t)(cap > 0 ? cap : 1) * sizeof *refs, 0); /* 3 */
    lua_pushnil(L);
    while (lua_next(L, 2) != 0) {
        const lbody *b = (const lbody *)lua_touserdata(L, -1);
        if (n < cap && b != NULL) {
            refs[n].serial = b->serial;
            refs[n].key = lua_tointeger(L, -2);
            n++;
        }
        lua_pop(L, 1);
    }
    qsort(refs, (size_t)n, sizeof *refs, bodyref_cmp);
    charge(L, n);
    lua_createtable(L, n, 0);
    for (i = 0; i < n; i++) {
        lua_rawgeti(L, 2, refs[i].key);
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

/* ---------------------------------------------------------------- springs */

static const char *const spring_options[] = { "a", "b", "anchor", "rest_length", "stiffness",
                                              "damping", NULL };

static lbody *option_body(lua_State *L, int t, const char *key, const char *what,
                          const lworld *lw)
{
    lbody *b;
    if (!getoption(L, t, key)) return NULL;
    b = (lbody *)luaL_testudata(L, -1, BODY_MT);
    if (b == NULL) option_error(L, what, key, "a body");
    if (b->world != lw) luaL_error(L, "%s: option '%s' is a body of another world", what, key);
    lua_pop(L, 1);
    return b;
}

static int world_spring(lua_State *L)
{
    const char *what = "world:spring";
    rg_world *w = checkopenworld(L, 1);
    const lworld *lw = (const lworld *)lua_touserdata(L, 1);
    rg_real anchor[2] = { 0, 0 }, rest = 0, k = 0, damping = 0;
    lbody *a, *b;
    lspring *s;
    uint64_t h = 0;
    luaL_checktype(L, 2, LUA_TTABLE);
    lua_settop(L, 2);
    check_option_names(L, 2, spring_options, what);
    a = option_body(L, 2, "a", what, lw);
    b = option_body(L, 2, "b", what, lw);
    if (a == NULL) luaL_error(L, "%s: option 'a' (a body) is required", what);
    if (!option_pair(L, 2, "anchor", what, anchor) && b == NULL)
        luaL_error(L, "%s: option 'anchor' {x, y} is required when there is no body 'b'", what);
    option_real(L, 2, "rest_length", what, &rest);
    if (!option_real(L, 2, "stiffness", what, &k))
        luaL_error(L, "%s: option 'stiffness' is required", what);
    option_real(L, 2, "damping", what, &damping);
    s = (lspring *)lua_newuserdatauv(L, sizeof *s, 1);
    s->h = 0;
    s->world = (lworld *)lua_touserdata(L, 1);
    luaL_setmetatable(L, SPRING_MT);
    lua_pushvalue(L, 1);
    lua_setiuservalue(L, -2, UV_WORLD);
    CHECK(L, rg_spring_create(w, a->h, b != NULL ? b->h : 0, (rg_vec2){ anchor[0], anchor[1] },
                              rest, k, damping, &h),
          what, "rest_length, stiffness and damping must be >= 0, and a and b distinct live bodies");
    s->h = h;
    return 1;
}

static lspring *checkspring(lua_State *L, int i)
{
    return (lspring *)luaL_checkudata(L, i, SPRING_MT);
}

static int spring_destroy(lua_State *L)
{
    lspring *s = checkspring(L, 1);
    lua_pushboolean(L, s->world->w != NULL && rg_spring_destroy(s->world->w, s->h) == RG_OK);
    return 1;
}

static int spring_is_valid(lua_State *L)
{
    lspring *s = checkspring(L, 1);
    lua_pushboolean(L, s->world->w != NULL && rg_spring_is_valid(s->world->w, s->h));
    return 1;
}

static int spring_tostring(lua_State *L)
{
    lspring *s = checkspring(L, 1);
    int valid = s->world->w != NULL && rg_spring_is_valid(s->world->w, s->h);
    lua_pushfstring(L, "rigid.spring (%s)", valid ? "live" : "destroyed");
    return 1;
}

/* ---------------------------------------------------------------- collision */

#ifdef LRIGID_COLLISION
/* Pushes the events of the last step, or of every step of the last advance, of the open world
 * at idx as an array of tables. */
static void push_events(lua_State *L, int idx, rg_world *w)
{
    int32_t n = rg_world_get_contact_events(w, NULL, 0), i;
    rg_contact_event *ev;
    idx = lua_absindex(L, idx);
    if (n < 0) status_error(L, n, "events", NULL);
    ev = (rg_contact_event *)lua_newuserdatauv(L, (size_t)(n > 0 ? n : 1) * sizeof *ev, 0);
    if (n > 0) n = rg_world_get_contact_events(w, ev, n);
    charge(L, n);
    lua_createtable(L, n, 0);
    for (i = 0; i < n; i++) {
        const rg_contact_event *e = &ev[i];
        lua_createtable(L, 0, 10);
        lua_pushstring(L, e->kind == RG_CONTACT_BEGIN ? "begin" : "end");
        lua_setfield(L, -2, "kind");
        lrigid_pushbody(L, idx, e->a);
        lua_setfield(L, -2, "a");
        lrigid_pushbody(L, idx, e->b);
        lua_setfield(L, -2, "b");
        pushreal(L, e->normal.x);
        lua_setfield(L, -2, "nx");
        pushreal(L, e->normal.y);
        lua_setfield(L, -2, "ny");
        pushreal(L, e->point.x);
        lua_setfield(L, -2, "x");
        pushreal(L, e->point.y);
        lua_setfield(L, -2, "y");
        pushreal(L, e->depth);
        lua_setfield(L, -2, "depth");
        pushreal(L, e->speed);
        lua_setfield(L, -2, "speed");
        lua_pushboolean(L, e->sensor != 0);
        lua_setfield(L, -2, "sensor");
        lua_rawseti(L, -2, i + 1);
    }
    lua_remove(L, -2);   /* the scratch buffer */
}

void lrigid_pushevents(lua_State *L, int world_idx)
{
    rg_world *w = lrigid_toworld(L, world_idx);
    if (w == NULL) luaL_error(L, "attempt to use a closed world");
    push_events(L, world_idx, w);
}

static int world_events(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    lua_settop(L, 1);
    push_events(L, 1, w);
    return 1;
}

static int world_raycast(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    rg_vec2 o = { checkreal(L, 2), checkreal(L, 3) }, d = { checkreal(L, 4), checkreal(L, 5) };
    uint32_t mask = lua_isnoneornil(L, 6) ? 0xFFFFFFFFu : checkmask(L, 6);
    rg_ray_hit hit;
    int32_t r = rg_world_raycast(w, o, d, mask, &hit);
    if (r < 0) return status_error(L, r, "raycast", NULL);
    charge(L, rg_world_body_count(w));
    if (r == 0) {
        lua_pushnil(L);
        return 1;
    }
    lrigid_pushbody(L, 1, hit.body);
    pushreal(L, hit.point.x);
    pushreal(L, hit.point.y);
    pushreal(L, hit.normal.x);
    pushreal(L, hit.normal.y);
    pushreal(L, hit.fraction);
    return 6;
}

static int world_query_aabb(lua_State *L)
{
    rg_world *w = checkopenworld(L, 1);
    rg_vec2 lo = { checkreal(L, 2), checkreal(L, 3) }, hi = { checkreal(L, 4), checkreal(L, 5) };
    uint32_t mask = lua_isnoneornil(L, 6) ? 0xFFFFFFFFu : checkmask(L, 6);
    int32_t n = rg_world_query_aabb(w, lo, hi, mask, NULL, 0), i;
    rg_body *out;
    lua_settop(L, 1);
    if (n < 0) return status_error(L, n, "query_aabb", "lower must not exceed upper");
    out = (rg_body *)lua_newuserdatauv(L, (size_t)(n > 0 ? n : 1) * sizeof *out, 0);
    if (n > 0) n = rg_world_query_aabb(w, lo, hi, mask, out, n);
    charge(L, rg_world_body_count(w));
    lua_createtable(L, n, 0);
    for (i = 0; i < n; i++) {
        lrigid_pushbody(L, 1, out[i]);
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}
#endif

/* ---------------------------------------------------------------- module */

static const luaL_Reg world_methods[] = {
    { "body", world_body },
    { "spring", world_spring },
    { "bodies", world_bodies },
    { "step", world_step },
    { "advance", world_advance },
    { "alpha", world_alpha },
    { "gravity", world_gravity },
    { "set_gravity", world_set_gravity },
    { "wind", world_wind },
    { "set_wind", world_set_wind },
    { "integrator", world_integrator },
    { "set_integrator", world_set_integrator },
    { "fixed_step", world_fixed_step },
    { "set_fixed_step", world_set_fixed_step },
    { "body_count", world_body_count },
    { "spring_count", world_spring_count },
    { "is_open", world_is_open },
    { "close", world_close },
#ifdef LRIGID_COLLISION
    { "events", world_events },
    { "raycast", world_raycast },
    { "query_aabb", world_query_aabb },
    { "set_sleeping", world_set_sleeping },
    { "sleeping", world_sleeping },
    { "set_sleep_thresholds", world_set_sleep_thresholds },
    { "set_solver_iterations", world_set_solver_iterations },
    { "set_contact_tuning", world_set_contact_tuning },
    { "set_continuous", world_set_continuous },
    { "awake_body_count", world_awake_body_count },
    { "touching_count", world_touching_count },
#endif
    { NULL, NULL }
};

static const luaL_Reg world_meta[] = {
    { "__tostring", world_tostring },
    { "__close", world_close },
    { NULL, NULL }
};

static const luaL_Reg body_methods[] = {
    { "position", body_position },
    { "velocity", body_velocity },
    { "set_position", body_set_position },
    { "set_velocity", body_set_velocity },
    { "apply_force", body_apply_force },
    { "apply_impulse", body_apply_impulse },
    { "interpolated_position", body_interpolated_position },
    { "acceleration", body_acceleration },
    { "type", body_type },
    { "mass", body_mass },
    { "set_mass", body_set_mass },
    { "set_gravity_scale", body_set_gravity_scale },
    { "set_drag", body_set_drag },
    { "set_surface_friction", body_set_surface_friction },
    { "set_speed_limits", body_set_speed_limits },
    { "user_data", body_user_data },
    { "set_user_data", body_set_user_data },
    { "name", body_name },
    { "world", body_world },
    { "id", body_id },
    { "is_valid", body_is_valid },
    { "destroy", body_destroy },
#ifdef LRIGID_COLLISION
    { "grounded", body_grounded },
    { "set_circle", body_set_circle },
    { "set_aabb", body_set_aabb },
    { "set_restitution", body_set_restitution },
    { "set_friction", body_set_friction },
    { "set_sensor", body_set_sensor },
    { "set_filter", body_set_filter },
    { "filter", body_filter },
    { "clear_shape", body_clear_shape },
    { "shape", body_shape },
    { "restitution", body_restitution },
    { "friction", body_friction },
    { "is_sensor", body_is_sensor },
    { "is_awake", body_is_awake },
    { "wake", body_wake },
#endif
    { NULL, NULL }
};

static const luaL_Reg body_meta[] = {
    { "__tostring", body_tostring },
    { "__eq", body_eq },
    { "__close", body_close },
    { NULL, NULL }
};

static const luaL_Reg spring_methods[] = {
    { "destroy", spring_destroy },
    { "is_valid", spring_is_valid },
    { NULL, NULL }
};

static const luaL_Reg spring_meta[] = {
    { "__tostring", spring_tostring },
    { "__close", spring_destroy },
    { NULL, NULL }
};

/* Builds a metatable with methods in __index; every function gets the metatable as
 * upvalue 1 (and extra upvalue 2 when given) for the fast type check.  Leaves it pushed. */
static void newclass(lua_State *L, const char *name, const luaL_Reg *methods,
                     const luaL_Reg *meta)
{
    luaL_newmetatable(L, name);
    lua_newtable(L);
    lua_pushvalue(L, -2);
    luaL_setfuncs(L, methods, 1);
    lua_setfield(L, -2, "__index");
    lua_pushvalue(L, -1);
    luaL_setfuncs(L, meta, 1);
    lua_pushstring(L, name);
    lua_setfield(L, -2, "__metatable");
}

LRIGID_API int luaopen_rigid(lua_State *L)
{
    int32_t v = rg_version();
    luaL_checkversion(L);
    newclass(L, BODY_MT, body_methods, body_meta);
    lua_pop(L, 1);
    newclass(L, SPRING_MT, spring_methods, spring_meta);
    lua_pop(L, 1);
    newclass(L, WORLD_MT, world_methods, world_meta);
    lua_pushcfunction(L, world_gc);
    lua_setfield(L, -2, "__gc");

    lua_newtable(L);
    lua_pushvalue(L, -2);
    lua_pushcclosure(L, l_world, 1);
    lua_setfield(L, -2, "world");
    lua_pushfstring(L, "%d.%d.%d", (int)(v / 10000), (int)(v / 100 % 100), (int)(v % 100));
    lua_setfield(L, -2, "version");
    lua_pushinteger(L, rg_real_size());
    lua_setfield(L, -2, "real_size");
#ifdef LRIGID_COLLISION
    lua_pushboolean(L, 1);
#else
    lua_pushboolean(L, 0);
#endif
    lua_setfield(L, -2, "collision");
    lua_remove(L, -2);
    return 1;
}
