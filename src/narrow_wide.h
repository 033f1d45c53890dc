/* narrow_wide.h: what the narrowphase's decision returns (narrow.c), and its measurement and
 * decision of eight contacts at once in AVX2 registers (narrow_wide.c) for the common case:
 * two boxes or two circles, continuous collision, no one-way body, no pass-through, no
 * sensor, no pre-solve hook.  Lane by lane the same operations as the scalar code on the same
 * values (no FMA; min and max as `a < b ? a : b`, which minps and maxps are), so the same
 * results: the state hash of the build without it (RG_NO_DISPATCH: make test's sse2 variant,
 * tools/snapshot.mk) and the pinned hashes of tests/test_determinism.c hold with it. */
#ifndef RG_NARROW_WIDE_H
#define RG_NARROW_WIDE_H

#include <stdint.h>

#include "dispatch.h"
#include "state.h"

#define COS45       RG_R(0.70710678)

/* What a contact's decision found, for the commit (contact.decided). */
#define ND_STAGE    1u  /* solved: stage its row */
#define ND_BEGIN    2u  /* began touching */
#define ND_END      4u  /* stopped touching */
#define ND_NOW      8u  /* touching after the step */
#define ND_WAS     16u  /* touching before it */
#define ND_GROUND_A 32u /* its surface grounds a (touching, a's gravity against the normal) */
#define ND_GROUND_B 64u
#define ND_SENSOR  128u /* a sensor pair: sense.c decides its touching where the step ends */

/* The wide path is built where dispatch.h's RG_AVX2_PATHS is 1 and picked per step from the
 * CPU (narrow_wide_ready); RG_NO_DISPATCH and the double build have the scalar code alone. */

#define NARROW_WIDE_LANES 8

/* Whether this step may use narrow_wide_decide: the CPU has AVX2, the collision is
 * continuous and no pre-solve hook is set (every pair would be decided in order). */
int narrow_wide_ready(const struct rg_world *w);

/* Eight lanes of contacts and their bodies' views: lane l's contact flags, its bodies' kinds
 * and views; a lane with CT_ACTIVE in its flags (none has it between measurements) is not a
 * contact and is skipped. */
typedef struct narrow_lanes {
    uint32_t flags[NARROW_WIDE_LANES];
    int32_t kind_a[NARROW_WIDE_LANES], kind_b[NARROW_WIDE_LANES];
    const cbody *a[NARROW_WIDE_LANES], *b[NARROW_WIDE_LANES];
    uint32_t asleep; /* lanes with a movable body that the step began with asleep: decided
                      * one by one (narrow.c's narrow_decide) */
} narrow_lanes;

/* Where narrow_wide_decide stages the rows of a block it decides whole: the lanes' dense
 * body indices and contact ids, the step, the destination (the step's rows on one thread, a
 * block's place in the spare rows with workers: narrow.c).  `staged` says it did: the rows
 * resolve.h's resolve_stage writes, with the same values, for the lanes with ND_STAGE in lane
 * order (and pmin and pp, which resolve_stage leaves and the solve sets before it reads them,
 * 0). */
typedef struct narrow_wide_stage {
    const struct collide_step *x;
    solver_dest d;
    const int32_t *ia, *ib, *id;
    int staged;
} narrow_wide_stage;

/* The contacts c[l] of the lanes in: those of the common case are measured and decided as
 * narrow.c's narrow_measure then narrow_decide (not in order) would, writing the same fields
 * of the contact, their ND_* bits in bits[l]; returns the mask of the lanes done.  The others
 * (another pair of kinds, a flag of the rare cases, or a pair apart and fast, which takes the
 * time of impact) are left untouched.  With st, a block done whole is staged too. */
uint32_t narrow_wide_decide(const struct rg_world *w, const narrow_lanes *in, contact *const *c, uint32_t *bits,
                            narrow_wide_stage *st);

#endif
