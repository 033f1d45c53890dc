/* lhtml.c: the replay recorder.  Each frame comes from rg_world_draw, one call per layer
 * (shapes, fat boxes, contacts, springs), plus the velocity of every drawn body and the
 * bodies without a shape (which rg_world_draw does not draw) from the binding's table; the
 * frames go to the stream of lframes.c and the page is lua/viewer/viewer.html with the
 * recording in place of its marker line. */
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

#define MAX_COLORS 1024
#define MAX_NAMES  (4u << 20)    /* bytes of body names kept */
#define QMAX       1125899906842624.0   /* 2^50 quanta: exact in a JavaScript number */

/* What a colour was seen on (the page's legend says what each colour means). */
#define SEEN_STATIC    1u
#define SEEN_KINEMATIC 2u
#define SEEN_AWAKE     4u    /* dynamic, awake */
#define SEEN_ASLEEP    8u    /* dynamic, asleep */
#define SEEN_SENSOR    16u
#define SEEN_BOUNDS    32u
#define SEEN_CONTACT   64u
#define SEEN_SPRING    128u

typedef struct track {
    rg_body body;
    long long serial;
    int32_t type, shape, sensor, named;
    int32_t first, last;      /* frames; first < 0 until a frame with it is written */
    int32_t name_off, name_len;
    int32_t col;              /* last colour index, -1 at first */
    int32_t stamp;            /* frame of its sample in cur, + 1 */
    int32_t cur;              /* its sample in cur */
} track;

typedef struct logline {
    int32_t frame;
    uint32_t off, len;
} logline;

struct lhtml {
    lframes *enc;
    int stopped;
    const char *why;          /* why recording stopped, or NULL */
    double q;                 /* position quantum (m); velocities in q m/s; 0 until set */
    double box[4];            /* union of the shapes drawn: min x, min y, max x, max y */
    track *tracks;
    int32_t ntracks, tracks_room;
    uint64_t *keys;           /* handle -> track + 1 (open addressing), 0 = empty */
    int32_t *vals, hcap;
    lenc_buf names;
    uint32_t colors[MAX_COLORS];
    uint32_t seen[MAX_COLORS];
    int32_t ncolors;
    lframes_body *cur;        /* this frame's bodies */
    int32_t ncur, cur_room;
    lframes_prim *lists[LFRAMES_LISTS];
    int32_t counts[LFRAMES_LISTS], rooms[LFRAMES_LISTS];
    int oom;
    int any[LFRAMES_LISTS + 1];   /* contacts, springs, bounds ever drawn */
    lenc_buf log;
    logline *lines;
    int32_t nlines, lines_room, dropped;
    int log_open;             /* a line is being printed */
};

lhtml *lhtml_new(void)
{
    lhtml *r = (lhtml *)calloc(1, sizeof *r);
    if (r == NULL) return NULL;
    r->enc = lframes_new(LHTML_MAX_BYTES);
    if (r->enc == NULL) {
        free(r);
        return NULL;
    }
    lenc_init(&r->names, MAX_NAMES);
    lenc_init(&r->log, LHTML_MAX_LOG);
    r->box[0] = r->box[1] = HUGE_VAL;
    r->box[2] = r->box[3] = -HUGE_VAL;
    return r;
}

static void drop_frames(lhtml *r)
{
    int i;
    lframes_free(r->enc);
    free(r->tracks);
    free(r->keys);
    free(r->vals);
    free(r->cur);
    for (i = 0; i < LFRAMES_LISTS; i++) free(r->lists[i]);
    lenc_free(&r->names);
}

void lhtml_free(lhtml *r)
{
    if (r == NULL) return;
    drop_frames(r);
    lenc_free(&r->log);
    free(r->lines);
    free(r);
}

void lhtml_restart(lhtml *r)
{
    lhtml keep;
    int32_t i;
    if (r == NULL) return;
    keep = *r;
    drop_frames(r);
    memset(r, 0, sizeof *r);
    r->log = keep.log;
    r->lines = keep.lines;
    r->nlines = keep.nlines;
    r->lines_room = keep.lines_room;
    r->dropped = keep.dropped;
    for (i = 0; i < r->nlines; i++) r->lines[i].frame = 0;
    r->enc = lframes_new(LHTML_MAX_BYTES);
    lenc_init(&r->names, MAX_NAMES);
    r->box[0] = r->box[1] = HUGE_VAL;
    r->box[2] = r->box[3] = -HUGE_VAL;
    if (r->enc == NULL) {
        r->stopped = 1;
        r->why = "out of memory";
    }
}

int lhtml_frames(const lhtml *r)
{
    return r != NULL && r->enc != NULL ? (int)lframes_count(r->enc) : 0;
}

static int grow(void **p, int32_t *room, int32_t n, size_t sz)
{
    int32_t k = *room < 64 ? 64 : *room;
    void *q;
    if (n <= *room) return 1;
    while (k < n) {
        if (k > (1 << 28)) return 0;
        k *= 2;
    }
    q = realloc(*p, (size_t)k * sz);
    if (q == NULL) return 0;
    *p = q;
    *room = k;
    return 1;
}

/* ---------------------------------------------------------------- tracks */

static uint32_t hash(uint64_t h)
{
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    return (uint32_t)h;
}

static int32_t find(const lhtml *r, rg_body body)
{
    uint32_t m, i;
    if (r->hcap == 0) return -1;
    m = (uint32_t)r->hcap - 1;
    for (i = hash(body) & m; r->keys[i] != 0; i = (i + 1) & m)
        if (r->keys[i] == body) return r->vals[i] - 1;
    return -1;
}

static void put(lhtml *r, rg_body body, int32_t t)
{
    uint32_t m = (uint32_t)r->hcap - 1, i;
    for (i = hash(body) & m; r->keys[i] != 0; i = (i + 1) & m) {}
    r->keys[i] = body;
    r->vals[i] = t + 1;
}

/* The track of a body, made on first sight; -1 when out of memory. */
static int32_t track_of(lhtml *r, const rg_world *w, rg_body body)
{
    int32_t t = find(r, body), i;
    track *tr;
    if (t >= 0) return t;
    if (2 * (r->ntracks + 1) > r->hcap) {   /* rehash at half full */
        int32_t cap = r->hcap < 1024 ? 1024 : 2 * r->hcap;
        uint64_t *ok = r->keys;
        int32_t *ov = r->vals, oc = r->hcap;
        r->keys = (uint64_t *)calloc((size_t)cap, sizeof *r->keys);
        r->vals = (int32_t *)calloc((size_t)cap, sizeof *r->vals);
        if (r->keys == NULL || r->vals == NULL || cap > (1 << 28)) {
            free(r->keys);
            free(r->vals);
            r->keys = ok;
            r->vals = ov;
            return -1;
        }
        r->hcap = cap;
        for (i = 0; i < oc; i++)
            if (ok[i] != 0) put(r, ok[i], ov[i] - 1);
        free(ok);
        free(ov);
    }
    if (!grow((void **)&r->tracks, &r->tracks_room, r->ntracks + 1, sizeof *r->tracks)) return -1;
    t = r->ntracks++;
    tr = &r->tracks[t];
    memset(tr, 0, sizeof *tr);
    tr->body = body;
    tr->first = tr->last = -1;
    tr->col = -1;
    if (rg_body_get_type(w, body, &tr->type) != RG_OK) tr->type = RG_BODY_DYNAMIC;
    put(r, body, t);
    return t;
}

static void name_track(lhtml *r, track *tr, const lrigid_body_info *info)
{
    size_t n = info->name != NULL ? strlen(info->name) : 0;
    tr->named = 1;
    tr->serial = (long long)info->serial;
    tr->type = info->type;
    tr->sensor = info->sensor;
    if (n > 200) n = 200;
    tr->name_off = (int32_t)r->names.len;
    lenc_bytes(&r->names, info->name, n);
    tr->name_len = r->names.failed ? 0 : (int32_t)n;
}

static int32_t color_index(lhtml *r, uint32_t rgba)
{
    int32_t i;
    for (i = r->ncolors - 1; i >= 0; i--)
        if (r->colors[i] == rgba) return i;
    if (r->ncolors == MAX_COLORS) return 0;
    r->colors[r->ncolors] = rgba;
    return r->ncolors++;
}

/* ---------------------------------------------------------------- one frame */

typedef struct pass {
    lhtml *r;
    const rg_world *w;
    int32_t frame;
    uint32_t layer;           /* RG_DRAW_* of this call */
    double hmin;              /* smallest half extent (the first frame's sizing pass) */
} pass;

static int64_t quant(double v, double q)
{
    double k = floor(v / q + 0.5);
    return (int64_t)(k > QMAX ? QMAX : k < -QMAX ? -QMAX : k);
}

static lframes_body *body_sample(pass *p, rg_body body)
{
    lhtml *r = p->r;
    int32_t t;
    track *tr;
    lframes_body *s;
    if (p->layer != RG_DRAW_SHAPES) {   /* a fat box: of a body drawn in this frame, or none */
        t = find(r, body);
        return t >= 0 && r->tracks[t].stamp == p->frame + 1 ? &r->cur[r->tracks[t].cur] : NULL;
    }
    if ((t = track_of(r, p->w, body)) < 0) {
        r->oom = 1;
        return NULL;
    }
    tr = &r->tracks[t];
    if (tr->stamp == p->frame + 1) return &r->cur[tr->cur];
    if (!grow((void **)&r->cur, &r->cur_room, r->ncur + 1, sizeof *r->cur)) {
        r->oom = 1;
        return NULL;
    }
    tr->stamp = p->frame + 1;
    tr->cur = r->ncur;
    s = &r->cur[r->ncur++];
    memset(s, 0, sizeof *s);
    s->track = t;
    return s;
}

/* A shape, or a fat box in the bounds layer, as the box [x0, x1] x [y0, y1]. */
static void on_shape(pass *p, rg_body body, double x0, double y0, double x1, double y1,
                     int32_t shape, uint32_t rgba)
{
    lhtml *r = p->r;
    lframes_body *s;
    int32_t col;
    if (p->layer == 0) {   /* sizing pass */
        if (x1 - x0 > 0 && x1 - x0 < 2 * p->hmin) p->hmin = (x1 - x0) / 2;
        if (y1 - y0 > 0 && y1 - y0 < 2 * p->hmin) p->hmin = (y1 - y0) / 2;
        return;
    }
    if ((s = body_sample(p, body)) == NULL) return;
    col = color_index(r, rgba);
    if (p->layer == RG_DRAW_BOUNDS) {
        s->q[LF_BOUNDS] = 1;
        s->q[LF_BX0] = quant(x0, r->q);
        s->q[LF_BY0] = quant(y0, r->q);
        s->q[LF_BX1] = quant(x1, r->q);
        s->q[LF_BY1] = quant(y1, r->q);
        r->seen[col] |= SEEN_BOUNDS;
        r->any[LFRAMES_LISTS] = 1;
        return;
    }
    /* centre and half extents from the integer corners, so the page's box has exactly the
     * recorded corners */
    s->q[LF_X] = quant((x0 + x1) / 2, r->q);
    s->q[LF_Y] = quant((y0 + y1) / 2, r->q);
    s->q[LF_HX] = quant((x1 - x0) / 2, r->q);
    s->q[LF_HY] = quant((y1 - y0) / 2, r->q);
    s->q[LF_COL] = col + 1;   /* 0: a body without a shape */
    r->tracks[s->track].shape = shape;
    if (x0 < r->box[0]) r->box[0] = x0;
    if (y0 < r->box[1]) r->box[1] = y0;
    if (x1 > r->box[2]) r->box[2] = x1;
    if (y1 > r->box[3]) r->box[3] = y1;
}

static void prim(pass *p, int kind, double a, double b, double c, double d, uint32_t rgba)
{
    lhtml *r = p->r;
    int l = p->layer == RG_DRAW_SPRINGS ? 1 : 0;
    lframes_prim *q;
    if (p->layer != RG_DRAW_CONTACTS && p->layer != RG_DRAW_SPRINGS) return;
    if (!grow((void **)&r->lists[l], &r->rooms[l], r->counts[l] + 1, sizeof *r->lists[l])) {
        r->oom = 1;
        return;
    }
    q = &r->lists[l][r->counts[l]++];
    q->kind = kind;
    q->col = color_index(r, rgba);
    q->q[0] = quant(a, r->q * LFRAMES_CQ);
    q->q[1] = quant(b, r->q * LFRAMES_CQ);
    q->q[2] = quant(c, r->q * LFRAMES_CQ);
    q->q[3] = quant(d, r->q * LFRAMES_CQ);
    r->seen[q->col] |= l == 1 ? SEEN_SPRING : SEEN_CONTACT;
    r->any[l] = 1;
}

static void cb_circle(rg_body body, rg_vec2 c, rg_real radius, uint32_t rgba, void *user)
{
    pass *p = (pass *)user;
    double x = (double)c.x, y = (double)c.y, rad = (double)radius;
    if (body == 0) prim(p, LFRAMES_CIRCLE, x, y, rad, 0, rgba);
    else on_shape(p, body, x - rad, y - rad, x + rad, y + rad, LRIGID_SHAPE_CIRCLE, rgba);
}

static void cb_box(rg_body body, rg_vec2 lo, rg_vec2 hi, uint32_t rgba, void *user)
{
    pass *p = (pass *)user;
    if (body == 0)
        prim(p, LFRAMES_BOX, (double)lo.x, (double)lo.y, (double)hi.x, (double)hi.y, rgba);
    else
        on_shape(p, body, (double)lo.x, (double)lo.y, (double)hi.x, (double)hi.y, LRIGID_SHAPE_AABB, rgba);
}

static void cb_segment(rg_vec2 a, rg_vec2 b, uint32_t rgba, void *user)
{
    prim((pass *)user, LFRAMES_SEGMENT, (double)a.x, (double)a.y, (double)b.x, (double)b.y, rgba);
}

static void cb_point(rg_vec2 pt, uint32_t rgba, void *user)
{
    prim((pass *)user, LFRAMES_POINT, (double)pt.x, (double)pt.y, 0, 0, rgba);
}

/* Bodies the binding knows: names for new tracks, and a sample for each body without a
 * shape (drawn as a point).  Only called when a body was not drawn or a track is new. */
static void bodies_from_lua(pass *p, lua_State *L, int world_idx)
{
    lhtml *r = p->r;
    int tbl;
    lrigid_pushbodies(L, world_idx);
    tbl = lua_gettop(L);
    lua_pushnil(L);
    while (lua_next(L, tbl) != 0) {
        lrigid_body_info info;
        rg_vec2 pos;
        if (lrigid_tobody(L, -1, &info)) {
            int shapeless = info.shape == LRIGID_SHAPE_NONE &&
                            rg_body_get_position(p->w, info.handle, &pos) == RG_OK;
            int32_t t = shapeless ? track_of(r, p->w, info.handle) : find(r, info.handle);
            if (t < 0 && shapeless) r->oom = 1;
            if (t >= 0 && !r->tracks[t].named) name_track(r, &r->tracks[t], &info);
            if (t >= 0 && shapeless && r->tracks[t].stamp != p->frame + 1) {
                lframes_body *s;
                p->layer = RG_DRAW_SHAPES;
                if ((s = body_sample(p, info.handle)) != NULL) {
                    s->q[LF_X] = quant((double)pos.x, r->q);
                    s->q[LF_Y] = quant((double)pos.y, r->q);
                    r->tracks[t].shape = LRIGID_SHAPE_NONE;
                }
            }
        }
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
}

static void stop(lhtml *r, const char *why)
{
    if (!r->stopped) r->why = why;
    r->stopped = 1;
}

static rg_status draw(pass *p, uint32_t layer)
{
    rg_debug_draw d;
    memset(&d, 0, sizeof d);
    d.circle = cb_circle;
    d.box = cb_box;
    d.segment = cb_segment;
    d.point = cb_point;
    d.user = p;
    p->layer = layer;
    d.flags = layer != 0 ? layer : RG_DRAW_SHAPES;
    return rg_world_draw(p->w, &d);
}

/* The quantum: 2^-10 m, finer when the smallest shape of the first frame is under 0.25 m
 * (1/256 of its half extent), so a shape is drawn to better than half a percent. */
static int choose_quantum(pass *p)
{
    lhtml *r = p->r;
    p->hmin = HUGE_VAL;
    if (draw(p, 0) != RG_OK) return 0;
    r->q = ldexp(1.0, -10);
    if (p->hmin < 0.25) r->q = ldexp(1.0, (int)floor(log2(p->hmin / 256)));
    if (r->q < ldexp(1.0, -30)) r->q = ldexp(1.0, -30);
    return 1;
}

void lhtml_record(lhtml *r, lua_State *L, int world_idx, double t)
{
    static const uint32_t layers[4] = { RG_DRAW_SHAPES, RG_DRAW_BOUNDS, RG_DRAW_CONTACTS,
                                        RG_DRAW_SPRINGS };
    rg_world *w = lrigid_toworld(L, world_idx);
    pass p;
    int32_t i, unnamed = 0;
    if (r == NULL || w == NULL || r->stopped) return;
    world_idx = lua_absindex(L, world_idx);
    memset(&p, 0, sizeof p);
    p.r = r;
    p.w = w;
    p.frame = lframes_count(r->enc);
    r->ncur = 0;
    r->counts[0] = r->counts[1] = 0;
    if (r->q == 0 && !choose_quantum(&p)) {
        stop(r, "rg_world_draw failed");
        return;
    }
    for (i = 0; i < 4; i++) {
        if (draw(&p, layers[i]) != RG_OK) {
            stop(r, "rg_world_draw failed");
            return;
        }
    }
    for (i = 0; i < r->ncur; i++) unnamed |= !r->tracks[r->cur[i].track].named;
    if (unnamed || rg_world_body_count(w) > r->ncur) bodies_from_lua(&p, L, world_idx);
    if (r->oom) {
        stop(r, "out of memory");
        return;
    }
    /* Velocities, and what each colour was seen on. */
    for (i = 0; i < r->ncur; i++) {
        lframes_body *s = &r->cur[i];
        track *tr = &r->tracks[s->track];
        int32_t col = (int32_t)s->q[LF_COL] - 1;
        rg_vec2 v = { 0, 0 };
        rg_body_get_velocity(w, tr->body, &v);
        s->q[LF_VX] = quant((double)v.x, r->q);
        s->q[LF_VY] = quant((double)v.y, r->q);
        if (col >= 0 && col != tr->col) {
            int32_t awake = 1, sensor = 0;
            rg_body_is_awake(w, tr->body, &awake);
            rg_body_is_sensor(w, tr->body, &sensor);
            r->seen[col] |= sensor ? SEEN_SENSOR : tr->type == RG_BODY_STATIC ? SEEN_STATIC
                            : tr->type == RG_BODY_KINEMATIC ? SEEN_KINEMATIC
                            : awake ? SEEN_AWAKE : SEEN_ASLEEP;
        }
        tr->col = col;
    }
    if (lframes_add(r->enc, quant(t, 1e-6), r->cur, r->ncur, r->lists, r->counts) != 0) {
        stop(r, lframes_count(r->enc) == 0 ? "out of memory" : "the recording reached its size cap");
        return;
    }
    for (i = 0; i < r->ncur; i++) {
        track *tr = &r->tracks[r->cur[i].track];
        if (tr->first < 0) tr->first = p.frame;
        tr->last = p.frame;
    }
}

/* ---------------------------------------------------------------- the script's lines */

static void log_begin(lhtml *r)
{
    logline *ln;
    r->log_open = 0;
    if (r->log.len + 1 >= LHTML_MAX_LOG ||
        !grow((void **)&r->lines, &r->lines_room, r->nlines + 1, sizeof *r->lines)) {
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

/* print, as Lua's own (luaB_print), that also logs. */
static int lhtml_print(lua_State *L)
{
    lhtml *r = (lhtml *)lua_touserdata(L, lua_upvalueindex(1));
    int n = lua_gettop(L), i;
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

void lhtml_capture_print(lua_State *L, lhtml *r)
{
    lua_pushlightuserdata(L, r);
    lua_pushcclosure(L, lhtml_print, 1);
    lua_setglobal(L, "print");
}

/* ---------------------------------------------------------------- the page */

extern const char *const lviewer_html[];   /* lua/viewer/viewer.html, by line (generated) */

static void write_meta(lhtml *r, FILE *f, const char *title, const char *subtitle, size_t bytes)
{
    int32_t i;
    double *b = r->box;
    fputs("{\"format\":1,\"title\":", f);
    lenc_json_string(f, title, strlen(title));
    fputs(",\"subtitle\":", f);
    lenc_json_string(f, subtitle, strlen(subtitle));
    fprintf(f, ",\"frames\":%d,\"q\":%.17g,\"qc\":%.17g,\"bytes\":%lu,\"raw\":%lu",
            lhtml_frames(r), r->q, r->q * LFRAMES_CQ, (unsigned long)bytes, (unsigned long)lframes_raw_bytes(r->enc));
    if (!(b[0] <= b[2])) b[0] = b[1] = -1, b[2] = b[3] = 1;
    fprintf(f, ",\"world\":[%.9g,%.9g,%.9g,%.9g]", b[0], b[1], b[2], b[3]);
    fprintf(f, ",\"recorded\":{\"contacts\":%s,\"springs\":%s,\"bounds\":%s}",
            r->any[0] ? "true" : "false", r->any[1] ? "true" : "false",
            r->any[LFRAMES_LISTS] ? "true" : "false");
    fputs(",\"stopped\":", f);
    if (r->why != NULL) lenc_json_string(f, r->why, strlen(r->why));
    else fputs("null", f);
    /* colours: [0xRRGGBBAA, what it was seen on (SEEN_*)] */
    fputs(",\"colors\":[", f);
    for (i = 0; i < r->ncolors; i++)
        fprintf(f, "%s[%lu,%lu]", i ? "," : "", (unsigned long)r->colors[i], (unsigned long)r->seen[i]);
    /* tracks: [name or null, type, shape, sensor, first frame, last frame, serial] */
    fputs("],\"tracks\":[\n", f);
    for (i = 0; i < r->ntracks; i++) {
        const track *tr = &r->tracks[i];
        fputs(i ? ",\n[" : "[", f);
        if (tr->name_len > 0) lenc_json_string(f, (const char *)r->names.data + tr->name_off, (size_t)tr->name_len);
        else fputs("null", f);
        fprintf(f, ",%d,%d,%d,%d,%d,%lld]", (int)tr->type, (int)tr->shape, (int)tr->sensor,
                (int)tr->first, (int)tr->last, tr->serial);
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
    if (r == NULL || r->enc == NULL || (data = lframes_finish(r->enc, &len)) == NULL ||
        r->names.failed) {
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
