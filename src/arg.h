/* arg.h: the checks of an entry point's arguments against the ranges the header states.  A
 * check that fails sets the world's last error to the function, the argument and the rule
 * ("rg_body_set_circle: radius 1e+08 is above RG_MAX_SHAPE_SIZE (1e+07)").  The ARG_*
 * macros return from the entry point: RG_ERR_INVALID_ARGUMENT (RG_ERR_STALE_HANDLE for a
 * handle); they take the argument itself, whose spelling names it, and bounds that are the
 * header's constants or plain numbers. */
#ifndef RG_ARG_H
#define RG_ARG_H

#include <stdint.h>

#include "error.h"
#include "pool.h"
#include "rigid.h"
#include "vec2.h"

/* Accepted: lo <= v <= hi (lo < v when lo_open); bounds compared as rg_real, so a bound the
 * float build cannot hold exactly is its float.  Names: a constant of the header (printed
 * with its value) or a number's spelling. */
typedef struct arg_rule {
    double lo, hi;
    const char *lo_name, *hi_name;
    int lo_open;
} arg_rule;

/* 1 when v (argument `name`, component `part`: "", ".x" or ".y") is finite and, when rule is
 * not NULL, within it; else 0 and the error set. */
int arg_real(const rg_world *w, const char *func, const char *name, const char *part, rg_real v,
             const arg_rule *rule);
/* arg_real's test alone (no error), inline: the ARG_* macros below try it first, so that a
 * passing argument costs a compare against constant bounds and the rule is only built for
 * the error. */
static inline int arg_within(rg_real v, double lo, double hi, int lo_open)
{
    return rg_finite(v) && (lo_open ? v > (rg_real)lo : v >= (rg_real)lo) && v <= (rg_real)hi;
}
/* Significant digits that print v (%.*g) apart from a bound it is beyond: %g's 6, or all
 * of an rg_real's when 6 would print the two alike (1.0000001e6 against 1e6). */
int arg_digits(double v, double bound);
/* Both components. */
int arg_vec(const rg_world *w, const char *func, const char *name, rg_vec2 v, const arg_rule *rule);
/* 1 when lo <= v <= hi; else 0 and the error "NAME V is not WHAT" set. */
int arg_int(const rg_world *w, const char *func, const char *name, int32_t v, int32_t lo,
            int32_t hi, const char *what);
/* 1 when p is not NULL; else 0 and the error "NAME is NULL" set. */
int arg_ptr(const rg_world *w, const char *func, const char *name, const void *p);
/* 1 when capacity >= 0 and out is not NULL if capacity > 0; else 0 and the error set. */
int arg_buffer(const rg_world *w, const char *func, const char *name, const void *out,
               int32_t capacity);
/* arg_handle's error, for a handle that is not live; returns -1. */
int32_t arg_handle_error(const rg_world *w, const char *func, const char *name, uint64_t h);
/* Dense index of the live handle h of pool p, or -1 and the error "NAME 0x... is stale". */
static inline int32_t arg_handle(const rg_world *w, const char *func, const char *name,
                                 const pool *p, uint64_t h)
{
    int32_t i = pool_lookup(p, h);
    return i >= 0 ? i : arg_handle_error(w, func, name, h);
}

#define ARG_RETURN_UNLESS(ok)                          \
    do {                                               \
        if (!(ok)) return RG_ERR_INVALID_ARGUMENT;     \
    } while (0)
#define ARG_RULE(lo, hi, lo_name, hi_name, open) \
    (&(const arg_rule){ (double)(lo), (double)(hi), lo_name, hi_name, open })

/* v finite */
#define ARG_FINITE(w, v) \
    ARG_RETURN_UNLESS(rg_finite(v) || arg_real((w), __func__, #v, "", (v), NULL))
/* lo <= v <= hi */
#define ARG_IN(w, v, lo, hi)                                  \
    ARG_RETURN_UNLESS(arg_within((v), (lo), (hi), 0) ||        \
                      arg_real((w), __func__, #v, "", (v), ARG_RULE(lo, hi, #lo, #hi, 0)))
/* lo < v <= hi */
#define ARG_ABOVE(w, v, lo, hi)                               \
    ARG_RETURN_UNLESS(arg_within((v), (lo), (hi), 1) ||        \
                      arg_real((w), __func__, #v, "", (v), ARG_RULE(lo, hi, #lo, #hi, 1)))
/* |v| <= max */
#define ARG_ABS(w, v, max)                                    \
    ARG_RETURN_UNLESS(arg_within((v), -(max), (max), 0) ||     \
                      arg_real((w), __func__, #v, "", (v), ARG_RULE(-(max), max, "-" #max, #max, 0)))
/* |v.x| <= max and |v.y| <= max */
#define ARG_VEC(w, v, max)                                                                 \
    ARG_RETURN_UNLESS((arg_within((v).x, -(max), (max), 0) &&                               \
                       arg_within((v).y, -(max), (max), 0)) ||                              \
                      arg_vec((w), __func__, #v, (v), ARG_RULE(-(max), max, "-" #max, #max, 0)))
/* v.x and v.y finite */
#define ARG_VEC_FINITE(w, v) \
    ARG_RETURN_UNLESS(rg_vec2_finite(v) || arg_vec((w), __func__, #v, (v), NULL))
/* integer lo <= v <= hi, described as `what` ("one of RG_BODY_* (0..2)") */
#define ARG_INT(w, v, lo, hi, what) ARG_RETURN_UNLESS(arg_int((w), __func__, #v, (v), lo, hi, what))
#define ARG_PTR(w, p) ARG_RETURN_UNLESS((p) != NULL || arg_ptr((w), __func__, #p, (p)))
/* an output array out of capacity elements */
#define ARG_BUFFER(w, out, capacity) ARG_RETURN_UNLESS(arg_buffer((w), __func__, #out, (out), (capacity)))

#endif
