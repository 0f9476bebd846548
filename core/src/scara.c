/* SCARA kinematics and joint timing (DESIGN §1, §2). Pure C99, no allocation. */
#include <math.h>
#include <stddef.h>

#include "hv/scara.h"

#define HV_PI        3.14159265358979323846
#define HV_LIMIT_TOL 1e-9

/* Planar link geometry derived from the zero-pose link origins. */
typedef struct link_geom {
    double j2x, j2y; /* joint 2 axis, base frame (m) */
    double len[3];   /* joint2->joint3, joint3->joint4, joint4->ee (m) */
    double beta[3];  /* their headings at zero joints (rad) */
    double ee_z0;    /* ee height at q1 = 0, base frame (m) */
} link_geom_t;

static void geom_of(const hv_arm_t *arm, link_geom_t *g)
{
    g->j2x = arm->origin_m[1][0];
    g->j2y = arm->origin_m[1][1];
    for (int i = 0; i < 3; i++) {
        double dx = arm->origin_m[i + 2][0] - arm->origin_m[i + 1][0];
        double dy = arm->origin_m[i + 2][1] - arm->origin_m[i + 1][1];
        g->len[i] = hypot(dx, dy);
        g->beta[i] = atan2(dy, dx);
    }
    g->ee_z0 = arm->origin_m[4][2];
}

/* Wrap to [-pi, pi). */
static double wrap_pi(double a)
{
    double w = fmod(a + HV_PI, 2.0 * HV_PI);
    if (w < 0.0) {
        w += 2.0 * HV_PI;
    }
    return w - HV_PI;
}

double hv_side_normal_heading(hv_side_t side)
{
    return side == HV_SIDE_LEFT ? HV_PI : 0.0;
}

hv_status_t hv_scara_fk(const hv_arm_t *arm, const double q[HV_NJOINTS], hv_pose_t *out)
{
    if (arm == NULL || q == NULL || out == NULL) {
        return HV_ERR_ARG;
    }
    for (int j = 0; j < HV_NJOINTS; j++) {
        if (!isfinite(q[j])) {
            return HV_ERR_NAN;
        }
    }
    link_geom_t g;
    geom_of(arm, &g);
    double a2 = q[1] + g.beta[0];
    double a3 = q[1] + q[2] + g.beta[1];
    double a4 = q[1] + q[2] + q[3] + g.beta[2];
    double bx = g.j2x + g.len[0] * cos(a2) + g.len[1] * cos(a3) + g.len[2] * cos(a4);
    double by = g.j2y + g.len[0] * sin(a2) + g.len[1] * sin(a3) + g.len[2] * sin(a4);
    double c = cos(arm->base_yaw_rad), s = sin(arm->base_yaw_rad);
    out->x_m = arm->base_m[0] + c * bx - s * by;
    out->y_m = arm->base_m[1] + s * bx + c * by;
    out->z_m = arm->base_m[2] + g.ee_z0 + q[0];
    out->heading_rad = wrap_pi(arm->base_yaw_rad + a4);
    return HV_OK;
}

static int within(double v, double lo, double hi)
{
    return v >= lo - HV_LIMIT_TOL && v <= hi + HV_LIMIT_TOL;
}

/* Joint 3's range in effect: lifting the elbow limit mirrors it to [-max, max]. */
static void q3_range(const hv_arm_t *arm, double *lo, double *hi)
{
    *hi = arm->limit[2].max;
    *lo = arm->elbow_free ? -arm->limit[2].max : arm->limit[2].min;
}

int hv_scara_within_limits(const hv_arm_t *arm, const double q[HV_NJOINTS])
{
    double lo3, hi3;
    q3_range(arm, &lo3, &hi3);
    for (int j = 0; j < HV_NJOINTS; j++) {
        double lo = j == 2 ? lo3 : arm->limit[j].min;
        double hi = j == 2 ? hi3 : arm->limit[j].max;
        if (!within(q[j], lo, hi)) {
            return 0;
        }
    }
    return 1;
}

double hv_trap_time(double dist, double vmax, double amax)
{
    if (!isfinite(dist) || !isfinite(vmax) || !isfinite(amax) || !(vmax > 0.0) || !(amax > 0.0)) {
        return -1.0;
    }
    double d = fabs(dist);
    if (d <= vmax * vmax / amax) {
        return 2.0 * sqrt(d / amax); /* triangular: never reaches vmax */
    }
    return d / vmax + vmax / amax;
}

float hv_trap_timef(float dist, float vmax, float amax)
{
    float d = fabsf(dist);
    if (!isfinite(d) || !isfinite(vmax) || !isfinite(amax) || !(vmax > 0.0f) || !(amax > 0.0f))
        return -1.0f;
    return d <= vmax * vmax / amax ? 2.0f * sqrtf(d / amax) : d / vmax + vmax / amax;
}

double hv_scara_move_time(const hv_arm_t *arm, const double q_from[HV_NJOINTS],
                          const double q_to[HV_NJOINTS])
{
    double t = 0.0;
    for (int j = 0; j < HV_NJOINTS; j++) {
        double tj = hv_trap_time(q_to[j] - q_from[j], arm->limit[j].vmax, arm->limit[j].amax);
        if (tj < 0.0) {
            return -1.0;
        }
        if (tj > t) {
            t = tj;
        }
    }
    return t;
}

hv_status_t hv_scara_ik(const hv_arm_t *arm, const hv_pose_t *pose, double q_out[HV_NJOINTS])
{
    if (arm == NULL || pose == NULL || q_out == NULL) {
        return HV_ERR_ARG;
    }
    if (!isfinite(pose->x_m) || !isfinite(pose->y_m) || !isfinite(pose->z_m) ||
        !isfinite(pose->heading_rad)) {
        return HV_ERR_NAN;
    }
    link_geom_t g;
    geom_of(arm, &g);

    double q1 = pose->z_m - arm->base_m[2] - g.ee_z0;
    if (!within(q1, arm->limit[0].min, arm->limit[0].max)) {
        return HV_ERR_UNREACHABLE; /* outside joint 1's vertical stroke */
    }

    /* target in the base frame, then the wrist (joint 4 axis) relative to joint 2 */
    double c = cos(arm->base_yaw_rad), s = sin(arm->base_yaw_rad);
    double dx = pose->x_m - arm->base_m[0], dy = pose->y_m - arm->base_m[1];
    double px = c * dx + s * dy, py = -s * dx + c * dy;
    double phi = pose->heading_rad - arm->base_yaw_rad;
    double wx = px - g.len[2] * cos(phi) - g.j2x;
    double wy = py - g.len[2] * sin(phi) - g.j2y;
    double l2 = g.len[0], l3 = g.len[1];
    double cos_d = (wx * wx + wy * wy - l2 * l2 - l3 * l3) / (2.0 * l2 * l3);
    if (cos_d > 1.0 + 1e-12 || cos_d < -1.0 - 1e-12) {
        return HV_ERR_UNREACHABLE; /* wrist outside the annulus of the two inner links */
    }
    cos_d = cos_d > 1.0 ? 1.0 : (cos_d < -1.0 ? -1.0 : cos_d);
    double delta = acos(cos_d);

    double best_t = HUGE_VAL;
    for (int elbow = 0; elbow < 2; elbow++) {
        double d = elbow == 0 ? delta : -delta; /* heading of link 3 minus link 2 */
        double a2 = atan2(wy, wx) - atan2(l3 * sin(d), l2 + l3 * cos(d));
        double q[HV_NJOINTS];
        q[0] = q1;
        q[1] = wrap_pi(a2 - g.beta[0]);
        q[2] = wrap_pi(d - g.beta[1] + g.beta[0]);
        double q4 = wrap_pi(phi - g.beta[2] - q[1] - q[2]);
        for (int k = -1; k <= 1; k++) { /* joint 4 may exceed half a turn each way */
            q[3] = q4 + 2.0 * HV_PI * k;
            if (!hv_scara_within_limits(arm, q)) {
                continue;
            }
            double t = hv_scara_move_time(arm, arm->home, q);
            if (t >= 0.0 && t < best_t) {
                best_t = t;
                for (int j = 0; j < HV_NJOINTS; j++) {
                    q_out[j] = q[j];
                }
            }
        }
        if (delta == 0.0) {
            break; /* both elbows coincide */
        }
    }
    return best_t < HUGE_VAL ? HV_OK : HV_ERR_JOINT_LIMIT;
}

hv_status_t hv_scara_pick_cost(const hv_arm_t *arm, const hv_pose_t *pose, double *cost_s,
                               double q_out[HV_NJOINTS])
{
    if (cost_s == NULL) {
        return HV_ERR_ARG;
    }
    double q[HV_NJOINTS];
    hv_status_t st = hv_scara_ik(arm, pose, q);
    if (st != HV_OK) {
        return st;
    }
    *cost_s = hv_scara_move_time(arm, arm->home, q);
    if (q_out != NULL) {
        for (int j = 0; j < HV_NJOINTS; j++) {
            q_out[j] = q[j];
        }
    }
    return HV_OK;
}
