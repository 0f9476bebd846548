/* The executor's port (hv/exec_port.h) and the loop that runs on it (hv/exec_loop.h),
 * through a port of this test's own: a third implementation of the interface whose clock,
 * bus and journal live in arrays (virtual time: wait() moves the clock to the next frame
 * or the deadline), with the vehicle and both arms answering at the DBC's frame level
 * (commands echoed and obeyed at once, moves arrived at once; setpoints never reached). */
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "exec_fixture.h"
#include "harvest_can.h"
#include "hv/can_enums.h"
#include "hv/exec_loop.h"
#include "hv/exec_port.h"
#include "hv/exec_status.h"

#define TP_MAX     1024
#define EMIT_NS    20000000ull /* the nodes' status period (virtual ns) */
#define TICK_NS    10000000ull
#define TIME_SCALE 10.0

typedef struct tnode {
    int state, homed, cmd_seq, move_seq, arrived;
    double pos_m;
} tnode_t;

typedef struct tport {
    uint64_t now_ns, next_emit_ns;
    int nodes; /* 1: the three nodes answer */
    tnode_t node[HV_EXEC_NODES];
    hv_can_frame_t rxq[64];
    unsigned rx_head, rx_n;
    uint32_t tx_id[TP_MAX]; /* ids of the frames sent, in order */
    unsigned n_tx, n_setpoints, n_estops, n_moves, first_setpoint;
    int send_fail_at; /* the n-th frame (0-based) fails; -1 never */
    unsigned journal_calls, n_jr;
    hv_exec_journal_kind_t jr[TP_MAX];
    unsigned jr_after_tx[TP_MAX]; /* frames sent before each record was stored */
    int journal_fail_at;          /* the n-th record (0-based) and every later one fail; -1 */
    unsigned waits;
    uint64_t wait_ahead_max_ns; /* the furthest deadline a wait was given, from now */
    uint64_t poll_ns;           /* no wait(): an empty can_recv moves the clock this far */
    volatile sig_atomic_t *stop_at_setpoint;
} tport_t;

static void push(tport_t *t, const hv_can_frame_t *f)
{
    assert_true(t->rx_n < sizeof t->rxq / sizeof t->rxq[0]);
    t->rxq[(t->rx_head + t->rx_n++) % (sizeof t->rxq / sizeof t->rxq[0])] = *f;
}

#define PACK(MSG, ID, m)                                                                           \
    do {                                                                                           \
        hv_can_frame_t f;                                                                          \
        memset(&f, 0, sizeof f);                                                                   \
        int n = harvest_can_##MSG##_pack(f.data, &(m), sizeof f.data);                             \
        assert_true(n > 0);                                                                        \
        f.id = ID;                                                                                 \
        f.dlc = (uint8_t)n;                                                                        \
        push(t, &f);                                                                               \
    } while (0)

#define EMIT_HB(MSG, ID)                                                                           \
    do {                                                                                           \
        struct harvest_can_##MSG##_t m;                                                            \
        harvest_can_##MSG##_init(&m);                                                              \
        m.health = HV_CAN_HEALTH_OK;                                                               \
        m.time_scale = harvest_can_##MSG##_time_scale_encode(TIME_SCALE);                          \
        m.protocol_version = HV_CAN_PROTOCOL_VERSION;                                              \
        PACK(MSG, ID, m);                                                                          \
    } while (0)

#define EMIT_ARM(PFX, NODE)                                                                        \
    do {                                                                                           \
        const tnode_t *a = &t->node[NODE];                                                         \
        struct harvest_can_##PFX##_status_t s;                                                     \
        harvest_can_##PFX##_status_init(&s);                                                       \
        s.state = (uint8_t)a->state;                                                               \
        s.homed = (uint8_t)a->homed;                                                               \
        s.command_seq = (uint8_t)a->cmd_seq;                                                       \
        PACK(PFX##_status, HARVEST_CAN_##NODE##_STATUS_FRAME_ID, s);                               \
        struct harvest_can_##PFX##_ee_status_t e;                                                  \
        harvest_can_##PFX##_ee_status_init(&e);                                                    \
        PACK(PFX##_ee_status, HARVEST_CAN_##NODE##_EE_STATUS_FRAME_ID, e);                         \
    } while (0)

/* node indices spelled as the DBC's frame names, for EMIT_ARM */
enum { LEFT_ARM = HV_EXEC_LEFT, RIGHT_ARM = HV_EXEC_RIGHT };

/* The nodes' heartbeats and statuses every EMIT_NS of virtual time. */
static void emit_due(tport_t *t)
{
    while (t->nodes && t->now_ns >= t->next_emit_ns) {
        EMIT_HB(vehicle_heartbeat, HARVEST_CAN_VEHICLE_HEARTBEAT_FRAME_ID);
        EMIT_HB(left_arm_heartbeat, HARVEST_CAN_LEFT_ARM_HEARTBEAT_FRAME_ID);
        EMIT_HB(right_arm_heartbeat, HARVEST_CAN_RIGHT_ARM_HEARTBEAT_FRAME_ID);
        const tnode_t *v = &t->node[HV_EXEC_VEHICLE];
        struct harvest_can_vehicle_status_t s;
        harvest_can_vehicle_status_init(&s);
        s.position = harvest_can_vehicle_status_position_encode(v->pos_m);
        s.state = (uint8_t)v->state;
        s.arrived = (uint8_t)v->arrived;
        s.move_seq = (uint8_t)v->move_seq;
        s.command_seq = (uint8_t)v->cmd_seq;
        PACK(vehicle_status, HARVEST_CAN_VEHICLE_STATUS_FRAME_ID, s);
        EMIT_ARM(left_arm, LEFT_ARM);
        EMIT_ARM(right_arm, RIGHT_ARM);
        t->next_emit_ns += EMIT_NS;
    }
}

static void obey(tnode_t *n, int command, int seq)
{
    n->cmd_seq = seq;
    if (command == HV_CAN_CMD_ENABLE)
        n->state = HV_CAN_STATE_IDLE;
    else if (command == HV_CAN_CMD_DISABLE || command == HV_CAN_CMD_CLEAR_FAULT)
        n->state = HV_CAN_STATE_DISABLED;
    else if (command == HV_CAN_CMD_HOME)
        n->homed = 1;
}

#define OBEY_ARM(PFX, NODE)                                                                        \
    do {                                                                                           \
        struct harvest_can_##PFX##_command_t c;                                                    \
        assert_int_equal(harvest_can_##PFX##_command_unpack(&c, f->data, f->dlc), 0);              \
        obey(&t->node[NODE], c.command, c.command_seq);                                            \
    } while (0)

/* ---- the test's port: hv_exec_port_t's members on a tport_t ---- */

static uint64_t tp_now(void *ctx)
{
    return ((tport_t *)ctx)->now_ns;
}

static hv_status_t tp_send(void *ctx, const hv_can_frame_t *f)
{
    tport_t *t = ctx;
    if ((int)t->n_tx == t->send_fail_at) {
        t->send_fail_at = -1;
        return HV_CAN_ERR_SEND;
    }
    assert_true(t->n_tx < TP_MAX);
    t->tx_id[t->n_tx++] = f->id;
    switch (f->id) {
    case HARVEST_CAN_ESTOP_FRAME_ID: t->n_estops++; break;
    case HARVEST_CAN_LEFT_ARM_SETPOINT_FRAME_ID:
    case HARVEST_CAN_RIGHT_ARM_SETPOINT_FRAME_ID:
        if (!t->n_setpoints++)
            t->first_setpoint = t->n_tx - 1;
        if (t->stop_at_setpoint)
            *t->stop_at_setpoint = 1;
        break;
    case HARVEST_CAN_VEHICLE_COMMAND_FRAME_ID: {
        struct harvest_can_vehicle_command_t c;
        assert_int_equal(harvest_can_vehicle_command_unpack(&c, f->data, f->dlc), 0);
        obey(&t->node[HV_EXEC_VEHICLE], c.command, c.command_seq);
        break;
    }
    case HARVEST_CAN_LEFT_ARM_COMMAND_FRAME_ID: OBEY_ARM(left_arm, HV_EXEC_LEFT); break;
    case HARVEST_CAN_RIGHT_ARM_COMMAND_FRAME_ID: OBEY_ARM(right_arm, HV_EXEC_RIGHT); break;
    case HARVEST_CAN_VEHICLE_MOVE_FRAME_ID: {
        struct harvest_can_vehicle_move_t m;
        assert_int_equal(harvest_can_vehicle_move_unpack(&m, f->data, f->dlc), 0);
        tnode_t *v = &t->node[HV_EXEC_VEHICLE];
        v->move_seq = m.move_seq;
        v->pos_m = harvest_can_vehicle_move_target_position_decode(m.target_position);
        v->arrived = 1;
        t->n_moves++;
        break;
    }
    default: break;
    }
    return HV_OK;
}

static hv_status_t tp_recv(void *ctx, hv_can_frame_t *f)
{
    tport_t *t = ctx;
    emit_due(t);
    if (!t->rx_n) {
        t->now_ns += t->poll_ns;
        return HV_CAN_ERR_TIMEOUT;
    }
    *f = t->rxq[t->rx_head];
    t->rx_head = (t->rx_head + 1) % (sizeof t->rxq / sizeof t->rxq[0]);
    t->rx_n--;
    return HV_OK;
}

static hv_status_t tp_wait(void *ctx, uint64_t until_ns)
{
    tport_t *t = ctx;
    t->waits++;
    if (until_ns > t->now_ns && until_ns - t->now_ns > t->wait_ahead_max_ns)
        t->wait_ahead_max_ns = until_ns - t->now_ns;
    if (t->rx_n)
        return HV_OK; /* a frame waits */
    uint64_t to = until_ns;
    if (t->nodes && t->next_emit_ns < to)
        to = t->next_emit_ns;
    if (to > t->now_ns)
        t->now_ns = to;
    emit_due(t);
    return HV_OK;
}

static hv_status_t tp_journal(void *ctx, const hv_exec_action_t *record, double t_s)
{
    tport_t *t = ctx;
    assert_int_equal(record->kind, HV_ACT_JOURNAL);
    assert_true(t_s >= 0.0);
    if (t->journal_fail_at >= 0 && (int)t->journal_calls++ >= t->journal_fail_at)
        return HV_ERR_EXEC_JOURNAL_IO;
    assert_true(t->n_jr < TP_MAX);
    t->jr_after_tx[t->n_jr] = t->n_tx;
    t->jr[t->n_jr++] = record->u.jr.kind;
    return HV_OK;
}

static void tp_init(tport_t *t, hv_exec_port_t *port, int nodes)
{
    memset(t, 0, sizeof *t);
    t->now_ns = 5000000000ull; /* any start: the loop reads the port's clock only */
    t->next_emit_ns = t->now_ns;
    t->nodes = nodes;
    t->send_fail_at = -1;
    t->journal_fail_at = -1;
    for (int i = 0; i < HV_EXEC_NODES; i++)
        t->node[i].cmd_seq = 40 + i; /* what a previous run left */
    t->node[HV_EXEC_VEHICLE].move_seq = 90;
    port->ctx = t;
    port->now_ns = tp_now;
    port->can_send = tp_send;
    port->can_recv = tp_recv;
    port->wait = tp_wait;
    port->journal_append = tp_journal;
}

/* ---- hv_exec_port_carry_out ---- */

static void batch(hv_exec_actions_t *out)
{
    memset(out, 0, sizeof *out);
    hv_exec_action_t *a = out->a;
    a[0].kind = HV_ACT_HEARTBEAT;
    a[0].u.hb.time_scale = TIME_SCALE;
    a[1].kind = HV_ACT_JOURNAL;
    a[1].u.jr.kind = HV_JR_STOP;
    a[2].kind = HV_ACT_COMMAND;
    a[2].node = HV_EXEC_VEHICLE;
    a[2].u.cmd.command = HV_CAN_CMD_ENABLE;
    a[2].u.cmd.seq = 5;
    a[3].kind = HV_ACT_PHASE; /* telemetry: not the port's */
    a[4].kind = HV_ACT_ESTOP;
    out->n = 5;
}

/* one batch carried out through a fresh port (no nodes), as each test sets it up */
typedef struct co {
    tport_t t;
    hv_exec_port_t port;
    hv_exec_actions_t out;
    hv_exec_can_tx_t tx;
    hv_exec_port_stats_t st;
    unsigned done;
} co_t;

static void co_init(co_t *c)
{
    memset(c, 0, sizeof *c);
    tp_init(&c->t, &c->port, 0);
    batch(&c->out);
    c->done = 99;
}

static hv_status_t co_run(co_t *c)
{
    return hv_exec_port_carry_out(&c->port, &c->tx, &c->out, 1.5, &c->st, &c->done);
}

static void test_carry_out_in_order(void **state)
{
    (void)state;
    co_t c;
    co_init(&c);
    assert_int_equal(co_run(&c), HV_OK);
    assert_int_equal(c.done, 5);
    assert_int_equal(c.t.n_tx, 3);
    assert_int_equal(c.t.tx_id[0], HARVEST_CAN_EXECUTOR_HEARTBEAT_FRAME_ID);
    assert_int_equal(c.t.tx_id[1], HARVEST_CAN_VEHICLE_COMMAND_FRAME_ID);
    assert_int_equal(c.t.tx_id[2], HARVEST_CAN_ESTOP_FRAME_ID);
    assert_int_equal(c.t.n_jr, 1);
    assert_int_equal(c.t.jr_after_tx[0], 1); /* stored after the heartbeat, before the command */
    assert_int_equal(c.st.frames_tx, 3);
    assert_int_equal(c.st.journal_records, 1);
    assert_int_equal(c.st.send_failures + c.st.encode_errors, 0);
}

static void test_carry_out_stops_at_a_record_not_stored(void **state)
{
    (void)state;
    co_t c;
    co_init(&c);
    c.t.journal_fail_at = 0;
    assert_int_equal(co_run(&c), HV_ERR_EXEC_JOURNAL_IO);
    assert_int_equal(c.done, 1); /* the heartbeat only: nothing after the record */
    assert_int_equal(c.t.n_tx, 1);
    assert_int_equal(c.t.journal_calls, 1);
    assert_int_equal(c.t.n_jr, 0);
    assert_int_equal(c.st.frames_tx, 1);
    assert_int_equal(c.st.journal_records, 0);
}

static void test_carry_out_counts_lost_frames_and_goes_on(void **state)
{
    (void)state;
    co_t c;
    co_init(&c);
    c.t.send_fail_at = 0;              /* the heartbeat is lost on the bus */
    c.out.a[2].kind = HV_ACT_SETPOINT; /* joint 3 beyond the DBC's range: never sent */
    c.out.a[2].node = HV_EXEC_RIGHT;
    c.out.a[2].u.sp.q[2] = 3.5;
    assert_int_equal(co_run(&c), HV_OK);
    assert_int_equal(c.done, 5);
    assert_int_equal(c.st.send_failures, 1);
    assert_int_equal(c.st.encode_errors, 1);
    assert_int_equal(c.st.frames_tx, 1);
    assert_int_equal(c.t.n_tx, 1);
    assert_int_equal(c.t.tx_id[0], HARVEST_CAN_ESTOP_FRAME_ID);
    assert_int_equal(c.st.journal_records, 1);
}

/* ---- the loop on the port ---- */

typedef struct rig {
    fx_t fx; /* the plan and parameters */
    tport_t t;
    hv_exec_port_t port;
    hv_exec_loop_t loop;
    volatile sig_atomic_t stop;
} rig_t;

static rig_t *rig_new(int nodes)
{
    rig_t *r = calloc(1, sizeof *r);
    assert_non_null(r);
    fx_plan(&r->fx, 1, 1);
    r->fx.prm.startup_timeout_s = 1.0;
    assert_int_equal(hv_exec_init(&r->fx.sm, &r->fx.plan, &r->fx.prm, NULL), HV_OK);
    tp_init(&r->t, &r->port, nodes);
    r->loop.sm = &r->fx.sm;
    r->loop.port = &r->port;
    r->loop.stop = &r->stop;
    r->loop.tick_s = (double)TICK_NS * 1e-9;
    r->loop.linger_s = 0.5;
    return r;
}

static void assert_frames_counted(const rig_t *r)
{
    assert_int_equal(r->loop.st.io.frames_tx, r->t.n_tx);
    assert_int_equal(r->loop.st.io.journal_records, r->t.n_jr);
}

static void test_loop_sleeps_in_wait(void **state)
{
    (void)state;
    rig_t *r = rig_new(0); /* no node ever answers */
    uint64_t t0 = r->t.now_ns;
    assert_int_equal(hv_exec_loop_run(&r->loop), HV_OK);
    assert_int_equal(r->fx.sm.phase, HV_PH_SAFE);
    assert_int_equal(r->fx.sm.safe_reason, HV_SAFE_NODES_ABSENT);
    /* the port's clock is the loop's: the start-up timeout and the linger passed on it */
    assert_true(r->t.now_ns - t0 >= 1500000000ull);
    /* it slept tick by tick: each wait ends by the next tick, and about one per tick */
    assert_true(r->t.wait_ahead_max_ns <= TICK_NS);
    assert_in_range(r->t.waits, (r->t.now_ns - t0) / TICK_NS / 2, 2 * (r->t.now_ns - t0) / TICK_NS);
    assert_true(r->t.n_estops > 0);
    assert_int_equal(r->loop.st.frames_rx, 0);
    assert_frames_counted(r);
    free(r);
}

static void test_loop_polls_without_wait(void **state)
{
    (void)state;
    rig_t *r = rig_new(0);
    r->port.wait = NULL; /* a board that cannot sleep: the loop polls can_recv */
    r->t.poll_ns = 1000000;
    assert_int_equal(hv_exec_loop_run(&r->loop), HV_OK);
    assert_int_equal(r->fx.sm.safe_reason, HV_SAFE_NODES_ABSENT);
    assert_int_equal(r->t.waits, 0);
    assert_true(r->t.n_estops > 0);
    assert_frames_counted(r);
    free(r);
}

static void test_loop_refuses_an_incomplete_port(void **state)
{
    (void)state;
    rig_t *r = rig_new(0);
    r->port.journal_append = NULL;
    assert_int_equal(hv_exec_loop_run(&r->loop), HV_ERR_ARG);
    assert_int_equal(r->t.n_tx, 0);
    free(r);
}

static void test_loop_journals_the_stop_before_the_setpoints(void **state)
{
    (void)state;
    rig_t *r = rig_new(1);
    r->t.stop_at_setpoint = &r->stop; /* SIGTERM once the arms are sent to the fruit */
    assert_int_equal(hv_exec_loop_run(&r->loop), HV_OK);
    /* a controlled stop: the picks under way finish, then every node is disabled */
    assert_int_equal(r->fx.sm.phase, HV_PH_STOPPED);
    assert_int_equal(r->fx.sm.safe_reason, HV_SAFE_NONE);
    assert_int_equal(r->t.n_moves, 1);
    assert_true(r->t.n_jr >= 1);
    assert_int_equal(r->t.jr[0], HV_JR_STOP);
    assert_true(r->t.n_setpoints >= 1);
    assert_true(r->t.jr_after_tx[0] <= r->t.first_setpoint);
    assert_true(r->loop.st.frames_rx > 0);
    assert_frames_counted(r);
    free(r);
}

static void test_loop_journal_failure_stops_before_the_next_frame(void **state)
{
    (void)state;
    rig_t *r = rig_new(1);
    r->t.journal_fail_at = 0; /* the stop's record cannot be stored */
    assert_int_equal(hv_exec_loop_run(&r->loop), HV_OK);
    assert_int_equal(r->fx.sm.phase, HV_PH_SAFE);
    assert_int_equal(r->fx.sm.safe_reason, HV_SAFE_JOURNAL);
    assert_int_equal(r->t.n_moves, 1); /* the vehicle did arrive at the stop */
    assert_int_equal(r->t.journal_calls, 1);
    assert_int_equal(r->t.n_jr, 0);
    assert_int_equal(r->t.n_setpoints, 0); /* the step's setpoints never went out */
    assert_true(r->t.n_estops > 0);
    assert_frames_counted(r);
    free(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_carry_out_in_order),
        cmocka_unit_test(test_carry_out_stops_at_a_record_not_stored),
        cmocka_unit_test(test_carry_out_counts_lost_frames_and_goes_on),
        cmocka_unit_test(test_loop_sleeps_in_wait),
        cmocka_unit_test(test_loop_polls_without_wait),
        cmocka_unit_test(test_loop_refuses_an_incomplete_port),
        cmocka_unit_test(test_loop_journals_the_stop_before_the_setpoints),
        cmocka_unit_test(test_loop_journal_failure_stops_before_the_next_frame),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
