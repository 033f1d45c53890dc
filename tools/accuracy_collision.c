/* accuracy_collision.c: tunnelling and pile scenes for the accuracy lab. */
#include <math.h>
#include <string.h>

#include "accuracy_collision.h"

static double wall_start(const acc_wall *s)
{
    return -(0.5 + s->radius + s->wall / 2) - s->phase * s->speed * s->dt;
}

/* Steps until the ball would be 0.5 m past the wall. */
static long wall_steps(const acc_wall *s)
{
    double travel = -wall_start(s) + 0.5;
    return (long)ceil(travel / (s->speed * s->dt)) + 1;
}

int acc_tunnel_naive(const acc_wall *s)
{
    double x = wall_start(s), h = (double)(rg_real)s->dt, reach = s->wall / 2 + s->radius;
    long n = wall_steps(s);
    for (long i = 0; i < n; i++) {
        x += s->speed * h;
        if (fabs(x) < reach) return 0; /* caught: the sample overlaps */
    }
    return x > 0;
}

int acc_tunnel_library(int integrator, int continuous, const acc_wall *s)
{
    rg_world *w = NULL;
    rg_body ball = 0, wall = 0;
    if (rg_world_create(&w) != RG_OK) return -1;
    rg_status st = rg_world_set_integrator(w, integrator);
    if (st == RG_OK) st = rg_world_set_continuous(w, continuous);
    if (st == RG_OK) st = rg_body_create(w, RG_BODY_STATIC, 0, acc_cv2(0, 0), &wall);
    if (st == RG_OK) st = rg_body_set_aabb(w, wall, (rg_real)(s->wall / 2), 1);
    if (st == RG_OK) st = rg_body_create(w, RG_BODY_DYNAMIC, 1, acc_cv2(wall_start(s), 0), &ball);
    if (st == RG_OK) st = rg_body_set_circle(w, ball, (rg_real)s->radius);
    if (st == RG_OK) st = rg_body_set_velocity(w, ball, acc_cv2(s->speed, 0));
    long n = wall_steps(s);
    for (long i = 0; i < n && st == RG_OK; i++) st = rg_world_step(w, (rg_real)s->dt);
    rg_vec2 p = {0, 0};
    if (st == RG_OK) st = rg_body_get_position(w, ball, &p);
    rg_world_destroy(w);
    if (st != RG_OK) return -1;
    return (double)p.x > 0;
}

#define PILE_MAX 64

rg_status acc_pile(int integrator, double dt, double ratio, int n, double seconds,
                   int velocity_iterations, acc_pile_result *out)
{
    rg_world *w = NULL;
    rg_body ground = 0, box[PILE_MAX];
    if (n < 1 || n > PILE_MAX) return RG_ERR_INVALID_ARGUMENT;
    rg_status st = rg_world_create(&w);
    if (st != RG_OK) return st;
    st = rg_world_set_gravity(w, acc_cv2(0, -9.81));
    if (st == RG_OK) st = rg_world_set_integrator(w, integrator);
    if (st == RG_OK && velocity_iterations > 0)
        st = rg_world_set_solver_iterations(w, velocity_iterations, 2);
    if (st == RG_OK) st = rg_body_create(w, RG_BODY_STATIC, 0, acc_cv2(0, -0.5), &ground);
    if (st == RG_OK) st = rg_body_set_aabb(w, ground, 5, 0.5);
    for (int i = 0; i < n && st == RG_OK; i++) {
        double m = n > 1 ? pow(ratio, (double)i / (n - 1)) : 1;
        st = rg_body_create(w, RG_BODY_DYNAMIC, (rg_real)m, acc_cv2(0, 0.5 + i), &box[i]);
        if (st == RG_OK) st = rg_body_set_aabb(w, box[i], 0.5, 0.5);
    }
    acc_pile_result r;
    memset(&r, 0, sizeof r);
    r.finite = 1;
    long steps = (long)ceil(seconds / dt - 1e-9);
    for (long k = 0; k < steps && st == RG_OK; k++) {
        st = rg_world_step(w, (rg_real)dt);
        double err = 0, sp = 0;
        for (int i = 0; i < n && st == RG_OK; i++) {
            rg_vec2 p, v;
            st = rg_body_get_position(w, box[i], &p);
            if (st == RG_OK) st = rg_body_get_velocity(w, box[i], &v);
            if (st != RG_OK) break;
            double e = fabs((double)p.y - (0.5 + i)), d = fabs((double)p.x);
            double s = hypot((double)v.x, (double)v.y);
            if (!isfinite(e) || !isfinite(d) || !isfinite(s)) r.finite = 0;
            if (e > err) err = e;
            if (d > r.max_drift) r.max_drift = d;
            if (s > sp) sp = s;
        }
        if (err > r.max_err) r.max_err = err;
        r.final_err = err;
        r.final_speed = sp;
    }
    rg_world_destroy(w);
    *out = r;
    return st;
}
