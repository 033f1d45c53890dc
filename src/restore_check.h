/* restore_check.h: a snapshot (snapshot.h) read where it lies, and the checks rg_world_restore
 * makes of it before anything of the world changes (restore_check.c, restore_body.c,
 * restore_links.c); restore.c loads it. */
#ifndef RG_RESTORE_CHECK_H
#define RG_RESTORE_CHECK_H

#include <float.h>

#include "mem.h"
#include "snapshot.h"
#include "state.h"

typedef struct snap_in {
    const uint8_t *p;
    size_t size;
    snap_scalars s;
    snap_layout l;
    const uint64_t *kept_key;  /* a kept state's tail (snapshot.h: snap_kept_tail_size), */
    const int16_t *kept_level; /* else NULL */
} snap_in;

/* ---------------------------------------------------------------- reading */

static inline int32_t rd_i32(const snap_in *in, size_t off, int32_t i)
{
    return (int32_t)snap_get32(in->p + off + 4 * (size_t)i);
}

static inline uint32_t rd_u32(const snap_in *in, size_t off, int32_t i)
{
    return snap_get32(in->p + off + 4 * (size_t)i);
}

/* Body field f of body i. */
#define BF_AT(in, f, i) ((in)->p + (in)->l.field[SNAP_F_##f] + (in)->l.stride[SNAP_F_##f] * (size_t)(i))
#define BF_I(in, f, i) ((int32_t)snap_get32(BF_AT(in, f, i)))
#define BF_U(in, f, i) (snap_get32(BF_AT(in, f, i)))
#define BF_R(in, f, i) (snap_get_real(BF_AT(in, f, i)))

static inline const uint8_t *rec(const snap_in *in, size_t off, size_t size, int32_t k)
{
    return in->p + off + size * (size_t)k;
}

typedef struct snap_cursor {
    const uint8_t *p;
} snap_cursor;

static inline int32_t cur_i32(snap_cursor *c)
{
    int32_t v = (int32_t)snap_get32(c->p);
    c->p += 4;
    return v;
}

static inline uint32_t cur_u32(snap_cursor *c)
{
    uint32_t v = snap_get32(c->p);
    c->p += 4;
    return v;
}

static inline rg_real cur_real(snap_cursor *c)
{
    rg_real v = snap_get_real(c->p);
    c->p += SNAP_REAL;
    return v;
}

static inline double cur_f64(snap_cursor *c)
{
    uint64_t u = snap_get64(c->p);
    double v;
    memcpy(&v, &u, 8);
    c->p += 8;
    return v;
}

/* ---------------------------------------------------------------- columns and reals */

/* A body field where it lies: element i at p + stride * i (stride 0: uniform). */
typedef struct snap_col {
    const uint8_t *p;
    size_t stride;
} snap_col;

static inline snap_col col_of(const snap_in *in, int f)
{
    snap_col c = { in->p + in->l.field[f], in->l.stride[f] };
    return c;
}

static inline rg_real col_real(snap_col c, int32_t i) { return snap_get_real(c.p + c.stride * (size_t)i); }
static inline int32_t col_i32(snap_col c, int32_t i) { return (int32_t)snap_get32(c.p + c.stride * (size_t)i); }

static inline int col_uniform(const snap_in *in, int f) { return in->l.stride[f] == 0; }

/* A real's bits: within [lo, hi] (finite bounds, hi >= 0) compared as integers, which the
 * compiler turns into vector code: the magnitude (sign cleared) orders non-negative reals as
 * their values, so a value is within when a positive one's magnitude is in [pmin, plim] and
 * a negative one's at most nlim (-1: none; 0: -0 alone).  NaN and the infinities have
 * magnitudes above every finite bound's. */
#ifdef RG_DOUBLE
typedef uint64_t real_bits;
typedef int64_t real_sbits;
#define REAL_SIGN 63
#define real_get snap_get64
#else
typedef uint32_t real_bits;
typedef int32_t real_sbits;
#define REAL_SIGN 31
#define real_get snap_get32
#endif

static inline real_sbits real_bits_magnitude(real_bits u) { return (real_sbits)(u & ~((real_bits)1 << REAL_SIGN)); }

static inline real_sbits real_magnitude(rg_real v)
{
    real_bits u;
    memcpy(&u, &v, sizeof u);
    return real_bits_magnitude(u);
}

/* A real field's bits at element i. */
static inline real_bits col_bits_at(snap_col c, int32_t i) { return real_get(c.p + c.stride * (size_t)i); }

static inline int real_out(real_bits u, real_sbits pmin, real_sbits plim, real_sbits nlim)
{
    real_sbits mag = real_bits_magnitude(u), neg = -(real_sbits)(u >> REAL_SIGN);
    real_sbits lim = (nlim & neg) | (plim & ~neg), least = pmin & ~neg;
    return (mag > lim) | (mag < least);
}

/* The largest finite rg_real. */
#ifdef RG_DOUBLE
#define REAL_MAX DBL_MAX
#else
#define REAL_MAX FLT_MAX
#endif

/* A member record: slot, box, next, prev, lnext, lprev, moved, apos. */
typedef struct snap_member {
    int32_t slot;
    rg_real lx, ly, ux, uy;
    int32_t next, prev, lnext, lprev, moved, apos;
} snap_member;

static inline void restore_member(const snap_in *in, int32_t k, snap_member *m)
{
    snap_cursor c = { rec(in, in->l.members, SNAP_MEMBER, k) };
    m->slot = cur_i32(&c);
    m->lx = cur_real(&c);
    m->ly = cur_real(&c);
    m->ux = cur_real(&c);
    m->uy = cur_real(&c);
    m->next = cur_i32(&c);
    m->prev = cur_i32(&c);
    m->lnext = cur_i32(&c);
    m->lprev = cur_i32(&c);
    m->moved = cur_i32(&c);
    m->apos = cur_i32(&c);
}

/* What the contact and broadphase checks work with (restore_links.c), kept for the load:
 * per contact id its record + 1 (live) or -1 (free); per slot its member index + 1; per
 * member its level and key (computed once); marks for the bucket heads, huge indices,
 * active places and the bodies island links lead to; the lists' links gathered as indices
 * (for restore_acyclic).  The load of a kept state (RESTORE_KEPT) needs rec_of and
 * member_of alone, that of the world's own snapshot (RESTORE_OWN) also key and level, and
 * the rest is not made. */
enum {
    RESTORE_KEPT,    /* a kept state (slots.c): unchecked, the levels and keys in its tail */
    RESTORE_CHECKED, /* a snapshot from outside: every invariant checked */
    RESTORE_OWN      /* one of the world's own last saves (own.h): unchecked */
};
typedef struct restore_scratch {
    int32_t *rec_of;        /* [ccap] */
    int32_t *member_of;     /* [bslots] */
    uint8_t *bucket_head;   /* [2^bucket_bits] */
    uint8_t *huge_used;     /* [n_huge] */
    uint8_t *active_used;   /* [n_bp_active] */
    uint8_t *isl_in;        /* [asleep]: whether an island link leads to the sleeping body */
    size_t zeroed;          /* the block's bytes up to here start at zero, the rest is written */
    uint64_t *key;          /* [members] */
    int16_t *level;         /* [members] */
    uint8_t *body_bits;     /* [count]: what a body gives its contacts' flags */
    uint8_t *wakes;         /* [clive]: the record has an awake body */
    int32_t *node_next;     /* [2 clive]: each body list's next node (record 2k + side) */
    int32_t *chain_next;    /* [members]: the next member along the chain, and the level */
    int32_t *level_next;    /* [members] */
    rg_real *box;           /* [4 members]: the members' boxes */
    int32_t *isl_next;      /* [asleep]: each sleeping body's next in its island (dense - n_active) */
    const snap_scalars *s;
    int checked; /* RESTORE_* */
} restore_scratch;

/* Dense index of a live body slot, or -1. */
static inline int32_t restore_dense(const snap_in *in, int32_t slot)
{
    if (slot < 0 || slot >= in->s.bslots) return -1;
    return rd_i32(in, in->l.bindex, slot);
}

/* Each check returns 1, or 0 for a snapshot that breaks what it checks. */
/* The header (magic, version, rg_real, size), with the reason set on failure (sealed: for
 * rg_world_restore, else for a kept state); it reads the scalars into in, which the checks
 * below may take before the checksum is known: they accept no bytes that break what they
 * check, whatever the bytes are. */
int restore_check_header(const rg_world *w, snap_in *in, const void *data, size_t size, int sealed);
/* The checksum of a sealed snapshot (rg_world_save) over its bytes past the header. */
int restore_check_sum(const snap_in *in);
/* The settings and counts, each within the range of the setter it enters by. */
int restore_check_scalars(snap_in *in);
/* A pool's slots against the dense places that name them (slot_of, slot_stride). */
int restore_check_pool(const snap_in *in, size_t gen, size_t index, int32_t slots, uint32_t max_gen,
                      int32_t head, int32_t live, const uint8_t *slot_of, size_t slot_stride);
/* The bodies: each field's values in the ranges of the setters they enter by, over the
 * partitions they hold in (restore_body.c). */
int restore_check_body_values(const snap_in *in);
int restore_check_springs(const snap_in *in);
int restore_check_events(const snap_in *in, size_t off, int32_t n);
/* The scratch the two checks below fill (sized from r->s and r->checked) and the load
 * reads (restore_links.c). */
void restore_check_scratch_layout(mem_layout *l, void *ctx);
/* Whether the links next[0..n) (a node, -1 at an end, below -1 for none) run round no cycle
 * (restore_links.c): every cycle has a link that does not lead to a lower node, so walks
 * start from those links alone, each marking the links it passes (next is scratch: it is
 * overwritten); a walk that meets its own mark has run round a cycle, one that meets an
 * earlier walk's mark joins a path already seen to end.  Each link is passed once. */
int restore_acyclic(int32_t *next, int32_t n);
/* The sleeping bodies' islands (restore_links.c). */
int restore_check_islands(const snap_in *in, restore_scratch *r);
/* Both spread what they can over w's task system (nothing of w changes). */
int restore_check_contacts(struct rg_world *w, const snap_in *in, restore_scratch *r);
int restore_check_broadphase(struct rg_world *w, const snap_in *in, restore_scratch *r);

#endif
