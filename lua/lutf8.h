/* lutf8.h: the utf8 library's scanning functions with a meter (see lutf8.c). */
#ifndef LUTF8_H
#define LUTF8_H

#include <lua.h>

#include "lpattern.h"

/* Replaces len, codepoint, offset and codes in the utf8 table at idx with versions that
 * charge meter by the bytes they scan.  meter must outlive the state. */
void lutf8_open(lua_State *L, int idx, const lpattern_meter *meter);

#endif
