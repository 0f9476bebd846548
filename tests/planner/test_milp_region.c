/* The regional bound (milp_region.h) and the bound solve with optional fruits
 * (hv_price_bound, milp_price.h) against brute force on tiny random instances. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "hv/milp.h"
#include "hv/milp_clock.h"
#include "hv/milp_price.h"
#include "hv/milp_region.h"
#include "random_instance.h"

static void test_bound_with_optional_fruits(void **state)
{
    (void)state;
    hv_milp_options_t o;
    hv_milp_options_default(&o); /* the defaults: hv_price_bound turns off what it cannot use */
    for (uint64_t seed = 1; seed <= 8; ++seed) {
        hv_instance_t in;
        hv_test_random_instance(&in, 7, 8, 4, 1, seed, 1000, 9001);
        assert_non_null(in.pairs);
        double skip[7];
        uint64_t r = seed * 77;
        for (size_t f = 0; f < 7; ++f) { /* every other fruit optional, at 1..13 s */
            skip[f] = f % 2 ? 1000.0 + (double)(hv_test_rng_next(&r) % 12000) : INFINITY;
        }
        double best = hv_test_brute_force_ms(&in, skip, NULL);
        uint32_t plan[7];
        hv_price_bound_result_t res;
        assert_int_equal(hv_price_bound(&in, &o, hv_milp_default_subsolver(), skip, INFINITY,
                                        hv_milp_now_s() + 30.0, plan, &res),
                         HV_OK);
        assert_true(res.finished);
        assert_true(res.has_plan);
        assert_true(fabs(res.lb_ms - best) < 1e-6);
        assert_true(fabs(hv_test_value_ms(&in, plan, skip) - best) < 1e-6);
        assert_true(res.root_lb_ms <= best + 1e-6);
        for (size_t f = 0; f < 7; ++f) { /* a mandatory reachable fruit is never left out */
            if (!isfinite(skip[f]) && in.fruit_begin[f] < in.fruit_begin[f + 1]) {
                assert_int_not_equal(plan[f], HV_NO_STOP);
            }
        }
        /* under a cutoff above the optimum the optimum is found (a bound that forgot the
         * fruits left out would prune it) */
        assert_int_equal(hv_price_bound(&in, &o, hv_milp_default_subsolver(), skip, best + 300.0,
                                        hv_milp_now_s() + 30.0, plan, &res),
                         HV_OK);
        assert_true(res.has_plan);
        assert_true(fabs(res.lb_ms - best) < 1e-6);
        /* a cutoff below the optimum is proved, and no solution is below it */
        assert_int_equal(hv_price_bound(&in, &o, hv_milp_default_subsolver(), skip, best - 500.0,
                                        hv_milp_now_s() + 30.0, plan, &res),
                         HV_OK);
        assert_true(res.finished);
        assert_false(res.has_plan);
        assert_true(fabs(res.lb_ms - (best - 500.0)) < 1e-6);
        hv_instance_free(&in);
    }
}

/* v_p = min(0, least c_P - pi(P) over the non-empty fruit sets P at stop p), by enumeration. */
static double stop_term_ms(const hv_instance_t *in, size_t p, const double *pi_ms)
{
    uint32_t f_at[16];
    double c_at[16];
    size_t n = 0;
    for (size_t f = 0; f < in->n_fruits; ++f) {
        for (size_t k = in->fruit_begin[f]; k < in->fruit_begin[f + 1]; ++k) {
            if (in->pairs[k].stop == p) {
                assert_true(n < 16);
                f_at[n] = (uint32_t)f;
                c_at[n++] = 1000.0 * in->pairs[k].cost_s;
            }
        }
    }
    double v = 0.0;
    for (uint32_t m = 1; m < (1u << n); ++m) {
        double arm[2] = {0.0, 0.0}, r = 1000.0 * in->stop_penalty_s;
        for (size_t i = 0; i < n; ++i) {
            if (m >> i & 1) {
                arm[in->fruits[f_at[i]].side == HV_SIDE_LEFT ? 0 : 1] += c_at[i];
                r -= pi_ms[f_at[i]];
            }
        }
        v = fmin(v, r + fmax(arm[0], arm[1]));
    }
    return v;
}

static void test_region_rise_is_a_valid_bound(void **state)
{
    (void)state;
    hv_milp_options_t o;
    hv_milp_options_default(&o); /* the defaults: hv_price_bound turns off what it cannot use */
    const size_t nf = 9, ns = 12;
    for (uint64_t seed = 1; seed <= 6; ++seed) {
        hv_instance_t in;
        hv_test_random_instance(&in, nf, ns, 5, 1, seed, 1000, 9001);
        assert_non_null(in.pairs);
        double pi[9], v[12], none[9];
        uint64_t r = seed * 131;
        for (size_t f = 0; f < nf; ++f) { /* any duals give a valid bound; a few negative */
            pi[f] = f % 4 == 3 ? -100.0 : 2000.0 + (double)(hv_test_rng_next(&r) % 8000);
            none[f] = INFINITY;
        }
        double lag = 1000.0 * in.travel_time_s;
        for (size_t f = 0; f < nf; ++f) {
            lag += in.fruit_begin[f] < in.fruit_begin[f + 1] ? pi[f] : 0.0;
        }
        for (size_t p = 0; p < ns; ++p) {
            v[p] = stop_term_ms(&in, p, pi);
            lag += v[p];
        }
        double opt = hv_test_brute_force_ms(&in, none, NULL);
        assert_true(lag <= opt + 1e-6);
        const uint32_t stretch[][2] = {{0, 3}, {4, 11}, {2, 8}, {0, 11}};
        double rise[4];
        for (size_t s = 0; s < 4; ++s) {
            hv_region_result_t rr;
            assert_int_equal(hv_region_rise(&in, stretch[s][0], stretch[s][1], pi, v, 1e9, &o,
                                            hv_milp_default_subsolver(), hv_milp_now_s() + 30.0,
                                            NULL, &rr),
                             HV_OK);
            assert_true(rr.finished);
            assert_true(rr.rise_ms >= 0.0);
            assert_true(rr.root_rise_ms <= rr.rise_ms + 1e-6);
            assert_true(lag + rr.rise_ms <= opt + 1e-6);
            rise[s] = rr.rise_ms;
        }
        /* disjoint stretches add up; the whole row is the problem itself */
        assert_true(lag + rise[0] + rise[1] <= opt + 1e-6);
        assert_true(fabs(lag + rise[3] - opt) < 1e-6);
        /* asked for less than the whole row's rise, it proves that much and stops there */
        if (rise[3] > 1.0) {
            hv_region_result_t rr;
            uint32_t plan[9];
            assert_int_equal(hv_region_rise(&in, 0, (uint32_t)ns - 1, pi, v, 0.5 * rise[3], &o,
                                            hv_milp_default_subsolver(), hv_milp_now_s() + 30.0,
                                            plan, &rr),
                             HV_OK);
            assert_true(fabs(rr.rise_ms - 0.5 * rise[3]) < 1e-6);
            assert_false(rr.has_plan);
        }
        hv_region_result_t rr;
        assert_int_equal(hv_region_rise(&in, 5, 2, pi, v, 1e9, &o, hv_milp_default_subsolver(),
                                        hv_milp_now_s() + 30.0, NULL, &rr),
                         HV_ERR_ARG);
        hv_instance_free(&in);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bound_with_optional_fruits),
        cmocka_unit_test(test_region_rise_is_a_valid_bound),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
