/* Supervision of the nodes (exec_nodes.h). */
#include "exec_nodes.h"

/* the vehicle's own faults (FaultBits): drive, position limit, following error */
#define VEHICLE_FAULTS                                                                             \
    (HV_CAN_VEHICLE_FAULT_DRIVE | HV_CAN_VEHICLE_FAULT_POSITION_LIMIT |                            \
     HV_CAN_VEHICLE_FAULT_FOLLOWING_ERROR)

/* node i's FaultBits bit for an e-stop, and for our heartbeat lost */
static unsigned estop_bit(int i)
{
    return i == HV_EXEC_VEHICLE ? HV_CAN_VEHICLE_FAULT_ESTOP : HV_CAN_ARM_FAULT_ESTOP;
}

static unsigned comm_bit(int i)
{
    return i == HV_EXEC_VEHICLE ? HV_CAN_VEHICLE_FAULT_COMM_TIMEOUT : HV_CAN_ARM_FAULT_COMM_TIMEOUT;
}

static void heartbeat(hv_exec_sm_t *sm, hv_exec_node_t *n, const hv_exec_event_t *ev,
                      uint64_t now_ns)
{
    if (ev->u.hb.protocol != HV_CAN_PROTOCOL_VERSION)
        return; /* another protocol version: treated as absent */
    n->seen = 1;
    n->hb_rx = ++sm->rx;
    n->last_hb_ns = now_ns;
    n->health = ev->u.hb.health;
    n->time_scale = ev->u.hb.time_scale;
}

static void vehicle_status(hv_exec_sm_t *sm, hv_exec_node_t *n, const hv_exec_event_t *ev)
{
    n->status_seen = 1;
    n->st_rx = ++sm->rx;
    n->position_m = ev->u.veh.position_m;
    n->state = ev->u.veh.state;
    n->arrived = ev->u.veh.arrived;
    n->fault_bits = ev->u.veh.fault_bits;
    n->move_seq = ev->u.veh.move_seq;
    n->cmd_seq = ev->u.veh.cmd_seq;
}

static void arm_status(hv_exec_sm_t *sm, hv_exec_node_t *n, const hv_exec_event_t *ev)
{
    n->status_seen = 1;
    n->st_rx = ++sm->rx;
    n->state = ev->u.arm.state;
    n->reached = ev->u.arm.reached;
    n->homed = ev->u.arm.homed;
    n->sp_seq = ev->u.arm.sp_seq;
    n->cmd_seq = ev->u.arm.cmd_seq;
    n->fault_bits = ev->u.arm.fault_bits;
}

static void ee_status(hv_exec_node_t *n, const hv_exec_event_t *ev)
{
    n->ee_seen = 1;
    n->ee_state = ev->u.ee.state;
    n->ee_action = ev->u.ee.action;
    n->ee_seq = ev->u.ee.ee_seq;
    n->fruit_held = ev->u.ee.fruit_held;
}

void exec_nodes_apply(hv_exec_sm_t *sm, const hv_exec_event_t *ev, uint64_t now_ns)
{
    switch (ev->kind) {
    case HV_EV_HEARTBEAT: heartbeat(sm, &sm->node[ev->node], ev, now_ns); break;
    case HV_EV_VEHICLE_STATUS: vehicle_status(sm, &sm->node[ev->node], ev); break;
    case HV_EV_ARM_STATUS: arm_status(sm, &sm->node[ev->node], ev); break;
    case HV_EV_EE_STATUS: ee_status(&sm->node[ev->node], ev); break;
    default: break;
    }
}

int exec_nodes_ready(const hv_exec_sm_t *sm)
{
    for (int i = 0; i < HV_EXEC_NODES; i++) {
        const hv_exec_node_t *n = &sm->node[i];
        if (!n->seen || !n->status_seen || (i != HV_EXEC_VEHICLE && !n->ee_seen))
            return 0;
    }
    return 1;
}

static int same_scale(hv_exec_real_t a, hv_exec_real_t b)
{
    return hv_exec_fabs(a - b) <= HV_EXEC_REAL(0.01) * (a > b ? a : b);
}

static int reports_estop(const hv_exec_sm_t *sm, int i)
{
    const hv_exec_node_t *n = &sm->node[i];
    return n->health == HV_CAN_HEALTH_ESTOP || n->state == HV_CAN_STATE_ESTOP ||
           (n->fault_bits & estop_bit(i));
}

/* The nodes' time scale, the same on all and (when given) the one of params, is ours. */
static int scales_agree(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    hv_exec_real_t ts = sm->node[0].time_scale;
    for (int i = 0; i < HV_EXEC_NODES; i++)
        if (!same_scale(sm->node[i].time_scale, ts) ||
            (sm->prm.time_scale > HV_EXEC_REAL(0.0) &&
             !same_scale(sm->node[i].time_scale, sm->prm.time_scale))) {
            exec_enter_safe(c, HV_SAFE_TIME_SCALE, i);
            return 0;
        }
    sm->time_scale = ts;
    return 1;
}

/* The nodes that report an e-stop now are latched: the operator's to clear, never a
 * restart's. */
static int latch_estops(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    for (int i = 0; i < HV_EXEC_NODES; i++)
        if (reports_estop(sm, i))
            sm->latched |= 1u << i;
    if (sm->latched && !sm->prm.clear_estop) {
        int first = 0;
        while (!(sm->latched & (1u << first)))
            first++;
        exec_enter_safe(c, HV_SAFE_ESTOP_LATCHED, first);
        return 0;
    }
    return 1;
}

int exec_nodes_take(exec_ctx_t *c)
{
    if (!scales_agree(c) || !latch_estops(c))
        return 0;
    for (int i = 0; i < HV_EXEC_NODES; i++) {
        hv_exec_node_t *n = &c->sm->node[i];
        /* continue after what the nodes last accepted: never reuse a seq they echo */
        n->next_cmd_seq = (n->cmd_seq + 1) & 0xFF;
        n->next_sp_seq = (n->sp_seq + 1) & 0x1F;
        n->next_ee_seq = (n->ee_seq + 1) & 0xFF;
        n->next_move_seq = (n->move_seq + 1) & 0xFF;
    }
    return 1;
}

int exec_nodes_fresh(const hv_exec_sm_t *sm, int i)
{
    const hv_exec_node_t *n = &sm->node[i];
    return sm->phase == HV_PH_ENABLE && sm->sub >= HV_EN_FRESH && n->hb_rx > sm->clear_rx &&
           n->st_rx > sm->clear_rx;
}

/* Whether what node i reports about an e-stop counts: not for a latched node while its
 * clear is under way, since its frames from before the clear still say ESTOP. */
static int estop_report_counts(const hv_exec_sm_t *sm, int i)
{
    int clearing = sm->phase == HV_PH_ENABLE && sm->sub <= HV_EN_FRESH;
    return !(clearing && (sm->latched & (1u << i)) && !exec_nodes_fresh(sm, i));
}

/* CLEAR_FAULT reached node i in this run: its comm-timeout bit means us from now on. */
static int fault_cleared(const hv_exec_sm_t *sm, int i)
{
    if (sm->phase != HV_PH_ENABLE)
        return sm->phase > HV_PH_ENABLE;
    return sm->sub == HV_EN_ENABLE || (sm->sub == HV_EN_CLEAR_FAULT && exec_echoed(sm, i));
}

/* SAFE (1) when a node's heartbeat is lost or its time scale is no longer ours. */
static int lost_or_rescaled(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    for (int i = 0; i < HV_EXEC_NODES; i++) {
        const hv_exec_node_t *n = &sm->node[i];
        if (c->now > n->last_hb_ns + hv_exec_real_ns(sm->prm.heartbeat_timeout_s)) {
            exec_enter_safe(c, HV_SAFE_HEARTBEAT, i);
            return 1;
        }
        if (!same_scale(n->time_scale, sm->time_scale)) {
            exec_enter_safe(c, HV_SAFE_TIME_SCALE, i);
            return 1;
        }
    }
    return 0;
}

/* SAFE (1) when a node reports an e-stop that counts, or that it lost our heartbeat. */
static int estop_or_comm(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    for (int i = 0; i < HV_EXEC_NODES; i++) {
        if (estop_report_counts(sm, i) && reports_estop(sm, i)) {
            exec_enter_safe(c, HV_SAFE_ESTOP, i);
            return 1;
        }
        if (fault_cleared(sm, i) && (sm->node[i].fault_bits & comm_bit(i))) {
            exec_enter_safe(c, HV_SAFE_COMM, i);
            return 1;
        }
    }
    return 0;
}

void exec_nodes_check(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    if (sm->phase == HV_PH_WAIT_NODES || lost_or_rescaled(c) || estop_or_comm(c))
        return;
    const hv_exec_node_t *v = &sm->node[HV_EXEC_VEHICLE];
    if (sm->phase >= HV_PH_HOMING &&
        (v->state == HV_CAN_STATE_FAULT || (v->fault_bits & VEHICLE_FAULTS)))
        exec_enter_safe(c, HV_SAFE_VEHICLE_FAULT, HV_EXEC_VEHICLE);
}

/* The node echoed the frame kept for it. */
static int acknowledged(const hv_exec_node_t *n)
{
    const hv_exec_action_t *a = &n->resend;
    switch (a->kind) {
    case HV_ACT_COMMAND: return n->cmd_seq == a->u.cmd.seq;
    case HV_ACT_SETPOINT: return n->sp_seq == a->u.sp.seq;
    case HV_ACT_EE: return n->ee_seen && n->ee_seq == a->u.ee.seq;
    case HV_ACT_MOVE: return n->move_seq == a->u.move.seq;
    default: return 1;
    }
}

void exec_nodes_resend(exec_ctx_t *c)
{
    for (int i = 0; i < HV_EXEC_NODES; i++) {
        hv_exec_node_t *n = &c->sm->node[i];
        if (!n->resend_active)
            continue;
        if (acknowledged(n)) {
            n->resend_active = 0;
        } else if (c->now >= n->resend_ns) {
            hv_exec_action_t *a = exec_push(c, n->resend.kind, i);
            if (a)
                *a = n->resend;
            c->sm->resends++;
            n->resend_ns = c->now + hv_exec_real_ns(c->sm->prm.resend_s);
        }
    }
}
