/* Fuzz target: CAN frames, decoded through the DBC (hv_exec_can_decode), into the
 * executor's step function (hv_exec_step), on the plan of fuzz/data/plan.json.
 *
 * Input: one flag byte (bit 0: the operator cleared the e-stop for this run; bit 1:
 * resume, the next n_picks bytes giving each pick's journalled progress), then a list of
 * operations, each an opcode byte and its arguments:
 *   0 tick       dt: 1 byte (x 5 ms)
 *   1 raw frame  id: 2 bytes (11 bits), dlc: 1 byte (mod 9), data
 *   2 heartbeat  node, health, time scale (0: 10.00, else the byte / 10)
 *   3 status     node, state, flags (bit 0 reached/arrived, 1 homed, 2 echo the awaited
 *                sequence numbers, else the next byte), fault bits
 *   4 ee status  arm, state, action, flags (bit 0 fruit held, 1 echo the ee sequence)
 *   5 a well-behaved round: every node's heartbeat and a status echoing what the state
 *                machine waits for (so inputs get deep into the run), then a tick
 *   6 operator stop request, 7 journal write failure
 * Frames 2-5 are packed with the DBC's generated code, as a node sends them.
 *
 * Properties, checked after every step: no crash or undefined behaviour; the step never
 * overflows its action list; every CAN action encodes; SAFE and ROW_DONE are final; in
 * SAFE only e-stops, heartbeats and telemetry leave the executor, and a start that finds
 * a latched e-stop without the operator's clear has commanded no node, nor does later;
 * no pick is
 * journalled after its outcome, nor given a second outcome. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_plan.h"
#include "fuzz_support.h"
#include "harvest_can.h"
#include "hv/exec_can.h"
#include "hv/exec_status.h"

typedef struct reader {
    const uint8_t *p;
    size_t n;
} reader_t;

static int next(reader_t *r)
{
    if (r->n == 0)
        return -1;
    r->n--;
    return *r->p++;
}

static uint8_t byte_or0(reader_t *r)
{
    int b = next(r);
    return b < 0 ? 0 : (uint8_t)b;
}

typedef struct run {
    hv_exec_sm_t sm;
    uint64_t now;
    uint8_t outcome_seen[HV_EXEC_MAX_PICKS];
    int latched_without_clear; /* a latch found at start-up, no operator clear */
    int commanded;             /* a command, setpoint, ee or move was sent in this run */
} run_t;

static void check_actions(run_t *R, hv_exec_phase_t before, const hv_exec_actions_t *out)
{
    hv_exec_can_tx_t tx = {0, 0};
    for (unsigned i = 0; i < out->n; i++) {
        const hv_exec_action_t *a = &out->a[i];
        hv_can_frame_t f;
        int has;
        if (hv_exec_can_encode(a, &tx, &f, &has) != HV_OK)
            hv_fuzz_fail("action %d does not encode", (int)a->kind);
        int commanding = a->kind == HV_ACT_COMMAND || a->kind == HV_ACT_SETPOINT ||
                         a->kind == HV_ACT_EE || a->kind == HV_ACT_MOVE;
        if (before == HV_PH_SAFE && (commanding || a->kind == HV_ACT_JOURNAL))
            hv_fuzz_fail("action %d sent while SAFE", (int)a->kind);
        if (R->latched_without_clear && commanding)
            hv_fuzz_fail("command to a latched node without the operator's clear");
        R->commanded |= commanding;
        if (a->kind == HV_ACT_JOURNAL && a->u.jr.kind != HV_JR_STOP && a->u.jr.kind != HV_JR_DONE &&
            a->u.jr.kind != HV_JR_ESTOP_CLEAR && a->u.jr.kind != HV_JR_HALT) {
            int p = a->u.jr.pick;
            if (p < 0 || p >= R->sm.plan->n_picks)
                hv_fuzz_fail("journal record of pick %d", p);
            if (R->outcome_seen[p])
                hv_fuzz_fail("pick %d journalled after its outcome", p);
            if (a->u.jr.kind == HV_JR_OUTCOME)
                R->outcome_seen[p] = 1;
        }
    }
}

static void step(run_t *R, const hv_exec_event_t *ev)
{
    hv_exec_actions_t out;
    out.n = 0;
    hv_exec_phase_t before = R->sm.phase;
    hv_status_t st = hv_exec_step(&R->sm, ev, R->now, &out);
    if (st == HV_ERR_EXEC_ACTIONS_FULL)
        hv_fuzz_fail("one step overflowed its action list");
    if (st != HV_OK && st != HV_ERR_EXEC_EVENT)
        hv_fuzz_fail("step returned %d", (int)st);
    if ((before == HV_PH_SAFE || before == HV_PH_ROW_DONE) && R->sm.phase != before)
        hv_fuzz_fail("left final phase %d for %d", (int)before, (int)R->sm.phase);
    check_actions(R, before, &out);
    if (R->sm.phase == HV_PH_SAFE && R->sm.safe_reason == HV_SAFE_ESTOP_LATCHED) {
        if (R->commanded)
            hv_fuzz_fail("a latched e-stop found after commands were sent");
        R->latched_without_clear = 1;
    }
}

static void frame_in(run_t *R, const hv_can_frame_t *f)
{
    hv_exec_event_t ev;
    hv_exec_arm_sample_t samples[2];
    memset(&ev, 0, sizeof ev);
    if (hv_exec_can_decode(f, &ev, samples) == HV_RX_EVENT)
        step(R, &ev);
}

static void tick(run_t *R, uint64_t dt_ns)
{
    R->now += dt_ns;
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = HV_EV_TICK;
    step(R, &ev);
}

/* ---- frames as the nodes send them (the DBC's generated pack) ---- */

static void send_packed(run_t *R, uint32_t id, const uint8_t *buf, int len)
{
    if (len < 0)
        hv_fuzz_fail("pack failed for id %x", (unsigned)id);
    hv_can_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = id;
    f.dlc = (uint8_t)len;
    memcpy(f.data, buf, (size_t)len);
    frame_in(R, &f);
}

#define PACK_HB(MSG, ID)                                                                           \
    do {                                                                                           \
        struct harvest_can_##MSG##_t m;                                                            \
        memset(&m, 0, sizeof m);                                                                   \
        m.health = health;                                                                         \
        m.time_scale = harvest_can_##MSG##_time_scale_encode(scale);                               \
        m.protocol_version = 1;                                                                    \
        send_packed(R, ID, buf, harvest_can_##MSG##_pack(buf, &m, sizeof buf));                    \
    } while (0)

static void heartbeat(run_t *R, int node, uint8_t health, double scale)
{
    uint8_t buf[8];
    if (node == HV_EXEC_VEHICLE)
        PACK_HB(vehicle_heartbeat, HARVEST_CAN_VEHICLE_HEARTBEAT_FRAME_ID);
    else if (node == HV_EXEC_LEFT)
        PACK_HB(left_arm_heartbeat, HARVEST_CAN_LEFT_ARM_HEARTBEAT_FRAME_ID);
    else
        PACK_HB(right_arm_heartbeat, HARVEST_CAN_RIGHT_ARM_HEARTBEAT_FRAME_ID);
}

/* the sequence numbers a well-behaved node would echo now */
static int wanted_cmd_seq(const run_t *R, int node)
{
    const hv_exec_node_t *n = &R->sm.node[node];
    return n->wait_cmd_seq >= 0 ? n->wait_cmd_seq : n->cmd_seq;
}

#define PACK_ARM_STATUS(MSG, ID)                                                                   \
    do {                                                                                           \
        struct harvest_can_##MSG##_t m;                                                            \
        memset(&m, 0, sizeof m);                                                                   \
        m.state = state;                                                                           \
        m.target_reached = flags & 1;                                                              \
        m.homed = (flags >> 1) & 1;                                                                \
        m.setpoint_seq = (uint8_t)sp_seq;                                                          \
        m.command_seq = (uint8_t)cmd_seq;                                                          \
        m.fault_bits = fault_bits;                                                                 \
        send_packed(R, ID, buf, harvest_can_##MSG##_pack(buf, &m, sizeof buf));                    \
    } while (0)

static void status(run_t *R, int node, uint8_t state, uint8_t flags, int seq_byte,
                   uint16_t fault_bits)
{
    uint8_t buf[8];
    int echo = (flags & 4) != 0;
    int cmd_seq = echo ? wanted_cmd_seq(R, node) : seq_byte;
    if (node == HV_EXEC_VEHICLE) {
        struct harvest_can_vehicle_status_t m;
        memset(&m, 0, sizeof m);
        m.state = state;
        m.arrived = flags & 1;
        m.homed = (flags >> 1) & 1;
        m.fault_bits = (uint8_t)fault_bits;
        m.move_seq = (uint8_t)(echo ? R->sm.node[node].next_move_seq - 1 : seq_byte);
        m.command_seq = (uint8_t)cmd_seq;
        m.position = harvest_can_vehicle_status_position_encode(
            R->sm.stop >= 0 && R->sm.stop < R->sm.plan->n_stops ? R->sm.plan->stops[R->sm.stop].y_m
                                                                : 0.0);
        send_packed(R, HARVEST_CAN_VEHICLE_STATUS_FRAME_ID, buf,
                    harvest_can_vehicle_status_pack(buf, &m, sizeof buf));
        return;
    }
    const hv_exec_arm_t *arm = &R->sm.arm[node == HV_EXEC_LEFT ? 0 : 1];
    int sp_seq = echo ? arm->sp_seq : seq_byte;
    if (node == HV_EXEC_LEFT)
        PACK_ARM_STATUS(left_arm_status, HARVEST_CAN_LEFT_ARM_STATUS_FRAME_ID);
    else
        PACK_ARM_STATUS(right_arm_status, HARVEST_CAN_RIGHT_ARM_STATUS_FRAME_ID);
}

#define PACK_EE(MSG, ID)                                                                           \
    do {                                                                                           \
        struct harvest_can_##MSG##_t m;                                                            \
        memset(&m, 0, sizeof m);                                                                   \
        m.state = state;                                                                           \
        m.action = action;                                                                         \
        m.ee_seq = (uint8_t)seq;                                                                   \
        m.fruit_held = flags & 1;                                                                  \
        send_packed(R, ID, buf, harvest_can_##MSG##_pack(buf, &m, sizeof buf));                    \
    } while (0)

static void ee_status(run_t *R, int node, uint8_t state, uint8_t action, uint8_t flags,
                      int seq_byte)
{
    uint8_t buf[8];
    int seq = (flags & 2) ? R->sm.arm[node == HV_EXEC_LEFT ? 0 : 1].ee_seq : seq_byte;
    if (node == HV_EXEC_LEFT)
        PACK_EE(left_arm_ee_status, HARVEST_CAN_LEFT_ARM_EE_STATUS_FRAME_ID);
    else
        PACK_EE(right_arm_ee_status, HARVEST_CAN_RIGHT_ARM_EE_STATUS_FRAME_ID);
}

/* What nodes that do everything they are told would report now. */
static void good_round(run_t *R)
{
    for (int n = 0; n < HV_EXEC_NODES; n++) {
        heartbeat(R, n, HV_CAN_HEALTH_OK, 10.0);
        status(R, n, HV_CAN_STATE_IDLE, 1 | 2 | 4, 0, 0);
        if (n != HV_EXEC_VEHICLE) {
            const hv_exec_arm_t *arm = &R->sm.arm[n == HV_EXEC_LEFT ? 0 : 1];
            uint8_t action =
                arm->phase == HV_ARM_RELEASE ? HV_CAN_EE_ACTION_RELEASE : HV_CAN_EE_ACTION_CUT;
            ee_status(R, n, HV_CAN_EE_STATE_DONE, action,
                      (uint8_t)(2 | (action == HV_CAN_EE_ACTION_CUT)), 0);
        }
    }
    tick(R, 10000000u);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const hv_exec_plan_t *plan = hv_fuzz_plan(1);
    reader_t r = {data, size};
    uint8_t flags = byte_or0(&r);
    static run_t R; /* ~60 KB: off the fuzzer's stack */
    static hv_exec_progress_t prog;
    memset(&R, 0, sizeof R);
    memset(&prog, 0, sizeof prog);
    if (flags & 2)
        for (unsigned i = 0; i < plan->n_picks; i++) {
            prog.pick[i] = byte_or0(&r) & 3;
            if (prog.pick[i] == HV_PROG_DONE)
                R.outcome_seen[i] = 1;
        }
    hv_exec_params_t prm;
    hv_exec_params_default(&prm);
    prm.home_max_s = 20.0;
    prm.clear_estop = flags & 1;
    if (hv_exec_init(&R.sm, plan, &prm, (flags & 2) ? &prog : NULL) != HV_OK)
        hv_fuzz_fail("init refused the defaults");
    R.now = 1000000000u;
    int op;
    unsigned ops = 0;
    while ((op = next(&r)) >= 0 && ops++ < 4096) {
        switch (op & 7) {
        case 0: tick(&R, (uint64_t)byte_or0(&r) * 5000000u + 1000000u); break;
        case 1: {
            hv_can_frame_t f;
            memset(&f, 0, sizeof f);
            f.id = (uint32_t)((byte_or0(&r) << 8) | byte_or0(&r)) & HV_CAN_SFF_MASK;
            f.dlc = byte_or0(&r) % 9;
            for (unsigned k = 0; k < f.dlc; k++)
                f.data[k] = byte_or0(&r);
            frame_in(&R, &f);
            break;
        }
        case 2: {
            int node = byte_or0(&r) % 3;
            uint8_t health = byte_or0(&r) & 3, s = byte_or0(&r);
            heartbeat(&R, node, health, s == 0 ? 10.0 : s / 10.0);
            break;
        }
        case 3: {
            int node = byte_or0(&r) % 3;
            uint8_t state = byte_or0(&r) & 7, fl = byte_or0(&r), seq = byte_or0(&r);
            uint16_t bits = (uint16_t)(byte_or0(&r) | (byte_or0(&r) << 8));
            status(&R, node, state, fl, seq, bits);
            break;
        }
        case 4: {
            int node = 1 + byte_or0(&r) % 2;
            uint8_t state = byte_or0(&r) & 7, action = byte_or0(&r) & 3, fl = byte_or0(&r);
            ee_status(&R, node, state, action, fl, byte_or0(&r));
            break;
        }
        case 5: good_round(&R); break;
        case 6:
        case 7: {
            hv_exec_event_t ev;
            memset(&ev, 0, sizeof ev);
            ev.kind = (op & 7) == 6 ? HV_EV_STOP_REQUEST : HV_EV_JOURNAL_FAILED;
            step(&R, &ev);
            break;
        }
        }
    }
    if (getenv("HV_FUZZ_TRACE"))
        fprintf(stderr, "fuzz_exec_step: %u ops, phase %s, stop %d, picked %u\n", ops,
                hv_exec_phase_name(R.sm.phase), R.sm.stop, R.sm.picked);
    return 0;
}
