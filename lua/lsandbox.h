/* lsandbox.h: a Lua state for untrusted gameplay scripts: a memory cap, an instruction
 * budget nothing in the script can swallow, and only the safe parts of the libraries. */
#ifndef LSANDBOX_H
#define LSANDBOX_H

#include <stddef.h>

#include <lua.h>

#include "lpattern.h"

typedef struct lsandbox lsandbox;

/* A new state whose allocations stop at memory_limit bytes (0: no cap) and whose every entry
 * (lsandbox_call) may spend `budget` units (0: no budget).  A unit is one VM instruction;
 * a function call (and each value past 64 that it passes), 64 bytes allocated, a byte of
 * source parsed (load), a byte scanned by utf8.len/codepoint/offset/codes, and C work
 * reported through lsandbox_charge cost units too; while two long strings (over 40 bytes) live, every instruction and call is charged
 * 1 + 2^(k+1)/64 units, 2^(k+1) bounding the shorter one: what one ==, < or rawequal
 * between them may read (inside one instruction, where the VM cannot be metered; llong.h).
 * The cap counts each block as malloc sizes it (request + 8, rounded to 16, at least 32)
 * and the sandbox's table of long strings: fragmentation and the process's own code and
 * libraries are not counted.  Libraries: base (load only for text, no dofile/loadfile), string (no dump;
 * metered patterns), table, math (seeded with 0, so runs repeat), utf8, coroutine, and os
 * with only clock and time.  Returns NULL when out of memory. */
lua_State *lsandbox_new(size_t memory_limit, long long budget, lsandbox **out);
/* Closes the state (finalizers run under a fresh budget) and frees the sandbox. */
void lsandbox_close(lua_State *L, lsandbox *sb);

/* Opens a module with openf, sets it as global `name` and makes require(name) return it.
 * require of any other name is an error. */
void lsandbox_provide(lua_State *L, const char *name, lua_CFunction openf);

/* Loads a script file as text only (never bytecode), under chunk name "@path". */
int lsandbox_loadfile(lua_State *L, const char *path);

/* lua_pcall with a fresh budget and a traceback handler.  On error the message at the top
 * of the stack reads "file:line: message" followed by the traceback. */
int lsandbox_call(lua_State *L, lsandbox *sb, int nargs, int nresults);
/* The same under what is left of the current entry's budget: several calls that share one
 * budget (a host frame: update and every contact call after it).  Once that budget is
 * spent, the call raises at its first instruction. */
int lsandbox_continue(lua_State *L, lsandbox *sb, int nargs, int nresults);

/* Pushes the global function `name`, looked up without metamethods, and returns 1; pushes
 * nothing and returns 0 when that global is not a function. */
int lsandbox_getfunction(lua_State *L, const char *name);

/* Seconds an entry may run besides its budget (0, the default: no limit; only with a
 * budget), on a monotonic clock.  A backstop for work the units undercharge, all of it
 * inside single calls or instructions: a float formatted to a string (some 400 ns, one
 * instruction), next() over a table whose deletions left a million empty slots (a scan of
 * all of them, one call).  The clock is read at every count hook (1,000 instructions) and
 * every 64th call, and passing the limit raises "time limit exceeded" as an exhausted
 * budget does.  Unlike the budget it depends on the machine and its load: it is for
 * scripts already far past what the budget allows. */
void lsandbox_set_time_limit(lsandbox *sb, double seconds);

/* Adds units of work done in C on the script's behalf.  Never raises: when the budget runs
 * out the script stops at its next instruction. */
void lsandbox_charge(lua_State *L, lsandbox *sb, double units);
/* The meter the sandbox's own library functions charge (raising once the budget is spent),
 * for a host's replacement of one of them; it lives as long as sb. */
const lpattern_meter *lsandbox_meter(const lsandbox *sb);

/* "file:line" where the count hook last saw the script in the current (or last) entry, or
 * "": the best position there is for a memory error, which Lua raises without a handler. */
const char *lsandbox_where(const lsandbox *sb);
/* The memory cap in bytes (0: none). */
size_t lsandbox_limit(const lsandbox *sb);

/* Bytes in use now, at most so far, and the units the current (or last) entry spent. */
size_t lsandbox_memory(const lsandbox *sb);
size_t lsandbox_peak_memory(const lsandbox *sb);
double lsandbox_spent(const lsandbox *sb);

#endif
