/* lrigid.c: the Lua 5.4 binding of rigid (module `rigid`): luaopen_rigid and the
 * interface a host sees (lrigid.h).  The methods live in lworld.c, lbody.c, lspring.c,
 * lquery.c and lcontact.c, the checks in lcheck.c (lrigid_int.h).
 *
 * Units are SI.  Numbers must be numbers (not numeric strings) and finite; option tables
 * accept only the names listed; a destroyed body raises "attempt to use a destroyed body".
 *
 *   rigid.version, rigid.real_size (4 or 8), rigid.collision (always true)
 *   rigid.world{ gravity = {x, y}, wind = {x, y}, integrator = "explicit" | "semi_implicit"
 *                | "verlet" | "rk4", dt = 1/60, max_steps = 8 }          -- all optional
 *   world:body{ type = "static" | "kinematic" | "dynamic", mass, x, y, vx, vy, gravity_scale,
 *               drag = {linear, quadratic}, surface_friction = {mu, normal_force},
 *               min_speed, max_speed, user_data (integer), name (string, for pictures),
 *               circle = r | aabb = {hw, hh}, restitution, friction, sensor (boolean),
 *               category, mask, one_way = {nx, ny} }                    --> body
 *   world:spring{ a = body, b = body | anchor = {x, y}, rest_length, stiffness, damping }
 *   world:step(dt)  world:advance(frame_time) --> steps  world:alpha()
 *   world:gravity() / set_gravity(x, y)   world:wind() / set_wind(x, y)
 *   world:integrator() / set_integrator(name)   world:fixed_step() / set_fixed_step(dt [, max])
 *   world:bodies() --> live bodies in creation order   world:body_count()  world:spring_count()
 *   world:events() --> { kind = "begin" | "end", a, b, nx, ny, x, y, depth, speed, sensor }...
 *                      (of the last world:step, or of every step of the last world:advance)
 *   world:raycast(x, y, dx, dy [, mask]) --> body, hit_x, hit_y, nx, ny, fraction | nil
 *   world:query_aabb(x0, y0, x1, y1 [, mask]) --> { body... }
 *   world:raycast_all(x, y, dx, dy [, mask]) --> { { body, x, y, nx, ny, fraction }... }
 *   world:query_point(x, y [, mask]) --> { body... }
 *   world:cast_circle(r, x, y, dx, dy [, mask]), world:cast_box(hw, hh, x, y, dx, dy [, mask])
 *                      --> body, hit_x, hit_y, nx, ny, fraction | nil   (as world:raycast)
 *   world:set_sleeping(on) / sleeping()  set_sleep_thresholds(speed, time)
 *   world:set_solver_iterations(velocity [, position]) (position kept when omitted)
 *   world:solver_iterations() --> velocity, position  set_contact_tuning(slop, bias_rate,
 *   max_push, restitution_threshold)  set_continuous(on)  awake_body_count()  touching_count()
 *   world:save() --> string   world:restore(string)   world:hash() --> integer (64 bits)
 *                      (a restore brings back the saved bodies as the values they had, and
 *                      destroys those made since; a bad string raises and changes nothing)
 *   world:save_slot(k)  restore_slot(k)  drop_slot(k)   the world's kept states, k in [0, 64)
 *                      (restore_slot as restore, without the checks a string needs)
 *   world:close() (also <close> and garbage collection)  world:is_open()
 *   body:position() / set_position(x, y)   body:velocity() / set_velocity(vx, vy)
 *   body:apply_force(fx, fy)  body:apply_impulse(ix, iy)  body:acceleration()
 *   body:interpolated_position()  body:type()  body:mass() / set_mass(m)
 *   body:set_gravity_scale(s) / gravity_scale()  set_drag(linear [, quadratic]) / drag() -->
 *   linear, quadratic  set_surface_friction(mu, n)  set_speed_limits(min [, max]) /
 *   speed_limits() --> min, max  user_data() / set_user_data(i)  name()  world()  id()
 *   body:set_circle(r)  set_aabb(hw, hh)  clear_shape()  shape() --> "circle", r | "aabb",
 *   hw, hh | "none"   restitution() / set_restitution(e)  friction() / set_friction(mu)
 *   is_sensor() / set_sensor(on)  filter() / set_filter(category, mask)  grounded()
 *   is_awake()  wake()  is_valid()  destroy() (also <close>)
 *   body:set_one_way(nx, ny) ((0, 0): two-way)  one_way() --> nx, ny  pass_through(other)
 *   body:contacts() --> { { other, nx, ny, x, y, separation, normal_impulse, tangent_impulse,
 *                       sensor }... }   (after the last step, by the other body's handle)
 *   body:move(tx, ty [, { mask = m, response = "slide" | "touch" | "cross" }]) --> x, y,
 *                       { { body, x, y, nx, ny, fraction }... }   (the surfaces met)
 *   spring:destroy()  spring:is_valid()
 * A body is one Lua value wherever it appears (world:body, world:bodies, events, queries),
 * also after it is destroyed, for as long as anyone holds it; a world stays alive while any
 * of its bodies is held. */
#include "lrigid_int.h"

/* ---------------------------------------------------------------- host interface */

void lrigid_sethooks(lua_State *L, const lrigid_hooks *hooks)
{
    lworld_sethooks(L, hooks);
}

rg_world *lrigid_toworld(lua_State *L, int idx)
{
    lworld *lw = lworld_test(L, idx);
    return lw != NULL ? lw->w : NULL;
}

void lrigid_pushbodies(lua_State *L, int idx)
{
    lua_getiuservalue(L, idx, LWORLD_UV_LIVE);
}

int lrigid_tobody(lua_State *L, int idx, lrigid_body_info *out)
{
    return lbody_info(L, idx, out);
}

void lrigid_pushbody(lua_State *L, int world_idx, rg_body h)
{
    lbody_push(L, world_idx, h);
}

void lrigid_pushevents(lua_State *L, int world_idx)
{
    lquery_pushevents(L, world_idx);
}

/* ---------------------------------------------------------------- module */

/* Builds a metatable with the methods of every list in __index; every function gets the
 * metatable as upvalue 1 for the fast type check.  Leaves it pushed. */
static void lrigid_newclass(lua_State *L, const char *name, const luaL_Reg *const methods[],
                            const luaL_Reg *meta)
{
    int i;
    luaL_newmetatable(L, name);
    lua_newtable(L);
    for (i = 0; methods[i] != NULL; i++) {
        lua_pushvalue(L, -2);
        luaL_setfuncs(L, methods[i], 1);
    }
    lua_setfield(L, -2, "__index");
    lua_pushvalue(L, -1);
    luaL_setfuncs(L, meta, 1);
    lua_pushstring(L, name);
    lua_setfield(L, -2, "__metatable");
}

LRIGID_API int luaopen_rigid(lua_State *L)
{
    static const luaL_Reg *const world[] = { lworld_methods, lbody_world_methods,
                                             lspring_world_methods, lquery_world_methods,
                                             lsnap_world_methods, NULL };
    static const luaL_Reg *const body[] = { lbody_methods, lcontact_methods, NULL };
    static const luaL_Reg *const spring[] = { lspring_methods, NULL };
    int32_t v = rg_version();
    luaL_checkversion(L);
    lrigid_newclass(L, LBODY_MT, body, lbody_meta);
    lua_pop(L, 1);
    lrigid_newclass(L, LSPRING_MT, spring, lspring_meta);
    lua_pop(L, 1);
    lrigid_newclass(L, LWORLD_MT, world, lworld_meta);
    lua_pushcfunction(L, lworld_gc);
    lua_setfield(L, -2, "__gc");

    lua_newtable(L);
    lua_pushvalue(L, -2);
    lua_pushcclosure(L, lworld_new, 1);
    lua_setfield(L, -2, "world");
    lua_pushfstring(L, "%d.%d.%d", (int)(v / 10000), (int)(v / 100 % 100), (int)(v % 100));
    lua_setfield(L, -2, "version");
    lua_pushinteger(L, rg_real_size());
    lua_setfield(L, -2, "real_size");
    lua_pushboolean(L, 1);   /* documented; scripts written before collision existed test it */
    lua_setfield(L, -2, "collision");
    lua_remove(L, -2);
    return 1;
}
