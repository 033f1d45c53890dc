/* test_shapeless.c: bodies without shapes change none of the bits of the bodies that collide.
 *
 * A world of many awake bodies of which few collide takes other paths through the solve than
 * a pile does (resolve.c: its body passes walk the list of the bodies the rows meet, and the
 * arrays per solver body are cleared row by row instead of whole; continuous.c and solver.c
 * likewise), and the range guard tests the bodies in blocks.  Those paths must give the same
 * bits as the pile alone: a pile of 160 circles and boxes (restitution, so that impacts are
 * timed; a deep drop, so that the position pass pushes) is stepped alone and beside 12,000
 * shapeless bodies made after it (falling far away: they meet nothing), on one thread and
 * under the shuffler (random splits and order of every task's ranges), and every pile body
 * must end each step with the same bits of position and velocity.  A body driven out of
 * range among the shapeless ones is stopped as the guard promises, the pile unchanged. */
#include "shuffler.h"
#include "testutil.h"

#define PILE 160
#define SHAPELESS 12000
#define STEPS 150

typedef struct pile {
    rg_world *w;
    rg_body b[PILE];
} pile;

static void pile_make(pile *p, const rg_task_system *tasks)
{
    assert_ok(rg_world_create(&p->w));
    if (tasks != NULL) assert_ok(rg_world_set_task_system(p->w, tasks));
    assert_ok(rg_world_set_gravity(p->w, v2(0, -9.81)));
    assert_ok(rg_world_set_sleeping(p->w, 0));
    for (int i = 0; i < PILE; i++) {
        rg_vec2 at = v2((rg_real)(-4.5 + (i % 10) * 1.0 + 0.011 * (i % 7)), (rg_real)(1 + (i / 10) * 1.1));
        assert_ok(rg_body_create(p->w, RG_BODY_DYNAMIC, (rg_real)(0.5 + 0.25 * (i % 5)), at, &p->b[i]));
        if (i % 3 == 0)
            assert_ok(rg_body_set_aabb(p->w, p->b[i], 0.4f, 0.35f));
        else
            assert_ok(rg_body_set_circle(p->w, p->b[i], (rg_real)(0.3 + 0.04 * (i % 4))));
        if (i % 4 == 1) assert_ok(rg_body_set_restitution(p->w, p->b[i], 0.5f));
        if (i % 10 == 3) assert_ok(rg_body_set_velocity(p->w, p->b[i], v2(0, -25))); /* an impact */
    }
    rg_body b;
    assert_ok(rg_body_create(p->w, RG_BODY_STATIC, 0, v2(0, -0.5), &b));
    assert_ok(rg_body_set_aabb(p->w, b, 6, 0.5));
    for (int side = -1; side <= 1; side += 2) {
        assert_ok(rg_body_create(p->w, RG_BODY_STATIC, 0, v2((rg_real)(side * 6.5), 10), &b));
        assert_ok(rg_body_set_aabb(p->w, b, 0.5, 11));
    }
}

/* The shapeless crowd, far to the side, after the pile. */
static void crowd(pile *p)
{
    for (int i = 0; i < SHAPELESS; i++) {
        rg_body b;
        rg_vec2 at = v2((rg_real)(1000 + (i % 100) * 2.0), (rg_real)(100 + (i / 100) * 2.0));
        assert_ok(rg_body_create(p->w, RG_BODY_DYNAMIC, 1, at, &b));
        assert_ok(rg_body_set_velocity(p->w, b, v2((rg_real)(0.1 * (i % 7)), 0)));
    }
}

static void assert_same_bits(const pile *a, const pile *b, int step)
{
    for (int i = 0; i < PILE; i++) {
        rg_vec2 pa, pb, va, vb;
        assert_ok(rg_body_get_position(a->w, a->b[i], &pa));
        assert_ok(rg_body_get_position(b->w, b->b[i], &pb));
        assert_ok(rg_body_get_velocity(a->w, a->b[i], &va));
        assert_ok(rg_body_get_velocity(b->w, b->b[i], &vb));
        if (memcmp(&pa, &pb, sizeof pa) != 0 || memcmp(&va, &vb, sizeof va) != 0) {
            printf("  body %d differs at step %d: (%.9g, %.9g) v (%.9g, %.9g) against (%.9g, %.9g) v (%.9g, %.9g)\n",
                   i, step, (double)pa.x, (double)pa.y, (double)va.x, (double)va.y, (double)pb.x, (double)pb.y,
                   (double)vb.x, (double)vb.y);
            fail();
        }
    }
}

static void run_beside(const rg_task_system *tasks)
{
    pile alone, beside;
    pile_make(&alone, NULL);
    pile_make(&beside, tasks);
    crowd(&beside);
    for (int s = 1; s <= STEPS; s++) {
        assert_ok(rg_world_step(alone.w, (rg_real)(1.0 / 60)));
        assert_ok(rg_world_step(beside.w, (rg_real)(1.0 / 60)));
        assert_same_bits(&alone, &beside, s);
    }
    /* the pile did collide: once it has settled every body rests on the floor or another
     * body (PILE touching pairs at least); half of that allows for bodies still bouncing off
     * the restitution, so the comparison above did cover colliding bodies */
    assert_true(rg_world_touching_count(alone.w) > PILE / 2);
    assert_int_equal(rg_world_touching_count(alone.w), rg_world_touching_count(beside.w));
    rg_world_destroy(alone.w);
    rg_world_destroy(beside.w);
}

static void test_shapeless_bodies_change_no_bit_of_a_pile(void **state)
{
    (void)state;
    run_beside(NULL);
}

static void test_shapeless_bodies_change_no_bit_of_a_pile_with_workers(void **state)
{
    (void)state;
    for (int32_t k = 2; k <= 4; k++) {
        shuffler sh;
        rg_task_system ts;
        shuffler_init(&sh, 0x2545F4914F6CDD1Dull * (uint64_t)k, k, 0);
        shuffler_tasks(&sh, &ts);
        run_beside(&ts);
        assert_true(sh.ranges > sh.tasks); /* the tasks were split */
        assert_int_equal(sh.misuse, 0);
    }
}

/* A shapeless body driven out of range in the middle of the crowd (a force past what the range
 * keeps over a step: RG_MAX_FORCE on the lightest mass for many steps) is stopped at the edge
 * and listed; its neighbours in the same block of the guard, and the pile, are untouched. */
static void test_the_guard_stops_one_body_in_a_block_of_the_crowd(void **state)
{
    (void)state;
    pile alone, beside;
    pile_make(&alone, NULL);
    pile_make(&beside, NULL);
    crowd(&beside);
    rg_body runaway, next;
    assert_ok(rg_body_create(beside.w, RG_BODY_DYNAMIC, (rg_real)RG_MIN_MASS, v2(5000, 0), &runaway));
    assert_ok(rg_body_create(beside.w, RG_BODY_DYNAMIC, 1, v2(5010, 0), &next));
    int stopped_at = 0;
    for (int s = 1; s <= STEPS && stopped_at == 0; s++) {
        assert_ok(rg_body_apply_force(beside.w, runaway, v2((rg_real)RG_MAX_FORCE, 0)));
        assert_ok(rg_world_step(alone.w, (rg_real)(1.0 / 60)));
        assert_ok(rg_world_step(beside.w, (rg_real)(1.0 / 60)));
        assert_same_bits(&alone, &beside, s);
        rg_body out[4];
        int32_t n = rg_world_get_stopped(beside.w, out, 4);
        if (n > 0) {
            assert_int_equal(n, 1);
            assert_true(out[0] == runaway);
            stopped_at = s;
        }
    }
    assert_true(stopped_at > 0);
    rg_vec2 p, v;
    assert_ok(rg_body_get_position(beside.w, runaway, &p));
    assert_ok(rg_body_get_velocity(beside.w, runaway, &v));
    assert_true(p.x <= (rg_real)RG_MAX_COORD && p.x > 0 && v.x == 0 && v.y == 0);
    /* its neighbour in the block fell on, unstopped */
    rg_vec2 vn;
    assert_ok(rg_body_get_velocity(beside.w, next, &vn));
    assert_true(vn.x == 0 && vn.y < 0);
    rg_world_destroy(alone.w);
    rg_world_destroy(beside.w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shapeless_bodies_change_no_bit_of_a_pile),
        cmocka_unit_test(test_shapeless_bodies_change_no_bit_of_a_pile_with_workers),
        cmocka_unit_test(test_the_guard_stops_one_body_in_a_block_of_the_crowd),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
