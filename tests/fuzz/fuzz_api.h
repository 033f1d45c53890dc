/* fuzz_api.h: what the API harness's files share: the input decoder, the allocator that
 * fails, the model of live handles, the checks, and the task systems. */
#ifndef FUZZ_API_H
#define FUZZ_API_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "fuzz_alloc.h"
#include "rigid.h"

#define NW       3     /* world slots */
#define MAXB     40    /* live bodies per world */
#define MAXS     12    /* live springs per world */
#define MAXISSUE 512   /* handles one world issued (for event checks) */
#define NDEAD    64    /* stale handles remembered */
#define MAXOPS   300
#define MAXEV    256

#define FAIL(...)                                                     \
    do {                                                              \
        fprintf(stderr, "fuzz_api: violation at op %d (%s): ", op_no, op_name); \
        fprintf(stderr, __VA_ARGS__);                                 \
        fputc('\n', stderr);                                          \
        abort();                                                      \
    } while (0)

typedef struct input {
    const uint8_t *p;
    size_t n;
} input;

typedef struct fworld {
    rg_world *w;
    fz_alloc *al;              /* NULL: the default allocator */
    int serial;                /* which world this is, over the input (a restore makes anew) */
    int identity;              /* whose handles it answers: its own serial, or after a restore
                                  the saving world's (a clone, a rollback) */
    rg_body live[MAXB];
    int nlive;
    uint64_t spring[MAXS];
    rg_body sa[MAXS], sb[MAXS];
    int nspring;
    rg_body issued[MAXISSUE];  /* every handle it issued, for events of destroyed bodies */
    int nissued;
    int tag_known;
    uint32_t tag;
    int presolve;              /* pre-solve hook set: its answers, bit by bit */
    int presolve_calls;
} fworld;

typedef struct dead_handle {
    rg_body h;
    int serial;                /* the world that issued it */
    int identity;
} dead_handle;

typedef struct snap {
    unsigned char *p;
    size_t n, cap;
} snap;

extern int trace, op_no, ndead, dead_next, next_serial;
extern const char *op_name;
extern fworld W[NW];
extern dead_handle dead[NDEAD];
extern const fworld *draw_world;

uint8_t u8(input *in);
uint32_t u32(input *in);
uint64_t u64(input *in);
rg_real real_arg(input *in);
rg_vec2 vec_arg(input *in);
int32_t int_arg(input *in);
int in_list(const rg_body *l, int n, uint64_t h);
void world_issued(fworld *fw, rg_body h);
void remember_dead(rg_body h, const fworld *fw);
void body_gone(fworld *fw, rg_body h);
void world_close(fworld *fw);
fworld *pick_world(input *in);
rg_body pick_body(input *in, const fworld *fw);
uint64_t pick_spring(input *in, const fworld *fw);
void snap_all(snap *s);
int finite2(rg_vec2 v);
/* What the last operation was, for the checks after it. */
enum { RAN_OTHER, RAN_STEP, RAN_ADVANCE };
void check_all(int ran);
void check_events(const fworld *fw);
void on_circle(rg_body body, rg_vec2 c, rg_real r, uint32_t rgba, void *user);
void on_box(rg_body body, rg_vec2 lo, rg_vec2 hi, uint32_t rgba, void *user);
void on_segment(rg_vec2 a, rg_vec2 b, uint32_t rgba, void *user);
void on_point(rg_vec2 p, uint32_t rgba, void *user);
int32_t on_pre_solve(rg_body a, rg_body b, rg_vec2 normal, rg_real separation, void *user);

/* fuzz_api_tasks.c: task systems, thread pools, and the step checked against a twin. */
int32_t tasks_set(input *in, fworld *fw);
int32_t tasks_pool(input *in);
int32_t tasks_step(fworld *fw, int advance, rg_real t, int32_t *out_steps);
int32_t tasks_restore(fworld *fw, const unsigned char *data, size_t n);
int32_t tasks_restore_slot(fworld *fw, int32_t slot);
int32_t tasks_crowd(input *in);
void tasks_check_thread(void);
void tasks_forget(const fworld *fw);
void tasks_teardown(void);

#endif
