/* host.c: build/rigid, which runs a gameplay script in a sandbox and can draw its world. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lauxlib.h>
#include <lua.h>

#include "lhtml.h"
#include "lrigid.h"
#include "lsandbox.h"
#include "lsvg.h"

#define DEFAULT_MEMORY_MIB 64
#define DEFAULT_BUDGET     100000000LL
#define DEFAULT_SECONDS    10.0
#define DEFAULT_TIMEOUT    10.0    /* seconds per call into the script: a backstop */
#define MAX_STEPS          1e12    /* a scene's steps, however long its duration */

static const char usage[] =
    "usage: rigid SCRIPT.lua [options] [-- script arguments]\n"
    "  --steps N      fixed steps a scene runs (default: its `duration` global, else 10 s)\n"
    "  --seconds S    simulated seconds a scene runs\n"
    "  --svg FILE     draw the world at the end as rg_world_draw does, with the paths\n"
    "                 that led there, into FILE (SVG)\n"
    "  --html FILE    record the run into FILE, a replay viewer (one self-contained page)\n"
    "  --memory MiB   memory cap of the script, physics included (default 64)\n"
    "  --budget N     instructions per call into the script: the main chunk, setup, each\n"
    "                 frame (update and the contact calls after its step share one) and\n"
    "                 finish (default 100000000; 0: no limit)\n"
    "  --timeout S    seconds per call into the script besides the budget, for work it\n"
    "                 undercharges (default 10; 0: none; no effect with --budget 0)\n"
    "  --threads N    step every world on a pool of N threads (1-64; the results are the\n"
    "                 same bits as on one thread, the default)\n"
    "A scene script defines setup(world), update(world, dt) (before each fixed step),\n"
    "contact(world, event) (for each contact event after a step) and/or finish(world);\n"
    "the host makes the world and steps it.  Other scripts run as they are.\n";

typedef struct host {
    const char *script;
    long long steps;         /* -1: not given */
    double seconds;          /* < 0: not given */
    double timeout;          /* seconds per call into the script; 0: none */
    const char *svg;
    const char *html;
    long long memory_mib;
    long long budget;
    long long threads;       /* 1: no pool */
    rg_thread_pool *pool;
    rg_task_system tasks;
    int nargs;
    char **args;

    lua_State *L;
    lsandbox *sb;
    lsvg *rec;               /* NULL unless --svg */
    lhtml *replay;           /* NULL unless --html */
    int world_ref;           /* the world drawn and stepped */
    int ctor_ref;            /* rigid.world as it was before the script ran */
    long long steps_taken;
    double sim_time;
    lrigid_hooks hooks;
} host;

static int parse_int(const char *s, long long lo, long long hi, long long *out)
{
    char *end;
    long long v;
    errno = 0;
    v = strtoll(s, &end, 10);
    if (errno != 0 || end == s || *end != '\0' || v < lo || v > hi) return 0;
    *out = v;
    return 1;
}

static int parse_args(host *h, int argc, char **argv)
{
    int i;
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--") == 0) {
            h->nargs = argc - i - 1;
            h->args = argv + i + 1;
            break;
        } else if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage, stdout);
            exit(0);
        } else if (strcmp(a, "--threads") == 0) {
            if (val == NULL || !parse_int(val, 1, RG_MAX_WORKERS, &h->threads)) {
                fprintf(stderr, "rigid: --threads wants a whole number in [1, %d], not '%s'\n", RG_MAX_WORKERS,
                        val != NULL ? val : "");
                return 0;
            }
            i++;
        } else if (strcmp(a, "--steps") == 0 || strcmp(a, "--memory") == 0 ||
                   strcmp(a, "--budget") == 0 || strcmp(a, "--seconds") == 0 || strcmp(a, "--timeout") == 0 ||
                   strcmp(a, "--svg") == 0 || strcmp(a, "--html") == 0) {
            if (val == NULL) {
                fprintf(stderr, "rigid: %s needs a value\n%s", a, usage);
                return 0;
            }
            i++;
            if (strcmp(a, "--svg") == 0) {
                h->svg = val;
            } else if (strcmp(a, "--html") == 0) {
                h->html = val;
            } else if (strcmp(a, "--seconds") == 0) {
                char *end;
                h->seconds = strtod(val, &end);
                if (end == val || *end != '\0' || !(h->seconds > 0) || !isfinite(h->seconds)) {
                    fprintf(stderr, "rigid: --seconds wants a positive number, not '%s'\n", val);
                    return 0;
                }
            } else if (strcmp(a, "--timeout") == 0) {
                char *end;
                h->timeout = strtod(val, &end);
                if (end == val || *end != '\0' || !(h->timeout >= 0) || !isfinite(h->timeout)) {
                    fprintf(stderr, "rigid: --timeout wants a number of seconds >= 0, not '%s'\n", val);
                    return 0;
                }
            } else if (!parse_int(val, strcmp(a, "--budget") == 0 ? 0 : 1,
                                  strcmp(a, "--memory") == 0 ? 1 << 20 : 1LL << 53,
                                  strcmp(a, "--steps") == 0 ? &h->steps
                                  : strcmp(a, "--memory") == 0 ? &h->memory_mib
                                                                : &h->budget)) {
                fprintf(stderr, "rigid: %s wants a whole number in range, not '%s'\n", a, val);
                return 0;
            }
        } else if (a[0] == '-' && a[1] != '\0') {
            fprintf(stderr, "rigid: unknown option '%s'\n%s", a, usage);
            return 0;
        } else if (h->script == NULL) {
            h->script = a;
        } else {
            fprintf(stderr, "rigid: one script at a time ('%s' and '%s')\n%s", h->script, a, usage);
            return 0;
        }
    }
    if (h->script == NULL) {
        fputs(usage, stderr);
        return 0;
    }
    return 1;
}

/* ---------------------------------------------------------------- hooks from the binding */

static void host_charge(lua_State *L, void *ud, double units)
{
    host *h = (host *)ud;
    lsandbox_charge(L, h->sb, units);
}

/* One frame of the drawn world for --svg and --html. */
static void record(host *h, lua_State *L, int world_idx, double t)
{
    world_idx = lua_absindex(L, world_idx);
    if (h->rec != NULL) lsvg_record(h->rec, L, world_idx, t);
    if (h->replay != NULL) lhtml_record(h->replay, L, world_idx, t);
}

static double fixed_dt(lua_State *L, int world_idx)
{
    rg_world *w = lrigid_toworld(L, world_idx);
    rg_real dt = 0;
    int32_t max = 0;
    if (w == NULL || rg_world_get_fixed_step(w, &dt, &max) != RG_OK) return 0;
    return (double)dt;
}

/* A step the script took itself (world:step or world:advance).  A plain script's first
 * stepped world becomes the one the host draws. */
static void host_after_step(lua_State *L, void *ud, int world_idx, int steps)
{
    host *h = (host *)ud;
    int same;
    world_idx = lua_absindex(L, world_idx);
    if (h->world_ref == LUA_NOREF) {
        lua_pushvalue(L, world_idx);
        h->world_ref = luaL_ref(L, LUA_REGISTRYINDEX);
    }
    lua_rawgeti(L, LUA_REGISTRYINDEX, h->world_ref);
    same = lua_rawequal(L, -1, world_idx);
    lua_pop(L, 1);
    if (!same) return;
    h->steps_taken += steps;
    h->sim_time += steps * fixed_dt(L, world_idx);
    record(h, L, world_idx, h->sim_time);
}

/* ---------------------------------------------------------------- running */

static int report(host *h, const char *what, int status)
{
    const char *msg = lua_tostring(h->L, -1);
    fprintf(stderr, "rigid: %s failed: %s\n", what, msg != NULL ? msg : "(no message)");
    if (status == LUA_ERRMEM) {
        /* Lua raises memory errors without a message handler: no position, no traceback. */
        const char *where = lsandbox_where(h->sb);
        fprintf(stderr, "  (the script reached its memory cap of %lld MiB in %s; %s%s)\n",
                h->memory_mib, h->script, where[0] != '\0' ? "last seen at " : "no position known",
                where);
    }
    lua_pop(h->L, 1);
    return 0;
}

static double global_number(lua_State *L, const char *name)
{
    double v = -1;
    lua_pushglobaltable(L);
    lua_pushstring(L, name);
    lua_rawget(L, -2);
    if (lua_type(L, -1) == LUA_TNUMBER) v = lua_tonumber(L, -1);
    lua_pop(L, 2);
    return isfinite(v) ? v : -1;
}

/* The host's own step: update -> one fixed step through the accumulator -> contacts.  The
 * frame is one entry: update and every contact call after the step share one budget (a
 * fresh budget per event would let each of thousands of events spend all of it). */
static int scene_step(host *h, double dt)
{
    lua_State *L = h->L;
    rg_world *w;
    int32_t taken = 0;
    int has_contact, fresh = 1;
    if (lsandbox_getfunction(L, "update")) {
        lua_rawgeti(L, LUA_REGISTRYINDEX, h->world_ref);
        lua_pushnumber(L, dt);
        int st = lsandbox_call(L, h->sb, 2, 0);
        if (st != LUA_OK) return report(h, "update", st);
        fresh = 0;
    }
    lua_rawgeti(L, LUA_REGISTRYINDEX, h->world_ref);
    w = lrigid_toworld(L, -1);
    if (w == NULL) {
        lua_pop(L, 1);
        fprintf(stderr, "rigid: the scene closed its world\n");
        return 0;
    }
    /* frame_time equals the fixed step exactly (both rg_real), so each advance takes one. */
    if (rg_world_advance(w, (rg_real)dt, &taken) != RG_OK) {
        fprintf(stderr, "rigid: %s\n", rg_world_last_error(w));
        lua_pop(L, 1);
        return 0;
    }
    h->steps_taken += taken;
    h->sim_time += taken * dt;
    record(h, L, -1, h->sim_time);
    has_contact = lsandbox_getfunction(L, "contact");
    if (has_contact) lua_pop(L, 1);
    if (has_contact) {
        int events, i, n;
        lrigid_pushevents(L, -1);
        events = lua_gettop(L);
        n = (int)lua_rawlen(L, events);
        for (i = 1; i <= n; i++) {
            if (!lsandbox_getfunction(L, "contact")) break;
            lua_rawgeti(L, LUA_REGISTRYINDEX, h->world_ref);
            lua_rawgeti(L, events, i);
            int st = fresh ? lsandbox_call(L, h->sb, 2, 0) : lsandbox_continue(L, h->sb, 2, 0);
            fresh = 0;
            if (st != LUA_OK) {
                report(h, "contact", st);
                lua_pop(L, 2);
                return 0;
            }
        }
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    return 1;
}

static int run_scene(host *h)
{
    lua_State *L = h->L;
    double dt, duration;
    long long n, k;
    int st;
    /* A world the main chunk stepped is not the scene's. */
    if (h->world_ref != LUA_NOREF) {
        luaL_unref(L, LUA_REGISTRYINDEX, h->world_ref);
        h->world_ref = LUA_NOREF;
        h->steps_taken = 0;
        h->sim_time = 0;
        if (h->rec != NULL) {
            lsvg_free(h->rec);
            h->rec = lsvg_new();
        }
        lhtml_restart(h->replay);
    }
    /* The world comes from the constructor the module had before the script ran. */
    lua_rawgeti(L, LUA_REGISTRYINDEX, h->ctor_ref);
    st = lsandbox_call(L, h->sb, 0, 1);
    if (st != LUA_OK) return report(h, "creating the world", st);
    h->world_ref = luaL_ref(L, LUA_REGISTRYINDEX);
    lua_rawgeti(L, LUA_REGISTRYINDEX, h->world_ref);
    {
        /* Store the default step as an rg_real, so the host's frame time matches it. */
        rg_world *w = lrigid_toworld(L, -1);
        rg_real d;
        int32_t m;
        if (rg_world_get_fixed_step(w, &d, &m) == RG_OK) rg_world_set_fixed_step(w, d, m);
    }
    if (lsandbox_getfunction(L, "setup")) {
        lua_pushvalue(L, -2);
        st = lsandbox_call(L, h->sb, 1, 0);
        if (st != LUA_OK) {
            report(h, "setup", st);
            lua_pop(L, 1);
            return 0;
        }
    }
    dt = fixed_dt(L, -1);
    lua_pop(L, 1);
    if (!(dt > 0)) {
        fprintf(stderr, "rigid: the scene closed its world\n");
        return 0;
    }
    duration = global_number(L, "duration");
    if (h->steps >= 0) {
        n = h->steps;
    } else {
        /* Clamped before the conversion: a script's duration may be anything. */
        double want = ceil((h->seconds > 0 ? h->seconds : duration > 0 ? duration
                                                                        : DEFAULT_SECONDS) / dt - 1e-9);
        n = want < MAX_STEPS ? (long long)want : (long long)MAX_STEPS;
    }
    lua_rawgeti(L, LUA_REGISTRYINDEX, h->world_ref);
    record(h, L, -1, 0);
    lua_pop(L, 1);
    for (k = 0; k < n; k++) {
        double d;
        lua_rawgeti(L, LUA_REGISTRYINDEX, h->world_ref);
        d = fixed_dt(L, -1);
        lua_pop(L, 1);
        if (!(d > 0)) {
            fprintf(stderr, "rigid: the scene closed its world\n");
            return 0;
        }
        if (!scene_step(h, d)) return 0;
    }
    if (lsandbox_getfunction(L, "finish")) {
        lua_rawgeti(L, LUA_REGISTRYINDEX, h->world_ref);
        st = lsandbox_call(L, h->sb, 1, 0);
        if (st != LUA_OK) return report(h, "finish", st);
    }
    return 1;
}

/* Writes what --svg and --html asked for; 0 when one cannot be written. */
static int write_picture(host *h, int ok)
{
    char title[512], sub[768], caption[300];
    const char *base = strrchr(h->script, '/');
    int bodies = 0;
    int written = 1;
    if (h->rec == NULL && h->replay == NULL) return 1;
    if (h->world_ref != LUA_NOREF) {
        rg_world *w;
        lua_rawgeti(h->L, LUA_REGISTRYINDEX, h->world_ref);
        w = lrigid_toworld(h->L, -1);
        bodies = w != NULL ? rg_world_body_count(w) : 0;
        lua_pop(h->L, 1);
    }
    snprintf(title, sizeof title, "rigid: %s", base != NULL ? base + 1 : h->script);
    /* A scene may say what its picture shows: a global string `caption`. */
    caption[0] = '\0';
    lua_pushglobaltable(h->L);
    lua_pushstring(h->L, "caption");
    lua_rawget(h->L, -2);
    if (lua_type(h->L, -1) == LUA_TSTRING) snprintf(caption, sizeof caption, "%s; ", lua_tostring(h->L, -1));
    lua_pop(h->L, 2);
    if (h->rec != NULL) {
        snprintf(sub, sizeof sub, "%s%lld steps, %.2f s simulated, %d bodies at the end%s", caption,
                 h->steps_taken, h->sim_time, bodies, ok ? "" : " (the script failed: this is the world it left)");
        if (lsvg_write(h->rec, h->svg, title, sub) != 0) {
            fprintf(stderr, "rigid: cannot write %s: %s\n", h->svg, strerror(errno));
            written = 0;
        } else
            printf("rigid: picture written to %s\n", h->svg);
    }
    if (h->replay != NULL) {
        snprintf(sub, sizeof sub, "%s%lld steps, %.2f s simulated, %d bodies at the end%s", caption,
                 h->steps_taken, h->sim_time, bodies,
                 ok ? "" : " (the script failed: the last frame is the world it left)");
        if (lhtml_write(h->replay, h->html, title, sub) != 0) {
            fprintf(stderr, "rigid: cannot write %s: %s\n", h->html, strerror(errno));
            written = 0;
        } else {
            printf("rigid: replay of %d frames written to %s\n", lhtml_frames(h->replay), h->html);
        }
    }
    return written;
}

int main(int argc, char **argv)
{
    host h;
    lua_State *L;
    int ok = 0, i, st;
    clock_t t0 = clock();

    memset(&h, 0, sizeof h);
    h.steps = -1;
    h.seconds = -1;
    h.memory_mib = DEFAULT_MEMORY_MIB;
    h.budget = DEFAULT_BUDGET;
    h.timeout = DEFAULT_TIMEOUT;
    h.threads = 1;
    h.world_ref = LUA_NOREF;
    if (!parse_args(&h, argc, argv)) return 2;

    L = lsandbox_new((size_t)h.memory_mib << 20, h.budget, &h.sb);
    if (L == NULL) {
        fprintf(stderr, "rigid: cannot create a Lua state\n");
        return 1;
    }
    h.L = L;
    lsandbox_set_time_limit(h.sb, h.timeout);
    lsandbox_provide(L, "rigid", luaopen_rigid);
    lua_getglobal(L, "rigid");
    lua_getfield(L, -1, "world");
    h.ctor_ref = luaL_ref(L, LUA_REGISTRYINDEX);
    lua_pop(L, 1);
    if (h.svg != NULL) h.rec = lsvg_new();
    if (h.html != NULL) {
        if ((h.replay = lhtml_new()) == NULL) {
            fprintf(stderr, "rigid: out of memory for --html\n");
            lsandbox_close(L, h.sb);
            lsvg_free(h.rec);
            return 1;
        }
        lhtml_capture_print(L, h.replay, lsandbox_meter(h.sb));
    }
    h.hooks.charge = host_charge;
    h.hooks.after_step = host_after_step;
    h.hooks.ud = &h;
    if (h.threads > 1) {
        rg_status pst = rg_thread_pool_create((int32_t)h.threads, &h.pool);
        if (pst == RG_OK) pst = rg_thread_pool_task_system(h.pool, &h.tasks);
        if (pst != RG_OK) {
            fprintf(stderr, "rigid: cannot start %lld threads (%s)\n", h.threads, rg_status_string(pst));
            lsandbox_close(L, h.sb);
            lsvg_free(h.rec);
            lhtml_free(h.replay);
            return 1;
        }
        h.hooks.tasks = &h.tasks;
    }
    lrigid_sethooks(L, &h.hooks);

    st = lsandbox_loadfile(L, h.script);
    if (st != LUA_OK) {
        report(&h, "loading", st);
    } else {
        for (i = 0; i < h.nargs; i++) lua_pushstring(L, h.args[i]);
        st = lsandbox_call(L, h.sb, h.nargs, 0);
        if (st != LUA_OK) {
            report(&h, h.script, st);
        } else if (lsandbox_getfunction(L, "setup") + lsandbox_getfunction(L, "update") +
                   lsandbox_getfunction(L, "contact") + lsandbox_getfunction(L, "finish") > 0) {
            lua_settop(L, 0);
            ok = run_scene(&h);
        } else {
            ok = 1;
        }
    }
    lua_settop(L, 0);
    if (!write_picture(&h, ok)) ok = 0;
    if (ok)
        fprintf(stderr, "rigid: %s: %lld steps (%.2f s simulated) in %.3f s CPU, peak memory %.2f MiB\n",
                h.script, h.steps_taken, h.sim_time, (double)(clock() - t0) / CLOCKS_PER_SEC,
                (double)lsandbox_peak_memory(h.sb) / (1 << 20));
    lrigid_sethooks(L, NULL);
    lsandbox_close(L, h.sb);
    rg_thread_pool_destroy(h.pool); /* after the worlds, which lsandbox_close destroys */
    lsvg_free(h.rec);
    lhtml_free(h.replay);
    return ok ? 0 : 1;
}
