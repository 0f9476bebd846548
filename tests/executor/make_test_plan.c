/* make-test-plan: a plan file for the executor's hardware-in-the-loop tests that does not
 * need the planner or cost tables: every fruit is placed by forward kinematics of the
 * configured arm from a random joint vector inside the limits, so the executor's IK
 * reaches it; stops spread over the row; costs are core's pick cost (home -> fruit).
 * Usage: make-test-plan CONFIG OUT.json STOPS PER_ARM SEED */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "hv/config.h"
#include "hv/file_io.h"

static double uniform(unsigned *s, double lo, double hi)
{
    *s = *s * 1103515245u + 12345u; /* a small LCG: reproducible across libcs */
    return lo + (hi - lo) * (double)((*s >> 8) & 0xFFFFu) / 65535.0;
}

int main(int argc, char **argv)
{
    if (argc != 6) {
        fprintf(stderr, "usage: make-test-plan CONFIG OUT.json STOPS PER_ARM SEED\n");
        return 2;
    }
    hv_config_t cfg;
    char err[256];
    if (hv_config_load(argv[1], &cfg, err, sizeof err) != HV_OK) {
        fprintf(stderr, "make-test-plan: %s\n", err);
        return 1;
    }
    int stops = atoi(argv[3]), per = atoi(argv[4]);
    unsigned seed = (unsigned)atoi(argv[5]) * 2654435761u + 1u;
    if (stops < 1 || stops > 50 || per < 0 || per > 50) {
        fprintf(stderr, "make-test-plan: STOPS in 1..50, PER_ARM in 0..50\n");
        return 2;
    }
    FILE *f = fopen(argv[2], "w");
    if (!f) {
        perror(argv[2]);
        return 1;
    }
    hv_arm_t arm[2];
    hv_config_arm(&cfg, HV_SIDE_LEFT, &arm[0]);
    hv_config_arm(&cfg, HV_SIDE_RIGHT, &arm[1]);
    double len = cfg.row_length_m, pick_total = 0.0, stop_total = 0.0;
    fprintf(f,
            "{\"format\": \"harvest-plan\", \"version\": 2, \"method\": \"fov\",\n"
            " \"inputs\": {\"fruit_map\": \"(make-test-plan)\", \"cost_table_left\": \"\","
            " \"cost_table_right\": \"\", \"config\": \"%s\"},\n"
            " \"params\": {\"stop_step_m\": %.3f, \"row_start_m\": 0.0, \"row_length_m\": %.3f,"
            " \"stop_penalty_s\": %.3f, \"vehicle_speed_mps\": %.3f, \"travel_time_s\": %.3f, "
            "\"stop_margin_m\": 0.0,"
            " \"pick_time\": \"one_way\"},\n"
            " \"solver\": {\"status\": \"heuristic\", \"gap\": 0, \"nodes\": 0, \"runtime_s\": 0,"
            " \"time_limit_s\": 0},\n \"stops\": [\n",
            argv[1], cfg.grid_step_m, len, cfg.stop_penalty_s, cfg.vehicle_speed_mps,
            len / cfg.vehicle_speed_mps);
    int id = 0;
    for (int p = 0; p < stops; p++) {
        double y = len * (p + 0.5) / stops;
        double c[2] = {0, 0};
        fprintf(f, "  {\"index\": %d, \"y_m\": %.4f, \"pass\": 0,",
                (int)lround(y / cfg.grid_step_m), y);
        char buf[2][8192];
        int used[2] = {0, 0};
        for (int s = 0; s < 2; s++) {
            double start = 0.0;
            used[s] += snprintf(buf[s] + used[s], sizeof buf[s] - (size_t)used[s], "[");
            for (int k = 0; k < per; k++) {
                double q[4];
                for (int j = 0; j < 4; j++) {
                    const hv_joint_limit_t *l = &arm[s].limit[j];
                    /* within 70 % of the range around home: clear of the limits */
                    double h = arm[s].home[j], lo = h - 0.35 * (h - l->min),
                           hi = h + 0.35 * (l->max - h);
                    q[j] = uniform(&seed, lo, hi);
                }
                hv_pose_t pose;
                hv_scara_fk(&arm[s], q, &pose);
                double cost;
                if (hv_scara_pick_cost(&arm[s], &pose, &cost, NULL) != HV_OK) {
                    k--; /* the IK picked another solution outside the limits: draw again */
                    continue;
                }
                double yaw = pose.heading_rad - hv_side_normal_heading((hv_side_t)s);
                yaw = atan2(sin(yaw), cos(yaw));
                used[s] += snprintf(
                    buf[s] + used[s], sizeof buf[s] - (size_t)used[s],
                    "%s{\"id\": \"%d\", \"x\": %.6f, \"y\": %.6f, \"z\": %.6f, \"yaw\": %.6f,"
                    " \"cost_s\": %.6f, \"start_s\": %.6f}",
                    k ? ", " : "", id++, pose.x_m, pose.y_m + y, pose.z_m, yaw, cost, start);
                start += cost;
            }
            c[s] = start;
            used[s] += snprintf(buf[s] + used[s], sizeof buf[s] - (size_t)used[s], "]");
        }
        double cp = c[0] > c[1] ? c[0] : c[1];
        pick_total += cp;
        stop_total += cfg.stop_penalty_s;
        fprintf(f,
                " \"C_left_s\": %.6f, \"C_right_s\": %.6f, \"C_s\": %.6f, \"idle_left_s\": %.6f,"
                " \"idle_right_s\": %.6f,\n   \"left\": %s,\n   \"right\": %s}%s\n",
                c[0], c[1], cp, cp - c[0], cp - c[1], buf[0], buf[1], p + 1 < stops ? "," : "");
    }
    double travel = len / cfg.vehicle_speed_mps, T = pick_total + stop_total + travel;
    fprintf(f,
            " ],\n \"totals\": {\"makespan_s\": %.6f, \"pick_time_s\": %.6f, \"stop_time_s\": %.6f,"
            " \"travel_time_s\": %.6f, \"stops\": %d, \"fruits_planned\": %d,"
            " \"fruits_unreachable\": 0, \"throughput_fruit_per_s\": %.6f},\n"
            " \"unreachable\": []}\n",
            T, pick_total, stop_total, travel, stops, id, id / T);
    if (fclose(f) != 0) {
        perror(argv[2]);
        return 1;
    }
    return 0;
}
