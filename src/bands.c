/* bands.c: phases over bands at once (see bands.h).
 *
 * Each band has a line of its own: whether a thread holds it (only the holder runs its
 * phases), how many of its phases have run whole (`next`, the holder's to write), and how
 * many have had their edge rows run (`edge`, published before the phase's inner rows).  Band
 * b may run phase s when every other band's `edge` is at least s.  The band with the fewest
 * phases run can always run its next one: every other band has run at least as many, edge
 * rows included.  A thread holds its own band (the one its range names) and runs its phases
 * while it may; when it may not, it runs one phase of the band furthest behind that no thread
 * holds, and comes back to its own.  A holder's writes reach the next holder through the
 * release of `held` and the acquire of its claim, and the edge rows' writes reach the other
 * bands through `edge`. */
#include <stdint.h>

#include "bands.h"
#include "task.h"

#if defined(__GNUC__) || defined(__clang__)
#define BANDS_ATOMIC 1
#define BANDS_LOAD(p) __atomic_load_n((p), __ATOMIC_ACQUIRE)
#define BANDS_STORE(p, v) __atomic_store_n((p), (v), __ATOMIC_RELEASE)
#else
#define BANDS_ATOMIC 0
#endif

typedef struct bands_line {
    int32_t held; /* atomic: a thread runs the band's phases */
    int32_t next; /* atomic: phases run whole (the holder writes it) */
    int32_t edge; /* atomic: phases whose edge rows have run */
    char pad[64 - 3 * sizeof(int32_t)];
} bands_line;

typedef struct bands_job {
    bands_line room[BANDS_MAX + 1]; /* the lines, from the first 64-byte boundary in it */
    bands_line *line;
    int32_t bands, phases;
    bands_fn *fn;
    void *context;
} bands_job;

int bands_available(void) { return BANDS_ATOMIC; }

#if BANDS_ATOMIC
static inline void bands_relax(void)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#elif defined(__aarch64__)
    __asm__ __volatile__("yield");
#endif
}

/* Whether band b may run phase s: every other band has run the edge rows of phase s - 1. */
static int bands_ready(const bands_job *j, int32_t b, int32_t s)
{
    for (int32_t u = 0; u < j->bands; u++)
        if (u != b && BANDS_LOAD(&j->line[u].edge) < s) return 0;
    return 1;
}

static int bands_hold(bands_line *l)
{
    int32_t free_ = 0;
    return __atomic_load_n(&l->held, __ATOMIC_RELAXED) == 0 &&
           __atomic_compare_exchange_n(&l->held, &free_, 1, 0, __ATOMIC_ACQUIRE, __ATOMIC_RELAXED);
}

/* Runs up to `most` phases of band b, which the caller holds, while it may; returns how many. */
static int32_t bands_advance(bands_job *j, int32_t b, int32_t most)
{
    bands_line *l = &j->line[b];
    int32_t s = BANDS_LOAD(&l->next), ran = 0;
    while (s < j->phases && ran < most && bands_ready(j, b, s)) {
        j->fn(b, s, 1, j->context);
        BANDS_STORE(&l->edge, s + 1);
        j->fn(b, s, 0, j->context);
        BANDS_STORE(&l->next, ++s);
        ran++;
    }
    BANDS_STORE(&l->held, 0);
    return ran;
}

/* The band furthest behind that no thread holds and that has phases left, or -1. */
static int32_t bands_behind(const bands_job *j)
{
    int32_t u = -1, least = j->phases;
    for (int32_t v = 0; v < j->bands; v++) {
        int32_t n = BANDS_LOAD(&j->line[v].next);
        if (n < least && __atomic_load_n(&j->line[v].held, __ATOMIC_RELAXED) == 0) {
            least = n;
            u = v;
        }
    }
    return u;
}

static void bands_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    bands_job *j = context;
    (void)worker;
    for (int32_t b = begin; b < end; b++) {
        bands_line *l = &j->line[b];
        while (BANDS_LOAD(&l->next) < j->phases) {
            int32_t ran = 0;
            if (bands_hold(l)) ran += bands_advance(j, b, j->phases);
            if (BANDS_LOAD(&l->next) >= j->phases) break;
            int32_t u = bands_behind(j);
            if (u >= 0 && bands_hold(&j->line[u])) ran += bands_advance(j, u, 1);
            if (ran == 0) bands_relax();
        }
    }
}
#endif

void bands_run(struct rg_world *w, int32_t bands, int32_t phases, bands_fn *fn, void *context)
{
#if BANDS_ATOMIC
    bands_job j;
    j.line = (bands_line *)(void *)(((uintptr_t)(void *)j.room + 63) & ~(uintptr_t)63);
    for (int32_t b = 0; b < bands; b++) j.line[b].held = j.line[b].next = j.line[b].edge = 0;
    j.bands = bands;
    j.phases = phases;
    j.fn = fn;
    j.context = context;
    task_for(w, bands_range, bands, 1, &j);
#else
    (void)w;
    for (int32_t s = 0; s < phases; s++)
        for (int32_t b = 0; b < bands; b++) {
            fn(b, s, 1, context);
            fn(b, s, 0, context);
        }
#endif
}
