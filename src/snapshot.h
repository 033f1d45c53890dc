/* snapshot.h: the snapshot format, shared by its writer (snapshot.c: rg_world_save,
 * rg_world_hash), its reader (restore.c: rg_world_restore) and its hash (snap_hash.c).
 *
 * One byte order (little-endian) and fixed field sizes (int32, uint32, uint64, rg_real as
 * IEEE 754 binary32 or binary64, the accumulator as binary64), whatever the machine:
 *
 *   0   "RIGIDSNP"                      8 bytes
 *   8   format version (SNAP_VERSION)   uint32
 *   12  sizeof(rg_real)                 uint32
 *   16  total size in bytes             uint64
 *   24  checksum of bytes [32, size)    uint64 (snap_hash)
 *   32  the scalars (snap_scalars: settings, counts, pool heads)
 *   ... the arrays, each starting on a multiple of 8 bytes (zero padding): the body pool;
 *       the body fields of SNAP_BODY_FIELDS, each a word (0: the array follows, 1: all its
 *       values are equal and one follows) and its data; the spring pool and the springs;
 *       the live contacts by ascending id, then the free ids in free-list order; the awake
 *       contacts; the events held and pending; the members of the broadphase with their
 *       boxes and links; its move buffer.
 *
 * What is not written is derived (a body's inverse mass and flags, a contact's mixed
 * materials and its place in the awake list) or scratch that every step rebuilds (the
 * views and displacements, the solver rows, indices and times of impact, the union-find,
 * the broadphase's pair-search marks), capacities, the allocator and the pre-solve hook.  rg_world_hash hashes the same stream with the world tag left out
 * (0, and event handles without it), so equal states give equal hashes in any world. */
#ifndef RG_SNAPSHOT_H
#define RG_SNAPSHOT_H

#include <stddef.h>
#include <stdint.h>

#include "snap_hash.h"
#include "snap_le.h"
#include "state.h"

#define SNAP_MAGIC "RIGIDSNP"
#define SNAP_VERSION 2u
#define SNAP_HEADER 32

/* The body fields a snapshot holds, in file order.  RG_BODY_FIELDS has these and the four
 * a restore derives (inv_mass, flags) or clears (dx, dy): snapshot.c checks the count. */
#define SNAP_BODY_FIELDS(X)                                                                  \
    X(rg_real, x) X(rg_real, y) X(rg_real, vx) X(rg_real, vy) X(rg_real, fx) X(rg_real, fy)   \
    X(rg_real, ax) X(rg_real, ay) X(rg_real, px) X(rg_real, py) X(rg_real, mass)              \
    X(rg_real, gscale) X(rg_real, drag_lin) X(rg_real, drag_quad) X(rg_real, fric)            \
    X(rg_real, min_speed) X(rg_real, max_speed) X(uint64_t, user) X(int32_t, slot)            \
    X(int32_t, type) X(int32_t, shape) X(rg_real, hx) X(rg_real, hy) X(rg_real, rest)         \
    X(rg_real, mu) X(uint32_t, cat) X(uint32_t, mask) X(uint32_t, cflags) X(int32_t, chead)   \
    X(rg_real, sleep_t) X(int32_t, isl_head) X(int32_t, isl_next) X(rg_real, owx) X(rg_real, owy)
#define SNAP_DERIVED_FIELDS 4

#define SNAP_FIELD_ENUM(T, name) SNAP_F_##name,
enum { SNAP_BODY_FIELDS(SNAP_FIELD_ENUM) SNAP_FIELDS };
#undef SNAP_FIELD_ENUM

/* The counts that size the arrays, and the scalars written before them. */
typedef struct snap_scalars {
    rg_vec2 gravity, wind;
    int32_t integrator, max_steps, prev_valid;
    double fixed_dt, accumulator;
    uint64_t step_count;
    int32_t iterations, position, sleeping, continuous, near_sleep;
    rg_real sleep_speed, sleep_time, slop, bias_rate, max_push, restitution_threshold;
    /* body pool and store */
    uint32_t btag, bmax_gen;
    int32_t bmax_slots, bslots, bfree, blive;
    int32_t count, n_active, n_moving;
    /* spring pool and store */
    uint32_t stag, smax_gen;
    int32_t smax_slots, sslots, sfree, slive, springs;
    /* contacts */
    int32_t ccap, clive, n_awake, n_touching;
    /* events */
    int32_t n_ev, n_pend;
    /* broadphase */
    int32_t members, bucket_bits, n_huge, n_moved, n_bp_active;
    uint32_t mark;
} snap_scalars;

/* Byte offsets of the arrays (from the snapshot's start) and the total size, found by
 * reading them in order.  A body field's element i is at field[k] + stride[k] * i (stride 0
 * for a uniform array). */
typedef struct snap_layout {
    size_t bgen, bindex;                 /* [bslots] */
    size_t field[SNAP_FIELDS], stride[SNAP_FIELDS];
    size_t sgen, sindex;                 /* [sslots] */
    size_t springs;                      /* [springs] records */
    size_t contacts;                     /* [clive] records */
    size_t free;                         /* [ccap - clive] ids */
    size_t awake;                        /* [n_awake] */
    size_t ev, pend;                     /* [n_ev], [n_pend] records */
    size_t members;                      /* [members] records */
    size_t moved;                        /* [n_moved] */
    size_t size;
} snap_layout;

/* Record sizes in the file. */
#define SNAP_REAL ((size_t)sizeof(rg_real))
#define SNAP_SPRING (3 * 4 + 5 * SNAP_REAL)              /* slot_a, slot_b, self; anchor, rest, k, c */
#define SNAP_CONTACT (8 * 4 + 10 * SNAP_REAL)            /* id, sa, sb, na, pa, nb, pb, flags;
                                                            nx, ny, px, py, s0, vn0, depth, speed, pn, pt */
#define SNAP_EVENT (2 * 8 + 6 * SNAP_REAL + 2 * 4)       /* a, b, normal, point, depth, speed, kind, sensor */
#define SNAP_MEMBER (4 + 4 * SNAP_REAL + 6 * 4)          /* slot, box, next, prev, lnext, lprev, moved, apos */

/* Where the machine's order is the file's (SNAP_NATIVE, below), a contact record is three
 * runs of its struct and a member record two runs of its entry, copied whole: sa .. pb and
 * nx .. pt of a contact, the box and next .. lprev of an entry lie in the file's order. */
#define SNAP_CONTACT_LINKS 4     /* sa, sb, na, pa, nb, pb: 6 int32 at this offset in a record */
#define SNAP_CONTACT_FLAGS 28
#define SNAP_CONTACT_REALS 32    /* nx .. pt: 10 reals */
#define SNAP_MEMBER_BOX 4        /* lx, ly, ux, uy */
#define SNAP_MEMBER_LINKS (4 + 4 * SNAP_REAL) /* next, prev, lnext, lprev: 4 int32 */
/* Each field where its run puts it, in the file's order. */
#define SNAP_AT(type, f, first, k, size) (offsetof(type, f) == offsetof(type, first) + (k) * (size))
typedef char snap_contact_runs[SNAP_AT(contact, sb, sa, 1, 4) && SNAP_AT(contact, na, sa, 2, 4) &&
                                       SNAP_AT(contact, pa, sa, 3, 4) && SNAP_AT(contact, nb, sa, 4, 4) &&
                                       SNAP_AT(contact, pb, sa, 5, 4) &&
                                       SNAP_AT(contact, ny, nx, 1, sizeof(rg_real)) &&
                                       SNAP_AT(contact, px, nx, 2, sizeof(rg_real)) &&
                                       SNAP_AT(contact, py, nx, 3, sizeof(rg_real)) &&
                                       SNAP_AT(contact, s0, nx, 4, sizeof(rg_real)) &&
                                       SNAP_AT(contact, vn0, nx, 5, sizeof(rg_real)) &&
                                       SNAP_AT(contact, depth, nx, 6, sizeof(rg_real)) &&
                                       SNAP_AT(contact, speed, nx, 7, sizeof(rg_real)) &&
                                       SNAP_AT(contact, pn, nx, 8, sizeof(rg_real)) &&
                                       SNAP_AT(contact, pt, nx, 9, sizeof(rg_real))
                                   ? 1
                                   : -1];
typedef char snap_member_runs[SNAP_AT(bp_entry, ly, lx, 1, sizeof(rg_real)) &&
                                      SNAP_AT(bp_entry, ux, lx, 2, sizeof(rg_real)) &&
                                      SNAP_AT(bp_entry, uy, lx, 3, sizeof(rg_real)) &&
                                      SNAP_AT(bp_entry, prev, next, 1, 4) && SNAP_AT(bp_entry, lnext, next, 2, 4) &&
                                      SNAP_AT(bp_entry, lprev, next, 3, 4)
                                  ? 1
                                  : -1];

/* The scalars' size in the file. */
size_t snap_scalars_size(void);

/* What a save of the world now writes: its scalars, which body fields are uniform, and the
 * size in bytes. */
typedef struct snap_plan {
    snap_scalars s;
    int uniform[SNAP_FIELDS];
    size_t size;
} snap_plan;
void snap_plan_of(const rg_world *w, snap_plan *plan);
/* Writes the planned snapshot (plan->size bytes at p).  sealed: with its checksum, as
 * rg_world_save; else checksum 0 and followed by the kept tail (below), for a state the
 * world keeps for itself (slots.c), which only rg_world_restore_slot reads. */
void snap_write_planned(const rg_world *w, const snap_plan *plan, uint8_t *p, int sealed);
/* A kept state's tail, at p + plan->size (a multiple of 8): each member's cell key
 * (uint64_t) and then its level (int16_t), in member order and the machine's own order
 * (the state never leaves the process), as the world holds them.  A level and key are a
 * function of the member's box, which a restore would otherwise compute again for every
 * box; this size in bytes, a multiple of 8. */
size_t snap_kept_tail_size(const snap_plan *plan);
/* restore.c: a state written unsealed by this world (slots.c), size bytes and its tail,
 * loaded as rg_world_restore loads a snapshot but without the checks of its values and
 * structure (the header and scalars are checked all the same). */
rg_status restore_kept(rg_world *w, const void *data, size_t size);

#endif
