/* lrigid_int.h: what the files of the Lua binding share; a host sees lrigid.h only.
 *
 * The files and what each may use (no circle):
 *   lcheck.c   argument and option checks, errors                 (nothing of the binding)
 *   lworld.c   the world value and its settings, the host hooks    lcheck
 *   lbody.c    body identity and the body methods, world:body/bodies   lcheck, lworld
 *   lspring.c  springs, world:spring                               lcheck, lworld, lbody
 *   lquery.c   contact events and queries                          lcheck, lworld, lbody
 *   lcontact.c a body's contacts, one-way, passing through, moving  lcheck, lbody, lquery
 *   lsnapshot.c world:save, world:restore, world:hash               lcheck, lworld, lbody
 *   lrigid.c   luaopen_rigid (metatables) and the host interface    all of the above
 *
 * Every method gets its class's metatable as upvalue 1 (lrigid.c), which lcheck_self
 * compares with the argument's. */
#ifndef LRIGID_INT_H
#define LRIGID_INT_H

#include <lauxlib.h>
#include <lua.h>

#include "lrigid.h"

#define LWORLD_MT  "rigid.world"
#define LBODY_MT   "rigid.body"
#define LSPRING_MT "rigid.spring"

/* ---------------------------------------------------------------- lcheck.c */

/* The userdata at i when its metatable is upvalue 1 of the running method (a pointer
 * compare, no registry lookup); else raises "tname expected". */
void *lcheck_self(lua_State *L, int i, const char *tname);
/* A number argument that is finite (numeric strings are refused). */
lua_Number lcheck_finite(lua_State *L, int i);
/* A finite number that fits rg_real (float builds refuse |v| > FLT_MAX). */
rg_real lcheck_real(lua_State *L, int i);
rg_real lcheck_optreal(lua_State *L, int i, rg_real def);
rg_vec2 lcheck_vec2(lua_State *L, int i);        /* arguments i and i + 1 */
/* An integer in [0, 0xFFFFFFFF] (categories and masks); the optional one defaults to all. */
uint32_t lcheck_mask(lua_State *L, int i);
uint32_t lcheck_optmask(lua_State *L, int i);
/* luaL_checkinteger, a string of digits charged to the host by its length first. */
lua_Integer lcheck_integer(lua_State *L, int i);
/* An integer in [lo, hi]; msg says what is wrong when it is outside. */
int32_t lcheck_int32(lua_State *L, int i, int32_t lo, int32_t hi, const char *msg);
int lcheck_boolean(lua_State *L, int i);
/* One of names (a NULL-terminated list); returns its index.  what names the kind; the
 * error lists the names. */
int lcheck_enum(lua_State *L, int i, const char *const names[], const char *what);

void lcheck_pushreal(lua_State *L, rg_real v);
void lcheck_pushvec2(lua_State *L, rg_vec2 v);   /* pushes x, y */

/* Raises for the failed call of status s on w: "what: " and the library's reason
 * (rg_world_last_error without the C function's name, which what replaces); w may be NULL
 * (rg_status_string then).  A stale handle raises "attempt to use a destroyed body". */
int lcheck_status(lua_State *L, const rg_world *w, rg_status s, const char *what);
/* That reason, valid until the next call on w, and a copy of it for a failure that must
 * undo library calls (which change it) before it raises. */
#define LCHECK_REASON_SIZE 256   /* rg_world_last_error holds at most 199 bytes */
const char *lcheck_reason(const rg_world *w, rg_status s);
void lcheck_copyreason(const rg_world *w, rg_status s, char *out, size_t size);
#define LCHECK(L, w, call, what)                                                \
    do {                                                                        \
        rg_status st_ = (call);                                                 \
        if (st_ != RG_OK) lcheck_status((L), (w), st_, (what));                 \
    } while (0)

/* Option tables (the table at index t; what names the call in messages).  Every key must
 * be one of names; each option_* returns 1 when the option is present (and valid), 0 when
 * absent, and raises when it is present and wrong. */
void lcheck_option_names(lua_State *L, int t, const char *const names[], const char *what);
int lcheck_getoption(lua_State *L, int t, const char *key);   /* pushes t[key] when present */
int lcheck_option_error(lua_State *L, const char *what, const char *key, const char *expected);
int lcheck_option_real(lua_State *L, int t, const char *key, const char *what, rg_real *out);
int lcheck_option_integer(lua_State *L, int t, const char *key, const char *what,
                          lua_Integer lo, lua_Integer hi, lua_Integer *out);
int lcheck_option_pair(lua_State *L, int t, const char *key, const char *what, rg_real out[2]);
int lcheck_option_boolean(lua_State *L, int t, const char *key, const char *what, int *out);
int lcheck_option_enum(lua_State *L, int t, const char *key, const char *what,
                       const char *const names[], int *out);

/* Lua names of RG_INTEGRATOR_* and RG_BODY_*, indexed by value. */
extern const char *const lcheck_integrator_names[];
extern const char *const lcheck_type_names[];

/* ---------------------------------------------------------------- lworld.c */

/* Uservalues of a world: the bodies created through Lua, by handle.  `live` holds every
 * live one strongly (a body lives in its world whether or not a script keeps its value),
 * `dead` holds destroyed ones weakly, so a body keeps its identity for as long as anyone
 * holds it.  `springs` holds the spring values weakly by handle (lspring.c).  A restore
 * (lsnapshot.c) puts every body value where the restored world says it is; `kept` holds,
 * by slot, the body list of each state the world keeps (world:save_slot). */
#define LWORLD_UV_LIVE    1
#define LWORLD_UV_DEAD    2
#define LWORLD_UV_SPRINGS 3
#define LWORLD_UV_KEPT    4   /* by slot: the body list kept with the state (lsnapshot.c) */
#define LWORLD_UVS        4

typedef struct lworld {
    rg_world *w;             /* NULL once closed */
    lua_Integer next_serial;
} lworld;

lworld *lworld_test(lua_State *L, int i);       /* NULL when i is not a world */
lworld *lworld_check(lua_State *L, int i);      /* methods only: compares with upvalue 1 */
rg_world *lworld_checkopen(lua_State *L, int i);
/* Reports work done in C for the script (see lrigid_hooks.charge). */
void lworld_charge(lua_State *L, double units);
/* Charges a shape put where it overlaps others for the pairs the next step makes of them
 * (the step charges its pairs only once it has run: a crowd of huge shapes would make its
 * first step cost what no budget allowed), LWORLD_UNITS_PAIR per other shape whose box meets
 * the body's. */
void lworld_charge_overlaps(lua_State *L, rg_world *w, rg_body h);
void lworld_sethooks(lua_State *L, const lrigid_hooks *hooks);
/* t[k] = v for (t, k, v) on the stack: called with lua_pcall, to insert into the world's
 * tables where a memory error must be caught and the library call undone. */
int lworld_rawset3(lua_State *L);
/* rigid.world{...}; upvalue 1 is the world metatable. */
int lworld_new(lua_State *L);
int lworld_gc(lua_State *L);
extern const luaL_Reg lworld_methods[];
extern const luaL_Reg lworld_meta[];

/* ---------------------------------------------------------------- lbody.c */

/* Uservalues of a body: its world value, which keeps the world alive, and its name. */
#define LBODY_UV_WORLD 1
#define LBODY_UV_NAME  2

typedef struct lbody {
    rg_body h;
    lworld *world;           /* kept alive by uservalue LBODY_UV_WORLD */
    lua_Integer serial;      /* creation order in its world (a restore puts back the saved) */
    int32_t type;
    int32_t shape;           /* LRIGID_SHAPE_*, as the library last had it (lbody_refresh) */
    double size[2];
    int32_t sensor;
    int32_t retired;         /* 1: destroyed for good, h now names a later body (lbody.c) */
} lbody;

lbody *lbody_test(lua_State *L, int i);         /* NULL when i is not a body */
lbody *lbody_check(lua_State *L, int i);        /* methods only: compares with upvalue 1 */
/* The open world of body b; raises when it is closed or b is retired. */
rg_world *lbody_world_of(lua_State *L, const lbody *b);
/* b's handle, for a body given as an argument; raises as lbody_world_of does. */
rg_body lbody_handle(lua_State *L, const lbody *b);
/* A new body value for handle h of the world at world_idx (no name, serial 0), pushed. */
lbody *lbody_new(lua_State *L, int world_idx, rg_body h);
/* Reads b's type, shape and sensor flag from the library when b is live. */
void lbody_refresh(lbody *b);
/* Pushes the body value for handle h of the world at world_idx (see lrigid_pushbody). */
void lbody_push(lua_State *L, int world_idx, rg_body h);
int lbody_info(lua_State *L, int idx, lrigid_body_info *out);
extern const luaL_Reg lbody_world_methods[];    /* world:body, world:bodies */
extern const luaL_Reg lbody_methods[];
extern const luaL_Reg lbody_meta[];

/* ---------------------------------------------------------------- lspring.c */

extern const luaL_Reg lspring_world_methods[];  /* world:spring */
extern const luaL_Reg lspring_methods[];
extern const luaL_Reg lspring_meta[];

/* ---------------------------------------------------------------- lquery.c */

/* Pushes the contact events of the last step of the open world at idx (world:events). */
void lquery_pushevents(lua_State *L, int idx);
/* Pushes a ray hit as { body, x, y, nx, ny, fraction } (the world value at world_idx). */
void lquery_pushhit(lua_State *L, int world_idx, const rg_ray_hit *hit);
/* events, raycast, raycast_all, query_aabb, query_point, cast_circle, cast_box */
extern const luaL_Reg lquery_world_methods[];

/* ---------------------------------------------------------------- lcontact.c */

/* body:contacts, body:pass_through, body:set_one_way, body:one_way, body:move */
extern const luaL_Reg lcontact_methods[];

/* ---------------------------------------------------------------- lsnapshot.c */

/* world:save, world:restore, world:hash */
extern const luaL_Reg lsnap_world_methods[];

#endif
