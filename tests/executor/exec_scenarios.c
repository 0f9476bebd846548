/* The scenarios of the recorded-run replay (exec_scenarios.h): a row, each fault, the e-stop
 * and its clear, lost nodes, the operator's stop, resume, online growth, odd events, and
 * seeded runs that inject faults at random. */
#include "exec_scenarios.h"

#include <string.h>

/* A fresh fixture with a plan of `stops` x `per_arm` picks per arm, traced into t. */
static void setup(fx_t *fx, exec_trace_t *t, int stops, int per_arm)
{
    fx_plan(fx, stops, per_arm);
    fx->on_step = exec_trace_hook;
    fx->on_step_ctx = t;
}

/* Run until the run ends (or `max_s` of fake time), then half a second more: what a
 * finished machine keeps sending is part of its behaviour. */
static void run(fx_t *fx, double max_s)
{
    for (double t = 0.0; t < max_s && !hv_exec_finished(&fx->sm); t += 1.0)
        fx_run(fx, 1.0);
    fx_run(fx, 0.5);
}

static void event(fx_t *fx, hv_exec_event_kind_t kind, int from_bus)
{
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = kind;
    ev.u.stop.from_bus = from_bus;
    fx_event(fx, &ev);
}

static void sc_arm_faults(fx_t *fx, exec_trace_t *t)
{
    setup(fx, t, 3, 2);
    fx->f.joint_fault_at[0] = 1;
    fx->f.joint_fault_at[1] = 3;
    fx->f.reject_setpoints[1] = 1;
    fx->f.cut_fail[1] = 1;
    fx->f.drop[0] = 1;
    fx->plan.picks[3].reachable = 0;
    fx_start(fx, NULL);
    run(fx, 120.0);
}

static void sc_estop_restarts(fx_t *fx, exec_trace_t *t)
{
    setup(fx, t, 2, 2);
    fx->f.estop_at_cut = 3;
    fx_start(fx, NULL);
    run(fx, 60.0);
    fx_restart(fx); /* no operator clear: stays safe */
    run(fx, 5.0);
    fx->prm.clear_estop = 1;
    fx_restart(fx);
    run(fx, 60.0);
}

static void sc_latched_at_start(fx_t *fx, exec_trace_t *t)
{
    setup(fx, t, 1, 2);
    fx_start(fx, NULL);
    fx_latch_estop(fx, HV_EXEC_LEFT);
    run(fx, 5.0);
}

static void sc_lost_heartbeat(fx_t *fx, exec_trace_t *t)
{
    setup(fx, t, 2, 2);
    fx_start(fx, NULL);
    fx_run(fx, 1.5);
    fx->node[HV_EXEC_VEHICLE].alive = 0;
    run(fx, 10.0);
}

static void sc_recovery_fails(fx_t *fx, exec_trace_t *t)
{
    for (int faults = 0; faults < 2; faults++) {
        setup(fx, t, 1, 1);
        fx->f.joint_fault_at[0] = 1;
        fx->motion_ns = 300000000ull;
        fx_start(fx, NULL);
        fx_run(fx, 0.5);
        if (faults)
            fx->f.home_faults[0] = 1;
        else
            fx->f.home_never[0] = 1;
        run(fx, 120.0);
    }
}

static void sc_start_fails(fx_t *fx, exec_trace_t *t)
{
    setup(fx, t, 1, 1);
    fx->f.home_never[1] = 1; /* start-up's homing times out */
    fx_start(fx, NULL);
    run(fx, 60.0);
    setup(fx, t, 1, 1);
    fx_start(fx, NULL);
    fx->node[HV_EXEC_RIGHT].alive = 0;
    run(fx, 12.0);
    setup(fx, t, 1, 1);
    fx_start(fx, NULL);
    fx->node[HV_EXEC_LEFT].time_scale = 5.0;
    run(fx, 5.0);
    setup(fx, t, 1, 1);
    fx->prm.time_scale = 20.0;
    fx_start(fx, NULL);
    run(fx, 5.0);
}

static void sc_operator_stop(fx_t *fx, exec_trace_t *t)
{
    setup(fx, t, 3, 2);
    fx->motion_ns = 300000000ull;
    fx_start(fx, NULL);
    fx_run(fx, 1.5);
    event(fx, HV_EV_STOP_REQUEST, 0);
    run(fx, 30.0);
    fx_restart(fx);
    run(fx, 60.0);
}

static void sc_stop_variants(fx_t *fx, exec_trace_t *t)
{
    setup(fx, t, 2, 2); /* the bus's request, repeated: one request */
    fx->motion_ns = 300000000ull;
    fx_start(fx, NULL);
    fx_run(fx, 1.5);
    for (int i = 0; i < 5; i++)
        event(fx, HV_EV_STOP_REQUEST, 1);
    run(fx, 30.0);
    event(fx, HV_EV_STOP_REQUEST, 2);
    setup(fx, t, 1, 2); /* before any node was seen: at once */
    fx_start(fx, NULL);
    event(fx, HV_EV_STOP_REQUEST, 0);
    run(fx, 1.0);
    for (int which = 0; which < 2; which++) { /* a second signal; a journal failure */
        setup(fx, t, 1, 2);
        fx->motion_ns = 300000000ull;
        fx_start(fx, NULL);
        fx_run(fx, 1.0);
        if (!which)
            event(fx, HV_EV_STOP_REQUEST, 0);
        event(fx, which ? HV_EV_JOURNAL_FAILED : HV_EV_STOP_REQUEST, 0);
        run(fx, 1.0);
    }
}

static void sc_resume(fx_t *fx, exec_trace_t *t)
{
    setup(fx, t, 2, 2);
    hv_exec_progress_t prog;
    memset(&prog, 0, sizeof prog);
    for (int i = 0; i < 4; i++) {
        prog.pick[i] = HV_PROG_DONE;
        prog.outcome[i] = HV_OUT_PICKED;
    }
    prog.stop_reached[0] = prog.stop_reached[1] = 1;
    prog.pick[fx->plan.stops[1].first[0]] = HV_PROG_CUT;
    prog.pick[fx->plan.stops[1].first[0] + 1] = HV_PROG_CUT; /* not held: never cut */
    prog.pick[fx->plan.stops[1].first[1]] = HV_PROG_RELEASE;
    fx_start(fx, &prog);
    fx->node[HV_EXEC_LEFT].held = 1;
    run(fx, 60.0);
}

static void sc_online(fx_t *fx, exec_trace_t *t)
{
    static fx_t src; /* what the planner commits, stop by stop */
    fx_plan(&src, 3, 2);
    setup(fx, t, 3, 2);
    fx_online(fx);
    fx_start(fx, NULL);
    fx_run(fx, 5.0);
    fx_append_stop(fx, &src.plan, 0);
    fx_grown(fx, 0, 0.7);
    fx_run(fx, 30.0);
    fx_append_stop(fx, &src.plan, 1);
    fx_append_stop(fx, &src.plan, 2);
    fx_grown(fx, 1, 1.9);
    run(fx, 60.0);
}

static void sc_online_stops(fx_t *fx, exec_trace_t *t)
{
    static fx_t src;
    fx_plan(&src, 2, 1);
    setup(fx, t, 1, 1); /* a silent planner: plan_timeout */
    fx_online(fx);
    fx->prm.wait_plan_timeout_s = 3.0;
    fx_start(fx, NULL);
    run(fx, 20.0);
    setup(fx, t, 1, 1); /* the operator's stop while the vehicle advances, then waits */
    fx_online(fx);
    fx->motion_ns = 300000000ull;
    fx_start(fx, NULL);
    fx_run(fx, 3.0);
    fx_append_stop(fx, &src.plan, 0);
    fx_grown(fx, 0, 1.5);
    fx_run(fx, 8.0);
    event(fx, HV_EV_STOP_REQUEST, 1);
    run(fx, 30.0);
    for (int never = 0; never < 2; never++) { /* stopped while advancing; never arriving */
        setup(fx, t, 1, 1);
        fx_online(fx);
        fx->f.move_never = never;
        fx_start(fx, NULL);
        fx_run(fx, 3.0);
        fx_grown(fx, 0, 1.0);
        if (!never)
            event(fx, HV_EV_STOP_REQUEST, 0);
        run(fx, 30.0);
    }
}

/* Run in 10 ms steps (the fake nodes speak at every one) until arm `side` is in `phase`,
 * at most `max_s`. */
static void until_arm(fx_t *fx, int side, hv_exec_arm_phase_t phase, double max_s)
{
    for (double t = 0.0; t < max_s && fx->sm.arm[side].phase != phase; t += 0.01)
        fx_run(fx, 0.01);
}

static void sc_odd_events(fx_t *fx, exec_trace_t *t)
{
    setup(fx, t, 1, 2); /* another protocol's heartbeat; a node's scale changes mid-row */
    fx->motion_ns = 300000000ull;
    fx_start(fx, NULL);
    fx_run(fx, 1.0);
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = HV_EV_HEARTBEAT;
    ev.node = HV_EXEC_RIGHT;
    ev.u.hb.time_scale = 10.0;
    ev.u.hb.protocol = HV_CAN_PROTOCOL_VERSION + 1;
    fx_event(fx, &ev);
    fx->now_ns += 300000000ull; /* a gap in the steps, short of the heartbeat timeout */
    fx_run(fx, 0.5);
    fx->node[HV_EXEC_LEFT].time_scale = 12.0;
    run(fx, 5.0);
    setup(fx, t, 1, 1); /* start-up's homing faults */
    fx->f.home_faults[0] = 1;
    fx_start(fx, NULL);
    run(fx, 5.0);
    setup(fx, t, 1, 1); /* start-up's commands lost until its timeout */
    fx->f.drop_next[HV_ACT_COMMAND] = 20;
    fx_start(fx, NULL);
    run(fx, 10.0);
}

static void sc_odd_arms(fx_t *fx, exec_trace_t *t)
{
    setup(fx, t, 1, 2); /* a release that fails */
    fx_start(fx, NULL);
    until_arm(fx, 0, HV_ARM_RELEASE, 10.0);
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = HV_EV_EE_STATUS;
    ev.node = HV_EXEC_LEFT;
    ev.u.ee.state = HV_CAN_EE_STATE_FAILED;
    ev.u.ee.action = HV_CAN_EE_ACTION_RELEASE;
    ev.u.ee.ee_seq = fx->sm.arm[0].ee_seq;
    ev.u.ee.fruit_held = 1;
    fx_event(fx, &ev);
    run(fx, 30.0);
    setup(fx, t, 1, 1); /* a fault of an arm done with its stop, the other still at work */
    fx->f.stall[1] = 1;
    fx_start(fx, NULL);
    until_arm(fx, 0, HV_ARM_DONE, 10.0);
    fx->node[HV_EXEC_LEFT].fault_bits |= HV_CAN_ARM_FAULT_JOINT2_LIMIT;
    fx->node[HV_EXEC_LEFT].state = HV_CAN_STATE_FAULT;
    fx_run(fx, 2.0);
    fx->f.stall[1] = 0;
    run(fx, 30.0);
}

/* xorshift32: the seeded runs' faults, the same on every machine */
static uint32_t rnd(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

/* One fault of the fixture's list, or a stop, a lost node, an e-stop, chosen by r. */
static void inject(fx_t *fx, uint32_t r)
{
    int side = (int)(r >> 8) & 1;
    switch ((r >> 9) % 12) {
    case 0: fx->f.drop_next[HV_ACT_COMMAND + (int)(r >> 13) % 4]++; break;
    case 1: fx->f.joint_fault_at[side] = fx->setpoints_sent[side] + 1; break;
    case 2: fx->f.reject_setpoints[side]++; break;
    case 3: fx->f.cut_fail[side]++; break;
    case 4: fx->f.drop[side]++; break;
    case 5: fx->f.stall[side] = !fx->f.stall[side]; break;
    case 6: fx->f.estop_at_cut = fx->cuts_sent[1] + 1; break;
    case 7: event(fx, HV_EV_STOP_REQUEST, (int)(r >> 13) & 1); break;
    case 8: fx->node[(r >> 13) % HV_EXEC_NODES].alive = 0; break;
    case 9: fx->f.comm_fault_arm = fx->setpoints_sent[0] + 1; break;
    case 10: fx->f.vehicle_fault_on_move = fx->moves_sent + 1; break;
    default: fx->f.drop_next[HV_ACT_MOVE]++; break;
    }
}

/* A row with faults at random (seeded) times; after each end short of the row's, a restart
 * on the journal with the operator's clear and the nodes alive again, three runs at most. */
static void seeded(fx_t *fx, exec_trace_t *t, uint32_t seed)
{
    uint32_t s = seed * 2654435761u + 1u;
    setup(fx, t, 3, 2);
    fx->motion_ns = 200000000ull;
    fx_start(fx, NULL);
    for (int runs = 0; runs < 3; runs++) {
        for (int k = 0; k < 600 && !hv_exec_finished(&fx->sm); k++) {
            uint32_t r = rnd(&s);
            if ((r & 0xFF) < 40) /* one 100 ms in six or so */
                inject(fx, r);
            fx_run(fx, 0.1);
        }
        fx_run(fx, 0.5);
        if (fx->sm.phase == HV_PH_ROW_DONE)
            return;
        memset(&fx->f, 0, sizeof fx->f);
        for (int i = 0; i < HV_EXEC_NODES; i++)
            fx->node[i].alive = 1;
        fx->prm.clear_estop = 1;
        fx_restart(fx);
    }
}

const exec_scenario_t exec_scenarios[] = {
    {"row", "a row of 3 stops, 2 picks per arm at each, healthy nodes", .stops = 3, .per_arm = 2,
     .max_s = 60.0},
    {"lossy", "the bus loses 2 of each kind of command frame: resent", .stops = 2, .per_arm = 2,
     .max_s = 60.0,
     .f = {.drop_next =
               {[HV_ACT_COMMAND] = 2, [HV_ACT_SETPOINT] = 2, [HV_ACT_EE] = 2, [HV_ACT_MOVE] = 2}}},
    {"arm-faults",
     "joint faults, a rejected setpoint, a failed cut, a dropped fruit, an unreachable pick",
     .run = sc_arm_faults},
    {"gives-up", "faults on every attempt: failed and skipped after the retries", .stops = 2,
     .per_arm = 2, .max_s = 120.0,
     .f = {.joint_fault_every = {0, 1}, .reject_setpoints = {100, 0}}},
    {"stall-cut-fail", "a stalled arm (timeouts) and cuts that always fail", .stops = 2,
     .per_arm = 1, .max_s = 120.0, .f = {.stall = {1, 0}, .cut_fail = {0, 100}}},
    {"estop-restarts", "an e-stop at a cut; a restart without the clear, one with it",
     .run = sc_estop_restarts},
    {"latched-at-start", "a node latched at start-up, no operator clear",
     .run = sc_latched_at_start},
    {"lost-heartbeat", "the vehicle's heartbeat stops mid-row", .run = sc_lost_heartbeat},
    {"comm-fault", "an arm reports it lost our heartbeat", .stops = 2, .per_arm = 2, .max_s = 30.0,
     .f = {.comm_fault_arm = 2}},
    {"vehicle-fault", "the vehicle faults on its second move", .stops = 2, .per_arm = 1,
     .max_s = 60.0, .f = {.vehicle_fault_on_move = 2}},
    {"move-never", "the vehicle never arrives", .stops = 2, .per_arm = 1, .max_s = 60.0,
     .f = {.move_never = 1}},
    {"recovery-fails", "a recovery's HOME never ends; then one that faults",
     .run = sc_recovery_fails},
    {"start-fails", "homing times out; a node absent; time scales that disagree",
     .run = sc_start_fails},
    {"operator-stop", "a signal mid-row, the controlled stop, a restart to the row's end",
     .run = sc_operator_stop},
    {"stop-variants",
     "bus stop requests repeated; at once before the nodes; a second signal; a journal failure",
     .run = sc_stop_variants},
    {"resume", "a restart with picks cut, held, not held and released", .run = sc_resume},
    {"online", "the plan grows while the row runs, the vehicle waits and advances",
     .run = sc_online},
    {"online-stops",
     "online: a silent planner; the operator's stop while waiting, while advancing; an "
     "advance that never arrives",
     .run = sc_online_stops},
    {"odd-events",
     "another protocol's heartbeat, a gap in the steps, a time scale that changes; start-up's "
     "homing faults, its commands lost",
     .run = sc_odd_events},
    {"odd-arms", "a release that fails; a fault of an arm done with its stop", .run = sc_odd_arms},
    {"seeded-1", "faults at random, seed 1", .seed = 1},
    {"seeded-2", "faults at random, seed 2", .seed = 2},
    {"seeded-3", "faults at random, seed 3", .seed = 3},
    {"seeded-4", "faults at random, seed 4", .seed = 4},
    {"seeded-5", "faults at random, seed 5", .seed = 5},
    {"seeded-6", "faults at random, seed 6", .seed = 6},
    {"seeded-7", "faults at random, seed 7", .seed = 7},
    {"seeded-8", "faults at random, seed 8", .seed = 8},
};

void exec_scenario_run(fx_t *fx, exec_trace_t *t, const exec_scenario_t *sc)
{
    if (sc->run) {
        sc->run(fx, t);
    } else if (sc->seed) {
        seeded(fx, t, sc->seed);
    } else {
        setup(fx, t, sc->stops, sc->per_arm);
        fx->f = sc->f;
        fx_start(fx, NULL);
        run(fx, sc->max_s);
    }
}

const size_t exec_n_scenarios = sizeof exec_scenarios / sizeof exec_scenarios[0];
