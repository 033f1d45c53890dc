/* lsvg.c: the SVG picture of a run.  Everything drawn for the moment shown (the last frame)
 * comes from that frame's sample (lsample.c, on rg_world_draw): shapes in their state's
 * colour, the contacts touching then, springs, velocities.  Paths are what led there: drawn
 * under the shapes, fainter when many.  Labels go where they cover nothing, with a leader
 * line when away from their body; the legend wraps to the picture's width and names every
 * kind of mark the picture holds. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lenc.h"
#include "lsample.h"
#include "lsvg.h"

#define MAX_TRAILS  1024   /* tracks (in order of first drawing) that keep a path */
#define MAX_POINTS  512    /* points per path; past it the path is thinned by half */
#define MAX_LABELS  24
#define CROWD       16     /* more paths than this are drawn faint, without second dots */
#define ARROW_S     0.25   /* a velocity arrow is this many seconds of motion */

#define PLOT_W      960.0
#define PLOT_H_MAX  620.0
#define LEFT        64.0
#define RIGHT       28.0
#define TOP         70.0
#define CHAR_W      6.5    /* a mean 12 px Helvetica advance, for wrapping lines */

typedef struct point {
    float x, y, t;
} point;

/* A thinned, bounded sample of a growing sequence of points. */
typedef struct trail {
    point *pts;
    int n, stride, skip;
} trail;

struct lsvg {
    lsample smp;
    trail *trails;            /* by track, for the first MAX_TRAILS */
    int32_t trails_room;
    lsample_body *lasts;      /* by track: as last drawn */
    int32_t lasts_room;
    double t_end;
    int failed;
};

static const char *const palette[] = { "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                       "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f" };
#define NPALETTE ((int)(sizeof palette / sizeof palette[0]))

lsvg *lsvg_new(void)
{
    lsvg *r = (lsvg *)calloc(1, sizeof *r);
    if (r != NULL) lsample_init(&r->smp);
    return r;
}

void lsvg_free(lsvg *r)
{
    int32_t i;
    if (r == NULL) return;
    for (i = 0; i < r->trails_room; i++) free(r->trails[i].pts);
    free(r->trails);
    free(r->lasts);
    lsample_release(&r->smp);
    free(r);
}

/* Appends p, keeping every stride-th point; when full, drops every other point. */
static void trail_add(trail *s, point p)
{
    if (s->pts == NULL) {
        if ((s->pts = (point *)malloc(MAX_POINTS * sizeof *s->pts)) == NULL) return;
        s->stride = 1;
    }
    if (s->skip > 0) {
        s->skip--;
        return;
    }
    if (s->n == MAX_POINTS) {
        int i;
        for (i = 0; i < MAX_POINTS / 2; i++) s->pts[i] = s->pts[2 * i];
        s->n = MAX_POINTS / 2;
        s->stride *= 2;
    }
    s->pts[s->n++] = p;
    s->skip = s->stride - 1;
}

void lsvg_record(lsvg *r, lua_State *L, int world_idx, double t)
{
    lsample *s;
    int32_t i;
    if (r == NULL || r->failed) return;
    s = &r->smp;
    if (lsample_frame(s, L, world_idx) != 0 ||
        !lenc_grow((void **)&r->lasts, &r->lasts_room, s->ntracks, sizeof *r->lasts) ||
        !lenc_grow((void **)&r->trails, &r->trails_room, s->ntracks < MAX_TRAILS ? s->ntracks : MAX_TRAILS,
              sizeof *r->trails)) {
        r->failed = 1;
        return;
    }
    r->t_end = t;
    for (i = 0; i < s->ncur; i++) {
        const lsample_body *b = &s->cur[i];
        r->lasts[b->track] = *b;
        if (b->track < MAX_TRAILS && s->tracks[b->track].type != RG_BODY_STATIC) {
            point p;
            p.x = (float)b->x;
            p.y = (float)b->y;
            p.t = (float)t;
            trail_add(&r->trails[b->track], p);
        }
    }
}

/* ---------------------------------------------------------------- layout */

typedef struct view {
    double minx, maxy, s;        /* world window and pixels per metre */
    double w, h;                 /* plot size, px */
    double top;                  /* the plot's top edge, below the title and subtitle lines */
} view;

static double sx(const view *v, double x) { return LEFT + (x - v->minx) * v->s; }
static double sy(const view *v, double y) { return v->top + (v->maxy - y) * v->s; }

static void put_text(FILE *f, const char *s, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        switch (s[i]) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fputc((unsigned char)s[i] >= 32 && (unsigned char)s[i] < 127 ? s[i] : '?', f);
        }
    }
}

static void css(char out[32], uint32_t rgba, double dark)
{
    snprintf(out, 32, "rgba(%d,%d,%d,%.3f)", (int)(((rgba >> 24) & 255) * dark),
             (int)(((rgba >> 16) & 255) * dark), (int)(((rgba >> 8) & 255) * dark),
             (double)(rgba & 255) / 255);
}

/* Advances of Helvetica (and Arial, Liberation Sans) for ' ' to '~', in 1/1000 em (the font's
 * AFM metrics); other bytes count as wide letters. */
static const short helvetica[95] = {
    278, 278, 355, 556, 556, 889, 667, 191, 333, 333, 389, 584, 278, 333, 278, 278,
    556, 556, 556, 556, 556, 556, 556, 556, 556, 556, 278, 278, 584, 584, 584, 556,
    1015, 667, 667, 722, 722, 667, 611, 778, 722, 278, 500, 667, 556, 833, 722, 778,
    667, 778, 722, 667, 611, 722, 667, 944, 667, 667, 611, 278, 278, 278, 469, 556,
    333, 556, 556, 500, 556, 556, 278, 556, 556, 222, 222, 500, 222, 833, 556, 556,
    556, 556, 333, 500, 278, 556, 500, 722, 500, 500, 500, 334, 260, 334, 584,
};

/* The width of text at 12 px. */
static double text_width(const char *t, size_t n)
{
    double w = 0;
    size_t i;
    for (i = 0; i < n; i++) {
        unsigned char c = (unsigned char)t[i];
        w += c >= 32 && c < 127 ? helvetica[c - 32] : 667;
    }
    return w * 12 / 1000;
}

/* The colour a track's path takes: one per name (all the coins share one), else its own. */
static int path_color(const lsample *s, int32_t t, const char **names, size_t *lens, int *nnames)
{
    size_t len;
    const char *name = lsample_name(s, t, &len);
    int i;
    if (name == NULL) return (int)(t % NPALETTE);
    for (i = 0; i < *nnames; i++)
        if (lens[i] == len && memcmp(names[i], name, len) == 0) return i % NPALETTE;
    if (*nnames < MAX_LABELS * 4) {
        names[*nnames] = name;
        lens[(*nnames)++] = len;
    }
    return (*nnames - 1) % NPALETTE;
}

static double nice_step(double span)
{
    double raw = span / 10, p = pow(10, floor(log10(raw))), m = raw / p;
    return p * (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10);
}

/* The world window: the bodies at the end, where destroyed ones were last, and the paths. */
static view fit(const lsvg *r)
{
    const lsample *s = &r->smp;
    double b[4] = { HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL }, wm, hm, pad;
    int32_t t;
    int k;
    view v;
    for (t = 0; t < s->ntracks; t++) {
        const lsample_body *l = &r->lasts[t];
        if (s->tracks[t].first < 0) continue;
        b[0] = fmin(b[0], l->x - l->hx);
        b[1] = fmin(b[1], l->y - l->hy);
        b[2] = fmax(b[2], l->x + l->hx);
        b[3] = fmax(b[3], l->y + l->hy);
        if (t < r->trails_room)
            for (k = 0; k < r->trails[t].n; k++) {
                const point *p = &r->trails[t].pts[k];
                b[0] = fmin(b[0], (double)p->x - l->hx);
                b[1] = fmin(b[1], (double)p->y - l->hy);
                b[2] = fmax(b[2], (double)p->x + l->hx);
                b[3] = fmax(b[3], (double)p->y + l->hy);
            }
    }
    if (!(b[0] <= b[2])) b[0] = b[1] = -1, b[2] = b[3] = 1;
    wm = fmax(b[2] - b[0], 1);
    hm = fmax(b[3] - b[1], 1);
    b[0] = (b[0] + b[2]) / 2 - wm / 2;
    b[1] = (b[1] + b[3]) / 2 - hm / 2;
    pad = 0.04 * fmax(wm, hm);
    wm += 2 * pad;
    hm += 2 * pad;
    v.minx = b[0] - pad;
    v.maxy = b[1] - pad + hm;
    v.s = fmin(PLOT_W / wm, PLOT_H_MAX / hm);
    if (wm * v.s < 640) {        /* a tall scene: widen the window around it */
        v.minx -= (640 / v.s - wm) / 2;
        wm = 640 / v.s;
    }
    v.w = wm * v.s;
    v.h = hm * v.s;
    v.top = TOP;
    return v;
}

/* A legend as lines of items; each item is a mark (markup at its origin) and a text, with an
 * estimated width. */
typedef struct legend {
    char items[64][400];
    double width[64];
    int n;
} legend;

static void item(legend *g, const char *mark, const char *text, size_t n)
{
    char *o;
    size_t i, k;
    if (g->n == 64) return;
    o = g->items[g->n];
    k = (size_t)snprintf(o, sizeof g->items[0], "%s<text x=\"14\">", mark);
    for (i = 0; i < n && k + 8 < sizeof g->items[0] - 8; i++) {
        const char *e = text[i] == '&' ? "&amp;" : text[i] == '<' ? "&lt;" : text[i] == '>' ? "&gt;" : NULL;
        if (e != NULL) k += (size_t)snprintf(o + k, 8, "%s", e);
        else o[k++] = (unsigned char)text[i] >= 32 && (unsigned char)text[i] < 127 ? text[i] : '?';
    }
    snprintf(o + k, sizeof g->items[0] - k, "</text>");
    g->width[g->n++] = text_width(text, n) + 34;
}

/* Lines the legend takes at width w. */
static int legend_lines(const legend *g, double w)
{
    double x = 0;
    int i, lines = g->n > 0;
    for (i = 0; i < g->n; i++) {
        if (x > 0 && x + g->width[i] > w) {
            lines++;
            x = 0;
        }
        x += g->width[i];
    }
    return lines;
}

static void legend_write(FILE *f, const legend *g, double x0, double y, double w)
{
    double x = 0;
    int i;
    fputs("<g font-size=\"12\" fill=\"#444\">\n", f);
    for (i = 0; i < g->n; i++) {
        if (x > 0 && x + g->width[i] > w) {
            y += 18;
            x = 0;
        }
        fprintf(f, "<g transform=\"translate(%.1f,%.1f)\">%s</g>\n", x0 + x, y, g->items[i]);
        x += g->width[i];
    }
    fputs("</g>\n", f);
}

/* ---------------------------------------------------------------- labels */

typedef struct rect {
    double x0, y0, x1, y1;
} rect;

static int overlaps(const rect *a, const rect *b)
{
    return a->x0 < b->x1 && b->x0 < a->x1 && a->y0 < b->y1 && b->y0 < a->y1;
}

static rect body_rect(const view *v, const lsample_body *b)
{
    rect q;
    double hx = fmax(b->hx * v->s, 2), hy = fmax(b->hy * v->s, 2);
    q.x0 = sx(v, b->x) - hx;
    q.x1 = sx(v, b->x) + hx;
    q.y0 = sy(v, b->y) - hy;
    q.y1 = sy(v, b->y) + hy;
    return q;
}

/* A place for a label of width tw beside body rect br that covers no body and no label and
 * stays in the plot; 0 when there is none.  *lx, *ly: the text's baseline start. */
static int place(const view *v, rect br, double tw, const rect *obst, int32_t nobst,
                 const rect *labels, int nlabels, double *lx, double *ly)
{
    static const double dist[4] = { 3, 14, 32, 60 };
    double cx = (br.x0 + br.x1) / 2, cy = (br.y0 + br.y1) / 2;
    int d, c;
    int32_t i;
    for (d = 0; d < 4; d++) {
        double e = dist[d];
        double cand[8][2] = { { br.x1 + e, cy + 4 }, { br.x0 - e - tw, cy + 4 },
                              { cx - tw / 2, br.y0 - e }, { cx - tw / 2, br.y1 + e + 10 },
                              { br.x1 + e, br.y0 - e }, { br.x1 + e, br.y1 + e + 10 },
                              { br.x0 - e - tw, br.y0 - e }, { br.x0 - e - tw, br.y1 + e + 10 } };
        for (c = 0; c < 8; c++) {
            rect q;
            int free_ = 1;
            q.x0 = cand[c][0] - 1;
            q.x1 = cand[c][0] + tw + 1;
            q.y0 = cand[c][1] - 11;
            q.y1 = cand[c][1] + 3;
            if (q.x0 < LEFT || q.y0 < v->top || q.x1 > LEFT + v->w || q.y1 > v->top + v->h) continue;
            for (i = 0; i < nobst && free_; i++) free_ = !overlaps(&q, &obst[i]);
            for (i = 0; i < nlabels && free_; i++) free_ = !overlaps(&q, &labels[i]);
            if (free_) {
                *lx = cand[c][0];
                *ly = cand[c][1];
                return 1;
            }
        }
    }
    return 0;
}

static void draw_labels(FILE *f, const lsvg *r, const view *v)
{
    const lsample *s = &r->smp;
    rect *obst = (rect *)malloc(((size_t)s->ncur + 1) * sizeof *obst), labels[MAX_LABELS];
    const char *done[MAX_LABELS];
    size_t done_len[MAX_LABELS];
    int nlabels = 0, j;
    int32_t i;
    if (obst == NULL) return;
    for (i = 0; i < s->ncur; i++) obst[i] = body_rect(v, &s->cur[i]);
    fputs("<g font-size=\"12\" fill=\"#111\">\n", f);
    for (i = 0; i < s->ncur && nlabels < MAX_LABELS; i++) {
        size_t len;
        const char *name = lsample_name(s, s->cur[i].track, &len);
        double tw, lx, ly;
        int seen = 0;
        if (name == NULL) continue;
        for (j = 0; j < nlabels; j++) seen |= done_len[j] == len && memcmp(done[j], name, len) == 0;
        if (seen) continue;
        tw = text_width(name, len);
        if (!place(v, obst[i], tw, obst, s->ncur, labels, nlabels, &lx, &ly)) continue;
        labels[nlabels].x0 = lx - 1;
        labels[nlabels].x1 = lx + tw + 1;
        labels[nlabels].y0 = ly - 11;
        labels[nlabels].y1 = ly + 3;
        {   /* a leader line from the label to its body when they do not touch */
            const rect *b = &obst[i], *q = &labels[nlabels];
            double bx = fmin(fmax((q->x0 + q->x1) / 2, b->x0), b->x1), by = fmin(fmax((q->y0 + q->y1) / 2, b->y0), b->y1);
            double qx = fmin(fmax(bx, q->x0), q->x1), qy = fmin(fmax(by, q->y0), q->y1);
            if (hypot(qx - bx, qy - by) > 2)
                fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#777\" "
                           "stroke-width=\"0.8\"/>\n", bx, by, qx, qy);
        }
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\">", lx, ly);
        put_text(f, name, len);
        fputs("</text>\n", f);
        done[nlabels] = name;
        done_len[nlabels++] = len;
    }
    fputs("</g>\n", f);
    free(obst);
}

/* ---------------------------------------------------------------- the picture */

/* extra: more attributes, never a stroke-width (a shape's is 0.8, a point's ring 1.5). */
static void draw_body(FILE *f, const view *v, const lsample_body *b, int32_t shape, const char *fill,
                      const char *stroke, const char *extra)
{
    double px = sx(v, b->x), py = sy(v, b->y);
    if (shape == RG_SHAPE_AABB) {
        double w = fmax(2 * b->hx * v->s, 1.5), h = fmax(2 * b->hy * v->s, 1.5);
        fprintf(f, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"%s\" stroke=\"%s\" "
                   "stroke-width=\"0.8\" %s/>\n", px - w / 2, py - h / 2, w, h, fill, stroke, extra);
    } else if (shape == RG_SHAPE_CIRCLE) {
        fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"%s\" stroke=\"%s\" stroke-width=\"0.8\" "
                   "%s/>\n", px, py, fmax(b->hx * v->s, 1.5), fill, stroke, extra);
    } else {   /* no shape: a ring and a dot */
        fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"4.5\" fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\" %s/>"
                   "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"1.3\" fill=\"%s\"/>\n", px, py, stroke, extra, px, py, stroke);
    }
}

static void draw_paths(FILE *f, const lsvg *r, const view *v, const int *pcol, int crowded)
{
    const lsample *s = &r->smp;
    int32_t t;
    int k;
    for (t = 0; t < r->trails_room && t < s->ntracks; t++) {
        const trail *tr = &r->trails[t];
        const char *c = palette[pcol[t]];
        double next;
        if (tr->n < 2) continue;
        fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"%s\" stroke-opacity=\"%s\" points=\"",
                c, crowded ? "1" : "1.6", crowded ? "0.22" : "0.6");
        for (k = 0; k < tr->n; k++) fprintf(f, "%.2f,%.2f ", sx(v, (double)tr->pts[k].x), sy(v, (double)tr->pts[k].y));
        fprintf(f, "%.2f,%.2f\"/>\n", sx(v, r->lasts[t].x), sy(v, r->lasts[t].y));
        if (crowded) continue;
        fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"3\" fill=\"#fff\" stroke=\"%s\"/>\n",
                sx(v, (double)tr->pts[0].x), sy(v, (double)tr->pts[0].y), c);
        next = floor((double)tr->pts[0].t + 1e-6) + 1;
        fprintf(f, "<g fill=\"%s\" stroke=\"#fff\" stroke-width=\"0.6\">", c);
        for (k = 0; k < tr->n; k++)
            if ((double)tr->pts[k].t + 1e-6 >= next) {
                fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"2.6\"/>", sx(v, (double)tr->pts[k].x),
                        sy(v, (double)tr->pts[k].y));
                next = floor((double)tr->pts[k].t + 1e-6) + 1;
            }
        fputs("</g>\n", f);
    }
}

static void draw_grid(FILE *f, const view *v)
{
    double span = fmax(v->w, v->h) / v->s, step = nice_step(span), g;
    double minx = v->minx, maxx = v->minx + v->w / v->s, maxy = v->maxy, miny = v->maxy - v->h / v->s;
    fputs("<g stroke=\"#e2e2dc\" stroke-width=\"1\">\n", f);
    for (g = ceil(minx / step) * step; g <= maxx; g += step)
        fprintf(f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"%s/>\n", sx(v, g), v->top, sx(v, g),
                v->top + v->h, fabs(g) < step / 2 ? " stroke=\"#b0b0a8\"" : "");
    for (g = ceil(miny / step) * step; g <= maxy; g += step)
        fprintf(f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"%s/>\n", LEFT, sy(v, g),
                LEFT + v->w, sy(v, g), fabs(g) < step / 2 ? " stroke=\"#b0b0a8\"" : "");
    fputs("</g>\n<g font-size=\"11\" fill=\"#777\">\n", f);
    for (g = ceil(minx / step) * step; g <= maxx; g += step)
        fprintf(f, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\">%g</text>\n", sx(v, g), v->top + v->h + 15,
                fabs(g) < step / 2 ? 0.0 : g);
    for (g = ceil(miny / step) * step; g <= maxy; g += step)
        fprintf(f, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"end\">%g</text>\n", LEFT - 6, sy(v, g) + 4,
                fabs(g) < step / 2 ? 0.0 : g);
    fprintf(f, "<text x=\"%.2f\" y=\"%.2f\">m</text>\n</g>\n", LEFT + v->w + 6, v->top + v->h + 15);
}

/* What a colour was drawn on, for the legend. */
static void describe(uint32_t seen, char *out, size_t n)
{
    static const struct { uint32_t bit; const char *what; } w[] = {
        { LSAMPLE_STATIC, "static" }, { LSAMPLE_KINEMATIC, "kinematic" },
        { LSAMPLE_AWAKE, "dynamic, awake" }, { LSAMPLE_ASLEEP, "dynamic, asleep" },
        { LSAMPLE_SENSOR, "sensor" } };
    size_t i;
    out[0] = '\0';
    for (i = 0; i < sizeof w / sizeof w[0]; i++)
        if (seen & w[i].bit) {
            if (out[0] != '\0') strncat(out, " / ", n - strlen(out) - 1);
            strncat(out, w[i].what, n - strlen(out) - 1);
        }
}

static void build_legend(legend *g, const lsvg *r, const char **names, const size_t *lens,
                         int nnames, int crowded, int ndead, int shapeless, int arrows)
{
    const lsample *s = &r->smp;
    int used[LSAMPLE_MAX_COLORS], k, ntrails = 0;
    char text[200], colour[32], mark[240];
    int32_t i;
    memset(used, 0, sizeof used);
    for (i = 0; i < s->ncur; i++)
        if (s->cur[i].col >= 0) used[s->cur[i].col] = 1;
    for (i = 0; i < s->ntracks; i++)
        if (s->tracks[i].first >= 0 && s->tracks[i].stamp != s->frames && r->lasts[i].col >= 0)
            used[r->lasts[i].col] = 1;
    for (k = 0; k < s->ncolors; k++) {   /* the fills: the state each colour was drawn for */
        describe(s->seen[k], text, sizeof text);
        if (!used[k] || text[0] == '\0') continue;
        css(colour, s->colors[k], 1);
        snprintf(mark, sizeof mark, "<rect y=\"-9\" width=\"10\" height=\"10\" fill=\"%s\" stroke=\"#555\" "
                                    "stroke-width=\"0.6\"/>", colour);
        item(g, mark, text, strlen(text));
    }
    if (ndead > 0) {
        snprintf(text, sizeof text, "dashed: destroyed before the end, where last seen");
        item(g, "<rect y=\"-9\" width=\"10\" height=\"10\" fill=\"none\" stroke=\"#777\" stroke-dasharray=\"3 2\"/>",
             text, strlen(text));
    }
    if (shapeless) {
        snprintf(text, sizeof text, "a body without a shape");
        item(g, "<circle cx=\"5\" cy=\"-4\" r=\"4\" fill=\"none\" stroke=\"#555\" stroke-width=\"1.4\"/>", text,
             strlen(text));
    }
    if (s->counts[LSAMPLE_CONTACTS] > 0) {
        int n = 0;
        for (i = 0; i < s->counts[LSAMPLE_CONTACTS]; i++) n += s->lists[LSAMPLE_CONTACTS][i].kind == LSAMPLE_POINT;
        css(colour, RG_COLOR_CONTACT, 1);
        snprintf(mark, sizeof mark, "<circle cx=\"3\" cy=\"-4\" r=\"2.4\" fill=\"%s\"/><line x1=\"3\" "
                                    "y1=\"-4\" x2=\"10\" y2=\"-4\" stroke=\"%s\" stroke-width=\"1.2\"/>", colour, colour);
        snprintf(text, sizeof text, "%d contact%s touching at the end: the point, and the normal from a toward b (%.2g m)",
                 n, n == 1 ? "" : "s", RG_DRAW_NORMAL_LENGTH);
        item(g, mark, text, strlen(text));
    }
    if (s->counts[LSAMPLE_SPRINGS] > 0) {
        css(colour, RG_COLOR_SPRING, 1);
        snprintf(mark, sizeof mark, "<line x1=\"0\" y1=\"-4\" x2=\"10\" y2=\"-4\" stroke=\"%s\" stroke-width=\"1.6\"/>",
                 colour);
        item(g, mark, "spring", 6);
    }
    if (arrows) {
        css(colour, RG_COLOR_VELOCITY, 1);
        snprintf(mark, sizeof mark, "<line x1=\"0\" y1=\"-4\" x2=\"9\" y2=\"-4\" stroke=\"%s\" stroke-width=\"1.4\" "
                                    "marker-end=\"url(#arrow)\"/>", colour);
        snprintf(text, sizeof text, "velocity at the end (an arrow is %.2g s of motion)", ARROW_S);
        item(g, mark, text, strlen(text));
    }
    for (i = 0; i < r->trails_room && i < s->ntracks; i++) ntrails += r->trails[i].n >= 2;
    if (ntrails == 0) return;
    if (crowded) {
        snprintf(text, sizeof text, "faint lines: the paths of %d bodies up to the end", ntrails);
        snprintf(mark, sizeof mark, "<line x1=\"0\" y1=\"-4\" x2=\"10\" y2=\"-4\" stroke=\"%s\" stroke-width=\"1.6\" "
                                    "stroke-opacity=\"0.4\"/>", palette[0]);
        item(g, mark, text, strlen(text));
        return;
    }
    item(g, "", "paths up to the end:", 20);
    item(g, "<circle cx=\"5\" cy=\"-4\" r=\"3\" fill=\"#fff\" stroke=\"#555\"/>", "start,", 6);
    item(g, "<circle cx=\"5\" cy=\"-4\" r=\"2.6\" fill=\"#555\"/>", "each second;", 12);
    for (k = 0; k < nnames && k < NPALETTE; k++) {
        snprintf(mark, sizeof mark, "<line x1=\"0\" y1=\"-4\" x2=\"10\" y2=\"-4\" stroke=\"%s\" stroke-width=\"2\"/>",
                 palette[k]);
        item(g, mark, names[k], lens[k]);
    }
}

/* Breaks s into at most 16 lines of about `chars` characters at spaces: line i is
 * s[at[i], at[i + 1]) (a leading space dropped); returns the count. */
static int wrap(const char *s, double chars, int at[17])
{
    int n = 0, len = (int)strlen(s), start = 0;
    while (start < len && n < 16) {
        int end = len, k;
        if (len - start > (int)chars) {
            for (k = start + (int)chars; k > start && s[k] != ' '; k--) {}
            end = k > start ? k : start + (int)chars;
        }
        at[n++] = start;
        start = end;
        while (start < len && s[start] == ' ') start++;
        at[n] = end;
    }
    if (n == 0) at[n++] = 0, at[1] = 0;
    return n;
}

int lsvg_write(const lsvg *r, const char *path, const char *title, const char *subtitle)
{
    const lsample *s = &r->smp;
    view v = fit(r);
    legend g;
    const char *names[MAX_LABELS * 4];
    size_t lens[MAX_LABELS * 4];
    int nnames = 0, crowded, ndead = 0, shapeless = 0, arrows = 0, ntrails = 0;
    int *pcol = (int *)calloc((size_t)s->ntracks + 1, sizeof *pcol);
    char fill[32], stroke[32];
    double height, dot;
    char sub[1024];
    int breaks[17], nsub;
    int32_t i;
    FILE *f;
    if (pcol == NULL) return -1;
    for (i = 0; i < s->ntracks; i++) {
        int has_path = i < r->trails_room && r->trails[i].n >= 2;
        pcol[i] = has_path ? path_color(s, i, names, lens, &nnames) : 0;
        ntrails += has_path;
        if (s->tracks[i].first >= 0 && s->tracks[i].stamp != s->frames) ndead++;
    }
    for (i = 0; i < s->ncur; i++) {
        const lsample_body *b = &s->cur[i];
        shapeless |= s->tracks[b->track].shape == RG_SHAPE_NONE;
        arrows |= s->tracks[b->track].type != RG_BODY_STATIC && hypot(b->vx, b->vy) * ARROW_S * v.s >= 4;
    }
    crowded = ntrails > CROWD;
    snprintf(sub, sizeof sub, "%s; the world at t = %.2f s, as rg_world_draw draws it", subtitle, r->t_end);
    nsub = wrap(sub, (LEFT + v.w + RIGHT - 32) / CHAR_W, breaks);
    v.top = TOP + 16.0 * (nsub - 1);
    memset(&g, 0, sizeof g);
    build_legend(&g, r, names, lens, nnames, crowded, ndead, shapeless, arrows);
    height = v.top + v.h + 30 + 18.0 * legend_lines(&g, v.w) + 6;

    if ((f = fopen(path, "w")) == NULL) {
        free(pcol);
        return -1;
    }
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
               "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
               "viewBox=\"0 0 %.0f %.0f\" font-family=\"Helvetica, Arial, sans-serif\">\n",
            LEFT + v.w + RIGHT, height, LEFT + v.w + RIGHT, height);
    css(fill, RG_COLOR_VELOCITY, 1);
    fprintf(f, "<defs><marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"6\" "
               "markerHeight=\"6\" orient=\"auto-start-reverse\"><path d=\"M0,0 L10,5 L0,10 z\" fill=\"%s\"/>"
               "</marker><clipPath id=\"plot\"><rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\"/>"
               "</clipPath></defs>\n", fill, LEFT, v.top, v.w, v.h);
    fprintf(f, "<rect width=\"100%%\" height=\"100%%\" fill=\"#ffffff\"/>\n<rect x=\"%.2f\" y=\"%.2f\" "
               "width=\"%.2f\" height=\"%.2f\" fill=\"#f7f7f4\" stroke=\"#c8c8c0\"/>\n", LEFT, v.top, v.w, v.h);
    fputs("<text x=\"16\" y=\"28\" font-size=\"18\" font-weight=\"bold\" fill=\"#222\">", f);
    put_text(f, title, strlen(title));
    fputs("</text>\n", f);
    for (i = 0; i < nsub; i++) {
        fprintf(f, "<text x=\"16\" y=\"%.0f\" font-size=\"13\" fill=\"#555\">", 50 + 16.0 * i);
        put_text(f, sub + breaks[i], (size_t)(breaks[i + 1] - breaks[i]));
        fputs("</text>\n", f);
    }
    draw_grid(f, &v);

    fputs("<g clip-path=\"url(#plot)\">\n", f);
    draw_paths(f, r, &v, pcol, crowded);
    for (i = 0; i < s->ntracks; i++) {   /* destroyed before the end: dashed, where last seen */
        const lsample_body *b = &r->lasts[i];
        if (s->tracks[i].first < 0 || s->tracks[i].stamp == s->frames) continue;
        css(stroke, b->col >= 0 ? s->colors[b->col] : 0x555555ffu, 0.8);
        draw_body(f, &v, b, s->tracks[i].shape, "none", stroke, "stroke-dasharray=\"3 2\" stroke-opacity=\"0.6\"");
    }
    for (i = 0; i < s->ncur; i++) {
        const lsample_body *b = &s->cur[i];
        uint32_t c = b->col >= 0 ? s->colors[b->col] : 0x555555ffu;
        css(fill, c, 1);
        css(stroke, c | 0xffu, 0.55);
        draw_body(f, &v, b, s->tracks[b->track].shape, fill, stroke, "");
    }
    /* Contact marks no bigger than a third of the smallest body on screen. */
    dot = 2.2;
    for (i = 0; i < s->ncur; i++)
        if (s->cur[i].hx > 0) dot = fmin(dot, fmax(0.8, fmin(s->cur[i].hx, s->cur[i].hy) * v.s / 3));
    for (i = 0; i < s->counts[LSAMPLE_SPRINGS] + s->counts[LSAMPLE_CONTACTS]; i++) {
        int springs = i < s->counts[LSAMPLE_SPRINGS];
        const lsample_prim *p = springs ? &s->lists[LSAMPLE_SPRINGS][i]
                                        : &s->lists[LSAMPLE_CONTACTS][i - s->counts[LSAMPLE_SPRINGS]];
        css(fill, s->colors[p->col], 1);
        if (p->kind == LSAMPLE_POINT)
            fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"%s\"/>\n", sx(&v, p->v[0]), sy(&v, p->v[1]),
                    dot, fill);
        else if (p->kind == LSAMPLE_SEGMENT)
            fprintf(f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"%s\" stroke-width=\"%.2f\"/>\n",
                    sx(&v, p->v[0]), sy(&v, p->v[1]), sx(&v, p->v[2]), sy(&v, p->v[3]), fill, springs ? 1.6 : dot / 2);
    }
    css(stroke, RG_COLOR_VELOCITY, 1);
    for (i = 0; i < s->ncur; i++) {
        const lsample_body *b = &s->cur[i];
        double sp = hypot(b->vx, b->vy), len = sp * ARROW_S * v.s;
        if (s->tracks[b->track].type == RG_BODY_STATIC || len < 4) continue;
        if (len > 120) len = 120;
        fprintf(f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"%s\" stroke-width=\"1.4\" "
                   "marker-end=\"url(#arrow)\"/>\n", sx(&v, b->x), sy(&v, b->y), sx(&v, b->x) + b->vx / sp * len,
                sy(&v, b->y) - b->vy / sp * len, stroke);
    }
    fputs("</g>\n", f);
    draw_labels(f, r, &v);
    legend_write(f, &g, LEFT, v.top + v.h + 36, v.w);
    fputs("</svg>\n", f);
    free(pcol);
    return fclose(f) == 0 ? 0 : -1;
}
