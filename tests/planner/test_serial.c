/* Serial baseline: each side's optimum, checked against brute force over all stop subsets. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hv/baselines.h"
#include "hv/plan_build.h"
#include "hv/plan_check.h"
#include "hv/plan_eval.h"
#include "tiny_tables.h"

/* Steep costs so that tau (5 s) trades against distance: 1 s + 0.8 s per cm, +-3 cm. */
static uint16_t steep(hv_side_t side, double y_rel, uint32_t ix, uint32_t iz, uint32_t iw,
                      void *ctx)
{
    (void)ix;
    (void)iw;
    (void)ctx;
    double cm = fabs(y_rel) * 100.0;
    if (cm > 3.0 + 1e-6) {
        return HV_COST_UNREACHABLE;
    }
    return (uint16_t)(1000 + 800 * lround(cm) + 7 * iz + (side == HV_SIDE_LEFT ? 3 : 0));
}

/* min over stop subsets S of sum_f min_{p in S} G(f, p) + tau |S|, for one side. */
static double brute_side(const hv_instance_t *inst, hv_side_t side)
{
    double best = INFINITY;
    size_t ns = inst->n_stops;
    for (unsigned mask = 1; mask < (1u << ns); ++mask) {
        double total = 0.0;
        int any = 0, ok = 1;
        unsigned used = 0;
        for (size_t f = 0; f < inst->n_fruits && ok; ++f) {
            if (inst->fruits[f].side != side || inst->fruit_begin[f] == inst->fruit_begin[f + 1]) {
                continue;
            }
            any = 1;
            double c = INFINITY;
            uint32_t at = 0;
            for (size_t k = inst->fruit_begin[f]; k < inst->fruit_begin[f + 1]; ++k) {
                if ((mask >> inst->pairs[k].stop) & 1u && inst->pairs[k].cost_s < c) {
                    c = inst->pairs[k].cost_s;
                    at = inst->pairs[k].stop;
                }
            }
            if (!isfinite(c)) {
                ok = 0;
            }
            total += c;
            used |= 1u << at;
        }
        if (!ok) {
            continue;
        }
        if (!any) {
            return inst->travel_time_s;
        }
        /* only stops that pick something pay tau: a subset with an idle stop is dominated
         * by the same subset without it, which is enumerated too */
        total += inst->stop_penalty_s * (double)__builtin_popcount(used);
        if (total < best) {
            best = total;
        }
    }
    return best + inst->travel_time_s;
}

static void test_serial_matches_brute_force(void **state)
{
    (void)state;
    tt_fixture_t fx;
    assert_int_equal(tt_fixture_init(&fx, steep, NULL), 0);
    unsigned seed = 12345;
    for (int trial = 0; trial < 6; ++trial) {
        hv_fruit_t fr[9];
        size_t n = 0;
        for (int s = 0; s < 2; ++s) {
            int m = 2 + (trial + s) % 3;
            for (int i = 0; i < m; ++i) {
                seed = seed * 1103515245u + 12345u;
                double y = 0.01 * (double)((seed >> 16) % 10); /* 0 .. 0.09 */
                char id[8];
                id[0] = s ? 'r' : 'l';
                id[1] = (char)('0' + i);
                id[2] = '\0';
                fr[n++] = tt_fruit(id, (hv_side_t)s, y, 0.40 + 0.01 * (double)((seed >> 8) % 30));
            }
        }
        hv_instance_params_t pr = {0.0, 0.09, 0.01, 5.0, 0.9, 0.0};
        hv_instance_t inst;
        hv_diag_t d;
        assert_int_equal(hv_instance_build(&pr, fr, n, &fx.model, &inst, &d), HV_OK);
        assert_int_equal(inst.n_stops, 10);
        hv_milp_options_t opt;
        hv_milp_options_default(&opt);
        opt.time_limit_s = 30;
        hv_assignment_t a;
        assert_int_equal(hv_assignment_alloc(&a, n), HV_OK);
        unsigned char passes[9];
        hv_serial_result_t res;
        assert_int_equal(hv_serial_solve(&inst, &opt, &a, passes, &res), HV_OK);
        assert_true(res.optimal);
        double want = brute_side(&inst, HV_SIDE_LEFT) + brute_side(&inst, HV_SIDE_RIGHT);
        if (fabs(res.makespan_s - want) > 1e-6) {
            print_error("trial %d: serial %.6f, brute force %.6f\n", trial, res.makespan_s, want);
            fail();
        }
        /* the plan: passes by side, T_travel twice, and the checker agrees */
        hv_plan_meta_t m;
        memset(&m, 0, sizeof m);
        m.method = "serial";
        m.params = pr;
        m.vehicle_speed_mps = fx.cfg.vehicle_speed_mps;
        m.solver_status = "optimal";
        hv_plan_t plan;
        assert_int_equal(hv_plan_build(&inst, &a, passes, &m, &plan), HV_OK);
        assert_true(fabs(plan.makespan_s - want) < 1e-6);
        char err[256] = "";
        hv_status_t st = hv_plan_check(&plan, &fx.cfg, fr, n, &fx.model, err, sizeof err);
        if (st != HV_OK) {
            print_error("%s\n", err);
        }
        assert_int_equal(st, HV_OK);
        hv_plan_free(&plan);
        hv_assignment_free(&a);
        hv_instance_free(&inst);
    }
    tt_fixture_free(&fx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_serial_matches_brute_force),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
