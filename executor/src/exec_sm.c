/* The executor's pure step function (hv/exec_sm.h has the run and its faults): the event
 * checked and taken, then the room of the run's phase (exec_startup, exec_run) after the
 * supervision of the nodes (exec_nodes), the frames not yet acknowledged sent again, our
 * heartbeat when due. */
#include "hv/exec_sm.h"

#include <math.h>
#include <string.h>

#include "exec_ctx.h"
#include "exec_nodes.h"
#include "exec_params.h"
#include "exec_run.h"
#include "exec_startup.h"
#include "hv/exec_status.h"

hv_status_t hv_exec_init(hv_exec_sm_t *sm, const hv_exec_plan_t *plan,
                         const hv_exec_params_t *params, const hv_exec_progress_t *progress)
{
    if (!sm || !plan || !params)
        return HV_ERR_ARG;
    if (!exec_params_ok(params))
        return HV_ERR_EXEC_PARAMS;
    memset(sm, 0, sizeof *sm);
    sm->plan = plan;
    sm->prm = *params;
    if (progress)
        sm->prog = *progress;
    sm->phase = HV_PH_WAIT_NODES;
    sm->safe_node = -1;
    sm->stop = -1;
    sm->time_scale =
        params->time_scale > HV_EXEC_REAL(0.0) ? params->time_scale : HV_EXEC_REAL(1.0);
    for (int n = 0; n < HV_EXEC_NODES; n++)
        sm->node[n].wait_cmd_seq = -1;
    for (int s = 0; s < 2; s++)
        sm->arm[s].pick = -1;
    return HV_OK;
}

/* The event is in its domain (its kind, node and values). */
static int event_ok(const hv_exec_event_t *ev)
{
    switch (ev->kind) {
    case HV_EV_TICK:
    case HV_EV_JOURNAL_FAILED: return 1;
    case HV_EV_STOP_REQUEST: return ev->u.stop.from_bus == 0 || ev->u.stop.from_bus == 1;
    case HV_EV_PLAN_GROWN:
        return (ev->u.plan.final == 0 || ev->u.plan.final == 1) && isfinite(ev->u.plan.advance_m);
    case HV_EV_HEARTBEAT:
        return ev->node >= 0 && ev->node < HV_EXEC_NODES && isfinite(ev->u.hb.time_scale);
    case HV_EV_VEHICLE_STATUS: return ev->node == HV_EXEC_VEHICLE && isfinite(ev->u.veh.position_m);
    case HV_EV_ARM_STATUS:
    case HV_EV_EE_STATUS: return ev->node == HV_EXEC_LEFT || ev->node == HV_EXEC_RIGHT;
    }
    return 0;
}

/* The first step starts the clocks: the start-up's deadline, our first heartbeat now. */
static void first_step(hv_exec_sm_t *sm, uint64_t now_ns)
{
    sm->advance_m = hv_exec_course_start(sm->plan);
    sm->started = 1;
    sm->t_start_ns = now_ns;
    sm->deadline_ns = now_ns + hv_exec_real_ns(sm->prm.startup_timeout_s);
    sm->next_hb_ns = now_ns;
}

static int finished_phase(hv_exec_phase_t ph)
{
    return ph == HV_PH_SAFE || ph == HV_PH_ROW_DONE || ph == HV_PH_STOPPED;
}

/* The room of the phase: start-up until homed, then the stops. */
static void phase_logic(exec_ctx_t *c, const hv_exec_event_t *ev)
{
    switch (c->sm->phase) {
    case HV_PH_WAIT_NODES:
    case HV_PH_ENABLE:
    case HV_PH_HOMING:
        if (exec_startup_step(c))
            exec_run_next_stop(c);
        break;
    case HV_PH_DRIVING:
    case HV_PH_FINAL_DRIVE:
    case HV_PH_WAIT_PLAN:
    case HV_PH_HARVEST: exec_run_step(c, ev); break;
    default: break;
    }
}

/* A run that has not ended: the event's own business, the nodes' supervision, the phase,
 * the resends. */
static void running(exec_ctx_t *c, const hv_exec_event_t *ev)
{
    hv_exec_sm_t *sm = c->sm;
    if (ev->kind == HV_EV_STOP_REQUEST)
        exec_run_request_stop(c, ev);
    else if (ev->kind == HV_EV_JOURNAL_FAILED)
        exec_enter_safe(c, HV_SAFE_JOURNAL, -1);
    else
        exec_nodes_check(c);
    if (sm->phase != HV_PH_SAFE && sm->phase != HV_PH_STOPPED)
        phase_logic(c, ev);
    if (!finished_phase(sm->phase))
        exec_nodes_resend(c);
}

/* Our heartbeat every heartbeat_period_s, in SAFE with the e-stop frame (the DBC's
 * repetition); after a long gap the next one period from now, not a burst to catch up. */
static void heartbeat_when_due(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    if (c->now < sm->next_hb_ns)
        return;
    if (sm->phase == HV_PH_SAFE)
        exec_push(c, HV_ACT_ESTOP, -1);
    exec_heartbeat(c);
    sm->next_hb_ns += hv_exec_real_ns(sm->prm.heartbeat_period_s);
    if (sm->next_hb_ns <= c->now)
        sm->next_hb_ns = c->now + hv_exec_real_ns(sm->prm.heartbeat_period_s);
}

/* The actions did not fit: cannot happen with the bounded work of one step; if it does,
 * nothing of it is carried out but the e-stop and a heartbeat, and the machine is SAFE. */
static hv_status_t overflowed(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    c->out->n = 0;
    c->overflow = 0;
    if (sm->phase != HV_PH_SAFE) {
        sm->phase = HV_PH_SAFE;
        sm->safe_reason = HV_SAFE_FAULT;
        sm->safe_node = -1;
    }
    exec_push(c, HV_ACT_ESTOP, -1);
    exec_heartbeat(c);
    return HV_ERR_EXEC_ACTIONS_FULL;
}

hv_status_t hv_exec_step(hv_exec_sm_t *sm, const hv_exec_event_t *ev, uint64_t now_ns,
                         hv_exec_actions_t *out)
{
    if (!sm || !ev || !out || out->n > HV_EXEC_MAX_ACTIONS)
        return HV_ERR_ARG;
    if (!event_ok(ev))
        return HV_ERR_EXEC_EVENT;
    exec_ctx_t c = {sm, now_ns, out, 0};
    if (!sm->started)
        first_step(sm, now_ns);
    if (ev->kind == HV_EV_PLAN_GROWN)
        exec_run_plan_grown(sm, ev);
    else
        exec_nodes_apply(sm, ev, now_ns);
    if (!finished_phase(sm->phase))
        running(&c, ev);
    heartbeat_when_due(&c);
    return c.overflow ? overflowed(&c) : HV_OK;
}

hv_exec_real_t hv_exec_executed_s(const hv_exec_sm_t *sm, uint64_t now_ns)
{
    if (sm->t_row_start_ns == 0)
        return HV_EXEC_REAL(0.0);
    uint64_t end = sm->t_row_end_ns ? sm->t_row_end_ns : now_ns;
    return hv_exec_ns_real(end - sm->t_row_start_ns) * sm->time_scale;
}

void hv_exec_plan_wait_s(const hv_exec_sm_t *sm, uint64_t now_ns, hv_exec_real_t *first_s,
                         hv_exec_real_t *row_s)
{
    uint64_t first = sm->wait_first_ns, row = sm->wait_row_ns;
    if (sm->phase == HV_PH_WAIT_PLAN && now_ns > sm->wait_from_ns) {
        if (sm->wait_first)
            first += now_ns - sm->wait_from_ns;
        else
            row += now_ns - sm->wait_from_ns;
    }
    *first_s = hv_exec_ns_real(first) * sm->time_scale;
    *row_s = hv_exec_ns_real(row) * sm->time_scale;
}

int hv_exec_finished(const hv_exec_sm_t *sm)
{
    return finished_phase(sm->phase);
}

const char *hv_exec_phase_name(int phase)
{
    static const char *const names[HV_PH_COUNT] = {
        "wait_nodes",  "enable",   "homing", "driving",   "harvest",
        "final_drive", "row_done", "safe",   "wait_plan", "stopped"};
    return phase >= 0 && phase < HV_PH_COUNT ? names[phase] : "unknown";
}

const char *hv_exec_arm_phase_name(int phase)
{
    static const char *const names[HV_ARM_PHASE_COUNT] = {"idle",    "approach", "cut", "return",
                                                          "release", "recover",  "done"};
    return phase >= 0 && phase < HV_ARM_PHASE_COUNT ? names[phase] : "unknown";
}

const char *hv_exec_safe_reason_name(int reason)
{
    static const char *const names[HV_SAFE_COUNT] = {
        "none",          "estop",         "lost_heartbeat", "nodes_absent", "time_scale_mismatch",
        "comm_timeout",  "vehicle_fault", "timeout",        "fault",        "journal_failed",
        "operator_stop", "estop_latched"};
    return reason >= 0 && reason < HV_SAFE_COUNT ? names[reason] : "unknown";
}

const char *hv_exec_node_name(int node)
{
    static const char *const names[HV_EXEC_NODES] = {
        HV_CAN_NODE_VEHICLE_NAME, HV_CAN_NODE_LEFT_ARM_NAME, HV_CAN_NODE_RIGHT_ARM_NAME};
    if (node == -1)
        return "none";
    return node >= 0 && node < HV_EXEC_NODES ? names[node] : "unknown";
}

hv_status_t hv_exec_node_list(unsigned nodes, char *buf, size_t len)
{
    if (!buf || len == 0 || (nodes >> HV_EXEC_NODES))
        return HV_ERR_ARG;
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; i < HV_EXEC_NODES; i++) {
        if (!(nodes & (1u << i)))
            continue;
        const char *name = hv_exec_node_name(i);
        size_t need = strlen(name) + (used ? 1 : 0);
        if (used + need >= len)
            return HV_ERR_ARG;
        if (used)
            buf[used++] = ',';
        memcpy(buf + used, name, strlen(name) + 1);
        used += strlen(name);
    }
    return HV_OK;
}
