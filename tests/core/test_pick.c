/* One pick (hv/pick.h): the IK and time the planner, checker and executor share, why a
 * fruit is out of reach, and how far beyond the row's ends the arms reach. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "core_fixture.h"
#include "hv/pick.h"

/* A reproducible stream in [lo, hi): 24 bits of a 32-bit LCG are plenty for poses. */
static double uniform(uint32_t *s, double lo, double hi)
{
    *s = *s * 1103515245u + 12345u;
    return lo + (hi - lo) * (double)(*s >> 8) / 16777216.0;
}

/* A pose made by forward kinematics comes back with the same time the executor derives
 * from its own IK solution (hv_scara_move_time from home). */
static void test_solve_round_trip(void **state)
{
    (void)state;
    uint32_t seed = 5;
    for (int side = 0; side < 2; side++) {
        hv_arm_t arm;
        fixture_arm(&arm, (hv_side_t)side, 0);
        for (int n = 0; n < 200; n++) {
            double q[HV_NJOINTS];
            for (int j = 0; j < HV_NJOINTS; j++) {
                double h = arm.home[j];
                q[j] = uniform(&seed, h - 0.3 * (h - arm.limit[j].min),
                               h + 0.3 * (arm.limit[j].max - h));
            }
            hv_pose_t p;
            assert_int_equal(hv_scara_fk(&arm, q, &p), HV_OK);
            double yaw = p.heading_rad - hv_side_normal_heading((hv_side_t)side);
            double qs[HV_NJOINTS], t = -1.0;
            hv_pick_why_t why = HV_PICK_HEIGHT;
            assert_int_equal(hv_pick_solve(&arm, p.x_m, p.y_m, p.z_m, yaw, qs, &t, &why), HV_OK);
            assert_int_equal(why, HV_PICK_OK);
            assert_float_equal(t, hv_scara_move_time(&arm, arm.home, qs), 1e-12);
            hv_pose_t back;
            assert_int_equal(hv_scara_fk(&arm, qs, &back), HV_OK);
            assert_float_equal(back.x_m, p.x_m, 1e-9);
            assert_float_equal(back.y_m, p.y_m, 1e-9);
            assert_float_equal(back.z_m, p.z_m, 1e-9);
        }
    }
}

static void test_why_names_the_cause(void **state)
{
    (void)state;
    hv_arm_t arm;
    fixture_arm(&arm, HV_SIDE_RIGHT, 0);
    double t;
    hv_pick_why_t why;
    /* joint 1's stroke: z in [0.34, 0.84] m */
    assert_int_equal(hv_pick_solve(&arm, 0.42, -0.2, 0.90, 0.0, NULL, &t, &why),
                     HV_ERR_UNREACHABLE);
    assert_int_equal(why, HV_PICK_HEIGHT);
    /* 1 m away laterally: outside the annulus */
    assert_int_equal(hv_pick_solve(&arm, 1.2, -0.2, 0.60, 0.0, NULL, &t, &why), HV_ERR_UNREACHABLE);
    assert_int_equal(why, HV_PICK_DEPTH);
    /* in reach, but joint 4 held at home cannot turn the wrist to the stem */
    hv_arm_t stiff = arm;
    stiff.limit[3].min = -0.01;
    stiff.limit[3].max = 0.01;
    int yaw_seen = 0;
    for (double y = -0.5; y <= 0.5; y += 0.01) {
        if (hv_pick_solve(&stiff, 0.42, y, 0.60, 0.7, NULL, &t, &why) == HV_ERR_JOINT_LIMIT) {
            assert_int_equal(why, HV_PICK_YAW);
            yaw_seen = 1;
        }
    }
    assert_true(yaw_seen);
    assert_string_equal(hv_pick_why_name(HV_PICK_YAW), "yaw");
    assert_string_equal(hv_pick_why_name(-1), "?");
    assert_int_equal(hv_pick_solve(NULL, 0, 0, 0, 0, NULL, &t, &why), HV_ERR_ARG);
}

/* Outside its reach span an arm reaches no fruit of the area; inside, it reaches some. */
static void test_reach_span_bounds_every_pick(void **state)
{
    (void)state;
    hv_config_t cfg;
    fixture_config(&cfg);
    uint32_t seed = 9;
    for (int side = 0; side < 2; side++) {
        hv_arm_t arm;
        hv_grid_t area;
        hv_config_arm(&cfg, (hv_side_t)side, &arm);
        hv_config_grid(&cfg, (hv_side_t)side, &area);
        double lo, hi;
        assert_int_equal(hv_pick_reach_span(&arm, &area, &lo, &hi), HV_OK);
        assert_true(lo < hi && hi - lo < 2.0);
        const hv_axis_t *ax = area.axis;
        int inside = 0;
        for (int n = 0; n < 20000; n++) {
            double x = uniform(&seed, ax[HV_AX_X].origin,
                               ax[HV_AX_X].origin + ax[HV_AX_X].step * (ax[HV_AX_X].count - 1));
            double z = uniform(&seed, ax[HV_AX_Z].origin,
                               ax[HV_AX_Z].origin + ax[HV_AX_Z].step * (ax[HV_AX_Z].count - 1));
            double yaw = uniform(&seed, -cfg.pick_yaw_max_rad, cfg.pick_yaw_max_rad);
            double y = uniform(&seed, lo - 0.5, hi + 0.5);
            double t;
            hv_status_t st = hv_pick_solve(&arm, x, y, z, yaw, NULL, &t, NULL);
            if (y < lo || y > hi) {
                assert_int_not_equal(st, HV_OK);
            } else {
                inside += st == HV_OK;
            }
        }
        assert_true(inside > 1000);
    }
}

/* The margin: a whole number of steps, and the row's first and last fruit are reached from
 * within it (a fruit straight ahead of each arm at the row's ends). */
static void test_stop_margin(void **state)
{
    (void)state;
    hv_config_t cfg;
    fixture_config(&cfg);
    double m = -1.0;
    assert_int_equal(hv_pick_stop_margin(&cfg, &m), HV_OK);
    assert_true(m > 0.5 * cfg.base_spacing_m);
    double steps = m / cfg.grid_step_m;
    assert_float_equal(steps, round(steps), 1e-9);
    double lo[2] = {-0.3, -0.1}, hi[2] = {0.2, 0.456};
    assert_float_equal(hv_pick_margin_of_spans(lo, hi, 0.01), 0.46, 1e-12);
    /* every reachable stop of a fruit at the row's start lies within the margin */
    for (int side = 0; side < 2; side++) {
        hv_arm_t arm;
        hv_config_arm(&cfg, (hv_side_t)side, &arm);
        double x = (side ? 1.0 : -1.0) * (0.5 * cfg.aisle_width_m + 0.07);
        int reached = 0;
        for (double s = -1.5; s <= 1.5; s += cfg.grid_step_m) {
            double t;
            if (hv_pick_solve(&arm, x, 0.0 - s, 0.6, 0.0, NULL, &t, NULL) == HV_OK) {
                assert_true(s >= -m - 1e-9);
                reached = 1;
            }
        }
        assert_true(reached);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_solve_round_trip),
        cmocka_unit_test(test_why_names_the_cause),
        cmocka_unit_test(test_reach_span_bounds_every_pick),
        cmocka_unit_test(test_stop_margin),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
