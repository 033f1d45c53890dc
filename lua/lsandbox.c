/* lsandbox.c: memory cap, uncatchable instruction budget and safe libraries for scripts. */
#if !defined(_POSIX_C_SOURCE) || _POSIX_C_SOURCE < 199309L
#undef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 199309L /* clock_gettime */
#endif
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>

#include "lcount.h"
#include "llong.h"
#include "lpattern.h"
#include "lsandbox.h"
#include "lutf8.h"

#define HOOK_EVERY      1000            /* instructions between count hooks */
#define BYTES_PER_UNIT  64              /* allocation charged to the budget */
#define REPORT_HEADROOM (1u << 20)      /* memory the error report may use past the cap */
#define LOOP_BATCH      1024            /* C loop iterations between budget checks */
#define NORMAL_MASK     (LUA_MASKCOUNT | LUA_MASKCALL)
/* Each block is counted as malloc sizes it: glibc's chunk is the request plus one size
 * word, rounded to 16, at least 32 bytes. */
#define CHUNK_OVERHEAD  8
#define COMPARE_BYTES_PER_UNIT 64       /* memcmp: 90 bytes in the 1.8 ns of one instruction */
#define PARSE_BYTES_PER_UNIT   1        /* the lexer skips a blank in 1.4 ns */
#define CLOCK_EVERY     64              /* calls between looks at the clock (26 ns) */

struct lsandbox {
    size_t used, peak, limit;
    int reporting;           /* a traceback is being built: allow the headroom */
    double budget;           /* units per entry; 0: none */
    double spent;
    int exhausted;           /* once set, every hook raises until the entry ends */
    int count;               /* instructions per count hook */
    double time_limit;       /* seconds per entry, besides the budget; 0: none */
    double start;            /* the clock when the entry began */
    int ticks;               /* calls since the last look at the clock */
    int out_of_time;         /* the entry passed time_limit: raises as an exhausted budget */
    lpattern_meter meter;
    char where[200];         /* "file:line" of the script at the last count hook */
    llong longs;             /* live long strings: every instruction and call is charged
                                what one comparison of two of them may read */
};

static const char modules_key = 'm';

/* Seconds on a monotonic clock (a vDSO call on Linux, 26 ns; clock(), a system call there,
 * takes 2 us on a VM). */
static double sb_now(void)
{
#ifdef CLOCK_MONOTONIC
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) == 0) return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
#endif
    return (double)clock() / CLOCKS_PER_SEC;
}

static lsandbox *getsb(lua_State *L)
{
    void *ud;
    lua_getallocf(L, &ud);
    return (lsandbox *)ud;
}

/* ---------------------------------------------------------------- memory */

static size_t block_cost(size_t n)
{
    size_t c = (n + CHUNK_OVERHEAD + 15) & ~(size_t)15;
    return c < 32 ? 32 : c;
}

static void *sb_alloc(void *ud, void *ptr, size_t osize, size_t nsize)
{
    lsandbox *sb = (lsandbox *)ud;
    size_t old = ptr != NULL ? block_cost(osize) : 0;   /* for a new block, osize is a type tag */
    size_t cost, limit = sb->limit + (sb->reporting ? REPORT_HEADROOM : 0);
    void *p;
    if (nsize == 0) {
        if (ptr != NULL) llong_forget(&sb->longs, ptr, osize);
        free(ptr);
        sb->used -= old;
        return NULL;
    }
    if (nsize > ((size_t)-1) / 2) return NULL;
    cost = block_cost(nsize);
    if (cost > old) {
        size_t grow = cost - old;
        if (sb->limit != 0 && (grow > limit || sb->used > limit - grow)) return NULL;
        if (sb->budget > 0 && nsize > (ptr != NULL ? osize : 0))
            sb->spent += (double)((nsize - (ptr != NULL ? osize : 0)) / BYTES_PER_UNIT);
    }
    p = realloc(ptr, nsize);
    if (p == NULL) return ptr != NULL && nsize <= osize ? ptr : NULL;   /* a shrink may keep it */
    if (ptr == NULL && osize == LUA_TSTRING && nsize >= LLONG_MIN_BLOCK) {
        size_t before = sb->longs.bytes;
        size_t room = sb->limit == 0 ? (size_t)-1 : limit - (sb->used < limit ? sb->used : limit);
        if (!llong_add(&sb->longs, p, nsize, room)) {
            free(p);
            return NULL;
        }
        sb->used += sb->longs.bytes - before;   /* the table counts against the cap */
    }
    sb->used = sb->used - old + cost;
    if (sb->used > sb->peak) sb->peak = sb->used;
    return p;
}

/* ---------------------------------------------------------------- budget */

static int msgh(lua_State *L);

/* Raises "file:line: instruction budget exhausted", at the innermost Lua function. */
static int raise_budget(lua_State *L, const lsandbox *sb)
{
    lua_Debug d;
    int level;
    lua_pushliteral(L, "");
    for (level = 0; lua_getstack(L, level, &d); level++) {
        lua_getinfo(L, "Sl", &d);
        if (d.currentline > 0) {
            lua_pop(L, 1);
            lua_pushfstring(L, "%s:%d: ", d.short_src, d.currentline);
            break;
        }
    }
    if (sb->out_of_time)
        lua_pushfstring(L, "time limit exceeded (%f s per call into the script)", (lua_Number)sb->time_limit);
    else
        lua_pushfstring(L, "instruction budget exhausted (%I units per call into the script)",
                        (lua_Integer)sb->budget);
    lua_concat(L, 2);
    return lua_error(L);
}

static void hook(lua_State *L, lua_Debug *ar);
static int guarded_handler(lua_State *L);

static void arm(lua_State *L, const lsandbox *sb)
{
    if (sb->budget <= 0) return;
    if (sb->exhausted) lua_sethook(L, hook, LUA_MASKCOUNT, 1);
    else lua_sethook(L, hook, NORMAL_MASK, sb->count);
}

/* What a call moved besides its own unit: the values it passes, one unit each past the first
 * CALL_FREE_VALUES.  The VM copies a vararg list (f(...)) or a function's results into an
 * argument list in one instruction, a million values each time when they come from
 * table.unpack.  A C function's arguments are its frame, where its call hook runs; a Lua
 * function's varargs lie below its frame, found by asking for vararg -k (O(1) each): doubling
 * k, then halving the step. */
#define CALL_FREE_VALUES 64
static double call_values(lua_State *L, lua_Debug *ar)
{
    int top = lua_gettop(L), lo, hi;   /* a Lua function's frame is its registers, <= 255 */
    if (top > CALL_FREE_VALUES && lua_getinfo(L, "f", ar)) {
        int c = lua_iscfunction(L, -1);
        lua_pop(L, 1);
        if (c) return top - CALL_FREE_VALUES;
    }
    if (lua_getlocal(L, ar, -(CALL_FREE_VALUES + 1)) == NULL) return 0;   /* also a C function */
    lua_pop(L, 1);
    /* at least lo varargs, fewer than hi */
    for (lo = CALL_FREE_VALUES + 1, hi = 2 * lo; lua_getlocal(L, ar, -hi) != NULL; lo = hi, hi *= 2)
        lua_pop(L, 1);
    while (hi - lo > 1) {
        int mid = lo + (hi - lo) / 2;
        if (lua_getlocal(L, ar, -mid) != NULL) {
            lua_pop(L, 1);
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return lo - CALL_FREE_VALUES;
}

/* Every hook event charges: a count event the instructions since the last, a call one unit
 * and the values it passes (call_values).
 * Once the budget is gone the thread raises on every instruction, so a pcall that catches
 * the error gets to run exactly nothing, in this thread or any other, until the host's own
 * pcall returns. */
static void hook(lua_State *L, lua_Debug *ar)
{
    lsandbox *sb = getsb(L);
    /* Each instruction or call since the last hook may have compared two long strings. */
    double per = 1.0 + (double)(llong_take_peak(&sb->longs) / COMPARE_BYTES_PER_UNIT);
    if (ar->event == LUA_HOOKCOUNT) {
        sb->spent += (double)lua_gethookcount(L) * per;
        /* Where the script is, for a memory error (Lua reports those without a handler,
         * so without a position); once per count hook, which is cheap. */
        if (lua_getinfo(L, "Sl", ar) && ar->currentline > 0)
            snprintf(sb->where, sizeof sb->where, "%s:%d", ar->short_src, ar->currentline);
    } else {
        sb->spent += per;
        if (!sb->exhausted) sb->spent += call_values(L, ar);
    }
    /* the clock at every count event (an instruction may take 24 us: a chain of __index
     * tables), at every CLOCK_EVERYth call */
    if (sb->time_limit > 0 && !sb->exhausted && (ar->event == LUA_HOOKCOUNT || ++sb->ticks >= CLOCK_EVERY)) {
        sb->ticks = 0;
        if (sb_now() - sb->start > sb->time_limit) sb->out_of_time = 1;
    }
    if (!sb->exhausted && !sb->out_of_time && sb->spent <= sb->budget) {
        if (lua_gethookmask(L) != NORMAL_MASK) arm(L, sb);   /* from an earlier entry */
        return;
    }
    if (ar->event != LUA_HOOKCOUNT && lua_getinfo(L, "f", ar)) {
        /* The handlers run C only (no script code once exhausted): let them run. */
        lua_CFunction f = lua_tocfunction(L, -1);
        int ours = f == msgh || f == guarded_handler;
        lua_pop(L, 1);
        if (ours) return;
    }
    sb->exhausted = 1;
    lua_sethook(L, hook, LUA_MASKCOUNT, 1);
    raise_budget(L, sb);
}

void lsandbox_charge(lua_State *L, lsandbox *sb, double units)
{
    if (sb->budget <= 0) return;
    sb->spent += units;
    if (sb->spent > sb->budget && !sb->exhausted) {
        sb->exhausted = 1;
        lua_sethook(L, hook, LUA_MASKCOUNT, 1);   /* stops at the next instruction */
    }
}

/* For C loops of the sandbox's own functions: charges and raises when over budget. */
static void charge_now(lua_State *L, lsandbox *sb, double units)
{
    if (sb->budget <= 0) return;
    sb->spent += units;
    if (sb->exhausted || sb->spent > sb->budget) {
        sb->exhausted = 1;
        lua_sethook(L, hook, LUA_MASKCOUNT, 1);
        raise_budget(L, sb);
    }
}

static void meter_charge(lua_State *L, void *ud, size_t units)
{
    charge_now(L, (lsandbox *)ud, (double)units);
}

const lpattern_meter *lsandbox_meter(const lsandbox *sb)
{
    return &sb->meter;
}

/* ---------------------------------------------------------------- safe library functions */

/* The reader of a load(function): the script's reader (upvalue 1), its pieces charged to
 * the budget by size before the parser reads them. */
static int metered_reader(lua_State *L)
{
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_call(L, 0, 1);
    if (lua_type(L, -1) == LUA_TSTRING)
        charge_now(L, getsb(L), (double)(lua_rawlen(L, -1) / PARSE_BYTES_PER_UNIT));
    return 1;
}

/* load(chunk [, chunkname [, mode [, env]]]) with mode forced to "t": no bytecode.  The
 * parser runs in C, so its input is charged by size: a string chunk before parsing, a reader
 * function's pieces as they come. */
static int safe_load(lua_State *L)
{
    int top = lua_gettop(L), n;
    int t = lua_type(L, 1);
    luaL_argexpected(L, t == LUA_TSTRING || t == LUA_TFUNCTION, 1, "string or function");
    if (t == LUA_TSTRING) {
        charge_now(L, getsb(L), (double)(lua_rawlen(L, 1) / PARSE_BYTES_PER_UNIT));
    } else {
        lua_pushvalue(L, 1);
        lua_pushcclosure(L, metered_reader, 1);
        lua_replace(L, 1);
    }
    if (!lua_isnoneornil(L, 2)) luaL_checkstring(L, 2);
    if (!lua_isnoneornil(L, 3)) luaL_checkstring(L, 3);
    lua_settop(L, 4);
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_pushvalue(L, 1);
    lua_pushvalue(L, 2);
    lua_pushliteral(L, "t");
    n = 3;
    if (top >= 4) {        /* an explicit nil env is not the same as none */
        lua_pushvalue(L, 4);
        n = 4;
    }
    lua_call(L, n, LUA_MULTRET);
    return lua_gettop(L) - 4;
}

static int safe_require(lua_State *L)
{
    const char *name = luaL_checkstring(L, 1);
    lua_rawgetp(L, LUA_REGISTRYINDEX, &modules_key);
    if (lua_getfield(L, -1, name) == LUA_TNIL)
        return luaL_error(L, "module '%s' is not available in the sandbox", name);
    return 1;
}

/* string.rep, with the empty case answered at once (the stock one loops n times copying
 * nothing, and n may be 2^62) and the copy made in O(log n) memcpy calls. */
static int safe_rep(lua_State *L)
{
    size_t l, lsep, total, done, step;
    const char *s = luaL_checklstring(L, 1, &l);
    lua_Integer n = luaL_checkinteger(L, 2);
    const char *sep = luaL_optlstring(L, 3, "", &lsep);
    luaL_Buffer b;
    char *p;
    if (n <= 0 || l + lsep == 0) {
        lua_pushliteral(L, "");
        return 1;
    }
    if (l + lsep < l || (lua_Unsigned)n > (lua_Unsigned)(((size_t)-1 / 2) / (l + lsep)))
        return luaL_error(L, "resulting string too large");
    total = (size_t)n * l + (size_t)(n - 1) * lsep;
    {
        /* Said with a position, where running out of memory would say nothing of where. */
        const lsandbox *sb = getsb(L);
        if (sb->limit != 0 && (total > sb->limit || sb->used > sb->limit - total))
            return luaL_error(L, "resulting string (%I bytes) would not fit in the memory cap "
                                 "(%I MiB)", (lua_Integer)total, (lua_Integer)(sb->limit >> 20));
    }
    /* The result is s..sep repeated, cut after the last s: one piece, then copies of what is
     * written, doubling, so the time goes with the bytes (which the allocation charged) and
     * not with n (the stock loop's 12 million memcpy calls of one byte take 0.25 s in the
     * sanitized fuzzer, for an allocation charged 200,000 units). */
    p = luaL_buffinitsize(L, &b, total);
    memcpy(p, s, l);
    if (n > 1) memcpy(p + l, sep, lsep);
    for (done = n > 1 ? l + lsep : l; done < total; done += step) {
        step = done < total - done ? done : total - done;
        memcpy(p + done, p, step);
    }
    luaL_pushresultsize(&b, total);
    return 1;
}

/* table.insert, table.remove and table.move shift elements in C, as many as #t (which a
 * __len metamethod may make 2^62) or the arguments say, with no instruction to count.
 * These versions follow the manual and charge their loops; they take plain tables. */
static int safe_insert(lua_State *L)
{
    lsandbox *sb = getsb(L);
    lua_Integer e, pos, i;
    luaL_checktype(L, 1, LUA_TTABLE);
    e = (lua_Integer)((lua_Unsigned)luaL_len(L, 1) + 1u);   /* first empty slot */
    switch (lua_gettop(L)) {
    case 2:
        pos = e;
        break;
    case 3:
        pos = luaL_checkinteger(L, 2);
        luaL_argcheck(L, (lua_Unsigned)pos - 1u < (lua_Unsigned)e, 2, "position out of bounds");
        for (i = e; i > pos; i--) {
            lua_geti(L, 1, i - 1);
            lua_seti(L, 1, i);
            if ((i & (LOOP_BATCH - 1)) == 0) charge_now(L, sb, LOOP_BATCH);
        }
        break;
    default:
        return luaL_error(L, "wrong number of arguments to 'insert'");
    }
    lua_seti(L, 1, pos);
    return 0;
}

static int safe_remove(lua_State *L)
{
    lsandbox *sb = getsb(L);
    lua_Integer size, pos;
    luaL_checktype(L, 1, LUA_TTABLE);
    size = luaL_len(L, 1);
    pos = luaL_optinteger(L, 2, size);
    if (pos != size)
        luaL_argcheck(L, (lua_Unsigned)pos - 1u <= (lua_Unsigned)size, 2, "position out of bounds");
    lua_geti(L, 1, pos);
    for (; pos < size; pos++) {
        lua_geti(L, 1, pos + 1);
        lua_seti(L, 1, pos);
        if ((pos & (LOOP_BATCH - 1)) == 0) charge_now(L, sb, LOOP_BATCH);
    }
    lua_pushnil(L);
    lua_seti(L, 1, pos);
    return 1;
}

static int safe_move(lua_State *L)
{
    lsandbox *sb = getsb(L);
    lua_Integer f = luaL_checkinteger(L, 2), e = luaL_checkinteger(L, 3);
    lua_Integer t = luaL_checkinteger(L, 4), n, i;
    int tt = !lua_isnoneornil(L, 5) ? 5 : 1;
    luaL_checktype(L, 1, LUA_TTABLE);
    luaL_checktype(L, tt, LUA_TTABLE);
    if (e >= f) {
        luaL_argcheck(L, f > 0 || e < LUA_MAXINTEGER + f, 3, "too many elements to move");
        n = e - f + 1;
        luaL_argcheck(L, t <= LUA_MAXINTEGER - n + 1, 4, "destination wrap around");
        if (t > e || t <= f || (tt != 1 && !lua_compare(L, 1, tt, LUA_OPEQ))) {
            for (i = 0; i < n; i++) {
                lua_geti(L, 1, f + i);
                lua_seti(L, tt, t + i);
                if ((i & (LOOP_BATCH - 1)) == LOOP_BATCH - 1) charge_now(L, sb, LOOP_BATCH);
            }
        } else {
            for (i = n - 1; i >= 0; i--) {
                lua_geti(L, 1, f + i);
                lua_seti(L, tt, t + i);
                if ((i & (LOOP_BATCH - 1)) == 0) charge_now(L, sb, LOOP_BATCH);
            }
        }
    }
    lua_pushvalue(L, tt);
    return 1;
}

/* setmetatable without finalizers: Lua runs __gc with every hook switched off, so a
 * finalizer that loops could never be stopped.  (A __gc field added to a metatable after
 * setmetatable does not make its objects finalizable, so checking here is enough.) */
static int safe_setmetatable(lua_State *L)
{
    if (lua_type(L, 2) == LUA_TTABLE) {
        lua_pushliteral(L, "__gc");
        if (lua_rawget(L, 2) != LUA_TNIL)
            return luaL_error(L, "__gc metamethods are not available in the sandbox");
        lua_pop(L, 1);
    }
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, 1);
    return 1;
}

/* A budget error is raised from inside the hook, where Lua has switched hooks off for the
 * thread; they come back only when the error reaches a pcall.  Two things run script code
 * before that: the message handler of an xpcall, and the __close handlers of a coroutine
 * that coroutine.wrap closes after it died.  Both would run with no budget at all, so once
 * the budget is gone neither runs: the handler passes the error through, and the dead
 * coroutine is not closed (the whole entry is being unwound anyway). */
static int guarded_handler(lua_State *L)
{
    if (getsb(L)->exhausted) return 1;
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, 1);
    return 1;
}

static int finish_pcall(lua_State *L, int status, lua_KContext extra)
{
    if (status != LUA_OK && status != LUA_YIELD) {
        lua_pushboolean(L, 0);
        lua_pushvalue(L, -2);
        return 2;
    }
    return lua_gettop(L) - (int)extra;
}

/* xpcall(f, msgh, ...) with msgh guarded; yieldable like the stock one. */
static int safe_xpcall(lua_State *L)
{
    int n = lua_gettop(L), status;
    luaL_checktype(L, 2, LUA_TFUNCTION);
    lua_pushvalue(L, 2);
    lua_pushcclosure(L, guarded_handler, 1);
    lua_replace(L, 2);
    lua_pushboolean(L, 1);                 /* first result when all goes well */
    lua_pushvalue(L, 1);
    lua_rotate(L, 3, 2);                   /* f, handler, true, f, args... */
    status = lua_pcallk(L, n - 2, LUA_MULTRET, 2, 2, finish_pcall);
    return finish_pcall(L, status, 2);
}

/* coroutine.create: a new thread armed with the budget hook (Lua 5.4 also copies the
 * creator's hook into a new thread; this does not rely on it). */
static lua_State *new_coroutine(lua_State *L)
{
    lua_State *co;
    luaL_checktype(L, 1, LUA_TFUNCTION);
    co = lua_newthread(L);
    lua_pushvalue(L, 1);
    lua_xmove(L, co, 1);
    arm(co, getsb(L));
    return co;
}

static int safe_cocreate(lua_State *L)
{
    new_coroutine(L);
    return 1;
}

static int wrap_call(lua_State *L)
{
    lua_State *co = lua_tothread(L, lua_upvalueindex(1));
    int narg = lua_gettop(L), nres = 0, status;
    if (!lua_checkstack(co, narg)) return luaL_error(L, "too many arguments to resume");
    lua_xmove(L, co, narg);
    status = lua_resume(co, L, narg, &nres);
    if (status == LUA_OK || status == LUA_YIELD) {
        if (!lua_checkstack(L, nres + 1)) {
            lua_pop(co, nres);
            return luaL_error(L, "too many results to resume");
        }
        lua_xmove(co, L, nres);
        return nres;
    }
    status = lua_status(co);
    if (status != LUA_OK && status != LUA_YIELD && !getsb(L)->exhausted) {
#if LUA_VERSION_RELEASE_NUM >= 50406
        status = lua_closethread(co, L);   /* close its to-be-closed variables */
#else
        status = lua_resetthread(co);
#endif
    }
    lua_xmove(co, L, 1);                   /* the error */
    if (status != LUA_ERRMEM && lua_type(L, -1) == LUA_TSTRING) {
        luaL_where(L, 1);
        lua_insert(L, -2);
        lua_concat(L, 2);
    }
    return lua_error(L);
}

static int safe_cowrap(lua_State *L)
{
    new_coroutine(L);
    lua_pushcclosure(L, wrap_call, 1);
    return 1;
}

/* ---------------------------------------------------------------- setup */

static void replace(lua_State *L, const char *table, const char *name, lua_CFunction f,
                    int keep_original)
{
    lua_getglobal(L, table);
    if (keep_original) {
        lua_getfield(L, -1, name);
        lua_pushcclosure(L, f, 1);
    } else if (f != NULL) {
        lua_pushcfunction(L, f);
    } else {
        lua_pushnil(L);
    }
    lua_setfield(L, -2, name);
    lua_pop(L, 1);
}

static int open_libraries(lua_State *L)
{
    static const luaL_Reg libs[] = {
        { LUA_GNAME, luaopen_base },
        { LUA_STRLIBNAME, luaopen_string },
        { LUA_TABLIBNAME, luaopen_table },
        { LUA_MATHLIBNAME, luaopen_math },
        { LUA_UTF8LIBNAME, luaopen_utf8 },
        { LUA_COLIBNAME, luaopen_coroutine },
        { NULL, NULL },
    };
    lsandbox *sb = getsb(L);
    const luaL_Reg *lib;
    for (lib = libs; lib->func != NULL; lib++) {
        luaL_requiref(L, lib->name, lib->func, 1);
        lua_pop(L, 1);
    }
    /* base: no files, no bytecode; require only what the host provides. */
    lua_pushnil(L);
    lua_setglobal(L, "dofile");
    lua_pushnil(L);
    lua_setglobal(L, "loadfile");
    lua_getglobal(L, "load");
    lua_pushcclosure(L, safe_load, 1);
    lua_setglobal(L, "load");
    lua_getglobal(L, "setmetatable");
    lua_pushcclosure(L, safe_setmetatable, 1);
    lua_setglobal(L, "setmetatable");
    lua_newtable(L);
    lua_rawsetp(L, LUA_REGISTRYINDEX, &modules_key);
    lua_pushcfunction(L, safe_require);
    lua_setglobal(L, "require");

    replace(L, LUA_STRLIBNAME, "dump", NULL, 0);
    replace(L, LUA_STRLIBNAME, "rep", safe_rep, 0);
    lua_getglobal(L, LUA_STRLIBNAME);
    lpattern_open(L, -1, &sb->meter);
    lua_pop(L, 1);
    lua_getglobal(L, LUA_UTF8LIBNAME);
    lutf8_open(L, -1, &sb->meter);
    lua_pop(L, 1);
    lcount_open(L, &sb->meter);
    replace(L, LUA_TABLIBNAME, "insert", safe_insert, 0);
    replace(L, LUA_TABLIBNAME, "remove", safe_remove, 0);
    replace(L, LUA_TABLIBNAME, "move", safe_move, 0);
    replace(L, LUA_COLIBNAME, "create", safe_cocreate, 0);
    replace(L, LUA_COLIBNAME, "wrap", safe_cowrap, 0);
    lua_pushcfunction(L, safe_xpcall);
    lua_setglobal(L, "xpcall");

    /* os: the clock and the time, nothing that touches the system. */
    lua_pushcfunction(L, luaopen_os);
    lua_call(L, 0, 1);
    lua_createtable(L, 0, 2);
    lua_getfield(L, -2, "clock");
    lua_setfield(L, -2, "clock");
    lua_getfield(L, -2, "time");
    lua_setfield(L, -2, "time");
    lua_setglobal(L, "os");
    lua_pop(L, 1);

    /* Runs repeat: the same script draws the same random numbers. */
    lua_getglobal(L, LUA_MATHLIBNAME);
    lua_getfield(L, -1, "randomseed");
    lua_pushinteger(L, 0);
    lua_call(L, 1, 0);
    lua_pop(L, 1);
    return 0;
}

static void sb_free(lsandbox *sb)
{
    llong_free(&sb->longs);
    free(sb);
}

lua_State *lsandbox_new(size_t memory_limit, long long budget, lsandbox **out)
{
    lsandbox *sb = (lsandbox *)calloc(1, sizeof *sb);
    lua_State *L;
    if (sb == NULL) return NULL;
    sb->limit = memory_limit;
    sb->budget = budget > 0 ? (double)budget : 0;
    sb->count = budget > 0 && budget < HOOK_EVERY ? (int)budget : HOOK_EVERY;
    sb->meter.charge = meter_charge;
    sb->meter.ud = sb;
    L = lua_newstate(sb_alloc, sb);
    if (L == NULL) {
        sb_free(sb);
        return NULL;
    }
    lua_pushcfunction(L, open_libraries);
    if (lua_pcall(L, 0, 0, 0) != LUA_OK) {
        lua_close(L);
        sb_free(sb);
        return NULL;
    }
    *out = sb;
    return L;
}

void lsandbox_close(lua_State *L, lsandbox *sb)
{
    if (L != NULL) {
        /* Finalizers are script code too: they get a budget of their own. */
        sb->spent = 0;
        sb->exhausted = 0;
        sb->out_of_time = 0;
        sb->start = sb_now();
        arm(L, sb);
        lua_close(L);
    }
    sb_free(sb);
}

void lsandbox_provide(lua_State *L, const char *name, lua_CFunction openf)
{
    luaL_requiref(L, name, openf, 1);
    lua_rawgetp(L, LUA_REGISTRYINDEX, &modules_key);
    lua_pushvalue(L, -2);
    lua_setfield(L, -2, name);
    lua_pop(L, 2);
}

int lsandbox_loadfile(lua_State *L, const char *path)
{
    return luaL_loadfilex(L, path, "t");
}

/* Message handler: the message, then the traceback.  It runs no Lua code (a __tostring
 * metamethod could loop), and may use the memory headroom. */
static int msgh(lua_State *L)
{
    lsandbox *sb = getsb(L);
    const char *msg = lua_tostring(L, 1);
    sb->reporting = 1;
    if (msg == NULL)
        msg = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
    luaL_traceback(L, L, msg, 1);
    return 1;
}

int lsandbox_call(lua_State *L, lsandbox *sb, int nargs, int nresults)
{
    sb->spent = 0;
    sb->exhausted = 0;
    sb->out_of_time = 0;
    sb->ticks = 0;
    sb->start = sb_now();
    sb->where[0] = '\0';
    return lsandbox_continue(L, sb, nargs, nresults);
}

void lsandbox_set_time_limit(lsandbox *sb, double seconds)
{
    sb->time_limit = seconds > 0 ? seconds : 0;
}

int lsandbox_continue(lua_State *L, lsandbox *sb, int nargs, int nresults)
{
    int base = lua_gettop(L) - nargs, status;
    sb->reporting = 0;
    arm(L, sb);
    lua_pushcfunction(L, msgh);
    lua_insert(L, base);
    status = lua_pcall(L, nargs, nresults, base);
    lua_remove(L, base);
    sb->reporting = 0;
    return status;
}

int lsandbox_getfunction(lua_State *L, const char *name)
{
    lua_pushglobaltable(L);
    lua_pushstring(L, name);
    lua_rawget(L, -2);
    lua_remove(L, -2);
    if (lua_type(L, -1) == LUA_TFUNCTION) return 1;
    lua_pop(L, 1);
    return 0;
}

const char *lsandbox_where(const lsandbox *sb)
{
    return sb->where;
}

size_t lsandbox_limit(const lsandbox *sb)
{
    return sb->limit;
}

size_t lsandbox_memory(const lsandbox *sb)
{
    return sb->used;
}

size_t lsandbox_peak_memory(const lsandbox *sb)
{
    return sb->peak;
}

double lsandbox_spent(const lsandbox *sb)
{
    return sb->spent;
}
