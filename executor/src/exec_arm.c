/* One arm's pick cycle (exec_arm.h). */
#include "exec_arm.h"

#include <string.h>

/* an arm's joint faults (FaultBits): any joint at its limit or behind its setpoint (stall) */
#define ARM_FAULT_JOINTS                                                                           \
    (HV_CAN_ARM_FAULT_JOINT1_LIMIT | HV_CAN_ARM_FAULT_JOINT2_LIMIT |                               \
     HV_CAN_ARM_FAULT_JOINT3_LIMIT | HV_CAN_ARM_FAULT_JOINT4_LIMIT |                               \
     HV_CAN_ARM_FAULT_JOINT1_FOLLOWING_ERROR | HV_CAN_ARM_FAULT_JOINT2_FOLLOWING_ERROR |           \
     HV_CAN_ARM_FAULT_JOINT3_FOLLOWING_ERROR | HV_CAN_ARM_FAULT_JOINT4_FOLLOWING_ERROR)

static void send_setpoint(exec_ctx_t *c, int side, const hv_exec_real_t q[HV_NJOINTS])
{
    int node = exec_arm_node(side);
    hv_exec_node_t *n = &c->sm->node[node];
    int seq = n->next_sp_seq;
    n->next_sp_seq = (seq + 1) & 0x1F;
    c->sm->arm[side].sp_seq = seq;
    hv_exec_action_t *a = exec_push(c, HV_ACT_SETPOINT, node);
    if (a) {
        memcpy(a->u.sp.q, q, sizeof a->u.sp.q);
        a->u.sp.seq = seq;
    }
    exec_remember(c, node, a);
}

static void send_ee(exec_ctx_t *c, int side, int action)
{
    int node = exec_arm_node(side);
    hv_exec_node_t *n = &c->sm->node[node];
    int seq = n->next_ee_seq;
    n->next_ee_seq = (seq + 1) & 0xFF;
    c->sm->arm[side].ee_seq = seq;
    hv_exec_action_t *a = exec_push(c, HV_ACT_EE, node);
    if (a) {
        a->u.ee.action = action;
        a->u.ee.seq = seq;
    }
    exec_remember(c, node, a);
}

static void start_approach(exec_ctx_t *c, int side)
{
    hv_exec_arm_t *arm = &c->sm->arm[side];
    const hv_exec_pick_t *pk = &c->sm->plan->picks[arm->pick];
    arm->phase = HV_ARM_APPROACH;
    arm->cut_confirmed = 0;
    send_setpoint(c, side, pk->q);
    arm->deadline_ns = exec_motion_deadline(c, pk->move_s);
    exec_fruit_event(c, HV_FE_APPROACH, arm->pick, (int)arm->attempt, 0, 0);
}

static void start_cut(exec_ctx_t *c, int side)
{
    hv_exec_sm_t *sm = c->sm;
    hv_exec_arm_t *arm = &sm->arm[side];
    const hv_exec_pick_t *pk = &sm->plan->picks[arm->pick];
    /* journal before the cut: a restart then knows the fruit may be off the stem */
    exec_journal(c, HV_JR_CUT, arm->pick, pk->stop, (int)arm->attempt, 0, 0);
    sm->prog.pick[arm->pick] = HV_PROG_CUT;
    arm->phase = HV_ARM_CUT;
    send_ee(c, side, HV_CAN_EE_ACTION_CUT);
    arm->deadline_ns = exec_motion_deadline(c, sm->prm.cut_s);
    exec_fruit_event(c, HV_FE_CUT, arm->pick, (int)arm->attempt, 0, 0);
}

static void start_release(exec_ctx_t *c, int side)
{
    hv_exec_sm_t *sm = c->sm;
    hv_exec_arm_t *arm = &sm->arm[side];
    exec_journal(c, HV_JR_RELEASE, arm->pick, sm->plan->picks[arm->pick].stop, (int)arm->attempt, 0,
                 0);
    sm->prog.pick[arm->pick] = HV_PROG_RELEASE;
    arm->phase = HV_ARM_RELEASE;
    send_ee(c, side, HV_CAN_EE_ACTION_RELEASE);
    arm->deadline_ns = exec_motion_deadline(c, sm->prm.release_s);
    exec_fruit_event(c, HV_FE_RELEASE, arm->pick, (int)arm->attempt, 0, 0);
}

static void start_return(exec_ctx_t *c, int side)
{
    hv_exec_arm_t *arm = &c->sm->arm[side];
    const hv_exec_pick_t *pk = &c->sm->plan->picks[arm->pick];
    arm->phase = HV_ARM_RETURN;
    send_setpoint(c, side, c->sm->plan->home[side]);
    arm->deadline_ns = exec_motion_deadline(c, pk->move_s);
    exec_fruit_event(c, HV_FE_RETURN, arm->pick, (int)arm->attempt, 0, 0);
}

/* Pick i, journalled cut or released before a restart with no outcome: release what the
 * arm holds, count a released fruit picked (1: go on to the next), or try again a cut that
 * never happened. */
static int resume_pick(exec_ctx_t *c, int side, int i)
{
    hv_exec_sm_t *sm = c->sm;
    if (sm->node[exec_arm_node(side)].fruit_held) {
        start_release(c, side);
    } else if (sm->prog.pick[i] == HV_PROG_RELEASE) {
        /* released before the restart: the fruit is in the container */
        exec_record_outcome(c, i, 1, HV_OUT_PICKED, HV_RSN_RESUMED);
        sm->arm[side].next++;
        return 1;
    } else {
        /* cut issued but nothing held: the cut never happened, so trying is safe */
        start_approach(c, side);
    }
    return 0;
}

/* Start the arm's next unfinished pick at the current stop, or mark the arm done. */
static void arm_advance(exec_ctx_t *c, int side)
{
    hv_exec_sm_t *sm = c->sm;
    hv_exec_arm_t *arm = &sm->arm[side];
    const hv_exec_stop_t *st = &sm->plan->stops[sm->stop];
    while (!sm->stop_requested && arm->next < st->count[side]) {
        int i = st->first[side] + (int)arm->next;
        if (sm->prog.pick[i] == HV_PROG_DONE) {
            arm->next++;
            continue;
        }
        arm->pick = i;
        arm->attempt = 1;
        arm->cut_confirmed = 0;
        arm->pick_start_ns = c->now;
        if (sm->prog.pick[i] == HV_PROG_PENDING) {
            start_approach(c, side);
            return;
        }
        if (!resume_pick(c, side, i))
            return;
    }
    arm->pick = -1;
    arm->phase = HV_ARM_DONE;
}

/* The outcome of the current pick, and the arm's next. */
static void give_outcome(exec_ctx_t *c, int side, hv_exec_outcome_t outcome, hv_exec_reason_t why)
{
    hv_exec_arm_t *arm = &c->sm->arm[side];
    exec_record_outcome(c, arm->pick, (int)arm->attempt, outcome, why);
    arm->next++;
    arm_advance(c, side);
}

/* The arm stands at home with its current pick unfinished: release a held fruit, try
 * again, or give the fruit up. */
static void retry_or_give_up(exec_ctx_t *c, int side, hv_exec_reason_t why)
{
    hv_exec_sm_t *sm = c->sm;
    hv_exec_arm_t *arm = &sm->arm[side];
    if (sm->node[exec_arm_node(side)].fruit_held && sm->prog.pick[arm->pick] >= HV_PROG_CUT) {
        start_release(c, side);
    } else if (arm->cut_confirmed) {
        /* cut but not held: approaching again would cut at an empty stem */
        give_outcome(c, side, HV_OUT_FAILED, HV_RSN_DROPPED);
    } else if (sm->stop_requested) {
        arm_advance(c, side); /* the fruit stays unfinished: the next run tries it */
    } else if (arm->attempt <= sm->prm.max_retries) {
        arm->attempt++;
        start_approach(c, side);
    } else {
        give_outcome(c, side, why == HV_RSN_REJECTED ? HV_OUT_SKIPPED : HV_OUT_FAILED, why);
    }
}

static void start_recover(exec_ctx_t *c, int side, hv_exec_reason_t why)
{
    hv_exec_sm_t *sm = c->sm;
    hv_exec_arm_t *arm = &sm->arm[side];
    sm->faults++;
    if (arm->pick >= 0)
        exec_fruit_event(c, HV_FE_FAULT, arm->pick, (int)arm->attempt, 0, why);
    arm->phase = HV_ARM_RECOVER;
    arm->fault_reason = why;
    arm->recover_step = 0;
    /* DISABLE first: whatever the arm was doing, its motion stops */
    exec_send_command(c, exec_arm_node(side), HV_CAN_CMD_DISABLE);
    arm->deadline_ns = exec_command_deadline(c);
}

/* RECOVER: the next command once the last was echoed (DISABLE -> CLEAR_FAULT -> ENABLE ->
 * HOME); at home, idle and without faults, the pick goes on. */
static void recover_progress(exec_ctx_t *c, int side)
{
    hv_exec_sm_t *sm = c->sm;
    hv_exec_arm_t *arm = &sm->arm[side];
    int node = exec_arm_node(side);
    const hv_exec_node_t *n = &sm->node[node];
    if (!exec_echoed(sm, node))
        return;
    if (arm->recover_step >= 2 && n->state == HV_CAN_STATE_FAULT) {
        /* faulted again after its fault was cleared: the recovery itself failed */
        exec_enter_safe(c, HV_SAFE_FAULT, node);
        return;
    }
    if (arm->recover_step < 2) {
        static const int next[2] = {HV_CAN_CMD_CLEAR_FAULT, HV_CAN_CMD_ENABLE};
        exec_send_command(c, node, next[arm->recover_step++]);
        arm->deadline_ns = exec_command_deadline(c);
    } else if (arm->recover_step == 2) {
        if (n->state != HV_CAN_STATE_IDLE)
            return;
        arm->recover_step = 3;
        exec_send_command(c, node, HV_CAN_CMD_HOME);
        arm->deadline_ns = exec_motion_deadline(c, sm->prm.home_max_s);
    } else if (n->state == HV_CAN_STATE_IDLE && n->homed && n->fault_bits == 0) {
        sm->node[node].wait_cmd_seq = -1;
        if (arm->pick < 0)
            arm->phase = HV_ARM_DONE;
        else
            retry_or_give_up(c, side, (hv_exec_reason_t)arm->fault_reason);
    }
}

/* A fault of this arm reported by its status or its end effector, or 0. */
static int arm_fault_reason(const hv_exec_node_t *n)
{
    if (n->fault_bits & HV_CAN_ARM_FAULT_SETPOINT_REJECTED)
        return HV_RSN_REJECTED;
    if ((n->fault_bits & HV_CAN_ARM_FAULT_EE) ||
        (n->ee_seen && n->ee_state == HV_CAN_EE_STATE_FAULT))
        return HV_RSN_EE_FAULT;
    if ((n->fault_bits & ARM_FAULT_JOINTS) || n->state == HV_CAN_STATE_FAULT)
        return HV_RSN_JOINT_FAULT;
    return 0;
}

/* CUT: the end effector's answer to this cut, done or failed; the arm returns either way. */
static void cut_answered(exec_ctx_t *c, int side, const hv_exec_node_t *n)
{
    hv_exec_arm_t *arm = &c->sm->arm[side];
    if (!n->ee_seen || n->ee_seq != arm->ee_seq)
        return;
    if (n->ee_state == HV_CAN_EE_STATE_DONE) {
        arm->cut_confirmed = 1;
        start_return(c, side);
    } else if (n->ee_state == HV_CAN_EE_STATE_FAILED) {
        arm->fault_reason = HV_RSN_CUT_FAILED;
        start_return(c, side);
    }
}

/* RETURN: at home, a held fruit is released; else the pick is retried or given up. */
static void returned(exec_ctx_t *c, int side, const hv_exec_node_t *n)
{
    hv_exec_arm_t *arm = &c->sm->arm[side];
    if (n->sp_seq != arm->sp_seq || !n->reached)
        return;
    if (arm->cut_confirmed && n->fruit_held)
        start_release(c, side);
    else
        retry_or_give_up(c, side,
                         arm->cut_confirmed ? HV_RSN_DROPPED : (hv_exec_reason_t)arm->fault_reason);
}

/* RELEASE: the fruit is in the container (picked; resumed when this run did not cut it),
 * or the release failed (recover). */
static void release_answered(exec_ctx_t *c, int side, const hv_exec_node_t *n)
{
    hv_exec_arm_t *arm = &c->sm->arm[side];
    if (!n->ee_seen || n->ee_seq != arm->ee_seq)
        return;
    if (n->ee_state == HV_CAN_EE_STATE_DONE)
        give_outcome(c, side, HV_OUT_PICKED, arm->cut_confirmed ? HV_RSN_OK : HV_RSN_RESUMED);
    else if (n->ee_state == HV_CAN_EE_STATE_FAILED)
        start_recover(c, side, HV_RSN_EE_FAULT);
}

void exec_arm_update(exec_ctx_t *c, int side)
{
    hv_exec_arm_t *arm = &c->sm->arm[side];
    const hv_exec_node_t *n = &c->sm->node[exec_arm_node(side)];
    if (arm->phase == HV_ARM_RECOVER) {
        recover_progress(c, side);
        return;
    }
    int fault = arm_fault_reason(n);
    if (fault) {
        start_recover(c, side, (hv_exec_reason_t)fault);
        return;
    }
    switch (arm->phase) {
    case HV_ARM_APPROACH:
        if (n->sp_seq == arm->sp_seq && n->reached)
            start_cut(c, side);
        break;
    case HV_ARM_CUT: cut_answered(c, side, n); break;
    case HV_ARM_RETURN: returned(c, side, n); break;
    case HV_ARM_RELEASE: release_answered(c, side, n); break;
    default: break;
    }
}

void exec_arm_timers(exec_ctx_t *c, int side)
{
    hv_exec_arm_t *arm = &c->sm->arm[side];
    if (arm->phase == HV_ARM_IDLE || arm->phase == HV_ARM_DONE || c->now < arm->deadline_ns)
        return;
    if (arm->phase == HV_ARM_RECOVER)
        exec_enter_safe(c, HV_SAFE_TIMEOUT, exec_arm_node(side)); /* recovery itself failed */
    else
        start_recover(c, side, HV_RSN_TIMEOUT);
}

void exec_arms_begin_stop(exec_ctx_t *c)
{
    for (int s = 0; s < 2; s++) {
        c->sm->arm[s].next = 0;
        c->sm->arm[s].phase = HV_ARM_IDLE;
    }
    arm_advance(c, HV_SIDE_LEFT);
    if (c->sm->phase == HV_PH_HARVEST)
        arm_advance(c, HV_SIDE_RIGHT);
}

int exec_arms_done(const hv_exec_sm_t *sm)
{
    return sm->arm[0].phase == HV_ARM_DONE && sm->arm[1].phase == HV_ARM_DONE;
}
