/* lsvg.c: a scene recorder and its SVG picture: shapes, trails with one-second dots,
 * contact points, velocity arrows, a metre grid and a legend. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lua.h>

#include "lrigid.h"
#include "lsvg.h"

#define MAX_TRAILS    1024   /* bodies (by creation order) that keep a trail */
#define MAX_POINTS    512    /* points per trail; past it the trail is thinned by half */
#define MAX_TRACKS    65536  /* bodies drawn at all */
#define MAX_CONTACTS  4096
#define MAX_NAMES     32
#define NAME_LEN      40

#define PLOT_W        960.0
#define PLOT_H_MAX    620.0
#define LEFT          64.0
#define RIGHT         28.0
#define TOP           70.0
#define BOTTOM        44.0

typedef struct point {
    float x, y, t;
} point;

typedef struct track {
    lua_Integer serial;
    int type, shape, sensor, alive, color, has_trail;
    double size[2];
    double x, y, vx, vy;         /* last seen */
    char name[NAME_LEN + 1];
    point *pts;
    int n, stride, skip;
    unsigned long last_frame;
} track;

/* A thinned, bounded sample of a growing sequence of points. */
typedef struct sample {
    point *pts;
    int n, cap, stride, skip;
} sample;

struct lsvg {
    track *tracks;
    size_t ntracks, cap;
    size_t *by_serial;           /* serial -> track index + 1 */
    size_t serial_cap;
    sample contacts;
    int contact_total;
    unsigned long frame;
    double t_end;
};

static const char *const palette[] = { "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                       "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f" };
#define NPALETTE ((int)(sizeof palette / sizeof palette[0]))

lsvg *lsvg_new(void)
{
    return (lsvg *)calloc(1, sizeof(lsvg));
}

void lsvg_free(lsvg *r)
{
    size_t i;
    if (r == NULL) return;
    for (i = 0; i < r->ntracks; i++) free(r->tracks[i].pts);
    free(r->tracks);
    free(r->by_serial);
    free(r->contacts.pts);
    free(r);
}

/* Appends p, keeping every stride-th point; when full, drops every other point. */
static void sample_add(sample *s, point p, int cap)
{
    if (s->pts == NULL) {
        s->pts = (point *)malloc((size_t)cap * sizeof *s->pts);
        if (s->pts == NULL) return;
        s->cap = cap;
        s->stride = 1;
    }
    if (s->skip > 0) {
        s->skip--;
        return;
    }
    if (s->n == s->cap) {
        int i;
        for (i = 0; i < s->cap / 2; i++) s->pts[i] = s->pts[2 * i];
        s->n = s->cap / 2;
        s->stride *= 2;
    }
    s->pts[s->n++] = p;
    s->skip = s->stride - 1;
}

static void copy_name(char *dst, const char *src)
{
    size_t i;
    for (i = 0; src != NULL && src[i] != '\0' && i < NAME_LEN; i++)
        dst[i] = (src[i] >= 32 && src[i] < 127) ? src[i] : '?';
    dst[i] = '\0';
}

/* Colours in creation order: bodies that share a name share a colour (all the coins). */
typedef struct colours {
    const char *names[MAX_NAMES];
    int colour[MAX_NAMES];
    int nnames, next;
} colours;

static int colour_for(colours *c, const char *name)
{
    int i;
    if (name[0] != '\0') {
        for (i = 0; i < c->nnames; i++)
            if (strcmp(c->names[i], name) == 0) return c->colour[i];
        if (c->nnames < MAX_NAMES) {
            c->names[c->nnames] = name;
            c->colour[c->nnames++] = c->next % NPALETTE;
        }
    }
    return c->next++ % NPALETTE;
}

static int by_serial(const void *x, const void *y)
{
    const track *a = *(const track *const *)x, *b = *(const track *const *)y;
    return (a->serial > b->serial) - (a->serial < b->serial);
}

static track *get_track(lsvg *r, const lrigid_body_info *info)
{
    size_t s = (size_t)info->serial, idx;
    track *t;
    if (s >= r->serial_cap) {
        size_t cap = r->serial_cap < 64 ? 64 : r->serial_cap;
        size_t *m;
        while (cap <= s) cap *= 2;
        m = (size_t *)realloc(r->by_serial, cap * sizeof *m);
        if (m == NULL) return NULL;
        memset(m + r->serial_cap, 0, (cap - r->serial_cap) * sizeof *m);
        r->by_serial = m;
        r->serial_cap = cap;
    }
    if (r->by_serial[s] != 0) return &r->tracks[r->by_serial[s] - 1];
    if (r->ntracks >= MAX_TRACKS) return NULL;
    if (r->ntracks == r->cap) {
        size_t cap = r->cap < 16 ? 16 : r->cap * 2;
        track *tr = (track *)realloc(r->tracks, cap * sizeof *tr);
        if (tr == NULL) return NULL;
        r->tracks = tr;
        r->cap = cap;
    }
    idx = r->ntracks++;
    t = &r->tracks[idx];
    memset(t, 0, sizeof *t);
    t->serial = info->serial;
    t->type = info->type;
    copy_name(t->name, info->name);
    t->has_trail = info->type != RG_BODY_STATIC && info->serial <= MAX_TRAILS;
    r->by_serial[s] = idx + 1;
    return t;
}

void lsvg_record(lsvg *r, lua_State *L, int world_idx, double t)
{
    rg_world *w = lrigid_toworld(L, world_idx);
    size_t i;
    int tbl;
    if (r == NULL || w == NULL) return;
    world_idx = lua_absindex(L, world_idx);
    r->frame++;
    r->t_end = t;
    lrigid_pushbodies(L, world_idx);
    tbl = lua_gettop(L);
    lua_pushnil(L);
    while (lua_next(L, tbl) != 0) {
        lrigid_body_info info;
        rg_vec2 p, v;
        if (lrigid_tobody(L, -1, &info) && info.serial > 0 &&
            rg_body_get_position(w, info.handle, &p) == RG_OK &&
            rg_body_get_velocity(w, info.handle, &v) == RG_OK) {
            track *tr = get_track(r, &info);
            if (tr != NULL) {
                tr->shape = info.shape;
                tr->size[0] = info.size[0];
                tr->size[1] = info.size[1];
                tr->sensor = info.sensor;
                tr->x = (double)p.x;
                tr->y = (double)p.y;
                tr->vx = (double)v.x;
                tr->vy = (double)v.y;
                tr->alive = 1;
                tr->last_frame = r->frame;
                if (tr->has_trail) {
                    sample s = { tr->pts, tr->n, MAX_POINTS, tr->stride, tr->skip };
                    point pt = { (float)p.x, (float)p.y, (float)t };
                    sample_add(&s, pt, MAX_POINTS);
                    tr->pts = s.pts;
                    tr->n = s.n;
                    tr->stride = s.stride;
                    tr->skip = s.skip;
                }
            }
        }
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    for (i = 0; i < r->ntracks; i++)
        if (r->tracks[i].last_frame != r->frame) r->tracks[i].alive = 0;
}

void lsvg_contact(lsvg *r, double x, double y)
{
    point p = { (float)x, (float)y, 0 };
    if (r == NULL) return;
    r->contact_total++;
    sample_add(&r->contacts, p, MAX_CONTACTS);
}

int lsvg_contact_count(const lsvg *r)
{
    return r != NULL ? r->contact_total : 0;
}

/* ---------------------------------------------------------------- drawing */

typedef struct view {
    double minx, maxy, s;        /* world window and pixels per metre */
} view;

static double vx_(const view *v, double x)
{
    return LEFT + (x - v->minx) * v->s;
}

static double vy_(const view *v, double y)
{
    return TOP + (v->maxy - y) * v->s;
}

static void grow(double *lo, double *hi, double a, double b)
{
    if (a < *lo) *lo = a;
    if (b > *hi) *hi = b;
}

static void extent(const track *t, double *hx, double *hy)
{
    *hx = *hy = 0;
    if (t->shape == LRIGID_SHAPE_CIRCLE) *hx = *hy = t->size[0];
    if (t->shape == LRIGID_SHAPE_AABB) {
        *hx = t->size[0];
        *hy = t->size[1];
    }
}

static double nice_step(double span)
{
    double raw = span / 10, p = pow(10, floor(log10(raw))), m = raw / p;
    return p * (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10);
}

static void put_text(FILE *f, const char *s)
{
    for (; *s != '\0'; s++) {
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fputc((unsigned char)*s >= 32 ? *s : '?', f);
        }
    }
}

static void draw_shape(FILE *f, const view *v, const track *t, double x, double y,
                       const char *fill, const char *stroke, const char *extra)
{
    double px = vx_(v, x), py = vy_(v, y);
    if (t->shape == LRIGID_SHAPE_AABB) {
        double w = fmax(2 * t->size[0] * v->s, 1.5), h = fmax(2 * t->size[1] * v->s, 1.5);
        fprintf(f, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"%s\" "
                   "stroke=\"%s\" %s/>\n", px - w / 2, py - h / 2, w, h, fill, stroke, extra);
    } else {
        double rad = t->shape == LRIGID_SHAPE_CIRCLE ? fmax(t->size[0] * v->s, 1.5) : 4.5;
        fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"%s\" stroke=\"%s\" %s/>\n",
                px, py, rad, fill, stroke, extra);
    }
}

int lsvg_write(const lsvg *r, const char *path, const char *title, const char *subtitle)
{
    double minx = HUGE_VAL, maxx = -HUGE_VAL, miny = HUGE_VAL, maxy = -HUGE_VAL;
    double wm, hm, pad, step, gx, gy, width, height, plot_w, plot_h;
    size_t i;
    int k, labels = 0, nlegend = 0;
    const char *legend_name[MAX_NAMES];
    int legend_color[MAX_NAMES];
    view v;
    FILE *f;
    track **T;
    colours pal;

    T = (track **)malloc((r->ntracks > 0 ? r->ntracks : 1) * sizeof *T);
    if (T == NULL) return -1;
    for (i = 0; i < r->ntracks; i++) T[i] = &r->tracks[i];
    qsort(T, r->ntracks, sizeof *T, by_serial);
    memset(&pal, 0, sizeof pal);
    for (i = 0; i < r->ntracks; i++)   /* static bodies are grey: they take no colour */
        T[i]->color = T[i]->type == RG_BODY_STATIC ? NPALETTE - 1 : colour_for(&pal, T[i]->name);

    for (i = 0; i < r->ntracks; i++) {
        const track *t = T[i];
        double hx, hy;
        extent(t, &hx, &hy);
        grow(&minx, &maxx, t->x - hx, t->x + hx);
        grow(&miny, &maxy, t->y - hy, t->y + hy);
        for (k = 0; k < t->n; k++) {
            grow(&minx, &maxx, (double)t->pts[k].x - hx, (double)t->pts[k].x + hx);
            grow(&miny, &maxy, (double)t->pts[k].y - hy, (double)t->pts[k].y + hy);
        }
    }
    for (k = 0; k < r->contacts.n; k++) {
        grow(&minx, &maxx, (double)r->contacts.pts[k].x, (double)r->contacts.pts[k].x);
        grow(&miny, &maxy, (double)r->contacts.pts[k].y, (double)r->contacts.pts[k].y);
    }
    if (!(minx <= maxx)) {
        minx = miny = -1;
        maxx = maxy = 1;
    }
    wm = maxx - minx;
    hm = maxy - miny;
    if (wm < 1) {
        minx -= (1 - wm) / 2;
        wm = 1;
    }
    if (hm < 1) {
        miny -= (1 - hm) / 2;
        hm = 1;
    }
    pad = 0.04 * fmax(wm, hm);
    minx -= pad;
    miny -= pad;
    wm += 2 * pad;
    hm += 2 * pad;
    maxy = miny + hm;
    v.minx = minx;
    v.maxy = maxy;
    v.s = fmin(PLOT_W / wm, PLOT_H_MAX / hm);
    if (wm * v.s < 640) {                 /* a tall scene: widen the window around it */
        double extra = 640 / v.s - wm;
        minx -= extra / 2;
        wm += extra;
        v.minx = minx;
    }
    plot_w = wm * v.s;
    plot_h = hm * v.s;
    width = LEFT + plot_w + RIGHT;
    height = TOP + plot_h + BOTTOM + 30;

    f = fopen(path, "w");
    if (f == NULL) {
        free(T);
        return -1;
    }
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
               "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
               "viewBox=\"0 0 %.0f %.0f\" font-family=\"Helvetica, Arial, sans-serif\">\n",
            width, height, width, height);
    fputs("<defs><marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" "
          "markerWidth=\"6\" markerHeight=\"6\" orient=\"auto-start-reverse\">"
          "<path d=\"M0,0 L10,5 L0,10 z\" fill=\"#333\"/></marker></defs>\n", f);
    fprintf(f, "<clipPath id=\"plot\"><rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" "
               "height=\"%.2f\"/></clipPath>\n", LEFT, TOP, plot_w, plot_h);
    fprintf(f, "<rect width=\"%.0f\" height=\"%.0f\" fill=\"#ffffff\"/>\n", width, height);
    fprintf(f, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"#f7f7f4\" "
               "stroke=\"#c8c8c0\"/>\n", LEFT, TOP, plot_w, plot_h);
    fputs("<text x=\"16\" y=\"28\" font-size=\"18\" font-weight=\"bold\" fill=\"#222\">", f);
    put_text(f, title);
    fputs("</text>\n<text x=\"16\" y=\"50\" font-size=\"13\" fill=\"#555\">", f);
    put_text(f, subtitle);
    fputs("</text>\n", f);

    /* Metre grid with labels. */
    step = nice_step(fmax(wm, hm));
    fputs("<g stroke=\"#e2e2dc\" stroke-width=\"1\">\n", f);
    for (gx = ceil(minx / step) * step; gx <= minx + wm; gx += step)
        fprintf(f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"%s/>\n", vx_(&v, gx),
                TOP, vx_(&v, gx), TOP + plot_h, fabs(gx) < step / 2 ? " stroke=\"#b0b0a8\"" : "");
    for (gy = ceil(miny / step) * step; gy <= maxy; gy += step)
        fprintf(f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"%s/>\n", LEFT,
                vy_(&v, gy), LEFT + plot_w, vy_(&v, gy),
                fabs(gy) < step / 2 ? " stroke=\"#b0b0a8\"" : "");
    fputs("</g>\n<g font-size=\"11\" fill=\"#777\">\n", f);
    for (gx = ceil(minx / step) * step; gx <= minx + wm; gx += step)
        fprintf(f, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\">%g</text>\n", vx_(&v, gx),
                TOP + plot_h + 15, fabs(gx) < step / 2 ? 0.0 : gx);
    for (gy = ceil(miny / step) * step; gy <= maxy; gy += step)
        fprintf(f, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"end\">%g</text>\n", LEFT - 6,
                vy_(&v, gy) + 4, fabs(gy) < step / 2 ? 0.0 : gy);
    fprintf(f, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"end\">m</text>\n</g>\n",
            LEFT + plot_w, TOP + plot_h + 30);

    fputs("<g clip-path=\"url(#plot)\">\n", f);
    /* Trails, with a dot at each whole second and a ring where they start. */
    for (i = 0; i < r->ntracks; i++) {
        const track *t = T[i];
        double next_tick;
        if (t->n < 2) continue;
        fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"1.6\" "
                   "stroke-opacity=\"0.55\" points=\"", palette[t->color]);
        for (k = 0; k < t->n; k++)
            fprintf(f, "%.2f,%.2f ", vx_(&v, (double)t->pts[k].x), vy_(&v, (double)t->pts[k].y));
        if (t->alive) fprintf(f, "%.2f,%.2f", vx_(&v, t->x), vy_(&v, t->y));
        fputs("\"/>\n", f);
        fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"3\" fill=\"#fff\" stroke=\"%s\"/>\n",
                vx_(&v, (double)t->pts[0].x), vy_(&v, (double)t->pts[0].y), palette[t->color]);
        next_tick = ceil((double)t->pts[0].t);
        if (next_tick <= 0) next_tick = 1;
        fprintf(f, "<g fill=\"%s\" stroke=\"#fff\" stroke-width=\"0.6\">", palette[t->color]);
        for (k = 0; k < t->n; k++) {
            if ((double)t->pts[k].t + 1e-6 >= next_tick) {
                fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"2.6\"/>", vx_(&v, (double)t->pts[k].x),
                        vy_(&v, (double)t->pts[k].y));
                next_tick = floor((double)t->pts[k].t + 1e-6) + 1;
            }
        }
        fputs("</g>\n", f);
    }

    /* Bodies where they ended: static grey, sensors and destroyed ones dashed. */
    for (i = 0; i < r->ntracks; i++) {
        const track *t = T[i];
        const char *col = t->sensor ? "#c99700" : palette[t->color];   /* sensors: gold */
        if (!t->alive)
            draw_shape(f, &v, t, t->x, t->y, "none", col,
                       "stroke-dasharray=\"3 2\" stroke-opacity=\"0.5\"");
        else if (t->type == RG_BODY_STATIC && t->sensor)
            draw_shape(f, &v, t, t->x, t->y, "#ffe08a", col,
                       "fill-opacity=\"0.6\" stroke-width=\"1.2\" stroke-dasharray=\"4 3\"");
        else if (t->type == RG_BODY_STATIC)
            draw_shape(f, &v, t, t->x, t->y, "#a7aab0", "#5f6368", "");
        else if (t->sensor)
            draw_shape(f, &v, t, t->x, t->y, "none", col, "stroke-width=\"1.5\" stroke-dasharray=\"4 3\"");
        else
            draw_shape(f, &v, t, t->x, t->y, col, "#222", "fill-opacity=\"0.85\" stroke-width=\"0.8\"");
    }

    /* Velocity at the end (a quarter second of motion), when the scene is not crowded. */
    if (r->ntracks <= 40) {
        for (i = 0; i < r->ntracks; i++) {
            const track *t = T[i];
            double len = hypot(t->vx, t->vy) * 0.25 * v.s;
            if (!t->alive || t->type != RG_BODY_DYNAMIC || len < 6) continue;
            if (len > 90) len = 90;
            {
                double sp = hypot(t->vx, t->vy), ux = t->vx / sp, uy = t->vy / sp;
                fprintf(f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#333\" "
                           "stroke-width=\"1.2\" marker-end=\"url(#arrow)\"/>\n",
                        vx_(&v, t->x), vy_(&v, t->y), vx_(&v, t->x) + ux * len,
                        vy_(&v, t->y) - uy * len);
            }
        }
    }

    /* Contact points. */
    fputs("<g fill=\"#d93025\" fill-opacity=\"0.65\">", f);
    for (k = 0; k < r->contacts.n; k++)
        fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"2.6\"/>", vx_(&v, (double)r->contacts.pts[k].x),
                vy_(&v, (double)r->contacts.pts[k].y));
    fputs("</g>\n</g>\n", f);

    /* One label per name, next to its first living body. */
    for (i = 0; i < r->ntracks && labels < 24; i++) {
        const track *t = T[i];
        double hx, hy;
        int seen = 0, j;
        if (t->name[0] == '\0') continue;
        for (j = 0; j < nlegend; j++)
            if (strcmp(legend_name[j], t->name) == 0) seen = 1;
        if (seen) continue;
        if (nlegend < MAX_NAMES) {
            legend_name[nlegend] = t->name;
            legend_color[nlegend] = t->sensor ? -2 : t->type == RG_BODY_STATIC ? -1 : t->color;
            nlegend++;
        }
        extent(t, &hx, &hy);
        if (t->type == RG_BODY_STATIC && hx > 0)   /* under its left end: statics are wide */
            fprintf(f, "<text x=\"%.2f\" y=\"%.2f\" font-size=\"12\" fill=\"#555\">",
                    vx_(&v, t->x - hx), vy_(&v, t->y - hy) + 13);
        else
            fprintf(f, "<text x=\"%.2f\" y=\"%.2f\" font-size=\"12\" fill=\"#222\">",
                    vx_(&v, t->x + hx) + 4, vy_(&v, t->y + hy) - 4);
        put_text(f, t->name);
        fputs("</text>\n", f);
        labels++;
    }

    /* Legend line under the plot. */
    {
        double x = LEFT, y = TOP + plot_h + 36;
        fprintf(f, "<g font-size=\"12\" fill=\"#444\">\n");
        for (k = 0; k < nlegend && x < width - 160; k++) {
            fprintf(f, "<rect x=\"%.1f\" y=\"%.1f\" width=\"10\" height=\"10\" fill=\"%s\"/>", x,
                    y - 9, legend_color[k] == -2 ? "#e0b000" : legend_color[k] < 0 ? "#a7aab0"
                                                                 : palette[legend_color[k]]);
            fprintf(f, "<text x=\"%.1f\" y=\"%.1f\">", x + 14, y);
            put_text(f, legend_name[k]);
            fputs("</text>\n", f);
            x += 24 + 7.0 * (double)strlen(legend_name[k]);
        }
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" fill=\"#777\">paths start at a ring, a dot every "
                   "second; arrows: velocity at the end; red: contact points; gold: sensors; "
                   "dashed: sensor or destroyed</text>\n</g>\n", LEFT, y + 18);
    }
    fputs("</svg>\n", f);
    free(T);
    return fclose(f) == 0 ? 0 : -1;
}
