/* The run's stops (exec_run.h). */
#include "exec_run.h"

#include "exec_arm.h"

/* The controlled stop's end: journalled with its reason, then every node disabled (motion
 * off, nothing latched). */
static void stopped(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    exec_journal(c, HV_JR_HALT, -1, -1, 0, 0, (int)sm->stop_reason);
    for (int i = 0; i < HV_EXEC_NODES; i++) {
        sm->node[i].resend_active = 0;
        exec_send_command(c, i, HV_CAN_CMD_DISABLE);
    }
    if (sm->t_row_start_ns && !sm->t_row_end_ns)
        sm->t_row_end_ns = c->now;
    exec_set_phase(c, HV_PH_STOPPED);
}

/* What is under way ends first: the next stop, the vehicle's arrival and the arms' cycles
 * (exec_arm.c) look at stop_requested. */
void exec_run_request_stop(exec_ctx_t *c, const hv_exec_event_t *ev)
{
    hv_exec_sm_t *sm = c->sm;
    if (sm->stop_requested) {
        if (!ev->u.stop.from_bus)
            exec_enter_safe(c, HV_SAFE_OPERATOR, -1); /* the operator insists */
        return;
    }
    sm->stop_requested = 1;
    sm->stop_reason = HV_STOP_OPERATOR;
    if (sm->phase == HV_PH_WAIT_NODES || sm->phase == HV_PH_ENABLE ||
        (sm->phase == HV_PH_WAIT_PLAN && !sm->advancing))
        stopped(c);
}

/* The vehicle sent to target_m, with the move's deadline; the row's time starts with the
 * first move. */
static void send_move(exec_ctx_t *c, hv_exec_real_t target_m)
{
    hv_exec_sm_t *sm = c->sm;
    hv_exec_node_t *v = &sm->node[HV_EXEC_VEHICLE];
    int seq = v->next_move_seq;
    v->next_move_seq = (seq + 1) & 0xFF;
    v->wait_cmd_seq = -1;
    hv_exec_action_t *a = exec_push(c, HV_ACT_MOVE, HV_EXEC_VEHICLE);
    if (a) {
        a->u.move.target_m = target_m;
        a->u.move.speed_mps = sm->prm.vehicle_speed_mps;
        a->u.move.seq = seq;
    }
    exec_remember(c, HV_EXEC_VEHICLE, a);
    sm->deadline_ns = exec_motion_deadline(c, hv_exec_vehicle_move_s(target_m - v->position_m,
                                                                     sm->prm.vehicle_speed_mps,
                                                                     sm->prm.vehicle_accel_mps2));
    if (sm->t_row_start_ns == 0)
        sm->t_row_start_ns = c->now ? c->now : 1;
}

/* Stop p has a pick to do; its unreachable picks are recorded skipped on the way. */
static int stop_has_work(exec_ctx_t *c, int p)
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
                exec_record_outcome(c, i, 0, HV_OUT_SKIPPED, HV_RSN_IK_UNREACHABLE);
            else
                work = 1;
        }
    return work;
}

/* WAIT_PLAN: the planner committed the course further than the vehicle stands and no stop
 * with work lies there: drive on to the commit line, so the camera sees further. */
static void advance(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    if (!sm->advancing &&
        sm->advance_m > sm->node[HV_EXEC_VEHICLE].position_m + HV_EXEC_REAL(0.005) &&
        sm->advance_m <= hv_exec_course_end(sm->plan)) {
        send_move(c, sm->advance_m);
        sm->advancing = 1;
    }
}

/* Online, the committed part done: wait for the planner's next stops where we are. */
static void wait_for_plan(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    sm->stop = sm->plan->n_stops - 1;
    sm->wait_from_ns = c->now;
    sm->wait_first = sm->t_row_start_ns == 0;
    sm->waits += !sm->wait_first;
    sm->advancing = 0;
    exec_set_phase(c, HV_PH_WAIT_PLAN);
    advance(c);
}

void exec_run_next_stop(exec_ctx_t *c)
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
            exec_set_phase(c, HV_PH_DRIVING);
            return;
        }
    }
    if (sm->prm.online && !sm->plan_final) {
        wait_for_plan(c);
        return;
    }
    sm->stop = plan->n_stops;
    send_move(c, hv_exec_course_end(plan));
    exec_set_phase(c, HV_PH_FINAL_DRIVE);
}

static int vehicle_arrived(const hv_exec_sm_t *sm)
{
    const hv_exec_node_t *v = &sm->node[HV_EXEC_VEHICLE];
    return v->arrived && v->move_seq == ((v->next_move_seq + 0xFF) & 0xFF);
}

/* WAIT_PLAN: go on once the plan has a stop after the current one or is final; stop in a
 * controlled way when the planner stays silent too long. */
static void wait_plan(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    if (sm->advancing) {
        if (!vehicle_arrived(sm)) {
            if (c->now >= sm->deadline_ns)
                exec_enter_safe(c, HV_SAFE_TIMEOUT, HV_EXEC_VEHICLE);
            return;
        }
        sm->advancing = 0;
        if (sm->stop_requested) {
            stopped(c);
            return;
        }
    }
    int more = sm->stop + 1 < (int)sm->plan->n_stops || sm->plan_final;
    if (!more && c->now - sm->wait_from_ns >= hv_exec_real_ns(sm->prm.wait_plan_timeout_s)) {
        /* the planner is silent, refused or gone: say so and stop, resumable */
        sm->stop_requested = 1;
        sm->stop_reason = HV_STOP_PLAN_TIMEOUT;
        stopped(c);
        return;
    }
    if (!more) {
        advance(c);
        return;
    }
    uint64_t w = c->now - sm->wait_from_ns;
    if (sm->wait_first)
        sm->wait_first_ns += w;
    else
        sm->wait_row_ns += w;
    exec_run_next_stop(c);
}

/* The vehicle arrived at the course end: the row is done, every node disabled. */
static void row_done(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    exec_journal(c, HV_JR_DONE, -1, -1, 0, 0, 0);
    sm->prog.row_done = 1;
    sm->t_row_end_ns = c->now;
    for (int i = 0; i < HV_EXEC_NODES; i++)
        exec_send_command(c, i, HV_CAN_CMD_DISABLE);
    exec_set_phase(c, HV_PH_ROW_DONE);
}

/* The vehicle arrived at the current stop: journalled, the arms start (a stop of which
 * nothing is left for either arm ends at once). */
static void stop_reached(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    exec_journal(c, HV_JR_STOP, -1, sm->stop, 0, 0, 0);
    sm->prog.stop_reached[sm->stop] = 1;
    exec_set_phase(c, HV_PH_HARVEST);
    exec_arms_begin_stop(c);
    if (exec_arms_done(sm))
        exec_run_next_stop(c);
}

/* DRIVING, FINAL_DRIVE: the vehicle's arrival, within the move's deadline. */
static void drive(exec_ctx_t *c)
{
    hv_exec_sm_t *sm = c->sm;
    if (!vehicle_arrived(sm)) {
        if (c->now >= sm->deadline_ns)
            exec_enter_safe(c, HV_SAFE_TIMEOUT, HV_EXEC_VEHICLE);
    } else if (sm->phase == HV_PH_FINAL_DRIVE) {
        row_done(c);
    } else if (sm->stop_requested) {
        stopped(c); /* arrived; the stop's picks are for the next run */
    } else {
        stop_reached(c);
    }
}

/* HARVEST: each arm hears its node's report (or goes on recovering) and its deadline; the
 * stop ends when both are done. */
static void harvest(exec_ctx_t *c, const hv_exec_event_t *ev)
{
    hv_exec_sm_t *sm = c->sm;
    for (int s = 0; s < 2 && sm->phase == HV_PH_HARVEST; s++) {
        int ev_arm = (ev->kind == HV_EV_ARM_STATUS || ev->kind == HV_EV_EE_STATUS) &&
                     ev->node == exec_arm_node(s);
        if (ev_arm || sm->arm[s].phase == HV_ARM_RECOVER) {
            exec_arm_update(c, s);
            if (exec_arms_done(sm))
                exec_run_next_stop(c);
        }
        if (sm->phase == HV_PH_HARVEST)
            exec_arm_timers(c, s);
    }
}

void exec_run_step(exec_ctx_t *c, const hv_exec_event_t *ev)
{
    switch (c->sm->phase) {
    case HV_PH_DRIVING:
    case HV_PH_FINAL_DRIVE: drive(c); break;
    case HV_PH_WAIT_PLAN: wait_plan(c); break;
    case HV_PH_HARVEST: harvest(c, ev); break;
    default: break;
    }
}

void exec_run_plan_grown(hv_exec_sm_t *sm, const hv_exec_event_t *ev)
{
    sm->plan_final |= ev->u.plan.final;
    if (ev->u.plan.advance_m > sm->advance_m)
        sm->advance_m = ev->u.plan.advance_m;
}
