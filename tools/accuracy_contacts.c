/* accuracy_contacts.c: contacts under each integrator, for the accuracy lab (accuracy
 * --contacts): the figures the README gives for jumps into a ceiling, bounces, landings,
 * friction that holds and friction that stops, and a pile that goes to sleep.  Each scene
 * states its exact answer; the table prints how far each integrator is from it. */
#include <math.h>
#include <stdio.h>

#include "accuracy_collision.h"

#define CT_TRY(call)                      \
    do {                                  \
        rg_status st_ = (call);           \
        if (st_ != RG_OK) return st_;     \
    } while (0)

/* A world with gravity (0, -g) and the integrator. */
static rg_status ct_world(int integrator, double g, rg_world **out)
{
    CT_TRY(rg_world_create(out));
    rg_status st = rg_world_set_gravity(*out, acc_cv2(0, -g));
    if (st == RG_OK) st = rg_world_set_integrator(*out, integrator);
    if (st != RG_OK) rg_world_destroy(*out);
    return st;
}

/* A body of mass m at (x, y) with a box of half extents (hw, hh), or a circle of radius hw
 * when hh is 0. */
static rg_status ct_body(rg_world *w, int32_t type, double m, double x, double y, double hw, double hh,
                         rg_body *out)
{
    CT_TRY(rg_body_create(w, type, (rg_real)m, acc_cv2(x, y), out));
    return hh > 0 ? rg_body_set_aabb(w, *out, (rg_real)hw, (rg_real)hh) : rg_body_set_circle(w, *out, (rg_real)hw);
}

static rg_status ct_state(rg_world *w, rg_body b, double *y, double *vy)
{
    rg_vec2 p, v;
    CT_TRY(rg_body_get_position(w, b, &p));
    CT_TRY(rg_body_get_velocity(w, b, &v));
    *y = (double)p.y;
    *vy = (double)v.y;
    return RG_OK;
}

/* Jumps of a 1 m box from `starts` heights (bottom at 0 to 1 m) at v = sqrt(2 g 1.8) into a
 * static ceiling whose face is at 3 m, 60 steps of dt: how many jumps end a step inside it by
 * more than the slop (5 mm), and the deepest.  Exact: none. */
static rg_status ct_ceiling(int integrator, double g, double dt, int starts, int *over, double *deepest)
{
    *over = 0;
    *deepest = 0;
    for (int k = 0; k < starts; k++) {
        rg_world *w;
        rg_body ceiling, box;
        CT_TRY(ct_world(integrator, g, &w));
        rg_status st = ct_body(w, RG_BODY_STATIC, 0, 0, 3.01, 100, 0.01, &ceiling);
        if (st == RG_OK) st = ct_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5 + (double)k / starts, 0.5, 0.5, &box);
        if (st == RG_OK) st = rg_body_set_velocity(w, box, acc_cv2(0, sqrt(2 * g * 1.8)));
        double worst = 0, y = 0, vy = 0;
        for (int s = 0; s < 60 && st == RG_OK; s++) {
            st = rg_world_step(w, (rg_real)dt);
            if (st == RG_OK) st = ct_state(w, box, &y, &vy);
            worst = fmax(worst, y + 0.5 - 3);
        }
        rg_world_destroy(w);
        CT_TRY(st);
        if (worst > 0.005) (*over)++;
        *deepest = fmax(*deepest, worst);
    }
    return RG_OK;
}

/* A ball of radius 0.5 dropped from `heights` heights h in [1, 10.2] m onto a static floor,
 * restitution e, g 10, 60 Hz: the largest excess of the first rebound's apex over e^2 h +
 * g dt^2 / 8 (the bound the header promises; Verlet and RK4 are exact in flight, explicit
 * and semi-implicit Euler within g dt^2 / 8 of it). */
static rg_status ct_bounce(int integrator, double e, int heights, double *above)
{
    const double g = 10, dt = 1.0 / 60;
    *above = -HUGE_VAL;
    for (int k = 0; k < heights; k++) {
        double h = 1 + 9.2 * k / (heights - 1);
        rg_world *w;
        rg_body floor, ball;
        CT_TRY(ct_world(integrator, g, &w));
        rg_status st = ct_body(w, RG_BODY_STATIC, 0, 0, -0.5, 100, 0.5, &floor);
        if (st == RG_OK) st = ct_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5 + h, 0.5, 0, &ball);
        if (st == RG_OK) st = rg_body_set_restitution(w, ball, (rg_real)e);
        int bounced = 0;
        double apex = 0, y = 0, vy = 0;
        for (int s = 0; s < 2000 && st == RG_OK; s++) {
            st = rg_world_step(w, (rg_real)dt);
            if (st == RG_OK) st = ct_state(w, ball, &y, &vy);
            if (vy > 0) bounced = 1;
            if (bounced) apex = fmax(apex, y - 0.5);
            if (bounced && vy < 0 && y - 0.5 < apex) break;
        }
        rg_world_destroy(w);
        CT_TRY(st);
        double bound = g * dt * dt / 8;
        *above = fmax(*above, apex - (e * e * h + bound));
    }
    return RG_OK;
}

/* A 1 m box dropped from 1 m with restitution 0 onto a static floor at 60 Hz, g 10: its gap
 * over the floor at the end of the step it lands in, and at the end of the next one.
 * Exact: 0 and 0. */
static rg_status ct_landing(int integrator, double *gap_landing, double *gap_next)
{
    rg_world *w;
    rg_body floor, box;
    CT_TRY(ct_world(integrator, 10, &w));
    rg_status st = ct_body(w, RG_BODY_STATIC, 0, 0, -0.5, 100, 0.5, &floor);
    if (st == RG_OK) st = ct_body(w, RG_BODY_DYNAMIC, 1, 0, 1.5, 0.5, 0.5, &box);
    double y = 0, vy = 0, prev = -1;
    *gap_landing = *gap_next = HUGE_VAL;
    for (int s = 0; s < 200 && st == RG_OK; s++) {
        st = rg_world_step(w, (rg_real)(1.0 / 60));
        if (st == RG_OK) st = ct_state(w, box, &y, &vy);
        if (prev < 0 && vy > -1e-3 && s > 0) {
            *gap_landing = y - 0.5;
            if (st == RG_OK) st = rg_world_step(w, (rg_real)(1.0 / 60));
            if (st == RG_OK) st = ct_state(w, box, &y, &vy);
            *gap_next = y - 0.5;
            break;
        }
        prev = vy < -1e-3 ? -1 : 0;
    }
    rg_world_destroy(w);
    return st;
}

/* A 1 kg box at rest on a static floor (mu 0.6 both: static friction up to 5.886 N) pushed
 * by a wind of 3 N for 5 s at 60 Hz: how far it moves, with sleeping off and with it on.
 * Exact: 0. */
static rg_status ct_hold(int integrator, int sleeping, double *moved)
{
    rg_world *w;
    rg_body floor, box;
    CT_TRY(ct_world(integrator, 9.81, &w));
    rg_status st = rg_world_set_sleeping(w, sleeping);
    if (st == RG_OK) st = ct_body(w, RG_BODY_STATIC, 0, 0, -0.5, 100, 0.5, &floor);
    if (st == RG_OK) st = ct_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5, 0.5, &box);
    if (st == RG_OK) st = rg_body_set_friction(w, floor, (rg_real)0.6);
    if (st == RG_OK) st = rg_body_set_friction(w, box, (rg_real)0.6);
    for (int s = 0; s < 10 && st == RG_OK; s++) st = rg_world_step(w, (rg_real)(1.0 / 60));
    if (st == RG_OK) st = rg_world_set_wind(w, acc_cv2(3, 0));
    rg_vec2 p0 = {0, 0}, p1 = {0, 0};
    if (st == RG_OK) st = rg_body_get_position(w, box, &p0);
    for (int s = 0; s < 300 && st == RG_OK; s++) st = rg_world_step(w, (rg_real)(1.0 / 60));
    if (st == RG_OK) st = rg_body_get_position(w, box, &p1);
    *moved = (double)p1.x - (double)p0.x;
    rg_world_destroy(w);
    return st;
}

/* A 2 kg box sent along a static floor at 6 m/s, mu 0.5 both, g 10, 60 Hz, 3 s: where it
 * stops.  Exact (Coulomb): v^2 / (2 mu g) = 3.6 m. */
static rg_status ct_slide(int integrator, double *stop)
{
    rg_world *w;
    rg_body floor, box;
    CT_TRY(ct_world(integrator, 10, &w));
    rg_status st = ct_body(w, RG_BODY_STATIC, 0, 0, -0.5, 100, 0.5, &floor);
    if (st == RG_OK) st = ct_body(w, RG_BODY_DYNAMIC, 2, 0, 0.5, 0.5, 0.5, &box);
    if (st == RG_OK) st = rg_body_set_friction(w, floor, (rg_real)0.5);
    if (st == RG_OK) st = rg_body_set_friction(w, box, (rg_real)0.5);
    if (st == RG_OK) st = rg_body_set_velocity(w, box, acc_cv2(6, 0));
    for (int s = 0; s < 180 && st == RG_OK; s++) st = rg_world_step(w, (rg_real)(1.0 / 60));
    rg_vec2 p = {0, 0};
    if (st == RG_OK) st = rg_body_get_position(w, box, &p);
    *stop = (double)p.x;
    rg_world_destroy(w);
    return st;
}

/* 100 boxes of 1 m in 10 columns of 10, 1 mm apart (each box 1 mm above the one below),
 * sleeping on, 60 Hz, g 10: when the last one falls asleep (s), and the deepest overlap
 * then.  Exact: they settle by 1 mm each and sleep after the sleep time (0.5 s) at rest. */
static rg_status ct_pile(int integrator, double *asleep, double *deepest)
{
    enum { COLS = 10, ROWS = 10 };
    rg_world *w;
    rg_body floor, box[COLS * ROWS];
    CT_TRY(ct_world(integrator, 10, &w));
    rg_status st = ct_body(w, RG_BODY_STATIC, 0, 0, -0.5, 100, 0.5, &floor);
    for (int c = 0; c < COLS && st == RG_OK; c++)
        for (int r = 0; r < ROWS && st == RG_OK; r++)
            st = ct_body(w, RG_BODY_DYNAMIC, 1, 1.5 * (c - COLS / 2), 0.501 + 1.001 * r, 0.5, 0.5, &box[c * ROWS + r]);
    *asleep = HUGE_VAL;
    *deepest = 0;
    for (int s = 1; s <= 600 && st == RG_OK; s++) {
        st = rg_world_step(w, (rg_real)(1.0 / 60));
        int awake = 0;
        for (int k = 0; k < COLS * ROWS && st == RG_OK; k++) {
            int32_t a = 0;
            st = rg_body_is_awake(w, box[k], &a);
            awake |= a;
        }
        if (!awake && st == RG_OK) {
            *asleep = s / 60.0;
            for (int c = 0; c < COLS && st == RG_OK; c++) {
                double below = 0; /* the top of the floor, then of each box */
                for (int r = 0; r < ROWS && st == RG_OK; r++) {
                    double y = 0, vy = 0;
                    st = ct_state(w, box[c * ROWS + r], &y, &vy);
                    *deepest = fmax(*deepest, below - (y - 0.5));
                    below = y + 0.5;
                }
            }
            break;
        }
    }
    rg_world_destroy(w);
    return st;
}

int acc_contacts_print(int quick)
{
    static const char *names[4] = {"explicit Euler", "semi-implicit Euler", "Verlet", "RK4"};
    int starts = quick ? 50 : 200, heights = quick ? 10 : 40;
    printf("Contacts under each integrator (%s build; exact answers in brackets)\n",
           sizeof(rg_real) == 8 ? "double" : "float");
    printf("  jumps into a ceiling: of %d starts, ending a step inside it beyond the 5 mm slop,\n"
           "    and the deepest (mm) [0]; bounces off a floor from %d heights of 1-10.2 m, the\n"
           "    rebound's apex over e^2 h + g dt^2/8 (mm, 60 Hz: g dt^2/8 = 0.35 mm) [<= 0];\n"
           "    a landing's gap at the end of its step and of the next (mm) [0]; a held box's\n"
           "    creep in 5 s (mm) [0]; a slide's stop (m) [3.6]; a pile of 100 asleep (s), its\n"
           "    deepest overlap then (mm) [0.5-0.6 s, < 5]\n",
           starts, heights);
    printf("%-20s %10s %10s %9s %9s %9s %9s %9s %9s %7s %7s\n", "integrator", "ceil30", "ceil60g40", "e=1",
           "e=0.5", "land", "next", "hold", "hold+zz", "slide", "pile");
    int fails = 0;
    for (int m = 0; m < 4; m++) {
        int over30, over60;
        double deep30, deep60, up1, up5, gap, gap2, hold, holdz, stop, asleep, deep;
        rg_status st = ct_ceiling(m, 9.81, 1.0 / 30, starts, &over30, &deep30);
        if (st == RG_OK) st = ct_ceiling(m, 40, 1.0 / 60, starts, &over60, &deep60);
        if (st == RG_OK) st = ct_bounce(m, 1, heights, &up1);
        if (st == RG_OK) st = ct_bounce(m, 0.5, heights, &up5);
        if (st == RG_OK) st = ct_landing(m, &gap, &gap2);
        if (st == RG_OK) st = ct_hold(m, 0, &hold);
        if (st == RG_OK) st = ct_hold(m, 1, &holdz);
        if (st == RG_OK) st = ct_slide(m, &stop);
        if (st == RG_OK) st = ct_pile(m, &asleep, &deep);
        if (st != RG_OK) {
            printf("%-20s failed: %s\n", names[m], rg_status_string(st));
            fails++;
            continue;
        }
        printf("%-20s %3d %6.2f %3d %6.2f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %7.3f %4.2f %4.2f\n", names[m], over30,
               1e3 * deep30, over60, 1e3 * deep60, 1e3 * up1, 1e3 * up5, 1e3 * gap, 1e3 * gap2, 1e3 * hold,
               1e3 * holdz, stop, asleep, 1e3 * deep);
    }
    return fails;
}
