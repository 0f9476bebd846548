/* The prepared plan's joint setpoints are the joint angles the fruit was placed with.
 *
 * Each fruit is placed here from a joint vector chosen by the test, through forward
 * kinematics of the test's own (each revolute joint turns the zero-pose points beyond it
 * about its zero-pose axis; the mount from the config's numbers and docs/FRAMES.md), not
 * core's hv_scara_fk or hv_config_arm. hv_exec_plan_prepare() must then set exactly those
 * angles: a flipped yaw, a stop offset or the other elbow branch in exec_plan.c changes
 * them. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "hv/config.h"
#include "hv/exec_plan.h"
#include "hv/file_io.h"

#define PI 3.14159265358979323846
/* the IK's round trip in double; in the firmware's float the setpoints are rounded to a
 * float (2^-24 relative on angles under 3.2 rad) */
#if defined(HV_EXEC_SINGLE_PRECISION) && HV_EXEC_SINGLE_PRECISION
#define Q_TOL 1e-6
#else
#define Q_TOL 1e-9
#endif

typedef struct world {
    hv_config_t cfg;
    hv_arm_t arm[2]; /* only for hv_exec_plan_prepare(), the code under test */
} world_t;

/* p turned by a (rad, counter-clockwise) about the vertical axis through c */
static void turn(double p[2], const double c[2], double a)
{
    double dx = p[0] - c[0], dy = p[1] - c[1];
    p[0] = c[0] + cos(a) * dx - sin(a) * dy;
    p[1] = c[1] + sin(a) * dx + cos(a) * dy;
}

/* The fruit pose (x, y relative to the stop, z, yaw relative to the side's normal) at
 * joints q, from the config's geometry and docs/FRAMES.md's mount. */
static void place(const hv_config_t *c, int side, const double q[4], double pose[4])
{
    const double(*o)[3] = c->origin_m;
    double ee[2] = {o[4][0], o[4][1]}, wrist[2] = {o[3][0], o[3][1]};
    for (int j = 3; j >= 1; j--) { /* joints 4, 3, 2: outermost first */
        const double axis[2] = {o[j][0], o[j][1]};
        turn(ee, axis, q[j]);
        turn(wrist, axis, q[j]);
    }
    double normal = side == HV_SIDE_LEFT ? PI : 0.0;
    double base_heading = normal - c->theta_rad[side];
    double lateral = 0.5 * c->aisle_width_m - c->offset_m, half = 0.5 * c->base_spacing_m;
    const double origin[2] = {0.0, 0.0};
    double heading = atan2(ee[1] - wrist[1], ee[0] - wrist[0]) + base_heading;
    turn(ee, origin, base_heading);
    pose[0] = (side == HV_SIDE_LEFT ? -lateral : lateral) + ee[0];
    pose[1] = (side == HV_SIDE_LEFT ? half : -half) + ee[1];
    pose[2] = c->base_height_m + o[4][2] + q[0];
    pose[3] = atan2(sin(heading - normal), cos(heading - normal));
}

/* equal up to the rounding of a few double operations */
static void assert_near(double a, double b)
{
    if (!(fabs(a - b) <= 1e-12))
        fail_msg("%.15g != %.15g", a, b);
}

static int setup(void **state)
{
    world_t *w = calloc(1, sizeof *w);
    char err[256];
    if (!w ||
        hv_config_load(HV_SOURCE_DIR "/config/harvest.cfg", &w->cfg, err, sizeof err) != HV_OK) {
        fprintf(stderr, "%s\n", err);
        free(w);
        return -1;
    }
    hv_config_arm(&w->cfg, HV_SIDE_LEFT, &w->arm[0]);
    hv_config_arm(&w->cfg, HV_SIDE_RIGHT, &w->arm[1]);
    *state = w;
    return 0;
}

static int teardown(void **state)
{
    free(*state);
    return 0;
}

/* A joint vector inside the limits: fraction f[j] of the way from min to max, kept off
 * joint 3's ends (the elbow's straight and folded poses, where its branch is undefined). */
static void joints(const hv_config_t *c, const double f[4], double q[4])
{
    for (int j = 0; j < 4; j++) {
        double lo = c->limit[j].min, hi = c->limit[j].max, m = 0.1 * (hi - lo);
        q[j] = lo + m + f[j] * (hi - lo - 2.0 * m);
    }
}

static void setpoints_are_the_placing_angles(void **state)
{
    world_t *w = *state;
    hv_exec_plan_t *plan = calloc(1, sizeof *plan);
    assert_non_null(plan);
    static const double fr[3] = {0.1, 0.5, 0.9};
    double want[81][4];
    plan->row_start_m = 0.0;
    plan->row_length_m = (hv_exec_real_t)w->cfg.row_length_m;
    plan->n_stops = 3;
    for (int s = 0; s < 3; s++) {
        hv_exec_stop_t *st = &plan->stops[s];
        st->plan_index = (uint32_t)(10 + 70 * s);
        st->y_m = (hv_exec_real_t)(0.1 + 0.7 * s); /* exact in float: rounded to 0.1 m */
        for (int side = 0; side < 2; side++) {
            st->first[side] = plan->n_picks;
            /* a 3^4 grid of joint fractions, spread over stops and sides */
            for (int g = 0; g < 81; g++) {
                if (g % 6 != s * 2 + side)
                    continue;
                double f[4] = {fr[g % 3], fr[(g / 3) % 3], fr[(g / 9) % 3], fr[(g / 27) % 3]};
                double q[4], pose[4];
                joints(&w->cfg, f, q);
                place(&w->cfg, side, q, pose);
                hv_exec_pick_t *pk = &plan->picks[plan->n_picks];
                snprintf(pk->id, sizeof pk->id, "g%d", g);
                pk->side = (hv_side_t)side;
                pk->stop = (uint16_t)s;
                pk->x_m = pose[0];
                pk->y_m = pose[1] + (double)st->y_m;
                pk->z_m = pose[2];
                pk->yaw_rad = pose[3];
                pk->cost_s = 1.0;
                memcpy(want[plan->n_picks], q, sizeof q);
                plan->n_picks++;
                st->count[side]++;
            }
        }
    }
    hv_exec_timing_t tm = {w->cfg.cut_s, w->cfg.release_s, w->cfg.vehicle_speed_mps,
                           w->cfg.vehicle_accel_mps2};
    assert_int_equal(hv_exec_plan_prepare(plan, w->arm, &tm), HV_OK);
    assert_int_equal(plan->n_picks, 81);
    for (uint16_t i = 0; i < plan->n_picks; i++) {
        const hv_exec_pick_t *pk = &plan->picks[i];
        for (int j = 0; j < 4; j++) {
            double got = (double)pk->q[j];
            if (!(fabs(got - want[i][j]) <= Q_TOL))
                fail_msg("pick %s (%s): joint %d set to %.9f, placed at %.9f", pk->id,
                         pk->side == HV_SIDE_LEFT ? "left" : "right", j + 1, got, want[i][j]);
        }
    }
    assert_int_equal(plan->n_unreachable, 0);
    free(plan);
}

/* The test's kinematics agree with the config's home pose as docs/FRAMES.md gives it: the
 * end effector at base height - 0.03 + q1, and the two arms mirror images under the half
 * turn about z. */
static void own_kinematics_match_the_frames(void **state)
{
    world_t *w = *state;
    const hv_config_t *c = &w->cfg;
    double l[4], r[4];
    place(c, HV_SIDE_LEFT, c->home, l);
    place(c, HV_SIDE_RIGHT, c->home, r);
    assert_near(l[2], c->base_height_m + c->origin_m[4][2] + c->home[0]);
    assert_near(l[0], -r[0]);
    assert_near(l[1], -r[1]);
    assert_near(l[3], r[3]);
    assert_true(r[0] > 0.0); /* the right arm reaches to +x, into its row */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(setpoints_are_the_placing_angles),
        cmocka_unit_test(own_kinematics_match_the_frames),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
