/* restore_body.c: the checks of a snapshot's body fields (restore_check.h), column by
 * column: a rule over one field runs over the whole column in blocks the compiler
 * vectorises (one element when the field is uniform), a rule over several fields over the
 * rows (one row when all are uniform). */
#include "snapshot.h"
#include "vec2.h"
#include "restore_check.h"

static int restore_unit_or_zero(rg_real x, rg_real y)
{
    if (x == 0 && y == 0) return 1;
    rg_real len = rg_sqrt(x * x + y * y);
    return rg_finite(x) && rg_finite(y) && rg_fabs(len - 1) <= RG_R(1e-3);
}

/* Elements are checked in blocks of COL_BLOCK (a loop of known length, which vectorises at
 * -O2), then one by one. */
#define COL_BLOCK 16

/* Elements [b, e) of real field f within [lo, hi] (finite, hi >= 0). */
static int col_within(const snap_in *in, int f, int32_t b, int32_t e, rg_real lo, rg_real hi)
{
    const uint8_t *p = in->p + in->l.field[f];
    if (b >= e) return 1;
    if (in->l.stride[f] == 0) {
        rg_real v = snap_get_real(p);
        return v >= lo && v <= hi;
    }
    real_sbits pmin = lo > 0 ? real_magnitude(lo) : 0, plim = real_magnitude(hi);
    real_sbits nlim = lo < 0 ? real_magnitude(-lo) : lo == 0 ? 0 : -1;
    int bad = 0;
    int32_t i = b;
    for (; e - i >= COL_BLOCK; i += COL_BLOCK)
        for (int k = 0; k < COL_BLOCK; k++)
            bad |= real_out(real_get(p + SNAP_REAL * (size_t)(i + k)), pmin, plim, nlim);
    for (; i < e; i++) bad |= real_out(real_get(p + SNAP_REAL * (size_t)i), pmin, plim, nlim);
    return !bad;
}

/* Elements [b, e) of integer field f within [lo, hi]. */
static int col_range(const snap_in *in, int f, int32_t b, int32_t e, int32_t lo, int32_t hi)
{
    const uint8_t *p = in->p + in->l.field[f];
    if (b >= e) return 1;
    if (in->l.stride[f] == 0) {
        int32_t v = (int32_t)snap_get32(p);
        return v >= lo && v <= hi;
    }
    int bad = 0;
    int32_t i = b;
    for (; e - i >= COL_BLOCK; i += COL_BLOCK)
        for (int k = 0; k < COL_BLOCK; k++) {
            int32_t v = (int32_t)snap_get32(p + 4 * (size_t)(i + k));
            bad |= (v < lo) | (v > hi);
        }
    for (; i < e; i++) {
        int32_t v = (int32_t)snap_get32(p + 4 * (size_t)i);
        bad |= (v < lo) | (v > hi);
    }
    return !bad;
}

/* Elements [b, e) of integer field f with no bits outside `allowed`. */
static int col_bits(const snap_in *in, int f, int32_t b, int32_t e, uint32_t allowed)
{
    const uint8_t *p = in->p + in->l.field[f];
    if (b >= e) return 1;
    if (in->l.stride[f] == 0) return (snap_get32(p) & ~allowed) == 0;
    uint32_t bits = 0;
    int32_t i = b;
    for (; e - i >= COL_BLOCK; i += COL_BLOCK)
        for (int k = 0; k < COL_BLOCK; k++) bits |= snap_get32(p + 4 * (size_t)(i + k));
    for (; i < e; i++) bits |= snap_get32(p + 4 * (size_t)i);
    return (bits & ~allowed) == 0;
}

/* The end of rows [b, e) of a rule over several fields: b + 1 when all are uniform. */
static int32_t rows_end(int all_uniform, int32_t b, int32_t e) { return all_uniform && e > b ? b + 1 : e; }

/* The rules over several fields, on the reals' bits (real_out, as col_within) and without
 * branches: compares of reals and a branch per row made GCC keep flags in bytes on the
 * stack, and a byte stored and read back as a word stalls the loop.  Rows [0, end) in
 * blocks of COL_BLOCK, then one by one; inlined, with the strides known where no field is
 * uniform, they vectorise.  Each returns the rows' breaks in bit 0. */

/* A dynamic body's mass in [RG_MIN_MASS, RG_MAX_MASS]; a kinematic one's mass and gravity
 * scale 0. */
static inline uint32_t row_mass(snap_col type, snap_col mass, snap_col gs, int32_t i)
{
    const real_sbits lo = real_magnitude((rg_real)RG_MIN_MASS), hi = real_magnitude((rg_real)RG_MAX_MASS);
    real_bits m = col_bits_at(mass, i), g = col_bits_at(gs, i);
    uint32_t dynamic = 0u - (uint32_t)(col_i32(type, i) == RG_BODY_DYNAMIC);
    uint32_t out = (uint32_t)real_out(m, lo, hi, -1), nonzero = ((m | g) << 1) != 0; /* +-0 alone */
    return (dynamic & out) | (~dynamic & nonzero);
}

static inline uint32_t rows_mass(snap_col type, snap_col mass, snap_col gs, int32_t end)
{
    uint32_t wrong = 0;
    int32_t i = 0;
    for (; end - i >= COL_BLOCK; i += COL_BLOCK)
        for (int k = 0; k < COL_BLOCK; k++) wrong |= row_mass(type, mass, gs, i + k);
    for (; i < end; i++) wrong |= row_mass(type, mass, gs, i);
    return wrong;
}

/* A shape has sizes in range (a circle's two equal: in range, equal bits); no shape, no
 * sizes and no contacts.  *shaped counts the rows with a shape. */
static inline uint32_t row_shape(snap_col shape, snap_col hx, snap_col hy, snap_col chead, int32_t i, int32_t *shaped)
{
    const real_sbits lo = real_magnitude((rg_real)RG_MIN_SHAPE_SIZE), hi = real_magnitude((rg_real)RG_MAX_SHAPE_SIZE);
    int32_t sh = col_i32(shape, i);
    real_bits x = col_bits_at(hx, i), y = col_bits_at(hy, i);
    uint32_t none = 0u - (uint32_t)(sh == RG_SHAPE_NONE);
    uint32_t nonzero = (((x | y) << 1) != 0) | (col_i32(chead, i) != 0);
    uint32_t out =
        (uint32_t)(real_out(x, lo, hi, -1) | real_out(y, lo, hi, -1) | ((sh == RG_SHAPE_CIRCLE) & (x != y)));
    *shaped += (int32_t)(none + 1); /* 0 for none (all ones), else 1 */
    return (none & nonzero) | (~none & out);
}

static inline uint32_t rows_shape(snap_col shape, snap_col hx, snap_col hy, snap_col chead, int32_t end,
                                  int32_t *shaped)
{
    uint32_t wrong = 0;
    int32_t i = 0, count = 0;
    for (; end - i >= COL_BLOCK; i += COL_BLOCK)
        for (int k = 0; k < COL_BLOCK; k++) wrong |= row_shape(shape, hx, hy, chead, i + k, &count);
    for (; i < end; i++) wrong |= row_shape(shape, hx, hy, chead, i, &count);
    *shaped += count;
    return wrong;
}

/* Each rule as the setter it enters by checks it (rigid.h), over the partition it holds in
 * (active [0, n_active), asleep [n_active, n_moving), static [n_moving, count)). */
int restore_check_body_values(const snap_in *in)
{
    const snap_scalars *s = &in->s;
    int32_t n = s->count, na = s->n_active, nm = s->n_moving;
    const rg_real coord = (rg_real)(2 * RG_MAX_COORD), speed = (rg_real)RG_MAX_SPEED, force = (rg_real)RG_MAX_FORCE;
    const rg_real gmax = (rg_real)RG_MAX_GRAVITY_SCALE, drag = (rg_real)RG_MAX_DRAG, big = (rg_real)REAL_MAX;
    int ok = col_range(in, SNAP_F_type, 0, nm, RG_BODY_KINEMATIC, RG_BODY_DYNAMIC) &&
             col_range(in, SNAP_F_type, nm, n, RG_BODY_STATIC, RG_BODY_STATIC);
    /* positions and velocities in their ranges, as every step leaves them (bounds.c;
     * positions with room for the rounding of a move to the edge), the accelerations and
     * the positions of the step before finite; what the setters put, in their ranges */
    ok = ok && col_within(in, SNAP_F_x, 0, n, -coord, coord) && col_within(in, SNAP_F_y, 0, n, -coord, coord) &&
         col_within(in, SNAP_F_vx, 0, n, -speed, speed) && col_within(in, SNAP_F_vy, 0, n, -speed, speed) &&
         col_within(in, SNAP_F_ax, 0, n, -big, big) && col_within(in, SNAP_F_ay, 0, n, -big, big) &&
         col_within(in, SNAP_F_px, 0, n, -big, big) && col_within(in, SNAP_F_py, 0, n, -big, big) &&
         col_within(in, SNAP_F_fx, 0, n, -force, force) && col_within(in, SNAP_F_fy, 0, n, -force, force) &&
         col_within(in, SNAP_F_gscale, 0, n, -gmax, gmax);
    ok = ok && col_within(in, SNAP_F_drag_lin, 0, n, 0, drag) && col_within(in, SNAP_F_drag_quad, 0, n, 0, drag) &&
         col_within(in, SNAP_F_min_speed, 0, n, 0, speed) && col_within(in, SNAP_F_max_speed, 0, n, 0, speed) &&
         col_within(in, SNAP_F_fric, 0, n, 0, (rg_real)RG_MAX_FRICTION * (rg_real)RG_MAX_FORCE) && /* mu * N */
         col_within(in, SNAP_F_rest, 0, n, 0, 1) && col_within(in, SNAP_F_mu, 0, n, 0, (rg_real)RG_MAX_FRICTION) &&
         col_within(in, SNAP_F_sleep_t, 0, n, 0, big);
    ok = ok && col_range(in, SNAP_F_shape, 0, n, RG_SHAPE_NONE, RG_SHAPE_AABB) &&
         col_range(in, SNAP_F_shape, na, nm, RG_SHAPE_CIRCLE, RG_SHAPE_AABB) && /* a sleeper has a shape */
         col_range(in, SNAP_F_chead, 0, n, 0, s->ccap) &&
         col_bits(in, SNAP_F_cflags, 0, n, CF_SENSOR | CF_GROUNDED | CF_TELEPORTED);
    /* island links: on sleeping bodies only */
    ok = ok && col_range(in, SNAP_F_isl_head, 0, na, 0, 0) && col_range(in, SNAP_F_isl_next, 0, na, 0, 0) &&
         col_range(in, SNAP_F_isl_head, nm, n, 0, 0) && col_range(in, SNAP_F_isl_next, nm, n, 0, 0) &&
         col_range(in, SNAP_F_isl_head, na, nm, 1, s->bslots) && col_range(in, SNAP_F_isl_next, na, nm, 0, s->bslots);
    /* the static bodies have no mass and no gravity; a moving body has a mass when dynamic */
    ok = ok && col_within(in, SNAP_F_mass, nm, n, 0, 0) && col_within(in, SNAP_F_gscale, nm, n, 0, 0);
    if (!ok) return 0;
    /* the rules over several fields (rows_mass, rows_shape above) */
    uint32_t wrong = 0;
    {
        snap_col type = col_of(in, SNAP_F_type), mass = col_of(in, SNAP_F_mass), gs = col_of(in, SNAP_F_gscale);
        if (!col_uniform(in, SNAP_F_type) && !col_uniform(in, SNAP_F_mass) && !col_uniform(in, SNAP_F_gscale)) {
            type.stride = 4; /* known, so that the loop vectorises */
            mass.stride = gs.stride = SNAP_REAL;
            wrong |= rows_mass(type, mass, gs, nm);
        } else {
            wrong |= rows_mass(type, mass, gs,
                               rows_end(col_uniform(in, SNAP_F_type) && col_uniform(in, SNAP_F_mass) &&
                                            col_uniform(in, SNAP_F_gscale), 0, nm));
        }
    }
    {
        /* both within [0, max speed] (or -0): a limit above 0 has its sign clear and a
         * magnitude above 0, and magnitudes order them as their values */
        snap_col lo = col_of(in, SNAP_F_min_speed), hi = col_of(in, SNAP_F_max_speed);
        for (int32_t i = 0, end = rows_end(col_uniform(in, SNAP_F_min_speed) && col_uniform(in, SNAP_F_max_speed), 0, n);
             i < end; i++) {
            real_bits l = col_bits_at(lo, i), h = col_bits_at(hi, i);
            wrong |= (uint32_t)(((real_sbits)h > 0) & (real_bits_magnitude(h) < real_bits_magnitude(l)));
        }
    }
    {
        snap_col ox = col_of(in, SNAP_F_owx), oy = col_of(in, SNAP_F_owy);
        for (int32_t i = 0, end = rows_end(col_uniform(in, SNAP_F_owx) && col_uniform(in, SNAP_F_owy), 0, n); i < end; i++)
            wrong |= (uint32_t)!restore_unit_or_zero(col_real(ox, i), col_real(oy, i));
    }
    int32_t shaped = 0;
    {
        snap_col shape = col_of(in, SNAP_F_shape), hx = col_of(in, SNAP_F_hx), hy = col_of(in, SNAP_F_hy);
        snap_col chead = col_of(in, SNAP_F_chead);
        int all = col_uniform(in, SNAP_F_shape) && col_uniform(in, SNAP_F_hx) && col_uniform(in, SNAP_F_hy) &&
                  col_uniform(in, SNAP_F_chead);
        if (!col_uniform(in, SNAP_F_shape) && !col_uniform(in, SNAP_F_hx) && !col_uniform(in, SNAP_F_hy) &&
            !col_uniform(in, SNAP_F_chead)) {
            shape.stride = chead.stride = 4; /* known, so that the loop vectorises */
            hx.stride = hy.stride = SNAP_REAL;
            wrong |= rows_shape(shape, hx, hy, chead, n, &shaped);
        } else {
            wrong |= rows_shape(shape, hx, hy, chead, rows_end(all, 0, n), &shaped);
        }
        if (all && n > 0) shaped *= n;
    }
    return !(wrong & 1) && shaped == s->members;
}

