/* dispatch.h: the run-time choice of a vector width for the passes over every body.
 *
 * On x86-64 with GCC and glibc a pass marked DISPATCH is also built for AVX2 and picked at
 * load time (an ifunc), so the library stays portable and uses the wider vectors where the
 * machine has them.  No FMA is enabled, and every operation is correctly rounded in either
 * width, so both versions give bit-identical results.  Define RG_NO_DISPATCH to build SSE2
 * only.  DISPATCH_INLINE puts a helper into each version. */
#ifndef RG_DISPATCH_H
#define RG_DISPATCH_H

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__GLIBC__) && \
    !defined(RG_NO_DISPATCH)
#define DISPATCH __attribute__((target_clones("avx2", "default")))
#define DISPATCH_INLINE __attribute__((always_inline)) inline
#else
#define DISPATCH
#define DISPATCH_INLINE inline
#endif

/* The hand-written AVX2 paths (the solver's velocity sweep, the narrowphase's eight contacts,
 * the views of eight bodies): built into the float library on x86-64 with GCC or Clang, and
 * taken when the CPU has AVX2 (asked at run time); RG_NO_DISPATCH builds without them. */
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__) && !defined(RG_NO_DISPATCH) && \
    !defined(RG_DOUBLE)
#define RG_AVX2_PATHS 1
#else
#define RG_AVX2_PATHS 0
#endif

#endif
