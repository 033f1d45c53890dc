/* lhtml.h: records a run frame by frame through rg_world_draw (shapes, contacts, bounds,
 * springs) with body names from the binding and the lines the script prints, and writes it
 * as one self-contained HTML replay viewer (lua/viewer/viewer.html). */
#ifndef LHTML_H
#define LHTML_H

#include <lua.h>

#include "lpattern.h"

typedef struct lhtml lhtml;

/* NULL when out of memory.  Uses malloc, not the script's allocator, and bounds what it
 * keeps (LHTML_MAX_BYTES compressed, the log to LHTML_MAX_LOG bytes); past a bound it stops
 * recording and the page says so. */
#define LHTML_MAX_BYTES (512u << 20)
#define LHTML_MAX_LOG   (8u << 20)
lhtml *lhtml_new(void);
void lhtml_free(lhtml *r);
/* Drops the frames (the log stays, its lines moved to frame 0): the world changes. */
void lhtml_restart(lhtml *r);

/* Replaces the global `print` of L with one that prints as Lua's does and also logs the
 * line, stamped with the frame the script sees (the last recorded), and that charges meter
 * (NULL: none) a unit per byte of its string arguments before it writes, as the sandbox's
 * print does (lcount.c).  r and meter must outlive L. */
void lhtml_capture_print(lua_State *L, lhtml *r, const lpattern_meter *meter);

/* Records one frame of the world value at world_idx, at simulated time t (s). */
void lhtml_record(lhtml *r, lua_State *L, int world_idx, double t);
int lhtml_frames(const lhtml *r);

/* Writes the viewer; title and subtitle are plain text.  0 on success, -1 with errno set
 * by the failing call (or EIO when the recording itself failed). */
int lhtml_write(lhtml *r, const char *path, const char *title, const char *subtitle);

#endif
