/* lhtml.c: the replay recorder.  Each frame is a sample (lsample.c: rg_world_draw's layers
 * and the binding's names), quantised into the stream of lframes.c; the page is
 * lua/viewer/viewer.html with the recording in place of its marker line.  print is
 * replaced, so the page can show each printed line at the frame it was printed at. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lauxlib.h>
#include <lua.h>

#include "lenc.h"
#include "lframes.h"
#include "lhtml.h"
#include "lrigid.h"
#include "lsample.h"

#define QMAX 1125899906842624.0   /* 2^50 quanta: exact in a JavaScript number */

/* The sample's primitives and lists go into the stream as they are. */
typedef char lhtml_kinds_agree[LSAMPLE_POINT == LFRAMES_POINT && LSAMPLE_SEGMENT == LFRAMES_SEGMENT &&
                               LSAMPLE_CIRCLE == LFRAMES_CIRCLE && LSAMPLE_BOX == LFRAMES_BOX &&
                               LSAMPLE_LISTS == LFRAMES_LISTS && LSAMPLE_CONTACTS == 0 ? 1 : -1];

typedef struct logline {
    int32_t frame;
    uint32_t off, len;
} logline;

struct lhtml {
    lsample smp;
    lframes *enc;
    int stopped;
    const char *why;          /* why recording stopped, or NULL */
    double q;                 /* position quantum (m); velocities in q m/s; 0 until set */
    lframes_body *cur;        /* the frame quantised */
    int32_t cur_room;
    lframes_prim *lists[LSAMPLE_LISTS];
    int32_t rooms[LSAMPLE_LISTS];
    lenc_buf log;
    logline *lines;
    int32_t nlines, lines_room, dropped;
    int log_open;             /* a line is being printed */
};

static void stop(lhtml *r, const char *why)
{
    if (!r->stopped) r->why = why;
    r->stopped = 1;
}

/* The frames' part of r, empty. */
static void frames_begin(lhtml *r)
{
    lsample_init(&r->smp);
    r->enc = lframes_new(LHTML_MAX_BYTES);
    if (r->enc == NULL) stop(r, "out of memory");
}

static void frames_end(lhtml *r)
{
    int i;
    lsample_release(&r->smp);
    lframes_free(r->enc);
    r->enc = NULL;
    free(r->cur);
    r->cur = NULL;
    r->cur_room = 0;
    for (i = 0; i < LSAMPLE_LISTS; i++) {
        free(r->lists[i]);
        r->lists[i] = NULL;
        r->rooms[i] = 0;
    }
    r->q = 0;
    r->stopped = 0;
    r->why = NULL;
}

lhtml *lhtml_new(void)
{
    lhtml *r = (lhtml *)calloc(1, sizeof *r);
    if (r == NULL) return NULL;
    lenc_init(&r->log, LHTML_MAX_LOG);
    frames_begin(r);
    if (r->enc == NULL) {
        lhtml_free(r);
        return NULL;
    }
    return r;
}

void lhtml_free(lhtml *r)
{
    if (r == NULL) return;
    frames_end(r);
    lenc_free(&r->log);
    free(r->lines);
    free(r);
}

void lhtml_restart(lhtml *r)
{
    int32_t i;
    if (r == NULL) return;
    frames_end(r);
    frames_begin(r);
    for (i = 0; i < r->nlines; i++) r->lines[i].frame = 0;
}

int lhtml_frames(const lhtml *r)
{
    return r != NULL && r->enc != NULL ? (int)lframes_count(r->enc) : 0;
}

/* ---------------------------------------------------------------- one frame */

static int64_t quant(double v, double q)
{
    double k = floor(v / q + 0.5);
    return (int64_t)(k > QMAX ? QMAX : k < -QMAX ? -QMAX : k);
}

void lhtml_record(lhtml *r, lua_State *L, int world_idx, double t)
{
    lsample *s;
    int32_t i, l, frame;
    if (r == NULL || r->stopped || lrigid_toworld(L, world_idx) == NULL) return;
    s = &r->smp;
    frame = s->frames;
    if (lsample_frame(s, L, world_idx) != 0) {
        stop(r, s->full ? "more bodies than the recording keeps (2^21)" : s->oom ? "out of memory"
                                                                                : "rg_world_draw failed");
        return;
    }
    if (r->q == 0) {
        /* 2^-10 m, finer when the first frame's smallest shape is under 0.25 m (1/256 of its
         * half extent), so a shape is drawn to better than half a percent of its size. */
        r->q = ldexp(1.0, -10);
        if (s->hmin < 0.25) r->q = ldexp(1.0, (int)floor(log2(s->hmin / 256)));
        if (r->q < ldexp(1.0, -30)) r->q = ldexp(1.0, -30);
    }
    if (!lenc_grow((void **)&r->cur, &r->cur_room, s->ncur, sizeof *r->cur)) {
        stop(r, "out of memory");
        return;
    }
    for (i = 0; i < s->ncur; i++) {
        const lsample_body *b = &s->cur[i];
        lframes_body *e = &r->cur[i];
        memset(e, 0, sizeof *e);
        e->track = b->track;
        e->q[LF_X] = quant(b->x, r->q);
        e->q[LF_Y] = quant(b->y, r->q);
        e->q[LF_VX] = quant(b->vx, r->q);
        e->q[LF_VY] = quant(b->vy, r->q);
        e->q[LF_HX] = quant(b->hx, r->q);
        e->q[LF_HY] = quant(b->hy, r->q);
        e->q[LF_COL] = b->col + 1;   /* 0: no colour known */
        e->q[LF_BOUNDS] = b->has_box;
        if (b->has_box) {
            e->q[LF_BX0] = quant(b->box[0], r->q);
            e->q[LF_BY0] = quant(b->box[1], r->q);
            e->q[LF_BX1] = quant(b->box[2], r->q);
            e->q[LF_BY1] = quant(b->box[3], r->q);
        }
    }
    for (l = 0; l < LSAMPLE_LISTS; l++) {
        if (!lenc_grow((void **)&r->lists[l], &r->rooms[l], s->counts[l], sizeof *r->lists[l])) {
            stop(r, "out of memory");
            return;
        }
        for (i = 0; i < s->counts[l]; i++) {
            const lsample_prim *p = &s->lists[l][i];
            lframes_prim *e = &r->lists[l][i];
            int k;
            e->kind = p->kind;
            e->col = p->col;
            for (k = 0; k < 4; k++) e->q[k] = quant(p->v[k], r->q * LFRAMES_CQ);
        }
    }
    if (lframes_add(r->enc, quant(t, 1e-6), r->cur, s->ncur, r->lists, s->counts) != 0) {
        stop(r, frame == 0 ? "out of memory" : "the recording reached its size cap");
        return;
    }
}

/* ---------------------------------------------------------------- the script's lines */

static void log_begin(lhtml *r)
{
    logline *ln;
    r->log_open = 0;
    if (r->log.len + 1 >= LHTML_MAX_LOG ||
        !lenc_grow((void **)&r->lines, &r->lines_room, r->nlines + 1, sizeof *r->lines)) {
        r->dropped++;
        return;
    }
    ln = &r->lines[r->nlines++];
    ln->frame = lhtml_frames(r) > 0 ? lhtml_frames(r) - 1 : 0;
    ln->off = (uint32_t)r->log.len;
    ln->len = 0;
    r->log_open = 1;
}

static void log_text(lhtml *r, const char *s, size_t n)
{
    if (!r->log_open) return;
    if (n > LHTML_MAX_LOG - 1 - r->log.len) n = LHTML_MAX_LOG - 1 - r->log.len;
    lenc_bytes(&r->log, s, n);
    if (!r->log.failed) r->lines[r->nlines - 1].len += (uint32_t)n;
}

/* print, as Lua's own (luaB_print), that also logs; charged as the sandbox's is (upvalue 2,
 * the meter, or nil): its strings' bytes, before anything is written. */
static int lhtml_print(lua_State *L)
{
    lhtml *r = (lhtml *)lua_touserdata(L, lua_upvalueindex(1));
    const lpattern_meter *m = (const lpattern_meter *)lua_touserdata(L, lua_upvalueindex(2));
    int n = lua_gettop(L), i;
    if (m != NULL) {
        size_t bytes = 0;
        for (i = 1; i <= n; i++)
            if (lua_type(L, i) == LUA_TSTRING) bytes += lua_rawlen(L, i);
        if (bytes > 0) m->charge(L, m->ud, bytes);
    }
    log_begin(r);
    for (i = 1; i <= n; i++) {
        size_t len;
        const char *s = luaL_tolstring(L, i, &len);
        if (i > 1) {
            fwrite("\t", 1, 1, stdout);
            log_text(r, "\t", 1);
        }
        fwrite(s, 1, len, stdout);
        log_text(r, s, len);
        lua_pop(L, 1);
    }
    fwrite("\n", 1, 1, stdout);
    fflush(stdout);
    r->log_open = 0;
    return 0;
}

void lhtml_capture_print(lua_State *L, lhtml *r, const lpattern_meter *meter)
{
    union { const lpattern_meter *c; void *p; } u;   /* stored, never written through */
    u.c = meter;
    lua_pushlightuserdata(L, r);
    if (meter != NULL) lua_pushlightuserdata(L, u.p);
    else lua_pushnil(L);
    lua_pushcclosure(L, lhtml_print, 2);
    lua_setglobal(L, "print");
}

/* ---------------------------------------------------------------- the page */

extern const char *const lviewer_html[];   /* lua/viewer/viewer.html, by line (generated) */

static void write_meta(lhtml *r, FILE *f, const char *title, const char *subtitle, size_t bytes)
{
    const lsample *s = &r->smp;
    int32_t i, frames = lhtml_frames(r);
    double b[4];
    memcpy(b, s->box, sizeof b);
    fputs("{\"format\":1,\"title\":", f);
    lenc_json_string(f, title, strlen(title));
    fputs(",\"subtitle\":", f);
    lenc_json_string(f, subtitle, strlen(subtitle));
    fprintf(f, ",\"frames\":%d,\"q\":%.17g,\"qc\":%.17g,\"bytes\":%lu,\"raw\":%lu", (int)frames,
            r->q, r->q * LFRAMES_CQ, (unsigned long)bytes, (unsigned long)lframes_raw_bytes(r->enc));
    if (!(b[0] <= b[2])) b[0] = b[1] = -1, b[2] = b[3] = 1;
    fprintf(f, ",\"world\":[%.9g,%.9g,%.9g,%.9g]", b[0], b[1], b[2], b[3]);
    fprintf(f, ",\"recorded\":{\"contacts\":%s,\"springs\":%s,\"bounds\":%s}",
            s->any[LSAMPLE_CONTACTS] ? "true" : "false", s->any[LSAMPLE_SPRINGS] ? "true" : "false",
            s->any[LSAMPLE_LISTS] ? "true" : "false");
    fputs(",\"stopped\":", f);
    if (r->why != NULL) lenc_json_string(f, r->why, strlen(r->why));
    else fputs("null", f);
    /* colours: [0xRRGGBBAA, what it was drawn on (LSAMPLE_*)] */
    fputs(",\"colors\":[", f);
    for (i = 0; i < s->ncolors; i++)
        fprintf(f, "%s[%lu,%lu]", i ? "," : "", (unsigned long)s->colors[i], (unsigned long)s->seen[i]);
    /* tracks: [name or null, type, shape, sensor, first frame, last frame, serial]; a track
     * first drawn in a frame the stream did not take has none */
    fputs("],\"tracks\":[\n", f);
    for (i = 0; i < s->ntracks; i++) {
        const lsample_track *tr = &s->tracks[i];
        size_t len;
        const char *name = lsample_name(s, i, &len);
        int none = tr->first < 0 || tr->first >= frames;
        fputs(i ? ",\n[" : "[", f);
        if (name != NULL) lenc_json_string(f, name, len);
        else fputs("null", f);
        fprintf(f, ",%d,%d,%d,%d,%d,%lld]", (int)tr->type, (int)tr->shape, (int)tr->sensor,
                none ? -1 : (int)tr->first, none ? -1 : (int)(tr->last < frames ? tr->last : frames - 1),
                tr->serial);
    }
    fputs("],\n\"log\":[\n", f);
    for (i = 0; i < r->nlines; i++) {
        fprintf(f, "%s[%d,", i ? ",\n" : "", (int)r->lines[i].frame);
        lenc_json_string(f, (const char *)r->log.data + r->lines[i].off, r->lines[i].len);
        fputc(']', f);
    }
    fprintf(f, "],\"log_dropped\":%d}", (int)r->dropped);
}

int lhtml_write(lhtml *r, const char *path, const char *title, const char *subtitle)
{
    const unsigned char *data;
    size_t len = 0;
    int i, st;
    FILE *f;
    if (r == NULL || r->enc == NULL || (data = lframes_finish(r->enc, &len)) == NULL) {
        errno = EIO;
        return -1;
    }
    if ((f = fopen(path, "w")) == NULL) return -1;
    for (i = 0; lviewer_html[i] != NULL; i++) {
        if (strcmp(lviewer_html[i], "<!-- rigid:recording -->\n") != 0) {
            fputs(lviewer_html[i], f);
            continue;
        }
        fputs("<script id=\"rigid-meta\" type=\"application/json\">", f);
        write_meta(r, f, title, subtitle, len);
        fputs("</script>\n<script id=\"rigid-frames\" type=\"application/octet-stream\">\n", f);
        lenc_base64(f, data, len);
        fputs("</script>\n", f);
    }
    st = ferror(f);
    if (fclose(f) != 0 || st) {
        if (errno == 0) errno = EIO;
        return -1;
    }
    return 0;
}
