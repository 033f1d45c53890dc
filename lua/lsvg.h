/* lsvg.h: a picture of a run as SVG: the world at the moment shown (the last frame recorded)
 * as rg_world_draw draws it (shapes in their state's colour, touching contacts, springs),
 * velocity arrows, the paths that led there, and a legend that says what each mark means. */
#ifndef LSVG_H
#define LSVG_H

#include <lua.h>

typedef struct lsvg lsvg;

lsvg *lsvg_new(void);
void lsvg_free(lsvg *r);

/* Samples the world value at world_idx, at simulated time t (s), through lsample.c.  Uses
 * malloc, not the state's allocator, and bounds what it keeps (paths of the first 1024
 * moving bodies, at most 512 points each, thinned evenly as a run grows). */
void lsvg_record(lsvg *r, lua_State *L, int world_idx, double t);

/* Writes the picture; title and subtitle are plain text (escaped here).  0 on success. */
int lsvg_write(const lsvg *r, const char *path, const char *title, const char *subtitle);

#endif
