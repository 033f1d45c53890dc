/* fuzz_api_model.c: the API harness's input decoder, failing allocator, model of live
 * handles, snapshots and invariant checks (see fuzz_api.c). */
#include <math.h>
#include <string.h>

#include "fuzz_api.h"

/* ---------------------------------------------------------------- input */


uint8_t u8(input *in)
{
    if (in->n == 0) return 0;
    in->n--;
    return *in->p++;
}

uint32_t u32(input *in)
{
    uint32_t v = 0;
    for (int k = 0; k < 4; k++) v = (v << 8) | u8(in);
    return v;
}

uint64_t u64(input *in)
{
    return ((uint64_t)u32(in) << 32) | u32(in);
}

int trace = -1;   /* FUZZ_API_TRACE set: print each op and its reals (reproducers) */

static rg_real real_value(input *in);

rg_real real_arg(input *in)
{
    rg_real r = real_value(in);
    if (trace > 0) fprintf(stderr, "  real %.9g\n", (double)r);
    return r;
}

static rg_real real_value(input *in)
{
    static const double edge[] = { 0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 10.0, 1e-3, 1.0 / 60, 1e3,
                                   1e6, 1e7, 1e10, 1e20, 1e30, 3.0e38, -3.0e38, 1e-38, 1e-40,
                                   1e-45, -1e-40, 1e300, 1e-300 };
    uint8_t sel = u8(in);
    if (sel < 96) {
        /* NaN and the infinities come in by raw bits below and here */
        if (sel == 0) return (rg_real)NAN;
        if (sel == 1) return (rg_real)INFINITY;
        if (sel == 2) return -(rg_real)INFINITY;
        return (rg_real)edge[sel % (sizeof edge / sizeof edge[0])];
    }
    if (sel < 160) return (rg_real)((int)(sel - 128) * 0.25);
#ifdef RG_DOUBLE
    uint64_t bits = u64(in);
    double d;
    memcpy(&d, &bits, sizeof d);
    return d;
#else
    uint32_t bits = u32(in);
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
#endif
}

rg_vec2 vec_arg(input *in)
{
    rg_vec2 v;
    v.x = real_arg(in);
    v.y = real_arg(in);
    return v;
}

int32_t int_arg(input *in)
{
    uint8_t sel = u8(in);
    if (sel < 200) return (int32_t)(sel % 12) - 2;
    return (int32_t)u32(in);
}

/* ---------------------------------------------------------------- allocator */


typedef struct fz_block {
    size_t size;
    size_t magic;
} fz_block;
#define FZ_MAGIC ((size_t)0x5a17b10c)

int op_no;
const char *op_name = "setup";

void *fz_allocf(void *user, void *ptr, size_t old_size, size_t new_size)
{
    fz_alloc *a = (fz_alloc *)user;
    fz_block *h = ptr != NULL ? (fz_block *)ptr - 1 : NULL;
    if (h != NULL && (h->magic != FZ_MAGIC || h->size != old_size))
        FAIL("allocator told old_size %zu for a block of %zu", old_size, h->magic == FZ_MAGIC ? h->size : 0);
    if (h == NULL && old_size != 0) FAIL("allocator: old_size %zu for a NULL block", old_size);
    if (new_size == 0) {
        if (h != NULL) {
            a->live_bytes -= h->size;
            a->live_blocks--;
            h->magic = 0;
            free(h);
        }
        return NULL;
    }
    a->calls++;
    if (a->fail_at >= 0 && a->calls >= a->fail_at) return NULL;
    if (new_size > ((size_t)1 << 31)) return NULL;   /* nothing the harness does needs more */
    fz_block *n = (fz_block *)malloc(sizeof *n + new_size);
    if (n == NULL) return NULL;
    n->size = new_size;
    n->magic = FZ_MAGIC;
    if (h != NULL) {
        memcpy(n + 1, h + 1, old_size < new_size ? old_size : new_size);
        a->live_bytes -= h->size;
        a->live_blocks--;
        h->magic = 0;
        free(h);
    }
    a->live_bytes += new_size;
    a->live_blocks++;
    return n + 1;
}

/* ---------------------------------------------------------------- the model */



fworld W[NW];
dead_handle dead[NDEAD];
int ndead, dead_next, next_serial;

static uint32_t tag_of(uint64_t h) { return (uint32_t)(h >> 44); }

/* Each world draws a random 20-bit tag: two share one with probability 2^-20, and then a
 * handle of one is valid in the other.  A limit of 64-bit handles, not a finding. */
static int same_tag(const fworld *fw, uint64_t h)
{
    return fw->tag_known && tag_of(h) == fw->tag;
}

void remember_dead(rg_body h, const fworld *fw)
{
    dead[dead_next].h = h;
    dead[dead_next].serial = fw->serial;
    dead[dead_next].identity = fw->identity;
    dead_next = (dead_next + 1) % NDEAD;
    if (ndead < NDEAD) ndead++;
}


int in_list(const rg_body *l, int n, uint64_t h)
{
    for (int i = 0; i < n; i++)
        if (l[i] == h) return 1;
    return 0;
}

void world_issued(fworld *fw, rg_body h)
{
    if (h == 0) FAIL("a body handle of 0");
    if (in_list(fw->issued, fw->nissued, h)) FAIL("handle %llx issued twice by one world", (unsigned long long)h);
    for (int k = 0; k < NW; k++) {
        if (&W[k] == fw || W[k].w == NULL || W[k].identity == fw->identity) continue;
        if (in_list(W[k].issued, W[k].nissued, h) && !same_tag(fw, h))
            FAIL("handle %llx issued by two live worlds", (unsigned long long)h);
    }
    for (int k = 0; k < ndead; k++)
        if (dead[k].h == h && (dead[k].serial == fw->serial ||
                               (dead[k].identity != fw->identity && !same_tag(fw, h))))
            FAIL("stale handle %llx issued again", (unsigned long long)h);
    if (fw->nissued < MAXISSUE) fw->issued[fw->nissued++] = h;
    if (!fw->tag_known) {
        fw->tag_known = 1;
        fw->tag = tag_of(h);
    }
}

void body_gone(fworld *fw, rg_body h)
{
    for (int i = 0; i < fw->nlive; i++)
        if (fw->live[i] == h) {
            fw->live[i] = fw->live[--fw->nlive];
            break;
        }
    for (int i = 0; i < fw->nspring;)
        if (fw->sa[i] == h || fw->sb[i] == h) {
            fw->spring[i] = fw->spring[fw->nspring - 1];
            fw->sa[i] = fw->sa[fw->nspring - 1];
            fw->sb[i] = fw->sb[fw->nspring - 1];
            fw->nspring--;
        } else {
            i++;
        }
    remember_dead(h, fw);
}

void world_close(fworld *fw)
{
    if (fw->w == NULL) return;
    for (int i = 0; i < fw->nissued; i++)
        if (in_list(fw->live, fw->nlive, fw->issued[i])) remember_dead(fw->issued[i], fw);
    rg_world_destroy(fw->w);
    if (fw->al != NULL) {
        if (fw->al->live_blocks != 0 || fw->al->live_bytes != 0)
            FAIL("a destroyed world left %ld blocks (%zu bytes)", fw->al->live_blocks, fw->al->live_bytes);
        free(fw->al);
    }
    memset(fw, 0, sizeof *fw);
}

fworld *pick_world(input *in)
{
    return &W[u8(in) % NW];
}

/* A handle for fw: mostly live, else stale, foreign, 0, forged or a live one altered. */
rg_body pick_body(input *in, const fworld *fw)
{
    uint8_t sel = u8(in);
    int k = sel >> 4;
    if (k < 9 && fw->nlive > 0) return fw->live[sel % fw->nlive];
    if (k < 11 && ndead > 0) return dead[sel % ndead].h;
    if (k < 12) {
        const fworld *o = &W[sel % NW];
        if (o->nlive > 0) return o->live[u8(in) % o->nlive];
    }
    if (k < 13) return 0;
    if (k < 14 && fw->nlive > 0) return fw->live[sel % fw->nlive] ^ ((uint64_t)1 << (u8(in) % 64));
    return u64(in);
}

uint64_t pick_spring(input *in, const fworld *fw)
{
    uint8_t sel = u8(in);
    if (sel < 160 && fw->nspring > 0) return fw->spring[sel % fw->nspring];
    if (sel < 200 && fw->nlive > 0) return fw->live[sel % fw->nlive];   /* a body, not a spring */
    if (sel < 220) return 0;
    return u64(in);
}

/* ---------------------------------------------------------------- snapshots */


static void put(snap *s, const void *v, size_t n)
{
    if (s->n + n > s->cap) {
        s->cap = (s->n + n) * 2 + 4096;
        s->p = (unsigned char *)realloc(s->p, s->cap);
        if (s->p == NULL) abort();
    }
    memcpy(s->p + s->n, v, n);
    s->n += n;
}

#define PUT(s, v) put((s), &(v), sizeof(v))

/* Every value the getters show of one world, in a fixed order. */
static void snap_world(snap *s, const fworld *fw)
{
    const rg_world *w = fw->w;
    rg_vec2 v;
    rg_real r[4];
    int32_t i[2], st;
    uint32_t u[2];
    uint64_t u64v;
    static rg_contact_event ev[MAXEV];
    memset(&v, 0, sizeof v);
    memset(r, 0, sizeof r);
    memset(i, 0, sizeof i);
    st = rg_world_get_gravity(w, &v); PUT(s, st); PUT(s, v);
    st = rg_world_get_wind(w, &v); PUT(s, st); PUT(s, v);
    st = rg_world_get_integrator(w, &i[0]); PUT(s, st); PUT(s, i[0]);
    st = rg_world_get_fixed_step(w, &r[0], &i[1]); PUT(s, st); PUT(s, r[0]); PUT(s, i[1]);
    st = rg_world_get_alpha(w, &r[1]); PUT(s, st); PUT(s, r[1]);
    st = rg_world_get_sleeping(w, &i[0]); PUT(s, st); PUT(s, i[0]);
    st = rg_world_get_sleep_thresholds(w, &r[0], &r[1]); PUT(s, st); PUT(s, r[0]); PUT(s, r[1]);
    st = rg_world_get_solver_iterations(w, &i[0], &i[1]); PUT(s, st); PUT(s, i);
    st = rg_world_get_contact_tuning(w, &r[0], &r[1], &r[2], &r[3]); PUT(s, st); PUT(s, r);
    st = rg_world_get_continuous(w, &i[0]); PUT(s, st); PUT(s, i[0]);
    st = rg_world_body_count(w); PUT(s, st);
    st = rg_world_spring_count(w); PUT(s, st);
    st = rg_world_awake_body_count(w); PUT(s, st);
    st = rg_world_touching_count(w); PUT(s, st);
    memset(ev, 0, sizeof ev);
    st = rg_world_get_contact_events(w, ev, MAXEV); PUT(s, st);
    if (st > 0) put(s, ev, (size_t)(st < MAXEV ? st : MAXEV) * sizeof ev[0]);
    for (int k = 0; k < fw->nlive; k++) {
        rg_body b = fw->live[k];
        st = rg_body_is_valid(w, b); PUT(s, st);
        memset(&v, 0, sizeof v);
        st = rg_body_get_position(w, b, &v); PUT(s, st); PUT(s, v);
        st = rg_body_get_velocity(w, b, &v); PUT(s, st); PUT(s, v);
        st = rg_body_get_acceleration(w, b, &v); PUT(s, st); PUT(s, v);
        st = rg_body_get_interpolated_position(w, b, &v); PUT(s, st); PUT(s, v);
        st = rg_body_get_type(w, b, &i[0]); PUT(s, st); PUT(s, i[0]);
        st = rg_body_get_mass(w, b, &r[0]); PUT(s, st); PUT(s, r[0]);
        st = rg_body_get_shape(w, b, &i[0], &v); PUT(s, st); PUT(s, i[0]); PUT(s, v);
        st = rg_body_get_restitution(w, b, &r[0]); PUT(s, st); PUT(s, r[0]);
        st = rg_body_get_friction(w, b, &r[0]); PUT(s, st); PUT(s, r[0]);
        st = rg_body_is_sensor(w, b, &i[0]); PUT(s, st); PUT(s, i[0]);
        memset(u, 0, sizeof u);
        st = rg_body_get_filter(w, b, &u[0], &u[1]); PUT(s, st); PUT(s, u);
        u64v = 0;
        st = rg_body_get_user_data(w, b, &u64v); PUT(s, st); PUT(s, u64v);
        st = rg_body_is_awake(w, b, &i[0]); PUT(s, st); PUT(s, i[0]);
        st = rg_body_is_grounded(w, b, &i[0]); PUT(s, st); PUT(s, i[0]);
    }
    for (int k = 0; k < fw->nspring; k++) {
        st = rg_spring_is_valid(w, fw->spring[k]);
        PUT(s, st);
    }
}

void snap_all(snap *s)
{
    s->n = 0;
    for (int k = 0; k < NW; k++)
        if (W[k].w != NULL) snap_world(s, &W[k]);
}

/* ---------------------------------------------------------------- invariants */

int finite2(rg_vec2 v) { return isfinite(v.x) && isfinite(v.y); }

/* Whether values derived from the state (not the state itself) must read finite. */
int derived_checked(const fworld *fw)
{
    return !fw->tainted;
}

/* 1 when every live body of fw reads finite. */
static int world_finite(fworld *fw)
{
    for (int k = 0; k < fw->nlive; k++) {
        rg_vec2 p, v, ip, a;
        rg_body b = fw->live[k];
        if (rg_body_get_position(fw->w, b, &p) != RG_OK || rg_body_get_velocity(fw->w, b, &v) != RG_OK ||
            rg_body_get_interpolated_position(fw->w, b, &ip) != RG_OK ||
            rg_body_get_acceleration(fw->w, b, &a) != RG_OK)
            FAIL("a getter failed on live body %llx", (unsigned long long)b);
        if (!finite2(p) || !finite2(v)) return 0;
#ifdef FUZZ_KNOWN_STEP_NOT_TOTAL
        /* Past the ranges a step may not take it (test_a_restored_clone_hashes_*). */
        if (fabs((double)p.x) > RG_MAX_COORD || fabs((double)p.y) > RG_MAX_COORD ||
            fabs((double)v.x) > RG_MAX_SPEED || fabs((double)v.y) > RG_MAX_SPEED)
            return 0;
#endif
        if (derived_checked(fw) && (!finite2(ip) || !finite2(a))) return 0;
    }
    return 1;
}

static void check_world(fworld *fw, int was_step)
{
    const rg_world *w = fw->w;
    if (rg_world_body_count(w) != fw->nlive)
        FAIL("body count %d, model %d", rg_world_body_count(w), fw->nlive);
    if (rg_world_spring_count(w) != fw->nspring)
        FAIL("spring count %d, model %d", rg_world_spring_count(w), fw->nspring);
    int awake = rg_world_awake_body_count(w);
    if (awake < 0 || awake > fw->nlive) FAIL("awake count %d of %d bodies", awake, fw->nlive);
    if (rg_world_touching_count(w) < 0) FAIL("touching count < 0");
    for (int k = 0; k < fw->nlive; k++)
        if (rg_body_is_valid(w, fw->live[k]) != 1) FAIL("live body %llx not valid", (unsigned long long)fw->live[k]);
    for (int k = 0; k < fw->nspring; k++)
        if (rg_spring_is_valid(w, fw->spring[k]) != 1) FAIL("live spring not valid");
    for (int k = 0; k < ndead; k++) {
        if (!in_list(fw->live, fw->nlive, dead[k].h) && rg_body_is_valid(w, dead[k].h) &&
            (dead[k].serial == fw->serial || !same_tag(fw, dead[k].h)))
            FAIL("stale handle %llx valid in world %d", (unsigned long long)dead[k].h, fw->serial);
    }
    for (int o = 0; o < NW; o++) {
        if (W[o].w == NULL || &W[o] == fw || W[o].identity == fw->identity) continue;
        for (int k = 0; k < W[o].nlive; k++) {
            rg_body h = W[o].live[k];
            if (rg_body_is_valid(w, h) && !same_tag(fw, h))
                FAIL("world %d's handle %llx valid in world %d", W[o].serial, (unsigned long long)h, fw->serial);
        }
    }
    if (!fw->tainted && !world_finite(fw)) {
#ifdef FUZZ_KNOWN_STEP_NOT_TOTAL
        if (was_step) {
            fw->tainted = 1;
            return;
        }
#else
        (void)was_step;
#endif
        FAIL("a live body of world %d is not finite", fw->serial);
    }
}

void check_all(int was_step)
{
    for (int k = 0; k < NW; k++)
        if (W[k].w != NULL) check_world(&W[k], was_step);
}

void check_events(const fworld *fw)
{
    static rg_contact_event ev[MAXEV];
    int32_t n = rg_world_get_contact_events(fw->w, NULL, 0);
    if (n < 0) FAIL("event count %d", n);
    int32_t cap = n < MAXEV ? n : MAXEV;
    if (rg_world_get_contact_events(fw->w, ev, cap) != n) FAIL("event count changed between reads");
    for (int k = 0; k < cap; k++) {
        const rg_contact_event *e = &ev[k];
        if (!(e->a < e->b)) FAIL("event %d: a >= b", k);
        if (e->kind != RG_CONTACT_BEGIN && e->kind != RG_CONTACT_END) FAIL("event kind %d", e->kind);
        if (e->sensor != 0 && e->sensor != 1) FAIL("event sensor %d", e->sensor);
        if (!in_list(fw->issued, fw->nissued, e->a) || !in_list(fw->issued, fw->nissued, e->b))
            if (fw->nissued < MAXISSUE) FAIL("event %d names a body this world never had", k);
        if (derived_checked(fw) && (!finite2(e->normal) || !finite2(e->point) || !isfinite(e->depth) || !isfinite(e->speed)))
            FAIL("event %d not finite", k);
    }
}

/* ---------------------------------------------------------------- draw callbacks */

const fworld *draw_world;

static void draw_body(rg_body body)
{
    if (!in_list(draw_world->live, draw_world->nlive, body)) FAIL("draw: body %llx not live", (unsigned long long)body);
}

static void draw_vec(rg_vec2 v)
{
    if (derived_checked(draw_world) && !finite2(v)) FAIL("draw: a non-finite point (%g, %g)", (double)v.x, (double)v.y);
}

void on_circle(rg_body body, rg_vec2 c, rg_real r, uint32_t rgba, void *user)
{
    (void)rgba;
    (void)user;
    draw_body(body);
    draw_vec(c);
    if (!(r > 0)) FAIL("draw: radius %g", (double)r);
}

void on_box(rg_body body, rg_vec2 lo, rg_vec2 hi, uint32_t rgba, void *user)
{
    (void)rgba;
    (void)user;
    draw_body(body);
    draw_vec(lo);
    draw_vec(hi);
    if (derived_checked(draw_world) && !(lo.x <= hi.x && lo.y <= hi.y)) FAIL("draw: box lower > upper");
}

void on_segment(rg_vec2 a, rg_vec2 b, uint32_t rgba, void *user)
{
    (void)rgba;
    (void)user;
    draw_vec(a);
    draw_vec(b);
}

void on_point(rg_vec2 p, uint32_t rgba, void *user)
{
    (void)rgba;
    (void)user;
    draw_vec(p);
}
