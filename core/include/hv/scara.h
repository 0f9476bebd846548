/* SCARA arm model: forward and inverse kinematics, joint limits, pick cost.
 *
 * Frames (see docs/FRAMES.md):
 *   vehicle frame: x lateral (positive towards the RIGHT row), y forward along the row,
 *   z up from the floor, origin on the aisle centre line at the current stop position.
 *   Headings are angles about +z measured from +x towards +y (rad).
 *
 * Joints: q[0] = joint 1, prismatic, vertical (m); q[1..3] = joints 2..4, revolute about z
 * (rad). At zero joints the link origins are those of DESIGN §2 in the arm base frame.
 * The end-effector heading is base_yaw + q2 + q3 + q4 (+ the zero-pose heading of the
 * last link, 0 for the paper's arm).
 */
#ifndef HV_SCARA_H
#define HV_SCARA_H

#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HV_NJOINTS 4

typedef enum hv_side { HV_SIDE_LEFT = 0, HV_SIDE_RIGHT = 1 } hv_side_t;

typedef struct hv_joint_limit {
    double min, max; /* position range (m or rad) */
    double vmax;     /* max speed (m/s or rad/s), > 0 */
    double amax;     /* max acceleration (m/s^2 or rad/s^2), > 0 */
} hv_joint_limit_t;

/* The arm as built and mounted. Everything the IK, the timing and the cost table need. */
typedef struct hv_arm {
    /* link origins at zero joints, arm base frame (m): joint1, joint2, joint3, joint4, ee */
    double origin_m[5][3];
    hv_joint_limit_t limit[HV_NJOINTS];
    double home[HV_NJOINTS]; /* home (collection) pose, joint space */
    /* mount: arm base origin in the vehicle frame (m) and its heading (rad) */
    double base_m[3];
    double base_yaw_rad;
    /* 0: joint 3 keeps its configured range (elbow on one side; the paper's default).
     * 1: the elbow limit is lifted: joint 3 may take [-max, max] and IK considers both
     *    elbow solutions, choosing the one with the shorter move time from home. */
    int elbow_free;
    hv_side_t side;
} hv_arm_t;

typedef struct hv_pose {
    double x_m, y_m, z_m; /* end-effector position, vehicle frame */
    double heading_rad;   /* end-effector approach heading, vehicle frame */
} hv_pose_t;

/* Heading of the inward normal of a side's row: 0 for the right row (+x), pi for the left. */
double hv_side_normal_heading(hv_side_t side);

/* Forward kinematics. Returns HV_ERR_NAN for non-finite joints. Limits are not checked. */
hv_status_t hv_scara_fk(const hv_arm_t *arm, const double q[HV_NJOINTS], hv_pose_t *out);

/* Inverse kinematics: the joint solution for `pose` that lies inside the joint limits.
 * When the arm has elbow_free set, both elbow solutions are tried and the one with the
 * shorter move time from home is returned. Joint 4 is chosen among q4 + k*2pi inside its
 * range. Errors: HV_ERR_NAN, HV_ERR_UNREACHABLE (wrist outside the annulus or z outside
 * joint 1's stroke), HV_ERR_JOINT_LIMIT (geometrically reachable, but not within limits). */
hv_status_t hv_scara_ik(const hv_arm_t *arm, const hv_pose_t *pose, double q_out[HV_NJOINTS]);

/* 1 when every joint lies within its limits (with a 1e-9 tolerance), else 0. */
int hv_scara_within_limits(const hv_arm_t *arm, const double q[HV_NJOINTS]);

/* Time (s) of a rest-to-rest move of one joint over `dist` on a trapezoidal velocity profile,
 * triangular when the distance is too short to reach vmax:
 *   t = 2 sqrt(d/a)       if d <= v^2/a
 *   t = d/v + v/a         otherwise.
 * dist may be negative (its magnitude is used). Returns a negative value for vmax<=0,
 * amax<=0 or non-finite input. */
double hv_trap_time(double dist, double vmax, double amax);
/* The same in single precision, for a target whose FPU has no double (hv/exec_real.h). */
float hv_trap_timef(float dist, float vmax, float amax);

/* Time (s) for all joints moving together from q_from to q_to: the slowest joint's time. */
double hv_scara_move_time(const hv_arm_t *arm, const double q_from[HV_NJOINTS],
                          const double q_to[HV_NJOINTS]);

/* Pick cost G of DESIGN §1: the slowest joint's time (s) from the home pose to the IK
 * solution of `pose`. q_out (optional, may be NULL) receives the solution. */
hv_status_t hv_scara_pick_cost(const hv_arm_t *arm, const hv_pose_t *pose, double *cost_s,
                               double q_out[HV_NJOINTS]);

#ifdef __cplusplus
}
#endif
#endif /* HV_SCARA_H */
