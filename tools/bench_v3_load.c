/* bench_v3_load.c: opens the Box2D v3 engines that tools/bench_v3.mk builds, one shared
 * library per SIMD build (libbench-v3-sse2.so, libbench-v3-avx2.so).  Each holds its own
 * copy of v3 with every symbol hidden but bench_v3_engine, and is opened RTLD_LOCAL, so
 * the two builds live side by side in one process without a name clash.  The AVX2 build is
 * opened only on a CPU with AVX2 and FMA. */
#define _GNU_SOURCE 1 /* readlink */
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "bench.h"

int bench_cpu_has_avx2(void)
{
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
    return 0;
#endif
}

/* The directory of the running program, "." when it cannot be told. */
static void v3_exe_dir(char *out, size_t size)
{
    ssize_t n = readlink("/proc/self/exe", out, size - 1);
    if (n <= 0) {
        snprintf(out, size, ".");
        return;
    }
    out[n] = 0;
    char *slash = strrchr(out, '/');
    if (slash != NULL) *slash = 0;
}

static void v3_say(char *why, size_t size, const char *text)
{
    size_t used = strlen(why);
    if (used + 1 < size) snprintf(why + used, size - used, "%s%s", used > 0 ? "; " : "", text);
}

int bench_v3_load(const char *dir, const bench_engine *out[2], char *why, size_t why_size)
{
    static const char *const builds[2] = { "sse2", "avx2" };
    char base[4096], path[4200], text[4400];
    out[0] = out[1] = NULL;
    if (why_size > 0) why[0] = 0;
    if (dir != NULL && strcmp(dir, "none") == 0) {
        v3_say(why, why_size, "Box2D v3 not built (its source was not found)");
        return 0;
    }
    if (dir == NULL) {
        v3_exe_dir(base, sizeof base);
        size_t len = strlen(base);
        snprintf(base + len, sizeof base - len, "/bench-v3");
    } else {
        snprintf(base, sizeof base, "%s", dir);
    }
    int loaded = 0;
    for (int b = 0; b < 2; b++) {
        snprintf(path, sizeof path, "%s/libbench-v3-%s.so", base, builds[b]);
        if (b == 1 && !bench_cpu_has_avx2()) {
            v3_say(why, why_size, "Box2D v3 AVX2 build skipped: this CPU lacks AVX2 or FMA");
            continue;
        }
        if (access(path, R_OK) != 0) {
            snprintf(text, sizeof text, "Box2D v3 %s build not found (%s)", builds[b], path);
            v3_say(why, why_size, text);
            continue;
        }
        void *lib = dlopen(path, RTLD_NOW | RTLD_LOCAL);
        const bench_engine *e = lib != NULL ? dlsym(lib, "bench_v3_engine") : NULL;
        if (e == NULL) {
            snprintf(text, sizeof text, "Box2D v3 %s build not loaded: %s", builds[b], dlerror());
            v3_say(why, why_size, text);
            if (lib != NULL) dlclose(lib);
            continue;
        }
        out[b] = e; /* the library stays open for the life of the process */
        loaded++;
    }
    return loaded;
}
