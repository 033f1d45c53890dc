/* error.c: the last error of a world and rg_world_last_error. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "error.h"
#include "state.h"

rg_status error_set(const rg_world *w, rg_status st, const char *func, const char *fmt, ...)
{
    size_t n = strlen(func);
    if (n > ERROR_SIZE - 3) n = ERROR_SIZE - 3;
    memcpy(w->err, func, n);
    w->err[n] = ':';
    w->err[n + 1] = ' ';
    va_list ap;
    va_start(ap, fmt);
    (void)vsnprintf(w->err + n + 2, ERROR_SIZE - n - 2, fmt, ap);
    va_end(ap);
    return st;
}

rg_status error_alloc(const rg_world *w, const char *func, rg_status st, const char *what,
                      const char *limit)
{
    if (st == RG_ERR_CAPACITY) return error_set(w, st, func, "capacity: %s is full (%s)", what, limit);
    return error_set(w, st, func, "out of memory (%s)", what);
}

RG_API const char *rg_world_last_error(const rg_world *world)
{
    return world != NULL ? world->err : "rg_world_last_error: world is NULL";
}
