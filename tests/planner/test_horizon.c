/* Receding horizon: a long synthetic row keeps every fruit exactly once (the checker says
 * so), and on a row the MILP solves whole it is never better than that optimum. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/horizon.h"
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

/* n fruits spread over [0, length], both sides, plus one unreachable (x off the grid). */
static hv_fruit_t *row_fruits(size_t n, double length, unsigned seed)
{
    hv_fruit_t *fr = calloc(n, sizeof *fr);
    for (size_t i = 0; i < n; ++i) {
        seed = seed * 1664525u + 1013904223u;
        double y = length * (double)(seed >> 8) / 16777216.0;
        char id[24];
        snprintf(id, sizeof id, "f%zu", i);
        fr[i] = tt_fruit(id, (seed >> 3) & 1 ? HV_SIDE_RIGHT : HV_SIDE_LEFT, y,
                         0.40 + 0.01 * (double)((seed >> 12) % 40));
    }
    fr[n / 2].x_m = fr[n / 2].side == HV_SIDE_LEFT ? -0.9 : 0.9;
    return fr;
}

static hv_plan_t plan_of(const hv_instance_t *inst, const hv_assignment_t *a,
                         const hv_instance_params_t *pr)
{
    hv_plan_meta_t m;
    memset(&m, 0, sizeof m);
    m.method = "milp";
    m.params = *pr;
    m.vehicle_speed_mps = g_fx.cfg.vehicle_speed_mps;
    m.solver_status = "heuristic";
    m.gap = -1;
    hv_plan_t plan;
    assert_int_equal(hv_plan_build(inst, a, NULL, &m, &plan), HV_OK);
    return plan;
}

static void test_long_row_every_fruit_once(void **state)
{
    (void)state;
    const size_t n = 150;
    const double length = 12.0;
    hv_fruit_t *fr = row_fruits(n, length, 7);
    hv_instance_params_t pr = {0.0, length, 0.01, 5.0, length / 0.1, 0.0};
    hv_instance_t inst;
    hv_diag_t d;
    assert_int_equal(hv_instance_build(&pr, fr, n, &g_fx.model, &inst, &d), HV_OK);
    hv_horizon_options_t ho;
    hv_horizon_options_default(&ho);
    ho.window_m = 2.0;
    ho.commit_m = 1.0;
    ho.milp.time_limit_s = 3.0;
    ho.milp.rel_gap = 0.01;
    ho.progress = stderr;
    hv_assignment_t a;
    assert_int_equal(hv_assignment_alloc(&a, n), HV_OK);
    hv_horizon_result_t hr;
    assert_int_equal(hv_horizon_solve(&inst, &ho, &a, &hr), HV_OK);
    assert_true(hr.windows >= 11); /* 12 m in 1 m commits */
    /* each reachable fruit at exactly one stop that reaches it, the unreachable one at none */
    for (size_t f = 0; f < n; ++f) {
        double c;
        if (f == n / 2) {
            assert_int_equal(a.fruit_stop[f], HV_NO_STOP);
        } else {
            assert_int_equal(hv_instance_pair_cost(&inst, (uint32_t)f, a.fruit_stop[f], &c), HV_OK);
        }
    }
    hv_plan_t plan = plan_of(&inst, &a, &pr);
    char err[256] = "";
    hv_status_t st = hv_plan_check(&plan, &g_fx.cfg, fr, n, &g_fx.model, err, sizeof err);
    if (st != HV_OK) {
        print_error("%s\n", err);
    }
    assert_int_equal(st, HV_OK);
    assert_int_equal(plan.fruits_planned, n - 1);
    assert_int_equal(plan.fruits_unreachable, 1);
    hv_plan_free(&plan);
    hv_assignment_free(&a);
    hv_instance_free(&inst);
    free(fr);
}

static void test_horizon_vs_single_window(void **state)
{
    (void)state;
    const size_t n = 16;
    hv_fruit_t *fr = row_fruits(n, 2.0, 99);
    hv_instance_params_t pr = {0.0, 2.0, 0.01, 5.0, 20.0, 0.0};
    hv_instance_t inst;
    hv_diag_t d;
    assert_int_equal(hv_instance_build(&pr, fr, n, &g_fx.model, &inst, &d), HV_OK);
    hv_milp_options_t mo;
    hv_milp_options_default(&mo);
    mo.time_limit_s = 30.0;
    hv_assignment_t whole, hz;
    assert_int_equal(hv_assignment_alloc(&whole, n), HV_OK);
    assert_int_equal(hv_assignment_alloc(&hz, n), HV_OK);
    hv_milp_result_t r;
    assert_int_equal(hv_milp_solve(&inst, &mo, NULL, &whole, &r), HV_OK);
    hv_horizon_options_t ho;
    hv_horizon_options_default(&ho);
    ho.window_m = 1.0;
    ho.commit_m = 0.5;
    ho.milp = mo;
    hv_horizon_result_t hr;
    assert_int_equal(hv_horizon_solve(&inst, &ho, &hz, &hr), HV_OK);
    double t_whole, t_hz;
    assert_int_equal(hv_assignment_makespan(&inst, &whole, &t_whole), HV_OK);
    assert_int_equal(hv_assignment_makespan(&inst, &hz, &t_hz), HV_OK);
    fprintf(stderr, "horizon 1 m / commit 0.5 m: %.3f s; whole row (%s): %.3f s (+%.2f %%)\n", t_hz,
            r.status == HV_SOLVE_OPTIMAL ? "optimal" : "not proven", t_whole,
            100.0 * (t_hz - t_whole) / t_whole);
    if (r.status == HV_SOLVE_OPTIMAL) {
        assert_true(t_hz >= t_whole - 1e-6 - r.gap * t_whole);
    }
    /* a window covering the whole row commits everything in one solve */
    ho.window_m = 2.0;
    ho.commit_m = 2.0;
    assert_int_equal(hv_horizon_solve(&inst, &ho, &hz, &hr), HV_OK);
    assert_int_equal(hr.windows, 1);
    assert_int_equal(hv_assignment_makespan(&inst, &hz, &t_hz), HV_OK);
    if (r.status == HV_SOLVE_OPTIMAL && hr.windows_optimal == 1) {
        assert_true(fabs(t_hz - t_whole) <= 1e-6 + r.gap * t_whole);
    }
    ho.commit_m = 3.0; /* commit beyond the window */
    assert_int_equal(hv_horizon_solve(&inst, &ho, &hz, &hr), HV_ERR_ARG);
    hv_assignment_free(&whole);
    hv_assignment_free(&hz);
    hv_instance_free(&inst);
    free(fr);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_long_row_every_fruit_once),
        cmocka_unit_test(test_horizon_vs_single_window),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
