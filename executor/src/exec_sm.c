/* The executor's pure step function (see hv/exec_sm.h for the run and its faults). */
#include "hv/exec_sm.h"

#include <math.h>
#include <string.h>

#include "hv/exec_status.h"

static const int arm_node[2] = {HV_EXEC_LEFT, HV_EXEC_RIGHT}; /* by hv_side_t */

void hv_exec_params_default(hv_exec_params_t *p)
{
    memset(p, 0, sizeof *p); /* a field added later is 0, not the caller's stack */
    p->time_scale = 0.0;
    p->margin = 0.5;
    p->slack_s = 1.0;
    p->latency_s = 0.3;
    p->heartbeat_timeout_s = 0.5; /* DBC: 500 ms without a heartbeat = lost node */
    p->heartbeat_period_s = 0.1;  /* DBC: ExecutorHeartbeat and Estop every 100 ms */
    p->startup_timeout_s = 10.0;
    p->command_timeout_s = 1.0;
    p->home_max_s = 30.0;
    p->cut_s = 1.0;
    p->release_s = 0.5; /* the simulator's default, like cut_s */
    p->vehicle_speed_mps = 0.1;
    p->vehicle_accel_mps2 = 0.1;
    p->max_retries = 2;
    p->resend_s = 0.25; /* 5 status periods at time scale 1 (DBC: status every 50 ms) */
    p->clear_estop = 0; /* only an operator clears an e-stop */
    /* twice online.horizon_limit_max's default: a horizon's solve plus as much again */
    p->wait_plan_timeout_s = 120.0;
}

double hv_exec_home_max_s(const hv_arm_t *arm)
{
    double worst = 0.0;
    for (int j = 0; j < HV_NJOINTS; j++) {
        const hv_joint_limit_t *l = &arm->limit[j];
        double d = fabs(arm->home[j] - l->min) > fabs(l->max - arm->home[j])
                       ? fabs(arm->home[j] - l->min)
                       : fabs(l->max - arm->home[j]);
        double t = hv_trap_time(d, l->vmax, l->amax);
        if (t > worst)
            worst = t;
    }
    return worst;
}

static int params_ok(const hv_exec_params_t *p)
{
    const hv_exec_real_t pos[] = {p->heartbeat_timeout_s, p->heartbeat_period_s,
                                  p->startup_timeout_s,   p->command_timeout_s,
                                  p->home_max_s,          p->cut_s,
                                  p->release_s,           p->vehicle_speed_mps,
                                  p->vehicle_accel_mps2,  p->resend_s};
    for (size_t i = 0; i < sizeof pos / sizeof pos[0]; i++)
        if (!(pos[i] > HV_EXEC_REAL(0.0)) || !isfinite(pos[i]))
            return 0;
    const hv_exec_real_t zero = HV_EXEC_REAL(0.0);
    return p->time_scale >= zero && isfinite(p->time_scale) && p->margin >= zero &&
           isfinite(p->margin) && p->slack_s >= zero && isfinite(p->slack_s) &&
           p->latency_s >= zero && isfinite(p->latency_s) && p->max_retries < 100 &&
           (p->clear_estop == 0 || p->clear_estop == 1) &&
           (p->online == 0 ||
            (p->online == 1 && p->wait_plan_timeout_s > zero && isfinite(p->wait_plan_timeout_s)));
}

hv_status_t hv_exec_init(hv_exec_sm_t *sm, const hv_exec_plan_t *plan,
                         const hv_exec_params_t *params, const hv_exec_progress_t *progress)
{
    if (!sm || !plan || !params)
        return HV_ERR_ARG;
    if (!params_ok(params))
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

/* ---- helpers -------------------------------------------------------------------- */

typedef struct ctx {
    hv_exec_sm_t *sm;
    uint64_t now;
    hv_exec_actions_t *out;
    int overflow;
} ctx_t;

static hv_exec_action_t *push(ctx_t *c, hv_exec_action_kind_t kind, int node)
{
    if (c->out->n >= HV_EXEC_MAX_ACTIONS) {
        c->overflow = 1;
        return NULL;
    }
    hv_exec_action_t *a = &c->out->a[c->out->n++];
    memset(a, 0, sizeof *a);
    a->kind = kind;
    a->node = node;
    return a;
}

/* Keep the frame just sent to `node` for resending until the node acknowledges it; it
 * supersedes whatever was pending for that node. */
static void remember(ctx_t *c, int node, const hv_exec_action_t *a)
{
    hv_exec_node_t *n = &c->sm->node[node];
    if (!a)
        return;
    n->resend = *a;
    n->resend_active = 1;
    n->resend_ns = c->now + hv_exec_real_ns(c->sm->prm.resend_s);
}

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

static void resend_unacknowledged(ctx_t *c)
{
    for (int i = 0; i < HV_EXEC_NODES; i++) {
        hv_exec_node_t *n = &c->sm->node[i];
        if (!n->resend_active)
            continue;
        if (acknowledged(n)) {
            n->resend_active = 0;
        } else if (c->now >= n->resend_ns) {
            hv_exec_action_t *a = push(c, n->resend.kind, i);
            if (a)
                *a = n->resend;
            c->sm->resends++;
            n->resend_ns = c->now + hv_exec_real_ns(c->sm->prm.resend_s);
        }
    }
}

/* A motion or action planned to take `planned_s` of plan time: its deadline from now. */
static uint64_t motion_deadline(const ctx_t *c, hv_exec_real_t planned_s)
{
    const hv_exec_params_t *p = &c->sm->prm;
    hv_exec_real_t real =
        (planned_s * (HV_EXEC_REAL(1.0) + p->margin) + p->slack_s) / c->sm->time_scale +
        p->latency_s;
    return c->now + hv_exec_real_ns(real);
}

static void set_phase(ctx_t *c, hv_exec_phase_t ph)
{
    if (c->sm->phase != ph) {
        c->sm->phase = ph;
        push(c, HV_ACT_PHASE, -1);
    }
}

static void send_heartbeat(ctx_t *c)
{
    hv_exec_action_t *a = push(c, HV_ACT_HEARTBEAT, -1);
    if (a) {
        a->u.hb.health = c->sm->phase == HV_PH_SAFE ? HV_CAN_HEALTH_ESTOP : HV_CAN_HEALTH_OK;
        a->u.hb.time_scale = c->sm->time_scale;
    }
}

static void enter_safe(ctx_t *c, hv_exec_safe_reason_t why, int node)
{
    hv_exec_sm_t *sm = c->sm;
    if (sm->phase == HV_PH_SAFE)
        return;
    sm->safe_reason = why;
    sm->safe_node = node;
    for (int i = 0; i < HV_EXEC_NODES; i++)
        sm->node[i].resend_active = 0; /* nothing is repeated once stopped */
    /* e-stop first: every node stops motion at once and latches */
    push(c, HV_ACT_ESTOP, -1);
    set_phase(c, HV_PH_SAFE);
    send_heartbeat(c);
    sm->next_hb_ns = c->now + hv_exec_real_ns(sm->prm.heartbeat_period_s);
}

static void send_command(ctx_t *c, int node, int command);
static hv_exec_action_t *journal(ctx_t *c, hv_exec_journal_kind_t kind, int pick, int stop,
                                 int attempt, int outcome, int reason);

/* The controlled stop's end: journalled with its reason, then every node disabled (motion
 * off, nothing latched). */
static void stopped(ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    journal(c, HV_JR_HALT, -1, -1, 0, 0, (int)sm->stop_reason);
    for (int i = 0; i < HV_EXEC_NODES; i++) {
        sm->node[i].resend_active = 0;
        send_command(c, i, HV_CAN_CMD_DISABLE);
    }
    if (sm->t_row_start_ns && !sm->t_row_end_ns)
        sm->t_row_end_ns = c->now;
    set_phase(c, HV_PH_STOPPED);
}

/* A controlled stop: at once where nothing moves, else once what is under way ends
 * (next_stop, the vehicle's arrival, arm_advance and retry_or_give_up look at the flag). */
static void request_stop(ctx_t *c, const hv_exec_event_t *ev)
{
    hv_exec_sm_t *sm = c->sm;
    if (sm->stop_requested) {
        if (!ev->u.stop.from_bus)
            enter_safe(c, HV_SAFE_OPERATOR, -1); /* the operator insists */
        return;
    }
    sm->stop_requested = 1;
    sm->stop_reason = HV_STOP_OPERATOR;
    if (sm->phase == HV_PH_WAIT_NODES || sm->phase == HV_PH_ENABLE ||
        (sm->phase == HV_PH_WAIT_PLAN && !sm->advancing))
        stopped(c);
}

static void send_command(ctx_t *c, int node, int command)
{
    hv_exec_node_t *n = &c->sm->node[node];
    hv_exec_action_t *a = push(c, HV_ACT_COMMAND, node);
    int seq = n->next_cmd_seq;
    n->next_cmd_seq = (seq + 1) & 0xFF;
    n->wait_cmd_seq = seq;
    if (a) {
        a->u.cmd.command = command;
        a->u.cmd.seq = seq;
    }
    remember(c, node, a);
}

static int echoed(const hv_exec_sm_t *sm, int node)
{
    const hv_exec_node_t *n = &sm->node[node];
    return n->wait_cmd_seq >= 0 && n->cmd_seq == n->wait_cmd_seq;
}

static void send_setpoint(ctx_t *c, int side, const hv_exec_real_t q[HV_NJOINTS])
{
    hv_exec_node_t *n = &c->sm->node[arm_node[side]];
    int seq = n->next_sp_seq;
    n->next_sp_seq = (seq + 1) & 0x1F;
    c->sm->arm[side].sp_seq = seq;
    hv_exec_action_t *a = push(c, HV_ACT_SETPOINT, arm_node[side]);
    if (a) {
        memcpy(a->u.sp.q, q, sizeof a->u.sp.q);
        a->u.sp.seq = seq;
    }
    remember(c, arm_node[side], a);
}

static void send_ee(ctx_t *c, int side, int action)
{
    hv_exec_node_t *n = &c->sm->node[arm_node[side]];
    int seq = n->next_ee_seq;
    n->next_ee_seq = (seq + 1) & 0xFF;
    c->sm->arm[side].ee_seq = seq;
    hv_exec_action_t *a = push(c, HV_ACT_EE, arm_node[side]);
    if (a) {
        a->u.ee.action = action;
        a->u.ee.seq = seq;
    }
    remember(c, arm_node[side], a);
}

static hv_exec_action_t *journal(ctx_t *c, hv_exec_journal_kind_t kind, int pick, int stop,
                                 int attempt, int outcome, int reason)
{
    hv_exec_action_t *a = push(c, HV_ACT_JOURNAL, -1);
    if (a) {
        a->u.jr.kind = kind;
        a->u.jr.pick = pick;
        a->u.jr.stop = stop;
        a->u.jr.attempt = attempt;
        a->u.jr.outcome = outcome;
        a->u.jr.reason = reason;
    }
    return a;
}

static void fruit_event(ctx_t *c, hv_exec_fruit_event_kind_t kind, int pick, int attempt,
                        int outcome, int reason)
{
    hv_exec_action_t *a = push(c, HV_ACT_FRUIT_EVENT, -1);
    if (a) {
        a->u.fe.kind = kind;
        a->u.fe.pick = pick;
        a->u.fe.attempt = attempt;
        a->u.fe.outcome = outcome;
        a->u.fe.reason = reason;
    }
}

static void record_outcome(ctx_t *c, int pick, int attempt, hv_exec_outcome_t outcome,
                           hv_exec_reason_t reason)
{
    hv_exec_sm_t *sm = c->sm;
    /* the journal first: the record must be durable before anything else happens */
    journal(c, HV_JR_OUTCOME, pick, sm->plan->picks[pick].stop, attempt, outcome, reason);
    sm->prog.pick[pick] = HV_PROG_DONE;
    sm->prog.outcome[pick] = (uint8_t)outcome;
    sm->prog.reason[pick] = (uint8_t)reason;
    if (outcome == HV_OUT_PICKED)
        sm->picked++;
    else if (outcome == HV_OUT_FAILED)
        sm->failed++;
    else
        sm->skipped++;
    fruit_event(c, HV_FE_OUTCOME, pick, attempt, outcome, reason);
}

/* ---- vehicle and stops ------------------------------------------------------------ */

static void send_move(ctx_t *c, hv_exec_real_t target_m)
{
    hv_exec_sm_t *sm = c->sm;
    hv_exec_node_t *v = &sm->node[HV_EXEC_VEHICLE];
    int seq = v->next_move_seq;
    v->next_move_seq = (seq + 1) & 0xFF;
    v->wait_cmd_seq = -1;
    hv_exec_action_t *a = push(c, HV_ACT_MOVE, HV_EXEC_VEHICLE);
    if (a) {
        a->u.move.target_m = target_m;
        a->u.move.speed_mps = sm->prm.vehicle_speed_mps;
        a->u.move.seq = seq;
    }
    remember(c, HV_EXEC_VEHICLE, a);
    sm->deadline_ns = motion_deadline(c, hv_exec_vehicle_move_s(target_m - v->position_m,
                                                                sm->prm.vehicle_speed_mps,
                                                                sm->prm.vehicle_accel_mps2));
    if (sm->t_row_start_ns == 0)
        sm->t_row_start_ns = c->now ? c->now : 1;
}

static int stop_has_work(ctx_t *c, int p)
{
    const hv_exec_plan_t *plan = c->sm->plan;
    const hv_exec_stop_t *st = &plan->stops[p];
    int work = 0;
    for (int s = 0; s < 2; s++)
        for (unsigned k = 0; k < st->count[s]; k++) {
            int i = st->first[s] + (int)k;
            if (c->sm->prog.pick[i] == HV_PROG_DONE)
                continue;
            if (!plan->picks[i].reachable)
                record_outcome(c, i, 0, HV_OUT_SKIPPED, HV_RSN_IK_UNREACHABLE);
            else
                work = 1;
        }
    return work;
}

static void advance(ctx_t *c);

static void next_stop(ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    const hv_exec_plan_t *plan = sm->plan;
    if (sm->stop_requested) {
        stopped(c);
        return;
    }
    for (int p = sm->stop + 1; p < plan->n_stops; p++) {
        if (stop_has_work(c, p)) {
            sm->stop = p;
            send_move(c, plan->stops[p].y_m);
            set_phase(c, HV_PH_DRIVING);
            return;
        }
    }
    if (sm->prm.online && !sm->plan_final) {
        /* the committed part is done: wait for the planner's next stops where we are */
        sm->stop = plan->n_stops - 1;
        sm->wait_from_ns = c->now;
        sm->wait_first = sm->t_row_start_ns == 0;
        sm->waits += !sm->wait_first;
        sm->advancing = 0;
        set_phase(c, HV_PH_WAIT_PLAN);
        advance(c);
        return;
    }
    sm->stop = plan->n_stops;
    send_move(c, hv_exec_course_end(plan));
    set_phase(c, HV_PH_FINAL_DRIVE);
}

static int vehicle_arrived(const hv_exec_sm_t *sm)
{
    const hv_exec_node_t *v = &sm->node[HV_EXEC_VEHICLE];
    return v->arrived && v->move_seq == ((v->next_move_seq + 0xFF) & 0xFF);
}

/* WAIT_PLAN: the planner committed the course further than the vehicle stands and no stop
 * with work lies there: drive on to the commit line, so the camera sees further. */
static void advance(ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    if (!sm->advancing &&
        sm->advance_m > sm->node[HV_EXEC_VEHICLE].position_m + HV_EXEC_REAL(0.005) &&
        sm->advance_m <= hv_exec_course_end(sm->plan)) {
        send_move(c, sm->advance_m);
        sm->advancing = 1;
    }
}

/* WAIT_PLAN: go on once the plan has a stop after the current one or is final. */
static void wait_plan(ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    if (sm->advancing) {
        if (!vehicle_arrived(sm)) {
            if (c->now >= sm->deadline_ns)
                enter_safe(c, HV_SAFE_TIMEOUT, HV_EXEC_VEHICLE);
            return;
        }
        sm->advancing = 0;
        if (sm->stop_requested) {
            stopped(c);
            return;
        }
    }
    if (sm->stop + 1 >= (int)sm->plan->n_stops && !sm->plan_final &&
        c->now - sm->wait_from_ns >= hv_exec_real_ns(sm->prm.wait_plan_timeout_s)) {
        /* the planner is silent, refused or gone: say so and stop, resumable */
        sm->stop_requested = 1;
        sm->stop_reason = HV_STOP_PLAN_TIMEOUT;
        stopped(c);
        return;
    }
    if (sm->stop + 1 < (int)sm->plan->n_stops || sm->plan_final) {
        uint64_t w = c->now - sm->wait_from_ns;
        if (sm->wait_first)
            sm->wait_first_ns += w;
        else
            sm->wait_row_ns += w;
        next_stop(c);
    } else {
        advance(c);
    }
}

/* ---- the pick cycle --------------------------------------------------------------- */

static void arm_advance(ctx_t *c, int side);

static void start_approach(ctx_t *c, int side)
{
    hv_exec_arm_t *arm = &c->sm->arm[side];
    const hv_exec_pick_t *pk = &c->sm->plan->picks[arm->pick];
    arm->phase = HV_ARM_APPROACH;
    arm->cut_confirmed = 0;
    send_setpoint(c, side, pk->q);
    arm->deadline_ns = motion_deadline(c, pk->move_s);
    fruit_event(c, HV_FE_APPROACH, arm->pick, (int)arm->attempt, 0, 0);
}

static void start_release(ctx_t *c, int side)
{
    hv_exec_sm_t *sm = c->sm;
    hv_exec_arm_t *arm = &sm->arm[side];
    journal(c, HV_JR_RELEASE, arm->pick, sm->plan->picks[arm->pick].stop, (int)arm->attempt, 0, 0);
    sm->prog.pick[arm->pick] = HV_PROG_RELEASE;
    arm->phase = HV_ARM_RELEASE;
    send_ee(c, side, HV_CAN_EE_ACTION_RELEASE);
    arm->deadline_ns = motion_deadline(c, sm->prm.release_s);
    fruit_event(c, HV_FE_RELEASE, arm->pick, (int)arm->attempt, 0, 0);
}

static void start_return(ctx_t *c, int side)
{
    hv_exec_arm_t *arm = &c->sm->arm[side];
    const hv_exec_pick_t *pk = &c->sm->plan->picks[arm->pick];
    arm->phase = HV_ARM_RETURN;
    send_setpoint(c, side, c->sm->plan->home[side]);
    arm->deadline_ns = motion_deadline(c, pk->move_s);
    fruit_event(c, HV_FE_RETURN, arm->pick, (int)arm->attempt, 0, 0);
}

/* The arm stands at home with its current pick unfinished: release a held fruit, try
 * again, or give the fruit up. */
static void retry_or_give_up(ctx_t *c, int side, hv_exec_reason_t why)
{
    hv_exec_sm_t *sm = c->sm;
    hv_exec_arm_t *arm = &sm->arm[side];
    const hv_exec_node_t *n = &sm->node[arm_node[side]];
    int pick = arm->pick;
    if (n->fruit_held && sm->prog.pick[pick] >= HV_PROG_CUT) {
        start_release(c, side);
        return;
    }
    if (arm->cut_confirmed) {
        /* cut but not held: approaching again would cut at an empty stem */
        record_outcome(c, pick, (int)arm->attempt, HV_OUT_FAILED, HV_RSN_DROPPED);
        arm->next++;
        arm_advance(c, side);
        return;
    }
    if (sm->stop_requested) {
        arm_advance(c, side); /* the fruit stays unfinished: the next run tries it */
        return;
    }
    if (arm->attempt <= sm->prm.max_retries) {
        arm->attempt++;
        start_approach(c, side);
        return;
    }
    record_outcome(c, pick, (int)arm->attempt,
                   why == HV_RSN_REJECTED ? HV_OUT_SKIPPED : HV_OUT_FAILED, why);
    arm->next++;
    arm_advance(c, side);
}

static void stop_finished(ctx_t *c)
{
    if (c->sm->arm[0].phase == HV_ARM_DONE && c->sm->arm[1].phase == HV_ARM_DONE)
        next_stop(c);
}

/* Start the arm's next unfinished pick at the current stop, or mark the arm done. */
static void arm_advance(ctx_t *c, int side)
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
        /* resumed after a restart with a cut or release issued and no outcome */
        const hv_exec_node_t *n = &sm->node[arm_node[side]];
        if (n->fruit_held) {
            start_release(c, side);
        } else if (sm->prog.pick[i] == HV_PROG_RELEASE) {
            /* released before the restart: the fruit is in the container */
            record_outcome(c, i, 1, HV_OUT_PICKED, HV_RSN_RESUMED);
            arm->next++;
            continue;
        } else {
            /* cut issued but nothing held: the cut never happened, so trying is safe */
            start_approach(c, side);
        }
        return;
    }
    arm->pick = -1;
    arm->phase = HV_ARM_DONE;
    stop_finished(c);
}

static void start_recover(ctx_t *c, int side, hv_exec_reason_t why)
{
    hv_exec_sm_t *sm = c->sm;
    hv_exec_arm_t *arm = &sm->arm[side];
    sm->faults++;
    if (arm->pick >= 0)
        fruit_event(c, HV_FE_FAULT, arm->pick, (int)arm->attempt, 0, why);
    arm->phase = HV_ARM_RECOVER;
    arm->fault_reason = why;
    arm->recover_step = 0;
    /* DISABLE first: whatever the arm was doing, its motion stops */
    send_command(c, arm_node[side], HV_CAN_CMD_DISABLE);
    arm->deadline_ns = c->now + hv_exec_real_ns(sm->prm.command_timeout_s);
}

static void recover_progress(ctx_t *c, int side)
{
    hv_exec_sm_t *sm = c->sm;
    hv_exec_arm_t *arm = &sm->arm[side];
    int node = arm_node[side];
    const hv_exec_node_t *n = &sm->node[node];
    if (!echoed(sm, node))
        return;
    if (arm->recover_step >= 2 && n->state == HV_CAN_STATE_FAULT) {
        /* faulted again after its fault was cleared: the recovery itself failed */
        enter_safe(c, HV_SAFE_FAULT, node);
        return;
    }
    switch (arm->recover_step) {
    case 0:
        arm->recover_step = 1;
        send_command(c, node, HV_CAN_CMD_CLEAR_FAULT);
        arm->deadline_ns = c->now + hv_exec_real_ns(sm->prm.command_timeout_s);
        break;
    case 1:
        arm->recover_step = 2;
        send_command(c, node, HV_CAN_CMD_ENABLE);
        arm->deadline_ns = c->now + hv_exec_real_ns(sm->prm.command_timeout_s);
        break;
    case 2:
        if (n->state != HV_CAN_STATE_IDLE)
            break;
        arm->recover_step = 3;
        send_command(c, node, HV_CAN_CMD_HOME);
        arm->deadline_ns = motion_deadline(c, sm->prm.home_max_s);
        break;
    default:
        if (n->state == HV_CAN_STATE_IDLE && n->homed && n->fault_bits == 0) {
            sm->node[node].wait_cmd_seq = -1;
            if (arm->pick < 0) {
                arm->phase = HV_ARM_DONE;
                stop_finished(c);
            } else {
                retry_or_give_up(c, side, (hv_exec_reason_t)arm->fault_reason);
            }
        }
        break;
    }
}

/* A fault of this arm reported by its status or its end effector, or 0. */
static int arm_fault_reason(const hv_exec_node_t *n)
{
    if (n->fault_bits & HV_ARM_FAULT_REJECTED)
        return HV_RSN_REJECTED;
    if ((n->fault_bits & HV_ARM_FAULT_EE) || (n->ee_seen && n->ee_state == HV_CAN_EE_STATE_FAULT))
        return HV_RSN_EE_FAULT;
    if ((n->fault_bits & HV_ARM_FAULT_JOINTS) || n->state == HV_CAN_STATE_FAULT)
        return HV_RSN_JOINT_FAULT;
    return 0;
}

static void arm_update(ctx_t *c, int side)
{
    hv_exec_sm_t *sm = c->sm;
    hv_exec_arm_t *arm = &sm->arm[side];
    const hv_exec_node_t *n = &sm->node[arm_node[side]];
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
        if (n->sp_seq == arm->sp_seq && n->reached) {
            const hv_exec_pick_t *pk = &sm->plan->picks[arm->pick];
            /* journal before the cut: a restart then knows the fruit may be off the stem */
            journal(c, HV_JR_CUT, arm->pick, pk->stop, (int)arm->attempt, 0, 0);
            sm->prog.pick[arm->pick] = HV_PROG_CUT;
            arm->phase = HV_ARM_CUT;
            send_ee(c, side, HV_CAN_EE_ACTION_CUT);
            arm->deadline_ns = motion_deadline(c, sm->prm.cut_s);
            fruit_event(c, HV_FE_CUT, arm->pick, (int)arm->attempt, 0, 0);
        }
        break;
    case HV_ARM_CUT:
        if (n->ee_seen && n->ee_seq == arm->ee_seq) {
            if (n->ee_state == HV_CAN_EE_STATE_DONE) {
                arm->cut_confirmed = 1;
                start_return(c, side);
            } else if (n->ee_state == HV_CAN_EE_STATE_FAILED) {
                arm->fault_reason = HV_RSN_CUT_FAILED;
                start_return(c, side);
            }
        }
        break;
    case HV_ARM_RETURN:
        if (n->sp_seq == arm->sp_seq && n->reached) {
            if (arm->cut_confirmed && n->fruit_held)
                start_release(c, side);
            else
                retry_or_give_up(c, side,
                                 arm->cut_confirmed ? HV_RSN_DROPPED
                                                    : (hv_exec_reason_t)arm->fault_reason);
        }
        break;
    case HV_ARM_RELEASE:
        if (n->ee_seen && n->ee_seq == arm->ee_seq) {
            if (n->ee_state == HV_CAN_EE_STATE_DONE) {
                int resumed = !arm->cut_confirmed;
                record_outcome(c, arm->pick, (int)arm->attempt, HV_OUT_PICKED,
                               resumed ? HV_RSN_RESUMED : HV_RSN_OK);
                arm->next++;
                arm_advance(c, side);
            } else if (n->ee_state == HV_CAN_EE_STATE_FAILED) {
                start_recover(c, side, HV_RSN_EE_FAULT);
            }
        }
        break;
    default: break;
    }
}

static void arm_timers(ctx_t *c, int side)
{
    hv_exec_arm_t *arm = &c->sm->arm[side];
    if (arm->phase == HV_ARM_IDLE || arm->phase == HV_ARM_DONE || c->now < arm->deadline_ns)
        return;
    if (arm->phase == HV_ARM_RECOVER)
        enter_safe(c, HV_SAFE_TIMEOUT, arm_node[side]); /* recovery itself failed */
    else
        start_recover(c, side, HV_RSN_TIMEOUT);
}

/* ---- events ---------------------------------------------------------------------- */

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

static void apply_event(hv_exec_sm_t *sm, const hv_exec_event_t *ev, uint64_t now)
{
    if (ev->kind == HV_EV_PLAN_GROWN) {
        sm->plan_final |= ev->u.plan.final;
        if (ev->u.plan.advance_m > sm->advance_m)
            sm->advance_m = ev->u.plan.advance_m;
        return;
    }
    if (ev->kind == HV_EV_TICK || ev->kind == HV_EV_STOP_REQUEST ||
        ev->kind == HV_EV_JOURNAL_FAILED)
        return;
    hv_exec_node_t *n = &sm->node[ev->node];
    switch (ev->kind) {
    case HV_EV_HEARTBEAT:
        if (ev->u.hb.protocol != HV_PROTOCOL_VERSION)
            return; /* another protocol version: treated as absent */
        n->seen = 1;
        n->hb_rx = ++sm->rx;
        n->last_hb_ns = now;
        n->health = ev->u.hb.health;
        n->time_scale = ev->u.hb.time_scale;
        break;
    case HV_EV_VEHICLE_STATUS:
        n->status_seen = 1;
        n->st_rx = ++sm->rx;
        n->position_m = ev->u.veh.position_m;
        n->state = ev->u.veh.state;
        n->arrived = ev->u.veh.arrived;
        n->fault_bits = ev->u.veh.fault_bits;
        n->move_seq = ev->u.veh.move_seq;
        n->cmd_seq = ev->u.veh.cmd_seq;
        break;
    case HV_EV_ARM_STATUS:
        n->status_seen = 1;
        n->st_rx = ++sm->rx;
        n->state = ev->u.arm.state;
        n->reached = ev->u.arm.reached;
        n->homed = ev->u.arm.homed;
        n->sp_seq = ev->u.arm.sp_seq;
        n->cmd_seq = ev->u.arm.cmd_seq;
        n->fault_bits = ev->u.arm.fault_bits;
        break;
    case HV_EV_EE_STATUS:
        n->ee_seen = 1;
        n->ee_state = ev->u.ee.state;
        n->ee_action = ev->u.ee.action;
        n->ee_seq = ev->u.ee.ee_seq;
        n->fruit_held = ev->u.ee.fruit_held;
        break;
    default: break;
    }
}

static int all_nodes_ready(const hv_exec_sm_t *sm)
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
    int estop_bit = i == HV_EXEC_VEHICLE ? HV_VEH_FAULT_ESTOP : HV_ARM_FAULT_ESTOP;
    return n->health == HV_CAN_HEALTH_ESTOP || n->state == HV_CAN_STATE_ESTOP ||
           (n->fault_bits & estop_bit);
}

/* A heartbeat and a status of node i arrived after the last CLEAR_ESTOP was echoed. */
static int fresh(const hv_exec_sm_t *sm, int i)
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
    return !(clearing && (sm->latched & (1u << i)) && !fresh(sm, i));
}

/* CLEAR_FAULT reached node i in this run: its comm-timeout bit means us from now on. */
static int fault_cleared(const hv_exec_sm_t *sm, int i)
{
    if (sm->phase != HV_PH_ENABLE)
        return sm->phase > HV_PH_ENABLE;
    return sm->sub == HV_EN_ENABLE || (sm->sub == HV_EN_CLEAR_FAULT && echoed(sm, i));
}

/* Checks that hold in every phase after WAIT_NODES. */
static void global_checks(ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    if (sm->phase == HV_PH_WAIT_NODES)
        return;
    for (int i = 0; i < HV_EXEC_NODES; i++) {
        const hv_exec_node_t *n = &sm->node[i];
        if (c->now > n->last_hb_ns + hv_exec_real_ns(sm->prm.heartbeat_timeout_s)) {
            enter_safe(c, HV_SAFE_HEARTBEAT, i);
            return;
        }
        if (!same_scale(n->time_scale, sm->time_scale)) {
            enter_safe(c, HV_SAFE_TIME_SCALE, i);
            return;
        }
    }
    for (int i = 0; i < HV_EXEC_NODES; i++) {
        int comm_bit = i == HV_EXEC_VEHICLE ? HV_VEH_FAULT_COMM : HV_ARM_FAULT_COMM;
        if (estop_report_counts(sm, i) && reports_estop(sm, i)) {
            enter_safe(c, HV_SAFE_ESTOP, i);
            return;
        }
        if (fault_cleared(sm, i) && (sm->node[i].fault_bits & comm_bit)) {
            enter_safe(c, HV_SAFE_COMM, i);
            return;
        }
    }
    const hv_exec_node_t *v = &sm->node[HV_EXEC_VEHICLE];
    if (sm->phase >= HV_PH_HOMING && (v->state == HV_CAN_STATE_FAULT || (v->fault_bits & 0x07)))
        enter_safe(c, HV_SAFE_VEHICLE_FAULT, HV_EXEC_VEHICLE);
}

static void send_to(ctx_t *c, unsigned nodes, int command)
{
    for (int i = 0; i < HV_EXEC_NODES; i++)
        if (nodes & (1u << i))
            send_command(c, i, command);
}

/* The first of `nodes` that has not echoed its command (in the ENABLE step, IDLE too), or
 * -1 when all have. */
static int first_pending(const hv_exec_sm_t *sm, unsigned nodes)
{
    for (int i = 0; i < HV_EXEC_NODES; i++)
        if ((nodes & (1u << i)) &&
            (!echoed(sm, i) || (sm->sub == HV_EN_ENABLE && sm->node[i].state != HV_CAN_STATE_IDLE)))
            return i;
    return -1;
}

/* Enter a start-up step: each has the command timeout to be answered. */
static void enable_step(ctx_t *c, int sub)
{
    c->sm->sub = sub;
    c->sm->deadline_ns = c->now + hv_exec_real_ns(c->sm->prm.command_timeout_s);
}

/* Start-up after every node was seen: DISABLE -> [e-stop clear] -> CLEAR_FAULT -> ENABLE
 * -> HOME (hv_exec_enable_step_t). */
static void enable_progress(ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    int waiting = -1;
    switch (sm->sub) {
    case HV_EN_DISABLE:
        if ((waiting = first_pending(sm, HV_EXEC_ALL_NODES)) >= 0)
            break;
        if (sm->latched) {
            /* the record first: the clear is the operator's, and must be on disk before a
             * node acts on it */
            hv_exec_action_t *a = journal(c, HV_JR_ESTOP_CLEAR, -1, -1, 0, 0, 0);
            if (a)
                a->u.jr.nodes = sm->latched;
            send_to(c, sm->latched, HV_CAN_CMD_CLEAR_ESTOP);
            enable_step(c, HV_EN_CLEAR_ESTOP);
        } else {
            send_to(c, HV_EXEC_ALL_NODES, HV_CAN_CMD_CLEAR_FAULT);
            enable_step(c, HV_EN_CLEAR_FAULT);
        }
        return;
    case HV_EN_CLEAR_ESTOP:
        if ((waiting = first_pending(sm, sm->latched)) >= 0)
            break;
        sm->clear_rx = sm->rx;
        enable_step(c, HV_EN_FRESH);
        return;
    case HV_EN_FRESH:
        for (int i = 0; i < HV_EXEC_NODES && waiting < 0; i++)
            if (!fresh(sm, i))
                waiting = i;
        if (waiting >= 0)
            break;
        /* every node spoke after the clear and none reports an e-stop (global_checks) */
        send_to(c, HV_EXEC_ALL_NODES, HV_CAN_CMD_CLEAR_FAULT);
        enable_step(c, HV_EN_CLEAR_FAULT);
        return;
    case HV_EN_CLEAR_FAULT:
        if ((waiting = first_pending(sm, HV_EXEC_ALL_NODES)) >= 0)
            break;
        send_to(c, HV_EXEC_ALL_NODES, HV_CAN_CMD_ENABLE);
        enable_step(c, HV_EN_ENABLE);
        return;
    default:
        for (int i = 0; i < HV_EXEC_NODES; i++)
            if (echoed(sm, i) && sm->node[i].state == HV_CAN_STATE_FAULT) {
                enter_safe(c, HV_SAFE_FAULT, i);
                return;
            }
        if ((waiting = first_pending(sm, HV_EXEC_ALL_NODES)) >= 0)
            break;
        for (int s = 0; s < 2; s++)
            send_command(c, arm_node[s], HV_CAN_CMD_HOME);
        sm->node[HV_EXEC_VEHICLE].wait_cmd_seq = -1;
        sm->deadline_ns = motion_deadline(c, sm->prm.home_max_s);
        set_phase(c, HV_PH_HOMING);
        return;
    }
    if (c->now >= sm->deadline_ns)
        enter_safe(c, HV_SAFE_TIMEOUT, waiting);
}

static void phase_logic(ctx_t *c, const hv_exec_event_t *ev)
{
    hv_exec_sm_t *sm = c->sm;
    switch (sm->phase) {
    case HV_PH_WAIT_NODES:
        if (all_nodes_ready(sm)) {
            hv_exec_real_t ts = sm->node[0].time_scale;
            for (int i = 0; i < HV_EXEC_NODES; i++)
                if (!same_scale(sm->node[i].time_scale, ts) ||
                    (sm->prm.time_scale > HV_EXEC_REAL(0.0) &&
                     !same_scale(sm->node[i].time_scale, sm->prm.time_scale))) {
                    enter_safe(c, HV_SAFE_TIME_SCALE, i);
                    return;
                }
            sm->time_scale = ts;
            for (int i = 0; i < HV_EXEC_NODES; i++)
                if (reports_estop(sm, i))
                    sm->latched |= 1u << i;
            if (sm->latched && !sm->prm.clear_estop) {
                /* a latched e-stop is the operator's to clear, never a restart's */
                int first = 0;
                while (!(sm->latched & (1u << first)))
                    first++;
                enter_safe(c, HV_SAFE_ESTOP_LATCHED, first);
                return;
            }
            for (int i = 0; i < HV_EXEC_NODES; i++) {
                hv_exec_node_t *n = &sm->node[i];
                /* continue after what the nodes last accepted: never reuse a seq they echo */
                n->next_cmd_seq = (n->cmd_seq + 1) & 0xFF;
                n->next_sp_seq = (n->sp_seq + 1) & 0x1F;
                n->next_ee_seq = (n->ee_seq + 1) & 0xFF;
                n->next_move_seq = (n->move_seq + 1) & 0xFF;
            }
            send_to(c, HV_EXEC_ALL_NODES, HV_CAN_CMD_DISABLE);
            enable_step(c, HV_EN_DISABLE);
            set_phase(c, HV_PH_ENABLE);
        } else if (c->now >= sm->deadline_ns) {
            enter_safe(c, HV_SAFE_NODES_ABSENT, -1);
        }
        break;
    case HV_PH_ENABLE: enable_progress(c); break;
    case HV_PH_HOMING: {
        int done = 1;
        for (int s = 0; s < 2; s++) {
            const hv_exec_node_t *n = &sm->node[arm_node[s]];
            if (echoed(sm, arm_node[s]) && (n->state == HV_CAN_STATE_FAULT || n->fault_bits)) {
                enter_safe(c, HV_SAFE_FAULT, arm_node[s]);
                return;
            }
            done &= echoed(sm, arm_node[s]) && n->state == HV_CAN_STATE_IDLE && n->homed;
        }
        if (done) {
            for (int s = 0; s < 2; s++)
                sm->node[arm_node[s]].wait_cmd_seq = -1;
            next_stop(c);
        } else if (c->now >= sm->deadline_ns) {
            enter_safe(c, HV_SAFE_TIMEOUT, -1);
        }
        break;
    }
    case HV_PH_DRIVING:
    case HV_PH_FINAL_DRIVE:
        if (vehicle_arrived(sm)) {
            if (sm->phase == HV_PH_FINAL_DRIVE) {
                journal(c, HV_JR_DONE, -1, -1, 0, 0, 0);
                sm->prog.row_done = 1;
                sm->t_row_end_ns = c->now;
                for (int i = 0; i < HV_EXEC_NODES; i++)
                    send_command(c, i, HV_CAN_CMD_DISABLE);
                set_phase(c, HV_PH_ROW_DONE);
                break;
            }
            if (sm->stop_requested) {
                stopped(c); /* arrived; the stop's picks are for the next run */
                break;
            }
            journal(c, HV_JR_STOP, -1, sm->stop, 0, 0, 0);
            sm->prog.stop_reached[sm->stop] = 1;
            set_phase(c, HV_PH_HARVEST);
            for (int s = 0; s < 2; s++) {
                sm->arm[s].next = 0;
                sm->arm[s].phase = HV_ARM_IDLE;
            }
            arm_advance(c, HV_SIDE_LEFT);
            if (sm->phase == HV_PH_HARVEST)
                arm_advance(c, HV_SIDE_RIGHT);
        } else if (c->now >= sm->deadline_ns) {
            enter_safe(c, HV_SAFE_TIMEOUT, HV_EXEC_VEHICLE);
        }
        break;
    case HV_PH_WAIT_PLAN: wait_plan(c); break;
    case HV_PH_HARVEST:
        for (int s = 0; s < 2 && sm->phase == HV_PH_HARVEST; s++) {
            int ev_arm = (ev->kind == HV_EV_ARM_STATUS || ev->kind == HV_EV_EE_STATUS) &&
                         ev->node == arm_node[s];
            if (ev_arm || sm->arm[s].phase == HV_ARM_RECOVER)
                arm_update(c, s);
            if (sm->phase == HV_PH_HARVEST)
                arm_timers(c, s);
        }
        break;
    default: break;
    }
}

hv_status_t hv_exec_step(hv_exec_sm_t *sm, const hv_exec_event_t *ev, uint64_t now_ns,
                         hv_exec_actions_t *out)
{
    if (!sm || !ev || !out || out->n > HV_EXEC_MAX_ACTIONS)
        return HV_ERR_ARG;
    if (!event_ok(ev))
        return HV_ERR_EXEC_EVENT;
    ctx_t c = {sm, now_ns, out, 0};
    if (!sm->started) {
        sm->advance_m = hv_exec_course_start(sm->plan);
        sm->started = 1;
        sm->t_start_ns = now_ns;
        sm->deadline_ns = now_ns + hv_exec_real_ns(sm->prm.startup_timeout_s);
        sm->next_hb_ns = now_ns;
    }
    apply_event(sm, ev, now_ns);
    if (sm->phase != HV_PH_SAFE && sm->phase != HV_PH_ROW_DONE && sm->phase != HV_PH_STOPPED) {
        if (ev->kind == HV_EV_STOP_REQUEST)
            request_stop(&c, ev);
        else if (ev->kind == HV_EV_JOURNAL_FAILED)
            enter_safe(&c, HV_SAFE_JOURNAL, -1);
        else
            global_checks(&c);
        if (sm->phase != HV_PH_SAFE && sm->phase != HV_PH_STOPPED)
            phase_logic(&c, ev);
        if (sm->phase != HV_PH_SAFE && sm->phase != HV_PH_ROW_DONE && sm->phase != HV_PH_STOPPED)
            resend_unacknowledged(&c);
    }
    if (now_ns >= sm->next_hb_ns) {
        if (sm->phase == HV_PH_SAFE)
            push(&c, HV_ACT_ESTOP, -1); /* DBC: repeated every 100 ms while safe */
        send_heartbeat(&c);
        sm->next_hb_ns += hv_exec_real_ns(sm->prm.heartbeat_period_s);
        if (sm->next_hb_ns <= now_ns) /* a long gap: do not burst to catch up */
            sm->next_hb_ns = now_ns + hv_exec_real_ns(sm->prm.heartbeat_period_s);
    }
    if (c.overflow) {
        /* cannot happen with the bounded work of one step; if it does, stop safely */
        out->n = 0;
        c.overflow = 0;
        if (sm->phase != HV_PH_SAFE) {
            sm->phase = HV_PH_SAFE;
            sm->safe_reason = HV_SAFE_FAULT;
            sm->safe_node = -1;
        }
        push(&c, HV_ACT_ESTOP, -1);
        send_heartbeat(&c);
        return HV_ERR_EXEC_ACTIONS_FULL;
    }
    return HV_OK;
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
    return sm->phase == HV_PH_ROW_DONE || sm->phase == HV_PH_SAFE || sm->phase == HV_PH_STOPPED;
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
    static const char *const names[HV_EXEC_NODES] = {"vehicle", "left_arm", "right_arm"};
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
