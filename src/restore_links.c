/* restore_links.c: the checks of a snapshot's linked structures (restore_check.h): the
 * contacts with their bodies' lists and the awake list, the broadphase's members with their
 * bucket chains and level lists, the sleeping bodies' islands.
 *
 * A list is checked link by link where it lies: each next link leads to a node of the same
 * list that links back, so no two links lead to one node (it links back to one) and none to
 * a head (it links back to nothing); and there are as many links as nodes that are not
 * heads, so every node but a head has one link leading to it.  With no cycle (restore_acyclic,
 * along the indices that pass gathered), each node is then reached from one head, once:
 * following the links back from a node ends, and only at a head.  No list is walked from
 * its head: the walks were chains of dependent loads, one step per node, where the links
 * that can close a cycle (those that lead to a higher node) are few (a list grows at its
 * head, so a link leads to an older, lower node). */
#include "body.h"
#include "broadphase.h"
#include "contact.h"
#include "snapshot.h"
#include "restore_check.h"
#include "task.h"

#define BAD 0

/* A body's bit, beside its contacts' flags, for a body no contact may have. */
#define RESTORE_SHAPELESS 0x80u
typedef char restore_shapeless_is_no_contact_flag[(RESTORE_SHAPELESS &
                                                   (CT_TOUCHING | CT_SENSOR | CT_SOLVE | CT_CLOSING |
                                                    CT_ONEWAY | CT_PASS)) == 0 ? 1 : -1];

void restore_check_scratch_layout(mem_layout *l, void *ctx)
{
    restore_scratch *r = ctx;
    const snap_scalars *s = r->s;
    size_t checked = r->checked == RESTORE_CHECKED; /* a kept state needs the places alone, */
    size_t located = r->checked != RESTORE_KEPT;    /* the world's own also the levels and keys */
    /* first what starts at zero (restore_state clears it), then what is written whole */
    r->rec_of = mem_take(l, (size_t)s->ccap, sizeof(int32_t));
    r->member_of = mem_take(l, (size_t)s->bslots, sizeof(int32_t));
    r->bucket_head = mem_take(l, checked * (s->bucket_bits > 0 ? (size_t)1 << s->bucket_bits : 0), 1);
    r->huge_used = mem_take(l, checked * (size_t)s->n_huge, 1);
    r->active_used = mem_take(l, checked * (size_t)s->n_bp_active, 1);
    r->isl_in = mem_take(l, checked * (size_t)(s->n_moving - s->n_active), 1);
    r->zeroed = l->size;
    r->key = mem_take(l, located * (size_t)s->members, sizeof(uint64_t));
    r->level = mem_take(l, located * (size_t)s->members, sizeof(int16_t));
    r->body_bits = mem_take(l, checked * (size_t)s->count, 1);
    r->wakes = mem_take(l, checked * (size_t)s->clive, 1);
    r->node_next = mem_take(l, checked * 2 * (size_t)s->clive, sizeof(int32_t));
    r->chain_next = mem_take(l, checked * (size_t)s->members, sizeof(int32_t));
    r->level_next = mem_take(l, checked * (size_t)s->members, sizeof(int32_t));
    r->box = mem_take(l, checked * 4 * (size_t)s->members, sizeof(rg_real));
    r->isl_next = mem_take(l, checked * (size_t)(s->n_moving - s->n_active), sizeof(int32_t));
}

/* ---------------------------------------------------------------- on the task system */

/* The passes that read the snapshot and write their items' own places alone run on the
 * world's task system, each range reporting what it finds (a broken invariant, counts) in
 * its worker's own slot, joined after; what marks a place that another item may name (a
 * slot or an id taken once) stays on one thread, so that a forged snapshot cannot make two
 * threads write one place.  What a check decides does not depend on the ranges. */
enum { RESTORE_BODY_BITS, RESTORE_RECORDS, RESTORE_LIST_LINKS, RESTORE_BOXES, RESTORE_MEMBER_LINKS };
#define RESTORE_RANGE 32

typedef struct restore_pass {
    const snap_in *in;
    restore_scratch *r;
    int what;
    uint8_t bad[RG_MAX_WORKERS];
    int32_t sums[RG_MAX_WORKERS][4]; /* RESTORE_RECORDS: touching, with an awake body;
                                      * RESTORE_LIST_LINKS and RESTORE_MEMBER_LINKS: links
                                      * and heads (of the chains, then of the levels) */
} restore_pass;

static void restore_body_bits(const snap_in *in, uint8_t *bits, int32_t i0, int32_t i1);
static int restore_records_range(const snap_in *in, restore_scratch *r, int32_t k0, int32_t k1, int32_t *touching,
                                 int32_t *should_wake);
static int restore_list_links_range(const snap_in *in, restore_scratch *r, int32_t k0, int32_t k1, int32_t *counts);
static int restore_boxes_range(const snap_in *in, restore_scratch *r, int32_t k0, int32_t k1);
static int restore_member_links_range(const snap_in *in, restore_scratch *r, int32_t k0, int32_t k1,
                                      int32_t *counts);

static void restore_pass_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    restore_pass *p = context;
    int bad = 0;
    switch (p->what) {
    case RESTORE_BODY_BITS: restore_body_bits(p->in, p->r->body_bits, begin, end); break;
    case RESTORE_RECORDS:
        bad = restore_records_range(p->in, p->r, begin, end, &p->sums[worker][0], &p->sums[worker][1]);
        break;
    case RESTORE_LIST_LINKS: bad = restore_list_links_range(p->in, p->r, begin, end, p->sums[worker]); break;
    case RESTORE_BOXES: bad = restore_boxes_range(p->in, p->r, begin, end); break;
    default: bad = restore_member_links_range(p->in, p->r, begin, end, p->sums[worker]); break;
    }
    if (bad) p->bad[worker] = 1;
}

/* Pass `what` over count items; 1 when no range found a broken invariant (and sums, when
 * given, the pass's four counts added to it). */
static int restore_spread(rg_world *w, const snap_in *in, restore_scratch *r, int what, int32_t count, int32_t *sums)
{
    restore_pass p;
    int32_t workers = task_workers(w);
    p.in = in;
    p.r = r;
    p.what = what;
    memset(p.bad, 0, (size_t)workers);
    memset(p.sums, 0, (size_t)workers * sizeof p.sums[0]);
    task_for(w, restore_pass_range, count, RESTORE_RANGE, &p);
    int ok = 1;
    for (int32_t k = 0; k < workers; k++) {
        ok &= !p.bad[k];
        if (sums != NULL)
            for (int c = 0; c < 4; c++) sums[c] += p.sums[k][c];
    }
    return ok;
}

/* Links per block of restore_acyclic's search for walks to start: a whole block without one
 * is passed in a loop of a known count, which the compiler vectorises. */
#define ACYCLIC_BLOCK 256

/* Whether a link of the block at b leads to a node not below its own. */
static int restore_block_up(const int32_t *restrict next, int32_t b)
{
    const int32_t *p = next + b;
    int32_t up = 0;
    for (int32_t j = 0; j < ACYCLIC_BLOCK; j++) up |= p[j] >= b + j;
    return up;
}

int restore_acyclic(int32_t *next, int32_t n)
{
    int32_t mark = -4; /* below every end (-1) and no-node (-3) */
    for (int32_t b = 0; b < n; b += ACYCLIC_BLOCK) {
        int32_t e = n - b > ACYCLIC_BLOCK ? b + ACYCLIC_BLOCK : n;
        if (e - b == ACYCLIC_BLOCK && !restore_block_up(next, b)) continue;
        for (int32_t s = b; s < e; s++) {
            if (next[s] < s) continue; /* an end, a lower node, or passed by a walk */
            for (int32_t at = s; at >= 0;) {
                int32_t to = next[at];
                if (to == mark) return BAD;
                next[at] = mark;
                at = to;
            }
            mark--;
        }
    }
    return 1;
}

/* ---------------------------------------------------------------- contacts */

/* The int fields of a live contact record. */
enum { CT_ID, CT_SA, CT_SB, CT_NA, CT_PA, CT_NB, CT_PB, CT_FLAGS };

static inline const uint8_t *ct_rec(const snap_in *in, int32_t k) { return rec(in, in->l.contacts, SNAP_CONTACT, k); }
static inline int32_t ct_at(const uint8_t *q, int field) { return (int32_t)snap_get32(q + 4 * field); }

/* Per body what its contacts take from it (their sensor and one-way flags) and whether it
 * has no shape: one byte to read per body of a contact instead of four fields.  A column at
 * a time, a uniform one once: the loops of a known stride vectorise. */
static uint32_t restore_sensor_bit(uint32_t cflags) { return (cflags & CF_SENSOR) ? CT_SENSOR : 0; }
static uint32_t restore_shapeless_bit(int32_t shape) { return shape == RG_SHAPE_NONE ? RESTORE_SHAPELESS : 0; }

static void restore_body_bits(const snap_in *in, uint8_t *restrict bits, int32_t i0, int32_t i1)
{
    snap_col cf = col_of(in, SNAP_F_cflags), ox = col_of(in, SNAP_F_owx), oy = col_of(in, SNAP_F_owy);
    snap_col shape = col_of(in, SNAP_F_shape);
    uint32_t base = 0;
    if (cf.stride == 0) base |= restore_sensor_bit(snap_get32(cf.p));
    if (shape.stride == 0) base |= restore_shapeless_bit(col_i32(shape, 0));
    if (ox.stride == 0 && oy.stride == 0 && (col_real(ox, 0) != 0 || col_real(oy, 0) != 0)) base |= CT_ONEWAY;
    for (int32_t i = i0; i < i1; i++) bits[i] = (uint8_t)base;
    if (cf.stride != 0) {
        const uint8_t *restrict p = cf.p;
        for (int32_t i = i0; i < i1; i++) bits[i] |= (uint8_t)restore_sensor_bit(snap_get32(p + 4 * (size_t)i));
    }
    if (shape.stride != 0) {
        const uint8_t *restrict p = shape.p;
        for (int32_t i = i0; i < i1; i++)
            bits[i] |= (uint8_t)restore_shapeless_bit((int32_t)snap_get32(p + 4 * (size_t)i));
    }
    if (ox.stride != 0 || oy.stride != 0)
        for (int32_t i = i0; i < i1; i++)
            if (col_real(ox, i) != 0 || col_real(oy, i) != 0) bits[i] |= CT_ONEWAY;
}

/* Live records k0..k1-1: ascending ids (each above the one before it, record k0's above
 * record k0 - 1's), bodies that exist, have shapes and are in handle order, flags as the
 * bodies make them, links in range, reals finite, impulses bounded; 1 when one breaks them.
 * Counts the touching records and those with an awake body (wakes).  What the loop reads
 * of `in` and `r` is in locals first: a store of a byte (wakes) may alias anything, and the
 * compiler would read them again after each. */
static int restore_records_range(const snap_in *in, restore_scratch *r, int32_t k0, int32_t k1, int32_t *touching,
                                 int32_t *should_wake)
{
    const uint32_t valid = CT_TOUCHING | CT_SENSOR | CT_SOLVE | CT_CLOSING | CT_ONEWAY | CT_PASS;
    const real_sbits impulse = real_magnitude((rg_real)CONTACT_MAX_IMPULSE), big = real_magnitude((rg_real)REAL_MAX);
    const uint8_t *rec0 = rec(in, in->l.contacts, SNAP_CONTACT, 0), *bindex = in->p + in->l.bindex;
    const uint8_t *bgen = in->p + in->l.bgen, *body_bits = r->body_bits;
    uint8_t *wakes_of = r->wakes;
    const int32_t ccap = in->s.ccap, bslots = in->s.bslots, n_active = in->s.n_active;
    int32_t last = k0 > 0 ? ct_at(rec0 + SNAP_CONTACT * (size_t)(k0 - 1), CT_ID) : -1, nt = 0, nw = 0;
    for (int32_t k = k0; k < k1; k++) {
        const uint8_t *q = rec0 + SNAP_CONTACT * (size_t)k;
        int32_t id = ct_at(q, CT_ID), sa = ct_at(q, CT_SA), sb = ct_at(q, CT_SB);
        if (id <= last || id >= ccap) return 1; /* ascending ids */
        last = id;
        /* live bodies (restore_dense), distinct, in handle order: the tag is one, so by
         * generation, then slot */
        if ((uint32_t)sa >= (uint32_t)bslots || (uint32_t)sb >= (uint32_t)bslots) return 1;
        int32_t ia = (int32_t)snap_get32(bindex + 4 * (size_t)sa), ib = (int32_t)snap_get32(bindex + 4 * (size_t)sb);
        uint32_t ga = snap_get32(bgen + 4 * (size_t)sa), gb = snap_get32(bgen + 4 * (size_t)sb);
        if (ia < 0 || ib < 0 || !(ga < gb || (ga == gb && sa < sb))) return 1;
        uint32_t flags = (uint32_t)ct_at(q, CT_FLAGS), from_bodies = (uint32_t)body_bits[ia] | body_bits[ib];
        uint32_t bad = (flags & ~valid) != 0;
        bad |= (from_bodies & RESTORE_SHAPELESS) != 0;
        bad |= (flags & (CT_SENSOR | CT_ONEWAY)) != from_bodies;
        for (int f = CT_NA; f <= CT_PB; f++) {
            int32_t link = ct_at(q, f);
            bad |= (link < -1) | (link >= ccap);
        }
        /* the reals finite, the warm start's impulses within what the solve keeps (state.h) */
        const uint8_t *reals = q + 32;
        for (int f = 0; f < 8; f++) bad |= (uint32_t)real_out(real_get(reals + SNAP_REAL * (size_t)f), 0, big, big);
        bad |= (uint32_t)real_out(real_get(reals + SNAP_REAL * 8), 0, impulse, 0);
        bad |= (uint32_t)real_out(real_get(reals + SNAP_REAL * 9), 0, impulse, impulse);
        if (bad) return 1;
        uint32_t wakes = (uint32_t)(ia < n_active) | (uint32_t)(ib < n_active);
        wakes_of[k] = (uint8_t)wakes;
        nt += (flags & CT_TOUCHING) != 0;
        nw += (int32_t)wakes;
    }
    *touching += nt;
    *should_wake += nw;
    return 0;
}

/* Records k0..k1-1's next nodes in their bodies' lists (node 2k + side is record k in the
 * list of its body a, side 0, or b, side 1): each a node of the same body's list that links
 * back; and a node that links back to nothing is its body's head; 1 when one is not.
 * Counts the links (counts[0]) and the heads (counts[1]). */
static int restore_list_links_range(const snap_in *in, restore_scratch *r, int32_t k0, int32_t k1, int32_t *counts)
{
    const uint8_t *rec0 = ct_rec(in, 0), *bindex = in->p + in->l.bindex;
    const int32_t *rec_of = r->rec_of;
    snap_col chead = col_of(in, SNAP_F_chead);
    int32_t *next = r->node_next;
    int32_t links = 0, heads = 0;
    for (int32_t k = k0; k < k1; k++) {
        const uint8_t *q = rec0 + SNAP_CONTACT * (size_t)k;
        int32_t id = ct_at(q, CT_ID);
        for (int side = 0; side < 2; side++) {
            int32_t slot = ct_at(q, side ? CT_SB : CT_SA), n = ct_at(q, side ? CT_NB : CT_NA), to = -1;
            if (ct_at(q, side ? CT_PB : CT_PA) == -1) {
                /* the body is live (restore_records_range) */
                if (col_i32(chead, (int32_t)snap_get32(bindex + 4 * (size_t)slot)) != id + 1) return 1;
                heads++;
            }
            if (n >= 0) { /* in range (restore_records_range) */
                links++;
                int32_t rn = rec_of[n];
                if (rn <= 0) return 1;
                const uint8_t *d = rec0 + SNAP_CONTACT * (size_t)(rn - 1);
                int32_t da = ct_at(d, CT_SA), db = ct_at(d, CT_SB), dside = db == slot;
                if ((da != slot && db != slot) || ct_at(d, dside ? CT_PB : CT_PA) != id) return 1;
                to = 2 * (rn - 1) + dside;
            }
            next[2 * k + side] = to;
        }
    }
    counts[0] += links;
    counts[1] += heads;
    return 0;
}

/* Each body's list: its contacts, each once, linked both ways (restore_list_links_range,
 * whose links and heads are counts[0] and counts[1]); all lists together hold every live
 * contact twice: each head a node of its body's that the body names (that pass), as many
 * bodies naming a head as there are heads (so each names one), as many links as nodes that
 * head no list, and no cycle. */
static int restore_check_lists(const snap_in *in, restore_scratch *r, const int32_t *counts)
{
    snap_col chead = col_of(in, SNAP_F_chead);
    const int32_t count = in->s.count, nodes = 2 * in->s.clive;
    int32_t named = 0;
    if (chead.stride == 0)
        named = col_i32(chead, 0) > 0 ? count : 0;
    else
        for (int32_t i = 0; i < count; i++) named += (int32_t)snap_get32(chead.p + 4 * (size_t)i) > 0;
    return named == counts[1] && counts[0] == nodes - counts[1] && restore_acyclic(r->node_next, nodes);
}

int restore_check_contacts(rg_world *w, const snap_in *in, restore_scratch *r)
{
    const snap_scalars *s = &in->s;
    int32_t sums[4] = { 0, 0, 0, 0 };
    restore_spread(w, in, r, RESTORE_BODY_BITS, s->count, NULL);
    if (!restore_spread(w, in, r, RESTORE_RECORDS, s->clive, sums)) return BAD;
    if (sums[0] != s->n_touching || sums[1] != s->n_awake) return BAD;
    /* the ids ascend below ccap: each record in its place, on one thread all the same (a
     * place marked by two threads would be a race, were the ids forged) */
    for (int32_t k = 0; k < s->clive; k++) r->rec_of[ct_at(ct_rec(in, k), CT_ID)] = k + 1;
    /* the free ids: the rest, each once */
    for (int32_t k = 0; k < s->ccap - s->clive; k++) {
        int32_t id = rd_i32(in, in->l.free, k);
        if (id < 0 || id >= s->ccap || r->rec_of[id] != 0) return BAD;
        r->rec_of[id] = -1;
    }
    /* the awake list: every contact with an awake body (as many as there are), each once */
    for (int32_t k = 0; k < s->n_awake; k++) {
        int32_t id = rd_i32(in, in->l.awake, k);
        if (id < 0 || id >= s->ccap || r->rec_of[id] <= 0 || !r->wakes[r->rec_of[id] - 1]) return BAD;
        r->rec_of[id] = -r->rec_of[id] - 2; /* listed; a second listing finds it negative */
    }
    for (int32_t k = 0; k < s->n_awake; k++) {
        int32_t id = rd_i32(in, in->l.awake, k);
        r->rec_of[id] = -(r->rec_of[id] + 2);
    }
    int32_t counts[4] = { 0, 0, 0, 0 };
    return restore_spread(w, in, r, RESTORE_LIST_LINKS, s->clive, counts) && restore_check_lists(in, r, counts);
}

/* ---------------------------------------------------------------- the broadphase */

/* A member's link (0 next, 1 prev, 2 lnext, 3 lprev), moved flag (4) or active place (5)
 * without reading the rest. */
static inline int32_t restore_link(const snap_in *in, int32_t k, int which)
{
    return (int32_t)snap_get32(rec(in, in->l.members, SNAP_MEMBER, k) + 4 + 4 * SNAP_REAL + 4 * (size_t)which);
}

/* Member k's next link along its chain (level_list 0) or level (1): the end (any negative),
 * or a member that is not huge, of k's bucket or level, linking back to k; its index, -1 at
 * the end, -2 when broken. */
static int32_t restore_next_member(const snap_in *in, const restore_scratch *r, int32_t k, int32_t slot,
                                   int level_list)
{
    int32_t n = restore_link(in, k, level_list ? 2 : 0);
    if (n < 0) return -1;
    if (n >= in->s.bslots || r->member_of[n] <= 0) return -2;
    int32_t kn = r->member_of[n] - 1;
    if (r->level[kn] == BP_HUGE || restore_link(in, kn, level_list ? 3 : 1) != slot) return -2;
    if (level_list) return r->level[kn] == r->level[k] ? kn : -2;
    int bits = in->s.bucket_bits;
    return broadphase_bucket(bits, r->key[kn]) == broadphase_bucket(bits, r->key[k]) ? kn : -2;
}

/* Members k0..k1-1's bodies, live and shaped, their moved flags and active places in range
 * (an awake body's member has one), and their boxes, finite and ordered, with their levels
 * and keys; 1 when one is not. */
static int restore_boxes_range(const snap_in *in, restore_scratch *r, int32_t k0, int32_t k1)
{
    rg_real *box = r->box;
    const int32_t n_active = in->s.n_active, n_bp_active = in->s.n_bp_active;
    snap_col shape = col_of(in, SNAP_F_shape);
    for (int32_t k = k0; k < k1; k++) {
        const uint8_t *m = rec(in, in->l.members, SNAP_MEMBER, k), *q = m + 4;
        int32_t i = restore_dense(in, (int32_t)snap_get32(m));
        int32_t moved = restore_link(in, k, 4), apos = restore_link(in, k, 5);
        if (i < 0 || col_i32(shape, i) == RG_SHAPE_NONE || (moved & ~1) != 0) return 1;
        if ((apos >= 0) != (i < n_active) || apos < -1 || apos >= n_bp_active) return 1;
        rg_real lx = snap_get_real(q), ly = snap_get_real(q + SNAP_REAL);
        rg_real ux = snap_get_real(q + 2 * SNAP_REAL), uy = snap_get_real(q + 3 * SNAP_REAL);
        if (!(rg_finite(lx) && rg_finite(ly) && rg_finite(ux) && rg_finite(uy) && lx <= ux && ly <= uy)) return 1;
        box[4 * k] = lx;
        box[4 * k + 1] = ly;
        box[4 * k + 2] = ux;
        box[4 * k + 3] = uy;
    }
    broadphase_locate_boxes(box + 4 * (size_t)k0, k1 - k0, r->level + k0, r->key + k0);
    return 0;
}

/* Members k0..k1-1's next links where they lie (-3: huge, in no list); 1 when one is
 * broken.  Counts the links and heads of the chains (counts[0], counts[1]) and of the
 * levels (counts[2], counts[3]). */
static int restore_member_links_range(const snap_in *in, restore_scratch *r, int32_t k0, int32_t k1,
                                      int32_t *counts)
{
    int32_t n[4] = { 0, 0, 0, 0 };
    for (int32_t k = k0; k < k1; k++) {
        if (r->level[k] == BP_HUGE) {
            r->chain_next[k] = r->level_next[k] = -3;
            continue;
        }
        int32_t slot = (int32_t)snap_get32(rec(in, in->l.members, SNAP_MEMBER, k));
        int32_t c = restore_next_member(in, r, k, slot, 0), l = restore_next_member(in, r, k, slot, 1);
        if (c == -2 || l == -2) return 1;
        r->chain_next[k] = c;
        r->level_next[k] = l;
        n[0] += c >= 0;
        n[1] += restore_link(in, k, 1) == -1;
        n[2] += l >= 0;
        n[3] += restore_link(in, k, 3) == -1;
    }
    for (int c = 0; c < 4; c++) counts[c] += n[c];
    return 0;
}

/* The broadphase: members are the shaped bodies, each once, awake ones in the active list;
 * every bucket chain and level list is a consistent doubly linked list of members of that
 * bucket or level, at most one per bucket or level, together holding each member once; the
 * huge indices, the active places and the move buffer are permutations of their members. */
int restore_check_broadphase(rg_world *w, const snap_in *in, restore_scratch *r)
{
    const snap_scalars *s = &in->s;
    int32_t huge = 0, moved = 0, active = 0;
    uint32_t level_seen = 0;
    /* the boxes first, and their levels and keys */
    if (!restore_spread(w, in, r, RESTORE_BOXES, s->members, NULL)) return BAD;
    /* the marks of what a member may share with another, on this thread: its slot, active
     * place, huge index, and bucket or level as a head (the rest is in range: the boxes'
     * pass) */
    for (int32_t k = 0; k < s->members; k++) {
        int32_t slot = (int32_t)snap_get32(rec(in, in->l.members, SNAP_MEMBER, k)), apos = restore_link(in, k, 5);
        if (r->member_of[slot] != 0) return BAD;
        r->member_of[slot] = k + 1;
        moved += restore_link(in, k, 4);
        if (apos >= 0) {
            if (r->active_used[apos]++) return BAD;
            active++;
        }
        if (r->level[k] == BP_HUGE) {
            int32_t at = restore_link(in, k, 0);
            if (at < 0 || at >= s->n_huge || r->huge_used[at]++) return BAD;
            huge++;
            continue;
        }
        if (restore_link(in, k, 1) == -1 && r->bucket_head[broadphase_bucket(s->bucket_bits, r->key[k])]++) return BAD;
        if (restore_link(in, k, 3) == -1) {
            if (level_seen & (1u << r->level[k])) return BAD; /* two lists of one level */
            level_seen |= 1u << r->level[k];
        }
    }
    if (huge != s->n_huge || moved != s->n_moved || active != s->n_bp_active) return BAD;
    /* every next link where it lies; as many links as members that head no chain (and no
     * level list), and no cycle (the file's opening comment) */
    int32_t counts[4] = { 0, 0, 0, 0 }, listed = s->members - s->n_huge;
    if (!restore_spread(w, in, r, RESTORE_MEMBER_LINKS, s->members, counts)) return BAD;
    if (counts[0] != listed - counts[1] || counts[2] != listed - counts[3] ||
        !restore_acyclic(r->chain_next, s->members) || !restore_acyclic(r->level_next, s->members))
        return BAD;
    /* the move buffer: members marked moved, each listed once (a listing flips the sign of
     * member_of; the load reads it through its absolute value) */
    for (int32_t k = 0; k < s->n_moved; k++) {
        int32_t slot = rd_i32(in, in->l.moved, k);
        if (slot < 0 || slot >= s->bslots || r->member_of[slot] <= 0) return BAD;
        if (restore_link(in, r->member_of[slot] - 1, 4) != 1) return BAD;
        r->member_of[slot] = -r->member_of[slot];
    }
    return 1;
}

/* The islands: each sleeping body's list head is a sleeping body heading its own list, and
 * the lists cover each sleeping body once.  As the contacts' lists (above): each next link
 * where it lies (a sleeping body of the same list that heads none), gathered as a dense
 * index; no two links lead to one body (a mark each, for these lists link one way), as many
 * links as bodies that head no list, and no cycle (restore_acyclic). */
int restore_check_islands(const snap_in *in, restore_scratch *r)
{
    /* what the loops read of `in` and `r` in locals: a store of a link may alias an int32_t
     * of either, and the compiler would read them again after each */
    const int32_t na = in->s.n_active, nm = in->s.n_moving, asleep = nm - na;
    const uint8_t *bindex = in->p + in->l.bindex;
    snap_col heads = col_of(in, SNAP_F_isl_head), nexts = col_of(in, SNAP_F_isl_next), slots = col_of(in, SNAP_F_slot);
    int32_t *next = r->isl_next;
    uint8_t *led = r->isl_in;
    int32_t links = 0, headed = 0;
    for (int32_t k = 0; k < asleep; k++) {
        /* in range (restore_body.c): head in [1, bslots], at in [0, bslots] */
        int32_t head = col_i32(heads, na + k), at = col_i32(nexts, na + k);
        int32_t j = (int32_t)snap_get32(bindex + 4 * (size_t)(head - 1)); /* restore_dense */
        if (j < na || j >= nm || col_i32(heads, j) != head) return BAD;
        headed += head == col_i32(slots, na + k) + 1;
        next[k] = -1;
        if (at == 0) continue;
        j = (int32_t)snap_get32(bindex + 4 * (size_t)(at - 1));
        if (j < na || j >= nm || col_i32(heads, j) != head || at == head || led[j - na]) return BAD;
        led[j - na] = 1;
        next[k] = j - na;
        links++;
    }
    return links == asleep - headed && restore_acyclic(next, asleep);
}
