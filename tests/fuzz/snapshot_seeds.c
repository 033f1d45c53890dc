/* snapshot_seeds.c: writes the seed corpus of fuzz_snapshot.c, snapshots of varied scenes,
 * into the folder given (make fuzz runs it; the snapshots are of the build's rg_real, so
 * they are made, not kept in git).  Each file is the harness's input: a mode byte (1: the
 * checksum is made right after mutation, the size field set) and the snapshot. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rigid.h"

static rg_vec2 vec(double x, double y)
{
    rg_vec2 v;
    v.x = (rg_real)x;
    v.y = (rg_real)y;
    return v;
}

static void must(rg_status st, const char *what)
{
    if (st != RG_OK) {
        fprintf(stderr, "snapshot_seeds: %s: %s\n", what, rg_status_string(st));
        exit(1);
    }
}

static rg_body body(rg_world *w, int32_t type, double m, double x, double y, int shape, double hx, double hy)
{
    rg_body b;
    must(rg_body_create(w, type, (rg_real)m, vec(x, y), &b), "body_create");
    if (shape == RG_SHAPE_CIRCLE) must(rg_body_set_circle(w, b, (rg_real)hx), "set_circle");
    if (shape == RG_SHAPE_AABB) must(rg_body_set_aabb(w, b, (rg_real)hx, (rg_real)hy), "set_aabb");
    return b;
}

static void steps(rg_world *w, int n)
{
    for (int k = 0; k < n; k++) must(rg_world_step(w, (rg_real)(1.0 / 60)), "step");
}

static void write_seed(const char *dir, const char *name, const rg_world *w)
{
    size_t n = 0;
    must(rg_world_save(w, NULL, 0, &n), "save");
    unsigned char *p = malloc(n + 1);
    if (p == NULL) exit(1);
    p[0] = 1;
    must(rg_world_save(w, p + 1, n, &n), "save");
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (f == NULL || fwrite(p, 1, n + 1, f) != n + 1 || fclose(f) != 0) {
        fprintf(stderr, "snapshot_seeds: cannot write %s\n", path);
        exit(1);
    }
    free(p);
}

/* Settings away from their defaults, no body. */
static void empty(rg_world *w)
{
    must(rg_world_set_gravity(w, vec(1, -20)), "gravity");
    must(rg_world_set_wind(w, vec(-3, 0)), "wind");
    must(rg_world_set_integrator(w, RG_INTEGRATOR_RK4), "integrator");
    must(rg_world_set_fixed_step(w, (rg_real)(1.0 / 120), 3), "fixed step");
    must(rg_world_set_sleep_thresholds(w, 0.1f, 0.25f), "sleep thresholds");
    must(rg_world_set_solver_iterations(w, 4, 1), "iterations");
    must(rg_world_set_contact_tuning(w, 0.01f, 0.3f, 3, 0.5f), "tuning");
    must(rg_world_set_continuous(w, 0), "continuous");
}

/* Circles and boxes settling on a floor between walls: contacts and warm starts, grounded
 * flags, islands. */
static void pile(rg_world *w)
{
    must(rg_world_set_gravity(w, vec(0, -9.81)), "gravity");
    body(w, RG_BODY_STATIC, 0, 0, -0.5, RG_SHAPE_AABB, 4, 0.5);
    body(w, RG_BODY_STATIC, 0, -4.5, 2, RG_SHAPE_AABB, 0.5, 3);
    body(w, RG_BODY_STATIC, 0, 4.5, 2, RG_SHAPE_AABB, 0.5, 3);
    for (int i = 0; i < 14; i++) {
        rg_body b = body(w, RG_BODY_DYNAMIC, 0.5 + 0.25 * (i % 3), -3 + (i % 7) * 0.9, 0.5 + (i / 7) * 0.9,
                         i % 2 ? RG_SHAPE_CIRCLE : RG_SHAPE_AABB, 0.4, 0.35);
        if (i % 4 == 1) must(rg_body_set_restitution(w, b, 0.5f), "restitution");
        if (i % 5 == 2) must(rg_body_set_friction(w, b, 0.1f), "friction");
    }
    steps(w, 45);
}

/* Forces and springs through the accumulator: the previous positions and a fraction left,
 * drag, surface friction, speed limits, springs body-body and to the world, a kinematic
 * body, the events of the last advance. */
static void forces(rg_world *w)
{
    uint64_t s;
    must(rg_world_set_gravity(w, vec(0, -9.81)), "gravity");
    must(rg_world_set_integrator(w, RG_INTEGRATOR_VELOCITY_VERLET), "integrator");
    rg_body floor_ = body(w, RG_BODY_STATIC, 0, 0, -0.5, RG_SHAPE_AABB, 6, 0.5);
    (void)floor_;
    rg_body a = body(w, RG_BODY_DYNAMIC, 1, -2, 3, RG_SHAPE_CIRCLE, 0.3, 0), b = body(w, RG_BODY_DYNAMIC, 2, 0, 3, RG_SHAPE_AABB, 0.3, 0.3);
    rg_body c = body(w, RG_BODY_DYNAMIC, 1, 2, 0.3, RG_SHAPE_AABB, 0.3, 0.3), free_ = body(w, RG_BODY_DYNAMIC, 3, 5, 5, RG_SHAPE_NONE, 0, 0);
    rg_body k = body(w, RG_BODY_KINEMATIC, 0, -4, 1, RG_SHAPE_AABB, 1, 0.1);
    must(rg_body_set_velocity(w, k, vec(1.5, 0)), "velocity");
    must(rg_spring_create(w, a, b, vec(0, 0), 1.5, 40, 0.5, &s), "spring");
    must(rg_spring_create(w, b, 0, vec(0, 5), 1, 25, 0.2, &s), "spring to the world");
    must(rg_body_set_drag(w, a, 0.2f, 0.05f), "drag");
    must(rg_body_set_surface_friction(w, c, 0.4f, 9.81f), "surface friction");
    must(rg_body_set_velocity(w, c, vec(3, 0)), "velocity");
    must(rg_body_set_speed_limits(w, free_, 0.01f, 4), "speed limits");
    must(rg_body_set_gravity_scale(w, free_, -0.5f), "gravity scale");
    must(rg_body_apply_force(w, free_, vec(10, 0)), "force");
    must(rg_body_set_user_data(w, b, 0x1234567890ull), "user data");
    int32_t n;
    for (int f = 0; f < 40; f++) must(rg_world_advance(w, (rg_real)(1.0 / 47), &n), "advance");
}

/* Gameplay collision: one-way platforms, a sensor, filters, a pass-through pair, bodies
 * destroyed and made again (free lists, generations), springs destroyed. */
static void gameplay(rg_world *w)
{
    uint64_t s1, s2;
    must(rg_world_set_gravity(w, vec(0, -9.81)), "gravity");
    body(w, RG_BODY_STATIC, 0, 0, -0.5, RG_SHAPE_AABB, 8, 0.5);
    rg_body ledge = body(w, RG_BODY_STATIC, 0, 0, 1.2, RG_SHAPE_AABB, 2, 0.1);
    must(rg_body_set_one_way(w, ledge, vec(0, 1)), "one way");
    rg_body coin = body(w, RG_BODY_STATIC, 0, 2, 0.5, RG_SHAPE_CIRCLE, 0.3, 0);
    must(rg_body_set_sensor(w, coin, 1), "sensor");
    rg_body hero = body(w, RG_BODY_DYNAMIC, 1, 0, 0.3, RG_SHAPE_AABB, 0.25, 0.3);
    must(rg_body_set_velocity(w, hero, vec(2, 6)), "jump");
    rg_body ghost = body(w, RG_BODY_DYNAMIC, 1, -1, 0.5, RG_SHAPE_CIRCLE, 0.3, 0);
    must(rg_body_set_filter(w, ghost, 2, 0xFFFFFFFDu), "filter");
    rg_body gone = body(w, RG_BODY_DYNAMIC, 1, 3, 3, RG_SHAPE_CIRCLE, 0.2, 0);
    must(rg_spring_create(w, hero, gone, vec(0, 0), 1, 10, 0, &s1), "spring");
    must(rg_spring_create(w, hero, ghost, vec(0, 0), 1, 10, 0, &s2), "spring");
    steps(w, 10);
    must(rg_spring_destroy(w, s2), "spring destroy");
    must(rg_body_destroy(w, gone), "destroy");
    body(w, RG_BODY_DYNAMIC, 1, -3, 2, RG_SHAPE_AABB, 0.2, 0.2);
    rg_body box = body(w, RG_BODY_DYNAMIC, 1, -5, 0.2, RG_SHAPE_AABB, 0.2, 0.2);
    rg_body plank = body(w, RG_BODY_DYNAMIC, 1, -5, 0.6, RG_SHAPE_AABB, 0.5, 0.2);
    steps(w, 5);
    must(rg_body_pass_through(w, plank, box), "pass through");
    steps(w, 12);
}

/* The range guard and the broadphase's huge level: a body a force stopped at the edge of
 * the range, a shape of the largest size, a sleeping island. */
static void edges(rg_world *w)
{
    must(rg_world_set_gravity(w, vec(0, -9.81)), "gravity");
    body(w, RG_BODY_STATIC, 0, 0, -RG_MAX_SHAPE_SIZE, RG_SHAPE_AABB, RG_MAX_SHAPE_SIZE, RG_MAX_SHAPE_SIZE);
    rg_body flung = body(w, RG_BODY_DYNAMIC, RG_MIN_MASS, 0, 5, RG_SHAPE_CIRCLE, 0.5, 0);
    for (int i = 0; i < 4; i++) body(w, RG_BODY_DYNAMIC, 1, i * 0.8 - 1.2, 0.4, RG_SHAPE_AABB, 0.4, 0.4);
    steps(w, 60);   /* the boxes fall asleep */
    must(rg_body_apply_force(w, flung, vec(RG_MAX_FORCE, 0)), "force");
    must(rg_world_step(w, RG_MAX_DT), "step");
}

int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        void (*build)(rg_world *);
    } scenes[] = { { "empty", empty }, { "pile", pile }, { "forces", forces }, { "gameplay", gameplay }, { "edges", edges } };
    if (argc != 2) {
        fprintf(stderr, "usage: snapshot_seeds FOLDER\n");
        return 2;
    }
    for (size_t k = 0; k < sizeof scenes / sizeof scenes[0]; k++) {
        rg_world *w;
        must(rg_world_create(&w), "world_create");
        scenes[k].build(w);
        write_seed(argv[1], scenes[k].name, w);
        rg_world_destroy(w);
    }
    return 0;
}
