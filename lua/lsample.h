/* lsample.h: one frame of a world as rg_world_draw draws it (shapes with their body and the
 * colour of its state, fat boxes, contacts, springs), with each body's velocity and, for the
 * bodies the binding knows, name, type and creation order.  The replay recorder (lhtml.c)
 * and the SVG picture (lsvg.c) are built on it. */
#ifndef LSAMPLE_H
#define LSAMPLE_H

#include <stddef.h>
#include <stdint.h>

#include <lua.h>

#include "rigid.h"

/* What a colour was drawn on (a picture's legend says what each colour means). */
#define LSAMPLE_STATIC    1u
#define LSAMPLE_KINEMATIC 2u
#define LSAMPLE_AWAKE     4u    /* dynamic, awake */
#define LSAMPLE_ASLEEP    8u    /* dynamic, asleep */
#define LSAMPLE_SENSOR    16u
#define LSAMPLE_BOUNDS    32u
#define LSAMPLE_CONTACT   64u
#define LSAMPLE_SPRING    128u

#define LSAMPLE_POINT   0       /* primitive kinds: x, y */
#define LSAMPLE_SEGMENT 1       /* x0, y0, x1, y1 */
#define LSAMPLE_CIRCLE  2       /* x, y, r */
#define LSAMPLE_BOX     3       /* x0, y0, x1, y1 */
#define LSAMPLE_CONTACTS 0      /* free lists: contact points and normals */
#define LSAMPLE_SPRINGS  1      /* springs */
#define LSAMPLE_LISTS    2

#define LSAMPLE_MAX_COLORS 1024
#define LSAMPLE_MAX_TRACKS (1 << 21)   /* bodies drawn in a run (about 64 bytes each) */

/* A body that has been drawn: its track lives as long as the sampler. */
typedef struct lsample_track {
    rg_body body;
    long long serial;         /* creation order in the binding, from 1; 0 if unknown */
    int32_t type;             /* RG_BODY_* */
    int32_t shape;            /* RG_SHAPE_* as last drawn */
    int32_t sensor, named;
    int32_t first, last;      /* frames it was drawn in (from 0) */
    int32_t name_off, name_len;
    int32_t col;              /* colour index as last drawn, -1 when not known */
    int32_t stamp, cur;       /* frame + 1 of its sample in `cur`, and where */
} lsample_track;

typedef struct lsample_body {
    int32_t track, col;       /* col: colour index, -1 when not known */
    double x, y;              /* centre, m */
    double hx, hy;            /* half extents (r, r for a circle; 0, 0 for a point), m */
    double vx, vy;            /* m/s */
    int32_t has_box, pad;
    double box[4];            /* fat box: lower x, lower y, upper x, upper y, m */
} lsample_body;

typedef struct lsample_prim {
    int32_t kind, col;
    double v[4];
} lsample_prim;

typedef struct lsample {
    lsample_track *tracks;
    int32_t ntracks, tracks_room;
    uint64_t *keys;           /* handle -> track + 1 (open addressing), 0 = empty */
    int32_t *vals, hcap;
    char *names;              /* every track's name, back to back */
    size_t names_len, names_room;
    uint32_t colors[LSAMPLE_MAX_COLORS];
    uint32_t seen[LSAMPLE_MAX_COLORS];   /* LSAMPLE_* bits */
    int32_t ncolors;
    lsample_body *cur;        /* the last frame's bodies, in draw order */
    int32_t ncur, cur_room;
    lsample_prim *lists[LSAMPLE_LISTS];
    int32_t counts[LSAMPLE_LISTS], rooms[LSAMPLE_LISTS];
    struct lsample_spot *spots;
    int32_t nspots, spots_room;
    int32_t frames;           /* frames sampled */
    double box[4];            /* union of all drawn: min x, min y, max x, max y */
    double hmin;              /* smallest half extent of a shape in the first frame */
    int any[LSAMPLE_LISTS + 1];   /* contacts, springs, fat boxes ever drawn */
    int oom;                  /* out of memory, or (full) past LSAMPLE_MAX_TRACKS bodies */
    int full;
} lsample;

void lsample_init(lsample *s);
void lsample_release(lsample *s);
/* Samples the world value at world_idx as the next frame.  0, or -1 when out of memory or
 * when rg_world_draw fails (the sampler then holds a partial frame: stop using it). */
int lsample_frame(lsample *s, lua_State *L, int world_idx);
/* A track's name (not NUL-terminated) and its length; NULL when it has none. */
const char *lsample_name(const lsample *s, int32_t track, size_t *len);

#endif
