/* test_bands.c: phases run over bands at once (src/bands.c) keep the order one thread gives,
 * and the solver's colours run that way give the one-thread bits.
 *   - bands_run's promises, under the shuffler (ranges in random order on one thread, so that
 *     a band that ran ahead of its turn would show) and under rg_thread_pool: every phase of
 *     every band runs once, its edge rows before its inner rows, in phase order, and a band's
 *     edge rows of phase s only after every other band's edge rows of phase s - 1;
 *   - a model of the solver's rows: cells updated by an operation that does not commute,
 *     each phase's cells split among the bands, the cells two bands share updated only in
 *     edge rows, ends in the cells one thread leaves, for 2 to 8 bands;
 *   - a pile large enough that the solve runs in bands (the world's count of banded solves
 *     says so: all but the first steps, while the pile holds few contacts) gives the hashes
 *     of the one-thread step at 2, 3 and 4 workers, under the shuffler and the pool, in float
 *     and in double (make test REAL=double). */
#include "testutil.h"
#include "shuffler.h"

#include "bands.h"
#include "state.h"

/* ---------------------------------------------------------------- bands_run's order */

enum { MAX_PHASES = 64 };

typedef struct order_check {
    int32_t bands, phases;
    int32_t next[BANDS_MAX];    /* per band: the next phase it may run, 2 * phase + (inner) */
    int32_t edge[BANDS_MAX];    /* atomic: phases whose edge rows have run */
    int32_t calls, bad;         /* atomic */
} order_check;

static void order_fn(int32_t band, int32_t phase, int edge, void *context)
{
    order_check *c = context;
    __atomic_fetch_add(&c->calls, 1, __ATOMIC_RELAXED);
    int ok = band >= 0 && band < c->bands && phase >= 0 && phase < c->phases;
    /* the band's own order: edge then inner rows, phase after phase (only its holder runs it) */
    if (ok && c->next[band] != 2 * phase + !edge) ok = 0;
    if (ok && edge)
        for (int32_t u = 0; u < c->bands; u++)
            if (u != band && __atomic_load_n(&c->edge[u], __ATOMIC_ACQUIRE) < phase) ok = 0;
    if (!ok) {
        __atomic_fetch_add(&c->bad, 1, __ATOMIC_RELAXED);
        return;
    }
    c->next[band]++;
    if (edge) __atomic_store_n(&c->edge[band], phase + 1, __ATOMIC_RELEASE);
}

static void check_order(rg_world *w, int32_t bands, int32_t phases)
{
    order_check c;
    memset(&c, 0, sizeof c);
    c.bands = bands;
    c.phases = phases;
    bands_run(w, bands, phases, order_fn, &c);
    assert_int_equal(c.bad, 0);
    assert_int_equal(c.calls, 2 * bands * phases);
    for (int32_t b = 0; b < bands; b++) assert_int_equal(c.next[b], 2 * phases);
}

static void test_bands_keep_the_order_of_one_thread(void **state)
{
    (void)state;
    rg_world *w;
    assert_ok(rg_world_create(&w));
    /* no task system: one thread runs every band in turn */
    for (int32_t bands = 1; bands <= BANDS_MAX; bands++) check_order(w, bands, 17);
    for (int eager = 0; eager <= 1; eager++)
        for (int32_t workers = 1; workers <= 4; workers++) {
            shuffler sh;
            rg_task_system ts;
            shuffler_init(&sh, 0xB5AD4ECEDA1CE2A9ull + (uint64_t)workers, workers, eager);
            shuffler_tasks(&sh, &ts);
            assert_ok(rg_world_set_task_system(w, &ts));
            for (int rep = 0; rep < 20; rep++)
                for (int32_t bands = 1; bands <= BANDS_MAX; bands++) check_order(w, bands, 1 + rep % 9);
            assert_int_equal(sh.misuse, 0);
        }
    for (int32_t threads = 2; threads <= 4; threads++) {
        rg_thread_pool *tp;
        rg_task_system ts;
        assert_ok(rg_thread_pool_create(threads, &tp));
        assert_ok(rg_thread_pool_task_system(tp, &ts));
        assert_ok(rg_world_set_task_system(w, &ts));
        for (int rep = 0; rep < 300; rep++) check_order(w, 1 + rep % BANDS_MAX, MAX_PHASES);
        assert_ok(rg_world_set_task_system(w, NULL));
        rg_thread_pool_destroy(tp);
    }
    rg_world_destroy(w);
}

/* ---------------------------------------------------------------- a model of the rows */

/* CELLS cells (bodies); each phase (colour) holds rows that update two cells each, no cell
 * twice in a phase, by c = c * 31 + (phase * 1000003 + row): the order of a cell's updates
 * shows in its value.  Rows are cut into bands by position, as resolve.c cuts a colour; a row
 * is an edge row when a cell of it is met by another band's rows in any phase. */
enum { CELLS = 4096, ROWS = 1024, MODEL_PHASES = 24 };

typedef struct model {
    int32_t a[MODEL_PHASES][ROWS], b[MODEL_PHASES][ROWS];
    uint8_t edge[MODEL_PHASES][ROWS];
    uint64_t cell[CELLS];
    int32_t bands;
} model;

static void model_rows(model *m, int32_t s, int32_t r0, int32_t r1, int edge)
{
    for (int32_t r = r0; r < r1; r++) {
        if (m->edge[s][r] != edge) continue;
        uint64_t tag = (uint64_t)s * 1000003u + (uint64_t)r;
        m->cell[m->a[s][r]] = m->cell[m->a[s][r]] * 31u + tag;
        m->cell[m->b[s][r]] = m->cell[m->b[s][r]] * 31u + tag;
    }
}

static void model_fn(int32_t band, int32_t phase, int edge, void *context)
{
    model *m = context;
    model_rows(m, phase, ROWS * band / m->bands, ROWS * (band + 1) / m->bands, edge);
}

/* Rows mostly local (cells near the row's place, as bodies near a contact), some far. */
static void model_build(model *m, uint64_t seed, int32_t bands)
{
    static uint8_t used[CELLS];
    static int16_t owner[CELLS];
    m->bands = bands;
    for (int32_t s = 0; s < MODEL_PHASES; s++) {
        memset(used, 0, sizeof used);
        for (int32_t r = 0; r < ROWS; r++) {
            int32_t pick[2];
            for (int e = 0; e < 2; e++) {
                do {
                    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
                    uint32_t x = (uint32_t)(seed >> 33);
                    pick[e] = x % 16 == 0 ? (int32_t)(x % CELLS) : (r * 4 + (int32_t)(x % 24) + CELLS - 12) % CELLS;
                } while (used[pick[e]]);
                used[pick[e]] = 1;
            }
            m->a[s][r] = pick[0];
            m->b[s][r] = pick[1];
        }
    }
    /* the cells each band meets; -2: two bands */
    for (int32_t c = 0; c < CELLS; c++) owner[c] = -1;
    for (int32_t s = 0; s < MODEL_PHASES; s++)
        for (int16_t band = 0; band < bands; band++)
            for (int32_t r = ROWS * band / bands; r < ROWS * (band + 1) / bands; r++) {
                int32_t two[2] = { m->a[s][r], m->b[s][r] };
                for (int e = 0; e < 2; e++)
                    owner[two[e]] = owner[two[e]] == -1 || owner[two[e]] == band ? band : -2;
            }
    for (int32_t s = 0; s < MODEL_PHASES; s++)
        for (int32_t r = 0; r < ROWS; r++) m->edge[s][r] = owner[m->a[s][r]] == -2 || owner[m->b[s][r]] == -2;
    for (int32_t c = 0; c < CELLS; c++) m->cell[c] = (uint64_t)c;
}

static void test_rows_in_bands_leave_the_cells_of_one_thread(void **state)
{
    (void)state;
    static model want, got;
    rg_world *w;
    assert_ok(rg_world_create(&w));
    for (int32_t bands = 2; bands <= BANDS_MAX; bands++) {
        uint64_t seed = 0x2545F4914F6CDD1Dull * (uint64_t)bands;
        model_build(&want, seed, bands);
        for (int32_t s = 0; s < MODEL_PHASES; s++) model_rows(&want, s, 0, ROWS, 0), model_rows(&want, s, 0, ROWS, 1);
        /* the serial order above is edge-blind: within a phase rows share no cell, so the
         * split of a phase into edge and inner rows changes nothing */
        int32_t edges = 0;
        model_build(&got, seed, bands);
        for (int32_t s = 0; s < MODEL_PHASES; s++)
            for (int32_t r = 0; r < ROWS; r++) edges += got.edge[s][r];
        assert_true(edges > 0 && edges < MODEL_PHASES * ROWS / 2); /* both kinds occur */
        for (int32_t threads = 1; threads <= 4; threads++) {
            shuffler sh;
            rg_thread_pool *tp = NULL;
            rg_task_system ts;
            if (threads == 1) { /* the shuffler stands for one thread taking the bands in any order */
                shuffler_init(&sh, seed ^ 0x9E3779B97F4A7C15ull, 4, 0);
                shuffler_tasks(&sh, &ts);
            } else {
                assert_ok(rg_thread_pool_create(threads, &tp));
                assert_ok(rg_thread_pool_task_system(tp, &ts));
            }
            assert_ok(rg_world_set_task_system(w, &ts));
            for (int rep = 0; rep < 10; rep++) {
                model_build(&got, seed, bands);
                bands_run(w, bands, MODEL_PHASES, model_fn, &got);
                assert_memory_equal(got.cell, want.cell, sizeof want.cell);
            }
            assert_ok(rg_world_set_task_system(w, NULL));
            if (tp != NULL) rg_thread_pool_destroy(tp);
        }
    }
    rg_world_destroy(w);
}

/* ---------------------------------------------------------------- the solve in bands */

/* 4000 unit boxes and circles in a container, 150 steps; the hash of the state every 30 steps
 * and how many solves ran in bands. */
static uint64_t pile_hash(const rg_task_system *tasks, int64_t *banded)
{
    rg_world *w;
    rg_body b;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_task_system(w, tasks));
    assert_ok(rg_world_set_gravity(w, v2(0, -10)));
    assert_ok(rg_world_set_sleeping(w, 0));
    assert_ok(rg_body_create(w, RG_BODY_STATIC, 0, v2(0, -0.5), &b));
    assert_ok(rg_body_set_aabb(w, b, 36, 0.5));
    for (int side = -1; side <= 1; side += 2) {
        assert_ok(rg_body_create(w, RG_BODY_STATIC, 0, v2(side * 36.5, 60), &b));
        assert_ok(rg_body_set_aabb(w, b, 0.5, 60));
    }
    for (int i = 0; i < 4000; i++) {
        double x = -34.65 + 1.1 * (i % 64) + 0.013 * (i % 5), y = 1 + 1.1 * (i / 64);
        assert_ok(rg_body_create(w, RG_BODY_DYNAMIC, 1, v2(x, y), &b));
        if (i % 2)
            assert_ok(rg_body_set_aabb(w, b, 0.5, 0.5));
        else
            assert_ok(rg_body_set_circle(w, b, 0.5));
    }
    uint64_t h = 1469598103934665603ull;
    for (int k = 1; k <= 150; k++) {
        assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
        if (k % 30 == 0) {
            uint64_t whole;
            assert_ok(rg_world_hash(w, &whole));
            h = fnv(h, &whole, 1, sizeof whole);
        }
    }
    *banded = w->coll.resolve.banded;
    rg_world_destroy(w);
    return h;
}

static void test_a_pile_solved_in_bands_gives_the_bits_of_one_thread(void **state)
{
    (void)state;
    int64_t banded;
    uint64_t one = pile_hash(NULL, &banded);
    assert_int_equal(banded, 0);
    for (int32_t workers = 2; workers <= 4; workers++) {
        shuffler sh;
        rg_task_system ts;
        shuffler_init(&sh, 0xD6E8FEB86659FD93ull * (uint64_t)workers, workers, workers == 3);
        shuffler_tasks(&sh, &ts);
        assert_int_equal(pile_hash(&ts, &banded), one);
        printf("  shuffler, %d workers: %lld of 150 solves in bands\n", (int)workers, (long long)banded);
        assert_true(banded > 0);
        assert_int_equal(sh.misuse, 0);
        rg_thread_pool *tp;
        assert_ok(rg_thread_pool_create(workers, &tp));
        assert_ok(rg_thread_pool_task_system(tp, &ts));
        assert_int_equal(pile_hash(&ts, &banded), one);
        printf("  thread pool, %d threads: %lld of 150 solves in bands\n", (int)workers, (long long)banded);
        assert_true(banded > 0);
        rg_thread_pool_destroy(tp);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bands_keep_the_order_of_one_thread),
        cmocka_unit_test(test_rows_in_bands_leave_the_cells_of_one_thread),
        cmocka_unit_test(test_a_pile_solved_in_bands_gives_the_bits_of_one_thread),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
