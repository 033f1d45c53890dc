/* broadphase.h: a hierarchical hashed grid of fat bounding boxes, keyed by body slot.
 *
 * Level L has square cells of side 2^L m (L in [BP_LEVEL_MIN, BP_LEVEL_MAX]); a box lives in
 * the finest level whose cell is larger than the box, in the one cell holding its lower
 * corner.  So a box overlapping a query box Q has its corner cell within one cell below Q's
 * and at most Q's upper cell: a query visits 2x2 to 3x3 cells per occupied level, whatever
 * the mix of sizes; a level with fewer members than the query has cells is walked as a list
 * instead (a few large platforms, a container's walls).  Cells hash (level, x, y) into one
 * bucket table of chains, so memory follows the member count, not the world's extent; the
 * hash is of integer cell coordinates, so iteration order never depends on addresses.
 * Members are updated in O(1) (unlink, relink); boxes too big for the coarsest level, or not
 * finite (a body thrown to infinity by an unstable scene), go into a short `huge` list every
 * query scans, and coordinates are clamped before any float-to-int conversion. */
#ifndef RG_BROADPHASE_H
#define RG_BROADPHASE_H

#include <stdint.h>

#include "mem.h"
#include "rigid.h"

#define BP_LEVEL_MIN (-10)
#define BP_LEVEL_MAX 20
#define BP_LEVELS (BP_LEVEL_MAX - BP_LEVEL_MIN + 1)
#define BP_HUGE BP_LEVELS /* level index of the huge list */

typedef struct bp_entry {
    rg_real lx, ly, ux, uy; /* fat box, m */
    uint64_t key;           /* packed level and lower-corner cell */
    int32_t next, prev;     /* bucket chain (slots; -1 ends); huge: next = index in huge[] */
    int32_t lnext, lprev;   /* the members of its level (slots; -1 ends); not for huge */
    int32_t member;         /* index in members[], -1 when not in the grid */
    int16_t level;          /* 0..BP_LEVELS-1, or BP_HUGE */
    int16_t moved;          /* 1 while in the move buffer */
    int32_t apos;           /* index in active[], -1 when not awake */
    uint32_t mark;          /* scratch for the pair search: == broadphase.mark when marked */
} bp_entry;

typedef struct broadphase {
    bp_entry *e;            /* per body slot, [0, cap) */
    int32_t *members;       /* slots in the grid, [0, count) */
    int32_t *huge;          /* slots in the huge list, [0, n_huge) */
    int32_t *moved;         /* move buffer: slots whose new pairs are still to be found */
    int32_t *active;        /* members that move (awake dynamic and kinematic), [0, n_active) */
    int32_t cap;
    int32_t count;
    int32_t n_huge;
    int32_t n_moved;
    int32_t n_active;
    uint32_t mark;          /* the current mark (bp_entry.mark), never 0 */
    int32_t *head;          /* bucket heads, 2^bucket_bits of them */
    int32_t bucket_bits;
    int32_t level_count[BP_LEVELS + 1];
    int32_t level_head[BP_LEVELS]; /* first member of each level, -1 when none */
    uint32_t levels;        /* bit li: level li has members */
} broadphase;

/* Makes room for slots [0, slots) and for `members` members; all-or-nothing. */
rg_status broadphase_reserve(broadphase *bp, const rg_mem *m, int32_t slots, int32_t members);
void broadphase_release(broadphase *bp, const rg_mem *m);
/* Inserts slot (not a member, after a reserve) with the given fat box. */
void broadphase_insert(broadphase *bp, int32_t slot, rg_real lx, rg_real ly, rg_real ux, rg_real uy);
/* Gives a member a new fat box. */
void broadphase_move(broadphase *bp, int32_t slot, rg_real lx, rg_real ly, rg_real ux, rg_real uy);
/* Removes a member (and drops it from the move buffer). */
void broadphase_remove(broadphase *bp, int32_t slot);
/* Adds a member to the move buffer (once). */
void broadphase_mark_moved(broadphase *bp, int32_t slot);
/* The members that move, kept apart so that per-step work follows them alone (a world of
 * static tiles, sleeping piles or bodies without shapes pays nothing for the rest). */
void broadphase_activate(broadphase *bp, int32_t slot);
void broadphase_deactivate(broadphase *bp, int32_t slot);

static inline int broadphase_contains(const broadphase *bp, int32_t slot)
{
    return slot < bp->cap && bp->e[slot].member >= 0;
}

/* Whether two members' fat boxes overlap (touching counts). */
static inline int broadphase_overlap(const broadphase *bp, int32_t s, int32_t t)
{
    const bp_entry *a = &bp->e[s], *b = &bp->e[t];
    return a->lx <= b->ux && b->lx <= a->ux && a->ly <= b->uy && b->ly <= a->uy;
}

/* A fresh mark for bp_entry.mark: no member carries it. */
static inline uint32_t broadphase_new_mark(broadphase *bp)
{
    if (++bp->mark == 0) {
        for (int32_t s = 0; s < bp->cap; s++) bp->e[s].mark = 0;
        bp->mark = 1;
    }
    return bp->mark;
}

/* ---- restoring a snapshot: the members' boxes and links are set from outside (restore.c
 * checks them), then the derived lists are rebuilt. */

/* The levels (or BP_HUGE) and cell keys of n fat boxes (box[4k .. 4k + 3]: lx, ly, ux, uy),
 * as insert and move compute them; in one loop, whose iterations the processor overlaps. */
void broadphase_locate_boxes(const rg_real *box, int32_t n, int16_t *level, uint64_t *key);
/* The bucket of a key in a table of 2^bits buckets (bits >= 1). */
uint32_t broadphase_bucket(int bits, uint64_t key);
/* Room for slots [0, slots), nothing else changed; all-or-nothing. */
rg_status broadphase_reserve_slots(broadphase *bp, const rg_mem *m, int32_t slots);
/* Empties the broadphase; with bits != its own, the bucket table becomes head (2^bits
 * entries allocated by the caller, or NULL with bits 0: none, as in a world that never had
 * a shape) and the old one is freed.  The entries of slots below nrewritten with
 * rewritten[slot] != 0 are left as they are, for the caller to set whole. */
void broadphase_clear(broadphase *bp, const rg_mem *m, int32_t *head, int bits, const int32_t *rewritten,
                      int32_t nrewritten);
/* After the entries of members[0, count) are set whole (box, level, key, member, chain and
 * level links, huge index in next, moved, apos, mark): their places in the bucket and level
 * heads, the huge and active lists and the level counts; count becomes theirs. */
void broadphase_restore_members(broadphase *bp, int32_t count);

/* Calls visit(ctx, slot) once for every member whose fat box overlaps [lx, ux] x [ly, uy]. */
typedef void (*bp_visit_fn)(void *ctx, int32_t slot);
void broadphase_query(const broadphase *bp, rg_real lx, rg_real ly, rg_real ux, rg_real uy,
                      bp_visit_fn visit, void *ctx);

/* Visits members whose fat box may meet the segment origin + t*d for t in [0, max_t]; visit
 * returns the new max_t (the closest hit so far), which prunes the rest.  A member may be
 * visited more than once. */
typedef rg_real (*bp_ray_fn)(void *ctx, int32_t slot, rg_real max_t);
void broadphase_raycast(const broadphase *bp, rg_vec2 origin, rg_vec2 d, bp_ray_fn visit, void *ctx);
/* The same for a box of half extents (hx, hy) swept along the segment (a shape cast); with
 * `once`, every member is visited at most once. */
void broadphase_sweep(const broadphase *bp, rg_vec2 origin, rg_vec2 d, rg_real hx, rg_real hy, int once,
                      bp_ray_fn visit, void *ctx);

#endif
