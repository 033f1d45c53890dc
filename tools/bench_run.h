/* bench_run.h: what the parts of the harness share (bench.c runs, bench_report.c prints,
 * bench_sweep.c sweeps solver settings): who runs (an engine at a worker count), the
 * figures of a run, and the figures of a scene over its runs. */
#ifndef RG_BENCH_RUN_H
#define RG_BENCH_RUN_H

#include <stdio.h>

#include "bench.h"

#define BENCH_DT (1.0 / 60.0)
#define BENCH_MAX_ENTRANTS 12
#define BENCH_SAMPLE_EVERY 10  /* steps between (untimed) samples for the rest time and peak */

/* An engine at a worker count, as the tables name it ("rigid", "rigid-2w", "b2v3-avx2"). */
typedef struct bench_entrant {
    const bench_engine *engine;
    int32_t workers;
    char label[24];
} bench_entrant;

typedef struct bench_options {
    int32_t steps;       /* steps asked of every run */
    int32_t repeats;     /* runs per scene and entrant, entrants interleaved */
    double budget_s;     /* a run stops after this much stepping time (its steps are capped) */
    FILE *dump;          /* --dump: the final state of every dynamic body of every run */
} bench_options;

/* A scene at a size; sleep: 0 off, 1 on, -1 as the scene's definition says. */
typedef struct bench_job {
    const bench_scene_def *def;
    int32_t n, sleep;
} bench_job;

/* One run of one entrant. */
typedef struct bench_run {
    int ok;
    int32_t steps;             /* steps done: fewer than asked when the budget ran out */
    double *times;             /* ms of each step done (owned) */
    double median, mean, p95;  /* ms per step */
    double settling;           /* mean ms per step until the rest time (all steps if none) */
    size_t bytes, peak;
    int64_t steady_allocs;     /* allocator calls in the second half of the steps; -1 unknown */
    bench_quality q;
    bench_contacts contacts;   /* mean per step over all steps */
    uint64_t hash;             /* of the final state, when the engine has a hash */
} bench_run;

/* A scene at one size and sleeping setting, one entrant, over its runs (medians). */
typedef struct bench_result {
    const bench_scene_def *def;
    char scene[32];
    int32_t n, sleep;
    const bench_entrant *who;
    int32_t nbodies, ndynamic;
    int32_t runs, steps, steps_asked;  /* steps: the fewest any run did */
    int ok;
    double median, mean, p95, min_median, max_median;
    double settling;
    double ns_body;
    double bytes_body, peak_body;      /* peak_body 0: unknown */
    int64_t steady_allocs;             /* most over the runs; -1 unknown */
    bench_quality q;                   /* of the last run */
    bench_contacts contacts;           /* medians over the runs of the means per step */
    int has_hash;                      /* hash: the final state's, the same in every run */
    uint64_t hash;
    int hash_varies;                   /* 1: runs ended in different states */
    int32_t solver_set, solver[2];     /* the solver setting it ran with (bench_sweep.c) */
    /* rigid with as many workers (else one) over the same steps, for the ratios; NaN when
     * rigid did not run */
    const bench_entrant *ref;
    double ref_median, ref_mean;
} bench_result;

/* bench.c: runs s on every entrant opts->repeats times (entrants interleaved) and fills
 * out[k] for who[k]; ref_median/ref_mean come from the first rigid entrant with as many
 * workers (else one worker) among who.  0 when out of memory. */
int bench_run_scene(const bench_scene *s, const bench_scene_def *d, const bench_entrant *const *who,
                    int nwho, const bench_options *opts, bench_result *out);
const bench_result *bench_find(const bench_result *rs, int32_t nr, const char *scene, int32_t n,
                               int32_t sleep, const char *label);

/* bench_report.c */
void bench_report_header(void);
void bench_report_row(const bench_result *r);
void bench_report_csv_header(FILE *f);
void bench_report_csv_row(FILE *f, const bench_result *r);
void bench_report_machine(FILE *f);
/* The median time of a cache line's round trip between two threads (bench_cores.c); -1
 * with one cpu. */
double bench_cores_round_trip_ns(void);
/* The median time a line of reading, in a random order, 8192 cache lines another thread has
 * just written (*other) and lines this thread wrote (*own), and of writing them after the
 * other thread has read them, in order (*shared) and in the random order (*shared_shuffled)
 * (bench_cores.c); 0 with one cpu or when the threads cannot run at once. */
int bench_cores_lines_ns(double *other, double *own, double *shared, double *shared_shuffled);
/* Two threads adding to a counter in memory at once, each timing its own: the median ns an
 * addition of the faster (*fast) and of the slower (*slow) (bench_cores.c); 0 with one cpu
 * or when the threads cannot run at once. */
int bench_cores_speeds_ns(double *fast, double *slow);
/* The three on one line to f, "machine WHEN: ..." (bench_cores.c); nothing with one cpu, and
 * a line saying so when two threads cannot run at once. */
void bench_cores_line(FILE *f, const char *when);
/* The tables: sleeping off (medians), sleeping on (means), quality, memory, free0; the
 * stage costs, the gameplay collision, the allocator calls. */
void bench_report_summary(const bench_result *rs, int32_t nr, const bench_entrant *who, int nwho,
                          const bench_options *opts);

/* bench_sweep.c: quality against cost (--sweep): each engine at several solver settings on
 * the given scenes, sleeping off (time, overlaps) and on (time, rest), printed and written
 * as CSV to csv when not NULL. */
int bench_sweep(const bench_job *jobs, int njobs, const bench_entrant *who, int nwho,
                const bench_options *opts, const char *csv);

#endif
