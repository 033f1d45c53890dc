/* inline.h: FORCE_INLINE, for the helpers of the hot loops that GCC leaves as calls once the
 * function using them grows (the narrowphase's measurement and decision, the box-box
 * manifold, the solve's body passes: a few percent of a step's instructions each, in
 * callgrind's count of the bench's piles); plain inline elsewhere. */
#ifndef RG_INLINE_H
#define RG_INLINE_H

#if defined(__GNUC__) || defined(__clang__)
#define FORCE_INLINE __attribute__((always_inline)) inline
#else
#define FORCE_INLINE inline
#endif

/* PREFETCH(p): asks for the cache line at p ahead of a walk that reads lines out of order
 * (the shock sweeps' rows in solving order, which the workers' bands have just written);
 * nothing where the compiler has no such builtin.  It changes no result. */
#if defined(__GNUC__) || defined(__clang__)
#define PREFETCH(p) __builtin_prefetch(p)
#else
#define PREFETCH(p) ((void)0)
#endif

#endif
