/* The fake clock and fake bus of the state machine tests (see exec_fixture.h). */
#include "exec_fixture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/config.h"
#include "hv/file_io.h"

#define TICK_NS 10000000ull /* 10 ms */

static hv_arm_t arms[2];

static void load_arms(void)
{
    hv_config_t cfg;
    char err[256];
    if (hv_config_load(HV_SOURCE_DIR "/config/harvest.cfg", &cfg, err, sizeof err) != HV_OK) {
        fprintf(stderr, "fixture: %s\n", err);
        abort();
    }
    hv_config_arm(&cfg, HV_SIDE_LEFT, &arms[0]);
    hv_config_arm(&cfg, HV_SIDE_RIGHT, &arms[1]);
}

void fx_plan(fx_t *fx, int n_stops, int per_arm)
{
    memset(fx, 0, sizeof *fx);
    load_arms();
    hv_exec_plan_t *p = &fx->plan;
    p->row_start_m = 0.0;
    p->row_length_m = 2.0;
    p->n_stops = (uint16_t)n_stops;
    for (int s = 0; s < n_stops; s++) {
        hv_exec_stop_t *st = &p->stops[s];
        st->plan_index = (uint32_t)(40 + 60 * s);
        st->y_m = 0.4 + 0.6 * s;
        for (int side = 0; side < 2; side++) {
            st->first[side] = p->n_picks;
            st->count[side] = (uint16_t)per_arm;
            for (int k = 0; k < per_arm; k++) {
                /* a pose the arm reaches by construction: FK of a joint vector near home */
                hv_exec_pick_t *pk = &p->picks[p->n_picks++];
                double q[4] = {0.15 + 0.05 * k, 0.2 - 0.1 * k, 1.0 + 0.1 * k, -0.3};
                hv_pose_t pose;
                hv_scara_fk(&arms[side], q, &pose);
                snprintf(pk->id, sizeof pk->id, "%c%d_%d", side ? 'R' : 'L', s, k);
                pk->side = (hv_side_t)side;
                pk->stop = (uint16_t)s;
                pk->x_m = pose.x_m;
                pk->y_m = pose.y_m + st->y_m;
                pk->z_m = pose.z_m;
                pk->yaw_rad = pose.heading_rad - hv_side_normal_heading((hv_side_t)side);
                pk->yaw_rad = atan2(sin(pk->yaw_rad), cos(pk->yaw_rad));
                pk->cost_s = 1.0;
            }
        }
    }
    hv_exec_timing_t tm = {1.0, 1.0, 0.1, 0.1};
    if (hv_exec_plan_prepare(p, arms, &tm) != HV_OK)
        abort();
    fx->motion_ns = 50000000ull;
    hv_exec_params_default(&fx->prm);
    fx->prm.home_max_s = hv_exec_home_max_s(&arms[0]);
}

void fx_start(fx_t *fx, const hv_exec_progress_t *progress)
{
    if (hv_exec_init(&fx->sm, &fx->plan, &fx->prm, progress) != HV_OK)
        abort();
    fx->now_ns = 1000000000ull;
    for (int i = 0; i < HV_EXEC_NODES; i++) {
        fx_node_t *n = &fx->node[i];
        n->alive = 1;
        n->time_scale = 10.0;
        n->state = HV_CAN_STATE_DISABLED;
        n->cmd_seq = 7 * (i + 1); /* whatever a previous run left */
        n->sp_seq = 3;
        n->ee_seq = 11;
        n->move_seq = 200;
    }
    fx->cur_pick[0] = fx->cur_pick[1] = -1;
}

int fx_restart(fx_t *fx)
{
    hv_exec_progress_t prog = fx->sm.prog; /* what the journal holds */
    if (hv_exec_init(&fx->sm, &fx->plan, &fx->prm, &prog) != HV_OK)
        abort();
    fx->nq = 0; /* frames in flight to the old executor are gone */
    return fx->nlog;
}

static int estop_bit(int node)
{
    return node == HV_EXEC_VEHICLE ? HV_CAN_VEHICLE_FAULT_ESTOP : HV_CAN_ARM_FAULT_ESTOP;
}

void fx_latch_estop(fx_t *fx, int node)
{
    fx_node_t *n = &fx->node[node];
    n->estop = 1;
    n->state = HV_CAN_STATE_ESTOP;
    n->fault_bits |= estop_bit(node);
    n->pending = 0;
}

/* A full table would drop what the state machine did or was told: the test then checks
 * less than it says, so it stops there (abort: cmocka reports the test failed). */
static void overflow(const char *what, int cap)
{
    fprintf(stderr, "fixture: more than %d %s: raise the capacity (exec_fixture.h)\n", cap, what);
    abort();
}

static void enqueue(fx_t *fx, const hv_exec_event_t *ev)
{
    if (fx->nq >= FX_MAX_EVENTS)
        overflow("events in flight", FX_MAX_EVENTS);
    fx->q[fx->nq++] = *ev;
}

static void status_event(fx_t *fx, int i)
{
    fx_node_t *n = &fx->node[i];
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.node = i;
    if (i == HV_EXEC_VEHICLE) {
        ev.kind = HV_EV_VEHICLE_STATUS;
        ev.u.veh.position_m = n->pos_m;
        ev.u.veh.state = n->state;
        ev.u.veh.arrived = n->arrived;
        ev.u.veh.fault_bits = n->fault_bits;
        ev.u.veh.move_seq = n->move_seq;
        ev.u.veh.cmd_seq = n->cmd_seq;
        enqueue(fx, &ev);
        return;
    }
    ev.kind = HV_EV_ARM_STATUS;
    ev.u.arm.state = n->state;
    ev.u.arm.reached = n->reached;
    ev.u.arm.homed = n->homed;
    ev.u.arm.sp_seq = n->sp_seq;
    ev.u.arm.cmd_seq = n->cmd_seq;
    ev.u.arm.fault_bits = n->fault_bits;
    enqueue(fx, &ev);
    memset(&ev, 0, sizeof ev);
    ev.node = i;
    ev.kind = HV_EV_EE_STATUS;
    ev.u.ee.state = n->ee_state;
    ev.u.ee.action = n->ee_action;
    ev.u.ee.ee_seq = n->ee_seq;
    ev.u.ee.fruit_held = n->held;
    enqueue(fx, &ev);
}

/* The fake nodes carry out one action of the state machine. */
static void node_act(fx_t *fx, const hv_exec_action_t *a)
{
    if (fx->nlog >= FX_MAX_LOG)
        overflow("logged actions", FX_MAX_LOG);
    fx->log[fx->nlog].a = *a;
    fx->log[fx->nlog].t_ns = fx->now_ns;
    fx->nlog++;
    if (a->kind == HV_ACT_ESTOP) {
        for (int i = 0; i < HV_EXEC_NODES; i++)
            fx_latch_estop(fx, i);
        return;
    }
    if (a->kind == HV_ACT_FRUIT_EVENT && a->u.fe.kind == HV_FE_APPROACH) {
        int side = fx->plan.picks[a->u.fe.pick].side;
        fx->cur_pick[side] = a->u.fe.pick;
    }
    if (a->node < 0)
        return;
    if (fx->f.drop_next[a->kind] > 0) {
        fx->f.drop_next[a->kind]--; /* lost on the bus: the node never sees it */
        return;
    }
    fx_node_t *n = &fx->node[a->node];
    int side = a->node == HV_EXEC_LEFT ? 0 : 1;
    switch (a->kind) {
    case HV_ACT_COMMAND:
        /* the DBC: only CLEAR_ESTOP releases an e-stop; a refused command is not echoed */
        if (n->estop &&
            (a->u.cmd.command == HV_CAN_CMD_CLEAR_FAULT || a->u.cmd.command == HV_CAN_CMD_ENABLE ||
             a->u.cmd.command == HV_CAN_CMD_HOME))
            break;
        n->cmd_seq = a->u.cmd.seq;
        switch (a->u.cmd.command) {
        case HV_CAN_CMD_CLEAR_ESTOP:
            fx->estop_clears[a->node]++;
            n->estop = 0;
            n->fault_bits &= ~estop_bit(a->node);
            if (n->state == HV_CAN_STATE_ESTOP)
                n->state = n->fault_bits ? HV_CAN_STATE_FAULT : HV_CAN_STATE_DISABLED;
            break;
        case HV_CAN_CMD_CLEAR_FAULT:
            n->fault_bits = 0;
            n->state = HV_CAN_STATE_DISABLED;
            break;
        case HV_CAN_CMD_ENABLE:
            if (n->state == HV_CAN_STATE_DISABLED)
                n->state = HV_CAN_STATE_IDLE;
            break;
        case HV_CAN_CMD_DISABLE:
            if (!n->estop)
                n->state = HV_CAN_STATE_DISABLED;
            n->pending = 0;
            break;
        case HV_CAN_CMD_HOME:
            if (a->node != HV_EXEC_VEHICLE && fx->f.home_faults[side]) {
                n->state = HV_CAN_STATE_FAULT;
                n->fault_bits |= 0x01; /* joint 1 limit */
            } else if (a->node != HV_EXEC_VEHICLE && fx->f.home_never[side])
                n->state = HV_CAN_STATE_HOMING;
            else {
                n->state = HV_CAN_STATE_HOMING;
                n->pending = 4;
                n->busy_until_ns = fx->now_ns + fx->motion_ns;
            }
            break;
        }
        break;
    case HV_ACT_SETPOINT: {
        int k = ++fx->setpoints_sent[side];
        int approach = memcmp(a->u.sp.q, fx->plan.home[side], sizeof a->u.sp.q) != 0;
        if (side == 0 && fx->f.comm_fault_arm && k == fx->f.comm_fault_arm) {
            n->fault_bits |= HV_CAN_ARM_FAULT_COMM_TIMEOUT;
            break;
        }
        if (approach && fx->f.reject_setpoints[side] > 0) {
            fx->f.reject_setpoints[side]--;
            n->fault_bits |= HV_CAN_ARM_FAULT_SETPOINT_REJECTED;
            n->state = HV_CAN_STATE_FAULT;
            break;
        }
        n->sp_seq = a->u.sp.seq;
        n->reached = 0;
        if (approach && (fx->f.joint_fault_every[side] || fx->f.joint_fault_at[side] == k)) {
            n->fault_bits |= 0x10; /* joint 1 following error */
            n->state = HV_CAN_STATE_FAULT;
            break;
        }
        n->state = HV_CAN_STATE_MOVING;
        if (!fx->f.stall[side]) {
            n->pending = 1;
            n->busy_until_ns = fx->now_ns + fx->motion_ns;
        }
        if (!approach && n->held && fx->f.drop[side] > 0) {
            fx->f.drop[side]--;
            n->held = 0;
        }
        break;
    }
    case HV_ACT_EE:
        n->ee_seq = a->u.ee.seq;
        n->ee_action = a->u.ee.action;
        n->ee_state = HV_CAN_EE_STATE_BUSY;
        n->pending = 2;
        n->pending_ee_action = a->u.ee.action;
        n->busy_until_ns = fx->now_ns + fx->motion_ns;
        if (a->u.ee.action == HV_CAN_EE_ACTION_CUT) {
            int k = ++fx->cuts_sent[side];
            if (side == 1 && fx->f.estop_at_cut && k == fx->f.estop_at_cut)
                fx_latch_estop(fx, a->node);
        }
        break;
    case HV_ACT_MOVE:
        fx->moves_sent++;
        n->move_seq = a->u.move.seq;
        n->arrived = 0;
        if (fx->f.vehicle_fault_on_move && fx->moves_sent == fx->f.vehicle_fault_on_move) {
            n->fault_bits |= 0x01;
            n->state = HV_CAN_STATE_FAULT;
            break;
        }
        n->state = HV_CAN_STATE_MOVING;
        if (!fx->f.move_never) {
            n->pending = 3;
            n->busy_until_ns = fx->now_ns + fx->motion_ns;
            n->pos_m = a->u.move.target_m; /* where it will be */
        }
        break;
    default: break;
    }
    status_event(fx, a->node);
}

static void step(fx_t *fx, const hv_exec_event_t *ev)
{
    hv_exec_actions_t out;
    out.n = 0;
    fx->last_status = hv_exec_step(&fx->sm, ev, fx->now_ns, &out);
    if (fx->on_step)
        fx->on_step(fx->on_step_ctx, &fx->sm, ev, fx->now_ns, fx->last_status, &out);
    for (unsigned i = 0; i < out.n; i++)
        node_act(fx, &out.a[i]);
}

static void nodes_progress(fx_t *fx)
{
    for (int i = 0; i < HV_EXEC_NODES; i++) {
        fx_node_t *n = &fx->node[i];
        int side = i == HV_EXEC_LEFT ? 0 : 1;
        if (n->pending && fx->now_ns >= n->busy_until_ns) {
            switch (n->pending) {
            case 1:
                n->reached = 1;
                n->state = HV_CAN_STATE_IDLE;
                break;
            case 3:
                n->arrived = 1;
                n->state = HV_CAN_STATE_IDLE;
                break;
            case 4:
                n->homed = 1;
                n->state = HV_CAN_STATE_IDLE;
                break;
            case 2:
                if (n->pending_ee_action == HV_CAN_EE_ACTION_CUT) {
                    if (fx->f.cut_fail[side] > 0) {
                        fx->f.cut_fail[side]--;
                        n->ee_state = HV_CAN_EE_STATE_FAILED;
                    } else {
                        n->ee_state = HV_CAN_EE_STATE_DONE;
                        n->held = 1;
                        if (fx->cur_pick[side] >= 0)
                            fx->cuts_done[side][fx->cur_pick[side]]++;
                    }
                } else {
                    n->ee_state = HV_CAN_EE_STATE_DONE;
                    n->held = 0;
                }
                break;
            }
            n->pending = 0;
            status_event(fx, i);
        }
    }
}

void fx_run(fx_t *fx, double seconds)
{
    uint64_t end = fx->now_ns + (uint64_t)(seconds * 1e9);
    int tick = 0;
    while (fx->now_ns < end) {
        /* heartbeats every 100 ms, statuses every 50 ms, as the DBC says */
        if (tick % 10 == 0)
            for (int i = 0; i < HV_EXEC_NODES; i++)
                if (fx->node[i].alive) {
                    hv_exec_event_t hb;
                    memset(&hb, 0, sizeof hb);
                    hb.kind = HV_EV_HEARTBEAT;
                    hb.node = i;
                    hb.u.hb.health =
                        fx->node[i].state == HV_CAN_STATE_ESTOP ? HV_CAN_HEALTH_ESTOP : 0;
                    hb.u.hb.time_scale = fx->node[i].time_scale;
                    hb.u.hb.protocol = HV_CAN_PROTOCOL_VERSION;
                    enqueue(fx, &hb);
                }
        if (tick % 5 == 0)
            for (int i = 0; i < HV_EXEC_NODES; i++)
                if (fx->node[i].alive)
                    status_event(fx, i);
        nodes_progress(fx);
        /* events in arrival order; actions may queue more */
        for (int k = 0; k < fx->nq; k++) {
            hv_exec_event_t ev = fx->q[k];
            step(fx, &ev);
        }
        fx->nq = 0;
        hv_exec_event_t t;
        memset(&t, 0, sizeof t);
        t.kind = HV_EV_TICK;
        step(fx, &t);
        if (fx->nq) {
            for (int k = 0; k < fx->nq; k++) {
                hv_exec_event_t ev = fx->q[k];
                step(fx, &ev);
            }
            fx->nq = 0;
        }
        if (hv_exec_finished(&fx->sm) && fx->sm.phase == HV_PH_ROW_DONE)
            break;
        fx->now_ns += TICK_NS;
        tick++;
    }
}

int fx_count(const fx_t *fx, hv_exec_action_kind_t kind, int jr_kind)
{
    int n = 0;
    for (int i = 0; i < fx->nlog; i++)
        if (fx->log[i].a.kind == kind &&
            (jr_kind < 0 || (kind == HV_ACT_JOURNAL && (int)fx->log[i].a.u.jr.kind == jr_kind) ||
             (kind == HV_ACT_COMMAND && fx->log[i].a.u.cmd.command == jr_kind)))
            n++;
    return n;
}

int fx_find(const fx_t *fx, int from, hv_exec_action_kind_t kind, int sub)
{
    for (int i = from < 0 ? 0 : from; i < fx->nlog; i++) {
        const hv_exec_action_t *a = &fx->log[i].a;
        if (a->kind != kind)
            continue;
        if (sub < 0 || (kind == HV_ACT_JOURNAL && (int)a->u.jr.kind == sub) ||
            (kind == HV_ACT_COMMAND && a->u.cmd.command == sub) ||
            (kind == HV_ACT_EE && a->u.ee.action == sub) ||
            (kind == HV_ACT_FRUIT_EVENT && (int)a->u.fe.kind == sub))
            return i;
    }
    return -1;
}

void fx_event(fx_t *fx, const hv_exec_event_t *ev)
{
    step(fx, ev);
}

void fx_online(fx_t *fx)
{
    fx->plan.n_stops = 0;
    fx->plan.n_picks = 0;
    fx->prm.online = 1;
}

void fx_grown(fx_t *fx, int final, double advance_m)
{
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = HV_EV_PLAN_GROWN;
    ev.u.plan.final = final;
    ev.u.plan.advance_m = advance_m;
    step(fx, &ev);
}

hv_status_t fx_append_stop(fx_t *fx, const hv_exec_plan_t *src, int s)
{
    const hv_exec_stop_t *st = &src->stops[s];
    hv_status_t r = hv_exec_plan_append(&fx->plan, st->plan_index, st->y_m,
                                        &src->picks[st->first[HV_SIDE_LEFT]],
                                        st->count[HV_SIDE_LEFT], st->count[HV_SIDE_RIGHT]);
    hv_exec_timing_t tm = {1.0, 1.0, 0.1, 0.1};
    if (r == HV_OK && hv_exec_plan_prepare(&fx->plan, arms, &tm) != HV_OK)
        abort();
    return r;
}
