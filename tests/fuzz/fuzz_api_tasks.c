/* fuzz_api_tasks.c: the API harness's task systems (see fuzz_api.c): rg_world_set_task_system
 * with good task systems (the shuffler of tests/shuffler.h at 1 to RG_MAX_WORKERS workers,
 * deferred or eager; a thread pool of 1 to 3 threads, as rg_thread_pool_task_system gives it
 * or wrapped to watch its calls) and bad ones (workers 0, negative or above RG_MAX_WORKERS,
 * NULL enqueue or finish: refused, and never called), rg_thread_pool_create/destroy/
 * task_system with good and bad arguments, and the twin oracle: a world with a task system
 * must take each step exactly as a clone of it without one takes the same step (the same
 * rg_world_hash, stopped list and pre-solve calls), and call its task system only from inside
 * its own steps and restores (whose checks and load run on it: a restore of a snapshot with a
 * task system must give the status, the reason and the state of the same restore into the
 * twin, which has none). */
#include <pthread.h>
#include <string.h>

#include "fuzz_api.h"
#include "shuffler.h"

enum { TASKS_NONE, TASKS_SHUFFLER, TASKS_POOL };

typedef struct fz_tasks {
    int kind;
    shuffler sh;       /* kind TASKS_SHUFFLER: the world's shuffler */
    shuffler decoy;    /* the user of every refused task system: must never be called */
} fz_tasks;

static fz_tasks T[NW];
/* The pool of this input, for any world: one of 1 thread (no thread started) made and
 * destroyed by the input, or one of the process's pools of 2 and 3 threads, made on first
 * use and kept, so that an input does not start threads (which would make libFuzzer run it
 * again for leaks, and slowly). */
static rg_thread_pool *pool, *kept_pool[2];
static int32_t pool_threads;
static rg_task_system pool_ts;     /* what rg_thread_pool_task_system gave */
static const fworld *stepping;     /* the model world inside rg_world_step or rg_world_advance */
static int in_step;                /* any world's step runs, on stepping_thread */
static pthread_t stepping_thread;

/* The twin: a clone without a task system, made before each step of a world that has one. */
static rg_world *twin;
static fworld twin_fw;
static unsigned char *twin_buf;
static size_t twin_cap;

static fz_tasks *tasks_of(const fworld *fw) { return &T[fw - W]; }

/* ---- the task systems the worlds get: each call checked to come from its world's step */

static void called_by(const fz_tasks *t)
{
    if (stepping == NULL || tasks_of(stepping) != t || t->kind == TASKS_NONE)
        FAIL("a task system was called outside a step of the world that has it");
    if (!pthread_equal(pthread_self(), stepping_thread)) FAIL("a task system was called from a worker");
}

static void *watched_enqueue(rg_task_fn *fn, int32_t count, int32_t min_range, void *context, void *user)
{
    fz_tasks *t = (fz_tasks *)user;
    called_by(t);
    if (t->kind == TASKS_POOL) return pool_ts.enqueue(fn, count, min_range, context, pool_ts.user);
    return shuffler_enqueue(fn, count, min_range, context, &t->sh);
}

static void watched_finish(void *task, void *user)
{
    fz_tasks *t = (fz_tasks *)user;
    called_by(t);
    if (t->kind == TASKS_POOL) pool_ts.finish(task, pool_ts.user);
    else shuffler_finish(task, &t->sh);
}

static void *never_enqueue(rg_task_fn *fn, int32_t count, int32_t min_range, void *context, void *user)
{
    (void)fn;
    (void)count;
    (void)min_range;
    (void)context;
    (void)user;
    FAIL("a refused task system was called");
}

static void never_finish(void *task, void *user)
{
    (void)task;
    (void)user;
    FAIL("a refused task system was called");
}

/* The pre-solve hook runs on the stepping thread (rigid.h: never on a worker). */
void tasks_check_thread(void)
{
    if (in_step && !pthread_equal(pthread_self(), stepping_thread))
        FAIL("the pre-solve hook ran on a worker thread");
}

/* ---- operations */

int32_t tasks_set(input *in, fworld *fw)
{
    static const int32_t bad_workers[] = { 0, -1, RG_MAX_WORKERS + 1, INT32_MIN, INT32_MAX };
    uint8_t mode = u8(in);
    fz_tasks *t = tasks_of(fw);
    rg_task_system ts = { 1, never_enqueue, never_finish, &t->decoy };
    rg_status want = fw->w == NULL ? RG_ERR_INVALID_ARGUMENT : RG_OK, st;
    int kind = TASKS_NONE;
    switch (mode % 8) {
    case 0:
        st = rg_world_set_task_system(fw->w, NULL);
        break;
    case 1:
        ts.workers = bad_workers[u8(in) % 5];
        want = RG_ERR_INVALID_ARGUMENT;
        st = rg_world_set_task_system(fw->w, &ts);
        break;
    case 2:
    case 3:
        ts.workers = 1 + (int32_t)(u8(in) % RG_MAX_WORKERS);
        if (mode % 8 == 2) ts.enqueue = NULL;
        else ts.finish = NULL;
        want = RG_ERR_INVALID_ARGUMENT;
        st = rg_world_set_task_system(fw->w, &ts);
        break;
    case 4:
    case 5:
    case 6: {
        int use_pool = mode % 8 == 6 && pool != NULL;
        shuffler sh;
        uint8_t w = u8(in);
        shuffler_init(&sh, u32(in), w < 128 ? 2 + w % 3 : 1 + w % RG_MAX_WORKERS, (mode >> 3) & 1);
        ts.workers = use_pool ? pool_threads : sh.workers;
        ts.enqueue = watched_enqueue;
        ts.finish = watched_finish;
        ts.user = t;
        kind = use_pool ? TASKS_POOL : TASKS_SHUFFLER;
        if (use_pool && (mode & 0x10)) ts = pool_ts;   /* the pool's own, unwatched */
        st = rg_world_set_task_system(fw->w, &ts);
        if (st == RG_OK) t->sh = sh;
        break;
    }
    default:
        want = RG_ERR_INVALID_ARGUMENT;
        st = rg_world_set_task_system(NULL, (mode & 8) ? NULL : &ts);
        break;
    }
    if (st != want) FAIL("set_task_system: status %d, expected %d", st, want);
    if (st == RG_OK) t->kind = kind;
    return st;
}

/* Worlds that have the pool's task system lose it (a pool is destroyed only when no world
 * steps with it). */
static void pool_release(void)
{
    for (int k = 0; k < NW; k++)
        if (W[k].w != NULL && T[k].kind == TASKS_POOL) {
            if (rg_world_set_task_system(W[k].w, NULL) != RG_OK) FAIL("set_task_system(NULL) failed");
            T[k].kind = TASKS_NONE;
        }
    if (pool != kept_pool[0] && pool != kept_pool[1]) rg_thread_pool_destroy(pool);
    pool = NULL;
}

int32_t tasks_pool(input *in)
{
    static const int32_t counts[] = { 0, -1, RG_MAX_WORKERS + 1, INT32_MIN, 1, 2, 3, 2 };
    uint8_t mode = u8(in);
    rg_task_system ts;
    rg_status st;
    switch (mode % 4) {
    case 0: {
        int32_t n = counts[u8(in) % 8];
        rg_thread_pool *p = (rg_thread_pool *)&ts, **out = (mode & 4) ? NULL : &p;
        if (n >= 1 && out != NULL) pool_release();
        if (n >= 2 && n <= 3 && out != NULL && kept_pool[n - 2] != NULL) {
            p = kept_pool[n - 2];
            st = RG_OK;
        } else {
            st = rg_thread_pool_create(n, out);
            if (st == RG_OK && n >= 2) kept_pool[n - 2] = p;
        }
        if (n < 1 || n > RG_MAX_WORKERS || out == NULL) {
            if (st != RG_ERR_INVALID_ARGUMENT || (out != NULL && p != NULL)) FAIL("thread_pool_create(%d): status %d", n, st);
            return st;
        }
        if (st != RG_OK) {   /* no memory or no threads: nothing made */
            if ((st != RG_ERR_OUT_OF_MEMORY && st != RG_ERR_CAPACITY) || p != NULL) FAIL("thread_pool_create: status %d", st);
            return st;
        }
        pool = p;
        pool_threads = n;
        if (rg_thread_pool_task_system(pool, &pool_ts) != RG_OK || pool_ts.workers != n ||
            pool_ts.enqueue == NULL || pool_ts.finish == NULL)
            FAIL("thread_pool_task_system of a fresh pool");
        return st;
    }
    case 1:
        if (rg_thread_pool_task_system(NULL, &ts) != RG_ERR_INVALID_ARGUMENT) FAIL("thread_pool_task_system(NULL pool)");
        if (pool == NULL) return RG_ERR_INVALID_ARGUMENT;
        if (rg_thread_pool_task_system(pool, NULL) != RG_ERR_INVALID_ARGUMENT) FAIL("thread_pool_task_system(NULL out)");
        st = rg_thread_pool_task_system(pool, &ts);
        if (st != RG_OK || ts.workers != pool_ts.workers || ts.enqueue != pool_ts.enqueue ||
            ts.finish != pool_ts.finish || ts.user != pool_ts.user)
            FAIL("thread_pool_task_system changed");
        return st;
    default:
        if (mode & 4) rg_thread_pool_destroy(NULL);
        else pool_release();
        return RG_OK;
    }
}

/* ---- stepping, and the twin */

static int twin_load(const fworld *fw)
{
    size_t n = 0;
    if (rg_world_save(fw->w, NULL, 0, &n) != RG_OK) FAIL("save: no size");
    if (n > twin_cap) {
        free(twin_buf);
        twin_buf = (unsigned char *)malloc(n);
        if (twin_buf == NULL) abort();
        twin_cap = n;
    }
    if (rg_world_save(fw->w, twin_buf, n, &n) != RG_OK) FAIL("save into its own size failed");
    if (twin == NULL && rg_world_create(&twin) != RG_OK) return 0;
    if (rg_world_restore(twin, twin_buf, n) != RG_OK) FAIL("a world's snapshot does not restore into its twin");
    twin_fw = *fw;
    twin_fw.w = twin;
    twin_fw.al = NULL;
    if (rg_world_set_pre_solve(twin, fw->presolve ? on_pre_solve : NULL, &twin_fw) != RG_OK)
        FAIL("set_pre_solve on the twin");
    return 1;
}

static void twin_compare(const fworld *fw)
{
    uint64_t h1 = 0, h2 = 0;
    rg_body s1[MAXB], s2[MAXB];
    if (rg_world_hash(fw->w, &h1) != RG_OK || rg_world_hash(twin, &h2) != RG_OK) FAIL("hash failed");
    if (h1 != h2) FAIL("the step with a task system differs from the step without (hash %016llx, twin %016llx)",
                       (unsigned long long)h1, (unsigned long long)h2);
    int32_t n1 = rg_world_get_stopped(fw->w, s1, MAXB), n2 = rg_world_get_stopped(twin, s2, MAXB);
    if (n1 != n2 || (n1 > 0 && memcmp(s1, s2, (size_t)(n1 < MAXB ? n1 : MAXB) * sizeof s1[0]) != 0))
        FAIL("the step with a task system stopped other bodies than the step without");
    if (twin_fw.presolve_calls != fw->presolve_calls)
        FAIL("the step with a task system called pre-solve %d times, without %d", fw->presolve_calls,
             twin_fw.presolve_calls);
}

int32_t tasks_step(fworld *fw, int advance, rg_real t, int32_t *out_steps)
{
    fz_tasks *ft = tasks_of(fw);
    int check = fw->w != NULL && ft->kind != TASKS_NONE && twin_load(fw);
    long refused = fw->al != NULL ? fw->al->refused : 0, misuse = ft->sh.misuse;
    stepping = fw;
    in_step = 1;
    stepping_thread = pthread_self();
    rg_status st = advance ? rg_world_advance(fw->w, t, out_steps) : rg_world_step(fw->w, t);
    stepping = NULL;
    in_step = 0;
    if (ft->sh.misuse != misuse) FAIL("the world misused its task system (enqueue with a task pending, or a stray finish)");
    /* out of memory the world may take fewer steps than its twin: no comparison then */
    if (!check || st != RG_OK || (fw->al != NULL && fw->al->refused != refused)) return st;
    int32_t steps = -1;
    st = advance ? rg_world_advance(twin, t, &steps) : rg_world_step(twin, t);
    if (st != RG_OK) FAIL("the twin's step failed: status %d", st);
    if (advance && out_steps != NULL && steps != *out_steps)
        FAIL("an advance took %d steps with a task system, %d without", *out_steps, steps);
    twin_compare(fw);
    return RG_OK;
}

/* ---- restoring (rigid.h: a restore runs its checks and load on the world's task system) */

/* A restore of fw (from data, or from kept slot when data is NULL) with the calls of its task
 * system watched as a step's; its status (a misuse of the task system fails the input). */
static rg_status tasks_watched(fworld *fw, const unsigned char *data, size_t n, int32_t slot)
{
    fz_tasks *ft = tasks_of(fw);
    long misuse = ft->sh.misuse;
    stepping = fw;
    in_step = 1;
    stepping_thread = pthread_self();
    rg_status st = data != NULL ? rg_world_restore(fw->w, data, n) : rg_world_restore_slot(fw->w, slot);
    stepping = NULL;
    in_step = 0;
    if (ft->sh.misuse != misuse) FAIL("the world misused its task system in a restore");
    return st;
}

int32_t tasks_restore(fworld *fw, const unsigned char *data, size_t n)
{
    long refused = fw->al != NULL ? fw->al->refused : 0;
    rg_status st = tasks_watched(fw, data, n, -1);
    /* out of memory the world may refuse what its twin takes: no comparison then */
    if (fw->w == NULL || tasks_of(fw)->kind == TASKS_NONE || (fw->al != NULL && fw->al->refused != refused)) return st;
    if (twin == NULL && rg_world_create(&twin) != RG_OK) return st;
    rg_status st2 = rg_world_restore(twin, data, n);
    if (st != st2) FAIL("a restore with a task system gave status %d, without %d", st, st2);
    if (st != RG_OK) {
        if (strcmp(rg_world_last_error(fw->w), rg_world_last_error(twin)) != 0)
            FAIL("a restore with a task system refused for \"%s\", without for \"%s\"", rg_world_last_error(fw->w),
                 rg_world_last_error(twin));
        return st;
    }
    uint64_t h1 = 0, h2 = 0;
    if (rg_world_hash(fw->w, &h1) != RG_OK || rg_world_hash(twin, &h2) != RG_OK || h1 != h2)
        FAIL("a restore with a task system left another state than without (hash %016llx, twin %016llx)",
             (unsigned long long)h1, (unsigned long long)h2);
    return st;
}

int32_t tasks_restore_slot(fworld *fw, int32_t slot) { return tasks_watched(fw, NULL, 0, slot); }

/* ---- the crowd: a scene large enough that every stage of the step splits (2,048 bodies for
 * the Euler pass, 512 awake shapes for the views, the sweep and the refit, 128 pairs for the
 * narrowphase, 16 rows of one colour for the solver), built by the same calls in a world with
 * a task system and in its twin without, from a few input bytes and a seed; after every step
 * the two must hash alike, stop the same bodies, make the same contact events and call the
 * pre-solve hook in the same order with the same arguments. */

typedef struct crowd_hook {
    uint64_t h;        /* of every call's arguments, in order */
    uint32_t keep;     /* which calls keep their pair (bit k: call k mod 32) */
    long calls;
} crowd_hook;

static rg_vec2 vec(rg_real x, rg_real y)
{
    rg_vec2 v;
    v.x = x;
    v.y = y;
    return v;
}

#define UNTAGGED(h) ((h) & ((1ull << 44) - 1))   /* a handle without its world's tag */

static uint64_t mix(uint64_t h, uint64_t v) { return (h ^ v) * 0x100000001b3ull; }

static int32_t crowd_pre_solve(rg_body a, rg_body b, rg_vec2 normal, rg_real separation, void *user)
{
    crowd_hook *c = (crowd_hook *)user;
    uint64_t bits[3] = { 0, 0, 0 };
    tasks_check_thread();
    memcpy(&bits[0], &normal.x, sizeof normal.x);
    memcpy(&bits[1], &normal.y, sizeof normal.y);
    memcpy(&bits[2], &separation, sizeof separation);
    c->h = mix(mix(mix(mix(mix(c->h, UNTAGGED(a)), UNTAGGED(b)), bits[0]), bits[1]), bits[2]);
    return (c->keep >> (c->calls++ % 32)) & 1;
}

typedef struct crowd_rng {
    uint64_t s;
} crowd_rng;

static uint32_t crowd_next(crowd_rng *r)
{
    r->s = r->s * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(r->s >> 33);
}

static rg_real crowd_real(crowd_rng *r, double lo, double hi)
{
    return (rg_real)(lo + (hi - lo) * (crowd_next(r) / 4294967296.0));
}

/* The same scene in both worlds: every call on each, the results compared. */
#define BOTH(call_a, call_b)                                                   \
    do {                                                                       \
        rg_status sa_ = (call_a), sb_ = (call_b);                              \
        if (sa_ != sb_) FAIL("crowd: the same call gave %d and %d", sa_, sb_); \
    } while (0)

static void crowd_build(rg_world *const w[2], input *in, crowd_rng *r, int32_t n, uint8_t most_shaped)
{
    rg_vec2 g = { 0, (rg_real)-9.81 }, wind = { 0, 0 };
    uint8_t shaped = u8(in), spacing = u8(in), extra = u8(in);
    if (shaped > most_shaped) shaped = most_shaped;   /* of 256: the part with a shape */
    if (extra & 1) g = vec_arg(in);       /* raw: may be refused, by both */
    if (extra & 2) wind = vec_arg(in);
    rg_real gap = (rg_real)(0.3 + (spacing % 8) * 0.1);
    int32_t integrator = (int32_t)((extra >> 2) % 4), cols = 8 + (int32_t)(spacing >> 3);
    rg_body floor_[2], prev[2] = { 0, 0 };
    for (int k = 0; k < 2; k++) {
        (void)rg_world_set_gravity(w[k], g);
        (void)rg_world_set_wind(w[k], wind);
        (void)rg_world_set_integrator(w[k], integrator);
        (void)rg_world_set_sleeping(w[k], (extra >> 4) & 1);
        (void)rg_world_set_continuous(w[k], !((extra >> 5) & 1));
    }
    BOTH(rg_body_create(w[0], RG_BODY_STATIC, 0, vec(0, -1), &floor_[0]),
         rg_body_create(w[1], RG_BODY_STATIC, 0, vec(0, -1), &floor_[1]));
    BOTH(rg_body_set_aabb(w[0], floor_[0], (rg_real)(cols * 0.6 + 2), 0.5f),
         rg_body_set_aabb(w[1], floor_[1], (rg_real)(cols * 0.6 + 2), 0.5f));
    for (int32_t i = 0; i < n; i++) {
        uint32_t kind = crowd_next(r);
        int32_t type = kind % 29 == 0 ? RG_BODY_KINEMATIC : kind % 23 == 0 ? RG_BODY_STATIC : RG_BODY_DYNAMIC;
        rg_real m = crowd_real(r, 0.5, 2), x = (rg_real)((i % cols) - cols / 2) * gap,
                y = (rg_real)(i / cols) * gap, size = crowd_real(r, 0.12, 0.3);
        rg_vec2 v = { crowd_real(r, -3, 3), crowd_real(r, -3, 3) };
        if (kind % 97 == 0) v.x = (rg_real)(kind % 2 ? 200 : -150);   /* a bullet */
        rg_body b[2];
        int with_shape = (crowd_next(r) & 255) < shaped;
        BOTH(rg_body_create(w[0], type, m, vec(x, y), &b[0]), rg_body_create(w[1], type, m, vec(x, y), &b[1]));
        for (int k = 0; k < 2; k++) {
            if (type != RG_BODY_STATIC) (void)rg_body_set_velocity(w[k], b[k], v);
            if (with_shape) {
                if (kind & 1) (void)rg_body_set_circle(w[k], b[k], size);
                else (void)rg_body_set_aabb(w[k], b[k], size, (rg_real)(0.7 * (double)size));
                if (kind % 7 == 1) (void)rg_body_set_restitution(w[k], b[k], 0.5f);
                if (kind % 11 == 2) (void)rg_body_set_friction(w[k], b[k], 0.1f);
                if (kind % 31 == 3) (void)rg_body_set_sensor(w[k], b[k], 1);
                if (kind % 37 == 4) (void)rg_body_set_one_way(w[k], b[k], vec(0, 1));
            }
            if (kind % 13 == 5) (void)rg_body_set_drag(w[k], b[k], 0.2f, 0.05f);
            if (kind % 17 == 6) (void)rg_body_set_surface_friction(w[k], b[k], 0.3f, 2);
        }
        if (kind % 19 == 7 && prev[0] != 0) {
            uint64_t s[2];
            BOTH(rg_spring_create(w[0], b[0], prev[0], vec(0, 0), gap, 40, 0.5f, &s[0]),
                 rg_spring_create(w[1], b[1], prev[1], vec(0, 0), gap, 40, 0.5f, &s[1]));
        }
        prev[0] = b[0];
        prev[1] = b[1];
    }
}

static void crowd_compare(rg_world *const w[2], const crowd_hook hook[2], int step)
{
    uint64_t h[2];
    rg_body s[2][MAXB];
    static rg_contact_event ev[2][MAXEV];
    for (int k = 0; k < 2; k++)
        if (rg_world_hash(w[k], &h[k]) != RG_OK) FAIL("crowd: hash failed");
    if (h[0] != h[1]) FAIL("crowd step %d: with a task system hash %016llx, without %016llx", step,
                           (unsigned long long)h[0], (unsigned long long)h[1]);
    if (hook[0].calls != hook[1].calls || hook[0].h != hook[1].h)
        FAIL("crowd step %d: pre-solve called %ld times with a task system, %ld without, or otherwise", step,
             hook[0].calls, hook[1].calls);
    int32_t n0 = rg_world_get_stopped(w[0], s[0], MAXB), n1 = rg_world_get_stopped(w[1], s[1], MAXB);
    if (n0 != n1) FAIL("crowd step %d: %d stopped with a task system, %d without", step, n0, n1);
    for (int32_t k = 0; k < n0 && k < MAXB; k++)
        if (UNTAGGED(s[0][k]) != UNTAGGED(s[1][k])) FAIL("crowd step %d: other bodies stopped", step);
    int32_t e0 = rg_world_get_contact_events(w[0], ev[0], MAXEV), e1 = rg_world_get_contact_events(w[1], ev[1], MAXEV);
    if (e0 != e1) FAIL("crowd step %d: %d events with a task system, %d without", step, e0, e1);
    for (int32_t k = 0; k < e0 && k < MAXEV; k++)
        if (UNTAGGED(ev[0][k].a) != UNTAGGED(ev[1][k].a) || UNTAGGED(ev[0][k].b) != UNTAGGED(ev[1][k].b) ||
            ev[0][k].kind != ev[1][k].kind || memcmp(&ev[0][k].normal, &ev[1][k].normal, sizeof(rg_vec2)) != 0)
            FAIL("crowd step %d: event %d differs", step, k);
}

int32_t tasks_crowd(input *in)
{
    uint8_t mode = u8(in), size = u8(in);
    /* 32 to 640 bodies; or 2,112 to 2,304, for the Euler pass, with fewer shapes */
    int32_t n = size < 224 ? 32 * (1 + size % 20) : 2112 + 64 * (size % 4);
    crowd_rng r = { u32(in) | 1 };
    rg_world *w[2] = { NULL, NULL };
    crowd_hook hook[2];
    shuffler sh;
    rg_task_system ts;
    if (rg_world_create(&w[0]) != RG_OK || rg_world_create(&w[1]) != RG_OK) abort();
    uint8_t workers = u8(in);
    shuffler_init(&sh, r.s, workers < 160 ? 2 + workers % 3 : 1 + workers % RG_MAX_WORKERS, mode & 1);
    shuffler_tasks(&sh, &ts);
    if ((mode & 2) && pool != NULL) ts = pool_ts;   /* real threads */
    if (rg_world_set_task_system(w[0], &ts) != RG_OK) FAIL("crowd: set_task_system");
    crowd_build(w, in, &r, n, n > 1000 ? 48 : 255);
    memset(hook, 0, sizeof hook);
    hook[0].keep = hook[1].keep = (mode & 4) ? crowd_next(&r) : 0xFFFFFFFFu;
    for (int k = 0; k < 2; k++)
        if (rg_world_set_pre_solve(w[k], (mode & 8) ? crowd_pre_solve : NULL, &hook[k]) != RG_OK) FAIL("crowd: pre-solve");
    int steps = 1 + (mode >> 4) % 2;
    rg_real dt = (mode & 0x40) ? real_arg(in) : (rg_real)(1.0 / 60);
    for (int s = 1; s <= steps; s++) {
        in_step = 1;
        stepping_thread = pthread_self();
        rg_status st0 = rg_world_step(w[0], dt), st1 = rg_world_step(w[1], dt);
        in_step = 0;
        if (st0 != st1) FAIL("crowd step %d: status %d with a task system, %d without", s, st0, st1);
        if (sh.misuse != 0) FAIL("crowd: the world misused its task system");
        crowd_compare(w, hook, s);
        if (st0 != RG_OK) break;
    }
    if (trace > 0)
        fprintf(stderr, "  crowd of %d bodies, %d touching: %ld tasks in %ld ranges\n", (int)n,
                (int)rg_world_touching_count(w[0]), sh.tasks, sh.ranges);
    rg_world_destroy(w[0]);
    rg_world_destroy(w[1]);
    return RG_OK;
}

void tasks_forget(const fworld *fw) { memset(tasks_of(fw), 0, sizeof(fz_tasks)); }

void tasks_teardown(void)
{
    pool_release();
    memset(T, 0, sizeof T);
    rg_world_destroy(twin);
    twin = NULL;
}
