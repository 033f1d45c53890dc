/* accuracy_soup.c: random soups of boxes and circles without gravity, for the accuracy lab:
 * how far contacts keep momentum and kinetic energy (accuracy --soup); a heavy box run into a
 * light one against a wall, which should stop dead; and a fast kinematic paddle through loose
 * bodies, which should push every one ahead. */
#include <math.h>

#include "accuracy_collision.h"

/* A uniform number in [0, 1) from a 32-bit linear congruential state. */
static double soup_uniform(uint32_t *s)
{
    *s = *s * 1103515245u + 12345u;
    return (double)((*s >> 8) & 0xFFFFFF) / 16777216.0;
}

/* The kinetic energy and momentum of the n bodies. */
static rg_status soup_measure(rg_world *w, const rg_body *b, const double *m, int n, double *ke, double *px,
                              double *py)
{
    *ke = *px = *py = 0;
    for (int i = 0; i < n; i++) {
        rg_vec2 v;
        rg_status st = rg_body_get_velocity(w, b[i], &v);
        if (st != RG_OK) return st;
        double vx = (double)v.x, vy = (double)v.y;
        *ke += 0.5 * m[i] * (vx * vx + vy * vy);
        *px += m[i] * vx;
        *py += m[i] * vy;
    }
    return RG_OK;
}

/* One scene: bodies on a 1 m grid (9 a row, jittered by up to 0.1 m, half extents or radii
 * 0.1-0.4 m, so that none overlaps at the start), masses 0.1-5.1 kg, half of them thrown. */
static rg_status soup_scene(const acc_soup *s, uint32_t seed, acc_soup_result *r)
{
    enum { SOUP_MAX = 80 };
    uint32_t u = seed * 7919u;
    rg_world *w = NULL;
    rg_body b[SOUP_MAX];
    double m[SOUP_MAX] = { 0 }; /* (set for every body made; gcc for s390x cannot tell) */
    int n = 20 + (int)(soup_uniform(&u) * (SOUP_MAX - 20));
    rg_status st = rg_world_create(&w);
    if (st == RG_OK) st = rg_world_set_sleeping(w, 0);
    if (st == RG_OK) st = rg_world_set_solver_iterations(w, s->velocity_iterations, 3);
    for (int i = 0; i < n && st == RG_OK; i++) {
        m[i] = 0.1 + soup_uniform(&u) * 5;
        double x = (i % 9) + soup_uniform(&u) * 0.1, y = (i / 9) + soup_uniform(&u) * 0.1;
        st = rg_body_create(w, RG_BODY_DYNAMIC, (rg_real)m[i], acc_cv2(x, y), &b[i]);
        double h0 = 0.1 + soup_uniform(&u) * 0.3, h1 = 0.1 + soup_uniform(&u) * 0.3;
        if (st == RG_OK)
            st = soup_uniform(&u) < 0.5 ? rg_body_set_circle(w, b[i], (rg_real)h0) : rg_body_set_aabb(w, b[i], (rg_real)h0, (rg_real)h1);
        double e = soup_uniform(&u) < 0.3 ? 1 : soup_uniform(&u), mu = soup_uniform(&u) < 0.5 ? 0 : soup_uniform(&u);
        if (st == RG_OK) st = rg_body_set_restitution(w, b[i], (rg_real)(s->restitution ? e : 0));
        if (st == RG_OK) st = rg_body_set_friction(w, b[i], (rg_real)(s->friction ? mu : 0));
        double speed = soup_uniform(&u) < 0.5 ? 0 : soup_uniform(&u) * s->max_speed, a = soup_uniform(&u) * 6.283185307179586;
        if (st == RG_OK) st = rg_body_set_velocity(w, b[i], acc_cv2(speed * cos(a), speed * sin(a)));
    }
    double ke0 = 0, px0 = 0, py0 = 0, scale = 0;
    if (st == RG_OK) st = soup_measure(w, b, m, n, &ke0, &px0, &py0);
    for (int i = 0; i < n && st == RG_OK; i++) {
        rg_vec2 v;
        st = rg_body_get_velocity(w, b[i], &v);
        scale += m[i] * hypot((double)v.x, (double)v.y);
    }
    double low = ke0, gain = 0;
    for (int k = 0; k < s->steps && st == RG_OK && ke0 > 0; k++) {
        double ke, px, py;
        st = rg_world_step(w, (rg_real)(1.0 / 60));
        if (st == RG_OK) st = soup_measure(w, b, m, n, &ke, &px, &py);
        if (st != RG_OK) break;
        double dp = hypot(px - px0, py - py0) / scale;
        if (dp > r->worst_momentum) r->worst_momentum = dp;
        if ((ke - low) / ke0 > gain) gain = (ke - low) / ke0;
        if (ke < low) low = ke;
    }
    if (gain > r->worst_gain) r->worst_gain = gain;
    if (gain > 1e-3) r->gaining++;
    rg_world_destroy(w);
    return st;
}

rg_status acc_soup_run(const acc_soup *s, acc_soup_result *r)
{
    r->worst_momentum = r->worst_gain = 0;
    r->gaining = 0;
    for (int k = 1; k <= s->scenes; k++) {
        rg_status st = soup_scene(s, (uint32_t)k, r);
        if (st != RG_OK) return st;
    }
    return RG_OK;
}

rg_status acc_push_rebound(double ratio, double speed, int velocity_iterations, double *out_back)
{
    rg_world *w = NULL;
    rg_body floor, wall, crate, pusher;
    rg_status st = rg_world_create(&w);
    if (st == RG_OK) st = rg_world_set_gravity(w, acc_cv2(0, -10));
    if (st == RG_OK) st = rg_world_set_solver_iterations(w, velocity_iterations, 3);
    if (st == RG_OK) st = rg_body_create(w, RG_BODY_STATIC, 0, acc_cv2(0, -0.5), &floor);
    if (st == RG_OK) st = rg_body_set_aabb(w, floor, 10, 0.5);
    if (st == RG_OK) st = rg_body_set_friction(w, floor, 0);
    if (st == RG_OK) st = rg_body_create(w, RG_BODY_STATIC, 0, acc_cv2(1, 2), &wall);
    if (st == RG_OK) st = rg_body_set_aabb(w, wall, 0.5, 2);
    if (st == RG_OK) st = rg_body_create(w, RG_BODY_DYNAMIC, 1, acc_cv2(0.25, 0.25), &crate);
    if (st == RG_OK) st = rg_body_set_aabb(w, crate, 0.25, 0.25);
    if (st == RG_OK) st = rg_body_create(w, RG_BODY_DYNAMIC, (rg_real)ratio, acc_cv2(-1, 0.3), &pusher);
    if (st == RG_OK) st = rg_body_set_aabb(w, pusher, 0.3, 0.3);
    if (st == RG_OK) st = rg_body_set_velocity(w, pusher, acc_cv2(speed, 0));
    double back = 0;
    for (int k = 0; k < 120 && st == RG_OK; k++) {
        rg_vec2 v;
        st = rg_world_step(w, (rg_real)(1.0 / 60));
        if (st == RG_OK) st = rg_body_get_velocity(w, pusher, &v);
        if (st == RG_OK && -(double)v.x > back) back = -(double)v.x;
    }
    rg_world_destroy(w);
    *out_back = back;
    return st;
}

/* One paddle scene (acc_paddle_run): adds its bodies and those that got behind the paddle. */
static rg_status paddle_scene(uint32_t u, double lo, double hi, int *through, int *bodies)
{
    enum { PADDLE_MAX = 20 };
    rg_world *w = NULL;
    rg_body floor, pad, b[PADDLE_MAX];
    int n = 1 + (int)(soup_uniform(&u) * 19), behind[PADDLE_MAX] = { 0 };
    double size[PADDLE_MAX];
    double th = 0.01 + 0.05 * soup_uniform(&u), speed = lo + (hi - lo) * soup_uniform(&u);
    rg_status st = rg_world_create(&w);
    if (st == RG_OK) st = rg_world_set_gravity(w, acc_cv2(0, soup_uniform(&u) < 0.5 ? 0 : -10));
    if (st == RG_OK) st = rg_world_set_sleeping(w, 0);
    if (st == RG_OK) st = rg_body_create(w, RG_BODY_STATIC, 0, acc_cv2(0, -0.5), &floor);
    if (st == RG_OK) st = rg_body_set_aabb(w, floor, 100, 0.5);
    if (st == RG_OK) st = rg_body_create(w, RG_BODY_KINEMATIC, 0, acc_cv2(-5, 1.5), &pad);
    if (st == RG_OK) st = rg_body_set_aabb(w, pad, (rg_real)th, 1.5);
    if (st == RG_OK) st = rg_body_set_velocity(w, pad, acc_cv2(speed, 0));
    for (int k = 0; k < n && st == RG_OK; k++) {
        double r = 0.03 + 0.3 * soup_uniform(&u), x = -3 + 8 * soup_uniform(&u), y = r + 2.2 * soup_uniform(&u);
        size[k] = r;
        int circle = soup_uniform(&u) < 0.5;
        st = rg_body_create(w, RG_BODY_DYNAMIC, (rg_real)(0.1 + 5 * soup_uniform(&u)), acc_cv2(x, y), &b[k]);
        if (st == RG_OK) st = circle ? rg_body_set_circle(w, b[k], (rg_real)r) : rg_body_set_aabb(w, b[k], (rg_real)r, (rg_real)r);
    }
    for (int i = 0; i < 120 && st == RG_OK; i++) {
        rg_vec2 p0, p1, q[PADDLE_MAX];
        st = rg_body_get_position(w, pad, &p0);
        for (int k = 0; k < n && st == RG_OK; k++) st = rg_body_get_position(w, b[k], &q[k]);
        if (st == RG_OK) st = rg_world_step(w, (rg_real)(1.0 / 60));
        if (st == RG_OK) st = rg_body_get_position(w, pad, &p1);
        for (int k = 0; k < n && st == RG_OK; k++) {
            rg_vec2 e;
            st = rg_body_get_position(w, b[k], &e);
            /* ahead of the paddle's centre, then behind it, level with it (not a body that
             * fell off the floor's end below it) */
            if (st == RG_OK && q[k].x > p0.x && e.x < p1.x && (double)e.y - size[k] < 3 && (double)e.y + size[k] > 0) behind[k] = 1;
        }
    }
    for (int k = 0; k < n; k++) *through += behind[k];
    *bodies += n;
    rg_world_destroy(w);
    return st;
}

rg_status acc_paddle_run(int scenes, double lo, double hi, int *out_through, int *out_bodies)
{
    *out_through = *out_bodies = 0;
    for (int k = 1; k <= scenes; k++) {
        rg_status st = paddle_scene((uint32_t)k * 104729u, lo, hi, out_through, out_bodies);
        if (st != RG_OK) return st;
    }
    return RG_OK;
}
