/* lpattern.h: string.find/match/gmatch/gsub with Lua 5.4 semantics and a step meter. */
#ifndef LPATTERN_H
#define LPATTERN_H

#include <stddef.h>

#include <lua.h>

/* The stock matcher backtracks without bound inside one C call (find("aaa...", "a-a-a-b")
 * takes hours), where no count hook can stop it.  This one reports its work: every pattern
 * step, expansion step and scanned candidate is one unit, handed to charge() in batches.
 * charge may raise a Lua error to stop the match; nothing needs cleaning up. */
typedef struct lpattern_meter {
    void (*charge)(lua_State *L, void *ud, size_t units);
    void *ud;
} lpattern_meter;

/* Sets find, match, gmatch and gsub in the table at idx.  meter may be NULL (no metering);
 * otherwise it must outlive the state. */
void lpattern_open(lua_State *L, int idx, const lpattern_meter *meter);

#endif
