/* test_pile.c: piles of circles and boxes in a container: they settle without escaping
 * or sinking, hold under a mass ratio of 100, and sleep. */
#include "testutil.h"

typedef struct pile_stats {
    double max_speed, max_overlap;
    int escaped;
    int32_t awake;
} pile_stats;

/* n bodies (circles r 0.5 or unit boxes) dropped on a 1.1 m grid with jitter into a
 * container of inner width W (floor top y = 0, walls 1 m thick and 40 m tall), run for
 * `seconds`. */
static pile_stats pile(int boxes, int n, double W, double seconds, int sleeping)
{
    rg_world *w = gravity_world(-10);
    assert_ok(rg_world_set_sleeping(w, sleeping));
    box_body(w, RG_BODY_STATIC, 0, 0, -0.5, W / 2 + 1, 0.5);
    box_body(w, RG_BODY_STATIC, 0, -W / 2 - 0.5, 20, 0.5, 20);
    box_body(w, RG_BODY_STATIC, 0, W / 2 + 0.5, 20, 0.5, 20);
    rg_body *b = malloc((size_t)n * sizeof *b);
    int cols = (int)(W / 1.1);
    uint32_t seed = 7;
    for (int i = 0; i < n; i++) {
        seed = seed * 1103515245u + 12345u;
        double jit = ((seed >> 16) % 1000) / 1000.0 * 0.08 - 0.04;
        double x = -W / 2 + 0.55 + (i % cols) * 1.1 + jit, y = 1.5 + (i / cols) * 1.1;
        b[i] = boxes ? box_body(w, RG_BODY_DYNAMIC, 1, x, y, 0.5, 0.5)
                     : circle_body(w, RG_BODY_DYNAMIC, 0.785, x, y, 0.5);
    }
    step_n(w, (int)(seconds / DT), DT);
    pile_stats st = {0, 0, 0, rg_world_awake_body_count(w)};
    rg_vec2 *p = malloc((size_t)n * sizeof *p);
    for (int i = 0; i < n; i++) {
        p[i] = pos_of(w, b[i]);
        rg_vec2 v = vel_of(w, b[i]);
        st.max_speed = fmax(st.max_speed, hypot((double)v.x, (double)v.y));
        double x = (double)p[i].x, y = (double)p[i].y;
        if (fabs(x) > W / 2 - 0.5 + 0.01 || y < 0.49 || y > 40) st.escaped++;
        st.max_overlap = fmax(st.max_overlap, 0.5 - y);
    }
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++) {
            double dx = fabs((double)p[j].x - (double)p[i].x), dy = fabs((double)p[j].y - (double)p[i].y);
            double ov = boxes ? fmin(1 - dx, 1 - dy) : 1 - hypot(dx, dy);
            if (boxes && (dx >= 1 || dy >= 1)) ov = 0;
            st.max_overlap = fmax(st.max_overlap, ov);
        }
    free(p);
    free(b);
    rg_world_destroy(w);
    return st;
}

static void test_a_pile_of_circles_comes_to_rest_in_its_container(void **state)
{
    (void)state;
    pile_stats s = pile(0, 300, 15.5, 10, 0);
    assert_true(s.max_speed < 0.05);
    assert_int_equal(s.escaped, 0);
    assert_true(s.max_overlap < 0.04);
    /* with sleeping, it also falls asleep */
    s = pile(0, 300, 15.5, 10, 1);
    assert_int_equal(s.awake, 0);
    assert_int_equal(s.escaped, 0);
}

static void test_a_pile_of_boxes_comes_to_rest_in_its_container(void **state)
{
    (void)state;
    pile_stats s = pile(1, 300, 15.5, 10, 0);
    assert_true(s.max_speed < 0.05);
    assert_int_equal(s.escaped, 0);
    assert_true(s.max_overlap < 0.04);
    s = pile(1, 300, 15.5, 10, 1);
    assert_int_equal(s.awake, 0);
}

/* A 1 kg box under a 100 kg box: the light one must not be crushed.  Each step the solver
 * carries the heavy box's weight through the light one. */
static void test_a_light_box_holds_a_box_a_hundred_times_heavier(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    assert_ok(rg_world_set_sleeping(w, 0));
    floor_of(w);
    rg_body light = box_body(w, RG_BODY_DYNAMIC, 1, 0, 0.5, 0.5, 0.5);
    rg_body heavy = box_body(w, RG_BODY_DYNAMIC, 100, 0, 1.5, 0.5, 0.5);
    rg_real slop_r, rate, push, thr;
    assert_ok(rg_world_get_contact_tuning(w, &slop_r, &rate, &push, &thr));
        double slop = (double)slop_r;
    for (int i = 0; i < 600; i++) {
        assert_ok(rg_world_step(w, (rg_real)DT));
        assert_true(fabs(PY(w, light) - 0.5) <= slop);
        assert_true(fabs(PY(w, heavy) - 1.5) <= 2 * slop);
    }
    /* a tower of ten, masses 1 .. 100 kg bottom up */
    rg_world *t = gravity_world(-10);
    assert_ok(rg_world_set_sleeping(t, 0));
    floor_of(t);
    rg_body tower[10];
    for (int i = 0; i < 10; i++) tower[i] = box_body(t, RG_BODY_DYNAMIC, pow(100.0, i / 9.0), 0, 0.5 + i, 0.5, 0.5);
    for (int s = 0; s < 600; s++) {
        assert_ok(rg_world_step(t, (rg_real)DT));
        for (int i = 0; i < 10; i++) assert_true(fabs(PY(t, tower[i]) - (0.5 + i)) <= (i + 1) * slop);
    }
    rg_world_destroy(t);
    rg_world_destroy(w);
}

/* Sixty small balls on one wide dynamic plank: the plank is in more rows than the solver has
 * colours (32), so some of its rows are solved one at a time; the load still holds. */
static void test_a_body_in_more_rows_than_colours_still_holds_its_load(void **state)
{
    (void)state;
    rg_world *w = gravity_world(-10);
    assert_ok(rg_world_set_sleeping(w, 0));
    floor_of(w);
    rg_body plank = box_body(w, RG_BODY_DYNAMIC, 10, 0, 0.25, 31, 0.25);
    rg_body ball[60];
    for (int i = 0; i < 60; i++) ball[i] = circle_body(w, RG_BODY_DYNAMIC, 1, -29.5 + i, 0.75, 0.25);
    step_n(w, 300, DT);
    assert_near(PY(w, plank), 0.25, 0.006);
    for (int i = 0; i < 60; i++) {
        assert_near(PY(w, ball[i]), 0.75, 0.011);
        assert_near(VY(w, ball[i]), 0, 1e-3);
    }
    rg_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_pile_of_circles_comes_to_rest_in_its_container),
        cmocka_unit_test(test_a_pile_of_boxes_comes_to_rest_in_its_container),
        cmocka_unit_test(test_a_light_box_holds_a_box_a_hundred_times_heavier),
        cmocka_unit_test(test_a_body_in_more_rows_than_colours_still_holds_its_load),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
