/* Online planning (online.h): a camera reveals a row as the vehicle advances; every
 * reachable fruit ends at exactly one committed stop (the checker says so), and each kind
 * of bad detection is refused with its reason, counted, and never picked. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/online.h"
#include "hv/plan_build.h"
#include "hv/plan_check.h"
#include "hv/plan_eval.h"
#include "tiny_tables.h"

static tt_fixture_t g_fx;

static int setup(void **state)
{
    (void)state;
    static tt_band_t band = {0.25, 2000, 20, 15};
    return tt_fixture_init(&g_fx, tt_band_cost, &band);
}

static int teardown(void **state)
{
    (void)state;
    tt_fixture_free(&g_fx);
    return 0;
}

static hv_instance_params_t row_params(double length)
{
    hv_instance_params_t pr = {0.0, length, 0.01, 5.0, length / 0.1, 0.0};
    return pr;
}

static hv_online_options_t fast_options(void)
{
    hv_online_options_t opt;
    hv_online_options_default(&opt);
    opt.milp.time_limit_s = 3.0;
    opt.milp.rel_gap = 0.01;
    return opt;
}

/* n fruits over [0, length] in y order (as a camera meets them), both sides. */
static hv_fruit_t *row_fruits(size_t n, double length, unsigned seed)
{
    hv_fruit_t *fr = calloc(n, sizeof *fr);
    for (size_t i = 0; i < n; ++i) {
        seed = seed * 1664525u + 1013904223u;
        char id[24];
        snprintf(id, sizeof id, "f%zu", i);
        fr[i] = tt_fruit(id, (seed >> 3) & 1 ? HV_SIDE_RIGHT : HV_SIDE_LEFT,
                         length * ((double)i + 0.5) / (double)n,
                         0.40 + 0.01 * (double)((seed >> 12) % 40));
    }
    return fr;
}

/* The camera sees [v + lead, v + lead + window]: reveal what came into view, plan what can
 * be planned, move the vehicle to the commit line; until the row is planned. */
static void camera_run(hv_online_t *o, const hv_fruit_t *fr, size_t n, double lead, double window,
                       size_t *next)
{
    double v = hv_online_commit_y(o);
    for (int guard = 0; !o->done; ++guard) {
        assert_true(guard < 1000);
        double seen = v + lead + window;
        while (*next < n && fr[*next].y_m <= seen) {
            hv_online_verdict_t verdict;
            assert_int_equal(hv_online_detect(o, &fr[(*next)++], &verdict), HV_OK);
            assert_true(verdict == HV_DET_ACCEPTED || verdict == HV_DET_UNREACHABLE);
        }
        hv_online_seen(o, seen);
        int stepped = 0;
        while (hv_online_ready(o)) {
            hv_online_step_result_t r;
            assert_int_equal(hv_online_step(o, &r), HV_OK);
            stepped = 1;
        }
        double c = hv_online_commit_y(o);
        assert_true(stepped || c > v || o->done); /* the camera's lead keeps it moving */
        v = c;
    }
}

/* The committed plan, built and checked against the accepted fruits. */
static void check_plan(const hv_online_t *o, const hv_instance_params_t *pr)
{
    hv_instance_t inst;
    hv_diag_t d;
    assert_int_equal(hv_instance_build(pr, o->fruits, o->n_fruits, &g_fx.model, &inst, &d), HV_OK);
    hv_assignment_t a;
    assert_int_equal(hv_assignment_alloc(&a, o->n_fruits), HV_OK);
    assert_int_equal(hv_online_assignment(o, &a), HV_OK);
    double t;
    assert_int_equal(hv_assignment_makespan(&inst, &a, &t), HV_OK); /* each exactly once */
    hv_plan_meta_t m;
    memset(&m, 0, sizeof m);
    m.method = "milp";
    m.params = *pr;
    m.vehicle_speed_mps = g_fx.cfg.vehicle_speed_mps;
    m.solver_status = "feasible";
    m.gap = -1;
    hv_plan_t plan;
    assert_int_equal(hv_plan_build(&inst, &a, NULL, &m, &plan), HV_OK);
    char err[256] = "";
    hv_status_t st =
        hv_plan_check(&plan, &g_fx.cfg, o->fruits, o->n_fruits, &g_fx.model, err, sizeof err);
    if (st != HV_OK) {
        print_error("%s\n", err);
    }
    assert_int_equal(st, HV_OK);
    /* the committed stops list each planned fruit once, in driving order */
    size_t listed = 0;
    for (size_t s = 0; s < o->n_stops; ++s) {
        if (s > 0) {
            assert_true(o->stops[s].index > o->stops[s - 1].index);
        }
        for (size_t k = 0; k < o->stops[s].count; ++k) {
            assert_int_equal(o->fruit_stop[o->fruit_of[o->stops[s].first + k]], o->stops[s].index);
        }
        listed += o->stops[s].count;
    }
    assert_int_equal(listed, plan.fruits_planned);
    hv_plan_free(&plan);
    hv_assignment_free(&a);
    hv_instance_free(&inst);
}

static void test_camera_row_every_fruit_once(void **state)
{
    (void)state;
    const size_t n = 60;
    const double length = 6.0;
    hv_fruit_t *fr = row_fruits(n, length, 3);
    fr[n / 3].x_m = fr[n / 3].side == HV_SIDE_LEFT ? -0.9 : 0.9; /* off every table */
    hv_instance_params_t pr = row_params(length);
    hv_online_options_t opt = fast_options();
    hv_online_t o;
    assert_int_equal(hv_online_init(&o, &pr, &g_fx.model, &opt), HV_OK);
    size_t next = 0;
    camera_run(&o, fr, n, 0.5, 2.0, &next);
    assert_int_equal(next, n);
    assert_int_equal(o.counts[HV_DET_ACCEPTED], n - 1);
    assert_int_equal(o.counts[HV_DET_UNREACHABLE], 1);
    assert_int_equal(o.fruit_stop[n / 3], HV_NO_STOP);
    assert_true(o.steps >= 5); /* 6 m in 1 m commits */
    check_plan(&o, &pr);
    hv_online_free(&o);
    free(fr);
}

static void test_waits_for_the_camera(void **state)
{
    (void)state;
    hv_instance_params_t pr = row_params(4.0);
    hv_online_options_t opt = fast_options();
    hv_online_t o;
    opt.commit_m = 3.0; /* more than the window */
    opt.window_m = 2.0;
    assert_int_equal(hv_online_init(&o, &pr, &g_fx.model, &opt), HV_ERR_ARG);
    opt = fast_options();
    assert_int_equal(hv_online_init(&o, &pr, &g_fx.model, &opt), HV_OK);
    /* a stop is committed only when all it reaches (0.8 m ahead here) has been seen */
    hv_online_seen(&o, 1.7);
    assert_false(hv_online_ready(&o));
    hv_online_step_result_t r;
    assert_int_equal(hv_online_step(&o, &r), HV_OK);
    assert_int_equal(r.stops_to, r.stops_from);
    assert_float_equal(hv_online_commit_y(&o), 0.0, 1e-12);
    hv_online_seen(&o, 1.9);
    assert_true(hv_online_ready(&o));
    assert_int_equal(hv_online_step(&o, &r), HV_OK); /* no fruit: the stops are passed */
    assert_int_equal(r.stops_to, 0);
    assert_float_equal(hv_online_commit_y(&o), 0.99, 1e-9);
    hv_online_seen(&o, 1.0); /* going back changes nothing */
    assert_float_equal(o.seen_to_m, 1.9, 0);
    hv_online_free(&o);
}

static void test_bad_detections(void **state)
{
    (void)state;
    const size_t n = 40;
    const double length = 4.0;
    hv_fruit_t *fr = row_fruits(n, length, 11);
    hv_instance_params_t pr = row_params(length);
    hv_online_options_t opt = fast_options();
    hv_online_t o;
    assert_int_equal(hv_online_init(&o, &pr, &g_fx.model, &opt), HV_OK);
    hv_online_verdict_t v;
    /* outside the row: before its start, past its end, not a number */
    hv_fruit_t bad = tt_fruit("out1", HV_SIDE_LEFT, -0.2, 0.5);
    assert_int_equal(hv_online_detect(&o, &bad, &v), HV_OK);
    assert_int_equal(v, HV_DET_OUTSIDE_ROW);
    bad = tt_fruit("out2", HV_SIDE_RIGHT, length + 0.05, 0.5);
    assert_int_equal(hv_online_detect(&o, &bad, &v), HV_OK);
    assert_int_equal(v, HV_DET_OUTSIDE_ROW);
    bad = tt_fruit("out3", HV_SIDE_RIGHT, NAN, 0.5);
    assert_int_equal(hv_online_detect(&o, &bad, &v), HV_OK);
    assert_int_equal(v, HV_DET_OUTSIDE_ROW);
    /* the first fruit seen twice, the second time elsewhere: the first detection stands */
    assert_int_equal(hv_online_detect(&o, &fr[0], &v), HV_OK);
    assert_int_equal(v, HV_DET_ACCEPTED);
    hv_fruit_t again = fr[0];
    again.y_m += 0.3;
    assert_int_equal(hv_online_detect(&o, &again, &v), HV_OK);
    assert_int_equal(v, HV_DET_DUPLICATE);
    /* a replay says the first detection again, exactly: known; the duplicate is not */
    assert_true(hv_online_known(&o, &fr[0]));
    assert_false(hv_online_known(&o, &again));
    again = fr[0];
    again.side = again.side == HV_SIDE_LEFT ? HV_SIDE_RIGHT : HV_SIDE_LEFT;
    assert_false(hv_online_known(&o, &again));
    assert_false(hv_online_known(&o, &bad)); /* refused, so never known */
    assert_false(hv_online_known(&o, &fr[1]));
    size_t next = 1;
    /* plan the first metres, then a fruit near the start turns up: its stops are gone */
    while (o.pos < 150) {
        double seen = hv_online_commit_y(&o) + 2.5;
        while (next < n && fr[next].y_m <= seen) {
            assert_int_equal(hv_online_detect(&o, &fr[next++], &v), HV_OK);
        }
        hv_online_seen(&o, seen);
        hv_online_step_result_t r;
        assert_int_equal(hv_online_step(&o, &r), HV_OK);
    }
    hv_fruit_t late = tt_fruit("late1", HV_SIDE_LEFT, 0.05, 0.5);
    assert_int_equal(hv_online_detect(&o, &late, &v), HV_OK);
    assert_int_equal(v, HV_DET_LATE);
    /* and a duplicate of a fruit already committed */
    assert_int_equal(hv_online_detect(&o, &fr[1], &v), HV_OK);
    assert_int_equal(v, HV_DET_DUPLICATE);
    camera_run(&o, fr, n, 0.5, 2.0, &next);
    assert_int_equal(o.counts[HV_DET_OUTSIDE_ROW], 3);
    assert_int_equal(o.counts[HV_DET_DUPLICATE], 2);
    assert_int_equal(o.counts[HV_DET_LATE], 1);
    assert_int_equal(o.counts[HV_DET_ACCEPTED], n);
    assert_int_equal(o.n_fruits, n); /* none of the refused is planned */
    assert_float_equal(o.fruits[0].y_m, fr[0].y_m, 0);
    check_plan(&o, &pr);
    assert_string_equal(hv_online_verdict_name(HV_DET_LATE), "late");
    assert_string_equal(hv_online_verdict_name(HV_DET_OUTSIDE_ROW), "outside_row");
    assert_string_equal(hv_online_verdict_name(HV_DET_DUPLICATE), "duplicate");
    hv_online_free(&o);
    free(fr);
}

/* A horizon's limit is half the robot time committed ahead, within the floor and the cap;
 * the work ahead is the drives and the stops' work (slower arm plus tau) after a stop. */
static void test_limit_follows_work_ahead(void **state)
{
    (void)state;
    const size_t n = 30;
    const double length = 3.0;
    hv_fruit_t *fr = row_fruits(n, length, 5);
    hv_instance_params_t pr = row_params(length);
    hv_online_options_t opt = fast_options();
    opt.limit_min_s = 2.0;
    opt.limit_max_s = 50.0;
    hv_online_t o;
    assert_int_equal(hv_online_init(&o, &pr, &g_fx.model, &opt), HV_OK);
    assert_float_equal(hv_online_horizon_limit_s(&o, 0.0), 2.0, 1e-12);    /* the floor */
    assert_float_equal(hv_online_horizon_limit_s(&o, 30.0), 15.0, 1e-12);  /* half */
    assert_float_equal(hv_online_horizon_limit_s(&o, 500.0), 50.0, 1e-12); /* the cap */
    size_t next = 0;
    camera_run(&o, fr, n, 0.5, 2.0, &next);
    assert_true(o.n_stops >= 2);
    /* the work ahead of stop 0: the drive to each later stop and its work, summed */
    double want = 0.0, y = o.stops[0].y_m, speed = length / pr.travel_time_s;
    for (size_t k = 1; k < o.n_stops; ++k) {
        double c[2] = {0.0, 0.0};
        for (size_t i = 0; i < o.stops[k].count; ++i) {
            const hv_fruit_t *f = &o.fruits[o.fruit_of[o.stops[k].first + i]];
            double cost;
            hv_pick_why_t why;
            assert_int_equal(g_fx.model.cost(g_fx.model.ctx, f, o.stops[k].y_m, &cost, &why),
                             HV_OK);
            c[f->side == HV_SIDE_LEFT ? 0 : 1] += cost;
        }
        assert_float_equal(hv_online_stop_work_s(&o, k), fmax(c[0], c[1]) + pr.stop_penalty_s,
                           1e-9);
        want += (o.stops[k].y_m - y) / speed + fmax(c[0], c[1]) + pr.stop_penalty_s;
        y = o.stops[k].y_m;
    }
    assert_float_equal(hv_online_ahead_s(&o, 1, o.stops[0].y_m, speed), want, 1e-6);
    assert_float_equal(hv_online_ahead_s(&o, o.n_stops, 0.0, speed), 0.0, 0.0);
    hv_online_free(&o);
    /* a floor above the cap is refused */
    opt.limit_min_s = 60.0;
    assert_int_equal(hv_online_init(&o, &pr, &g_fx.model, &opt), HV_ERR_ARG);
    free(fr);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_camera_row_every_fruit_once),
        cmocka_unit_test(test_waits_for_the_camera),
        cmocka_unit_test(test_bad_detections),
        cmocka_unit_test(test_limit_follows_work_ahead),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
