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
#include "hv/plan_build.h"
#include "hv/plan_check.h"
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

/* The stop of every fruit and the counts of hv_fov_stats_t are those expected. */
static void expect_fov(const hv_assignment_t *a, const uint32_t *want, const hv_fov_stats_t *st,
                       hv_fov_stats_t want_st)
{
    for (size_t f = 0; f < a->n_fruits; ++f) {
        assert_int_equal(a->fruit_stop[f], want[f]);
    }
    assert_int_equal(st->windows, want_st.windows);
    assert_int_equal(st->stops, want_st.stops);
    assert_int_equal(st->moved, want_st.moved);
    assert_int_equal(st->extra_stops, want_st.extra_stops);
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
    expect_fov(&a, want, &st, (hv_fov_stats_t){3, 3, 0, 0});
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
    assert_int_equal(st.moved, 2); /* r2 and r3 */
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

/* Each arm reaches its own stretch of row from the stop, as the real arms do: the left one
 * ahead (y_rel in [lo, 0.30]), the right one behind (y_rel in [-0.30, -lo]); *ctx = lo. */
static uint16_t own_stretch(hv_side_t side, double y_rel, uint32_t ix, uint32_t iz, uint32_t iw,
                            void *ctx)
{
    (void)ix;
    (void)iz;
    (void)iw;
    double lo = *(const double *)ctx;
    double d = side == HV_SIDE_LEFT ? y_rel : -y_rel;
    if (d < lo - 1e-9 || d > 0.30 + 1e-9) {
        return HV_COST_UNREACHABLE;
    }
    return (uint16_t)(2000 + (unsigned)lround(fabs(d - 0.15) * 1000.0));
}

/* Windows of 0.2 m centred 0.15 m ahead (left) and behind (right) of the vehicle: inside
 * each arm's reach. */
static const hv_fov_params_t k_arm_windows = {0.2, {0.15, -0.15}};

static void test_fov_arm_windows(void **state)
{
    (void)state;
    double lo = 0.0;
    tt_fixture_t fx;
    assert_int_equal(tt_fixture_init(&fx, own_stretch, &lo), 0);
    /* s0 = l1's y - 0.15 + 0.1 = 0.35: vehicle positions 0.35, 0.55, 0.75, 0.95; left
     * windows [0.40, 0.60) [0.60, 0.80) ..., right windows [0.10, 0.30) [0.30, 0.50)
     * [0.50, 0.70) [0.70, 0.90). l3 0.62 is within the left arm's reach from 0.35 (up to
     * 0.65) but outside its view there: picked from 0.55. Nothing is in view at 0.75. */
    hv_fruit_t fr[5] = {
        tt_fruit("l1", HV_SIDE_LEFT, 0.40, 0.5), tt_fruit("l2", HV_SIDE_LEFT, 0.55, 0.5),
        tt_fruit("l3", HV_SIDE_LEFT, 0.62, 0.5), tt_fruit("r1", HV_SIDE_RIGHT, 0.32, 0.5),
        tt_fruit("r2", HV_SIDE_RIGHT, 0.80, 0.5)};
    hv_instance_t inst = build(&fx, fr, 5);
    hv_assignment_t a;
    assert_int_equal(hv_assignment_alloc(&a, 5), HV_OK);
    hv_fov_stats_t st;
    assert_int_equal(hv_fov_solve_params(&inst, &k_arm_windows, &a, &st), HV_OK);
    const uint32_t want[5] = {35, 35, 55, 55, 95};
    /* 4 positions, 3 stops: the empty window at 0.75 is driven through */
    expect_fov(&a, want, &st, (hv_fov_stats_t){4, 3, 0, 0});

    /* one window centred on the vehicle: l1 is in view at 0.42, behind the left arm's
     * reach there, so it is moved */
    hv_fov_params_t centred = {0.2, {0.0, 0.0}};
    assert_int_equal(hv_fov_solve_params(&inst, &centred, &a, &st), HV_OK);
    assert_true(st.moved > 0);

    hv_fov_params_t bad = k_arm_windows;
    bad.centre_y_m[HV_SIDE_RIGHT] = NAN;
    assert_int_equal(hv_fov_solve_params(&inst, &bad, &a, &st), HV_ERR_ARG);
    bad = k_arm_windows;
    bad.width_m = 0.0;
    assert_int_equal(hv_fov_solve_params(&inst, &bad, &a, &st), HV_ERR_ARG);
    hv_assignment_free(&a);
    hv_instance_free(&inst);
    tt_fixture_free(&fx);
}

static void test_fov_arm_in_view_out_of_reach(void **state)
{
    (void)state;
    double lo = 0.10; /* the left arm misses the first 0.10 m ahead: the window's near end */
    tt_fixture_t fx;
    assert_int_equal(tt_fixture_init(&fx, own_stretch, &lo), 0);
    /* positions 0.35 (left view [0.40, 0.60), reach [0.45, 0.65]) and 0.55 (view [0.60,
     * 0.80), reach [0.65, 0.85]). l1 0.40 is in view at 0.35, not in its reach, nor in
     * 0.55's: an extra stop, the nearest that reaches it (0.30). l4 0.61 is in view at
     * 0.55, out of its reach, within 0.35's: moved there. */
    hv_fruit_t fr[4] = {
        tt_fruit("l1", HV_SIDE_LEFT, 0.40, 0.5), tt_fruit("l2", HV_SIDE_LEFT, 0.55, 0.5),
        tt_fruit("l3", HV_SIDE_LEFT, 0.70, 0.5), tt_fruit("l4", HV_SIDE_LEFT, 0.61, 0.5)};
    hv_instance_t inst = build(&fx, fr, 4);
    hv_assignment_t a;
    assert_int_equal(hv_assignment_alloc(&a, 4), HV_OK);
    hv_fov_stats_t st;
    assert_int_equal(hv_fov_solve_params(&inst, &k_arm_windows, &a, &st), HV_OK);
    const uint32_t want[4] = {30, 35, 55, 35};
    expect_fov(&a, want, &st, (hv_fov_stats_t){2, 3, 2, 1});

    /* the plan passes the independent checker */
    hv_plan_meta_t m;
    memset(&m, 0, sizeof m);
    m.method = "fov";
    m.fruit_map = "map.csv";
    m.params = (hv_instance_params_t){
        0.0, 1.0, 0.01, fx.cfg.stop_penalty_s, 1.0 / fx.cfg.vehicle_speed_mps, 0.0};
    m.vehicle_speed_mps = fx.cfg.vehicle_speed_mps;
    m.solver_status = "heuristic";
    m.gap = -1;
    hv_instance_t chk;
    hv_diag_t d;
    assert_int_equal(hv_instance_build(&m.params, fr, 4, &fx.model, &chk, &d), HV_OK);
    hv_plan_t plan;
    assert_int_equal(hv_plan_build(&chk, &a, NULL, &m, &plan), HV_OK);
    char err[512] = "";
    hv_status_t ck = hv_plan_check(&plan, &fx.cfg, fr, 4, &fx.model, err, sizeof err);
    if (ck != HV_OK) {
        print_error("%s\n", err);
    }
    assert_int_equal(ck, HV_OK);
    assert_int_equal(plan.n_stops, 3);
    hv_plan_free(&plan);
    hv_instance_free(&chk);
    hv_assignment_free(&a);
    hv_instance_free(&inst);
    tt_fixture_free(&fx);
}

static void test_fov_arm_empty_row(void **state)
{
    (void)state;
    double lo = 0.0;
    tt_fixture_t fx;
    assert_int_equal(tt_fixture_init(&fx, own_stretch, &lo), 0);
    hv_fruit_t fr[1] = {tt_fruit("r1", HV_SIDE_RIGHT, 0.5, 0.5)};
    fr[0].x_m = 0.9; /* outside the table's x grid: no stop reaches it, nothing in view */
    hv_instance_t inst = build(&fx, fr, 1);
    hv_assignment_t a;
    assert_int_equal(hv_assignment_alloc(&a, 1), HV_OK);
    hv_fov_stats_t st;
    assert_int_equal(hv_fov_solve_params(&inst, &k_arm_windows, &a, &st), HV_OK);
    assert_int_equal(a.fruit_stop[0], HV_NO_STOP);
    assert_int_equal(st.windows, 0);
    assert_int_equal(st.stops, 0);
    hv_assignment_free(&a);
    hv_instance_free(&inst);
    tt_fixture_free(&fx);
}

static void test_fov_params_from_config(void **state)
{
    (void)state;
    hv_config_t cfg;
    assert_int_equal(tt_load_config(&cfg), 0);
    cfg.base_spacing_m = 0.4;
    cfg.fov_offset_m = 0.1;
    cfg.fov_width_m = 0.3;
    hv_fov_params_t p;
    hv_fov_params_from_config(&cfg, &p);
    assert_true(fabs(p.width_m - 0.3) < 1e-12);
    assert_true(fabs(p.centre_y_m[HV_SIDE_LEFT] - 0.3) < 1e-12);  /* 0.2 + 0.1 ahead */
    assert_true(fabs(p.centre_y_m[HV_SIDE_RIGHT] + 0.3) < 1e-12); /* mirrored, behind */
    cfg.base_spacing_m = 0.0; /* bases side by side: offsets from the vehicle itself */
    hv_fov_params_from_config(&cfg, &p);
    assert_true(fabs(p.centre_y_m[HV_SIDE_LEFT] - 0.1) < 1e-12);
    assert_true(fabs(p.centre_y_m[HV_SIDE_RIGHT] + 0.1) < 1e-12);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fov_windows),
        cmocka_unit_test(test_fov_moved_and_extra),
        cmocka_unit_test(test_fov_unreachable_kept_out),
        cmocka_unit_test(test_fov_arm_windows),
        cmocka_unit_test(test_fov_arm_in_view_out_of_reach),
        cmocka_unit_test(test_fov_arm_empty_row),
        cmocka_unit_test(test_fov_params_from_config),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
