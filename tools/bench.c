/* bench.c: the benchmark harness: named scenes at several sizes on rigid, Box2D v3 (its SSE2
 * and AVX2 builds, loaded from their own build) and, when built with them, Box2D 2.4 and
 * Chipmunk 7, side by side in one run.
 *
 *   bench [--quick] [--scene NAME[:N,N...]]... [--engine a,b] [--steps S] [--repeats R]
 *         [--sleep off|on|both] [--workers N] [--budget SECONDS] [--sweep] [--v3 DIR|none]
 *         [--csv FILE] [--dump FILE] [--list]
 *
 * Every engine runs the same body list (bench.h) for S steps of 1/60 s; each step is timed
 * alone.  An engine that can use threads runs once with one worker and once with N (all the
 * machine's cores by default).  A run gives the median, mean and 95th percentile of its step
 * times; a scene is run R times per engine, engines interleaved, and the figures printed
 * are the medians over the runs.  The piles run with sleeping off (every engine, the main
 * table: medians) and on (the second table: means, what a game pays over the whole run).
 * Quality is measured by one piece of code for every engine from the state each hands back
 * (bench_quality.c).  A run that exceeds the budget of stepping time stops there; its
 * figures are over the steps it did and its ratios against rigid's same steps.  The runs
 * themselves are bench_run.c's. */
#define _GNU_SOURCE 1 /* sysconf's _SC_NPROCESSORS_ONLN */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench_run.h"

/* ---------------------------------------------------------------- entrants */

/* Every engine this build has, each with one worker and, when it can use threads, with
 * `workers` (when more than one). */
static int entrants(bench_entrant *who, int32_t workers, const char *v3_dir, char *why, size_t why_size)
{
    const bench_engine *v3[2];
    bench_v3_load(v3_dir, v3, why, why_size);
    const bench_engine *all[] = {
        &bench_rigid_engine, v3[0], v3[1],
#ifdef RG_BENCH_PEERS
        &bench_box2d_engine, &bench_chipmunk_engine,
#endif
        &bench_floor_engine,
    };
    int n = 0;
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++) {
        if (all[i] == NULL) continue;
        for (int t = 0; t < 2 && n < BENCH_MAX_ENTRANTS; t++) {
            int32_t w = t == 0 ? 1 : workers;
            if (t == 1 && (!all[i]->threaded || workers < 2)) break;
            who[n].engine = all[i];
            who[n].workers = w;
            if (w > 1) snprintf(who[n].label, sizeof who[n].label, "%s-%dw", all[i]->name, (int)w);
            else snprintf(who[n].label, sizeof who[n].label, "%s", all[i]->name);
            n++;
        }
    }
    return n;
}

/* --engine a,b: the entrants whose label or engine name is in the list. */
static int entrant_picked(const bench_entrant *w, const char *list)
{
    if (list == NULL) return 1;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", list);
    for (char *tok = strtok(buf, ","); tok != NULL; tok = strtok(NULL, ","))
        if (strcmp(tok, w->label) == 0 || strcmp(tok, w->engine->name) == 0) return 1;
    return 0;
}

/* ---------------------------------------------------------------- main */

static void usage(FILE *f)
{
    fprintf(f, "usage: bench [--quick] [--scene NAME[:N,N...]]... [--engine a,b,...] [--steps S]\n"
               "             [--repeats R] [--sleep off|on|both] [--workers N] [--budget SECONDS]\n"
               "             [--sweep] [--v3 DIR|none] [--csv FILE] [--dump FILE] [--list]\n"
               "  --quick     a smoke run: small sizes, 60 steps, 1 run\n"
               "  --scene     a scene, optionally with sizes (default: every scene, default sizes)\n"
               "  --engine    engines or entrants by name (rigid, rigid-2w, b2v3-avx2 ...; default all)\n"
               "  --steps     steps per run (default 600)\n"
               "  --repeats   runs per scene and engine; figures are medians over runs (default 3)\n"
               "  --sleep     the piles with sleeping off, on or both (default both; the other\n"
               "              scenes as they are defined)\n"
               "  --workers   the worker count of the threaded runs (default: the machine's cores)\n"
               "  --budget    seconds of stepping a run may take before its steps are capped (120)\n"
               "  --sweep     quality against cost: every engine at several solver settings on the\n"
               "              scenes given (default boxes:4000 and rain:4000)\n"
               "  --v3        where the Box2D v3 engines are (default: bench-v3/ beside this program)\n"
               "  --csv       also write the results as CSV\n"
               "  --dump      write the final state of every dynamic body of every run (CSV)\n");
}

/* --scene NAME[:N,N...] into jobs; 0 on a bad argument (said on stderr). */
static int parse_scene(const char *arg, bench_job *jobs, int32_t *njobs, int32_t cap)
{
    char name[64];
    const char *colon = strchr(arg, ':');
    size_t len = colon != NULL ? (size_t)(colon - arg) : strlen(arg);
    if (len >= sizeof name) len = sizeof name - 1;
    memcpy(name, arg, len);
    name[len] = 0;
    const bench_scene_def *d = bench_scene_find(name);
    if (d == NULL) {
        fprintf(stderr, "bench: unknown scene '%s' (--list)\n", name);
        return 0;
    }
    if (colon == NULL) {
        for (int k = 0; k < 4 && d->default_sizes[k] > 0 && *njobs < cap; k++)
            jobs[(*njobs)++] = (bench_job){ d, d->default_sizes[k], -1 };
        return 1;
    }
    const char *p = colon + 1;
    while (*p != 0 && *njobs < cap) {
        char *end;
        long v = strtol(p, &end, 10);
        if (end == p || v < 1 || v > 10000000 || (*end != ',' && *end != 0)) {
            fprintf(stderr, "bench: bad size list in '%s'\n", arg);
            return 0;
        }
        jobs[(*njobs)++] = (bench_job){ d, (int32_t)v, -1 };
        p = *end == ',' ? end + 1 : end;
    }
    return 1;
}

int main(int argc, char **argv)
{
    int quick = 0, sweep = 0, sleep_mode = -1; /* -1 both for the piles */
    bench_options o = { 0, 0, 120.0, NULL };
    long nproc = sysconf(_SC_NPROCESSORS_ONLN);
    int32_t workers = nproc > 1 ? (int32_t)nproc : 1;
    const char *csv = NULL, *engines_arg = NULL, *v3_dir = NULL;
    bench_job jobs[64];
    int32_t njobs = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int has = i + 1 < argc;
        if (strcmp(a, "--quick") == 0) {
            quick = 1;
        } else if (strcmp(a, "--sweep") == 0) {
            sweep = 1;
        } else if (strcmp(a, "--list") == 0) {
            for (int k = 0; k < bench_nscenes; k++)
                printf("%-20s %s (default N:%d%s%s)\n", bench_scenes[k].name, bench_scenes[k].what,
                       (int)bench_scenes[k].default_sizes[0], bench_scenes[k].default_sizes[1] ? "," : "",
                       bench_scenes[k].default_sizes[1] ? "..." : "");
            return 0;
        } else if ((strcmp(a, "--steps") == 0 || strcmp(a, "--repeats") == 0 ||
                    strcmp(a, "--workers") == 0 || strcmp(a, "--budget") == 0) && has) {
            char *end;
            double v = strtod(argv[++i], &end);
            if (*end != 0 || !(v >= 1 && v <= 1000000)) {
                fprintf(stderr, "bench: %s wants a positive number\n", a);
                return 2;
            }
            if (a[2] == 's') o.steps = (int32_t)v;
            else if (a[2] == 'r') o.repeats = (int32_t)(v > 64 ? 64 : v);
            else if (a[2] == 'w') workers = (int32_t)(v > 64 ? 64 : v);
            else o.budget_s = v;
        } else if (strcmp(a, "--sleep") == 0 && has) {
            const char *v = argv[++i];
            sleep_mode = strcmp(v, "off") == 0 ? 0 : strcmp(v, "on") == 0 ? 1 : strcmp(v, "both") == 0 ? -1 : -2;
            if (sleep_mode == -2) {
                fprintf(stderr, "bench: --sleep wants off, on or both\n");
                return 2;
            }
        } else if (strcmp(a, "--v3") == 0 && has) {
            v3_dir = argv[++i];
        } else if (strcmp(a, "--csv") == 0 && has) {
            csv = argv[++i];
        } else if (strcmp(a, "--dump") == 0 && has) {
            o.dump = fopen(argv[++i], "w");
            if (o.dump == NULL) {
                perror(argv[i]);
                return 1;
            }
            fprintf(o.dump, "scene,n,engine,k,x,y,vx,vy\n");
        } else if (strcmp(a, "--engine") == 0 && has) {
            engines_arg = argv[++i];
        } else if (strcmp(a, "--scene") == 0 && has) {
            if (!parse_scene(argv[++i], jobs, &njobs, 64)) return 2;
        } else if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return 0;
        } else {
            usage(stderr);
            return 2;
        }
    }
    if (o.steps == 0) o.steps = quick ? 60 : 600;
    if (o.repeats == 0) o.repeats = quick ? 1 : 3;
    if (njobs == 0 && sweep) {
        parse_scene(quick ? "boxes:1000" : "boxes:4000", jobs, &njobs, 64);
        parse_scene(quick ? "rain:1000" : "rain:4000", jobs, &njobs, 64);
    }
    if (njobs == 0)
        for (int k = 0; k < bench_nscenes; k++) {
            const bench_scene_def *d = &bench_scenes[k];
            for (int m = 0; m < 4 && d->default_sizes[m] > 0; m++) {
                jobs[njobs++] = (bench_job){ d, quick ? d->quick_size : d->default_sizes[m], -1 };
                if (quick) break;
            }
        }

    bench_entrant all[BENCH_MAX_ENTRANTS], who[BENCH_MAX_ENTRANTS];
    char why[1024];
    int nall = entrants(all, workers, v3_dir, why, sizeof why), nwho = 0;
    for (int i = 0; i < nall; i++)
        if (entrant_picked(&all[i], engines_arg)) who[nwho++] = all[i];
    if (nwho == 0) {
        fprintf(stderr, "bench: no such engine in '%s'\n", engines_arg);
        return 2;
    }
    const char *versions[BENCH_MAX_ENTRANTS];
    for (int i = 0; i < nwho; i++) versions[i] = who[i].engine->version(); /* banners first */
    fflush(stderr);
    printf("rigid bench: dt = 1/60 s, %d steps per run (a run stops after %.0f s of stepping), %d run(s) "
           "per scene and engine, engines interleaved; figures are medians over runs\n",
           (int)o.steps, o.budget_s, (int)o.repeats);
    bench_report_machine(stdout);
    printf("engines:");
    for (int i = 0; i < nwho; i++)
        if (i == 0 || who[i].engine != who[i - 1].engine) printf(" [%s]", versions[i]);
    printf("\n");
    if (why[0] != 0) printf("(%s)\n", why);
#ifndef RG_BENCH_PEERS
    printf("(built without Box2D 2.4 and Chipmunk 7: `make bench` builds them when libbox2d-dev and "
           "libchipmunk-dev are installed)\n");
#endif
    if (!bench_rigid_engine.threaded)
        printf("(rigid runs on one thread: this build has no task system)\n");
    printf("-Nw: the engine with N worker threads (its own scheduler); the others one thread\n");
    if (sweep) {
        int ok = bench_sweep(jobs, njobs, who, nwho, &o, csv);
        if (o.dump != NULL) fclose(o.dump);
        return ok ? 0 : 1;
    }
    printf("ns/body-step counts dynamic bodies; B/body: bytes held at the end over all bodies incl. "
           "static (rigid, v3: a counting allocator, peak in the CSV; the others: heap growth)\n"
           "overlap: deepest between two moving bodies; mean: over the overlapping pairs (bodies and "
           "statics); wall: a moving body into a static shape;\nvmax at the end; rest: s until the "
           "fastest body stays < %.1f m/s; x rigid: the engine's median (sleeping on: mean) over "
           "rigid's with as many workers\n\n", BENCH_REST_SPEED);
    bench_report_header();
    fflush(stdout);

    FILE *cf = NULL;
    if (csv != NULL) {
        cf = fopen(csv, "w");
        if (cf == NULL) {
            perror(csv);
            return 1;
        }
        bench_report_csv_header(cf);
    }
    bench_result *results = calloc((size_t)njobs * 2 * (size_t)nwho, sizeof *results);
    if (results == NULL) return 1;
    int32_t nres = 0;
    for (int32_t j = 0; j < njobs; j++) {
        const bench_scene_def *d = jobs[j].def;
        bench_scene s;
        if (!bench_scene_build(&s, d, jobs[j].n)) return 1;
        int sleeps[2] = { s.sleep, -1 }; /* the definition's setting; gameplay variants stay off */
        if (d->variant == BENCH_PLAIN && d->sleep_both) {
            if (sleep_mode == -1) {
                sleeps[0] = 0;
                sleeps[1] = 1;
            } else {
                sleeps[0] = sleep_mode;
            }
        } else if (d->variant == BENCH_PLAIN && sleep_mode >= 0) {
            sleeps[0] = sleep_mode;
        }
        /* a gameplay variant runs on rigid alone, one worker */
        const bench_entrant *only[BENCH_MAX_ENTRANTS];
        int nonly = 0;
        for (int e = 0; e < nwho; e++)
            if (d->variant == BENCH_PLAIN || (who[e].engine == &bench_rigid_engine && who[e].workers == 1))
                only[nonly++] = &who[e];
        for (int k = 0; k < 2 && sleeps[k] >= 0 && nonly > 0; k++) {
            s.sleep = sleeps[k];
            if (!bench_run_scene(&s, d, only, nonly, &o, &results[nres])) return 1;
            for (int e = 0; e < nonly; e++) {
                const bench_result *r = &results[nres + e];
                if (r->who->engine == &bench_floor_engine && !r->ok) continue; /* free scenes only */
                bench_report_row(r);
                if (cf != NULL) bench_report_csv_row(cf, r);
            }
            nres += nonly;
            fflush(stdout);
        }
        free(s.bodies);
    }
    bench_report_summary(results, nres, who, nwho, &o);
    printf("\n");
    bench_report_machine(stdout);
    if (cf != NULL) fclose(cf);
    if (o.dump != NULL) fclose(o.dump);
    free(results);
    return 0;
}
