/* The LCM telemetry sink: executor state -> harvest_*_t messages (lcm_types/). */
#include <lcm/lcm.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harvest_lcm_arm_joint_state_t.h"
#include "harvest_lcm_can_stats_t.h"
#include "harvest_lcm_exec_state_t.h"
#include "harvest_lcm_fruit_event_t.h"
#include "harvest_lcm_plan_t.h"
#include "hv/exec_status.h"
#include "hv/exec_telemetry.h"

static lcm_t *lcm_of(hv_exec_telemetry_t *t)
{
    return (lcm_t *)t->impl;
}

static int pub_plan(hv_exec_telemetry_t *t, const hv_exec_plan_t *plan, const char *path,
                    const hv_exec_params_t *prm, double time_scale, int64_t utime)
{
    /* sent once at the start (and as an online plan grows): arrays of this plan's size, on
     * the heap for the call (the largest plan's would be ~0.5 MB of stack) */
    harvest_lcm_plan_stop_t *stops = calloc(plan->n_stops ? plan->n_stops : 1u, sizeof *stops);
    harvest_lcm_plan_pick_t *picks = calloc(plan->n_picks ? plan->n_picks : 1u, sizeof *picks);
    if (!stops || !picks) {
        free(stops);
        free(picks);
        return -1;
    }
    harvest_lcm_plan_t m;
    memset(&m, 0, sizeof m);
    m.utime = utime;
    m.plan_path = (char *)(path ? path : "");
    m.planned_makespan_s = plan->planned_makespan_s;
    m.expected_makespan_s = plan->expected_makespan_s;
    m.final_drive_s = plan->final_drive_s;
    m.cut_s = prm->cut_s;
    m.release_s = prm->release_s;
    m.time_scale = time_scale;
    m.n_stops = (int16_t)plan->n_stops;
    m.stops = stops;
    for (uint16_t p = 0; p < plan->n_stops; p++) {
        const hv_exec_stop_t *s = &plan->stops[p];
        stops[p].plan_index = (int32_t)s->plan_index;
        stops[p].y_m = s->y_m;
        stops[p].arm_s[0] = s->arm_s[0];
        stops[p].arm_s[1] = s->arm_s[1];
        stops[p].expected_s = s->expected_s;
        stops[p].drive_s = s->drive_s;
    }
    m.n_picks = (int16_t)plan->n_picks;
    m.picks = picks;
    for (uint16_t i = 0; i < plan->n_picks; i++) {
        const hv_exec_pick_t *k = &plan->picks[i];
        harvest_lcm_plan_pick_t *o = &picks[i];
        o->fruit_id = (char *)k->id;
        o->side = (int8_t)k->side;
        o->stop = (int16_t)k->stop;
        o->x_m = k->x_m;
        o->y_m = k->y_m;
        o->z_m = k->z_m;
        o->yaw_rad = k->yaw_rad;
        o->cost_s = k->cost_s;
        o->start_s = k->start_s;
        o->move_s = k->move_s;
        o->cycle_s = k->cycle_s;
        o->reachable = (int8_t)k->reachable;
    }
    int rc = harvest_lcm_plan_t_publish(lcm_of(t), HV_TM_CH_PLAN, &m);
    free(stops);
    free(picks);
    return rc;
}

static int pub_state(hv_exec_telemetry_t *t, const hv_exec_sm_t *sm, const char *planner,
                     uint64_t now_ns, int64_t utime)
{
    harvest_lcm_exec_state_t m;
    memset(&m, 0, sizeof m);
    m.utime = utime;
    m.t_s = hv_exec_executed_s(sm, now_ns);
    m.phase = (char *)hv_exec_phase_name(sm->phase);
    m.safe_reason = (char *)hv_exec_safe_reason_name(sm->safe_reason);
    m.stop = (int16_t)(sm->stop >= 0 && sm->stop < sm->plan->n_stops ? sm->stop : -1);
    m.vehicle_position_m = sm->node[HV_EXEC_VEHICLE].position_m;
    m.arm_phase[0] = (char *)hv_exec_arm_phase_name(sm->arm[0].phase);
    m.arm_phase[1] = (char *)hv_exec_arm_phase_name(sm->arm[1].phase);
    m.picked = (int32_t)sm->picked;
    m.failed = (int32_t)sm->failed;
    m.skipped = (int32_t)sm->skipped;
    m.remaining = (int32_t)hv_exec_remaining(sm);
    m.faults = (int32_t)sm->faults;
    m.executed_s = m.t_s;
    m.expected_makespan_s = sm->plan->expected_makespan_s;
    m.time_scale = sm->time_scale;
    m.planner = (char *)(planner ? planner : "");
    return harvest_lcm_exec_state_t_publish(lcm_of(t), HV_TM_CH_STATE, &m);
}

static const char *const fe_names[] = {"approach", "cut", "return", "release", "outcome", "fault"};

static int pub_fruit(hv_exec_telemetry_t *t, const hv_exec_sm_t *sm, const hv_exec_action_t *a,
                     uint64_t now_ns, int64_t utime)
{
    const hv_exec_pick_t *pk = &sm->plan->picks[a->u.fe.pick];
    harvest_lcm_fruit_event_t m;
    memset(&m, 0, sizeof m);
    m.utime = utime;
    m.t_s = hv_exec_executed_s(sm, now_ns);
    m.fruit_id = (char *)pk->id;
    m.side = (int8_t)pk->side;
    m.stop = (int16_t)pk->stop;
    m.pick = (int16_t)a->u.fe.pick;
    m.event = (char *)fe_names[a->u.fe.kind];
    m.attempt = (int8_t)a->u.fe.attempt;
    m.outcome =
        (char *)(a->u.fe.kind == HV_FE_OUTCOME ? hv_exec_outcome_name(a->u.fe.outcome) : "");
    m.reason = (char *)(a->u.fe.kind == HV_FE_OUTCOME || a->u.fe.kind == HV_FE_FAULT
                            ? hv_exec_reason_name(a->u.fe.reason)
                            : "");
    return harvest_lcm_fruit_event_t_publish(lcm_of(t), HV_TM_CH_FRUIT, &m);
}

static int pub_arm(hv_exec_telemetry_t *t, const hv_exec_sm_t *sm, const hv_exec_arm_sample_t *s,
                   int64_t utime)
{
    const hv_exec_node_t *n = &sm->node[s->side == HV_SIDE_LEFT ? HV_EXEC_LEFT : HV_EXEC_RIGHT];
    harvest_lcm_arm_joint_state_t m;
    memset(&m, 0, sizeof m);
    m.utime = utime;
    m.side = (int8_t)s->side;
    memcpy(m.q, s->q, sizeof m.q);
    memcpy(m.qd, s->qd, sizeof m.qd);
    m.state = (int8_t)n->state;
    m.fault_bits = n->fault_bits;
    m.setpoint_seq = (int8_t)n->sp_seq;
    m.target_reached = (int8_t)n->reached;
    m.homed = (int8_t)n->homed;
    return harvest_lcm_arm_joint_state_t_publish(
        lcm_of(t), s->side == HV_SIDE_LEFT ? HV_TM_CH_ARM_LEFT : HV_TM_CH_ARM_RIGHT, &m);
}

static int pub_can(hv_exec_telemetry_t *t, const hv_exec_bus_stats_t *s, int64_t utime)
{
    harvest_lcm_can_stats_t m;
    memset(&m, 0, sizeof m);
    m.utime = utime;
    m.bus = (char *)(s->bus ? s->bus : "");
    m.tx_frames = (int64_t)s->tx_frames;
    m.rx_frames = (int64_t)s->rx_frames;
    m.rx_error_frames = (int64_t)s->rx_error_frames;
    m.rx_malformed = (int64_t)s->rx_malformed;
    m.rx_unsupported = (int64_t)s->rx_unsupported;
    m.rx_filtered = (int64_t)s->rx_filtered;
    m.rx_kernel_drops = (int64_t)s->rx_kernel_drops;
    m.tx_failures = (int64_t)s->tx_failures;
    return harvest_lcm_can_stats_t_publish(lcm_of(t), HV_TM_CH_CAN_STATS, &m);
}

static void lcm_close(hv_exec_telemetry_t *t)
{
    if (t->impl)
        lcm_destroy(lcm_of(t));
    t->impl = NULL;
}

static const hv_exec_telemetry_ops_t lcm_ops = {pub_plan, pub_state, pub_fruit,
                                                pub_arm,  pub_can,   lcm_close};

hv_status_t hv_exec_telemetry_lcm_open(hv_exec_telemetry_t *t, const char *url, char *err,
                                       size_t errlen)
{
    hv_exec_telemetry_null(t);
    lcm_t *l = lcm_create(url);
    if (!l) {
        snprintf(err, errlen,
                 "LCM: cannot open '%s' (a udpm URL needs a multicast route, "
                 "e.g. `ip route add 224.0.0.0/4 dev lo` in a private namespace)",
                 url ? url : "(default)");
        return HV_ERR_EXEC_TELEMETRY;
    }
    t->ops = &lcm_ops;
    t->impl = l;
    return HV_OK;
}
