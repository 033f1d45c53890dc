/* seed.c: the seed scene.  A 1 kg ball thrown at (12, 14) m/s under gravity (0, -9.81),
 * a wind force (1.5, 0) N and quadratic drag 0.02 kg/m, once per integrator at 60 Hz,
 * printed next to a reference: the same ODE integrated by RK4 in double precision at
 * 1/6000 s (its global error, O(dt^4), is below 1e-9 m here). */
#include <math.h>
#include <stdio.h>

#include "rigid.h"

#define MASS 1.0
#define DRAG 0.02
#define WINDX 1.5
#define G 9.81
#define VX0 12.0
#define VY0 14.0
#define DT (1.0 / 60.0)
#define STEPS 180

typedef struct { double x, y, vx, vy; } state;

static state deriv(state s)
{
    double speed = sqrt(s.vx * s.vx + s.vy * s.vy);
    state d = { s.vx, s.vy, (WINDX - DRAG * speed * s.vx) / MASS, -G - DRAG * speed * s.vy / MASS };
    return d;
}

static state axpy(state s, state d, double h)
{
    state r = { s.x + h * d.x, s.y + h * d.y, s.vx + h * d.vx, s.vy + h * d.vy };
    return r;
}

/* Reference: RK4 at DT/100 up to time t. */
static state reference(double t)
{
    state s = { 0, 0, VX0, VY0 };
    int n = (int)lround(t / DT) * 100;
    double h = DT / 100;
    for (int i = 0; i < n; i++) {
        state k1 = deriv(s), k2 = deriv(axpy(s, k1, h / 2)), k3 = deriv(axpy(s, k2, h / 2)),
              k4 = deriv(axpy(s, k3, h));
        s.x += h / 6 * (k1.x + 2 * k2.x + 2 * k3.x + k4.x);
        s.y += h / 6 * (k1.y + 2 * k2.y + 2 * k3.y + k4.y);
        s.vx += h / 6 * (k1.vx + 2 * k2.vx + 2 * k3.vx + k4.vx);
        s.vy += h / 6 * (k1.vy + 2 * k2.vy + 2 * k3.vy + k4.vy);
    }
    return s;
}

static int check(rg_status st, const char *what)
{
    if (st != RG_OK) fprintf(stderr, "seed: %s: %s\n", what, rg_status_string(st));
    return st != RG_OK;
}

int main(void)
{
    static const char *names[] = { "explicit Euler", "semi-implicit Euler", "velocity Verlet", "RK4" };
    printf("rigid %d.%d.%d seed scene: 1 kg ball, v0 = (%.0f, %.0f) m/s, gravity %.2f m/s^2, "
           "wind %.1f N, quadratic drag %.2f kg/m, dt = 1/60 s\n",
           RG_VERSION_MAJOR, RG_VERSION_MINOR, RG_VERSION_PATCH, VX0, VY0, G, WINDX, DRAG);
    printf("reference: the same equations by RK4 in double at dt/100\n");
    for (int integ = RG_INTEGRATOR_EXPLICIT_EULER; integ <= RG_INTEGRATOR_RK4; integ++) {
        rg_world *w = NULL;
        rg_body b = 0;
        if (check(rg_world_create(&w), "world")) return 1;
        rg_vec2 g = { 0, (rg_real)-G }, wind = { (rg_real)WINDX, 0 }, p0 = { 0, 0 },
                v0 = { (rg_real)VX0, (rg_real)VY0 };
        if (check(rg_world_set_gravity(w, g), "gravity") || check(rg_world_set_wind(w, wind), "wind") ||
            check(rg_world_set_integrator(w, integ), "integrator") ||
            check(rg_body_create(w, RG_BODY_DYNAMIC, (rg_real)MASS, p0, &b), "body") ||
            check(rg_body_set_velocity(w, b, v0), "velocity") ||
            check(rg_body_set_drag(w, b, 0, (rg_real)DRAG), "drag"))
            return 1;
        printf("\n%s\n%6s %10s %10s %10s | %10s %10s %10s | %10s\n", names[integ], "t (s)", "x (m)",
               "y (m)", "speed", "ref x", "ref y", "ref speed", "|err| (m)");
        for (int step = 0; step <= STEPS; step++) {
            if (step % 30 == 0) {
                rg_vec2 p, v;
                if (check(rg_body_get_position(w, b, &p), "position") ||
                    check(rg_body_get_velocity(w, b, &v), "velocity"))
                    return 1;
                double t = step * DT;
                state r = reference(t);
                double err = hypot((double)p.x - r.x, (double)p.y - r.y);
                printf("%6.2f %10.4f %10.4f %10.4f | %10.4f %10.4f %10.4f | %10.2e\n", t, (double)p.x,
                       (double)p.y, hypot((double)v.x, (double)v.y), r.x, r.y, hypot(r.vx, r.vy), err);
            }
            if (step < STEPS && check(rg_world_step(w, (rg_real)DT), "step")) return 1;
        }
        rg_world_destroy(w);
    }
    return 0;
}
