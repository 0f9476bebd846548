/* Completing a loaded plan: IK setpoints and the executor's expected times. */
#include "hv/exec_plan.h"

#include <math.h>
#include <string.h>

#include "hv/exec_status.h"
#include "hv/pick.h"

double hv_exec_vehicle_move_s(double dist_m, double speed_mps, double accel_mps2)
{
    /* the same trapezoid as a joint: the drive is one more axis with speed/accel limits */
    return hv_trap_time(dist_m, speed_mps, accel_mps2);
}

static int timing_ok(const hv_exec_timing_t *t)
{
    return t->cut_s > 0.0 && isfinite(t->cut_s) && t->release_s > 0.0 &&
           isfinite(t->release_s) && t->vehicle_speed_mps > 0.0 &&
           isfinite(t->vehicle_speed_mps) && t->vehicle_accel_mps2 > 0.0 &&
           isfinite(t->vehicle_accel_mps2);
}

hv_status_t hv_exec_plan_prepare(hv_exec_plan_t *plan, const hv_arm_t arm[2],
                                 const hv_exec_timing_t *timing)
{
    if (!plan || !arm || !timing || plan->n_stops > HV_EXEC_MAX_STOPS ||
        plan->n_picks > HV_EXEC_MAX_PICKS)
        return HV_ERR_ARG;
    if (!timing_ok(timing))
        return HV_ERR_EXEC_PARAMS;
    for (int s = 0; s < 2; s++)
        memcpy(plan->home[s], arm[s].home, sizeof plan->home[s]);

    plan->n_unreachable = 0;
    for (uint16_t i = 0; i < plan->n_picks; i++) {
        hv_exec_pick_t *pk = &plan->picks[i];
        if (pk->stop >= plan->n_stops || (pk->side != HV_SIDE_LEFT && pk->side != HV_SIDE_RIGHT))
            return HV_ERR_ARG;
        const hv_arm_t *a = &arm[pk->side];
        pk->ik_status = hv_pick_solve(a, pk->x_m, pk->y_m - plan->stops[pk->stop].y_m, pk->z_m,
                                      pk->yaw_rad, pk->q, &pk->move_s, NULL);
        pk->reachable = pk->ik_status == HV_OK;
        if (pk->reachable) {
            /* return home is the same distances reversed: the same time */
            pk->cycle_s = 2.0 * pk->move_s + timing->cut_s + timing->release_s;
        } else {
            memcpy(pk->q, a->home, sizeof pk->q);
            pk->move_s = 0.0;
            pk->cycle_s = 0.0;
            plan->n_unreachable++;
        }
    }

    double total = 0.0, y_prev = hv_exec_course_start(plan);
    for (uint16_t p = 0; p < plan->n_stops; p++) {
        hv_exec_stop_t *st = &plan->stops[p];
        for (int s = 0; s < 2; s++) {
            if ((unsigned)st->first[s] + st->count[s] > plan->n_picks)
                return HV_ERR_ARG;
            st->arm_s[s] = 0.0;
            for (uint16_t k = 0; k < st->count[s]; k++)
                st->arm_s[s] += plan->picks[st->first[s] + k].cycle_s;
        }
        st->expected_s = st->arm_s[0] > st->arm_s[1] ? st->arm_s[0] : st->arm_s[1];
        st->drive_s = hv_exec_vehicle_move_s(st->y_m - y_prev, timing->vehicle_speed_mps,
                                             timing->vehicle_accel_mps2);
        y_prev = st->y_m;
        total += st->expected_s + st->drive_s;
    }
    double end = hv_exec_course_end(plan);
    plan->final_drive_s = end > y_prev
                              ? hv_exec_vehicle_move_s(end - y_prev, timing->vehicle_speed_mps,
                                                       timing->vehicle_accel_mps2)
                              : 0.0;
    plan->expected_makespan_s = total + plan->final_drive_s;
    return HV_OK;
}

double hv_exec_course_start(const hv_exec_plan_t *plan)
{
    return plan->row_start_m - plan->stop_margin_m;
}

double hv_exec_course_end(const hv_exec_plan_t *plan)
{
    return plan->row_start_m + plan->row_length_m + plan->stop_margin_m;
}

int hv_exec_plan_find(const hv_exec_plan_t *plan, hv_side_t side, const char *id)
{
    for (uint16_t i = 0; i < plan->n_picks; i++)
        if (plan->picks[i].side == side && strcmp(plan->picks[i].id, id) == 0)
            return i;
    return -1;
}
