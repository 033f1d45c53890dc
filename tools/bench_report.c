/* bench_report.c: what the harness prints: a row per scene and engine as the runs finish, the
 * CSV, and the tables at the end (sleeping off: medians; sleeping on: means; the piles'
 * quality; memory; the free scenes), each engine's figure beside its ratio to rigid with as
 * many workers, measured in the same run. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench_run.h"

static void fmt_q(char *buf, size_t size, double v, const char *f)
{
    if (v != v) snprintf(buf, size, "-");
    else if (isinf(v)) snprintf(buf, size, "none");
    else snprintf(buf, size, f, v);
}

static void fmt_rest(char *buf, size_t size, double rest)
{
    if (rest != rest) snprintf(buf, size, "-");
    else if (rest < 0) snprintf(buf, size, "never");
    else snprintf(buf, size, "%.2f", rest);
}

static int capped(const bench_result *r) { return r->ok && r->steps < r->steps_asked; }

void bench_report_header(void)
{
    printf("%-19s %7s %-5s %-13s %8s %8s %8s %6s %8s %7s %7s %7s %7s %7s %7s %6s %4s %7s\n", "scene", "N",
           "sleep", "engine", "median", "mean", "p95", "spread", "ns/body", "B/body", "overlap", "mean",
           "wall", "peak", "vmax", "rest", "lost", "x rigid");
    printf("%-19s %7s %-5s %-13s %8s %8s %8s %6s %8s %7s %7s %7s %7s %7s %7s %6s %4s %7s\n", "", "", "", "",
           "ms/step", "ms/step", "ms/step", "%", "-step", "", "m", "m", "m", "m", "m/s", "s", "", "");
}

void bench_report_row(const bench_result *r)
{
    const char *sl = r->sleep ? "on" : "off";
    if (!r->ok) {
        printf("%-19s %7d %-5s %-13s %s\n", r->scene, (int)r->n, sl, r->who->label,
               r->who->engine == &bench_rigid_engine ? "n/a: scene needs what this build lacks" : "n/a");
        return;
    }
    char ov[16], mo[16], wl[16], pk[16], rest[16], ratio[24] = "-";
    fmt_q(pk, sizeof pk, r->q.peak, "%.4f");
    fmt_q(ov, sizeof ov, r->q.overlap, "%.4f");
    fmt_q(mo, sizeof mo, r->q.mean_overlap, "%.4f");
    fmt_q(wl, sizeof wl, r->q.wall, "%.4f");
    fmt_rest(rest, sizeof rest, r->q.rest);
    if (r->ref != NULL && r->ref != r->who && r->ref_median == r->ref_median) /* as the tables */
        snprintf(ratio, sizeof ratio, "%.2fx", r->sleep ? r->mean / r->ref_mean : r->median / r->ref_median);
    double spread = r->median > 0 ? 100.0 * (r->max_median - r->min_median) / r->median : 0;
    printf("%-19s %7d %-5s %-13s %8.3f %8.3f %8.3f %6.1f %8.2f %7.0f %7s %7s %7s %7s %7.3f %6s %4d %7s",
           r->scene, (int)r->n, sl, r->who->label, r->median, r->mean, r->p95, spread, r->ns_body,
           r->bytes_body, ov, mo, wl, pk, r->q.vmax, rest, (int)r->q.lost, ratio);
    if (capped(r)) printf("  capped: %d of %d steps", (int)r->steps, (int)r->steps_asked);
    printf("\n");
}

void bench_report_csv_header(FILE *f)
{
    fprintf(f, "scene,n,engine,workers,sleep,bodies,dynamic,runs,steps,median_ms,mean_ms,p95_ms,"
               "min_median_ms,max_median_ms,ns_per_body_step,bytes_per_body,peak_bytes_per_body,"
               "max_overlap_m,mean_overlap_m,max_wall_overlap_m,peak_overlap_m,max_speed_end,rest_s,lost,"
               "steady_state_alloc_calls,settling_mean_ms,rigid_median_ms,rigid_mean_ms\n");
}

void bench_report_csv_row(FILE *f, const bench_result *r)
{
    if (!r->ok) return;
    fprintf(f, "%s,%d,%s,%d,%d,%d,%d,%d,%d,%.6f,%.6f,%.6f,%.6f,%.6f,%.4f,%.1f,%.1f,%.6g,%.6g,%.6g,%.6g,%.6g,"
               "%.4g,%d,%lld,%.6f,%.6f,%.6f\n",
            r->scene, (int)r->n, r->who->label, (int)r->who->workers, (int)r->sleep, (int)r->nbodies,
            (int)r->ndynamic, (int)r->runs, (int)r->steps, r->median, r->mean, r->p95, r->min_median,
            r->max_median, r->ns_body, r->bytes_body, r->peak_body, r->q.overlap, r->q.mean_overlap,
            r->q.wall, r->q.peak, r->q.vmax, r->q.rest, (int)r->q.lost, (long long)r->steady_allocs, r->settling,
            r->ref_median, r->ref_mean);
}

void bench_report_machine(FILE *f)
{
    char model[128] = "unknown", family[16] = "?", modelno[16] = "?", line[256];
    FILE *c = fopen("/proc/cpuinfo", "r");
    if (c != NULL) {
        while (fgets(line, sizeof line, c) != NULL) {
            char *v = strchr(line, ':');
            if (v == NULL) continue;
            v++;
            while (*v == ' ' || *v == '\t') v++;
            v[strcspn(v, "\n")] = 0;
            if (strncmp(line, "model name", 10) == 0 && strcmp(model, "unknown") == 0)
                snprintf(model, sizeof model, "%s", v);
            else if (strncmp(line, "cpu family", 10) == 0 && family[0] == '?')
                snprintf(family, sizeof family, "%s", v);
            else if (strncmp(line, "model\t", 6) == 0 && modelno[0] == '?')
                snprintf(modelno, sizeof modelno, "%s", v);
        }
        fclose(c);
    }
    char load[64] = "?";
    FILE *l = fopen("/proc/loadavg", "r");
    if (l != NULL) {
        if (fgets(load, sizeof load, l) == NULL) snprintf(load, sizeof load, "?");
        load[strcspn(load, "\n")] = 0;
        fclose(l);
    }
    fprintf(f, "machine: %ld cpus, %s (family %s model %s), AVX2+FMA %s; load average %s\n",
            sysconf(_SC_NPROCESSORS_ONLN), model, family, modelno, bench_cpu_has_avx2() ? "yes" : "no", load);
    double trip = bench_cores_round_trip_ns();
    if (trip > 0)
        fprintf(f, "machine: a cache line to another core and back (two threads handing a counter over): %.0f ns\n",
                trip);
    double other, own, shared, shuffled; /* only where the threads run at once, as the round trip shows */
    if (trip > 0 && bench_cores_lines_ns(&other, &own, &shared, &shuffled))
        fprintf(f, "machine: 8192 cache lines: reading at random %.1f ns a line another core has just written, "
                "%.1f ns a line of this core's own; writing lines another core has just read %.1f ns a line in "
                "order, %.1f at random\n", other, own, shared, shuffled);
    double fast, slow;
    if (trip > 0 && bench_cores_speeds_ns(&fast, &slow))
        fprintf(f, "machine: two threads at once, each adding to a counter in memory: %.2f and %.2f ns an "
                "addition (the slower %.2fx the faster)\n", fast, slow, slow / fast);
}

/* ---------------------------------------------------------------- the tables */

/* A cell of a table: the figure and its ratio, into buf; 0 when the result has none.  rigid:
 * rigid's one-worker result of the same scene, N and sleeping, or NULL. */
typedef int cell_fn(const bench_result *r, const bench_result *rigid, char *buf, size_t size);

/* figure, then figure's time over rigid's (when there is a reference), * when capped. */
static int cell_ratio(const bench_result *r, double figure, double time, double ref_time, char *buf,
                      size_t size)
{
    if (r->ref == r->who || ref_time != ref_time) snprintf(buf, size, "%.3f", figure);
    else snprintf(buf, size, "%.3f %5.1fx", figure, time / ref_time);
    if (capped(r)) strncat(buf, "*", size - strlen(buf) - 1);
    return 1;
}

static int cell_median(const bench_result *r, const bench_result *rigid, char *buf, size_t size)
{
    (void)rigid;
    return cell_ratio(r, r->median, r->median, r->ref_median, buf, size);
}

static int cell_mean(const bench_result *r, const bench_result *rigid, char *buf, size_t size)
{
    (void)rigid;
    return cell_ratio(r, r->mean, r->mean, r->ref_mean, buf, size);
}

static int cell_ns(const bench_result *r, const bench_result *rigid, char *buf, size_t size)
{
    (void)rigid;
    return cell_ratio(r, r->ns_body, r->median, r->ref_median, buf, size);
}

static int cell_bytes(const bench_result *r, const bench_result *rigid, char *buf, size_t size)
{
    (void)rigid;
    snprintf(buf, size, "%.0f", r->bytes_body);
    return 1;
}

/* Overlap in mm, deepest / mean, then deepest against rigid's (x: times deeper). */
static int cell_overlap(const bench_result *r, const bench_result *rg, char *buf, size_t size)
{
    if (r->q.overlap != r->q.overlap) return 0;
    if (rg != NULL && rg != r && rg->q.overlap > 0)
        snprintf(buf, size, "%.2f/%.2f %4.0fx", 1e3 * r->q.overlap, 1e3 * r->q.mean_overlap,
                 r->q.overlap / rg->q.overlap);
    else
        snprintf(buf, size, "%.2f/%.2f", 1e3 * r->q.overlap, 1e3 * r->q.mean_overlap);
    if (capped(r)) strncat(buf, "*", size - strlen(buf) - 1);
    return 1;
}

static int cell_rest(const bench_result *r, const bench_result *rigid, char *buf, size_t size)
{
    (void)rigid;
    fmt_rest(buf, size, r->q.rest);
    if (capped(r)) strncat(buf, "*", size - strlen(buf) - 1);
    return r->q.rest == r->q.rest;
}

static const bench_result *rigid_of(const bench_result *rs, int32_t nr, const bench_result *r)
{
    for (int32_t i = 0; i < nr; i++)
        if (rs[i].ok && rs[i].who->engine == &bench_rigid_engine && rs[i].who->workers == 1 &&
            rs[i].n == r->n && rs[i].sleep == r->sleep && strcmp(rs[i].scene, r->scene) == 0)
            return &rs[i];
    return NULL;
}

enum { ROWS_PILES = 0, ROWS_FREE = 1 };

static int row_wanted(const bench_result *r, int rows)
{
    const bench_scene_def *d = r->def;
    if (d->variant != BENCH_PLAIN) return 0;
    if (rows == ROWS_FREE) return !d->shaped;
    return d->sleep_both;
}

/* One table: a row per (scene, N) of the kind asked at this sleeping setting, a column per
 * entrant (one-worker entrants only when single). */
static void table(const char *title, const bench_result *rs, int32_t nr, const bench_entrant *who,
                  int nwho, int rows, int32_t sleep, int single, cell_fn *cell, int width)
{
    int any = 0;
    for (int32_t i = 0; i < nr; i++) {
        const bench_result *r = &rs[i];
        if (!r->ok || r->sleep != sleep || !row_wanted(r, rows)) continue;
        int first = 1; /* the first result of its (scene, N, sleep) */
        for (int32_t j = 0; j < i && first; j++)
            first = !(rs[j].ok && rs[j].sleep == sleep && rs[j].n == r->n && strcmp(rs[j].scene, r->scene) == 0);
        if (!first) continue;
        if (!any) {
            printf("\n%s\n%-7s %7s", title, "scene", "N");
            for (int e = 0; e < nwho; e++)
                if (who[e].engine != &bench_floor_engine && (!single || who[e].workers == 1))
                    printf(" %*s", width, who[e].label);
            printf("\n");
            any = 1;
        }
        printf("%-7s %7d", r->scene, (int)r->n);
        for (int e = 0; e < nwho; e++) {
            if (who[e].engine == &bench_floor_engine || (single && who[e].workers != 1)) continue;
            const bench_result *c = bench_find(rs, nr, r->scene, r->n, sleep, who[e].label);
            char buf[48] = "-";
            if (c == NULL || !cell(c, rigid_of(rs, nr, c), buf, sizeof buf)) snprintf(buf, sizeof buf, "-");
            printf(" %*s", width, buf);
        }
        printf("\n");
    }
}

static void print_capped(const bench_result *rs, int32_t nr)
{
    int any = 0;
    for (int32_t i = 0; i < nr; i++) {
        if (!capped(&rs[i])) continue;
        if (!any) printf("\n*: capped (the run's stepping time ran out):");
        any = 1;
        printf(" %s %s %d (sleep %s): %d of %d steps;", rs[i].who->label, rs[i].scene, (int)rs[i].n,
               rs[i].sleep ? "on" : "off", (int)rs[i].steps, (int)rs[i].steps_asked);
    }
    if (any) printf("\n   its figures are over those steps, and so are rigid's in its ratio; its quality is "
                    "the state where it stopped\n");
}

/* What more workers buy, and whether they change the result: each threaded run against the
 * same engine's one-worker run of the scene (time, and the final state's hash). */
static void print_threads(const bench_result *rs, int32_t nr)
{
    int any = 0, differ = 0, varies = 0;
    for (int32_t i = 0; i < nr; i++) {
        const bench_result *r = &rs[i], *one = NULL;
        varies |= r->ok && r->hash_varies;
        if (!r->ok || r->who->workers == 1) continue;
        for (int32_t j = 0; j < nr && one == NULL; j++)
            if (rs[j].ok && rs[j].who->engine == r->who->engine && rs[j].who->workers == 1 && rs[j].n == r->n &&
                rs[j].sleep == r->sleep && strcmp(rs[j].scene, r->scene) == 0)
                one = &rs[j];
        if (one == NULL) continue;
        if (!any) printf("\nthreads: one worker's time over N workers' (median, sleeping on: mean), and the final "
                         "state (hash) against one worker's:\n");
        any = 1;
        int same = !r->has_hash || (r->hash == one->hash && r->steps == one->steps);
        differ |= !same;
        printf("  %-13s %-7s %7d sleep %-3s %5.2fx%s\n", r->who->label, r->scene, (int)r->n, r->sleep ? "on" : "off",
               r->sleep ? one->mean / r->mean : one->median / r->median,
               !r->has_hash ? "" : r->steps != one->steps ? "  (capped: not compared)" : same ? "  same state"
                                                                                             : "  STATE DIFFERS");
    }
    if (any && !differ) printf("  every threaded run that hashes ended in its one-worker run's state\n");
    if (varies) printf("\nSOME ENGINE ENDED IN DIFFERENT STATES IN RUNS OF THE SAME SCENE (see the hashes in the CSV)\n");
}

/* No allocation in a steady-state step: allocator calls in the second half of each run, for
 * the engines that count them, per engine: in how many of its scenes any, and the most. */
static void print_allocs(const bench_result *rs, int32_t nr, const bench_entrant *who, int nwho)
{
    int any = 0;
    for (int e = 0; e < nwho; e++) {
        int32_t scenes = 0, with = 0;
        const bench_result *most = NULL;
        for (int32_t i = 0; i < nr; i++) {
            const bench_result *r = &rs[i];
            if (!r->ok || r->steady_allocs < 0 || strcmp(r->who->label, who[e].label) != 0) continue;
            scenes++;
            if (r->steady_allocs > 0) with++;
            if (r->steady_allocs > 0 && (most == NULL || r->steady_allocs > most->steady_allocs)) most = r;
        }
        if (scenes == 0) continue;
        if (!any) printf("\nallocator calls in the second half of each run (the steady state; engines that count them):\n");
        any = 1;
        if (most == NULL)
            printf("  %-13s none in any of its %d scene runs\n", who[e].label, (int)scenes);
        else
            printf("  %-13s some in %d of its %d scene runs, the most %lld (%s %d, sleeping %s)\n", who[e].label,
                   (int)with, (int)scenes, (long long)most->steady_allocs, most->scene, (int)most->n,
                   most->sleep ? "on" : "off");
    }
}

/* What the step costs for stages a scene does not use: should be (about) nothing. */
static void print_stage_costs(const bench_result *rs, int32_t nr)
{
    const bench_result *sp = bench_find(rs, nr, "sparse", 0, -1, "rigid");
    const bench_result *fd = bench_find(rs, nr, "free0", 0, -1, "rigid");
    const bench_result *fn = bench_find(rs, nr, "free-nodrag", 0, -1, "rigid");
    const bench_result *fl = bench_find(rs, nr, "free-nodrag", 0, -1, "floor");
    const bench_result *fld = bench_find(rs, nr, "free0", 0, -1, "floor");
    if (sp == NULL && fn == NULL) return;
    printf("\nstage costs (rigid; a stage nobody uses should cost nothing):\n");
    if (fn != NULL && fd != NULL && fd->n == fn->n)
        printf("  drag: free0 (linear drag on every body) %.3f ns/body-step; free-nodrag (none set) "
               "%.3f ns/body-step\n", fd->ns_body, fn->ns_body);
    if (fn != NULL && fl != NULL && fl->n == fn->n)
        printf("  free-nodrag %.3f ns/body-step vs the floor loop (x, y, vx, vy only) %.3f: %.2fx\n",
               fn->ns_body, fl->ns_body, fn->ns_body / fl->ns_body);
    if (fd != NULL && fld != NULL && fld->n == fd->n)
        printf("  free0 %.3f ns/body-step vs the floor loop with drag %.3f: %.2fx\n", fd->ns_body,
               fld->ns_body, fd->ns_body / fld->ns_body);
    if (sp != NULL && fn != NULL) {
        /* Means, not medians: the 1% settle and may sleep, which a median hides. */
        int32_t shaped = sp->n / 100 > 0 ? sp->n / 100 : 1;
        const bench_result *rain = bench_find(rs, nr, "rain", shaped, sp->sleep, "rigid");
        double particles = fn->mean * (double)(sp->n - shaped) / fn->n;
        printf("  sparse %d (1%% shaped, sleep %s): mean %.3f ms/step; its %d shape-less bodies at "
               "free-nodrag's rate: %.3f ms; so the 1%% with collision: %.3f ms",
               (int)sp->n, sp->sleep ? "on" : "off", sp->mean, (int)(sp->n - shaped), particles,
               sp->mean - particles);
        if (rain != NULL)
            printf(" vs rain %d alone: mean %.3f ms (%.2fx)\n", (int)shaped, rain->mean,
                   (sp->mean - particles) / rain->mean);
        else
            printf(" (run rain:%d to compare)\n", (int)shaped);
    }
}

/* The gameplay variants against their plain scenes (tools/bench_gameplay.c). */
static void print_gameplay(const bench_result *rs, int32_t nr)
{
    bench_gameplay_row *rows = calloc((size_t)(nr > 0 ? nr : 1), sizeof *rows);
    int32_t n = 0;
    if (rows == NULL) return;
    for (int32_t i = 0; i < nr; i++) {
        const bench_result *r = &rs[i];
        if (!r->ok || r->who->engine != &bench_rigid_engine || r->def->variant == BENCH_PLAIN) continue;
        rows[n++] = (bench_gameplay_row){ r->scene, r->def->base, r->n, r->def->variant, r->median,
                                          r->min_median, r->max_median, r->contacts };
    }
    bench_gameplay_report(rows, n);
    free(rows);
}

void bench_report_summary(const bench_result *rs, int32_t nr, const bench_entrant *who, int nwho,
                          const bench_options *opts)
{
    char title[512];
    snprintf(title, sizeof title,
             "== sleeping OFF for every engine: median ms per step over %d steps (medians of %d runs); "
             "after each figure, the engine's over rigid's with as many workers, same run",
             (int)opts->steps, (int)opts->repeats);
    table(title, rs, nr, who, nwho, ROWS_PILES, 0, 0, cell_median, 13);
    snprintf(title, sizeof title,
             "== sleeping ON for every engine (each its own thresholds): mean ms per step over the %d "
             "steps, the total a game pays; ratios as above", (int)opts->steps);
    table(title, rs, nr, who, nwho, ROWS_PILES, 1, 0, cell_mean, 13);
    table("== the piles' quality, sleeping off: overlap at the end in mm, deepest between two moving "
          "bodies / mean over the overlapping pairs; x: deepest against rigid's",
          rs, nr, who, nwho, ROWS_PILES, 0, 1, cell_overlap, 17);
    table("== time to rest with sleeping on: s until the fastest body stays below 0.1 m/s",
          rs, nr, who, nwho, ROWS_PILES, 1, 1, cell_rest, 10);
    table("== memory: bytes per body held at the end (all bodies, static too), sleeping off",
          rs, nr, who, nwho, ROWS_PILES, 0, 0, cell_bytes, 13);
    table(bench_cpu_has_avx2()
              ? "== free scenes (no shapes): ns per body-step (median; this CPU has AVX2, which a GCC/glibc "
                "x86-64 build of rigid picks at load); x: against rigid's"
              : "== free scenes (no shapes): ns per body-step (median; no AVX2 here: rigid's portable pass); "
                "x: against rigid's",
          rs, nr, who, nwho, ROWS_FREE, 0, 0, cell_ns, 13);
    print_capped(rs, nr);
    print_threads(rs, nr);
    print_stage_costs(rs, nr);
    print_gameplay(rs, nr);
    print_allocs(rs, nr, who, nwho);
}
