/* fuzz_api.c: libFuzzer harness over every entry point of rigid.h.
 *
 * The input is a sequence of operations, each a byte choosing the entry point followed by its
 * arguments: every real is a raw bit pattern or one of the edge values (NaN, infinities,
 * denormals, the float range's ends), every handle a live one, a stale one, another world's,
 * 0 or a forged one, every out pointer sometimes NULL, the world sometimes NULL.  Up to three
 * worlds live at once, each with the default allocator or one that fails from its Nth call.
 * After every operation the harness checks what the header promises, through the getters:
 *   - every live body's position, velocity, interpolated position and acceleration is finite;
 *   - the body and spring counts match the harness's own model of live handles, every live
 *     handle is valid and no stale or foreign handle is;
 *   - a handle is never issued twice, in one world or across worlds;
 *   - a call that returned an error (and any call on a const world) changed nothing
 *     observable: the observable state of every world is snapshotted before and compared
 *     bit for bit after;
 *   - after a step or an advance, the range guard's promise: every body within the ranges
 *     (positions give or take a shape's size), and rg_world_get_stopped's list live,
 *     ascending and, after rg_world_step, at rest (bodies without a shape);
 *   - a world with a task system (fuzz_api_tasks.c) takes every step exactly as a clone of it
 *     without one, and a crowd of up to 2,304 bodies, large enough that every stage splits,
 *     steps alike in two worlds built by the same calls, one with a task system;
 *   - outputs are sane (events a < b, query results live and ascending, ray fractions in
 *     [0, 1]), every allocator block is freed with the size it was allocated with, and a
 *     destroyed world leaves no block behind.
 * A violation aborts, so libFuzzer reports it with the input that caused it.  Library
 * findings awaiting their fix go to tests/fuzz/pending (make pending); none is tolerated
 * here. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_api.h"

/* ---------------------------------------------------------------- operations */

/* Out pointers: mostly real, sometimes NULL. */
#define OUT(in, var) ((u8(in) < 24) ? NULL : &(var))

enum {
    OP_CREATE_WORLD, OP_DESTROY_WORLD, OP_ARM_ALLOC, OP_MISC, OP_SET_GRAVITY, OP_GET_GRAVITY,
    OP_SET_WIND, OP_GET_WIND, OP_SET_INTEGRATOR, OP_GET_INTEGRATOR, OP_STEP, OP_SET_FIXED_STEP,
    OP_GET_FIXED_STEP, OP_ADVANCE, OP_GET_ALPHA, OP_GET_INTERP, OP_COUNTS, OP_BODY_CREATE,
    OP_BODY_DESTROY, OP_IS_VALID, OP_GET_TYPE, OP_GET_MASS, OP_SET_MASS, OP_GET_POSITION,
    OP_SET_POSITION, OP_GET_VELOCITY, OP_SET_VELOCITY, OP_GET_ACCEL, OP_APPLY_FORCE,
    OP_APPLY_IMPULSE, OP_GRAVITY_SCALE, OP_DRAG, OP_SURFACE_FRICTION, OP_SPEED_LIMITS,
    OP_SET_USER, OP_GET_USER, OP_SPRING_CREATE, OP_SPRING_DESTROY, OP_SPRING_VALID, OP_CIRCLE,
    OP_AABB, OP_CLEAR_SHAPE, OP_GET_SHAPE, OP_SET_RESTITUTION, OP_GET_RESTITUTION,
    OP_SET_FRICTION, OP_GET_FRICTION, OP_SET_SENSOR, OP_IS_SENSOR, OP_SET_FILTER, OP_GET_FILTER,
    OP_GROUNDED, OP_SET_SLEEPING, OP_GET_SLEEPING, OP_SET_SLEEP_THRESH, OP_GET_SLEEP_THRESH,
    OP_IS_AWAKE, OP_WAKE, OP_SET_ITER, OP_GET_ITER, OP_SET_TUNING, OP_GET_TUNING,
    OP_SET_CONTINUOUS, OP_GET_CONTINUOUS, OP_EVENTS, OP_RAYCAST, OP_QUERY, OP_DRAW,
    OP_STEP_SMALL, OP_BODY_CREATE_SHAPED, OP_SET_ONE_WAY, OP_GET_ONE_WAY, OP_PASS_THROUGH,
    OP_PRE_SOLVE, OP_CONTACTS, OP_RAYCAST_ALL, OP_QUERY_POINT, OP_CAST_SHAPE, OP_MOVE, OP_SAVE,
    OP_RESTORE, OP_HASH, OP_SET_TASKS, OP_POOL, OP_STOPPED, OP_CROWD, OP_BY_VALUE, OP_KEPT, OP_COUNT
};

static const char *const op_names[OP_COUNT] = {
    "create_world", "destroy_world", "arm_alloc", "status_version_real_size", "set_gravity",
    "get_gravity", "set_wind", "get_wind", "set_integrator", "get_integrator", "step",
    "set_fixed_step", "get_fixed_step", "advance", "get_alpha", "get_interpolated_position",
    "counts", "body_create", "body_destroy", "is_valid", "get_type", "get_mass", "set_mass",
    "get_position", "set_position", "get_velocity", "set_velocity", "get_acceleration",
    "apply_force", "apply_impulse", "set_gravity_scale", "set_drag", "set_surface_friction",
    "set_speed_limits", "set_user_data", "get_user_data", "spring_create", "spring_destroy",
    "spring_is_valid", "set_circle", "set_aabb", "clear_shape", "get_shape", "set_restitution",
    "get_restitution", "set_friction", "get_friction", "set_sensor", "is_sensor", "set_filter",
    "get_filter", "is_grounded", "set_sleeping", "get_sleeping", "set_sleep_thresholds",
    "get_sleep_thresholds", "is_awake", "wake", "set_solver_iterations",
    "get_solver_iterations", "set_contact_tuning", "get_contact_tuning", "set_continuous",
    "get_continuous", "contact_events", "raycast", "query_aabb", "draw", "step(1/60)",
    "body_create+shape", "set_one_way", "get_one_way", "pass_through", "set_pre_solve",
    "get_contacts", "raycast_all", "query_point", "cast_shape", "move", "save", "restore",
    "hash", "set_task_system", "thread_pool", "get_stopped", "crowd",
    "position/velocity by value", "kept_state"
};

/* Kept states: per world, the model of slots 0, 1 and RG_MAX_SLOTS - 1 when kept, and the
 * hash the world had then. */
#define KEPT 3
static fworld kept_model[NW][KEPT];
static uint64_t kept_hash[NW][KEPT];
static int kept_valid[NW][KEPT];

/* The world closed, and with it the model of its kept states (they are the world's own
 * memory: a later world in its place has none). */
static void forget_world(fworld *fw)
{
    world_close(fw);
    memset(kept_valid[fw - W], 0, sizeof kept_valid[0]);
}

static void create_world(input *in, fworld *fw)
{
    uint8_t how = u8(in);
    rg_world *w = NULL;
    rg_status st;
    forget_world(fw);
    if (how < 16) {                       /* the argument checks */
        if (rg_world_create(NULL) != RG_ERR_INVALID_ARGUMENT) FAIL("create(NULL)");
        if (rg_world_create_with_allocator(NULL, NULL, &w) != RG_ERR_INVALID_ARGUMENT || w != NULL)
            FAIL("create_with_allocator(NULL)");
        return;
    }
    if (how < 128) {
        st = rg_world_create(&w);
    } else {
        fw->al = (fz_alloc *)calloc(1, sizeof *fw->al);
        if (fw->al == NULL) abort();
        fw->al->fail_at = how < 192 ? -1 : (long)(u8(in) % 64);
        st = rg_world_create_with_allocator(fz_allocf, fw->al, &w);
    }
    if (st != RG_OK) {
        if (st != RG_ERR_OUT_OF_MEMORY || w != NULL) FAIL("world create: status %d", st);
        free(fw->al);
        fw->al = NULL;
        return;
    }
    fw->w = w;
    fw->serial = fw->identity = ++next_serial;
}

static void do_body_create(input *in, fworld *fw, int shaped)
{
    int32_t type = (int32_t)(u8(in) % 5) - 1;
    rg_real mass = real_arg(in);
    rg_vec2 pos = vec_arg(in);
    rg_body b = 12345, *out = OUT(in, b);
    rg_status st;
    if (fw->nlive >= MAXB) return;
    st = rg_body_create(fw->w, type, mass, pos, out);
    if (trace > 0) fprintf(stderr, "  type %d -> body %llx\n", (int)type, (unsigned long long)b);
    if (st == RG_OK) {
        if (fw->w == NULL || out == NULL) FAIL("body_create succeeded without a world or an out pointer");
        world_issued(fw, b);
        fw->live[fw->nlive++] = b;
        if (shaped) {
            rg_real r = (rg_real)((u8(in) % 16 + 1) * 0.25), h = r;
            int circle = u8(in) & 1;
            if (!circle) h = (rg_real)((u8(in) % 16 + 1) * 0.25);
            if (trace > 0) fprintf(stderr, "  %s %g %g\n", circle ? "circle" : "aabb", (double)r, (double)h);
            if (circle) (void)rg_body_set_circle(fw->w, b, r);
            else (void)rg_body_set_aabb(fw->w, b, r, h);
        }
    } else if (b != 12345) {
        FAIL("body_create failed (%d) but wrote the handle", st);
    }
}

static rg_status do_spring_create(input *in, fworld *fw)
{
    rg_body a = pick_body(in, fw), b = (u8(in) < 64) ? 0 : pick_body(in, fw);
    rg_vec2 anchor = vec_arg(in);
    rg_real rest = real_arg(in), k = real_arg(in), c = real_arg(in);
    uint64_t s = 777, *out = OUT(in, s);
    if (fw->nspring >= MAXS) return RG_OK;
    rg_status st = rg_spring_create(fw->w, a, b, anchor, rest, k, c, out);
    if (st == RG_OK) {
        if (!in_list(fw->live, fw->nlive, a) || (b != 0 && !in_list(fw->live, fw->nlive, b)) || a == b)
            FAIL("spring_create accepted bodies that are not two live bodies of the world");
        if (s == 0 || in_list(fw->spring, fw->nspring, s)) FAIL("spring handle reused");
        fw->spring[fw->nspring] = s;
        fw->sa[fw->nspring] = a;
        fw->sb[fw->nspring] = b;
        fw->nspring++;
    } else if (s != 777) {
        FAIL("spring_create failed but wrote the handle");
    }
    return st;
}

static void check_query(const fworld *fw, const rg_body *out, int32_t n, int32_t cap)
{
    if (n > fw->nlive) FAIL("query found %d of %d bodies", n, fw->nlive);
    for (int k = 0; k < n && k < cap; k++) {
        if (!in_list(fw->live, fw->nlive, out[k])) FAIL("query returned a body that is not live");
        if (k > 0 && !(out[k - 1] < out[k])) FAIL("query results not ascending");
    }
}

static void check_hit(const fworld *fw, int32_t n, const rg_ray_hit *hit)
{
    if (n != 1) return;
    if (!in_list(fw->live, fw->nlive, hit->body)) FAIL("ray hit a body that is not live");
    if (!(hit->fraction >= 0 && hit->fraction <= 1)) FAIL("ray fraction %g", (double)hit->fraction);
    if ((!finite2(hit->point) || !finite2(hit->normal))) FAIL("ray hit not finite");
}

/* ---- pre-solve: checks its arguments, and that the world is locked while it runs */

int32_t on_pre_solve(rg_body a, rg_body b, rg_vec2 normal, rg_real separation, void *user)
{
    fworld *fw = (fworld *)user;
    rg_vec2 p;
    tasks_check_thread();
    if (!(a < b)) FAIL("pre-solve: a >= b");
    if (!in_list(fw->live, fw->nlive, a) || !in_list(fw->live, fw->nlive, b))
        FAIL("pre-solve: a body that is not live");
    if ((!finite2(normal) || !isfinite(separation))) FAIL("pre-solve: not finite");
    if (rg_body_get_position(fw->w, a, &p) != RG_OK) FAIL("pre-solve: a getter failed");
    if (rg_body_set_position(fw->w, a, p) != RG_ERR_LOCKED) FAIL("pre-solve: set_position not locked");
    if (rg_world_step(fw->w, (rg_real)(1.0 / 60)) != RG_ERR_LOCKED) FAIL("pre-solve: step not locked");
    if (rg_body_destroy(fw->w, b) != RG_ERR_LOCKED) FAIL("pre-solve: destroy not locked");
    if (rg_world_set_task_system(fw->w, NULL) != RG_ERR_LOCKED) FAIL("pre-solve: set_task_system not locked");
    if (fw->presolve_calls++ == 0) rg_world_destroy(fw->w);   /* a no-op from inside */
    return (fw->presolve >> (fw->presolve_calls % 8)) & 1;
}

/* ---- snapshots: two slots, each with the model of the world as it was saved */

typedef struct saved {
    unsigned char *buf;
    size_t n;
    fworld model;
    int valid;
} saved;

static saved slots[2];
static int crowds;   /* crowd operations in this input */

static void hit_sane(const fworld *fw, const rg_ray_hit *h, int k)
{
    if (!in_list(fw->live, fw->nlive, h->body)) FAIL("hit %d: a body that is not live", k);
    if (!(h->fraction >= 0 && h->fraction <= 1)) FAIL("hit %d: fraction %g", k, (double)h->fraction);
    if ((!finite2(h->point) || !finite2(h->normal))) FAIL("hit %d: not finite", k);
}

static int32_t do_save(input *in, fworld *fw)
{
    saved *sl = &slots[u8(in) & 1];
    size_t n = 0, cap;
    rg_status st = rg_world_save(fw->w, NULL, 0, (u8(in) < 16) ? NULL : &n);
    if (st != RG_OK) return st;
    cap = (u8(in) < 32) ? n / 2 : n;   /* sometimes too small: nothing written past cap */
    unsigned char *buf = (unsigned char *)malloc(cap > 0 ? cap : 1);
    if (buf == NULL) abort();
    st = rg_world_save(fw->w, buf, cap, &n);
    if (st != RG_OK) {
        free(buf);
        if (cap >= n || st != RG_ERR_CAPACITY) FAIL("save into %zu bytes of %zu: status %d", cap, n, st);
        return st;
    }
    free(sl->buf);
    sl->buf = buf;
    sl->n = n;
    sl->model = *fw;
    sl->valid = 1;
    /* A fresh world restored from it answers the same handles and hashes alike. */
    rg_world *clone;
    uint64_t h1 = 0, h2 = 0;
    if (rg_world_create(&clone) != RG_OK) abort();
    st = rg_world_restore(clone, buf, n);
    if (st != RG_OK) FAIL("a fresh snapshot (%zu bytes) does not restore: status %d", n, st);
    if (rg_world_hash(fw->w, &h1) != RG_OK || rg_world_hash(clone, &h2) != RG_OK || h1 != h2)
        FAIL("a world and its restored clone hash differently");
    for (int k = 0; k < fw->nlive; k++) {
        rg_vec2 a, b;
        if (rg_body_get_position(clone, fw->live[k], &b) != RG_OK ||
            rg_body_get_position(fw->w, fw->live[k], &a) != RG_OK || memcmp(&a, &b, sizeof a) != 0)
            FAIL("the clone does not answer a handle as the original does");
    }
    rg_world_destroy(clone);
    return RG_OK;
}

/* After a restore: the world is the model's, but for what is its own (the allocator, the
 * pre-solve hook); bodies live before and not in the model are dead. */
static void adopt_model(fworld *fw, const fworld *model)
{
    for (int k = 0; k < fw->nlive; k++)
        if (!in_list(model->live, model->nlive, fw->live[k])) remember_dead(fw->live[k], fw);
    rg_world *w = fw->w;
    fz_alloc *al = fw->al;
    int presolve = fw->presolve;
    *fw = *model;
    fw->w = w;
    fw->al = al;
    fw->presolve = presolve;   /* the hook is the world's own, not saved */
    fw->serial = ++next_serial;
}

static int32_t do_restore(input *in, fworld *fw)
{
    saved *sl = &slots[u8(in) & 1];
    uint8_t how = u8(in);
    if (!sl->valid || fw->w == NULL) return rg_world_restore(fw->w, NULL, 0);
    size_t n = sl->n;
    unsigned char *data = (unsigned char *)malloc(n);
    if (data == NULL) abort();
    memcpy(data, sl->buf, n);
    int corrupt = how >= 128;
    if (how >= 192) {
        n = n * (size_t)u8(in) / 256;                  /* truncated */
    } else if (corrupt) {
        size_t at = ((size_t)u8(in) << 8 | u8(in)) % n;
        data[at] ^= (unsigned char)(u8(in) | 1);       /* one byte flipped */
    }
    rg_status st = tasks_restore(fw, data, n);
    free(data);
    if (st == RG_OK && corrupt) FAIL("a corrupted snapshot was accepted");
    if (st != RG_OK) return st;
    adopt_model(fw, &sl->model);
    return RG_OK;
}

/* Keeps (how 0; const), brings back (1) or drops (2; const) a slot, sometimes out of range. */
static int32_t do_kept(input *in, fworld *fw, int *is_const)
{
    static const int32_t slot_of[KEPT] = { 0, 1, RG_MAX_SLOTS - 1 };
    uint8_t how = u8(in) % 3, b = u8(in);
    int in_range = b >= 8, k = b % KEPT, wi = (int)(fw - W);
    int32_t slot = in_range ? slot_of[k] : (b & 1) ? -1 : RG_MAX_SLOTS;
    *is_const = how != 1;
    rg_status st = how == 0 ? rg_world_save_slot(fw->w, slot)
                 : how == 1 ? tasks_restore_slot(fw, slot)
                            : rg_world_drop_slot(fw->w, slot);
    if ((fw->w == NULL || !in_range) && st != RG_ERR_INVALID_ARGUMENT)
        FAIL("kept state %d of slot %ld: status %d, not INVALID_ARGUMENT", how, (long)slot, st);
    if (st != RG_OK) {
        if (st != RG_ERR_INVALID_ARGUMENT && st != RG_ERR_OUT_OF_MEMORY) FAIL("kept state %d: status %d", how, st);
        if (how == 1 && st == RG_ERR_INVALID_ARGUMENT && in_range && kept_valid[wi][k])
            FAIL("a kept state was refused: %s", rg_world_last_error(fw->w));
        return st;
    }
    if (how == 0) {
        kept_model[wi][k] = *fw;
        kept_valid[wi][k] = rg_world_hash(fw->w, &kept_hash[wi][k]) == RG_OK;
    } else if (how == 2) {
        kept_valid[wi][k] = 0;
    } else {
        uint64_t h = 0;
        if (!kept_valid[wi][k]) FAIL("an empty slot was restored");
        if (rg_world_hash(fw->w, &h) != RG_OK || h != kept_hash[wi][k]) FAIL("a kept state came back with another hash");
        adopt_model(fw, &kept_model[wi][k]);
    }
    return RG_OK;
}

/* Runs one operation; returns its status (< 0: an error) and whether it steps. */
static int32_t run_op(input *in, int op, int *is_step, int *is_const)
{
    fworld *fw = pick_world(in);
    rg_world *w = fw->w;
    if (trace) fprintf(stderr, "op %d %s on world %d\n", op_no, op_name, (int)(fw - W));
    rg_vec2 v = { 0, 0 };
    rg_real r[4] = { 0, 0, 0, 0 };
    int32_t i[2] = { 0, 0 }, st = RG_OK;
    uint32_t u[2] = { 0, 0 };
    uint64_t u64v = 0;
    rg_body b;
    *is_step = RAN_OTHER;
    *is_const = 0;
    switch (op) {
    case OP_CREATE_WORLD: create_world(in, fw); return RG_OK;
    case OP_DESTROY_WORLD:
        if (u8(in) < 16) rg_world_destroy(NULL);
        else forget_world(fw);
        return RG_OK;
    case OP_ARM_ALLOC:
        if (fw->al != NULL) fw->al->fail_at = (u8(in) < 64) ? -1 : fw->al->calls + (long)(u8(in) % 32);
        return RG_OK;
    case OP_MISC:
        *is_const = 1;
        if (rg_status_string(int_arg(in)) == NULL) FAIL("status string NULL");
        if (rg_version() != RG_VERSION || rg_real_size() != (int32_t)sizeof(rg_real)) FAIL("version");
        return RG_OK;
    case OP_SET_GRAVITY: return rg_world_set_gravity(w, vec_arg(in));
    case OP_GET_GRAVITY: *is_const = 1; return rg_world_get_gravity(w, OUT(in, v));
    case OP_SET_WIND: return rg_world_set_wind(w, vec_arg(in));
    case OP_GET_WIND: *is_const = 1; return rg_world_get_wind(w, OUT(in, v));
    case OP_SET_INTEGRATOR: return rg_world_set_integrator(w, int_arg(in));
    case OP_GET_INTEGRATOR: *is_const = 1; return rg_world_get_integrator(w, OUT(in, i[0]));
    case OP_STEP: *is_step = RAN_STEP; return tasks_step(fw, 0, real_arg(in), NULL);
    case OP_STEP_SMALL: *is_step = RAN_STEP; return tasks_step(fw, 0, (rg_real)(1.0 / 60), NULL);
    case OP_SET_FIXED_STEP: {
        rg_real dt = real_arg(in);
        return rg_world_set_fixed_step(w, dt, int_arg(in));
    }
    case OP_GET_FIXED_STEP: *is_const = 1; return rg_world_get_fixed_step(w, OUT(in, r[0]), OUT(in, i[0]));
    case OP_ADVANCE: {
        rg_real t = real_arg(in), fdt = 0;
        int32_t steps = -7, *out = OUT(in, steps), max = 0;
        *is_step = RAN_ADVANCE;
        /* An advance takes the steps the caller allowed (max_steps_per_advance may be 2^31):
         * work asked for, not a finding.  Keep each to 256 steps. */
        if (w != NULL && rg_world_get_fixed_step(w, &fdt, &max) == RG_OK && max > 256 &&
            (double)t / (double)fdt > 256)
            return RG_OK;
        st = tasks_step(fw, 1, t, out);
        if (st == RG_OK && out != NULL && steps < 0) FAIL("advance took %d steps", steps);
        return st;
    }
    case OP_GET_ALPHA:
        *is_const = 1;
        st = rg_world_get_alpha(w, OUT(in, r[0]));
        if (st == RG_OK && !(r[0] >= 0)) FAIL("alpha %g", (double)r[0]);
        return st;
    case OP_GET_INTERP: *is_const = 1; return rg_body_get_interpolated_position(w, pick_body(in, fw), OUT(in, v));
    case OP_COUNTS:
        *is_const = 1;
        if (rg_world_body_count(NULL) != 0 || rg_world_spring_count(NULL) != 0 ||
            rg_world_awake_body_count(NULL) != 0 || rg_world_touching_count(NULL) != 0)
            FAIL("a count of the NULL world is not 0");
        return RG_OK;
    case OP_BODY_CREATE: do_body_create(in, fw, 0); return RG_OK;
    case OP_BODY_CREATE_SHAPED: do_body_create(in, fw, 1); return RG_OK;
    case OP_BODY_DESTROY:
        b = pick_body(in, fw);
        st = rg_body_destroy(w, b);
        if (st == RG_OK) {
            if (!in_list(fw->live, fw->nlive, b)) FAIL("destroyed a body the model does not have");
            body_gone(fw, b);
        }
        return st;
    case OP_IS_VALID: {
        *is_const = 1;
        b = pick_body(in, fw);
        int32_t valid = rg_body_is_valid(w, b);
        if (valid != in_list(fw->live, fw->nlive, b)) FAIL("is_valid %d for a handle the model says %d", valid, !valid);
        return RG_OK;
    }
    case OP_GET_TYPE: *is_const = 1; return rg_body_get_type(w, pick_body(in, fw), OUT(in, i[0]));
    case OP_GET_MASS: *is_const = 1; return rg_body_get_mass(w, pick_body(in, fw), OUT(in, r[0]));
    case OP_SET_MASS: b = pick_body(in, fw); return rg_body_set_mass(w, b, real_arg(in));
    case OP_GET_POSITION: *is_const = 1; return rg_body_get_position(w, pick_body(in, fw), OUT(in, v));
    case OP_SET_POSITION: b = pick_body(in, fw); return rg_body_set_position(w, b, vec_arg(in));
    case OP_GET_VELOCITY: *is_const = 1; return rg_body_get_velocity(w, pick_body(in, fw), OUT(in, v));
    case OP_SET_VELOCITY: b = pick_body(in, fw); return rg_body_set_velocity(w, b, vec_arg(in));
    case OP_BY_VALUE: { /* the by-value getters give what the out-pointer ones give, or NaN */
        *is_const = 1;
        b = pick_body(in, fw);
        int vel = u8(in) & 1;
        rg_vec2 got = vel ? rg_body_velocity(w, b) : rg_body_position(w, b), want;
        st = vel ? rg_body_get_velocity(w, b, &want) : rg_body_get_position(w, b, &want);
        if (st == RG_OK ? !(got.x == want.x && got.y == want.y) : !(got.x != got.x && got.y != got.y))
            FAIL("by-value %s (%g, %g) against status %d (%g, %g)", vel ? "velocity" : "position",
                 (double)got.x, (double)got.y, (int)st, (double)want.x, (double)want.y);
        return st;
    }
    case OP_GET_ACCEL: *is_const = 1; return rg_body_get_acceleration(w, pick_body(in, fw), OUT(in, v));
    case OP_APPLY_FORCE: b = pick_body(in, fw); return rg_body_apply_force(w, b, vec_arg(in));
    case OP_APPLY_IMPULSE: b = pick_body(in, fw); return rg_body_apply_impulse(w, b, vec_arg(in));
    case OP_GRAVITY_SCALE: b = pick_body(in, fw); return rg_body_set_gravity_scale(w, b, real_arg(in));
    case OP_DRAG:
        b = pick_body(in, fw);
        r[0] = real_arg(in);
        return rg_body_set_drag(w, b, r[0], real_arg(in));
    case OP_SURFACE_FRICTION:
        b = pick_body(in, fw);
        r[0] = real_arg(in);
        return rg_body_set_surface_friction(w, b, r[0], real_arg(in));
    case OP_SPEED_LIMITS:
        b = pick_body(in, fw);
        r[0] = real_arg(in);
        return rg_body_set_speed_limits(w, b, r[0], real_arg(in));
    case OP_SET_USER: b = pick_body(in, fw); return rg_body_set_user_data(w, b, u64(in));
    case OP_GET_USER: *is_const = 1; return rg_body_get_user_data(w, pick_body(in, fw), OUT(in, u64v));
    case OP_SPRING_CREATE: return do_spring_create(in, fw);
    case OP_SPRING_DESTROY: {
        uint64_t s = pick_spring(in, fw);
        st = rg_spring_destroy(w, s);
        if (st == RG_OK) {
            int k;
            for (k = 0; k < fw->nspring && fw->spring[k] != s; k++) {}
            if (k == fw->nspring) FAIL("destroyed a spring the model does not have");
            fw->nspring--;
            fw->spring[k] = fw->spring[fw->nspring];
            fw->sa[k] = fw->sa[fw->nspring];
            fw->sb[k] = fw->sb[fw->nspring];
        }
        return st;
    }
    case OP_SPRING_VALID: {
        *is_const = 1;
        uint64_t s = pick_spring(in, fw);
        if (rg_spring_is_valid(w, s) != in_list(fw->spring, fw->nspring, s)) FAIL("spring_is_valid disagrees with the model");
        return RG_OK;
    }
    case OP_CIRCLE: b = pick_body(in, fw); return rg_body_set_circle(w, b, real_arg(in));
    case OP_AABB:
        b = pick_body(in, fw);
        r[0] = real_arg(in);
        return rg_body_set_aabb(w, b, r[0], real_arg(in));
    case OP_CLEAR_SHAPE: return rg_body_clear_shape(w, pick_body(in, fw));
    case OP_GET_SHAPE: *is_const = 1; b = pick_body(in, fw); return rg_body_get_shape(w, b, OUT(in, i[0]), OUT(in, v));
    case OP_SET_RESTITUTION: b = pick_body(in, fw); return rg_body_set_restitution(w, b, real_arg(in));
    case OP_GET_RESTITUTION: *is_const = 1; return rg_body_get_restitution(w, pick_body(in, fw), OUT(in, r[0]));
    case OP_SET_FRICTION: b = pick_body(in, fw); return rg_body_set_friction(w, b, real_arg(in));
    case OP_GET_FRICTION: *is_const = 1; return rg_body_get_friction(w, pick_body(in, fw), OUT(in, r[0]));
    case OP_SET_SENSOR: b = pick_body(in, fw); return rg_body_set_sensor(w, b, int_arg(in));
    case OP_IS_SENSOR: *is_const = 1; return rg_body_is_sensor(w, pick_body(in, fw), OUT(in, i[0]));
    case OP_SET_FILTER: b = pick_body(in, fw); u[0] = u32(in); return rg_body_set_filter(w, b, u[0], u32(in));
    case OP_GET_FILTER: *is_const = 1; b = pick_body(in, fw); return rg_body_get_filter(w, b, OUT(in, u[0]), OUT(in, u[1]));
    case OP_GROUNDED: *is_const = 1; return rg_body_is_grounded(w, pick_body(in, fw), OUT(in, i[0]));
    case OP_SET_SLEEPING: return rg_world_set_sleeping(w, int_arg(in));
    case OP_GET_SLEEPING: *is_const = 1; return rg_world_get_sleeping(w, OUT(in, i[0]));
    case OP_SET_SLEEP_THRESH: r[0] = real_arg(in); return rg_world_set_sleep_thresholds(w, r[0], real_arg(in));
    case OP_GET_SLEEP_THRESH: *is_const = 1; return rg_world_get_sleep_thresholds(w, OUT(in, r[0]), OUT(in, r[1]));
    case OP_IS_AWAKE: *is_const = 1; return rg_body_is_awake(w, pick_body(in, fw), OUT(in, i[0]));
    case OP_WAKE: return rg_body_wake(w, pick_body(in, fw));
    case OP_SET_ITER: i[0] = int_arg(in); return rg_world_set_solver_iterations(w, i[0], int_arg(in));
    case OP_GET_ITER: *is_const = 1; return rg_world_get_solver_iterations(w, OUT(in, i[0]), OUT(in, i[1]));
    case OP_SET_TUNING:
        for (int k = 0; k < 4; k++) r[k] = real_arg(in);
        return rg_world_set_contact_tuning(w, r[0], r[1], r[2], r[3]);
    case OP_GET_TUNING:
        *is_const = 1;
        return rg_world_get_contact_tuning(w, OUT(in, r[0]), OUT(in, r[1]), OUT(in, r[2]), OUT(in, r[3]));
    case OP_SET_CONTINUOUS: return rg_world_set_continuous(w, int_arg(in));
    case OP_GET_CONTINUOUS: *is_const = 1; return rg_world_get_continuous(w, OUT(in, i[0]));
    case OP_EVENTS: {
        *is_const = 1;
        int32_t cap = int_arg(in);
        rg_contact_event *out = NULL;
        if (cap > 0 && cap <= MAXEV && u8(in) >= 24) out = (rg_contact_event *)malloc((size_t)cap * sizeof *out);
        st = rg_world_get_contact_events(w, out, cap);
        free(out);
        if (w != NULL && st >= 0) check_events(fw);
        return st;
    }
    case OP_RAYCAST: {
        *is_const = 1;
        rg_ray_hit hit;
        rg_vec2 o = vec_arg(in), d = vec_arg(in);
        memset(&hit, 0, sizeof hit);
        st = rg_world_raycast(w, o, d, u32(in), OUT(in, hit));
        if (st > 1) FAIL("raycast returned %d", st);
        check_hit(fw, st, &hit);
        return st;
    }
    case OP_QUERY: {
        *is_const = 1;
        rg_vec2 lo = vec_arg(in), hi = vec_arg(in);
        uint32_t mask = u32(in);
        int32_t cap = int_arg(in);
        rg_body *out = NULL;
        if (cap > 0 && cap <= MAXB && u8(in) >= 24) out = (rg_body *)malloc((size_t)cap * sizeof *out);
        st = rg_world_query_aabb(w, lo, hi, mask, out, cap);
        if (st >= 0) check_query(fw, out, st, out != NULL ? cap : 0);
        free(out);
        return st;
    }
    case OP_DRAW: {
        *is_const = 1;
        uint8_t which = u8(in);
        rg_debug_draw d;
        d.circle = (which & 1) ? on_circle : NULL;
        d.box = (which & 2) ? on_box : NULL;
        d.segment = (which & 4) ? on_segment : NULL;
        d.point = (which & 8) ? on_point : NULL;
        d.flags = (u8(in) < 32) ? u32(in) : (uint32_t)(u8(in) & 31);
        d.user = NULL;
        draw_world = fw;
        return rg_world_draw(w, (which & 16) ? NULL : &d);
    }
    case OP_SET_ONE_WAY: b = pick_body(in, fw); return rg_body_set_one_way(w, b, vec_arg(in));
    case OP_GET_ONE_WAY: *is_const = 1; return rg_body_get_one_way(w, pick_body(in, fw), OUT(in, v));
    case OP_PASS_THROUGH: b = pick_body(in, fw); return rg_body_pass_through(w, b, pick_body(in, fw));
    case OP_PRE_SOLVE: {
        uint8_t mode = u8(in);
        st = rg_world_set_pre_solve(w, mode < 64 ? NULL : on_pre_solve, fw);
        if (st == RG_OK) fw->presolve = mode < 64 ? 0 : (mode | 1);
        return st;
    }
    case OP_CONTACTS: {
        *is_const = 1;
        b = pick_body(in, fw);
        int32_t cap = int_arg(in);
        rg_contact *out = NULL;
        if (cap > 0 && cap <= MAXB && u8(in) >= 24) out = (rg_contact *)malloc((size_t)cap * sizeof *out);
        st = rg_body_get_contacts(w, b, out, cap);
        for (int k = 0; st > 0 && out != NULL && k < st && k < cap; k++) {
            if (!in_list(fw->live, fw->nlive, out[k].other)) FAIL("contact with a body that is not live");
            if (k > 0 && !(out[k - 1].other < out[k].other)) FAIL("contacts not ascending");
            if (out[k].sensor != 0 && out[k].sensor != 1) FAIL("contact sensor %d", out[k].sensor);
            if ((!finite2(out[k].normal) || !finite2(out[k].point) ||
                                        !isfinite(out[k].separation) || !isfinite(out[k].normal_impulse)))
                FAIL("contact not finite");
        }
        free(out);
        return st;
    }
    case OP_RAYCAST_ALL: {
        *is_const = 1;
        rg_vec2 o = vec_arg(in), d = vec_arg(in);
        uint32_t mask = u32(in);
        int32_t cap = int_arg(in);
        rg_ray_hit *out = NULL;
        if (cap > 0 && cap <= MAXB && u8(in) >= 24) out = (rg_ray_hit *)malloc((size_t)cap * sizeof *out);
        st = rg_world_raycast_all(w, o, d, mask, out, cap);
        if (st > fw->nlive) FAIL("raycast_all hit %d of %d bodies", st, fw->nlive);
        for (int k = 0; st > 0 && out != NULL && k < st && k < cap; k++) {
            hit_sane(fw, &out[k], k);
            if (k > 0 && (out[k - 1].fraction > out[k].fraction ||
                          (out[k - 1].fraction == out[k].fraction && !(out[k - 1].body < out[k].body))))
                FAIL("raycast_all hits not in order");
        }
        free(out);
        return st;
    }
    case OP_QUERY_POINT: {
        *is_const = 1;
        rg_vec2 p = vec_arg(in);
        uint32_t mask = u32(in);
        int32_t cap = int_arg(in);
        rg_body *out = NULL;
        if (cap > 0 && cap <= MAXB && u8(in) >= 24) out = (rg_body *)malloc((size_t)cap * sizeof *out);
        st = rg_world_query_point(w, p, mask, out, cap);
        if (st >= 0) check_query(fw, out, st, out != NULL ? cap : 0);
        free(out);
        return st;
    }
    case OP_CAST_SHAPE: {
        *is_const = 1;
        rg_ray_hit hit;
        int32_t shape = int_arg(in);
        rg_vec2 size = vec_arg(in), o = vec_arg(in), d = vec_arg(in);
        memset(&hit, 0, sizeof hit);
        st = rg_world_cast_shape(w, shape, size, o, d, u32(in), OUT(in, hit));
        if (st > 1) FAIL("cast_shape returned %d", st);
        if (st == 1) hit_sane(fw, &hit, 0);
        return st;
    }
    case OP_MOVE: {
        rg_vec2 target, pos = { 0, 0 }, now;
        rg_ray_hit hits[8];
        int32_t count = -5, *outc;
        b = pick_body(in, fw);
        target = vec_arg(in);
        uint32_t mask = u32(in);
        int32_t response = int_arg(in), cap = (int32_t)(u8(in) % 9);
        rg_vec2 *outp = OUT(in, pos);
        outc = OUT(in, count);
        st = rg_body_move(w, b, target, mask, response, outp, (u8(in) < 24) ? NULL : hits,
                          cap, outc);
        if (st == RG_OK) {
            if (rg_body_get_position(w, b, &now) != RG_OK) FAIL("move: the body is gone");
            if (outp != NULL && memcmp(&pos, &now, sizeof pos) != 0) FAIL("move: out_position is not the position");
            if (outc != NULL && count < 0) FAIL("move: %d hits", count);
        }
        return st;
    }
    case OP_SAVE: *is_const = 1; return w == NULL ? rg_world_save(NULL, NULL, 0, NULL) : do_save(in, fw);
    case OP_RESTORE: return do_restore(in, fw);
    case OP_HASH: *is_const = 1; return rg_world_hash(w, OUT(in, u64v));
    case OP_KEPT: return do_kept(in, fw, is_const);
    case OP_SET_TASKS: return tasks_set(in, fw);
    case OP_POOL: return tasks_pool(in);
    case OP_CROWD:
        *is_const = 1;   /* its worlds are its own */
        if (crowds++ > 0) return RG_OK;   /* one per input: they are slow */
        return tasks_crowd(in);
    case OP_STOPPED: {
        *is_const = 1;
        int32_t cap = int_arg(in);
        rg_body out[MAXB];
        int bad = w == NULL || cap < 0 || (cap > 0 && u8(in) < 24);
        st = rg_world_get_stopped(w, bad && cap > 0 ? NULL : out, cap < MAXB ? cap : MAXB);
        if ((st < 0) != bad || (st < 0 && st != RG_ERR_INVALID_ARGUMENT)) FAIL("get_stopped: %d", st);
        return st;
    }
    default: return RG_OK;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static snap before, after;
    input in = { data, size };
    if (trace < 0) trace = getenv("FUZZ_API_TRACE") != NULL;   /* the ops of a reproducer */
    memset(W, 0, sizeof W);
    memset(kept_valid, 0, sizeof kept_valid);
    ndead = dead_next = next_serial = crowds = 0;
    op_name = "setup";
    for (op_no = 0; op_no < MAXOPS && in.n > 0; op_no++) {
        int op = u8(&in) % OP_COUNT, is_step, is_const;
        op_name = op_names[op];
        snap_all(&before);
        int32_t st = run_op(&in, op, &is_step, &is_const);
        if (trace) fprintf(stderr, "  -> %d\n", st);
        if (st < 0 || is_const) {
            snap_all(&after);
            if (after.n != before.n || (before.n > 0 && memcmp(after.p, before.p, before.n) != 0))
                FAIL("%s changed what the getters show (status %d)", st < 0 ? "a failed call" : "a const call", st);
        }
        check_all(st < 0 ? RAN_OTHER : is_step);
    }
    op_name = "teardown";
    for (int k = 0; k < NW; k++) world_close(&W[k]);
    tasks_teardown();
    for (int k = 0; k < 2; k++) {
        free(slots[k].buf);
        memset(&slots[k], 0, sizeof slots[k]);
    }
    return 0;
}

