/* arg.c: argument checks of the entry points and their messages. */
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#include "arg.h"
#include "vec2.h"

/* A bound's text: a constant of the header with its value, or a number as spelled. */
static int arg_named(const char *name) { return strchr(name, '_') != NULL; }

int arg_digits(double v, double bound)
{
    char a[32], b[32];
    snprintf(a, sizeof a, "%g", v);
    snprintf(b, sizeof b, "%g", bound);
    return strcmp(a, b) != 0 ? 6 : (int)sizeof(rg_real) == 4 ? 9 : 17;
}

int arg_real(const rg_world *w, const char *func, const char *name, const char *part, rg_real v,
             const arg_rule *r)
{
    if (!rg_finite(v)) {
        error_set(w, 0, func, "%s%s is %s", name, part, v != v ? "NaN" : v > 0 ? "inf" : "-inf");
        return 0;
    }
    if (r == NULL) return 1;
    rg_real lo = (rg_real)r->lo, hi = (rg_real)r->hi;
    if (r->lo_open ? !(v > lo) : !(v >= lo)) {
        int g = arg_digits((double)v, r->lo);
        if (arg_named(r->lo_name))
            error_set(w, 0, func, "%s%s %.*g is below %s (%g)", name, part, g, (double)v, r->lo_name, r->lo);
        else
            error_set(w, 0, func, "%s%s %.*g is not %s %s", name, part, g, (double)v, r->lo_open ? ">" : ">=",
                      r->lo_name);
        return 0;
    }
    if (!(v <= hi)) {
        int g = arg_digits((double)v, r->hi);
        if (arg_named(r->hi_name))
            error_set(w, 0, func, "%s%s %.*g is above %s (%g)", name, part, g, (double)v, r->hi_name, r->hi);
        else
            error_set(w, 0, func, "%s%s %.*g is above %s", name, part, g, (double)v, r->hi_name);
        return 0;
    }
    return 1;
}

int arg_int(const rg_world *w, const char *func, const char *name, int32_t v, int32_t lo,
            int32_t hi, const char *what)
{
    if (v >= lo && v <= hi) return 1;
    error_set(w, 0, func, "%s %" PRId32 " is not %s", name, v, what);
    return 0;
}

int arg_ptr(const rg_world *w, const char *func, const char *name, const void *p)
{
    if (p != NULL) return 1;
    error_set(w, 0, func, "%s is NULL", name);
    return 0;
}

int arg_buffer(const rg_world *w, const char *func, const char *name, const void *out,
               int32_t capacity)
{
    if (capacity < 0) {
        error_set(w, 0, func, "capacity %" PRId32 " is not >= 0", capacity);
        return 0;
    }
    if (out == NULL && capacity > 0) {
        error_set(w, 0, func, "%s is NULL with capacity %" PRId32, name, capacity);
        return 0;
    }
    return 1;
}

int arg_vec(const rg_world *w, const char *func, const char *name, rg_vec2 v, const arg_rule *r)
{
    return arg_real(w, func, name, ".x", v.x, r) && arg_real(w, func, name, ".y", v.y, r);
}

int32_t arg_handle_error(const rg_world *w, const char *func, const char *name, uint64_t h)
{
    if (h == 0)
        error_set(w, 0, func, "%s is 0 (never a handle)", name);
    else
        error_set(w, 0, func, "%s 0x%" PRIx64 " is stale (destroyed, forged or of another world)", name, h);
    return -1;
}
