/* lworld.c: the Lua world value (rigid.world), its stepping and settings, and the hooks a
 * host installs to watch what scripts make the library do. */
#include "lrigid_int.h"

static const char lworld_hooks_key = 'h';

/* ---------------------------------------------------------------- host hooks */

static const lrigid_hooks *lworld_gethooks(lua_State *L)
{
    const lrigid_hooks *h;
    lua_rawgetp(L, LUA_REGISTRYINDEX, &lworld_hooks_key);
    h = (const lrigid_hooks *)lua_touserdata(L, -1);
    lua_pop(L, 1);
    return h;
}

void lworld_sethooks(lua_State *L, const lrigid_hooks *hooks)
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
    lua_rawsetp(L, LUA_REGISTRYINDEX, &lworld_hooks_key);
}

void lworld_charge(lua_State *L, double units)
{
    const lrigid_hooks *h = lworld_gethooks(L);
    if (h != NULL && h->charge != NULL) h->charge(L, h->ud, units);
}

/* Units one step costs, from the counts the step leaves, each at the most measured (a unit
 * is one VM instruction, about 1.8 ns here): a touching pair is narrowphase and solver rows
 * (30 units for circles in a pile, 180 for 300 overlapping circles of radius 1e7), an awake
 * body its integration and broadphase (0.5 without a shape, 60 for a falling circle), a
 * spring its force.  Sleeping and static bodies cost nothing and are not charged. */
#define LWORLD_UNITS_PAIR   200
#define LWORLD_UNITS_BODY   64
#define LWORLD_UNITS_SPRING 8

void lworld_charge_overlaps(lua_State *L, rg_world *w, rg_body h)
{
    const lrigid_hooks *hooks = lworld_gethooks(L);
    rg_vec2 p, half;
    int32_t kind = RG_SHAPE_NONE;
    if (hooks == NULL || hooks->charge == NULL) return;
    if (rg_body_get_shape(w, h, &kind, &half) != RG_OK || kind == RG_SHAPE_NONE) return;
    if (rg_body_get_position(w, h, &p) != RG_OK) return;
    rg_vec2 lo = { p.x - half.x, p.y - half.y }, hi = { p.x + half.x, p.y + half.y };
    int32_t n = rg_world_query_aabb(w, lo, hi, 0xFFFFFFFFu, NULL, 0);
    if (n > 1) hooks->charge(L, hooks->ud, LWORLD_UNITS_PAIR * (double)(n - 1));
}

static double lworld_step_units(const rg_world *w)
{
    return 1.0 + LWORLD_UNITS_PAIR * (double)rg_world_touching_count(w) +
           LWORLD_UNITS_BODY * (double)rg_world_awake_body_count(w) +
           LWORLD_UNITS_SPRING * (double)rg_world_spring_count(w);
}

static void lworld_after_step(lua_State *L, int idx, rg_world *w, int steps)
{
    const lrigid_hooks *h;
    if (steps <= 0) return;
    h = lworld_gethooks(L);
    if (h == NULL) return;
    if (h->charge != NULL) h->charge(L, h->ud, (double)steps * lworld_step_units(w));
    if (h->after_step != NULL) h->after_step(L, h->ud, idx, steps);
}

/* ---------------------------------------------------------------- the world value */

lworld *lworld_test(lua_State *L, int i)
{
    return (lworld *)luaL_testudata(L, i, LWORLD_MT);
}

lworld *lworld_check(lua_State *L, int i)
{
    return (lworld *)lcheck_self(L, i, LWORLD_MT);
}

rg_world *lworld_checkopen(lua_State *L, int i)
{
    lworld *lw = lworld_check(L, i);
    if (lw->w == NULL) luaL_error(L, "attempt to use a closed world");
    return lw->w;
}

int lworld_rawset3(lua_State *L)
{
    lua_rawset(L, 1);
    return 0;
}

/* Pushes a new table with weak values. */
static void lworld_newweak(lua_State *L)
{
    lua_newtable(L);
    lua_newtable(L);
    lua_pushliteral(L, "v");
    lua_setfield(L, -2, "__mode");
    lua_setmetatable(L, -2);
}

static const char *const lworld_options[] = { "gravity", "wind", "integrator", "dt",
                                              "max_steps", NULL };

int lworld_new(lua_State *L)
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
    const char *failed = NULL;
    const lrigid_hooks *hooks;

    if (!lua_isnoneornil(L, 1)) {
        luaL_checktype(L, 1, LUA_TTABLE);
        lcheck_option_names(L, 1, lworld_options, what);
        has_gravity = lcheck_option_pair(L, 1, "gravity", what, gravity);
        has_wind = lcheck_option_pair(L, 1, "wind", what, wind);
        has_integrator = lcheck_option_enum(L, 1, "integrator", what, lcheck_integrator_names,
                                            &integrator);
        has_dt = lcheck_option_real(L, 1, "dt", what, &dt);
        has_max = lcheck_option_integer(L, 1, "max_steps", what, 1, 0x7FFFFFFF, &max_steps);
    }
    /* Everything that allocates on the Lua side comes first, so that a memory error cannot
     * leave a world nobody owns. */
    lw = (lworld *)lua_newuserdatauv(L, sizeof *lw, LWORLD_UVS);
    lw->w = NULL;
    lw->next_serial = 1;
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_setmetatable(L, -2);
    lua_newtable(L);
    lua_setiuservalue(L, -2, LWORLD_UV_LIVE);
    lworld_newweak(L);
    lua_setiuservalue(L, -2, LWORLD_UV_DEAD);
    lworld_newweak(L);
    lua_setiuservalue(L, -2, LWORLD_UV_SPRINGS);
    lua_newtable(L);
    lua_setiuservalue(L, -2, LWORLD_UV_KEPT);

    /* The world allocates through the state's allocator, so a host's memory cap counts it. */
    alloc = lua_getallocf(L, &alloc_ud);
    st = rg_world_create_with_allocator(alloc, alloc_ud, &w);
    if (st != RG_OK) return lcheck_status(L, NULL, st, what);
    hooks = lworld_gethooks(L);
    if (hooks != NULL && hooks->tasks != NULL) {
        st = rg_world_set_task_system(w, hooks->tasks);
        failed = "the host's task system";
    }
    if (st == RG_OK && has_gravity) {
        st = rg_world_set_gravity(w, (rg_vec2){ gravity[0], gravity[1] });
        failed = "gravity";
    }
    if (st == RG_OK && has_wind) {
        st = rg_world_set_wind(w, (rg_vec2){ wind[0], wind[1] });
        failed = "wind";
    }
    if (st == RG_OK && has_integrator) {
        st = rg_world_set_integrator(w, integrator);
        failed = "integrator";
    }
    if (st == RG_OK && (has_dt || has_max)) {
        rg_real cur_dt;
        int32_t cur_max;
        st = rg_world_get_fixed_step(w, &cur_dt, &cur_max);
        if (st == RG_OK)
            st = rg_world_set_fixed_step(w, has_dt ? dt : cur_dt,
                                         has_max ? (int32_t)max_steps : cur_max);
        failed = has_dt ? "dt" : "max_steps";
    }
    if (st != RG_OK) {
        char why[LCHECK_REASON_SIZE];
        lcheck_copyreason(w, st, why, sizeof why);
        rg_world_destroy(w);
        return luaL_error(L, "%s: option '%s': %s", what, failed, why);
    }
    lw->w = w;
    return 1;
}

static int lworld_close(lua_State *L)
{
    lworld *lw = lworld_check(L, 1);
    rg_world_destroy(lw->w);
    lw->w = NULL;
    return 0;
}

int lworld_gc(lua_State *L)
{
    lworld *lw = (lworld *)lua_touserdata(L, 1);
    if (lw != NULL) {
        rg_world_destroy(lw->w);
        lw->w = NULL;
    }
    return 0;
}

static int lworld_tostring(lua_State *L)
{
    lworld *lw = lworld_check(L, 1);
    if (lw->w == NULL) lua_pushliteral(L, "rigid.world (closed)");
    else
        lua_pushfstring(L, "rigid.world (%d bodies, %d springs)", (int)rg_world_body_count(lw->w),
                        (int)rg_world_spring_count(lw->w));
    return 1;
}

static int lworld_is_open(lua_State *L)
{
    lua_pushboolean(L, lworld_check(L, 1)->w != NULL);
    return 1;
}

/* ---------------------------------------------------------------- stepping */

static int lworld_step(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    rg_real dt = lcheck_real(L, 2);
    LCHECK(L, w, rg_world_step(w, dt), "step");
    lworld_after_step(L, 1, w, 1);
    return 0;
}

static int lworld_advance(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    rg_real frame_time = lcheck_real(L, 2);
    int32_t steps = 0;
    LCHECK(L, w, rg_world_advance(w, frame_time, &steps), "advance");
    lworld_after_step(L, 1, w, steps);
    lua_pushinteger(L, steps);
    return 1;
}

static int lworld_alpha(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    rg_real a = 0;
    LCHECK(L, w, rg_world_get_alpha(w, &a), "alpha");
    lcheck_pushreal(L, a);
    return 1;
}

static int lworld_fixed_step(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    rg_real dt = 0;
    int32_t max = 0;
    LCHECK(L, w, rg_world_get_fixed_step(w, &dt, &max), "fixed_step");
    lcheck_pushreal(L, dt);
    lua_pushinteger(L, max);
    return 2;
}

static int lworld_set_fixed_step(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    rg_real dt = lcheck_real(L, 2), cur_dt;
    int32_t max;
    LCHECK(L, w, rg_world_get_fixed_step(w, &cur_dt, &max), "set_fixed_step");
    if (!lua_isnoneornil(L, 3)) max = lcheck_int32(L, 3, 1, 0x7FFFFFFF, "max_steps must be >= 1");
    LCHECK(L, w, rg_world_set_fixed_step(w, dt, max), "set_fixed_step");
    return 0;
}

/* ---------------------------------------------------------------- forces and integrator */

/* gravity and wind: one getter and one setter for a world vector. */
typedef rg_status (*lworld_getvec)(const rg_world *, rg_vec2 *);
typedef rg_status (*lworld_setvec)(rg_world *, rg_vec2);

static int lworld_get_vec2(lua_State *L, lworld_getvec get, const char *what)
{
    rg_world *w = lworld_checkopen(L, 1);
    rg_vec2 v;
    LCHECK(L, w, get(w, &v), what);
    lcheck_pushvec2(L, v);
    return 2;
}

static int lworld_set_vec2(lua_State *L, lworld_setvec set, const char *what)
{
    rg_world *w = lworld_checkopen(L, 1);
    LCHECK(L, w, set(w, lcheck_vec2(L, 2)), what);
    return 0;
}

static int lworld_gravity(lua_State *L)
{
    return lworld_get_vec2(L, rg_world_get_gravity, "gravity");
}

static int lworld_set_gravity(lua_State *L)
{
    return lworld_set_vec2(L, rg_world_set_gravity, "set_gravity");
}

static int lworld_wind(lua_State *L)
{
    return lworld_get_vec2(L, rg_world_get_wind, "wind");
}

static int lworld_set_wind(lua_State *L)
{
    return lworld_set_vec2(L, rg_world_set_wind, "set_wind");
}

static int lworld_integrator(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    int32_t i = 0;
    LCHECK(L, w, rg_world_get_integrator(w, &i), "integrator");
    if (i < 0 || i > 3) return luaL_error(L, "integrator: unknown integrator %d", (int)i);
    lua_pushstring(L, lcheck_integrator_names[i]);
    return 1;
}

static int lworld_set_integrator(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    int i = lcheck_enum(L, 2, lcheck_integrator_names, "integrator");
    LCHECK(L, w, rg_world_set_integrator(w, i), "set_integrator");
    return 0;
}

/* ---------------------------------------------------------------- collision settings */

static int lworld_set_sleeping(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    LCHECK(L, w, rg_world_set_sleeping(w, lcheck_boolean(L, 2)), "set_sleeping");
    return 0;
}

static int lworld_sleeping(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    int32_t on = 0;
    LCHECK(L, w, rg_world_get_sleeping(w, &on), "sleeping");
    lua_pushboolean(L, on != 0);
    return 1;
}

static int lworld_set_sleep_thresholds(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    rg_real speed = lcheck_real(L, 2), time = lcheck_real(L, 3);
    LCHECK(L, w, rg_world_set_sleep_thresholds(w, speed, time), "set_sleep_thresholds");
    return 0;
}

/* Without `position`, the world keeps the position iterations it has. */
static int lworld_set_solver_iterations(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    const int32_t big = 0x7FFFFFFF;
    int32_t velocity, position;
    LCHECK(L, w, rg_world_get_solver_iterations(w, &velocity, &position), "set_solver_iterations");
    velocity = lcheck_int32(L, 2, -big, big, "out of range");
    if (!lua_isnoneornil(L, 3)) position = lcheck_int32(L, 3, -big, big, "out of range");
    LCHECK(L, w, rg_world_set_solver_iterations(w, velocity, position), "set_solver_iterations");
    return 0;
}

static int lworld_solver_iterations(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    int32_t velocity = 0, position = 0;
    LCHECK(L, w, rg_world_get_solver_iterations(w, &velocity, &position), "solver_iterations");
    lua_pushinteger(L, velocity);
    lua_pushinteger(L, position);
    return 2;
}

static int lworld_set_contact_tuning(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    rg_real slop = lcheck_real(L, 2), bias = lcheck_real(L, 3), push = lcheck_real(L, 4);
    rg_real threshold = lcheck_real(L, 5);
    LCHECK(L, w, rg_world_set_contact_tuning(w, slop, bias, push, threshold), "set_contact_tuning");
    return 0;
}

static int lworld_set_continuous(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    LCHECK(L, w, rg_world_set_continuous(w, lcheck_boolean(L, 2)), "set_continuous");
    return 0;
}

/* ---------------------------------------------------------------- counts */

/* body_count, spring_count, awake_body_count, touching_count: 0 never means an error. */
static int lworld_count(lua_State *L, int32_t (*count)(const rg_world *))
{
    lua_pushinteger(L, count(lworld_checkopen(L, 1)));
    return 1;
}

static int lworld_body_count(lua_State *L) { return lworld_count(L, rg_world_body_count); }
static int lworld_spring_count(lua_State *L) { return lworld_count(L, rg_world_spring_count); }
static int lworld_awake_body_count(lua_State *L)
{
    return lworld_count(L, rg_world_awake_body_count);
}
static int lworld_touching_count(lua_State *L) { return lworld_count(L, rg_world_touching_count); }

const luaL_Reg lworld_methods[] = {
    { "step", lworld_step },
    { "advance", lworld_advance },
    { "alpha", lworld_alpha },
    { "gravity", lworld_gravity },
    { "set_gravity", lworld_set_gravity },
    { "wind", lworld_wind },
    { "set_wind", lworld_set_wind },
    { "integrator", lworld_integrator },
    { "set_integrator", lworld_set_integrator },
    { "fixed_step", lworld_fixed_step },
    { "set_fixed_step", lworld_set_fixed_step },
    { "body_count", lworld_body_count },
    { "spring_count", lworld_spring_count },
    { "is_open", lworld_is_open },
    { "close", lworld_close },
    { "set_sleeping", lworld_set_sleeping },
    { "sleeping", lworld_sleeping },
    { "set_sleep_thresholds", lworld_set_sleep_thresholds },
    { "set_solver_iterations", lworld_set_solver_iterations },
    { "solver_iterations", lworld_solver_iterations },
    { "set_contact_tuning", lworld_set_contact_tuning },
    { "set_continuous", lworld_set_continuous },
    { "awake_body_count", lworld_awake_body_count },
    { "touching_count", lworld_touching_count },
    { NULL, NULL }
};

const luaL_Reg lworld_meta[] = {
    { "__tostring", lworld_tostring },
    { "__close", lworld_close },
    { NULL, NULL }
};
