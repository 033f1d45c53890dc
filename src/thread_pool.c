/* thread_pool.c: rg_thread_pool, a ready task system for games without one (POSIX threads).
 *
 * One task at a time, its items split into one part per thread: thread t takes ranges from
 * part t first, then from the others (so that, stage after stage, a thread meets the same
 * bodies, which stay in its core's caches), and enqueue returns when every item is done: it
 * never waits for a thread that is asleep or descheduled, which simply finds no range left
 * when it comes.  Each part has its cursor, the task's generation (high 32 bits) and the
 * start of the part's next range (low 32 bits); a thread claims a range by a compare-and-swap
 * of the cursor, so it runs a range of the current task only (a stale generation fails), and
 * the task cannot end, nor the next one be written, before that range is counted done.  The
 * count of items done is kept per part, beside its cursor: a thread counts the items of the
 * ranges it ran in a part and adds them to that part's count once, when it finds nothing left
 * there, so that the owner of a part writes only its own line, and the caller, done with its
 * own part, finds on one line of another part both what is left to take and what is done
 * (where moving a line between two cores costs some hundreds of ns, as on the VMs of the
 * README's figures, those moves are most of a task's cost).  Before it
 * writes the next task, enqueue closes the last one's generation in every part: a thread late
 * from the last task, holding a spent cursor, may read the next task's count (larger than
 * where the last one's ranges ran out), and its claim must then fail rather than run a range
 * of the next task under the last one's generation (those items would run twice, and the
 * task could end before they were done).  `state` publishes the generation to idle threads,
 * which spin a while on it (the stages of a step follow each other within microseconds),
 * then sleep on a condition variable until the next task. */
#undef _POSIX_C_SOURCE /* whatever the build set: this file needs threads */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <sched.h>
#include <stdlib.h>

#include "rigid.h"

#if !defined(__GNUC__) && !defined(__clang__)
#error "thread_pool.c needs the __atomic builtins of GCC or Clang"
#endif

#define POOL_LOAD(p) __atomic_load_n((p), __ATOMIC_ACQUIRE)
#define POOL_RELAXED(p) __atomic_load_n((p), __ATOMIC_RELAXED)
#define POOL_STORE(p, v) __atomic_store_n((p), (v), __ATOMIC_RELEASE)
#define POOL_SET(p, v) __atomic_store_n((p), (v), __ATOMIC_RELAXED)
#define POOL_ADD(p, v) __atomic_fetch_add((p), (v), __ATOMIC_ACQ_REL)

/* The start of a closed generation's next range: past any count, so nothing is claimed. */
#define POOL_CLOSED 0x7FFFFFFFu

/* A part's cursor and count of items done, on a cache line of their own. */
typedef struct pool_part {
    uint64_t cursor;             /* atomic: generation << 32 | the part's next range's start */
    int32_t done;                /* atomic: the part's items run and counted */
    char pad[64 - sizeof(uint64_t) - sizeof(int32_t)];
} pool_part;

/* Spins of an idle thread before it sleeps (a pause each: some 0.1-1 ms). */
#define POOL_SPINS 20000

static inline void pool_relax(void)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#elif defined(__aarch64__)
    __asm__ __volatile__("yield");
#endif
}

typedef struct pool_thread {
    struct rg_thread_pool *pool;
    int32_t worker;
} pool_thread;

struct rg_thread_pool {
    int32_t threads;             /* in all, the caller's included */
    pthread_t *th;               /* threads - 1 */
    pool_thread *pt;
    pthread_mutex_t task_lock;   /* one task at a time */
    pthread_mutex_t lock;        /* sleepers and stop, with wake */
    pthread_cond_t wake;
    int32_t sleepers;
    int32_t stop;                /* atomic */
    /* the current task (atomics: a late thread may read them while the next is written,
     * and then fails its claim) */
    rg_task_fn *fn;
    void *context;
    int32_t count, least, parts; /* least: min_range; parts: up to threads, each at least
                                  * least items */
    uint64_t state;              /* atomic: generation << 32 */
    pool_part *part;             /* threads */
};

/* Where part k of a task of count items in `parts` parts ends (it begins where part k - 1
 * ends). */
static inline int32_t pool_part_end(int32_t count, int32_t parts, int32_t k)
{
    return (int32_t)((int64_t)count * (k + 1) / parts);
}

/* Claims and runs ranges of part k of the task of generation gen until none is left there,
 * then adds their items to the part's count; returns 0 when the generation has passed
 * (then the thread ran nothing there: the task ended, which it cannot while a range of it is
 * not counted). */
static int pool_work_part(rg_thread_pool *p, uint32_t gen, int32_t k, int32_t worker)
{
    uint64_t *cur = &p->part[k].cursor;
    int32_t ran = 0;
    for (;;) {
        uint64_t st = POOL_LOAD(cur);
        if ((uint32_t)(st >> 32) != gen) return 0;
        /* acquire: a count written after the close of this generation makes the claim below
         * see the close, and fail */
        int32_t begin = (int32_t)(uint32_t)st, count = POOL_LOAD(&p->count), least = POOL_LOAD(&p->least);
        int32_t pend = pool_part_end(count, POOL_LOAD(&p->parts), k);
        if (begin >= pend) {
            if (ran > 0) POOL_ADD(&p->part[k].done, ran);
            return 1;
        }
        /* half of what is left of the part (guided: the ranges shrink toward the end, so
         * the threads finish together), at least `least`, and all of it when less than
         * `least` would remain */
        int32_t left = pend - begin, take = left / 2 > least ? left / 2 : least;
        int32_t end = left - take < least ? pend : begin + take;
        uint64_t claimed = ((uint64_t)gen << 32) | (uint32_t)end;
        if (!__atomic_compare_exchange_n(cur, &st, claimed, 0, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE)) continue;
        /* the claim holds the task: it cannot end before this range is counted done */
        rg_task_fn *fn = POOL_RELAXED(&p->fn);
        fn(begin, end, worker, POOL_RELAXED(&p->context));
        ran += end - begin;
    }
}

/* The worker's own part, then the others'. */
static void pool_work(rg_thread_pool *p, uint32_t gen, int32_t worker)
{
    int32_t parts = POOL_LOAD(&p->parts);
    for (int32_t k = 0; k < parts; k++)
        if (!pool_work_part(p, gen, (worker + k) % parts, worker)) return;
}

static void *pool_main(void *arg)
{
    pool_thread *t = arg;
    rg_thread_pool *p = t->pool;
    uint32_t seen = 0;
    for (;;) {
        uint32_t g;
        int spins = 0;
        while ((g = (uint32_t)(POOL_LOAD(&p->state) >> 32)) == seen) {
            if (POOL_LOAD(&p->stop)) return NULL;
            if (++spins < POOL_SPINS) {
                pool_relax();
                continue;
            }
            pthread_mutex_lock(&p->lock);
            p->sleepers++;
            while ((uint32_t)(POOL_LOAD(&p->state) >> 32) == seen && !POOL_LOAD(&p->stop))
                pthread_cond_wait(&p->wake, &p->lock);
            p->sleepers--;
            pthread_mutex_unlock(&p->lock);
            spins = 0;
        }
        seen = g;
        pool_work(p, g, t->worker);
    }
}

static void *pool_enqueue(rg_task_fn *fn, int32_t count, int32_t min_range, void *context, void *user)
{
    rg_thread_pool *p = user;
    if (count <= 0) return NULL;
    if (p->threads < 2) {
        fn(0, count, 0, context);
        return NULL;
    }
    pthread_mutex_lock(&p->task_lock);
    /* a part per thread, fewer when a part would hold less than min_range */
    if (min_range < 1) min_range = 1;
    int32_t parts = count / min_range < p->threads ? count / min_range : p->threads;
    if (parts < 1) parts = 1;
    /* the last task's generation closed first (the file's opening comment), then the fields,
     * then the task under a generation of its own */
    uint32_t gen = (uint32_t)(POOL_RELAXED(&p->state) >> 32) + 1u;
    for (int32_t k = 0; k < p->threads; k++) POOL_STORE(&p->part[k].cursor, ((uint64_t)gen << 32) | POOL_CLOSED);
    gen++;
    POOL_SET(&p->fn, fn);
    POOL_SET(&p->context, context);
    POOL_STORE(&p->count, count);
    POOL_STORE(&p->least, min_range);
    POOL_STORE(&p->parts, parts);
    /* no thread holds a range of the last task (it ended), so none adds to a count now */
    for (int32_t k = 0; k < parts; k++) POOL_SET(&p->part[k].done, 0);
    /* each cursor publishes the fields above to the threads that claim from it */
    for (int32_t k = 0; k < parts; k++) {
        uint32_t start = k > 0 ? (uint32_t)pool_part_end(count, parts, k - 1) : 0u;
        POOL_STORE(&p->part[k].cursor, ((uint64_t)gen << 32) | start);
    }
    POOL_STORE(&p->state, (uint64_t)gen << 32);
    pthread_mutex_lock(&p->lock);
    if (p->sleepers > 0) pthread_cond_broadcast(&p->wake);
    pthread_mutex_unlock(&p->lock);
    pool_work(p, gen, 0);
    for (int32_t k = 0, spins = 0; k < parts; k++) {
        int32_t items = pool_part_end(count, parts, k) - (k > 0 ? pool_part_end(count, parts, k - 1) : 0);
        while (POOL_LOAD(&p->part[k].done) < items) {
            if (spins < POOL_SPINS) {
                spins++;
                pool_relax();
            } else {
                sched_yield();
            }
        }
    }
    pthread_mutex_unlock(&p->task_lock);
    return NULL;
}

static void pool_finish(void *task, void *user)
{
    (void)task;
    (void)user;
}

static void pool_stop(rg_thread_pool *p, int32_t started)
{
    pthread_mutex_lock(&p->lock);
    POOL_STORE(&p->stop, 1);
    pthread_cond_broadcast(&p->wake);
    pthread_mutex_unlock(&p->lock);
    for (int32_t k = 0; k < started; k++) pthread_join(p->th[k], NULL);
}

RG_API rg_status rg_thread_pool_create(int32_t threads, rg_thread_pool **out_pool)
{
    if (out_pool == NULL || threads < 1 || threads > RG_MAX_WORKERS) {
        if (out_pool != NULL) *out_pool = NULL;
        return RG_ERR_INVALID_ARGUMENT;
    }
    *out_pool = NULL;
    rg_thread_pool *p = calloc(1, sizeof *p);
    if (p == NULL) return RG_ERR_OUT_OF_MEMORY;
    p->threads = threads;
    p->part = calloc((size_t)threads, sizeof *p->part);
    if (threads > 1) {
        p->th = calloc((size_t)(threads - 1), sizeof *p->th);
        p->pt = calloc((size_t)(threads - 1), sizeof *p->pt);
    }
    if (p->part == NULL || (threads > 1 && (p->th == NULL || p->pt == NULL))) {
        free(p->part);
        free(p->th);
        free(p->pt);
        free(p);
        return RG_ERR_OUT_OF_MEMORY;
    }
    pthread_mutex_init(&p->task_lock, NULL);
    pthread_mutex_init(&p->lock, NULL);
    pthread_cond_init(&p->wake, NULL);
    for (int32_t k = 0; k < threads - 1; k++) {
        p->pt[k].pool = p;
        p->pt[k].worker = k + 1;
        if (pthread_create(&p->th[k], NULL, pool_main, &p->pt[k]) != 0) {
            pool_stop(p, k);
            pthread_cond_destroy(&p->wake);
            pthread_mutex_destroy(&p->lock);
            pthread_mutex_destroy(&p->task_lock);
            free(p->part);
            free(p->th);
            free(p->pt);
            free(p);
            return RG_ERR_CAPACITY;
        }
    }
    *out_pool = p;
    return RG_OK;
}

RG_API void rg_thread_pool_destroy(rg_thread_pool *pool)
{
    if (pool == NULL) return;
    pool_stop(pool, pool->threads - 1);
    pthread_cond_destroy(&pool->wake);
    pthread_mutex_destroy(&pool->lock);
    pthread_mutex_destroy(&pool->task_lock);
    free(pool->part);
    free(pool->th);
    free(pool->pt);
    free(pool);
}

RG_API rg_status rg_thread_pool_task_system(rg_thread_pool *pool, rg_task_system *out)
{
    if (pool == NULL || out == NULL) return RG_ERR_INVALID_ARGUMENT;
    out->workers = pool->threads;
    out->enqueue = pool_enqueue;
    out->finish = pool_finish;
    out->user = pool;
    return RG_OK;
}
