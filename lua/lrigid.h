/* lrigid.h: the Lua 5.4 binding of rigid (module `rigid`) and what a host sees of it. */
#ifndef LRIGID_H
#define LRIGID_H

#include <lua.h>

#include "rigid.h"

/* luaopen_rigid is the one symbol build/rigid.so exports. */
#if defined(_WIN32)
#define LRIGID_API __declspec(dllexport)
#elif defined(__GNUC__) || defined(__clang__)
#define LRIGID_API __attribute__((visibility("default")))
#else
#define LRIGID_API
#endif

LRIGID_API int luaopen_rigid(lua_State *L);

/* ---------------------------------------------------------------- host interface
 * A host that links the binding statically (build/rigid) may watch what scripts do.  None
 * of this is reachable from Lua. */

/* Shape of a body as the binding set it. */
#define LRIGID_SHAPE_NONE   0
#define LRIGID_SHAPE_CIRCLE 1
#define LRIGID_SHAPE_AABB   2

typedef struct lrigid_body_info {
    rg_body handle;
    lua_Integer serial;  /* creation order within its world, from 1; 0 for a handle met only
                            after its body was destroyed and its Lua value collected */
    int32_t type;        /* RG_BODY_* at creation */
    int32_t shape;       /* LRIGID_SHAPE_* */
    double size[2];      /* radius, or half width and half height (m) */
    int32_t sensor;
    const char *name;    /* the `name` option, or NULL; valid while the body value is */
} lrigid_body_info;

typedef struct lrigid_hooks {
    /* Cost of work done in C on the script's behalf (a world:step by the touching pairs,
     * awake bodies and springs it leaves; bodies visited by a query; a snapshot saved,
     * restored or hashed by its bytes), in units comparable to VM instructions.  Must not
     * raise. */
    void (*charge)(lua_State *L, void *ud, double units);
    /* Called after world:step or world:advance took `steps` (> 0) steps; the world is at
     * stack index world_index.  May raise a Lua error, which reaches the script. */
    void (*after_step)(lua_State *L, void *ud, int world_index, int steps);
    void *ud;
    /* The task system every world made from now on steps with (rg_world_set_task_system);
     * NULL: one thread.  Not copied: it must outlive the worlds. */
    const rg_task_system *tasks;
} lrigid_hooks;

/* Installs hooks for every world of this state (NULL removes them).  The struct is not
 * copied: it must outlive the state or the next call. */
void lrigid_sethooks(lua_State *L, const lrigid_hooks *hooks);

/* The rg_world of the world value at idx, or NULL when idx is not an open world. */
rg_world *lrigid_toworld(lua_State *L, int idx);
/* Pushes the table handle (integer) -> body value of the live bodies of the world at idx.
 * Read it, never change it. */
void lrigid_pushbodies(lua_State *L, int idx);
/* Fills *out from the body value at idx; 0 when idx is not a body. */
int lrigid_tobody(lua_State *L, int idx, lrigid_body_info *out);
/* Pushes the body value for handle h of the world at world_idx: the value scripts hold
 * when there is one, a new one otherwise (identity). */
void lrigid_pushbody(lua_State *L, int world_idx, rg_body h);

/* Pushes the contact events of the last step of the world at world_idx, as world:events()
 * returns them (the bodies are the values scripts hold). */
void lrigid_pushevents(lua_State *L, int world_idx);

#endif
