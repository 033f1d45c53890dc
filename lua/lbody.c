/* lbody.c: Lua body values: one value per body (identity), world:body{...} and
 * world:bodies(), and the body methods.
 *
 * A body is one Lua value wherever it appears (world:body, world:bodies, events, queries),
 * also after it is destroyed, for as long as anyone holds it: the world's uservalues map
 * handles to values (lrigid_int.h).  A body value holds its world value, so a world stays
 * alive while any of its bodies is held. */
#include <stdlib.h>
#include <string.h>

#include "lrigid_int.h"

/* Handles are Lua integer keys; the conversion wraps modulo 2^64 on every two's complement
 * target, which is all that matters here (it is a bijection). */
static lua_Integer lbody_key(uint64_t h)
{
    return (lua_Integer)h;
}

/* ---------------------------------------------------------------- identity */

lbody *lbody_test(lua_State *L, int i)
{
    return (lbody *)luaL_testudata(L, i, LBODY_MT);
}

lbody *lbody_check(lua_State *L, int i)
{
    return (lbody *)lcheck_self(L, i, LBODY_MT);
}

rg_world *lbody_world_of(lua_State *L, const lbody *b)
{
    if (b->world->w == NULL) luaL_error(L, "attempt to use a body of a closed world");
    if (b->retired) luaL_error(L, "attempt to use a destroyed body");
    return b->world->w;
}

rg_body lbody_handle(lua_State *L, const lbody *b)
{
    lbody_world_of(L, b);
    return b->h;
}

int lbody_info(lua_State *L, int idx, lrigid_body_info *out)
{
    lbody *b = lbody_test(L, idx);
    if (b == NULL) return 0;
    /* A live body's shape comes from the library; a destroyed one keeps what it had. */
    lbody_refresh(b);
    out->handle = b->h;
    out->serial = b->serial;
    out->type = b->type;
    out->shape = b->shape;
    out->size[0] = b->size[0];
    out->size[1] = b->size[1];
    out->sensor = b->sensor;
    lua_getiuservalue(L, idx, LBODY_UV_NAME);
    out->name = lua_tostring(L, -1);   /* the body value holds the string */
    lua_pop(L, 1);
    return 1;
}

lbody *lbody_new(lua_State *L, int world_idx, rg_body h)
{
    lworld *lw = (lworld *)lua_touserdata(L, world_idx);
    lbody *b = (lbody *)lua_newuserdatauv(L, sizeof *b, 2);
    memset(b, 0, sizeof *b);
    b->h = h;
    b->world = lw;
    b->type = -1;
    luaL_setmetatable(L, LBODY_MT);
    lua_pushvalue(L, world_idx);
    lua_setiuservalue(L, -2, LBODY_UV_WORLD);
    return b;
}

void lbody_push(lua_State *L, int world_idx, rg_body h)
{
    lworld *lw;
    world_idx = lua_absindex(L, world_idx);
    lw = (lworld *)lua_touserdata(L, world_idx);
    lua_getiuservalue(L, world_idx, LWORLD_UV_LIVE);
    if (lua_rawgeti(L, -1, lbody_key(h)) != LUA_TNIL) {
        lua_remove(L, -2);
        return;
    }
    lua_pop(L, 2);
    lua_getiuservalue(L, world_idx, LWORLD_UV_DEAD);
    if (lua_rawgeti(L, -1, lbody_key(h)) != LUA_TNIL) {
        lua_remove(L, -2);
        return;
    }
    lua_pop(L, 1);
    /* Met for the first time: a destroyed body nobody held any more. */
    {
        lbody *b = lbody_new(L, world_idx, h);
        int32_t type;
        if (lw->w != NULL && rg_body_get_type(lw->w, h, &type) == RG_OK) b->type = type;
        lua_pushvalue(L, -1);
        lua_rawseti(L, -3, lbody_key(h));
        lua_remove(L, -2);
    }
}

/* A body was just created with handle h in the world at world_idx.  A value of a body
 * destroyed with that handle can only exist when a restore took the world back to before
 * that body was made and the world has now given its handle out again (the same creation
 * after a rollback, or another): that old value stays destroyed for good (retired), and
 * the handle's value is the new one.  Never allocates. */
static void lbody_retire(lua_State *L, int world_idx, rg_body h)
{
    lua_getiuservalue(L, world_idx, LWORLD_UV_DEAD);
    if (lua_rawgeti(L, -1, lbody_key(h)) != LUA_TNIL) {
        ((lbody *)lua_touserdata(L, -1))->retired = 1;
        lua_pushnil(L);
        lua_rawseti(L, -3, lbody_key(h));
    }
    lua_pop(L, 2);
}

/* ---------------------------------------------------------------- world:body{...} */

static const char *const lbody_options[] = {
    "type", "mass", "x", "y", "vx", "vy", "gravity_scale", "drag", "surface_friction",
    "min_speed", "max_speed", "user_data", "name",
    "circle", "aabb", "restitution", "friction", "sensor", "category", "mask", "one_way",
    NULL
};

static int lbody_create(lua_State *L)
{
    const char *what = "world:body";
    rg_world *w = lworld_checkopen(L, 1);
    lworld *lw = (lworld *)lua_touserdata(L, 1);
    int type = RG_BODY_DYNAMIC;
    rg_real mass = 1, x = 0, y = 0, vx = 0, vy = 0, gscale = 1, min_speed = 0, max_speed = 0;
    rg_real drag[2], sfric[2];
    int has_v, has_gscale, has_drag, has_sfric, has_limits, has_ud;
    lua_Integer user_data = 0;
    rg_real circle = 0, aabb[2], restitution = 0, friction = 0, one_way[2];
    int has_circle, has_aabb, has_rest, has_fric, has_sensor, has_filter, has_one_way, sensor = 0;
    lua_Integer category = 1, mask = 0xFFFFFFFF;
    rg_body h = 0;
    rg_status st;
    lbody *b;
    const char *failed = NULL;

    if (lua_isnoneornil(L, 2)) {
        lua_settop(L, 1);
        lua_newtable(L);
    }
    luaL_checktype(L, 2, LUA_TTABLE);
    lua_settop(L, 2);
    lcheck_option_names(L, 2, lbody_options, what);
    lcheck_option_enum(L, 2, "type", what, lcheck_type_names, &type);
    lcheck_option_real(L, 2, "mass", what, &mass);
    lcheck_option_real(L, 2, "x", what, &x);
    lcheck_option_real(L, 2, "y", what, &y);
    has_v = lcheck_option_real(L, 2, "vx", what, &vx);
    has_v |= lcheck_option_real(L, 2, "vy", what, &vy);
    has_gscale = lcheck_option_real(L, 2, "gravity_scale", what, &gscale);
    has_drag = lcheck_option_pair(L, 2, "drag", what, drag);
    has_sfric = lcheck_option_pair(L, 2, "surface_friction", what, sfric);
    has_limits = lcheck_option_real(L, 2, "min_speed", what, &min_speed);
    has_limits |= lcheck_option_real(L, 2, "max_speed", what, &max_speed);
    has_ud = lcheck_option_integer(L, 2, "user_data", what, LUA_MININTEGER, LUA_MAXINTEGER,
                                   &user_data);
    if (lcheck_getoption(L, 2, "name")) {
        if (lua_type(L, -1) != LUA_TSTRING) lcheck_option_error(L, what, "name", "a string");
    } else {
        lua_pushnil(L);
    }
    has_circle = lcheck_option_real(L, 2, "circle", what, &circle);
    has_aabb = lcheck_option_pair(L, 2, "aabb", what, aabb);
    has_rest = lcheck_option_real(L, 2, "restitution", what, &restitution);
    has_fric = lcheck_option_real(L, 2, "friction", what, &friction);
    has_sensor = lcheck_option_boolean(L, 2, "sensor", what, &sensor);
    has_filter = lcheck_option_integer(L, 2, "category", what, 0, 0xFFFFFFFF, &category);
    has_filter |= lcheck_option_integer(L, 2, "mask", what, 0, 0xFFFFFFFF, &mask);
    has_one_way = lcheck_option_pair(L, 2, "one_way", what, one_way);
    if (has_circle && has_aabb)
        luaL_error(L, "%s: options 'circle' and 'aabb' exclude each other", what);
    /* Stack: world, options, name.  The value first, so that nothing after the body exists
     * needs Lua memory except the table insert, which runs protected. */
    b = lbody_new(L, 1, 0);
    lua_pushvalue(L, 3);
    lua_setiuservalue(L, -2, LBODY_UV_NAME);
    b->type = type;

    st = rg_body_create(w, type, mass, (rg_vec2){ x, y }, &h);
    if (st != RG_OK) return lcheck_status(L, w, st, what);
#define TRY(cond, call, opt)                                                    \
    if (st == RG_OK && (cond)) {                                                \
        st = (call);                                                            \
        if (st != RG_OK) failed = (opt);                                        \
    }
    TRY(has_v, rg_body_set_velocity(w, h, (rg_vec2){ vx, vy }), "vx/vy")
    TRY(has_gscale, rg_body_set_gravity_scale(w, h, gscale), "gravity_scale")
    TRY(has_drag, rg_body_set_drag(w, h, drag[0], drag[1]), "drag")
    TRY(has_sfric, rg_body_set_surface_friction(w, h, sfric[0], sfric[1]), "surface_friction")
    TRY(has_limits, rg_body_set_speed_limits(w, h, min_speed, max_speed), "min_speed/max_speed")
    TRY(has_ud, rg_body_set_user_data(w, h, (uint64_t)user_data), "user_data")
    TRY(has_circle, rg_body_set_circle(w, h, circle), "circle")
    TRY(has_aabb, rg_body_set_aabb(w, h, aabb[0], aabb[1]), "aabb")
    TRY(has_rest, rg_body_set_restitution(w, h, restitution), "restitution")
    TRY(has_fric, rg_body_set_friction(w, h, friction), "friction")
    TRY(has_sensor, rg_body_set_sensor(w, h, sensor), "sensor")
    TRY(has_filter, rg_body_set_filter(w, h, (uint32_t)category, (uint32_t)mask), "category/mask")
    TRY(has_one_way, rg_body_set_one_way(w, h, (rg_vec2){ one_way[0], one_way[1] }), "one_way")
#undef TRY
    if (st != RG_OK) {
        char why[LCHECK_REASON_SIZE];
        lcheck_copyreason(w, st, why, sizeof why);   /* before the destroy replaces it */
        rg_body_destroy(w, h);
        return luaL_error(L, "%s: option '%s': %s", what, failed, why);
    }
    b->h = h;
    b->serial = lw->next_serial++;
    lbody_refresh(b);
    /* live[h] = body, protected: under a memory cap the insert may fail, and then the body
     * must not stay behind in the world. */
    lua_pushcfunction(L, lworld_rawset3);
    lua_getiuservalue(L, 1, LWORLD_UV_LIVE);
    lua_pushinteger(L, lbody_key(h));
    lua_pushvalue(L, -4);
    if (lua_pcall(L, 3, 0, 0) != LUA_OK) {
        rg_body_destroy(w, h);
        b->h = 0;
        return lua_error(L);
    }
    lbody_retire(L, 1, h);
    lworld_charge_overlaps(L, w, h);
    return 1;
}

/* Bodies of the world in creation order. */
typedef struct lbody_ref {
    lua_Integer serial;
    lua_Integer key;
} lbody_ref;

static int lbody_ref_cmp(const void *x, const void *y)
{
    const lbody_ref *a = (const lbody_ref *)x, *b = (const lbody_ref *)y;
    return (a->serial > b->serial) - (a->serial < b->serial);
}

static int lbody_all(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    int n = 0, i, cap = rg_world_body_count(w);
    lbody_ref *refs;
    lua_settop(L, 1);
    lua_getiuservalue(L, 1, LWORLD_UV_LIVE);   /* 2 */
    refs = (lbody_ref *)lua_newuserdatauv(L, (size_t)(cap > 0 ? cap : 1) * sizeof *refs, 0);
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
    qsort(refs, (size_t)n, sizeof *refs, lbody_ref_cmp);
    lworld_charge(L, n);
    lua_createtable(L, n, 0);
    for (i = 0; i < n; i++) {
        lua_rawgeti(L, 2, refs[i].key);
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

/* ---------------------------------------------------------------- lifecycle */

static int lbody_destroy(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    rg_world *w = b->world->w;
    if (w == NULL || b->retired || rg_body_destroy(w, b->h) != RG_OK) {
        lua_pushboolean(L, 0);
        return 1;
    }
    /* Move the value from live to dead; setting an existing key to nil never allocates. */
    lua_getiuservalue(L, 1, LBODY_UV_WORLD);
    lua_getiuservalue(L, -1, LWORLD_UV_LIVE);
    lua_pushnil(L);
    lua_rawseti(L, -2, lbody_key(b->h));
    lua_pop(L, 1);
    lua_getiuservalue(L, -1, LWORLD_UV_DEAD);
    lua_pushvalue(L, 1);
    lua_rawseti(L, -2, lbody_key(b->h));
    lua_pushboolean(L, 1);
    return 1;
}

static int lbody_close(lua_State *L)
{
    lua_settop(L, 1);
    lbody_destroy(L);
    return 0;
}

static int lbody_live(const lbody *b)
{
    return b->world->w != NULL && !b->retired && rg_body_is_valid(b->world->w, b->h);
}

static int lbody_is_valid(lua_State *L)
{
    lua_pushboolean(L, lbody_live(lbody_check(L, 1)));
    return 1;
}

static int lbody_tostring(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    const char *state = !lbody_live(b) ? "destroyed"
                        : b->type >= 0 && b->type <= 2 ? lcheck_type_names[b->type] : "?";
    lua_getiuservalue(L, 1, LBODY_UV_NAME);
    if (lua_isstring(L, -1))
        lua_pushfstring(L, "rigid.body #%I \"%s\" (%s)", b->serial, lua_tostring(L, -1), state);
    else
        lua_pushfstring(L, "rigid.body #%I (%s)", b->serial, state);
    return 1;
}

/* Two values of one body are the same body (the binding keeps one value per body, so this
 * only matters for a value made after the first was collected).  A retired value is only
 * itself: its handle names a body created after it. */
static int lbody_eq(lua_State *L)
{
    const lbody *a = lbody_test(L, 1);
    const lbody *b = lbody_test(L, 2);
    lua_pushboolean(L, a != NULL && b != NULL && a->h == b->h && a->world == b->world &&
                           !a->retired && !b->retired);
    return 1;
}

static int lbody_name(lua_State *L)
{
    lbody_check(L, 1);
    lua_getiuservalue(L, 1, LBODY_UV_NAME);
    return 1;
}

static int lbody_world(lua_State *L)
{
    lbody_check(L, 1);
    lua_getiuservalue(L, 1, LBODY_UV_WORLD);
    return 1;
}

static int lbody_id(lua_State *L)
{
    lua_pushinteger(L, lbody_key(lbody_check(L, 1)->h));
    return 1;
}

/* ---------------------------------------------------------------- getters and setters
 *
 * One function per shape of call; each method below names the library call and its Lua
 * name (for errors: the library says which argument broke which rule). */

typedef rg_status (*lbody_getvec)(const rg_world *, rg_body, rg_vec2 *);
typedef rg_status (*lbody_setvec)(rg_world *, rg_body, rg_vec2);
typedef rg_status (*lbody_getreal)(const rg_world *, rg_body, rg_real *);
typedef rg_status (*lbody_setreal)(rg_world *, rg_body, rg_real);
typedef rg_status (*lbody_setreal2)(rg_world *, rg_body, rg_real, rg_real);
typedef rg_status (*lbody_getreal2)(const rg_world *, rg_body, rg_real *, rg_real *);
typedef rg_status (*lbody_getflag)(const rg_world *, rg_body, int32_t *);

static int lbody_get_vec2(lua_State *L, lbody_getvec get, const char *what)
{
    lbody *b = lbody_check(L, 1);
    rg_world *w = lbody_world_of(L, b);
    rg_vec2 v;
    LCHECK(L, w, get(w, b->h, &v), what);
    lcheck_pushvec2(L, v);
    return 2;
}

static int lbody_set_vec2(lua_State *L, lbody_setvec set, const char *what)
{
    lbody *b = lbody_check(L, 1);
    rg_vec2 v = lcheck_vec2(L, 2);
    rg_world *w = lbody_world_of(L, b);
    LCHECK(L, w, set(w, b->h, v), what);
    return 0;
}

static int lbody_get_real(lua_State *L, lbody_getreal get, const char *what)
{
    lbody *b = lbody_check(L, 1);
    rg_world *w = lbody_world_of(L, b);
    rg_real v = 0;
    LCHECK(L, w, get(w, b->h, &v), what);
    lcheck_pushreal(L, v);
    return 1;
}

static int lbody_set_real(lua_State *L, lbody_setreal set, const char *what)
{
    lbody *b = lbody_check(L, 1);
    rg_real v = lcheck_real(L, 2);
    rg_world *w = lbody_world_of(L, b);
    LCHECK(L, w, set(w, b->h, v), what);
    return 0;
}

/* Two numbers; when opt, an omitted second one is 0. */
static int lbody_set_real2(lua_State *L, lbody_setreal2 set, int opt, const char *what)
{
    lbody *b = lbody_check(L, 1);
    rg_real first = lcheck_real(L, 2), second = opt ? lcheck_optreal(L, 3, 0) : lcheck_real(L, 3);
    rg_world *w = lbody_world_of(L, b);
    LCHECK(L, w, set(w, b->h, first, second), what);
    return 0;
}

static int lbody_get_real2(lua_State *L, lbody_getreal2 get, const char *what)
{
    lbody *b = lbody_check(L, 1);
    rg_world *w = lbody_world_of(L, b);
    rg_real first = 0, second = 0;
    LCHECK(L, w, get(w, b->h, &first, &second), what);
    lcheck_pushreal(L, first);
    lcheck_pushreal(L, second);
    return 2;
}

static int lbody_get_flag(lua_State *L, lbody_getflag get, const char *what)
{
    lbody *b = lbody_check(L, 1);
    rg_world *w = lbody_world_of(L, b);
    int32_t v = 0;
    LCHECK(L, w, get(w, b->h, &v), what);
    lua_pushboolean(L, v != 0);
    return 1;
}

#define LBODY_GET_VEC2(name, call)                                              \
    static int lbody_##name(lua_State *L) { return lbody_get_vec2(L, call, #name); }
#define LBODY_SET_VEC2(name, call)                                              \
    static int lbody_##name(lua_State *L) { return lbody_set_vec2(L, call, #name); }
#define LBODY_GET_REAL(name, call)                                              \
    static int lbody_##name(lua_State *L) { return lbody_get_real(L, call, #name); }
#define LBODY_SET_REAL(name, call)                                              \
    static int lbody_##name(lua_State *L) { return lbody_set_real(L, call, #name); }
#define LBODY_SET_REAL2(name, call, opt)                                        \
    static int lbody_##name(lua_State *L) { return lbody_set_real2(L, call, opt, #name); }
#define LBODY_GET_REAL2(name, call)                                             \
    static int lbody_##name(lua_State *L) { return lbody_get_real2(L, call, #name); }
#define LBODY_GET_FLAG(name, call)                                              \
    static int lbody_##name(lua_State *L) { return lbody_get_flag(L, call, #name); }

LBODY_GET_VEC2(position, rg_body_get_position)
LBODY_GET_VEC2(velocity, rg_body_get_velocity)
LBODY_GET_VEC2(interpolated_position, rg_body_get_interpolated_position)
LBODY_GET_VEC2(acceleration, rg_body_get_acceleration)
static int lbody_set_position(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    rg_vec2 v = lcheck_vec2(L, 2);
    rg_world *w = lbody_world_of(L, b);
    LCHECK(L, w, rg_body_set_position(w, b->h, v), "set_position");
    lworld_charge_overlaps(L, w, b->h);
    return 0;
}
LBODY_SET_VEC2(set_velocity, rg_body_set_velocity)
LBODY_SET_VEC2(apply_force, rg_body_apply_force)
LBODY_SET_VEC2(apply_impulse, rg_body_apply_impulse)
LBODY_GET_REAL(mass, rg_body_get_mass)
LBODY_GET_REAL(restitution, rg_body_get_restitution)
LBODY_GET_REAL(friction, rg_body_get_friction)
LBODY_GET_REAL(gravity_scale, rg_body_get_gravity_scale)
LBODY_GET_REAL2(drag, rg_body_get_drag)
LBODY_GET_REAL2(speed_limits, rg_body_get_speed_limits)
LBODY_SET_REAL(set_mass, rg_body_set_mass)
LBODY_SET_REAL(set_gravity_scale, rg_body_set_gravity_scale)
LBODY_SET_REAL(set_restitution, rg_body_set_restitution)
LBODY_SET_REAL(set_friction, rg_body_set_friction)
LBODY_SET_REAL2(set_drag, rg_body_set_drag, 1)
LBODY_SET_REAL2(set_surface_friction, rg_body_set_surface_friction, 0)
LBODY_SET_REAL2(set_speed_limits, rg_body_set_speed_limits, 1)
LBODY_GET_FLAG(grounded, rg_body_is_grounded)
LBODY_GET_FLAG(is_sensor, rg_body_is_sensor)
LBODY_GET_FLAG(is_awake, rg_body_is_awake)

static int lbody_type(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    rg_world *w = lbody_world_of(L, b);
    int32_t t = 0;
    LCHECK(L, w, rg_body_get_type(w, b->h, &t), "type");
    lua_pushstring(L, lcheck_type_names[t >= 0 && t <= 2 ? t : 0]);
    return 1;
}

static int lbody_user_data(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    rg_world *w = lbody_world_of(L, b);
    uint64_t u = 0;
    LCHECK(L, w, rg_body_get_user_data(w, b->h, &u), "user_data");
    lua_pushinteger(L, (lua_Integer)u);
    return 1;
}

static int lbody_set_user_data(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    lua_Integer u = lcheck_integer(L, 2);
    rg_world *w = lbody_world_of(L, b);
    LCHECK(L, w, rg_body_set_user_data(w, b->h, (uint64_t)u), "set_user_data");
    return 0;
}

/* ---------------------------------------------------------------- shapes and contacts */

/* What the binding keeps of a live body's shape for when it is destroyed (lbody_info),
 * read from the library. */
void lbody_refresh(lbody *b)
{
    rg_world *w = b->world->w;
    int32_t kind, sensor, type;
    rg_vec2 half;
    if (w == NULL || b->retired || !rg_body_is_valid(w, b->h)) return;
    if (rg_body_get_type(w, b->h, &type) == RG_OK) b->type = type;
    if (rg_body_get_shape(w, b->h, &kind, &half) == RG_OK) {
        b->shape = kind == RG_SHAPE_CIRCLE ? LRIGID_SHAPE_CIRCLE
                   : kind == RG_SHAPE_AABB ? LRIGID_SHAPE_AABB : LRIGID_SHAPE_NONE;
        b->size[0] = (double)half.x;
        b->size[1] = (double)half.y;
    }
    if (rg_body_is_sensor(w, b->h, &sensor) == RG_OK) b->sensor = sensor;
}

static int lbody_set_circle(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    rg_real r = lcheck_real(L, 2);
    rg_world *w = lbody_world_of(L, b);
    LCHECK(L, w, rg_body_set_circle(w, b->h, r), "set_circle");
    lbody_refresh(b);
    lworld_charge_overlaps(L, w, b->h);
    return 0;
}

static int lbody_set_aabb(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    rg_real hw = lcheck_real(L, 2), hh = lcheck_real(L, 3);
    rg_world *w = lbody_world_of(L, b);
    LCHECK(L, w, rg_body_set_aabb(w, b->h, hw, hh), "set_aabb");
    lbody_refresh(b);
    lworld_charge_overlaps(L, w, b->h);
    return 0;
}

static int lbody_clear_shape(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    rg_world *w = lbody_world_of(L, b);
    LCHECK(L, w, rg_body_clear_shape(w, b->h), "clear_shape");
    lbody_refresh(b);
    return 0;
}

/* "circle", r | "aabb", half_width, half_height | "none" */
static int lbody_shape(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    rg_world *w = lbody_world_of(L, b);
    int32_t kind = 0;
    rg_vec2 half;
    LCHECK(L, w, rg_body_get_shape(w, b->h, &kind, &half), "shape");
    if (kind == RG_SHAPE_CIRCLE) {
        lua_pushliteral(L, "circle");
        lcheck_pushreal(L, half.x);
        return 2;
    }
    if (kind == RG_SHAPE_AABB) {
        lua_pushliteral(L, "aabb");
        lcheck_pushvec2(L, half);
        return 3;
    }
    lua_pushliteral(L, "none");
    return 1;
}

static int lbody_set_sensor(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    int s = lcheck_boolean(L, 2);
    rg_world *w = lbody_world_of(L, b);
    LCHECK(L, w, rg_body_set_sensor(w, b->h, s), "set_sensor");
    b->sensor = s;
    return 0;
}

static int lbody_set_filter(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    uint32_t category = lcheck_mask(L, 2), mask = lcheck_mask(L, 3);
    rg_world *w = lbody_world_of(L, b);
    LCHECK(L, w, rg_body_set_filter(w, b->h, category, mask), "set_filter");
    return 0;
}

static int lbody_filter(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    rg_world *w = lbody_world_of(L, b);
    uint32_t category = 0, mask = 0;
    LCHECK(L, w, rg_body_get_filter(w, b->h, &category, &mask), "filter");
    lua_pushinteger(L, (lua_Integer)category);
    lua_pushinteger(L, (lua_Integer)mask);
    return 2;
}

static int lbody_wake(lua_State *L)
{
    lbody *b = lbody_check(L, 1);
    rg_world *w = lbody_world_of(L, b);
    LCHECK(L, w, rg_body_wake(w, b->h), "wake");
    return 0;
}

/* ---------------------------------------------------------------- tables */

const luaL_Reg lbody_world_methods[] = {
    { "body", lbody_create },
    { "bodies", lbody_all },
    { NULL, NULL }
};

const luaL_Reg lbody_methods[] = {
    { "position", lbody_position },
    { "velocity", lbody_velocity },
    { "set_position", lbody_set_position },
    { "set_velocity", lbody_set_velocity },
    { "apply_force", lbody_apply_force },
    { "apply_impulse", lbody_apply_impulse },
    { "interpolated_position", lbody_interpolated_position },
    { "acceleration", lbody_acceleration },
    { "type", lbody_type },
    { "mass", lbody_mass },
    { "set_mass", lbody_set_mass },
    { "set_gravity_scale", lbody_set_gravity_scale },
    { "gravity_scale", lbody_gravity_scale },
    { "set_drag", lbody_set_drag },
    { "drag", lbody_drag },
    { "set_surface_friction", lbody_set_surface_friction },
    { "set_speed_limits", lbody_set_speed_limits },
    { "speed_limits", lbody_speed_limits },
    { "user_data", lbody_user_data },
    { "set_user_data", lbody_set_user_data },
    { "name", lbody_name },
    { "world", lbody_world },
    { "id", lbody_id },
    { "is_valid", lbody_is_valid },
    { "destroy", lbody_destroy },
    { "grounded", lbody_grounded },
    { "set_circle", lbody_set_circle },
    { "set_aabb", lbody_set_aabb },
    { "set_restitution", lbody_set_restitution },
    { "set_friction", lbody_set_friction },
    { "set_sensor", lbody_set_sensor },
    { "set_filter", lbody_set_filter },
    { "filter", lbody_filter },
    { "clear_shape", lbody_clear_shape },
    { "shape", lbody_shape },
    { "restitution", lbody_restitution },
    { "friction", lbody_friction },
    { "is_sensor", lbody_is_sensor },
    { "is_awake", lbody_is_awake },
    { "wake", lbody_wake },
    { NULL, NULL }
};

const luaL_Reg lbody_meta[] = {
    { "__tostring", lbody_tostring },
    { "__eq", lbody_eq },
    { "__close", lbody_close },
    { NULL, NULL }
};
