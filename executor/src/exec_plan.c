/* Completing a loaded plan: IK setpoints and the executor's expected times. */
#include "hv/exec_plan.h"

#include <math.h>
#include <string.h>

#include "hv/exec_status.h"
#include "hv/pick.h"

hv_exec_real_t hv_exec_vehicle_move_s(hv_exec_real_t dist_m, hv_exec_real_t speed_mps,
                                      hv_exec_real_t accel_mps2)
{
    /* the same trapezoid as a joint: the drive is one more axis with speed/accel limits */
    return hv_exec_trap_time(dist_m, speed_mps, accel_mps2);
}

static int timing_ok(const hv_exec_timing_t *t)
{
    return t->cut_s > 0.0 && isfinite(t->cut_s) && t->release_s > 0.0 && isfinite(t->release_s) &&
           t->vehicle_speed_mps > 0.0 && isfinite(t->vehicle_speed_mps) &&
           t->vehicle_accel_mps2 > 0.0 && isfinite(t->vehicle_accel_mps2);
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
        for (int j = 0; j < HV_NJOINTS; j++)
            plan->home[s][j] = (hv_exec_real_t)arm[s].home[j];

    plan->n_unreachable = 0;
    for (uint16_t i = 0; i < plan->n_picks; i++) {
        hv_exec_pick_t *pk = &plan->picks[i];
        if (pk->stop >= plan->n_stops || (pk->side != HV_SIDE_LEFT && pk->side != HV_SIDE_RIGHT))
            return HV_ERR_ARG;
        const hv_arm_t *a = &arm[pk->side];
        /* solved in double, kept in the executor's real type (hv/exec_real.h) */
        double q[HV_NJOINTS], move_s = 0.0;
        pk->ik_status = hv_pick_solve(a, pk->x_m, pk->y_m - (double)plan->stops[pk->stop].y_m,
                                      pk->z_m, pk->yaw_rad, q, &move_s, NULL);
        pk->reachable = pk->ik_status == HV_OK;
        if (pk->reachable) {
            /* return home is the same distances reversed: the same time */
            pk->cycle_s = 2.0 * move_s + timing->cut_s + timing->release_s;
        } else {
            memcpy(q, a->home, sizeof q);
            move_s = 0.0;
            pk->cycle_s = 0.0;
            plan->n_unreachable++;
        }
        for (int j = 0; j < HV_NJOINTS; j++)
            pk->q[j] = (hv_exec_real_t)q[j];
        pk->move_s = (hv_exec_real_t)move_s;
    }

    double total = 0.0, y_prev = (double)hv_exec_course_start(plan);
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
        st->drive_s = hv_trap_time((double)st->y_m - y_prev, timing->vehicle_speed_mps,
                                   timing->vehicle_accel_mps2);
        y_prev = (double)st->y_m;
        total += st->expected_s + st->drive_s;
    }
    double end = (double)hv_exec_course_end(plan);
    plan->final_drive_s = end > y_prev ? hv_trap_time(end - y_prev, timing->vehicle_speed_mps,
                                                      timing->vehicle_accel_mps2)
                                       : 0.0;
    plan->expected_makespan_s = total + plan->final_drive_s;
    return HV_OK;
}

hv_exec_real_t hv_exec_course_start(const hv_exec_plan_t *plan)
{
    return plan->row_start_m - plan->stop_margin_m;
}

hv_exec_real_t hv_exec_course_end(const hv_exec_plan_t *plan)
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

hv_status_t hv_exec_plan_append(hv_exec_plan_t *plan, uint32_t plan_index, hv_exec_real_t y_m,
                                const hv_exec_pick_t *picks, uint16_t n_left, uint16_t n_right)
{
    if (!plan || (!picks && n_left + n_right > 0))
        return HV_ERR_ARG;
    unsigned n = (unsigned)n_left + n_right;
    if (plan->n_stops >= HV_EXEC_MAX_STOPS || plan->n_picks + n > HV_EXEC_MAX_PICKS)
        return HV_ERR_EXEC_PLAN_CAPACITY;
    const hv_exec_stop_t *last = plan->n_stops ? &plan->stops[plan->n_stops - 1] : NULL;
    if (!isfinite(y_m) || y_m < hv_exec_course_start(plan) - HV_EXEC_REAL(1e-6) ||
        y_m > hv_exec_course_end(plan) + HV_EXEC_REAL(1e-6) ||
        (last && (plan_index <= last->plan_index || y_m <= last->y_m)))
        return HV_ERR_EXEC_PLAN_RANGE;
    for (unsigned k = 0; k < n; k++) {
        hv_side_t side = k < n_left ? HV_SIDE_LEFT : HV_SIDE_RIGHT;
        if (picks[k].side != side || memchr(picks[k].id, '\0', sizeof picks[k].id) == NULL ||
            hv_exec_plan_find(plan, side, picks[k].id) >= 0)
            return HV_ERR_EXEC_PLAN_RANGE;
        for (unsigned j = 0; j < k; j++)
            if (picks[j].side == side && strcmp(picks[j].id, picks[k].id) == 0)
                return HV_ERR_EXEC_PLAN_RANGE;
    }
    uint16_t s = plan->n_stops;
    hv_exec_stop_t *st = &plan->stops[s];
    memset(st, 0, sizeof *st);
    st->plan_index = plan_index;
    st->y_m = y_m;
    st->first[HV_SIDE_LEFT] = plan->n_picks;
    st->count[HV_SIDE_LEFT] = n_left;
    st->first[HV_SIDE_RIGHT] = (uint16_t)(plan->n_picks + n_left);
    st->count[HV_SIDE_RIGHT] = n_right;
    for (unsigned k = 0; k < n; k++) {
        hv_exec_pick_t *pk = &plan->picks[plan->n_picks++];
        memset(pk, 0, sizeof *pk);
        memcpy(pk->id, picks[k].id, sizeof pk->id);
        pk->side = picks[k].side;
        pk->stop = s;
        pk->x_m = picks[k].x_m;
        pk->y_m = picks[k].y_m;
        pk->z_m = picks[k].z_m;
        pk->yaw_rad = picks[k].yaw_rad;
        pk->cost_s = picks[k].cost_s;
        pk->start_s = picks[k].start_s;
    }
    plan->n_stops = (uint16_t)(s + 1);
    return HV_OK;
}

int hv_exec_plan_stop_matches(const hv_exec_plan_t *plan, uint16_t s, uint32_t plan_index,
                              hv_exec_real_t y_m, const hv_exec_pick_t *picks, uint16_t n_left,
                              uint16_t n_right)
{
    if (!plan || s >= plan->n_stops || (!picks && n_left + n_right > 0))
        return 0;
    const hv_exec_stop_t *st = &plan->stops[s];
    if (st->plan_index != plan_index || !(hv_exec_fabs(st->y_m - y_m) <= HV_EXEC_REAL(1e-9)) ||
        st->count[HV_SIDE_LEFT] != n_left || st->count[HV_SIDE_RIGHT] != n_right)
        return 0;
    for (unsigned k = 0; k < (unsigned)n_left + n_right; k++) {
        int side = k < n_left ? HV_SIDE_LEFT : HV_SIDE_RIGHT;
        const hv_exec_pick_t *pk =
            &plan->picks[st->first[side] + (side == HV_SIDE_LEFT ? k : k - n_left)];
        if (picks[k].side != (hv_side_t)side || strncmp(pk->id, picks[k].id, sizeof pk->id) != 0)
            return 0;
    }
    return 1;
}
