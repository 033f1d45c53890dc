/* shock.c: the shock sweeps on two workers at once (see shock.h).
 *
 * Each chain has a line of its own: whether a thread holds it (only the holder runs its
 * rows) and how many of its rows have run (`done`, the holder's to write, published every
 * SHOCK_RUN rows).  A holder's writes reach the next holder through the release of `held`
 * and the acquire of its claim, and the other chain's rows through `done`. */
#include <string.h>

#include "shock.h"
#include "task.h"
#include "vec2.h"

#if defined(__GNUC__) || defined(__clang__)
#define SHOCK_ATOMIC 1
#define SHOCK_LOAD(p) __atomic_load_n((p), __ATOMIC_ACQUIRE)
#define SHOCK_STORE(p, v) __atomic_store_n((p), (v), __ATOMIC_RELEASE)
#else
#define SHOCK_ATOMIC 0
#endif

/* Rows a chain runs before it publishes its progress: the other chain may be waiting for
 * any of them. */
#define SHOCK_RUN 64

int shock_available(void) { return SHOCK_ATOMIC; }

/* (shock.h) last[q]: 0 while no row has met solver body q, else k + 1 for chain 0's row k,
 * -(k + 1) for chain 1's. */
void shock_plan(shock_chains *ch, const int32_t *ord, int32_t nc, const int32_t *ab, const rg_real *x,
                const rg_real *y, rg_real ux, rg_real uy, rg_real split, int32_t *last, int32_t bodies,
                rg_real *lo, rg_real *hi)
{
    int32_t n[2] = { 0, 0 };
    rg_real least = RG_HUGE, most = -RG_HUGE;
    memset(last, 0, (size_t)bodies * sizeof *last);
    for (int32_t j = 0; j < nc; j++) {
        int32_t r = ord[j], qa = ab[2 * r], qb = ab[2 * r + 1], q = qa > 0 ? qa : qb;
        int s = 0;
        if (q > 0) {
            rg_real across = x[q - 1] * uy - y[q - 1] * ux;
            least = rg_min(least, across);
            most = rg_max(most, across);
            s = across >= split;
        }
        /* the last row of the other chain that met a body of this one */
        int32_t la = s ? last[qa] : -last[qa], lb = s ? last[qb] : -last[qb];
        int32_t need = la > lb ? la : lb;
        int32_t k = n[s]++;
        ch->row[s][k] = r;
        ch->need[s][k] = need > 0 ? need : 0;
        int32_t tag = s ? -(k + 1) : k + 1;
        if (qa > 0) last[qa] = tag;
        if (qb > 0) last[qb] = tag;
    }
    ch->n[0] = n[0];
    ch->n[1] = n[1];
    *lo = least;
    *hi = most;
}

#if SHOCK_ATOMIC
typedef struct shock_line {
    int32_t held; /* atomic: a thread runs the chain's rows */
    int32_t done; /* atomic: rows run (the holder writes it) */
    char pad[64 - 2 * sizeof(int32_t)];
} shock_line;

typedef struct shock_job {
    shock_line room[3]; /* the lines, from the first 64-byte boundary in it */
    shock_line *line;
    const shock_chains *ch;
    solver_constraint *c;
    rg_real *v, gx, gy;
    int position;
} shock_job;

static inline void shock_relax(void)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#elif defined(__aarch64__)
    __asm__ __volatile__("yield");
#endif
}

static int shock_hold(shock_line *l)
{
    int32_t free_ = 0;
    return __atomic_load_n(&l->held, __ATOMIC_RELAXED) == 0 &&
           __atomic_compare_exchange_n(&l->held, &free_, 1, 0, __ATOMIC_ACQUIRE, __ATOMIC_RELAXED);
}

/* Runs rows of chain s, which the caller holds, from its `done` while their needs are met,
 * SHOCK_RUN at most, and publishes them; returns how many ran. */
static int32_t shock_step(shock_job *j, int s)
{
    const shock_chains *ch = j->ch;
    const int32_t *row = ch->row[s], *need = ch->need[s];
    int32_t k = SHOCK_LOAD(&j->line[s].done), n = ch->n[s], seen = SHOCK_LOAD(&j->line[1 - s].done), e = k;
    while (e < n && e - k < SHOCK_RUN && need[e] <= seen) e++;
    if (e == k) return 0;
    if (j->position)
        solver_shock_position(j->c, row + k, e - k, j->v, j->gx, j->gy);
    else
        solver_shock(j->c, row + k, e - k, j->v, j->gx, j->gy);
    SHOCK_STORE(&j->line[s].done, e);
    return e - k;
}

/* Items are chains: a thread holds its own and runs it to the end.  Where a row waits for
 * the other chain and no thread holds that one, it runs the other chain itself until the row
 * may go on (then lets it go, for its thread to take up); where a thread holds it, it waits. */
static void shock_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    shock_job *j = context;
    (void)worker;
    for (int32_t s = begin; s < end; s++) {
        shock_line *l = &j->line[s], *o = &j->line[1 - s];
        int32_t n = j->ch->n[s];
        int mine = 0;
        while (SHOCK_LOAD(&l->done) < n) {
            if (!mine && !(mine = shock_hold(l))) { /* a thread helping it holds it a while */
                shock_relax();
                continue;
            }
            if (shock_step(j, (int)s) > 0) continue;
            if (__atomic_load_n(&o->held, __ATOMIC_RELAXED) == 0 && shock_hold(o)) {
                while (shock_step(j, 1 - (int)s) > 0 && shock_step(j, (int)s) == 0) {
                }
                SHOCK_STORE(&o->held, 0);
            } else {
                shock_relax();
            }
        }
        if (mine) SHOCK_STORE(&l->held, 0);
    }
}

void shock_run(struct rg_world *w, const shock_chains *ch, solver_constraint *c, rg_real *v, rg_real gx,
               rg_real gy, int position)
{
    shock_job j;
    j.line = (shock_line *)(void *)(((uintptr_t)(void *)j.room + 63) & ~(uintptr_t)63);
    for (int s = 0; s < 2; s++) j.line[s].held = j.line[s].done = 0;
    j.ch = ch;
    j.c = c;
    j.v = v;
    j.gx = gx;
    j.gy = gy;
    j.position = position;
    task_for(w, shock_range, 2, 1, &j);
}

void shock_once(int32_t *state, void (*fn)(void *), void *context)
{
    int32_t idle = 0;
    if (__atomic_compare_exchange_n(state, &idle, 1, 0, __ATOMIC_ACQUIRE, __ATOMIC_RELAXED)) {
        fn(context);
        SHOCK_STORE(state, 2);
        return;
    }
    while (SHOCK_LOAD(state) != 2) shock_relax();
}
#else
/* One thread: whichever chain's next row has its need met runs (shock.h). */
void shock_run(struct rg_world *w, const shock_chains *ch, solver_constraint *c, rg_real *v, rg_real gx,
               rg_real gy, int position)
{
    int32_t k[2] = { 0, 0 };
    (void)w;
    while (k[0] < ch->n[0] || k[1] < ch->n[1])
        for (int s = 0; s < 2; s++)
            for (; k[s] < ch->n[s] && ch->need[s][k[s]] <= k[1 - s]; k[s]++) {
                if (position)
                    solver_shock_position(c, ch->row[s] + k[s], 1, v, gx, gy);
                else
                    solver_shock(c, ch->row[s] + k[s], 1, v, gx, gy);
            }
}

void shock_once(int32_t *state, void (*fn)(void *), void *context)
{
    if (*state == 0) fn(context);
    *state = 2;
}
#endif
