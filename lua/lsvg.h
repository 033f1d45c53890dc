/* lsvg.h: records a world while it runs (bodies, trails, contacts) and draws it as SVG. */
#ifndef LSVG_H
#define LSVG_H

#include <lua.h>

typedef struct lsvg lsvg;

lsvg *lsvg_new(void);
void lsvg_free(lsvg *r);

/* Samples the live bodies of the world value at world_idx, at simulated time t (s).  Uses
 * malloc, not the state's allocator, and bounds what it keeps (trails of the first 1024
 * bodies, at most 512 points each, thinned evenly as a run grows). */
void lsvg_record(lsvg *r, lua_State *L, int world_idx, double t);
/* A contact point (begin event) in world coordinates. */
void lsvg_contact(lsvg *r, double x, double y);
int lsvg_contact_count(const lsvg *r);

/* Writes the picture; title and subtitle are plain text (escaped here).  0 on success. */
int lsvg_write(const lsvg *r, const char *path, const char *title, const char *subtitle);

#endif
