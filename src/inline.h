/* inline.h: FORCE_INLINE, for the helpers of the hot loops that GCC leaves as calls once the
 * function using them grows (a call there costs a fifth of the loop); plain inline elsewhere. */
#ifndef RG_INLINE_H
#define RG_INLINE_H

#if defined(__GNUC__) || defined(__clang__)
#define FORCE_INLINE __attribute__((always_inline)) inline
#else
#define FORCE_INLINE inline
#endif

#endif
