/* lsnapshot.c: world:save(), world:restore(s) and world:hash(): the library's snapshots
 * (rg_world_save, rg_world_restore, rg_world_hash) with what the binding knows of the bodies;
 * and the kept states (world:save_slot(k), restore_slot(k), drop_slot(k)).
 *
 * A snapshot string holds the library's snapshot and the binding's list of the live bodies
 * (handle, creation serial, name), which the library does not keep.  Restoring it puts every
 * body value where the restored world says it is: a value of a body alive in the snapshot is
 * live again (the same value when the world still holds it for that handle, else a new one
 * with the saved name), every other value is a destroyed body's.  A handle the world gave
 * again after a restore went back before its body's creation (the same handle, as a replay
 * makes the same bodies) holds the new value from then on, and a snapshot of the abandoned
 * timeline brings the body back as that value.  Nothing changes unless all of it
 * succeeds.
 *
 * Format (little-endian, the same in the LuaJIT binding, lua/rigid_jit/snapshot.lua):
 *    0   8  "rgluasn1"
 *    8   4  n: bytes of the body list
 *   12   n  the body list: i64 next serial, u32 count, then per body u64 handle, i64 serial,
 *           u32 name length (0xFFFFFFFF: no name), the name's bytes; in creation order
 *   12+n 8  FNV-1a (64 bits) of bytes 0 .. 12+n-1 (the library's snapshot has its own)
 *   20+n    the library's snapshot, to the end */
#include <stdlib.h>
#include <string.h>

#include "lrigid_int.h"

static const char lsnap_magic[8] = { 'r', 'g', 'l', 'u', 'a', 's', 'n', '1' };
#define LSNAP_HEAD    12            /* magic and n */
#define LSNAP_ENTRY   20            /* an entry without its name */
#define LSNAP_NONAME  0xFFFFFFFFu

/* Snapshots are charged to the host by their size, before the work wherever that size is
 * known first (a string may be any length a script made, a body's name too, and a restore
 * that fails has read it all the same): LSNAP_BYTE_UNITS a byte of a snapshot read or
 * written -- the body list hashed, checked or copied here, the library's part saved,
 * checked or loaded, the copy of the world a restore keeps -- which takes 0.7-1.7 ns, an
 * instruction 1.1-1.4; a unit per LSNAP_HASH_BYTES of the state world:hash reads (0.06-0.1
 * ns a byte); and LSNAP_VALUE_UNITS per body value a restore looks over, the values of
 * destroyed bodies the script still holds included, any number of them (50-126 ns each).
 * lua/bench_sandbox.lua times them. */
#define LSNAP_BYTE_UNITS  1
#define LSNAP_HASH_BYTES  8
#define LSNAP_VALUE_UNITS 64

/* ---------------------------------------------------------------- bytes */

static void lsnap_put(unsigned char *p, uint64_t v, int bytes)
{
    int i;
    for (i = 0; i < bytes; i++) p[i] = (unsigned char)(v >> (8 * i));
}

static uint64_t lsnap_get(const unsigned char *p, int bytes)
{
    uint64_t v = 0;
    int i;
    for (i = 0; i < bytes; i++) v |= (uint64_t)p[i] << (8 * i);
    return v;
}

static uint64_t lsnap_fnv(const unsigned char *p, size_t n)
{
    uint64_t h = 0xcbf29ce484222325ULL;
    size_t i;
    for (i = 0; i < n; i++) h = (h ^ p[i]) * 0x100000001b3ULL;
    return h;
}

static void lsnap_charge_bytes(lua_State *L, size_t bytes)
{
    lworld_charge(L, (double)bytes * LSNAP_BYTE_UNITS);
}

/* The size of the world's snapshot now: what keeping, loading or hashing its state goes
 * through (the library answers for any world that is not NULL). */
static size_t lsnap_size(const rg_world *w)
{
    size_t size = 0;
    return rg_world_save(w, NULL, 0, &size) == RG_OK ? size : 0;
}

/* ---------------------------------------------------------------- save */

typedef struct lsnap_ref {
    lua_Integer serial;
    lua_Integer key;
} lsnap_ref;

static int lsnap_ref_cmp(const void *x, const void *y)
{
    const lsnap_ref *a = (const lsnap_ref *)x, *b = (const lsnap_ref *)y;
    if (a->serial != b->serial) return (a->serial > b->serial) - (a->serial < b->serial);
    return (a->key > b->key) - (a->key < b->key);
}

/* The name of the body value at the top of the stack, pushed (a string or nil). */
static size_t lsnap_name(lua_State *L, const char **name)
{
    size_t len = 0;
    lua_getiuservalue(L, -1, LBODY_UV_NAME);
    *name = lua_tolstring(L, -1, &len);
    return len;
}

/* Pushes the snapshot string of the world at 1 (stack: the world alone): the body list and,
 * with_world, the library's snapshot after it; without, the list alone (what a kept state
 * pairs with).  `what` names the method in errors. */
static void lsnap_push(lua_State *L, rg_world *w, const lworld *lw, int with_world, const char *what)
{
    int count = 0, cap = rg_world_body_count(w), i;
    size_t csize = 0, list = 12, total, off, got = 0;
    lsnap_ref *refs;
    unsigned char *p;
    luaL_Buffer buf;
    if (with_world) LCHECK(L, w, rg_world_save(w, NULL, 0, &csize), what);
    lua_getiuservalue(L, 1, LWORLD_UV_LIVE);   /* 2 */
    refs = (lsnap_ref *)lua_newuserdatauv(L, (size_t)(cap > 0 ? cap : 1) * sizeof *refs, 0);
    lua_pushnil(L);
    while (lua_next(L, 2) != 0) {
        const lbody *b = (const lbody *)lua_touserdata(L, -1);
        const char *name;
        size_t len = lsnap_name(L, &name);
        if (count == cap || b == NULL) luaL_error(L, "%s: the world's bodies changed", what);
        refs[count].serial = b->serial;
        refs[count].key = lua_tointeger(L, -3);
        list += LSNAP_ENTRY + (name != NULL ? len : 0);
        count++;
        lua_pop(L, 2);
    }
    qsort(refs, (size_t)count, sizeof *refs, lsnap_ref_cmp);
    lworld_charge(L, cap);

    total = LSNAP_HEAD + list + 8 + csize;
    lsnap_charge_bytes(L, total);   /* the names copied and hashed, the world written */
    p = (unsigned char *)luaL_buffinitsize(L, &buf, total);
    memcpy(p, lsnap_magic, sizeof lsnap_magic);
    lsnap_put(p + 8, list, 4);
    lsnap_put(p + 12, (uint64_t)lw->next_serial, 8);
    lsnap_put(p + 20, (uint64_t)count, 4);
    off = 24;
    for (i = 0; i < count; i++) {
        const char *name;
        size_t len;
        lua_rawgeti(L, 2, refs[i].key);
        len = lsnap_name(L, &name);
        lsnap_put(p + off, (uint64_t)refs[i].key, 8);
        lsnap_put(p + off + 8, (uint64_t)refs[i].serial, 8);
        lsnap_put(p + off + 16, name != NULL ? (uint64_t)len : LSNAP_NONAME, 4);
        off += LSNAP_ENTRY;
        if (name != NULL) memcpy(p + off, name, len);
        off += name != NULL ? len : 0;
        lua_pop(L, 2);
    }
    lsnap_put(p + off, lsnap_fnv(p, off), 8);
    off += 8;
    if (with_world) LCHECK(L, w, rg_world_save(w, p + off, csize, &got), what);
    luaL_pushresultsize(&buf, total);
}

static int lsnap_save(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    lua_settop(L, 1);
    lsnap_push(L, w, (const lworld *)lua_touserdata(L, 1), 1, "save");
    return 1;
}

/* ---------------------------------------------------------------- restore */

/* The body list of a snapshot string, checked. */
typedef struct lsnap_list {
    const unsigned char *p;  /* the list's first entry */
    const unsigned char *end;
    lua_Integer next_serial;
    int32_t count;
} lsnap_list;

/* One entry at *at: its handle, serial and name (NULL when none); advances *at. */
static void lsnap_entry(const unsigned char **at, rg_body *h, lua_Integer *serial,
                        const char **name, size_t *len)
{
    const unsigned char *e = *at;
    uint64_t n = lsnap_get(e + 16, 4);
    *h = lsnap_get(e, 8);
    *serial = (lua_Integer)lsnap_get(e + 8, 8);
    *name = n == LSNAP_NONAME ? NULL : (const char *)e + LSNAP_ENTRY;
    *len = n == LSNAP_NONAME ? 0 : (size_t)n;
    *at = e + LSNAP_ENTRY + *len;
}

/* Reads the header and the list of s; raises unless they are whole and well formed.
 * Returns where the library's snapshot starts. */
static size_t lsnap_read(lua_State *L, const unsigned char *s, size_t len, lsnap_list *out)
{
    const unsigned char *at, *end;
    size_t n;
    int32_t i;
    if (len < LSNAP_HEAD || memcmp(s, lsnap_magic, sizeof lsnap_magic) != 0)
        luaL_error(L, "restore: not a snapshot of world:save (%I bytes)", (lua_Integer)len);
    n = (size_t)lsnap_get(s + 8, 4);
    if (n > len - LSNAP_HEAD || len - LSNAP_HEAD - n < 8)
        luaL_error(L, "restore: truncated (%I bytes; its body list alone needs %I)",
                   (lua_Integer)len, (lua_Integer)(LSNAP_HEAD + n + 8));
    lsnap_charge_bytes(L, LSNAP_HEAD + n + 8);   /* hashed, then walked */
    if (lsnap_get(s + LSNAP_HEAD + n, 8) != lsnap_fnv(s, LSNAP_HEAD + n))
        luaL_error(L, "restore: checksum mismatch (the snapshot's body list is corrupted)");
    at = s + LSNAP_HEAD;
    end = at + n;
    if (n < 12) luaL_error(L, "restore: the snapshot's body list is malformed");
    out->next_serial = (lua_Integer)lsnap_get(at, 8);
    out->count = (int32_t)lsnap_get(at + 8, 4);
    at += 12;
    if (out->next_serial < 1 || out->count < 0 ||
        (size_t)out->count > (size_t)(end - at) / LSNAP_ENTRY)
        luaL_error(L, "restore: the snapshot's body list is malformed");
    out->p = at;
    for (i = 0; i < out->count; i++) {
        rg_body h;
        lua_Integer serial;
        const char *name;
        size_t nlen;
        uint64_t raw;
        if ((size_t)(end - at) < LSNAP_ENTRY) break;
        raw = lsnap_get(at + 16, 4);
        if (raw != LSNAP_NONAME && raw > (uint64_t)(end - at) - LSNAP_ENTRY) break;
        lsnap_entry(&at, &h, &serial, &name, &nlen);
        if (h == 0 || serial < 1 || serial >= out->next_serial) break;
    }
    if (i < out->count || at != end)
        luaL_error(L, "restore: the snapshot's body list is malformed (entry %d)", (int)i + 1);
    out->end = end;
    return LSNAP_HEAD + n + 8;
}

/* Stack: 1 world, 2 the string.  Leaves 3 new live, 4 new dead, 5 the values and 6 the
 * names of the list's bodies by position: everything the swap needs, made before anything
 * changes (each may raise a memory error). */
static void lsnap_prepare(lua_State *L, const lsnap_list *list)
{
    const unsigned char *at = list->p;
    int32_t i;
    lua_createtable(L, 0, list->count);   /* 3 */
    lua_newtable(L);                      /* 4: weak, as lworld.c makes it */
    lua_getiuservalue(L, 1, LWORLD_UV_DEAD);
    lua_getmetatable(L, -1);
    lua_setmetatable(L, 4);
    lua_pop(L, 1);
    lua_createtable(L, list->count, 0);   /* 5 */
    lua_createtable(L, list->count, 0);   /* 6 */
    lua_getiuservalue(L, 1, LWORLD_UV_LIVE);   /* 7 */
    lua_getiuservalue(L, 1, LWORLD_UV_DEAD);   /* 8 */
    for (i = 0; i < list->count; i++) {
        rg_body h;
        lua_Integer serial, key;
        const char *name;
        size_t len;
        lsnap_entry(&at, &h, &serial, &name, &len);
        key = (lua_Integer)h;
        if (lua_rawgeti(L, 3, key) != LUA_TNIL)
            luaL_error(L, "restore: the snapshot's body list is malformed (body %d twice)",
                       (int)i + 1);
        lua_pop(L, 1);
        if (lua_rawgeti(L, 7, key) == LUA_TNIL) {
            lua_pop(L, 1);
            if (lua_rawgeti(L, 8, key) == LUA_TNIL) {
                lua_pop(L, 1);
                lbody_new(L, 1, h);
            }
        }
        lua_pushvalue(L, -1);
        lua_rawseti(L, 3, key);
        lua_rawseti(L, 5, i + 1);
        if (name != NULL) lua_pushlstring(L, name, len);
        else lua_pushboolean(L, 0);
        lua_rawseti(L, 6, i + 1);
    }
    /* Every other value is a destroyed body's.  The values the script holds may be any
     * number: charged by the count. */
    for (i = 7; i <= 8; i++) {
        double values = 0;
        lua_pushnil(L);
        while (lua_next(L, i) != 0) {
            lua_pushvalue(L, -2);
            if (lua_rawget(L, 3) == LUA_TNIL) {
                lua_pushvalue(L, -3);
                lua_pushvalue(L, -3);
                lua_rawset(L, 4);
            }
            lua_pop(L, 2);
            values++;
        }
        lworld_charge(L, values * LSNAP_VALUE_UNITS);
    }
    lua_settop(L, 6);
}

/* After the library restored: the world's tables become the new ones, and the list's bodies
 * take their saved serials and names.  Allocates nothing. */
static void lsnap_commit(lua_State *L, lworld *lw, const lsnap_list *list)
{
    const unsigned char *at = list->p;
    int32_t i;
    lua_pushvalue(L, 3);
    lua_setiuservalue(L, 1, LWORLD_UV_LIVE);
    lua_pushvalue(L, 4);
    lua_setiuservalue(L, 1, LWORLD_UV_DEAD);
    for (i = 0; i < list->count; i++) {
        rg_body h;
        lua_Integer serial;
        const char *name;
        size_t len;
        lbody *b;
        lsnap_entry(&at, &h, &serial, &name, &len);
        lua_rawgeti(L, 5, i + 1);
        b = (lbody *)lua_touserdata(L, -1);
        b->serial = serial;
        lbody_refresh(b);
        if (lua_rawgeti(L, 6, i + 1) == LUA_TBOOLEAN) {
            lua_pop(L, 1);
            lua_pushnil(L);
        }
        lua_setiuservalue(L, -2, LBODY_UV_NAME);
        lua_pop(L, 1);
    }
    lw->next_serial = list->next_serial;
}

/* 1 when the restored world has exactly the list's bodies. */
static int lsnap_matches(const rg_world *w, const lsnap_list *list)
{
    const unsigned char *at = list->p;
    int32_t i;
    if (rg_world_body_count(w) != list->count) return 0;
    for (i = 0; i < list->count; i++) {
        rg_body h;
        lua_Integer serial;
        const char *name;
        size_t len;
        lsnap_entry(&at, &h, &serial, &name, &len);
        if (!rg_body_is_valid(w, h)) return 0;
    }
    return 1;
}

static int lsnap_restore(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    lworld *lw = (lworld *)lua_touserdata(L, 1);
    const unsigned char *s;
    size_t len, at, bsize = 0;
    lsnap_list list;
    void *backup;
    rg_status st;
    if (lua_type(L, 2) != LUA_TSTRING) return luaL_typeerror(L, 2, "string");
    lua_settop(L, 2);
    s = (const unsigned char *)lua_tolstring(L, 2, &len);
    at = lsnap_read(L, s, len, &list);
    lsnap_prepare(L, &list);
    /* The library checks its snapshot; whether the list names the bodies it holds shows only
     * once it is loaded, so the world's state is kept to put back. */
    LCHECK(L, w, rg_world_save(w, NULL, 0, &bsize), "restore");
    lsnap_charge_bytes(L, bsize + (len - at));   /* the backup written, the library's part read */
    backup = lua_newuserdatauv(L, bsize, 0);
    LCHECK(L, w, rg_world_save(w, backup, bsize, &bsize), "restore");
    lworld_charge(L, (double)rg_world_body_count(w) + list.count);
    LCHECK(L, w, rg_world_restore(w, s + at, len - at), "restore");
    if (!lsnap_matches(w, &list)) {
        int32_t n = rg_world_body_count(w);
        lsnap_charge_bytes(L, bsize);
        st = rg_world_restore(w, backup, bsize);
        if (st != RG_OK) return lcheck_status(L, w, st, "restore (putting the world back)");
        return luaL_error(L, "restore: the snapshot's body list does not match its world "
                             "(%d bodies listed, %d in the world)", (int)list.count, (int)n);
    }
    lsnap_commit(L, lw, &list);
    return 0;
}

/* ---------------------------------------------------------------- kept states */

/* world:save_slot(k), world:restore_slot(k), world:drop_slot(k): the library's kept states
 * (rg_world_save_slot), k in [0, 64) as there, each paired with the body list of the moment
 * (as a snapshot string's, without the library's part) in the world's `kept` table.  A state
 * and its list are written together and nothing outside the binding reaches either, so a
 * restore from a slot needs no copy of the world to put back. */

static int32_t lsnap_slot(lua_State *L)
{
    return lcheck_int32(L, 2, 0, RG_MAX_SLOTS - 1, "slot must be in [0, 64)");
}

static int lsnap_save_slot(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    int32_t slot = lsnap_slot(L);
    lua_settop(L, 1);
    lsnap_push(L, w, (const lworld *)lua_touserdata(L, 1), 0, "save_slot");   /* the list */
    lsnap_charge_bytes(L, lsnap_size(w));
    LCHECK(L, w, rg_world_save_slot(w, slot), "save_slot");
    lua_getiuservalue(L, 1, LWORLD_UV_KEPT);
    lua_pushvalue(L, -2);
    lua_rawseti(L, -2, slot);
    return 0;
}

static int lsnap_restore_slot(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    lworld *lw = (lworld *)lua_touserdata(L, 1);
    int32_t slot = lsnap_slot(L);
    const unsigned char *s;
    size_t len;
    lsnap_list list;
    lua_getiuservalue(L, 1, LWORLD_UV_KEPT);
    if (lua_rawgeti(L, -1, slot) != LUA_TSTRING) return luaL_error(L, "restore_slot: slot %d is empty", (int)slot);
    lua_replace(L, 2);
    lua_settop(L, 2);   /* 1 the world, 2 the list */
    s = (const unsigned char *)lua_tolstring(L, 2, &len);
    lsnap_read(L, s, len, &list);
    lsnap_prepare(L, &list);
    lworld_charge(L, (double)rg_world_body_count(w) + list.count);
    LCHECK(L, w, rg_world_restore_slot(w, slot), "restore_slot");
    if (!lsnap_matches(w, &list))   /* they were kept together: never */
        return luaL_error(L, "restore_slot: slot %d's state does not match its body list", (int)slot);
    lsnap_commit(L, lw, &list);
    /* the kept state loaded, its size known only now (a charge never raises) */
    lsnap_charge_bytes(L, lsnap_size(w));
    return 0;
}

static int lsnap_drop_slot(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    int32_t slot = lsnap_slot(L);
    LCHECK(L, w, rg_world_drop_slot(w, slot), "drop_slot");
    lua_getiuservalue(L, 1, LWORLD_UV_KEPT);
    lua_pushnil(L);
    lua_rawseti(L, -2, slot);
    return 0;
}

/* ---------------------------------------------------------------- hash */

static int lsnap_hash(lua_State *L)
{
    rg_world *w = lworld_checkopen(L, 1);
    uint64_t h = 0;
    lworld_charge(L, (double)(lsnap_size(w) / LSNAP_HASH_BYTES));
    LCHECK(L, w, rg_world_hash(w, &h), "hash");
    lua_pushinteger(L, (lua_Integer)h);   /* the 64 bits, as lbody.c keys handles */
    return 1;
}

const luaL_Reg lsnap_world_methods[] = {
    { "save", lsnap_save },
    { "restore", lsnap_restore },
    { "hash", lsnap_hash },
    { "save_slot", lsnap_save_slot },
    { "restore_slot", lsnap_restore_slot },
    { "drop_slot", lsnap_drop_slot },
    { NULL, NULL }
};
