/* SCARA kinematics and joint timing against hand-computed and round-trip expectations. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "core_fixture.h"
#include "hv/scara.h"

static void test_trapezoid_branches(void **state)
{
    (void)state;
    /* triangular: d = 0.05 <= v^2/a = 0.1  ->  2 sqrt(0.05 / 0.1) */
    assert_float_equal(hv_trap_time(0.05, 0.1, 0.1), 2.0 * sqrt(0.5), 1e-12);
    /* trapezoidal: d = 0.5 > 0.1  ->  0.5 / 0.1 + 0.1 / 0.1 = 6 */
    assert_float_equal(hv_trap_time(0.5, 0.1, 0.1), 6.0, 1e-12);
    /* both branches meet at d = v^2/a: 2 sqrt(1) = 1 + 1 */
    assert_float_equal(hv_trap_time(0.1, 0.1, 0.1), 2.0, 1e-12);
    assert_float_equal(hv_trap_time(0.1 + 1e-9, 0.1, 0.1), 2.0, 1e-8);
    /* revolute joint: 1 rad at 0.2 rad/s, 0.2 rad/s^2 -> 5 + 1; sign does not matter */
    assert_float_equal(hv_trap_time(-1.0, 0.2, 0.2), 6.0, 1e-12);
    assert_float_equal(hv_trap_time(0.0, 0.2, 0.2), 0.0, 0.0);
    assert_true(hv_trap_time(1.0, 0.0, 0.2) < 0.0);
    assert_true(hv_trap_time(1.0, 0.2, -1.0) < 0.0);
    assert_true(hv_trap_time(NAN, 0.2, 0.2) < 0.0);
}

/* The single-precision twin (the firmware's vehicle moves) agrees with the double one to
 * float's precision on both branches, and refuses the same bad input. */
static void test_trapezoid_single_precision(void **state)
{
    (void)state;
    for (int k = -40; k <= 40; k++) {
        double d = 0.0125 * k;
        double want = hv_trap_time(d, 0.1, 0.1);
        assert_float_equal((double)hv_trap_timef((float)d, 0.1f, 0.1f), want, 1e-6 * (1.0 + want));
    }
    assert_true(hv_trap_timef(1.0f, 0.0f, 0.2f) < 0.0f);
    assert_true(hv_trap_timef(1.0f, 0.2f, -1.0f) < 0.0f);
    assert_true(hv_trap_timef(NAN, 0.2f, 0.2f) < 0.0f);
    assert_true(hv_trap_timef(INFINITY, 0.2f, 0.2f) < 0.0f);
}

static void test_move_time_is_slowest_joint(void **state)
{
    (void)state;
    hv_arm_t arm;
    fixture_arm(&arm, HV_SIDE_RIGHT, 0);
    double from[4] = {0.0, 0.0, 0.0, 0.0};
    double to[4] = {0.05, 1.0, 0.1, -0.3}; /* 1.414 s, 6 s, 1.414 s, 2.449 s */
    assert_float_equal(hv_scara_move_time(&arm, from, to), 6.0, 1e-12);
    double to2[4] = {0.5, 0.1, 0.1, 0.1}; /* joint 1: 6 s wins */
    assert_float_equal(hv_scara_move_time(&arm, from, to2), 6.0, 1e-12);
}

static void test_fk_zero_pose_matches_link_origins(void **state)
{
    (void)state;
    hv_arm_t arm;
    fixture_arm(&arm, HV_SIDE_RIGHT, 0);
    /* put the base at the origin, heading 0: FK at zero joints is the ee origin */
    memset(arm.base_m, 0, sizeof arm.base_m);
    arm.base_yaw_rad = 0.0;
    double q[4] = {0, 0, 0, 0};
    hv_pose_t p;
    assert_int_equal(hv_scara_fk(&arm, q, &p), HV_OK);
    assert_float_equal(p.x_m, 0.53, 1e-12);
    assert_float_equal(p.y_m, 0.0, 1e-12);
    assert_float_equal(p.z_m, -0.03, 1e-12);
    assert_float_equal(p.heading_rad, 0.0, 1e-12);
    /* elbow at 90 deg: link 3 and 4 point along +y */
    double q2[4] = {0.2, 0.0, M_PI / 2, 0.0};
    assert_int_equal(hv_scara_fk(&arm, q2, &p), HV_OK);
    assert_float_equal(p.x_m, 0.23, 1e-12);
    assert_float_equal(p.y_m, 0.30, 1e-12);
    assert_float_equal(p.z_m, 0.17, 1e-12);
    assert_float_equal(p.heading_rad, M_PI / 2, 1e-12);
}

static double urand(uint64_t *s, double lo, double hi)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * (double)(*s >> 11) / 9007199254740992.0;
}

static void roundtrip(int elbow_free, hv_side_t side)
{
    hv_arm_t arm;
    fixture_arm(&arm, side, elbow_free);
    uint64_t seed = 12345u + (uint64_t)side * 7u + (uint64_t)elbow_free;
    int solved = 0;
    for (int n = 0; n < 5000; n++) {
        double q[4];
        for (int j = 0; j < 4; j++) {
            double lo = arm.limit[j].min, hi = arm.limit[j].max;
            if (j == 2 && elbow_free) {
                lo = -hi;
            }
            q[j] = urand(&seed, lo, hi);
        }
        hv_pose_t p, p2;
        assert_int_equal(hv_scara_fk(&arm, q, &p), HV_OK);
        double qi[4];
        hv_status_t st = hv_scara_ik(&arm, &p, qi);
        /* every pose produced by FK from in-limit joints is reachable */
        assert_int_equal(st, HV_OK);
        assert_true(hv_scara_within_limits(&arm, qi));
        assert_int_equal(hv_scara_fk(&arm, qi, &p2), HV_OK);
        assert_float_equal(p2.x_m, p.x_m, 1e-9);
        assert_float_equal(p2.y_m, p.y_m, 1e-9);
        assert_float_equal(p2.z_m, p.z_m, 1e-9);
        assert_float_equal(remainder(p2.heading_rad - p.heading_rad, 2 * M_PI), 0.0, 1e-9);
        solved++;
    }
    assert_int_equal(solved, 5000);
}

static void test_fk_ik_roundtrip_limited(void **state)
{
    (void)state;
    roundtrip(0, HV_SIDE_RIGHT);
    roundtrip(0, HV_SIDE_LEFT);
}

static void test_fk_ik_roundtrip_elbow_free(void **state)
{
    (void)state;
    roundtrip(1, HV_SIDE_RIGHT);
}

static void test_ik_random_poses_respect_limits(void **state)
{
    (void)state;
    hv_arm_t arm;
    fixture_arm(&arm, HV_SIDE_RIGHT, 0);
    uint64_t seed = 99;
    int ok = 0, bad = 0;
    for (int n = 0; n < 20000; n++) {
        hv_pose_t p = {urand(&seed, -0.2, 1.0), urand(&seed, -1.0, 1.0), urand(&seed, 0.2, 1.0),
                       urand(&seed, -M_PI, M_PI)};
        double q[4];
        hv_status_t st = hv_scara_ik(&arm, &p, q);
        if (st == HV_OK) {
            assert_true(hv_scara_within_limits(&arm, q));
            hv_pose_t p2;
            hv_scara_fk(&arm, q, &p2);
            assert_float_equal(p2.x_m, p.x_m, 1e-9);
            assert_float_equal(p2.y_m, p.y_m, 1e-9);
            ok++;
        } else {
            assert_true(st == HV_ERR_UNREACHABLE || st == HV_ERR_JOINT_LIMIT);
            bad++;
        }
    }
    assert_true(ok > 500); /* the region sampled contains a real share of the workspace */
    assert_true(bad > 500);
}

static void test_just_outside_workspace_rejected(void **state)
{
    (void)state;
    hv_arm_t arm;
    fixture_arm(&arm, HV_SIDE_RIGHT, 0);
    double q[4] = {0.5, 0.3, 0.0, 0.0}; /* top of the stroke, arm straight */
    hv_pose_t p;
    hv_scara_fk(&arm, q, &p);
    double qi[4];
    assert_int_equal(hv_scara_ik(&arm, &p, qi), HV_OK);
    hv_pose_t above = p;
    above.z_m += 1e-6; /* beyond joint 1's stroke */
    assert_int_equal(hv_scara_ik(&arm, &above, qi), HV_ERR_UNREACHABLE);
    hv_pose_t beyond = p; /* 1 um past full extension along the arm */
    beyond.x_m += 1e-6 * cos(p.heading_rad);
    beyond.y_m += 1e-6 * sin(p.heading_rad);
    assert_int_equal(hv_scara_ik(&arm, &beyond, qi), HV_ERR_UNREACHABLE);
    double q_low[4] = {0.0, 0.3, 0.0, 0.0};
    hv_scara_fk(&arm, q_low, &p);
    p.z_m -= 1e-6;
    assert_int_equal(hv_scara_ik(&arm, &p, qi), HV_ERR_UNREACHABLE);
}

static void test_elbow_limit_and_lifted(void **state)
{
    (void)state;
    hv_arm_t limited, freed;
    fixture_arm(&limited, HV_SIDE_RIGHT, 0);
    fixture_arm(&freed, HV_SIDE_RIGHT, 1);
    /* a pose made with the elbow on the forbidden side (q3 < 0): no in-limit solution
     * when limited (the mirror solution needs q4 or q2 outside their ranges or exists) */
    double q[4] = {0.2, 0.5, -1.2, 0.4};
    hv_pose_t p;
    hv_scara_fk(&freed, q, &p);
    double ql[4], qf[4];
    hv_status_t sl = hv_scara_ik(&limited, &p, ql);
    assert_int_equal(hv_scara_ik(&freed, &p, qf), HV_OK);
    if (sl == HV_OK) {
        assert_true(ql[2] >= 0.0); /* the limited arm can only use the positive elbow */
    } else {
        assert_int_equal(sl, HV_ERR_JOINT_LIMIT);
    }
    /* lifting the limit never makes a pose more expensive: both elbows are considered */
    double cl, cf;
    if (hv_scara_pick_cost(&limited, &p, &cl, NULL) == HV_OK) {
        assert_int_equal(hv_scara_pick_cost(&freed, &p, &cf, NULL), HV_OK);
        assert_true(cf <= cl + 1e-12);
    }
}

static void test_nan_and_null(void **state)
{
    (void)state;
    hv_arm_t arm;
    fixture_arm(&arm, HV_SIDE_RIGHT, 0);
    double q[4];
    hv_pose_t p = {NAN, 0.0, 0.5, 0.0};
    assert_int_equal(hv_scara_ik(&arm, &p, q), HV_ERR_NAN);
    p.x_m = 0.4;
    p.heading_rad = INFINITY;
    assert_int_equal(hv_scara_ik(&arm, &p, q), HV_ERR_NAN);
    double qn[4] = {0.1, NAN, 0, 0};
    assert_int_equal(hv_scara_fk(&arm, qn, &p), HV_ERR_NAN);
    assert_int_equal(hv_scara_ik(NULL, &p, q), HV_ERR_ARG);
    double c;
    assert_int_equal(hv_scara_pick_cost(&arm, &p, NULL, NULL), HV_ERR_ARG);
    p.heading_rad = NAN;
    assert_int_equal(hv_scara_pick_cost(&arm, &p, &c, NULL), HV_ERR_NAN);
}

static void test_pick_cost_from_home_is_zero_at_home(void **state)
{
    (void)state;
    hv_arm_t arm;
    fixture_arm(&arm, HV_SIDE_LEFT, 0);
    hv_pose_t home;
    assert_int_equal(hv_scara_fk(&arm, arm.home, &home), HV_OK);
    double c, q[4];
    assert_int_equal(hv_scara_pick_cost(&arm, &home, &c, q), HV_OK);
    assert_float_equal(c, 0.0, 1e-6);
    /* one joint moved: the cost is that joint's trapezoid time */
    double moved[4] = {arm.home[0], arm.home[1] + 0.5, arm.home[2], arm.home[3] - 0.5};
    hv_pose_t p;
    hv_scara_fk(&arm, moved, &p);
    assert_int_equal(hv_scara_pick_cost(&arm, &p, &c, q), HV_OK);
    assert_float_equal(c, hv_trap_time(0.5, 0.2, 0.2), 1e-6);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_trapezoid_branches),
        cmocka_unit_test(test_trapezoid_single_precision),
        cmocka_unit_test(test_move_time_is_slowest_joint),
        cmocka_unit_test(test_fk_zero_pose_matches_link_origins),
        cmocka_unit_test(test_fk_ik_roundtrip_limited),
        cmocka_unit_test(test_fk_ik_roundtrip_elbow_free),
        cmocka_unit_test(test_ik_random_poses_respect_limits),
        cmocka_unit_test(test_just_outside_workspace_rejected),
        cmocka_unit_test(test_elbow_limit_and_lifted),
        cmocka_unit_test(test_nan_and_null),
        cmocka_unit_test(test_pick_cost_from_home_is_zero_at_home),
    };
    return cmocka_run_group_tests_name("core_scara", tests, NULL, NULL);
}
