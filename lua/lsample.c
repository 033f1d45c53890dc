/* lsample.c: a frame through rg_world_draw, one call per layer (shapes, fat boxes, contacts,
 * springs), completed from the binding: names, and the bodies without a shape, which the
 * draw shows as points without their handle. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <lua.h>

#include "lrigid.h"
#include "lenc.h"
#include "lsample.h"

#define MAX_NAMES ((size_t)4 << 20)   /* bytes of names kept */
#define NAME_MAX  200

typedef struct lsample_spot {
    double x, y;
    int32_t col, pad;
} spot;

void lsample_init(lsample *s)
{
    memset(s, 0, sizeof *s);
    s->box[0] = s->box[1] = HUGE_VAL;
    s->box[2] = s->box[3] = -HUGE_VAL;
    s->hmin = HUGE_VAL;
}

void lsample_release(lsample *s)
{
    int i;
    free(s->tracks);
    free(s->keys);
    free(s->vals);
    free(s->names);
    free(s->cur);
    free(s->spots);
    for (i = 0; i < LSAMPLE_LISTS; i++) free(s->lists[i]);
    lsample_init(s);
}

const char *lsample_name(const lsample *s, int32_t track, size_t *len)
{
    const lsample_track *t = &s->tracks[track];
    *len = (size_t)t->name_len;
    return t->name_len > 0 ? s->names + t->name_off : NULL;
}

/* ---------------------------------------------------------------- tracks by handle */

static uint32_t hash(uint64_t h)
{
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    return (uint32_t)h;
}

static int32_t find(const lsample *s, rg_body body)
{
    uint32_t m, i;
    if (s->hcap == 0) return -1;
    m = (uint32_t)s->hcap - 1;
    for (i = hash(body) & m; s->keys[i] != 0; i = (i + 1) & m)
        if (s->keys[i] == body) return s->vals[i] - 1;
    return -1;
}

static void put(lsample *s, rg_body body, int32_t t)
{
    uint32_t m = (uint32_t)s->hcap - 1, i;
    for (i = hash(body) & m; s->keys[i] != 0; i = (i + 1) & m) {}
    s->keys[i] = body;
    s->vals[i] = t + 1;
}

/* The track of a body, made on first sight; -1 when out of memory. */
static int32_t track_of(lsample *s, const rg_world *w, rg_body body)
{
    int32_t t = find(s, body), i;
    lsample_track *tr;
    if (t >= 0) return t;
    if (s->ntracks >= LSAMPLE_MAX_TRACKS) {
        s->full = 1;
        return -1;
    }
    if (2 * (s->ntracks + 1) > s->hcap) {   /* rehash at half full */
        int32_t cap = s->hcap < 1024 ? 1024 : 2 * s->hcap;
        uint64_t *ok = s->keys;
        int32_t *ov = s->vals, oc = s->hcap;
        if (cap > (1 << 28)) return -1;
        s->keys = (uint64_t *)calloc((size_t)cap, sizeof *s->keys);
        s->vals = (int32_t *)calloc((size_t)cap, sizeof *s->vals);
        if (s->keys == NULL || s->vals == NULL) {
            free(s->keys);
            free(s->vals);
            s->keys = ok;
            s->vals = ov;
            return -1;
        }
        s->hcap = cap;
        for (i = 0; i < oc; i++)
            if (ok[i] != 0) put(s, ok[i], ov[i] - 1);
        free(ok);
        free(ov);
    }
    if (!lenc_grow((void **)&s->tracks, &s->tracks_room, s->ntracks + 1, sizeof *s->tracks)) return -1;
    t = s->ntracks++;
    tr = &s->tracks[t];
    memset(tr, 0, sizeof *tr);
    tr->body = body;
    tr->first = tr->last = -1;
    tr->col = -1;
    if (rg_body_get_type(w, body, &tr->type) != RG_OK) tr->type = RG_BODY_DYNAMIC;
    put(s, body, t);
    return t;
}

static void name_track(lsample *s, lsample_track *tr, const lrigid_body_info *info)
{
    size_t n = 0;
    /* Only what is kept is read: a script's name may be megabytes long, given to any number
     * of bodies, and strlen would read it whole for each, where no budget sees it. */
    while (info->name != NULL && n <= NAME_MAX && info->name[n] != '\0') n++;
    tr->named = 1;
    tr->serial = (long long)info->serial;
    tr->type = info->type;
    tr->sensor = info->sensor;
    if (n > NAME_MAX) n = NAME_MAX;
    if (n == 0 || s->names_len + n > MAX_NAMES) return;
    if (s->names_len + n > s->names_room) {
        size_t room = s->names_room < 4096 ? 4096 : s->names_room;
        char *p;
        while (room < s->names_len + n) room *= 2;
        if ((p = (char *)realloc(s->names, room)) == NULL) return;
        s->names = p;
        s->names_room = room;
    }
    memcpy(s->names + s->names_len, info->name, n);
    tr->name_off = (int32_t)s->names_len;
    tr->name_len = (int32_t)n;
    s->names_len += n;
}

static int32_t color_index(lsample *s, uint32_t rgba)
{
    int32_t i;
    for (i = s->ncolors - 1; i >= 0; i--)
        if (s->colors[i] == rgba) return i;
    if (s->ncolors == LSAMPLE_MAX_COLORS) return 0;
    s->colors[s->ncolors] = rgba;
    return s->ncolors++;
}

static void grow_box(lsample *s, double x0, double y0, double x1, double y1)
{
    if (x0 < s->box[0]) s->box[0] = x0;
    if (y0 < s->box[1]) s->box[1] = y0;
    if (x1 > s->box[2]) s->box[2] = x1;
    if (y1 > s->box[3]) s->box[3] = y1;
}

/* ---------------------------------------------------------------- the draw callbacks */

typedef struct pass {
    lsample *s;
    const rg_world *w;
    uint32_t layer;           /* RG_DRAW_* of this call */
} pass;

/* The body's sample in this frame; made in the shapes layer, looked up in the others. */
static lsample_body *body_sample(pass *p, rg_body body)
{
    lsample *s = p->s;
    int32_t t;
    lsample_track *tr;
    lsample_body *b;
    if (p->layer != RG_DRAW_SHAPES) {
        t = find(s, body);
        return t >= 0 && s->tracks[t].stamp == s->frames + 1 ? &s->cur[s->tracks[t].cur] : NULL;
    }
    if ((t = track_of(s, p->w, body)) < 0 ||
        !lenc_grow((void **)&s->cur, &s->cur_room, s->ncur + 1, sizeof *s->cur)) {
        s->oom = 1;
        return NULL;
    }
    tr = &s->tracks[t];
    if (tr->stamp == s->frames + 1) return &s->cur[tr->cur];
    tr->stamp = s->frames + 1;
    tr->cur = s->ncur;
    b = &s->cur[s->ncur++];
    memset(b, 0, sizeof *b);
    b->track = t;
    b->col = -1;
    return b;
}

static void on_shape(pass *p, rg_body body, double x0, double y0, double x1, double y1,
                     int32_t shape, uint32_t rgba)
{
    lsample *s = p->s;
    lsample_body *b = body_sample(p, body);
    int32_t col;
    if (b == NULL) return;
    col = color_index(s, rgba);
    if (p->layer == RG_DRAW_BOUNDS) {
        b->has_box = 1;
        b->box[0] = x0;
        b->box[1] = y0;
        b->box[2] = x1;
        b->box[3] = y1;
        s->seen[col] |= LSAMPLE_BOUNDS;
        s->any[LSAMPLE_LISTS] = 1;
        return;
    }
    b->x = (x0 + x1) / 2;
    b->y = (y0 + y1) / 2;
    b->hx = (x1 - x0) / 2;
    b->hy = (y1 - y0) / 2;
    b->col = col;
    s->tracks[b->track].shape = shape;
    if (s->frames == 0 && b->hx > 0 && b->hx < s->hmin) s->hmin = b->hx;
    if (s->frames == 0 && b->hy > 0 && b->hy < s->hmin) s->hmin = b->hy;
    grow_box(s, x0, y0, x1, y1);
}

static void prim(pass *p, int kind, double a, double b, double c, double d, uint32_t rgba)
{
    lsample *s = p->s;
    int l = p->layer == RG_DRAW_SPRINGS ? LSAMPLE_SPRINGS : LSAMPLE_CONTACTS;
    lsample_prim *q;
    if (p->layer != RG_DRAW_CONTACTS && p->layer != RG_DRAW_SPRINGS) return;
    if (!lenc_grow((void **)&s->lists[l], &s->rooms[l], s->counts[l] + 1, sizeof *s->lists[l])) {
        s->oom = 1;
        return;
    }
    q = &s->lists[l][s->counts[l]++];
    q->kind = kind;
    q->col = color_index(s, rgba);
    q->v[0] = a;
    q->v[1] = b;
    q->v[2] = c;
    q->v[3] = d;
    s->seen[q->col] |= l == LSAMPLE_SPRINGS ? LSAMPLE_SPRING : LSAMPLE_CONTACT;
    s->any[l] = 1;
}

static void cb_circle(rg_body body, rg_vec2 c, rg_real radius, uint32_t rgba, void *user)
{
    pass *p = (pass *)user;
    double x = (double)c.x, y = (double)c.y, rad = (double)radius;
    if (body == 0) prim(p, LSAMPLE_CIRCLE, x, y, rad, 0, rgba);
    else on_shape(p, body, x - rad, y - rad, x + rad, y + rad, RG_SHAPE_CIRCLE, rgba);
}

static void cb_box(rg_body body, rg_vec2 lo, rg_vec2 hi, uint32_t rgba, void *user)
{
    pass *p = (pass *)user;
    if (body == 0)
        prim(p, LSAMPLE_BOX, (double)lo.x, (double)lo.y, (double)hi.x, (double)hi.y, rgba);
    else
        on_shape(p, body, (double)lo.x, (double)lo.y, (double)hi.x, (double)hi.y, RG_SHAPE_AABB, rgba);
}

static void cb_segment(rg_vec2 a, rg_vec2 b, uint32_t rgba, void *user)
{
    prim((pass *)user, LSAMPLE_SEGMENT, (double)a.x, (double)a.y, (double)b.x, (double)b.y, rgba);
}

/* A point in the shapes layer is a body without a shape (its handle is not given): kept to
 * give that body, found through the binding, its colour. */
static void cb_point(rg_vec2 pt, uint32_t rgba, void *user)
{
    pass *p = (pass *)user;
    lsample *s = p->s;
    if (p->layer != RG_DRAW_SHAPES) {
        prim(p, LSAMPLE_POINT, (double)pt.x, (double)pt.y, 0, 0, rgba);
        return;
    }
    if (!lenc_grow((void **)&s->spots, &s->spots_room, s->nspots + 1, sizeof *s->spots)) {
        s->oom = 1;
        return;
    }
    s->spots[s->nspots].x = (double)pt.x;
    s->spots[s->nspots].y = (double)pt.y;
    s->spots[s->nspots++].col = color_index(s, rgba);
}

/* ---------------------------------------------------------------- bodies without a shape */

static int spot_cmp(const void *a, const void *b)
{
    const spot *x = (const spot *)a, *y = (const spot *)b;
    if (x->x != y->x) return x->x < y->x ? -1 : 1;
    return (x->y > y->y) - (x->y < y->y);
}

/* The colour index of the shapes layer's point at exactly (x, y), or -1.  Where several
 * bodies share the place, the one drawn in `want`: the palette's colour of the body's state
 * (the draw gives no handle to tell them apart). */
static int32_t spot_color(const lsample *s, double x, double y, uint32_t want)
{
    int32_t lo = 0, hi = s->nspots, i, first = -1;
    spot key;
    key.x = x;
    key.y = y;
    while (lo < hi) {   /* the first spot not below (x, y) */
        int32_t mid = (lo + hi) / 2;
        if (spot_cmp(&s->spots[mid], &key) < 0) lo = mid + 1;
        else hi = mid;
    }
    for (i = lo; i < s->nspots && spot_cmp(&s->spots[i], &key) == 0; i++) {
        if (first < 0) first = s->spots[i].col;
        if (s->colors[s->spots[i].col] == want) return s->spots[i].col;
    }
    return first;
}

static uint32_t state_color(const rg_world *w, const lsample_track *tr)
{
    int32_t sensor = 0, awake = 1;
    rg_body_is_sensor(w, tr->body, &sensor);
    rg_body_is_awake(w, tr->body, &awake);
    return sensor ? RG_COLOR_SENSOR : tr->type == RG_BODY_STATIC ? RG_COLOR_STATIC
           : tr->type == RG_BODY_KINEMATIC ? RG_COLOR_KINEMATIC : awake ? RG_COLOR_AWAKE
           : RG_COLOR_SLEEPING;
}

/* The binding's bodies: names for new tracks, and a sample for each body without a shape. */
static void bodies_from_lua(pass *p, lua_State *L, int world_idx)
{
    lsample *s = p->s;
    int tbl;
    if (s->nspots > 1) qsort(s->spots, (size_t)s->nspots, sizeof *s->spots, spot_cmp);
    lrigid_pushbodies(L, world_idx);
    tbl = lua_gettop(L);
    lua_pushnil(L);
    while (lua_next(L, tbl) != 0) {
        lrigid_body_info info;
        rg_vec2 pos;
        if (lrigid_tobody(L, -1, &info)) {
            int shapeless = info.shape == LRIGID_SHAPE_NONE &&
                            rg_body_get_position(p->w, info.handle, &pos) == RG_OK;
            int32_t t = shapeless ? track_of(s, p->w, info.handle) : find(s, info.handle);
            if (t < 0 && shapeless) s->oom = 1;
            if (t >= 0 && !s->tracks[t].named) name_track(s, &s->tracks[t], &info);
            if (t >= 0 && shapeless && s->tracks[t].stamp != s->frames + 1) {
                lsample_body *b;
                p->layer = RG_DRAW_SHAPES;
                if ((b = body_sample(p, info.handle)) != NULL) {
                    b->x = (double)pos.x;
                    b->y = (double)pos.y;
                    b->col = spot_color(s, b->x, b->y, state_color(p->w, &s->tracks[t]));
                    s->tracks[t].shape = RG_SHAPE_NONE;
                    grow_box(s, b->x, b->y, b->x, b->y);
                }
            }
        }
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
}

/* ---------------------------------------------------------------- a frame */

int lsample_frame(lsample *s, lua_State *L, int world_idx)
{
    static const uint32_t layers[4] = { RG_DRAW_SHAPES, RG_DRAW_BOUNDS, RG_DRAW_CONTACTS,
                                        RG_DRAW_SPRINGS };
    rg_world *w = lrigid_toworld(L, world_idx);
    rg_debug_draw d;
    pass p;
    int32_t i, unnamed = 0;
    if (w == NULL) return -1;
    world_idx = lua_absindex(L, world_idx);
    p.s = s;
    p.w = w;
    s->ncur = s->nspots = 0;
    s->counts[0] = s->counts[1] = 0;
    memset(&d, 0, sizeof d);
    d.circle = cb_circle;
    d.box = cb_box;
    d.segment = cb_segment;
    d.point = cb_point;
    d.user = &p;
    for (i = 0; i < 4; i++) {
        p.layer = d.flags = layers[i];
        if (rg_world_draw(w, &d) != RG_OK) return -1;
    }
    for (i = 0; i < s->ncur; i++) unnamed |= !s->tracks[s->cur[i].track].named;
    if (unnamed || rg_world_body_count(w) > s->ncur) bodies_from_lua(&p, L, world_idx);
    if (s->oom) return -1;
    /* Velocities, and what each colour was drawn on. */
    for (i = 0; i < s->ncur; i++) {
        lsample_body *b = &s->cur[i];
        lsample_track *tr = &s->tracks[b->track];
        rg_vec2 v = { 0, 0 };
        rg_body_get_velocity(w, tr->body, &v);
        b->vx = (double)v.x;
        b->vy = (double)v.y;
        if (b->col >= 0 && b->col != tr->col) {
            int32_t awake = 1, sensor = 0;
            rg_body_is_awake(w, tr->body, &awake);
            rg_body_is_sensor(w, tr->body, &sensor);
            s->seen[b->col] |= sensor ? LSAMPLE_SENSOR : tr->type == RG_BODY_STATIC ? LSAMPLE_STATIC
                               : tr->type == RG_BODY_KINEMATIC ? LSAMPLE_KINEMATIC
                               : awake ? LSAMPLE_AWAKE : LSAMPLE_ASLEEP;
        }
        tr->col = b->col;
        if (tr->first < 0) tr->first = s->frames;
        tr->last = s->frames;
    }
    s->frames++;
    return 0;
}
