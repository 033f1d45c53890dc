/* lcount.h: library functions charged by the values they move and the strings they read. */
#ifndef LCOUNT_H
#define LCOUNT_H

#include "lpattern.h"

/* Replaces, in the state's libraries, table.unpack, string.byte (by result count),
 * table.sort (n log2 n for #t = n), table.concat (by its elements, numbers costing more
 * than strings), string.format (by the bytes it writes that no string argument gave),
 * string.pack/unpack/packsize (by the length of the format), collectgarbage (by the heap,
 * for what walks it), tonumber, print and the string metatable's arithmetic (by the length
 * of each string they read).
 * meter must outlive the state. */
void lcount_open(lua_State *L, const lpattern_meter *meter);

#endif
