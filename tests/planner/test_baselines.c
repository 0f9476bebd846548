/* FOV baseline on hand-made layouts whose stops are known. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hv/baselines.h"
#include "hv/plan_eval.h"
#include "tiny_tables.h"

/* The arm reaches only fruit at or behind the stop: y_rel in [-0.15, 0]. */
static uint16_t behind_only(hv_side_t side, double y_rel, uint32_t ix, uint32_t iz, uint32_t iw,
                            void *ctx)
{
    (void)side;
    (void)ix;
    (void)iz;
    (void)iw;
    (void)ctx;
    if (y_rel > 1e-9 || y_rel < -0.15 - 1e-9) {
        return HV_COST_UNREACHABLE;
    }
    return (uint16_t)(2000 + (unsigned)lround(-y_rel * 1000.0));
}

static hv_instance_t build(const tt_fixture_t *fx, const hv_fruit_t *fr, size_t n)
{
    hv_instance_params_t pr = {0.0, 1.0, 0.01, 5.0, 10.0, 0.0};
    hv_instance_t inst;
    hv_diag_t d;
    assert_int_equal(hv_instance_build(&pr, fr, n, &fx->model, &inst, &d), HV_OK);
    return inst;
}

static void test_fov_windows(void **state)
{
    (void)state;
    tt_fixture_t fx;
    tt_band_t band = {0.15, 2000, 15, 10};
    assert_int_equal(tt_fixture_init(&fx, tt_band_cost, &band), 0);
    /* width 0.2 from the first fruit (0.12): windows [0.12,0.32) [0.32,0.52) [0.52,0.72),
     * stops at their centres 0.22, 0.42, 0.62 */
    hv_fruit_t fr[7] = {
        tt_fruit("r1", HV_SIDE_RIGHT, 0.12, 0.5), tt_fruit("r2", HV_SIDE_RIGHT, 0.25, 0.5),
        tt_fruit("r3", HV_SIDE_RIGHT, 0.33, 0.5), tt_fruit("r4", HV_SIDE_RIGHT, 0.62, 0.5),
        tt_fruit("l1", HV_SIDE_LEFT, 0.18, 0.5),  tt_fruit("l2", HV_SIDE_LEFT, 0.45, 0.5),
        tt_fruit("l3", HV_SIDE_LEFT, 0.51, 0.5)};
    hv_instance_t inst = build(&fx, fr, 7);
    hv_assignment_t a;
    assert_int_equal(hv_assignment_alloc(&a, 7), HV_OK);
    hv_fov_stats_t st;
    assert_int_equal(hv_fov_solve(&inst, 0.2, &a, &st), HV_OK);
    const uint32_t want[7] = {22, 22, 42, 62, 22, 42, 42};
    for (int f = 0; f < 7; ++f) {
        assert_int_equal(a.fruit_stop[f], want[f]);
    }
    assert_int_equal(st.windows, 3);
    assert_int_equal(st.stops, 3);
    assert_int_equal(st.moved, 0);
    assert_int_equal(st.extra_stops, 0);
    double t;
    assert_int_equal(hv_assignment_makespan(&inst, &a, &t), HV_OK);

    /* a wider view: one window [0.12, 0.72), stop 0.42 reaches 0.33..0.51 only; the rest
     * is reached by no window stop and gets the nearest reaching stop */
    assert_int_equal(hv_fov_solve(&inst, 0.6, &a, &st), HV_OK);
    assert_int_equal(st.windows, 1);
    assert_int_equal(a.fruit_stop[2], 42);
    assert_int_equal(a.fruit_stop[5], 42);
    assert_int_equal(a.fruit_stop[6], 42);
    assert_int_equal(a.fruit_stop[0], 12); /* nearest reaching stop = its own y */
    assert_int_equal(a.fruit_stop[3], 62);
    assert_int_equal(st.extra_stops, 4); /* 0.12, 0.25, 0.62, 0.18 */
    assert_int_equal(hv_assignment_makespan(&inst, &a, &t), HV_OK);

    assert_int_equal(hv_fov_solve(&inst, 0.0, &a, &st), HV_ERR_ARG);
    assert_int_equal(hv_fov_solve(&inst, NAN, &a, &st), HV_ERR_ARG);
    hv_assignment_free(&a);
    hv_instance_free(&inst);
    tt_fixture_free(&fx);
}

static void test_fov_moved_and_extra(void **state)
{
    (void)state;
    tt_fixture_t fx;
    assert_int_equal(tt_fixture_init(&fx, behind_only, NULL), 0);
    /* windows of 0.2 from 0.12: stops 0.22, 0.42, 0.62.
     * r1 0.12 -> 0.22 (behind by 0.10); r2 0.50 is in window 1 but ahead of 0.42: the
     * nearest window stop reaching it is 0.62 (moved); r3 0.70 is ahead of 0.62 and no
     * window stop reaches it: extra stop at 0.70, the nearest stop that does. */
    hv_fruit_t fr[4] = {
        tt_fruit("r1", HV_SIDE_RIGHT, 0.12, 0.5), tt_fruit("r2", HV_SIDE_RIGHT, 0.50, 0.5),
        tt_fruit("r3", HV_SIDE_RIGHT, 0.70, 0.5), tt_fruit("l1", HV_SIDE_LEFT, 0.40, 0.5)};
    hv_instance_t inst = build(&fx, fr, 4);
    hv_assignment_t a;
    assert_int_equal(hv_assignment_alloc(&a, 4), HV_OK);
    hv_fov_stats_t st;
    assert_int_equal(hv_fov_solve(&inst, 0.2, &a, &st), HV_OK);
    assert_int_equal(a.fruit_stop[0], 22);
    assert_int_equal(a.fruit_stop[1], 62);
    assert_int_equal(a.fruit_stop[2], 70);
    assert_int_equal(a.fruit_stop[3], 42);
    assert_int_equal(st.moved, 1);
    assert_int_equal(st.extra_stops, 1);
    assert_int_equal(st.stops, 4);
    hv_assignment_free(&a);
    hv_instance_free(&inst);
    tt_fixture_free(&fx);
}

static void test_fov_unreachable_kept_out(void **state)
{
    (void)state;
    tt_fixture_t fx;
    tt_band_t band = {0.15, 2000, 15, 10};
    assert_int_equal(tt_fixture_init(&fx, tt_band_cost, &band), 0);
    hv_fruit_t fr[2] = {tt_fruit("r1", HV_SIDE_RIGHT, 0.5, 0.5),
                        tt_fruit("r2", HV_SIDE_RIGHT, 0.5, 0.5)};
    fr[1].x_m = 0.9; /* outside the table's x grid: no stop reaches it */
    hv_instance_t inst = build(&fx, fr, 2);
    hv_assignment_t a;
    assert_int_equal(hv_assignment_alloc(&a, 2), HV_OK);
    assert_int_equal(hv_fov_solve(&inst, 0.25, &a, NULL), HV_OK);
    assert_int_equal(a.fruit_stop[0], 62); /* window [0.5, 0.75): centre 0.625 -> 0.62 */
    assert_int_equal(a.fruit_stop[1], HV_NO_STOP);
    hv_assignment_free(&a);
    hv_instance_free(&inst);
    tt_fixture_free(&fx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fov_windows),
        cmocka_unit_test(test_fov_moved_and_extra),
        cmocka_unit_test(test_fov_unreachable_kept_out),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
