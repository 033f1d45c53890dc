/* errors.h: the fixture of the error-path tests (test_errors_*.c, test_ranges.c): a scene
 * with one body of each kind, a fingerprint of everything the getters say about it, and
 * checks that a call failed with a status, changed nothing and said why. */
#ifndef RG_TEST_ERRORS_H
#define RG_TEST_ERRORS_H

#include <ctype.h>
#include <inttypes.h>

#include "testutil.h"

/* NAN and INFINITY as doubles (they are floats, and v2 takes doubles) */
#define NaN ((double)NAN)
#define INF ((double)INFINITY)
#define INVALID RG_ERR_INVALID_ARGUMENT
#define STALE RG_ERR_STALE_HANDLE
#define ALL 0xFFFFFFFFu

/* A world on a counting allocator: a dynamic circle resting on a static floor, a kinematic
 * box, a shapeless dynamic body tied to the circle by a spring, after one step (contacts,
 * events, accelerations); stale handles of four kinds. */
typedef struct scene {
    rg_world *w, *other;
    test_alloc ta;
    rg_body dyn, kin, floor, bare;
    uint64_t spring;
    rg_body bad[4];    /* 0, destroyed, another world's, a spring handle */
} scene;

/* The scene on an allocator that passes its calls on to test_alloc_fn(&s->ta, ...). */
static inline int scene_setup_on(void **state, rg_alloc_fn alloc)
{
    scene *s = calloc(1, sizeof *s);
    assert_non_null(s);
    assert_ok(rg_world_create_with_allocator(alloc, &s->ta, &s->w));
    assert_ok(rg_world_create(&s->other));
    rg_world *w = s->w;
    assert_ok(rg_world_set_gravity(w, v2(0, -10)));
    s->floor = box_body(w, RG_BODY_STATIC, 0, 0, -0.5, 20, 0.5);
    s->dyn = circle_body(w, RG_BODY_DYNAMIC, 2, 0, 0.5, 0.5);
    s->kin = box_body(w, RG_BODY_KINEMATIC, 0, 5, 3, 0.5, 0.25);
    assert_ok(rg_body_set_velocity(w, s->kin, v2(1, 0)));
    s->bare = make_body(w, 1, 3, 6);
    assert_ok(rg_body_set_drag(w, s->bare, 0.1f, 0.01f));
    assert_ok(rg_spring_create(w, s->dyn, s->bare, v2(0, 0), 4, 10, 0.5f, &s->spring));
    rg_body dead = make_body(w, 1, 0, 0);
    assert_ok(rg_body_destroy(w, dead));
    s->bad[0] = 0;
    s->bad[1] = dead;
    s->bad[2] = make_body(s->other, 1, 0, 0);
    s->bad[3] = s->spring;
    assert_ok(rg_world_step(w, (rg_real)DT));
    *state = s;
    return 0;
}

static inline int scene_setup(void **state) { return scene_setup_on(state, test_alloc_fn); }

static inline int scene_teardown(void **state)
{
    scene *s = *state;
    rg_world_destroy(s->w);
    rg_world_destroy(s->other);
    assert_int_equal(s->ta.live_blocks, 0);
    free(s);
    return 0;
}

/* Everything the getters say about the scene, as bytes. */
typedef struct fp {
    unsigned char b[8192];
    size_t n;
} fp;

static inline void fp_put(fp *f, const void *p, size_t k)
{
    assert_true(f->n + k <= sizeof f->b);
    memcpy(f->b + f->n, p, k);
    f->n += k;
}
#define FP(f, v) fp_put((f), &(v), sizeof(v))

static inline void fp_body(const scene *s, rg_body b, fp *f)
{
    const rg_world *w = s->w;
    int32_t i[6];
    rg_real r[3];
    rg_vec2 v[6];
    uint32_t u[2];
    uint64_t user;
    i[0] = rg_body_is_valid(w, b);
    assert_ok(rg_body_get_type(w, b, &i[1]));
    assert_ok(rg_body_get_mass(w, b, &r[0]));
    assert_ok(rg_body_get_position(w, b, &v[0]));
    assert_ok(rg_body_get_velocity(w, b, &v[1]));
    assert_ok(rg_body_get_acceleration(w, b, &v[2]));
    assert_ok(rg_body_get_interpolated_position(w, b, &v[3]));
    assert_ok(rg_body_get_shape(w, b, &i[2], &v[4]));
    assert_ok(rg_body_get_one_way(w, b, &v[5]));
    assert_ok(rg_body_get_restitution(w, b, &r[1]));
    assert_ok(rg_body_get_friction(w, b, &r[2]));
    assert_ok(rg_body_is_sensor(w, b, &i[3]));
    assert_ok(rg_body_is_grounded(w, b, &i[4]));
    assert_ok(rg_body_is_awake(w, b, &i[5]));
    assert_ok(rg_body_get_filter(w, b, &u[0], &u[1]));
    assert_ok(rg_body_get_user_data(w, b, &user));
    FP(f, i);
    FP(f, r);
    FP(f, v);
    FP(f, u);
    FP(f, user);
    rg_contact c[4];
    memset(c, 0, sizeof c); /* padding, in the double build */
    int32_t n = rg_body_get_contacts(w, b, c, 4);
    assert_true(n >= 0);
    FP(f, n);
    FP(f, c);
}

static inline void fingerprint(const scene *s, fp *f)
{
    const rg_world *w = s->w;
    f->n = 0;
    rg_vec2 v[2];
    rg_real r[8];
    int32_t i[12];
    assert_ok(rg_world_get_gravity(w, &v[0]));
    assert_ok(rg_world_get_wind(w, &v[1]));
    assert_ok(rg_world_get_integrator(w, &i[0]));
    assert_ok(rg_world_get_fixed_step(w, &r[0], &i[1]));
    assert_ok(rg_world_get_alpha(w, &r[1]));
    assert_ok(rg_world_get_sleeping(w, &i[2]));
    assert_ok(rg_world_get_sleep_thresholds(w, &r[2], &r[3]));
    assert_ok(rg_world_get_solver_iterations(w, &i[3], &i[4]));
    assert_ok(rg_world_get_contact_tuning(w, &r[4], &r[5], &r[6], &r[7]));
    assert_ok(rg_world_get_continuous(w, &i[5]));
    i[6] = rg_world_body_count(w);
    i[7] = rg_world_spring_count(w);
    i[8] = rg_world_awake_body_count(w);
    i[9] = rg_world_touching_count(w);
    i[10] = rg_spring_is_valid(w, s->spring);
    FP(f, v);
    FP(f, r);
    rg_contact_event ev[8];
    memset(ev, 0, sizeof ev);
    i[11] = rg_world_get_contact_events(w, ev, 8);
    FP(f, i);
    FP(f, ev);
    const rg_body bodies[] = { s->dyn, s->kin, s->floor, s->bare };
    for (int k = 0; k < 4; k++) fp_body(s, bodies[k], f);
}

/* The name of the function a call's text starts with ("rg_world_step(w, 1)"). */
static inline void call_name(const char *call, char *out, size_t cap)
{
    size_t n = strcspn(call, "( ");
    assert_true(n < cap);
    memcpy(out, call, n);
    out[n] = '\0';
}

/* Whether text holds word as a word (not inside a longer name): "b" is in "b 0x10 is
 * stale" but not in "body". */
static inline int has_word(const char *text, const char *word)
{
    size_t k = strlen(word);
    for (const char *p = strstr(text, word); p != NULL; p = strstr(p + 1, word)) {
        int before = p == text || !(isalnum((unsigned char)p[-1]) || p[-1] == '_');
        int after = !(isalnum((unsigned char)p[k]) || p[k] == '_');
        if (before && after) return 1;
    }
    return 0;
}

/* got == want, the scene's fingerprint is still *before, and the last error (read right
 * after the call, before any getter clears it) is "<function>: ..." naming arg (and holding
 * `also` unless NULL). */
static inline void check_failed(const scene *s, const fp *before, int32_t got, int32_t want,
                                const char *arg, const char *also, const char *call, int line)
{
    char err[256], fn[64];
    snprintf(err, sizeof err, "%s", rg_world_last_error(s->w));
    call_name(call, fn, sizeof fn);
    if (got != want) fail_msg("line %d: %s returned %d, expected %d (%s)", line, call, got, want, err);
    size_t k = strlen(fn);
    if (strncmp(err, fn, k) != 0 || strncmp(err + k, ": ", 2) != 0 || !has_word(err + k, arg))
        fail_msg("line %d: %s: the last error \"%s\" does not name %s and '%s'", line, call, err, fn, arg);
    if (also != NULL && strstr(err, also) == NULL)
        fail_msg("line %d: %s: the last error \"%s\" does not say '%s'", line, call, err, also);
    fp after;
    fingerprint(s, &after);
    if (after.n != before->n || memcmp(after.b, before->b, after.n) != 0)
        fail_msg("line %d: %s failed but changed what the getters say", line, call);
}

/* The call fails with status st, names its function and `arg` (and says `also`), and
 * changes nothing. */
#define FAILS_SAYING(s, st, arg, also, call)                                       \
    do {                                                                           \
        fp before_;                                                                \
        fingerprint((s), &before_);                                                \
        int32_t got_ = (int32_t)(call);                                            \
        check_failed((s), &before_, got_, (st), (arg), (also), #call, __LINE__);   \
    } while (0)
#define FAILS(s, st, arg, call) FAILS_SAYING(s, st, arg, NULL, call)

/* The call, after another call left an error, succeeds (status >= 0) and leaves "". */
#define SUCCEEDS(s, call)                                                              \
    do {                                                                               \
        assert_status(rg_world_get_gravity((s)->w, NULL), INVALID);                    \
        assert_true(rg_world_last_error((s)->w)[0] != '\0');                           \
        int32_t got_ = (int32_t)(call);                                                \
        if (got_ < 0) fail_msg("line %d: %s returned %d (%s)", __LINE__, #call, got_,  \
                               rg_world_last_error((s)->w));                           \
        if (rg_world_last_error((s)->w)[0] != '\0')                                    \
            fail_msg("line %d: %s succeeded but left \"%s\"", __LINE__, #call,         \
                     rg_world_last_error((s)->w));                                     \
    } while (0)

/* With a NULL world the call returns st (RG_ERR_INVALID_ARGUMENT, or 0 for a count or a
 * validity test), and there is no world to keep a reason. */
#define NULL_WORLD(st, call) assert_int_equal((int32_t)(call), (st))

/* For each stale handle h of the scene (0, destroyed, another world's, a spring's), the
 * call fails with RG_ERR_STALE_HANDLE naming `arg` and "stale" or "0". */
#define EACH_STALE(s, h, arg, call)                                                \
    for (int k_ = 0; k_ < 4; k_++) {                                               \
        rg_body h = (s)->bad[k_];                                                  \
        FAILS_SAYING((s), STALE, arg, k_ == 0 ? "is 0" : "is stale", call);        \
    }

/* The rg_real just beyond an edge, away from zero (toward +inf for a maximum, -inf for the
 * negative of a maximum, 0 for a minimum). */
static inline rg_real next_real(double edge, double toward)
{
#ifdef RG_DOUBLE
    return nextafter(edge, toward);
#else
    return nextafterf((float)edge, (float)toward);
#endif
}

#endif
