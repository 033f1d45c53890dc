/* snaptool.c: a fixed scene for checking snapshots and hashes across builds and machines.
 *   snaptool hash               run the scene 240 steps, print rg_world_hash
 *   snaptool save FILE          run 120 steps, save to FILE, run on to 240, print the hash
 *   snaptool restore FILE       restore FILE into a fresh world, run to 240, print the hash
 * Every build (compiler, optimisation level, SIMD path, machine) must print the same hash
 * for the same rg_real, and a snapshot saved by one must continue in another to it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rigid.h"

#define CHECK(call)                                                                  \
    do {                                                                             \
        rg_status st_ = (call);                                                      \
        if (st_ != RG_OK) {                                                          \
            fprintf(stderr, "snaptool: %s: %s\n", #call, rg_status_string(st_));    \
            exit(1);                                                                 \
        }                                                                            \
    } while (0)

static rg_body body(rg_world *w, int32_t type, double m, double x, double y)
{
    rg_body b;
    CHECK(rg_body_create(w, type, (rg_real)m, (rg_vec2){ (rg_real)x, (rg_real)y }, &b));
    return b;
}

/* A container with a pile of 240 circles and boxes, a kinematic platform, a one-way shelf,
 * a sensor, springs, drag and a few bullets; sleeping and continuous collision on. */
static rg_world *scene(void)
{
    rg_world *w;
    CHECK(rg_world_create(&w));
    CHECK(rg_world_set_gravity(w, (rg_vec2){ 0, -(rg_real)9.81 }));
    rg_body floor = body(w, RG_BODY_STATIC, 0, 0, -0.5);
    CHECK(rg_body_set_aabb(w, floor, 12, (rg_real)0.5));
    for (int side = -1; side <= 1; side += 2) {
        rg_body wall = body(w, RG_BODY_STATIC, 0, side * 12.5, 8);
        CHECK(rg_body_set_aabb(w, wall, (rg_real)0.5, 9));
    }
    rg_body shelf = body(w, RG_BODY_STATIC, 0, 6, 4);
    CHECK(rg_body_set_aabb(w, shelf, 3, (rg_real)0.1));
    CHECK(rg_body_set_one_way(w, shelf, (rg_vec2){ 0, 1 }));
    rg_body plat = body(w, RG_BODY_KINEMATIC, 0, -6, 2);
    CHECK(rg_body_set_aabb(w, plat, 2, (rg_real)0.2));
    CHECK(rg_body_set_velocity(w, plat, (rg_vec2){ (rg_real)1.5, 0 }));
    rg_body coin = body(w, RG_BODY_STATIC, 0, 0, 1);
    CHECK(rg_body_set_circle(w, coin, (rg_real)0.6));
    CHECK(rg_body_set_sensor(w, coin, 1));
    rg_body prev = 0;
    for (int i = 0; i < 240; i++) {
        rg_body b = body(w, RG_BODY_DYNAMIC, 0.5 + 0.1 * (i % 7), -10 + (i % 20) * 1.05 + 0.01 * (i % 3),
                         6 + (i / 20) * 1.1);
        if (i % 3)
            CHECK(rg_body_set_circle(w, b, (rg_real)0.45));
        else
            CHECK(rg_body_set_aabb(w, b, (rg_real)0.45, (rg_real)0.4));
        if (i % 11 == 0) CHECK(rg_body_set_drag(w, b, (rg_real)0.2, (rg_real)0.05));
        if (i % 13 == 0) CHECK(rg_body_set_restitution(w, b, (rg_real)0.6));
        if (i % 17 == 0 && prev != 0) {
            uint64_t sp;
            CHECK(rg_spring_create(w, b, prev, (rg_vec2){ 0, 0 }, (rg_real)1.1, 25, (rg_real)0.3, &sp));
        }
        prev = b;
    }
    for (int i = 0; i < 6; i++) {
        rg_body bullet = body(w, RG_BODY_DYNAMIC, 0.05, -9 + 3 * i, 15);
        CHECK(rg_body_set_circle(w, bullet, (rg_real)0.05));
        CHECK(rg_body_set_velocity(w, bullet, (rg_vec2){ (rg_real)(i % 2 ? 80 : -60), -200 }));
    }
    return w;
}

static void run(rg_world *w, int from, int to)
{
    for (int k = from; k < to; k++) {
        if (k == 150) CHECK(rg_world_set_integrator(w, RG_INTEGRATOR_RK4));
        if (k == 200) CHECK(rg_world_set_integrator(w, RG_INTEGRATOR_SEMI_IMPLICIT_EULER));
        CHECK(rg_world_step(w, (rg_real)1.0 / 60));
    }
}

static void print_hash(rg_world *w)
{
    uint64_t h;
    CHECK(rg_world_hash(w, &h));
    printf("%016llx\n", (unsigned long long)h);
}

int main(int argc, char **argv)
{
    if (argc >= 2 && strcmp(argv[1], "hash") == 0) {
        rg_world *w = scene();
        run(w, 0, 240);
        print_hash(w);
        rg_world_destroy(w);
        return 0;
    }
    if (argc >= 3 && strcmp(argv[1], "save") == 0) {
        rg_world *w = scene();
        run(w, 0, 120);
        size_t size;
        CHECK(rg_world_save(w, NULL, 0, &size));
        void *buf = malloc(size);
        CHECK(rg_world_save(w, buf, size, &size));
        FILE *f = fopen(argv[2], "wb");
        if (f == NULL || fwrite(buf, 1, size, f) != size || fclose(f) != 0) {
            perror(argv[2]);
            return 1;
        }
        free(buf);
        run(w, 120, 240);
        print_hash(w);
        rg_world_destroy(w);
        return 0;
    }
    if (argc >= 3 && strcmp(argv[1], "restore") == 0) {
        FILE *f = fopen(argv[2], "rb");
        if (f == NULL) {
            perror(argv[2]);
            return 1;
        }
        static unsigned char buf[1 << 24];
        size_t size = fread(buf, 1, sizeof buf, f);
        fclose(f);
        rg_world *w;
        CHECK(rg_world_create(&w));
        CHECK(rg_world_restore(w, buf, size));
        run(w, 120, 240);
        print_hash(w);
        rg_world_destroy(w);
        return 0;
    }
    fprintf(stderr, "usage: snaptool hash | save FILE | restore FILE\n");
    return 2;
}
