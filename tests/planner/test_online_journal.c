/* The online planner's journal (online_journal.h) and hv_online_recommit: a row planned
 * half way with its journal, then replayed into a new planner, is where it was (the same
 * committed stops, fruits, view and commit line) and goes on to plan the rest; a horizon
 * whose records a crash cut short is dropped, a corrupt record or another course refused. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hv/cost_table.h" /* hv_crc32 */
#include "hv/online.h"
#include "hv/online_journal.h"
#include "hv/plan_status.h"
#include "tiny_tables.h"

static tt_fixture_t g_fx;
static char g_dir[64];

static int setup(void **state)
{
    (void)state;
    static tt_band_t band = {0.25, 2000, 20, 15};
    snprintf(g_dir, sizeof g_dir, "/tmp/hv_pj_XXXXXX");
    return mkdtemp(g_dir) == NULL ? -1 : tt_fixture_init(&g_fx, tt_band_cost, &band);
}

static int teardown(void **state)
{
    (void)state;
    tt_fixture_free(&g_fx);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_dir);
    return system(cmd) == 0 ? 0 : -1;
}

static const hv_instance_params_t k_row = {0.0, 5.0, 0.01, 5.0, 50.0, 0.0};

static void init(hv_online_t *o)
{
    hv_online_options_t opt;
    hv_online_options_default(&opt);
    opt.milp.time_limit_s = 3.0;
    opt.milp.rel_gap = 0.01;
    assert_int_equal(hv_online_init(o, &k_row, &g_fx.model, &opt), HV_OK);
}

/* A camera over the row up to `until` m of commit line, every input and commit journalled
 * as harvest-plan-online does; one fruit arrives twice (refused, journalled all the same). */
static void plan_until(hv_online_t *o, hv_online_journal_t *j, double until, size_t *next)
{
    const size_t n = 50;
    double v = hv_online_commit_y(o);
    while (!o->done && v < until) {
        double seen = v + 2.5;
        for (; *next < n && 5.0 * ((double)*next + 0.5) / (double)n <= seen; ++*next) {
            char id[16];
            snprintf(id, sizeof id, "f%zu", *next);
            hv_fruit_t f = tt_fruit(id, *next % 3 ? HV_SIDE_LEFT : HV_SIDE_RIGHT,
                                    5.0 * ((double)*next + 0.5) / (double)n,
                                    0.40 + 0.02 * (double)(*next % 7));
            hv_online_verdict_t verdict;
            for (int twice = 0; twice < (*next == 7 ? 2 : 1); ++twice) {
                assert_int_equal(hv_online_journal_detection(j, &f), HV_OK);
                assert_int_equal(hv_online_detect(o, &f, &verdict), HV_OK);
            }
        }
        assert_int_equal(hv_online_journal_seen(j, seen), HV_OK);
        hv_online_seen(o, seen);
        while (hv_online_ready(o)) {
            hv_online_step_result_t r;
            size_t pos = o->pos;
            assert_int_equal(hv_online_step(o, &r), HV_OK);
            if (o->pos != pos) {
                assert_int_equal(hv_online_journal_horizon(j, o, r.stops_from), HV_OK);
            }
        }
        v = hv_online_commit_y(o);
    }
}

static void assert_same(const hv_online_t *a, const hv_online_t *b)
{
    assert_int_equal(a->n_fruits, b->n_fruits);
    assert_int_equal(a->n_stops, b->n_stops);
    assert_int_equal(a->n_order, b->n_order);
    assert_int_equal(a->pos, b->pos);
    assert_int_equal(a->done, b->done);
    assert_true(a->seen_to_m == b->seen_to_m);
    assert_memory_equal(a->counts, b->counts, sizeof a->counts);
    for (size_t i = 0; i < a->n_fruits; ++i) {
        assert_string_equal(a->fruits[i].id, b->fruits[i].id);
        assert_true(a->fruits[i].y_m == b->fruits[i].y_m && a->fruits[i].z_m == b->fruits[i].z_m);
        assert_int_equal(a->fruit_stop[i], b->fruit_stop[i]);
    }
    for (size_t s = 0; s < a->n_stops; ++s) {
        assert_int_equal(a->stops[s].index, b->stops[s].index);
        assert_int_equal(a->stops[s].count, b->stops[s].count);
        assert_int_equal(a->stops[s].first, b->stops[s].first);
    }
    assert_memory_equal(a->fruit_of, b->fruit_of, a->n_order * sizeof *a->fruit_of);
}

static long size_of(const char *path)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fclose(f);
    return n;
}

static void append(const char *path, const char *text)
{
    FILE *f = fopen(path, "ab");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void append_record(const char *path, const char *text)
{
    char line[128];
    snprintf(line, sizeof line, "%s *%08x\n", text, (unsigned)hv_crc32(0, text, strlen(text)));
    append(path, line);
}

static void test_replay_restores_and_goes_on(void **state)
{
    (void)state;
    char path[128], err[256];
    snprintf(path, sizeof path, "%s/a.journal", g_dir);
    hv_online_t o, back;
    hv_online_journal_t j;
    size_t next = 0;
    init(&o);
    assert_int_equal(hv_online_journal_open(&j, path, &o, err, sizeof err), HV_OK);
    plan_until(&o, &j, 2.0, &next);
    hv_online_journal_close(&j);
    assert_true(o.n_stops > 0 && !o.done);
    assert_int_equal(o.counts[HV_DET_DUPLICATE], 1);

    /* a restart: the same planner state, without a solve */
    init(&back);
    assert_int_equal(hv_online_journal_open(&j, path, &back, err, sizeof err), HV_OK);
    assert_int_equal(j.torn_bytes, 0);
    assert_true(j.horizons > 0 && j.detections == next + 1);
    assert_int_equal(back.steps, 0);
    assert_same(&o, &back);
    /* and both go on alike to the end of the row */
    size_t next_back = next;
    plan_until(&back, &j, 99.0, &next_back);
    hv_online_journal_close(&j);
    assert_true(back.done);
    hv_online_free(&o);
    hv_online_free(&back);
}

static void test_torn_and_refused(void **state)
{
    (void)state;
    char path[128], err[256];
    snprintf(path, sizeof path, "%s/c.journal", g_dir);
    hv_online_t o, back;
    hv_online_journal_t j;
    size_t next = 0;
    init(&o);
    assert_int_equal(hv_online_journal_open(&j, path, &o, err, sizeof err), HV_OK);
    plan_until(&o, &j, 1.0, &next);
    hv_online_journal_close(&j);
    long whole = size_of(path);
    /* a horizon whose H record never made it, then a torn line: both cut off */
    append_record(path, "F 30 120");
    append(path, "F 31 12");
    init(&back);
    assert_int_equal(hv_online_journal_open(&j, path, &back, err, sizeof err), HV_OK);
    assert_int_equal(size_of(path), whole);
    assert_true(j.torn_bytes > 0);
    assert_same(&o, &back);
    hv_online_journal_close(&j);
    hv_online_free(&back);
    /* a horizon that could not have been committed (a stop behind the commit line) */
    append_record(path, "F 0 0");
    append_record(path, "H 400 n=1");
    init(&back);
    assert_int_equal(hv_online_journal_open(&j, path, &back, err, sizeof err), HV_ERR_ARG);
    assert_non_null(strstr(err, "cannot be what was committed"));
    hv_online_free(&back);
    assert_int_equal(truncate(path, whole), 0);
    /* a corrupt record: refused, the line named */
    append(path, "V 3.5 *00000000\n");
    init(&back);
    assert_int_equal(hv_online_journal_open(&j, path, &back, err, sizeof err), HV_ERR_PLAN_FORMAT);
    assert_non_null(strstr(err, "checksum mismatch"));
    hv_online_free(&back);
    /* another course */
    assert_int_equal(truncate(path, whole), 0);
    hv_online_options_t opt;
    hv_online_options_default(&opt);
    hv_instance_params_t longer = k_row;
    longer.row_length_m = 6.0;
    assert_int_equal(hv_online_init(&back, &longer, &g_fx.model, &opt), HV_OK);
    assert_int_equal(hv_online_journal_open(&j, path, &back, err, sizeof err), HV_ERR_PLAN_FORMAT);
    assert_non_null(strstr(err, "line 1: the journal of another course"));
    hv_online_free(&back);
    hv_online_free(&o);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_replay_restores_and_goes_on),
        cmocka_unit_test(test_torn_and_refused),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
