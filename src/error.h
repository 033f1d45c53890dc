/* error.h: the last error of a world, the text rg_world_last_error returns: the entry points
 * set it when a call fails (function, argument, rule) and clear it when a call succeeds. */
#ifndef RG_ERROR_H
#define RG_ERROR_H

#include "rigid.h"

/* Room for one message, its terminating NUL included; a longer one is cut. */
#define ERROR_SIZE 200

#if defined(__GNUC__) || defined(__clang__)
#define ERROR_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define ERROR_PRINTF(f, a)
#endif

/* Sets w's last error to "func: " and the printf-style text; returns st.  The one place a
 * message is formatted. */
rg_status error_set(const rg_world *w, rg_status st, const char *func, const char *fmt, ...)
    ERROR_PRINTF(4, 5);
/* The failure st (RG_ERR_OUT_OF_MEMORY or RG_ERR_CAPACITY) of growing `what`, whose most is
 * `limit` (a constant's name); returns st. */
rg_status error_alloc(const rg_world *w, const char *func, rg_status st, const char *what,
                      const char *limit);

/* An entry point's failure: return RG_FAIL(world, status, "radius %g is ...", (double)r). */
#define RG_FAIL(w, st, ...) error_set((w), (st), __func__, __VA_ARGS__)

/* Clears w's last error (non-NULL w).  It writes only when there is one, so that calls that
 * succeed only read it.  Where it is used, struct rg_world is known (state.h). */
#define ERROR_CLEAR(w)                           \
    do {                                         \
        if ((w)->err[0] != '\0') (w)->err[0] = '\0'; \
    } while (0)

/* Opens an entry point on world: RG_ERR_INVALID_ARGUMENT for NULL (there is no world to hold
 * a reason), else its last error cleared. */
#define ERROR_BEGIN(w)                                   \
    if ((w) == NULL) return RG_ERR_INVALID_ARGUMENT;     \
    ERROR_CLEAR(w)

#endif
