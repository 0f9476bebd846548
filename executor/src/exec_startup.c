/* The run's start-up (exec_startup.h). */
#include "exec_startup.h"

#include "exec_nodes.h"

/* Enter a start-up step: each has the command timeout to be answered. */
static void enable_step(exec_ctx_t *c, hv_exec_enable_step_t sub)
{
    c->sm->sub = sub;
    c->sm->deadline_ns = exec_command_deadline(c);
}

static void wait_nodes(exec_ctx_t *c)
{
    if (exec_nodes_ready(c->sm)) {
        if (!exec_nodes_take(c))
            return;
        exec_send_to(c, HV_EXEC_ALL_NODES, HV_CAN_CMD_DISABLE);
        enable_step(c, HV_EN_DISABLE);
        exec_set_phase(c, HV_PH_ENABLE);
    } else if (c->now >= c->sm->deadline_ns) {
        exec_enter_safe(c, HV_SAFE_NODES_ABSENT, -1);
    }
}

/* The first of `nodes` that has not echoed its command (in the ENABLE step, IDLE too), or
 * -1 when all have. */
static int first_pending(const hv_exec_sm_t *sm, unsigned nodes)
{
    for (int i = 0; i < HV_EXEC_NODES; i++)
        if ((nodes & (1u << i)) &&
            (!exec_echoed(sm, i) ||
             (sm->sub == HV_EN_ENABLE && sm->node[i].state != HV_CAN_STATE_IDLE)))
            return i;
    return -1;
}

/* The steps of ENABLE: each returns the node it still waits for, or -1 once it moved on
 * (or went SAFE). */

static int disabled(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    int waiting = first_pending(sm, HV_EXEC_ALL_NODES);
    if (waiting >= 0)
        return waiting;
    if (sm->latched) {
        /* the record first: the clear is the operator's, and must be on disk before a node
         * acts on it */
        hv_exec_action_t *a = exec_journal(c, HV_JR_ESTOP_CLEAR, -1, -1, 0, 0, 0);
        if (a)
            a->u.jr.nodes = sm->latched;
        exec_send_to(c, sm->latched, HV_CAN_CMD_CLEAR_ESTOP);
        enable_step(c, HV_EN_CLEAR_ESTOP);
    } else {
        exec_send_to(c, HV_EXEC_ALL_NODES, HV_CAN_CMD_CLEAR_FAULT);
        enable_step(c, HV_EN_CLEAR_FAULT);
    }
    return -1;
}

static int estop_cleared(exec_ctx_t *c)
{
    int waiting = first_pending(c->sm, c->sm->latched);
    if (waiting >= 0)
        return waiting;
    c->sm->clear_rx = c->sm->rx;
    enable_step(c, HV_EN_FRESH);
    return -1;
}

static int all_fresh(exec_ctx_t *c)
{
    for (int i = 0; i < HV_EXEC_NODES; i++)
        if (!exec_nodes_fresh(c->sm, i))
            return i;
    /* every node spoke after the clear and none reports an e-stop (exec_nodes_check) */
    exec_send_to(c, HV_EXEC_ALL_NODES, HV_CAN_CMD_CLEAR_FAULT);
    enable_step(c, HV_EN_CLEAR_FAULT);
    return -1;
}

static int faults_cleared(exec_ctx_t *c)
{
    int waiting = first_pending(c->sm, HV_EXEC_ALL_NODES);
    if (waiting >= 0)
        return waiting;
    exec_send_to(c, HV_EXEC_ALL_NODES, HV_CAN_CMD_ENABLE);
    enable_step(c, HV_EN_ENABLE);
    return -1;
}

static int enabled(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    for (int i = 0; i < HV_EXEC_NODES; i++)
        if (exec_echoed(sm, i) && sm->node[i].state == HV_CAN_STATE_FAULT) {
            exec_enter_safe(c, HV_SAFE_FAULT, i);
            return -1;
        }
    int waiting = first_pending(sm, HV_EXEC_ALL_NODES);
    if (waiting >= 0)
        return waiting;
    for (int s = 0; s < 2; s++)
        exec_send_command(c, exec_arm_node(s), HV_CAN_CMD_HOME);
    sm->node[HV_EXEC_VEHICLE].wait_cmd_seq = -1;
    sm->deadline_ns = exec_motion_deadline(c, sm->prm.home_max_s);
    exec_set_phase(c, HV_PH_HOMING);
    return -1;
}

static void enable(exec_ctx_t *c)
{
    int waiting;
    switch (c->sm->sub) {
    case HV_EN_DISABLE: waiting = disabled(c); break;
    case HV_EN_CLEAR_ESTOP: waiting = estop_cleared(c); break;
    case HV_EN_FRESH: waiting = all_fresh(c); break;
    case HV_EN_CLEAR_FAULT: waiting = faults_cleared(c); break;
    default: waiting = enabled(c); break;
    }
    if (waiting >= 0 && c->now >= c->sm->deadline_ns)
        exec_enter_safe(c, HV_SAFE_TIMEOUT, waiting);
}

/* 1 once both arms echoed HOME and stand homed and idle. */
static int homing(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    int done = 1;
    for (int s = 0; s < 2; s++) {
        int node = exec_arm_node(s);
        const hv_exec_node_t *n = &sm->node[node];
        if (exec_echoed(sm, node) && (n->state == HV_CAN_STATE_FAULT || n->fault_bits)) {
            exec_enter_safe(c, HV_SAFE_FAULT, node);
            return 0;
        }
        done &= exec_echoed(sm, node) && n->state == HV_CAN_STATE_IDLE && n->homed;
    }
    if (done) {
        for (int s = 0; s < 2; s++)
            sm->node[exec_arm_node(s)].wait_cmd_seq = -1;
        return 1;
    }
    if (c->now >= sm->deadline_ns)
        exec_enter_safe(c, HV_SAFE_TIMEOUT, -1);
    return 0;
}

int exec_startup_step(exec_ctx_t *c)
{
    switch (c->sm->phase) {
    case HV_PH_WAIT_NODES: wait_nodes(c); return 0;
    case HV_PH_ENABLE: enable(c); return 0;
    case HV_PH_HOMING: return homing(c);
    default: return 0;
    }
}
