/* The executor's state machine through every transition and each fault, with the fake
 * clock and bus of exec_fixture.c. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "exec_fixture.h"
#include "hv/exec_status.h"

static fx_t *new_fx(int stops, int per_arm)
{
    fx_t *fx = malloc(sizeof *fx); /* large: keep it off the stack */
    assert_non_null(fx);
    fx_plan(fx, stops, per_arm);
    return fx;
}

/* Outcome records in the log, for one pick. */
static int outcome_of(const fx_t *fx, int pick, int *reason, int *attempt)
{
    int found = -1;
    for (int i = 0; i < fx->nlog; i++) {
        const hv_exec_action_t *a = &fx->log[i].a;
        if (a->kind == HV_ACT_JOURNAL && a->u.jr.kind == HV_JR_OUTCOME && a->u.jr.pick == pick) {
            assert_int_equal(found, -1); /* never two outcomes */
            found = a->u.jr.outcome;
            if (reason)
                *reason = a->u.jr.reason;
            if (attempt)
                *attempt = a->u.jr.attempt;
        }
    }
    return found;
}

static void test_whole_row(void **state)
{
    (void)state;
    fx_t *fx = new_fx(2, 2);
    fx_start(fx, NULL);
    fx_run(fx, 30.0);
    assert_int_equal(fx->sm.phase, HV_PH_ROW_DONE);
    assert_int_equal(fx->sm.picked, fx->plan.n_picks);
    assert_int_equal(fx->sm.failed + fx->sm.skipped + fx->sm.faults, 0);
    /* start-up: DISABLE, CLEAR_FAULT, ENABLE to all, then HOME to both arms */
    int d = fx_find(fx, 0, HV_ACT_COMMAND, HV_CAN_CMD_DISABLE);
    int c = fx_find(fx, 0, HV_ACT_COMMAND, HV_CAN_CMD_CLEAR_FAULT);
    int e = fx_find(fx, 0, HV_ACT_COMMAND, HV_CAN_CMD_ENABLE);
    int h = fx_find(fx, 0, HV_ACT_COMMAND, HV_CAN_CMD_HOME);
    int m = fx_find(fx, 0, HV_ACT_MOVE, -1);
    assert_true(d >= 0 && d < c && c < e && e < h && h < m);
    assert_int_equal(fx_count(fx, HV_ACT_COMMAND, HV_CAN_CMD_HOME), 2);
    /* sequence numbers continue after what the nodes echoed before we started */
    assert_int_equal(fx->log[d].a.u.cmd.seq, (fx->log[d].a.node + 1) * 7 + 1);
    assert_int_equal(fx->log[c].a.u.cmd.seq, (fx->log[c].a.node + 1) * 7 + 2);
    /* 2 stops + the row end; journal: one S per stop, C R F per pick, D */
    assert_int_equal(fx_count(fx, HV_ACT_MOVE, -1), 3);
    assert_int_equal(fx_count(fx, HV_ACT_JOURNAL, HV_JR_STOP), 2);
    assert_int_equal(fx_count(fx, HV_ACT_JOURNAL, HV_JR_CUT), fx->plan.n_picks);
    assert_int_equal(fx_count(fx, HV_ACT_JOURNAL, HV_JR_RELEASE), fx->plan.n_picks);
    assert_int_equal(fx_count(fx, HV_ACT_JOURNAL, HV_JR_OUTCOME), fx->plan.n_picks);
    assert_int_equal(fx_count(fx, HV_ACT_JOURNAL, HV_JR_DONE), 1);
    /* every cut is journalled before it is commanded, and each arm picks in plan order */
    int last[2] = {-1, -1};
    for (int i = 0; i < fx->nlog; i++) {
        const hv_exec_action_t *a = &fx->log[i].a;
        if (a->kind == HV_ACT_EE && a->u.ee.action == HV_CAN_EE_ACTION_CUT) {
            assert_true(i > 0);
            const hv_exec_action_t *prev = &fx->log[i - 1].a;
            assert_int_equal(prev->kind, HV_ACT_JOURNAL);
            assert_int_equal(prev->u.jr.kind, HV_JR_CUT);
        }
        if (a->kind == HV_ACT_JOURNAL && a->u.jr.kind == HV_JR_OUTCOME) {
            int side = fx->plan.picks[a->u.jr.pick].side;
            assert_true(a->u.jr.pick > last[side]);
            last[side] = a->u.jr.pick;
        }
    }
    for (int p = 0; p < fx->plan.n_picks; p++) {
        int reason;
        assert_int_equal(outcome_of(fx, p, &reason, NULL), HV_OUT_PICKED);
        assert_int_equal(reason, HV_RSN_OK);
        assert_int_equal(fx->cuts_done[fx->plan.picks[p].side][p], 1);
    }
    /* the row ends with every node disabled (3 more DISABLEs than at start-up) */
    assert_int_equal(fx_count(fx, HV_ACT_COMMAND, HV_CAN_CMD_DISABLE), 6);
    assert_true(hv_exec_executed_s(&fx->sm, fx->now_ns) > 0.0);
    assert_int_equal(fx_count(fx, HV_ACT_ESTOP, -1), 0);
    free(fx);
}

static void test_heartbeats_sent(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 1);
    fx->motion_ns = 300000000ull; /* a slower row, so it is still running */
    fx_start(fx, NULL);
    fx_run(fx, 1.0);
    /* 100 ms period over 1 s: 10 or 11 of them */
    int n = fx_count(fx, HV_ACT_HEARTBEAT, -1);
    assert_true(n >= 10 && n <= 11);
    free(fx);
}

static void test_nodes_absent(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 1);
    fx_start(fx, NULL);
    fx->node[HV_EXEC_RIGHT].alive = 0;
    fx_run(fx, 12.0);
    assert_int_equal(fx->sm.phase, HV_PH_SAFE);
    assert_int_equal(fx->sm.safe_reason, HV_SAFE_NODES_ABSENT);
    assert_int_equal(fx_count(fx, HV_ACT_MOVE, -1), 0);
    free(fx);
}

static void test_time_scale_mismatch(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 1);
    fx_start(fx, NULL);
    fx->node[HV_EXEC_LEFT].time_scale = 5.0;
    fx_run(fx, 1.0);
    assert_int_equal(fx->sm.safe_reason, HV_SAFE_TIME_SCALE);
    assert_int_equal(fx->sm.safe_node, HV_EXEC_LEFT);
    free(fx);

    fx = new_fx(1, 1);
    fx->prm.time_scale = 20.0; /* we were told 20, the nodes run at 10 */
    fx_start(fx, NULL);
    fx_run(fx, 1.0);
    assert_int_equal(fx->sm.safe_reason, HV_SAFE_TIME_SCALE);
    free(fx);
}

static void test_lost_heartbeat(void **state)
{
    (void)state;
    fx_t *fx = new_fx(2, 2);
    fx->motion_ns = 300000000ull; /* a slower row, so it is still running */
    fx_start(fx, NULL);
    fx_run(fx, 0.8);
    assert_int_not_equal(fx->sm.phase, HV_PH_SAFE);
    int before = fx->nlog;
    fx->node[HV_EXEC_VEHICLE].alive = 0;
    fx_run(fx, 2.0);
    assert_int_equal(fx->sm.phase, HV_PH_SAFE);
    assert_int_equal(fx->sm.safe_reason, HV_SAFE_HEARTBEAT);
    assert_int_equal(fx->sm.safe_node, HV_EXEC_VEHICLE);
    /* the e-stop is the first action, then repeated every 100 ms with ESTOP heartbeats */
    int first = fx_find(fx, before, HV_ACT_ESTOP, -1);
    assert_true(first >= 0);
    /* detected within the heartbeat timeout after the last heartbeat (<= 100 ms before
     * the node fell silent) plus one tick */
    double silent_for = (double)(fx->log[first].t_ns - fx->log[before - 1].t_ns) * 1e-9;
    assert_true(silent_for <= fx->prm.heartbeat_timeout_s + 0.1 + 0.011);
    assert_true(silent_for >= fx->prm.heartbeat_timeout_s - 0.1);
    /* nothing moves after the e-stop */
    assert_true(fx_find(fx, first, HV_ACT_SETPOINT, -1) < 0);
    assert_true(fx_find(fx, first, HV_ACT_MOVE, -1) < 0);
    assert_true(fx_count(fx, HV_ACT_ESTOP, -1) >= 10);
    int hb = fx_find(fx, first, HV_ACT_HEARTBEAT, -1);
    assert_int_equal(fx->log[hb].a.u.hb.health, HV_CAN_HEALTH_ESTOP);
    free(fx);
}

static void test_node_estop(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 2);
    fx->f.estop_at_cut = 1;
    fx_start(fx, NULL);
    fx_run(fx, 10.0);
    assert_int_equal(fx->sm.phase, HV_PH_SAFE);
    assert_int_equal(fx->sm.safe_reason, HV_SAFE_ESTOP);
    assert_int_equal(fx->sm.safe_node, HV_EXEC_RIGHT);
    /* what was done is kept: the right arm's cut was journalled, nothing after the stop */
    int safe_at = fx_find(fx, 0, HV_ACT_ESTOP, -1);
    assert_true(fx_find(fx, safe_at, HV_ACT_SETPOINT, -1) < 0);
    assert_true(fx_find(fx, safe_at, HV_ACT_EE, -1) < 0);
    free(fx);
}

static void test_comm_fault(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 1);
    fx->f.comm_fault_arm = 1;
    fx_start(fx, NULL);
    fx_run(fx, 10.0);
    assert_int_equal(fx->sm.safe_reason, HV_SAFE_COMM);
    assert_int_equal(fx->sm.safe_node, HV_EXEC_LEFT);
    free(fx);
}

static void test_joint_fault_retry(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 2);
    fx->f.joint_fault_at[0] = 1; /* the left arm's first setpoint faults */
    fx_start(fx, NULL);
    fx_run(fx, 30.0);
    assert_int_equal(fx->sm.phase, HV_PH_ROW_DONE);
    assert_int_equal(fx->sm.faults, 1);
    assert_int_equal(fx->sm.picked, fx->plan.n_picks);
    int attempt;
    assert_int_equal(outcome_of(fx, 0, NULL, &attempt), HV_OUT_PICKED);
    assert_int_equal(attempt, 2);
    /* recovery: DISABLE, CLEAR_FAULT, ENABLE, HOME to the left arm, in that order */
    int d = fx_find(fx, fx_find(fx, 0, HV_ACT_MOVE, -1), HV_ACT_COMMAND, HV_CAN_CMD_DISABLE);
    assert_true(d >= 0);
    assert_int_equal(fx->log[d].a.node, HV_EXEC_LEFT);
    int cl = fx_find(fx, d, HV_ACT_COMMAND, HV_CAN_CMD_CLEAR_FAULT);
    int en = fx_find(fx, cl, HV_ACT_COMMAND, HV_CAN_CMD_ENABLE);
    int ho = fx_find(fx, en, HV_ACT_COMMAND, HV_CAN_CMD_HOME);
    assert_true(cl > d && en > cl && ho > en);
    assert_int_equal(fx->log[ho].a.node, HV_EXEC_LEFT);
    free(fx);
}

static void test_joint_fault_gives_up(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 2);
    fx->f.joint_fault_every[1] = 1;
    fx_start(fx, NULL);
    fx_run(fx, 60.0);
    assert_int_equal(fx->sm.phase, HV_PH_ROW_DONE);
    int first_right = fx->plan.stops[0].first[1];
    for (int k = 0; k < 2; k++) {
        int reason, attempt;
        assert_int_equal(outcome_of(fx, first_right + k, &reason, &attempt), HV_OUT_FAILED);
        assert_int_equal(reason, HV_RSN_JOINT_FAULT);
        assert_int_equal(attempt, (int)fx->prm.max_retries + 1);
    }
    assert_int_equal(fx->sm.picked, 2); /* the left arm was not held up */
    assert_int_equal(fx->sm.failed, 2);
    assert_int_equal(fx->sm.faults, 2 * (fx->prm.max_retries + 1));
    free(fx);
}

static void test_rejected_setpoint(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 1);
    fx->f.reject_setpoints[0] = 100; /* always */
    fx_start(fx, NULL);
    fx_run(fx, 60.0);
    assert_int_equal(fx->sm.phase, HV_PH_ROW_DONE);
    int reason;
    assert_int_equal(outcome_of(fx, 0, &reason, NULL), HV_OUT_SKIPPED);
    assert_int_equal(reason, HV_RSN_REJECTED);
    assert_int_equal(fx_count(fx, HV_ACT_JOURNAL, HV_JR_CUT), 1); /* only the right arm */
    free(fx);

    fx = new_fx(1, 1);
    fx->f.reject_setpoints[0] = 1; /* once: the retry succeeds */
    fx_start(fx, NULL);
    fx_run(fx, 60.0);
    int attempt;
    assert_int_equal(outcome_of(fx, 0, &reason, &attempt), HV_OUT_PICKED);
    assert_int_equal(attempt, 2);
    free(fx);
}

static void test_approach_timeout(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 1);
    fx->f.stall[0] = 1;
    fx_start(fx, NULL);
    fx_run(fx, 120.0);
    assert_int_equal(fx->sm.phase, HV_PH_ROW_DONE);
    int reason;
    assert_int_equal(outcome_of(fx, 0, &reason, NULL), HV_OUT_FAILED);
    assert_int_equal(reason, HV_RSN_TIMEOUT);
    /* the timeout came after the planned time / scale, not before */
    int sp = fx_find(fx, 0, HV_ACT_SETPOINT, -1);
    int dis = fx_find(fx, sp, HV_ACT_COMMAND, HV_CAN_CMD_DISABLE);
    double waited = (double)(fx->log[dis].t_ns - fx->log[sp].t_ns) * 1e-9;
    double planned = fx->plan.picks[0].move_s / 10.0;
    assert_true(waited >= planned * (1.0 + fx->prm.margin));
    free(fx);
}

static void test_cut_failed(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 1);
    fx->f.cut_fail[1] = 1; /* the right arm's first cut fails, the second works */
    fx_start(fx, NULL);
    fx_run(fx, 30.0);
    int right = fx->plan.stops[0].first[1], attempt;
    assert_int_equal(outcome_of(fx, right, NULL, &attempt), HV_OUT_PICKED);
    assert_int_equal(attempt, 2);
    free(fx);

    fx = new_fx(1, 1);
    fx->f.cut_fail[1] = 100;
    fx_start(fx, NULL);
    fx_run(fx, 60.0);
    int reason;
    assert_int_equal(outcome_of(fx, right, &reason, NULL), HV_OUT_FAILED);
    assert_int_equal(reason, HV_RSN_CUT_FAILED);
    assert_int_equal(fx->sm.phase, HV_PH_ROW_DONE);
    free(fx);
}

static void test_dropped_never_cut_twice(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 2);
    fx->f.drop[0] = 1;
    fx_start(fx, NULL);
    fx_run(fx, 30.0);
    int reason;
    assert_int_equal(outcome_of(fx, 0, &reason, NULL), HV_OUT_FAILED);
    assert_int_equal(reason, HV_RSN_DROPPED);
    assert_int_equal(fx->cuts_done[0][0], 1);
    assert_int_equal(outcome_of(fx, 1, NULL, NULL), HV_OUT_PICKED);
    free(fx);
}

static void test_vehicle_faults(void **state)
{
    (void)state;
    fx_t *fx = new_fx(2, 1);
    fx->f.move_never = 1;
    fx_start(fx, NULL);
    fx_run(fx, 60.0);
    assert_int_equal(fx->sm.safe_reason, HV_SAFE_TIMEOUT);
    assert_int_equal(fx->sm.safe_node, HV_EXEC_VEHICLE);
    free(fx);

    fx = new_fx(2, 1);
    fx->f.vehicle_fault_on_move = 2;
    fx_start(fx, NULL);
    fx_run(fx, 60.0);
    assert_int_equal(fx->sm.safe_reason, HV_SAFE_VEHICLE_FAULT);
    assert_int_equal(fx->sm.picked, 2); /* the first stop was finished */
    free(fx);
}

static void test_recovery_fails(void **state)
{
    (void)state;
    /* the recovery's HOME never completes (its timeout), or faults the arm again (at once) */
    for (int faults = 0; faults < 2; faults++) {
        fx_t *fx = new_fx(1, 1);
        fx->f.joint_fault_at[0] = 1;
        fx->motion_ns = 300000000ull; /* a slower row, so it is still running */
        fx_start(fx, NULL);
        fx_run(fx, 0.5); /* through start-up homing, which works */
        if (faults)
            fx->f.home_faults[0] = 1;
        else
            fx->f.home_never[0] = 1;
        fx_run(fx, 120.0);
        assert_int_equal(fx->sm.phase, HV_PH_SAFE);
        assert_int_equal(fx->sm.safe_reason, faults ? HV_SAFE_FAULT : HV_SAFE_TIMEOUT);
        assert_int_equal(fx->sm.safe_node, HV_EXEC_LEFT);
        /* the e-stop comes after the recovery's HOME; a fault stops before its deadline */
        int home = fx_find(fx, fx_find(fx, 0, HV_ACT_MOVE, -1), HV_ACT_COMMAND, HV_CAN_CMD_HOME);
        int stop = fx_find(fx, home, HV_ACT_ESTOP, -1);
        assert_true(home >= 0 && stop > home);
        assert_true(faults == (fx->log[stop].t_ns < fx->sm.arm[0].deadline_ns));
        free(fx);
    }
}

static void test_homing_fails(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 1);
    fx->f.home_never[1] = 1;
    fx_start(fx, NULL);
    fx_run(fx, 60.0);
    assert_int_equal(fx->sm.safe_reason, HV_SAFE_TIMEOUT);
    assert_int_equal(fx_count(fx, HV_ACT_MOVE, -1), 0);
    free(fx);
}

/* from_bus: 0 a signal (SIGTERM), 1 the bus's ExecutorStopRequest */
static void stop_request(fx_t *fx, int from_bus)
{
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = HV_EV_STOP_REQUEST;
    ev.u.stop.from_bus = from_bus;
    fx_event(fx, &ev);
}

/* A slower row (0.3 s per motion), started and run for `seconds`, so work is under way. */
static fx_t *running_fx(int stops, int per_arm, double seconds)
{
    fx_t *fx = new_fx(stops, per_arm);
    fx->motion_ns = 300000000ull;
    fx_start(fx, NULL);
    fx_run(fx, seconds);
    return fx;
}

/* SIGTERM mid-row: the picks under way finish, every node is disabled, nothing is latched,
 * and a plain restart picks the rest, none twice. */
static void test_operator_stop_is_controlled_and_resumable(void **state)
{
    (void)state;
    fx_t *fx = running_fx(3, 2, 1.5);
    assert_int_equal(fx->sm.phase, HV_PH_HARVEST);
    int from = fx->nlog;
    stop_request(fx, 0);
    assert_false(hv_exec_finished(&fx->sm)); /* a pick was under way */
    fx_run(fx, 30.0);
    assert_int_equal(fx->sm.phase, HV_PH_STOPPED);
    assert_true(hv_exec_finished(&fx->sm));
    assert_int_equal(fx_count(fx, HV_ACT_ESTOP, -1), 0);
    /* journalled, with its reason, before the DISABLEs */
    int h = fx_find(fx, from, HV_ACT_JOURNAL, HV_JR_HALT);
    assert_true(h >= 0);
    assert_int_equal(fx->log[h].a.u.jr.reason, HV_STOP_OPERATOR);
    assert_true(fx_find(fx, h, HV_ACT_COMMAND, HV_CAN_CMD_DISABLE) > h);
    for (int i = 0; i < HV_EXEC_NODES; i++)
        assert_int_equal(fx->node[i].estop, 0);
    /* every cut issued has its outcome: no pick left half done */
    assert_int_equal(fx_count(fx, HV_ACT_JOURNAL, HV_JR_CUT),
                     fx_count(fx, HV_ACT_JOURNAL, HV_JR_OUTCOME));
    assert_int_equal(fx_count(fx, HV_ACT_JOURNAL, HV_JR_DONE), 0);
    unsigned picked = fx->sm.picked;
    assert_true(picked > 0 && picked < (unsigned)fx->plan.n_picks);
    /* after the request: no move, and each node's last command is DISABLE */
    assert_true(fx_find(fx, from, HV_ACT_MOVE, -1) < 0);
    for (int i = 0; i < HV_EXEC_NODES; i++) {
        int last = -1;
        for (int k = from; k < fx->nlog; k++)
            if (fx->log[k].a.kind == HV_ACT_COMMAND && fx->log[k].a.node == i)
                last = fx->log[k].a.u.cmd.command;
        assert_int_equal(last, HV_CAN_CMD_DISABLE);
    }

    int run2 = fx_restart(fx); /* no --clear-estop: none is needed */
    fx_run(fx, 60.0);
    assert_int_equal(fx->sm.phase, HV_PH_ROW_DONE);
    assert_int_equal(picked + fx->sm.picked, fx->plan.n_picks);
    for (int p = 0; p < fx->plan.n_picks; p++)
        assert_int_equal(fx->cuts_done[fx->plan.picks[p].side][p], 1);
    assert_true(fx_find(fx, run2, HV_ACT_COMMAND, HV_CAN_CMD_CLEAR_ESTOP) < 0);
    free(fx);
}

/* The bus's stop request, repeated as a panel repeats it, stays one controlled stop. */
static void test_a_repeated_bus_stop_request_is_one_request(void **state)
{
    (void)state;
    fx_t *fx = running_fx(2, 2, 1.5);
    for (int i = 0; i < 5; i++)
        stop_request(fx, 1);
    assert_false(hv_exec_finished(&fx->sm));
    fx_run(fx, 30.0);
    assert_int_equal(fx->sm.phase, HV_PH_STOPPED);
    assert_int_equal(fx_count(fx, HV_ACT_ESTOP, -1), 0);
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = HV_EV_STOP_REQUEST;
    ev.u.stop.from_bus = 2; /* neither bus nor signal: refused */
    hv_exec_actions_t out = {0};
    assert_int_equal(hv_exec_step(&fx->sm, &ev, fx->now_ns, &out), HV_ERR_EXEC_EVENT);
    free(fx);
}

/* Where nothing moves (waiting for the nodes), the stop is at once; a second request
 * before a controlled stop ends is an e-stop; a journal failure always is. */
static void test_second_stop_and_journal_failure_are_estops(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 2);
    fx_start(fx, NULL);
    stop_request(fx, 0); /* the first step: no node seen yet */
    assert_int_equal(fx->sm.phase, HV_PH_STOPPED);
    assert_int_equal(fx_count(fx, HV_ACT_ESTOP, -1), 0);
    free(fx);
    for (int which = 0; which < 2; which++) {
        fx = running_fx(1, 2, 1.0);
        hv_exec_event_t ev;
        memset(&ev, 0, sizeof ev);
        ev.kind = which ? HV_EV_JOURNAL_FAILED : HV_EV_STOP_REQUEST;
        if (!which) {
            stop_request(fx, 0);
            assert_false(hv_exec_finished(&fx->sm));
        }
        hv_exec_actions_t out = {0};
        assert_int_equal(hv_exec_step(&fx->sm, &ev, fx->now_ns, &out), HV_OK);
        assert_true(out.n >= 1);
        assert_int_equal(out.a[0].kind, HV_ACT_ESTOP);
        assert_int_equal(fx->sm.safe_reason, which ? HV_SAFE_JOURNAL : HV_SAFE_OPERATOR);
        assert_true(hv_exec_finished(&fx->sm));
        free(fx);
    }
}

/* ---- the e-stop latch and the operator's clear ---------------------------------------- */

static int commands_from(const fx_t *fx, int from, int command)
{
    int n = 0;
    for (int i = from; (i = fx_find(fx, i, HV_ACT_COMMAND, command)) >= 0; i++)
        n++;
    return n;
}

static void test_latched_estop_keeps_a_start_safe(void **state)
{
    (void)state;
    for (int latched = 0; latched < HV_EXEC_NODES; latched++) {
        fx_t *fx = new_fx(1, 2);
        fx_start(fx, NULL);
        fx_latch_estop(fx, latched); /* a previous run's e-stop, or a button on the node */
        fx_run(fx, 5.0);
        assert_int_equal(fx->sm.phase, HV_PH_SAFE);
        assert_int_equal(fx->sm.safe_reason, HV_SAFE_ESTOP_LATCHED);
        assert_int_equal(fx->sm.safe_node, latched);
        /* not a single command: no DISABLE, CLEAR_FAULT, CLEAR_ESTOP, ENABLE, HOME */
        assert_int_equal(fx_count(fx, HV_ACT_COMMAND, -1), 0);
        assert_int_equal(fx_count(fx, HV_ACT_JOURNAL, HV_JR_ESTOP_CLEAR), 0);
        assert_int_equal(fx_count(fx, HV_ACT_MOVE, -1) + fx_count(fx, HV_ACT_SETPOINT, -1), 0);
        assert_true(fx_count(fx, HV_ACT_ESTOP, -1) >= 10); /* it stays safe, saying so */
        assert_int_equal(fx->estop_clears[latched], 0);
        assert_int_equal(fx->node[latched].estop, 1);
        free(fx);
    }
}

/* An e-stop mid-row; a restart without the operator's clear stays safe; one with it
 * resumes: no fruit cut twice, none lost. */
static void test_estop_then_restarts(void **state)
{
    (void)state;
    fx_t *fx = new_fx(2, 2);
    fx->f.estop_at_cut = 3; /* the right arm's e-stop trips on its third cut */
    fx_start(fx, NULL);
    fx_run(fx, 30.0);
    assert_int_equal(fx->sm.safe_reason, HV_SAFE_ESTOP);
    assert_int_equal(fx->sm.safe_node, HV_EXEC_RIGHT);
    unsigned picked = fx->sm.picked;
    assert_true(picked > 0 && picked < fx->plan.n_picks);

    int run2 = fx_restart(fx); /* the operator did not clear it */
    fx_run(fx, 5.0);
    assert_int_equal(fx->sm.safe_reason, HV_SAFE_ESTOP_LATCHED);
    assert_true(fx_find(fx, run2, HV_ACT_COMMAND, -1) < 0);
    for (int i = 0; i < HV_EXEC_NODES; i++)
        assert_int_equal(fx->node[i].estop, 1);

    fx->prm.clear_estop = 1;
    int run3 = fx_restart(fx);
    fx_run(fx, 60.0);
    assert_int_equal(fx->sm.phase, HV_PH_ROW_DONE);
    assert_int_equal(picked + fx->sm.picked, fx->plan.n_picks);
    for (int p = 0; p < fx->plan.n_picks; p++)
        assert_int_equal(fx->cuts_done[fx->plan.picks[p].side][p], 1);
    /* the clear: journalled first, then CLEAR_ESTOP once to each latched node, and only
     * then CLEAR_FAULT, ENABLE and HOME */
    int e = fx_find(fx, run3, HV_ACT_JOURNAL, HV_JR_ESTOP_CLEAR);
    assert_true(e >= 0);
    assert_int_equal(fx->log[e].a.u.jr.nodes, HV_EXEC_ALL_NODES);
    assert_int_equal(fx_count(fx, HV_ACT_JOURNAL, HV_JR_ESTOP_CLEAR), 1);
    int c = fx_find(fx, run3, HV_ACT_COMMAND, HV_CAN_CMD_CLEAR_ESTOP);
    int f = fx_find(fx, run3, HV_ACT_COMMAND, HV_CAN_CMD_CLEAR_FAULT);
    int en = fx_find(fx, run3, HV_ACT_COMMAND, HV_CAN_CMD_ENABLE);
    int h = fx_find(fx, run3, HV_ACT_COMMAND, HV_CAN_CMD_HOME);
    assert_true(e < c && c < f && f < en && en < h);
    assert_int_equal(commands_from(fx, 0, HV_CAN_CMD_CLEAR_ESTOP), HV_EXEC_NODES);
    for (int i = 0; i < HV_EXEC_NODES; i++)
        assert_int_equal(fx->estop_clears[i], 1);
    free(fx);
}

/* ---- by hand: the frames of each node in the order they arrive -------------------------- */

typedef struct hand {
    fx_t *fx;
    hv_exec_actions_t out;                               /* the last step's actions */
    int sent[HV_EXEC_NODES][HV_CAN_CMD_CLEAR_ESTOP + 1]; /* commands sent so far, by kind */
    int seq[HV_EXEC_NODES];                              /* the last command's sequence number */
} hand_t;

static void hand_step(hand_t *h, hv_exec_event_t *ev)
{
    h->fx->now_ns += 10000000ull; /* 10 ms a frame: far inside every timeout */
    h->out.n = 0;
    assert_int_equal(hv_exec_step(&h->fx->sm, ev, h->fx->now_ns, &h->out), HV_OK);
    for (unsigned k = 0; k < h->out.n; k++) {
        const hv_exec_action_t *a = &h->out.a[k];
        if (a->kind == HV_ACT_COMMAND) {
            h->sent[a->node][a->u.cmd.command]++;
            h->seq[a->node] = a->u.cmd.seq;
        }
    }
}

static void hand_hb(hand_t *h, int node, int health)
{
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = HV_EV_HEARTBEAT;
    ev.node = node;
    ev.u.hb.health = health;
    ev.u.hb.time_scale = 10.0;
    ev.u.hb.protocol = HV_CAN_PROTOCOL_VERSION;
    hand_step(h, &ev);
}

/* A status echoing `cmd_seq`; `estop` says whether the node still holds its e-stop. */
static void hand_status(hand_t *h, int node, int state, int cmd_seq, int estop)
{
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.node = node;
    if (node == HV_EXEC_VEHICLE) {
        ev.kind = HV_EV_VEHICLE_STATUS;
        ev.u.veh.state = state;
        ev.u.veh.cmd_seq = cmd_seq;
        ev.u.veh.fault_bits = estop ? HV_CAN_VEHICLE_FAULT_ESTOP : 0;
    } else {
        ev.kind = HV_EV_ARM_STATUS;
        ev.u.arm.state = state;
        ev.u.arm.cmd_seq = cmd_seq;
        ev.u.arm.fault_bits = estop ? HV_CAN_ARM_FAULT_ESTOP : 0;
    }
    hand_step(h, &ev);
}

static void hand_tick(hand_t *h)
{
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = HV_EV_TICK;
    hand_step(h, &ev);
}

static int hand_sent(const hand_t *h, int command)
{
    int n = 0;
    for (int i = 0; i < HV_EXEC_NODES; i++)
        n += h->sent[i][command];
    return n;
}

/* Start-up with both arms latched (the vehicle not) and the operator's clear: up to the
 * point where every CLEAR_ESTOP has been echoed. The nodes' heartbeats from before the
 * clear still say ESTOP. */
static void hand_clear(hand_t *h)
{
    fx_t *fx = new_fx(1, 1);
    fx->prm.clear_estop = 1;
    fx_start(fx, NULL);
    memset(h, 0, sizeof *h);
    h->fx = fx;
    for (int i = 0; i < HV_EXEC_NODES; i++) {
        int latched = i != HV_EXEC_VEHICLE;
        hand_hb(h, i, latched ? HV_CAN_HEALTH_ESTOP : HV_CAN_HEALTH_OK);
        hand_status(h, i, latched ? HV_CAN_STATE_ESTOP : HV_CAN_STATE_DISABLED, 40 + i, latched);
        if (i != HV_EXEC_VEHICLE) {
            hv_exec_event_t ee;
            memset(&ee, 0, sizeof ee);
            ee.kind = HV_EV_EE_STATUS;
            ee.node = i;
            hand_step(h, &ee);
        }
    }
    assert_int_equal(fx->sm.phase, HV_PH_ENABLE);
    assert_int_equal(hand_sent(h, HV_CAN_CMD_DISABLE), HV_EXEC_NODES);
    for (int i = 0; i < HV_EXEC_NODES; i++)
        hand_status(h, i, i == HV_EXEC_VEHICLE ? HV_CAN_STATE_DISABLED : HV_CAN_STATE_ESTOP,
                    h->seq[i], i != HV_EXEC_VEHICLE);
    /* the journal record first, in the same step as the clears, to the latched nodes only */
    assert_int_equal(h->out.a[0].kind, HV_ACT_JOURNAL);
    assert_int_equal(h->out.a[0].u.jr.kind, HV_JR_ESTOP_CLEAR);
    assert_int_equal(h->out.a[0].u.jr.nodes, (1u << HV_EXEC_LEFT) | (1u << HV_EXEC_RIGHT));
    assert_int_equal(h->sent[HV_EXEC_VEHICLE][HV_CAN_CMD_CLEAR_ESTOP], 0);
    assert_int_equal(h->sent[HV_EXEC_LEFT][HV_CAN_CMD_CLEAR_ESTOP], 1);
    assert_int_equal(h->sent[HV_EXEC_RIGHT][HV_CAN_CMD_CLEAR_ESTOP], 1);
    /* a heartbeat already on its way when the clear went out: from before it */
    hand_hb(h, HV_EXEC_RIGHT, HV_CAN_HEALTH_ESTOP);
    for (int i = HV_EXEC_LEFT; i <= HV_EXEC_RIGHT; i++)
        hand_status(h, i, HV_CAN_STATE_DISABLED, h->seq[i], 0);
}

static void test_stale_estop_reports_after_a_clear_do_not_count(void **state)
{
    (void)state;
    hand_t h;
    hand_clear(&h);
    /* every arm's last heartbeat says ESTOP, but it was sent before the arm's clear */
    assert_int_equal(h.fx->sm.node[HV_EXEC_RIGHT].health, HV_CAN_HEALTH_ESTOP);
    hand_tick(&h);
    assert_int_equal(h.fx->sm.phase, HV_PH_ENABLE);
    assert_int_equal(hand_sent(&h, HV_CAN_CMD_CLEAR_FAULT) + hand_sent(&h, HV_CAN_CMD_ENABLE), 0);
    free(h.fx);
}

static void test_enable_waits_for_every_node_after_the_clear(void **state)
{
    (void)state;
    hand_t h;
    hand_clear(&h);
    /* the arms speak after their clears; the vehicle (not latched) only by a heartbeat */
    for (int i = HV_EXEC_LEFT; i <= HV_EXEC_RIGHT; i++) {
        hand_hb(&h, i, HV_CAN_HEALTH_OK);
        hand_status(&h, i, HV_CAN_STATE_DISABLED, h.seq[i], 0);
    }
    hand_hb(&h, HV_EXEC_VEHICLE, HV_CAN_HEALTH_OK);
    hand_tick(&h);
    assert_int_equal(hand_sent(&h, HV_CAN_CMD_CLEAR_FAULT) + hand_sent(&h, HV_CAN_CMD_ENABLE), 0);
    /* the vehicle's status after the clear: now every node is fresh */
    hand_status(&h, HV_EXEC_VEHICLE, HV_CAN_STATE_DISABLED, h.seq[HV_EXEC_VEHICLE], 0);
    assert_int_equal(hand_sent(&h, HV_CAN_CMD_CLEAR_FAULT), HV_EXEC_NODES);
    assert_int_equal(hand_sent(&h, HV_CAN_CMD_ENABLE), 0);
    for (int i = 0; i < HV_EXEC_NODES; i++)
        hand_status(&h, i, HV_CAN_STATE_DISABLED, h.seq[i], 0);
    assert_int_equal(hand_sent(&h, HV_CAN_CMD_ENABLE), HV_EXEC_NODES);
    assert_int_equal(h.fx->sm.phase, HV_PH_ENABLE);
    free(h.fx);
}

static void test_estop_reported_after_the_clear_stops(void **state)
{
    (void)state;
    hand_t h;
    hand_clear(&h);
    hand_hb(&h, HV_EXEC_LEFT, HV_CAN_HEALTH_OK);
    hand_status(&h, HV_EXEC_LEFT, HV_CAN_STATE_DISABLED, h.seq[HV_EXEC_LEFT], 0);
    /* the right arm's e-stop is still pressed: it latches again after the clear */
    hand_hb(&h, HV_EXEC_RIGHT, HV_CAN_HEALTH_ESTOP);
    assert_int_equal(h.fx->sm.phase, HV_PH_ENABLE); /* its status is not fresh yet */
    hand_status(&h, HV_EXEC_RIGHT, HV_CAN_STATE_ESTOP, h.seq[HV_EXEC_RIGHT], 1);
    assert_int_equal(h.fx->sm.phase, HV_PH_SAFE);
    assert_int_equal(h.fx->sm.safe_reason, HV_SAFE_ESTOP);
    assert_int_equal(h.fx->sm.safe_node, HV_EXEC_RIGHT);
    assert_int_equal(h.out.a[0].kind, HV_ACT_ESTOP);
    assert_int_equal(hand_sent(&h, HV_CAN_CMD_CLEAR_FAULT) + hand_sent(&h, HV_CAN_CMD_ENABLE), 0);
    free(h.fx);
}

static void test_resume(void **state)
{
    (void)state;
    fx_t *fx = new_fx(2, 2);
    hv_exec_progress_t prog;
    memset(&prog, 0, sizeof prog);
    /* stop 0 done entirely; at stop 1 the left arm's first fruit was cut and is held,
     * the right arm's first fruit was released before the restart */
    for (int i = 0; i < 4; i++) {
        prog.pick[i] = HV_PROG_DONE;
        prog.outcome[i] = HV_OUT_PICKED;
    }
    prog.stop_reached[0] = prog.stop_reached[1] = 1;
    int l1 = fx->plan.stops[1].first[0], r1 = fx->plan.stops[1].first[1];
    prog.pick[l1] = HV_PROG_CUT;
    prog.pick[r1] = HV_PROG_RELEASE;
    fx_start(fx, &prog);
    fx->node[HV_EXEC_LEFT].held = 1;
    fx_run(fx, 30.0);
    assert_int_equal(fx->sm.phase, HV_PH_ROW_DONE);
    /* one move to stop 1, one to the row end: stop 0 is not visited again */
    assert_int_equal(fx_count(fx, HV_ACT_MOVE, -1), 2);
    for (int i = 0; i < 4; i++)
        assert_int_equal(outcome_of(fx, i, NULL, NULL), -1);
    int reason;
    assert_int_equal(outcome_of(fx, l1, &reason, NULL), HV_OUT_PICKED);
    assert_int_equal(reason, HV_RSN_RESUMED);
    assert_int_equal(outcome_of(fx, r1, &reason, NULL), HV_OUT_PICKED);
    assert_int_equal(reason, HV_RSN_RESUMED);
    /* neither was cut again; the others were picked normally */
    assert_int_equal(fx->cuts_done[0][l1], 0);
    assert_int_equal(fx->cuts_done[1][r1], 0);
    assert_int_equal(fx_count(fx, HV_ACT_EE, -1), 2 * 2 + 1); /* 2 full cycles + 1 release */
    assert_int_equal(fx->sm.picked, 4);
    free(fx);
}

static void test_resume_cut_not_held(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 1);
    hv_exec_progress_t prog;
    memset(&prog, 0, sizeof prog);
    prog.pick[0] = HV_PROG_CUT; /* journalled, but the arm holds nothing: never cut */
    fx_start(fx, &prog);
    fx_run(fx, 30.0);
    int reason;
    assert_int_equal(outcome_of(fx, 0, &reason, NULL), HV_OUT_PICKED);
    assert_int_equal(reason, HV_RSN_OK);
    assert_int_equal(fx->cuts_done[0][0], 1);
    free(fx);
}

static void test_unreachable_skipped(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 2);
    fx->plan.picks[1].reachable = 0;
    fx_start(fx, NULL);
    fx_run(fx, 30.0);
    int reason;
    assert_int_equal(outcome_of(fx, 1, &reason, NULL), HV_OUT_SKIPPED);
    assert_int_equal(reason, HV_RSN_IK_UNREACHABLE);
    assert_int_equal(fx->sm.picked, 3);
    free(fx);
}

static void test_lost_frames_are_resent(void **state)
{
    (void)state;
    fx_t *fx = new_fx(2, 2);
    fx->f.drop_next[HV_ACT_COMMAND] = 1; /* the first CLEAR_FAULT */
    fx->f.drop_next[HV_ACT_SETPOINT] = 1;
    fx->f.drop_next[HV_ACT_EE] = 1;
    fx->f.drop_next[HV_ACT_MOVE] = 1;
    fx_start(fx, NULL);
    fx_run(fx, 60.0);
    assert_int_equal(fx->sm.phase, HV_PH_ROW_DONE);
    assert_int_equal(fx->sm.picked, fx->plan.n_picks);
    assert_int_equal(fx->sm.faults, 0);
    assert_int_equal(fx->sm.resends, 4);
    /* the resent frame is the same frame (same sequence number) */
    int first = fx_find(fx, 0, HV_ACT_MOVE, -1), again = fx_find(fx, first + 1, HV_ACT_MOVE, -1);
    assert_int_equal(fx->log[first].a.u.move.seq, fx->log[again].a.u.move.seq);
    double gap = (double)(fx->log[again].t_ns - fx->log[first].t_ns) * 1e-9;
    assert_true(gap >= fx->prm.resend_s && gap < fx->prm.resend_s + 0.02);
    free(fx);
}

/* The defaults set every field: a struct full of junk before them is accepted by init
 * (a field the defaults forget is whatever the caller's stack held). */
static void test_params_default_complete(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 1);
    hv_exec_params_t p;
    hv_exec_sm_t sm;
    memset(&p, 0xA5, sizeof p);
    hv_exec_params_default(&p);
    assert_int_equal(hv_exec_init(&sm, &fx->plan, &p, NULL), HV_OK);
    assert_int_equal(p.online, 0);
    assert_int_equal(p.clear_estop, 0);
    free(fx);
}

static void test_bad_input(void **state)
{
    (void)state;
    fx_t *fx = new_fx(1, 1);
    fx_start(fx, NULL);
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = HV_EV_ARM_STATUS;
    ev.node = HV_EXEC_VEHICLE; /* an arm status cannot come from the vehicle */
    hv_exec_actions_t out = {0};
    assert_int_equal(hv_exec_step(&fx->sm, &ev, fx->now_ns, &out), HV_ERR_EXEC_EVENT);
    ev.kind = (hv_exec_event_kind_t)99;
    assert_int_equal(hv_exec_step(&fx->sm, &ev, fx->now_ns, &out), HV_ERR_EXEC_EVENT);
    hv_exec_params_t p = fx->prm;
    p.heartbeat_timeout_s = 0.0;
    hv_exec_sm_t sm;
    assert_int_equal(hv_exec_init(&sm, &fx->plan, &p, NULL), HV_ERR_EXEC_PARAMS);
    assert_int_equal(hv_exec_init(NULL, &fx->plan, &p, NULL), HV_ERR_ARG);
    assert_string_equal(hv_exec_status_name(HV_ERR_EXEC_EVENT), "HV_ERR_EXEC_EVENT");
    assert_string_equal(hv_exec_phase_name(HV_PH_ROW_DONE), "row_done");
    assert_string_equal(hv_exec_safe_reason_name(HV_SAFE_ESTOP_LATCHED), "estop_latched");
    char list[32];
    assert_int_equal(
        hv_exec_node_list((1u << HV_EXEC_VEHICLE) | (1u << HV_EXEC_RIGHT), list, sizeof list),
        HV_OK);
    assert_string_equal(list, "vehicle,right_arm");
    assert_int_equal(hv_exec_node_list(0, list, sizeof list), HV_OK);
    assert_string_equal(list, "");
    assert_int_equal(hv_exec_node_list(1u << HV_EXEC_NODES, list, sizeof list), HV_ERR_ARG);
    assert_int_equal(hv_exec_node_list(7u, list, 12), HV_ERR_ARG); /* does not fit */
    free(fx);
}

static void test_expected_makespan(void **state)
{
    (void)state;
    fx_t *fx = new_fx(2, 2);
    const hv_exec_plan_t *p = &fx->plan;
    double sum = 0.0;
    for (int s = 0; s < p->n_stops; s++) {
        double arm[2] = {0, 0};
        for (int k = 0; k < p->n_picks; k++)
            if (p->picks[k].stop == s)
                arm[p->picks[k].side] += 2.0 * p->picks[k].move_s + 1.0 + 1.0;
        sum += (arm[0] > arm[1] ? arm[0] : arm[1]) + p->stops[s].drive_s;
        assert_true(p->stops[s].drive_s > 0.0);
    }
    /* 0.4 m from the row start at 0.1 m/s, 0.1 m/s^2: 4 s + 1 s */
    assert_float_equal(p->stops[0].drive_s, 5.0, 1e-9);
    assert_float_equal(p->expected_makespan_s, sum + p->final_drive_s, 1e-9);
    free(fx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_whole_row),
        cmocka_unit_test(test_params_default_complete),
        cmocka_unit_test(test_heartbeats_sent),
        cmocka_unit_test(test_nodes_absent),
        cmocka_unit_test(test_time_scale_mismatch),
        cmocka_unit_test(test_lost_heartbeat),
        cmocka_unit_test(test_node_estop),
        cmocka_unit_test(test_comm_fault),
        cmocka_unit_test(test_joint_fault_retry),
        cmocka_unit_test(test_joint_fault_gives_up),
        cmocka_unit_test(test_rejected_setpoint),
        cmocka_unit_test(test_approach_timeout),
        cmocka_unit_test(test_cut_failed),
        cmocka_unit_test(test_dropped_never_cut_twice),
        cmocka_unit_test(test_vehicle_faults),
        cmocka_unit_test(test_recovery_fails),
        cmocka_unit_test(test_homing_fails),
        cmocka_unit_test(test_operator_stop_is_controlled_and_resumable),
        cmocka_unit_test(test_second_stop_and_journal_failure_are_estops),
        cmocka_unit_test(test_a_repeated_bus_stop_request_is_one_request),
        cmocka_unit_test(test_latched_estop_keeps_a_start_safe),
        cmocka_unit_test(test_estop_then_restarts),
        cmocka_unit_test(test_stale_estop_reports_after_a_clear_do_not_count),
        cmocka_unit_test(test_enable_waits_for_every_node_after_the_clear),
        cmocka_unit_test(test_estop_reported_after_the_clear_stops),
        cmocka_unit_test(test_resume),
        cmocka_unit_test(test_resume_cut_not_held),
        cmocka_unit_test(test_unreachable_skipped),
        cmocka_unit_test(test_lost_frames_are_resent),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_expected_makespan),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
