/* vec2.h: inline vector and scalar math on rg_real, one spelling for the float and double builds. */
#ifndef RG_VEC2_H
#define RG_VEC2_H

#include <float.h>
#include <math.h>

#include "rigid.h"

/* Every operation on rg_real rounds to rg_real, as IEEE 754 and the other machines do: a
 * build that keeps excess precision (the x87 of 32-bit x86; gcc for s390x under -std=c99)
 * would give other results (README: Determinism; the Makefile's FPMATH). */
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD > 0
#if !defined(RG_ALLOW_EXCESS_PRECISION)
#error "rigid: this compiler keeps excess floating-point precision (FLT_EVAL_METHOD > 0), so results would differ from every other machine's; build with -msse2 -mfpmath=sse on 32-bit x86, -fexcess-precision=fast where the machine has float operations (the Makefile does either), or define RG_ALLOW_EXCESS_PRECISION to accept results of their own"
#endif
#endif

#ifdef RG_DOUBLE
#define rg_sqrt(x)  sqrt(x)
#define rg_fabs(x)  fabs(x)
#define rg_floor(x) floor(x)
#define rg_exp(x)   exp(x)
#define RG_EPSILON  2.220446049250313e-16
#define RG_HUGE     1.0e300
#else
#define rg_sqrt(x)  sqrtf(x)
#define rg_fabs(x)  fabsf(x)
#define rg_floor(x) floorf(x)
#define rg_exp(x)   expf(x)
#define RG_EPSILON  1.1920929e-7f
#define RG_HUGE     1.0e30f
#endif
#define RG_R(c) ((rg_real)(c))

/* isfinite on rg_real without promotion warnings. */
static inline int rg_finite(rg_real v) { return isfinite(v) != 0; }
static inline int rg_vec2_finite(rg_vec2 v) { return rg_finite(v.x) && rg_finite(v.y); }

static inline rg_vec2 rg_v2(rg_real x, rg_real y) { rg_vec2 v; v.x = x; v.y = y; return v; }
static inline rg_vec2 rg_v2_add(rg_vec2 a, rg_vec2 b) { return rg_v2(a.x + b.x, a.y + b.y); }
static inline rg_vec2 rg_v2_sub(rg_vec2 a, rg_vec2 b) { return rg_v2(a.x - b.x, a.y - b.y); }
static inline rg_vec2 rg_v2_scale(rg_vec2 a, rg_real s) { return rg_v2(a.x * s, a.y * s); }
static inline rg_vec2 rg_v2_neg(rg_vec2 a) { return rg_v2(-a.x, -a.y); }
static inline rg_real rg_v2_dot(rg_vec2 a, rg_vec2 b) { return a.x * b.x + a.y * b.y; }
static inline rg_real rg_v2_cross(rg_vec2 a, rg_vec2 b) { return a.x * b.y - a.y * b.x; }
static inline rg_real rg_v2_len2(rg_vec2 a) { return a.x * a.x + a.y * a.y; }
static inline rg_real rg_v2_len(rg_vec2 a) { return rg_sqrt(a.x * a.x + a.y * a.y); }
static inline rg_real rg_min(rg_real a, rg_real b) { return a < b ? a : b; }
static inline rg_real rg_max(rg_real a, rg_real b) { return a > b ? a : b; }
static inline rg_real rg_clamp(rg_real v, rg_real lo, rg_real hi) { return v < lo ? lo : (v > hi ? hi : v); }
static inline rg_vec2 rg_v2_min(rg_vec2 a, rg_vec2 b) { return rg_v2(rg_min(a.x, b.x), rg_min(a.y, b.y)); }
static inline rg_vec2 rg_v2_max(rg_vec2 a, rg_vec2 b) { return rg_v2(rg_max(a.x, b.x), rg_max(a.y, b.y)); }

/* Unit vector along a, or (0, 0) when a is zero. */
static inline rg_vec2 rg_v2_normalize(rg_vec2 a)
{
    rg_real l = rg_v2_len(a);
    return l > 0 ? rg_v2(a.x / l, a.y / l) : rg_v2(0, 0);
}

#endif
