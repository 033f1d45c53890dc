/* lframes.h: the frame stream of a recording, quantised and delta-encoded, then deflated.
 * lua/viewer/viewer.html decodes it (function decodeFrames); the two must agree.
 *
 * Every number is an integer count of quanta (positions and sizes: the position quantum,
 * velocities: the velocity quantum; colours: an index into the colour table) written as a
 * varint (lenc.h).  Per frame:
 *   sv  time in microseconds, as a second difference (t - 2 t' + t'')
 *   uv  births, then each born track as the uv gap from the previous one (first: id + 1)
 *   uv  deaths, likewise
 *   per channel, for every live track in ascending id:
 *       x, y, vx, vy   sv of the second difference (prediction 2 q' - q'', or q' after one
 *                      sample, 0 for a track just born)
 *       hx, hy, colour sv of the first difference (0 for a track just born)
 *       bounds         uv 1 when the track has a fat box in this frame, else 0; then for
 *                      each that has: lower x, lower y, upper x, upper y as sv of the
 *                      first difference from its last fat box
 *   per free list (primitives without a body: contact points and normals, springs), in
 *   quanta of LFRAMES_CQ position quanta:
 *       uv  0 when the list is the last frame's (the same primitives), else its count + 1
 *           and each primitive: uv g > 0, the reference g places after the last (from -1)
 *           into the last frame's list as written, then per coordinate sv of its
 *           difference from the one referred to (for a second point, of the difference from
 *           the first point's difference); or uv 0, uv kind (LFRAMES_POINT...), uv colour
 *           and per coordinate sv of the difference from the last new primitive's (from 0).
 *       The references come first in ascending order; the list as written is the one the
 *       next frame refers to. */
#ifndef LFRAMES_H
#define LFRAMES_H

#include <stddef.h>
#include <stdint.h>

#include "lenc.h"

enum { LF_X, LF_Y, LF_VX, LF_VY, LF_HX, LF_HY, LF_COL, LF_BOUNDS, LF_BX0, LF_BY0, LF_BX1, LF_BY1,
       LF_CHANNELS };

#define LFRAMES_POINT   0   /* x, y */
#define LFRAMES_SEGMENT 1   /* x0, y0, x1, y1 */
#define LFRAMES_CIRCLE  2   /* x, y, r */
#define LFRAMES_BOX     3   /* x0, y0, x1, y1 */
#define LFRAMES_LISTS   2   /* free lists: 0 contacts, 1 springs */
#define LFRAMES_CQ      4   /* their quantum, in position quanta */

typedef struct lframes_body {
    int32_t track;
    int32_t pad;
    int64_t q[LF_CHANNELS];
} lframes_body;

typedef struct lframes_prim {
    int32_t kind, col;
    int64_t q[4];
} lframes_prim;

typedef struct lframes lframes;

/* cap bounds the compressed stream (bytes).  NULL when out of memory. */
lframes *lframes_new(size_t cap);
void lframes_free(lframes *e);
/* One frame: the bodies in any order (sorted here, by track), the free lists (sorted here).
 * Returns 0, or -1 once the stream failed (out of memory or over its cap); after that
 * every call fails and nothing more is written. */
int lframes_add(lframes *e, int64_t t_us, lframes_body *bodies, int32_t nbodies,
                lframes_prim *lists[LFRAMES_LISTS], const int32_t counts[LFRAMES_LISTS]);
int32_t lframes_count(const lframes *e);
/* Ends the stream and returns its bytes (owned by e), or NULL on failure. */
const unsigned char *lframes_finish(lframes *e, size_t *out_len);
/* Bytes before compression, for the report. */
size_t lframes_raw_bytes(const lframes *e);

#endif
