/* See fuzz_nodes.h. */
#include "fuzz_nodes.h"

#include <string.h>

#include "fuzz_support.h"
#include "harvest_can.h"
#include "hv/exec_can.h"
#include "hv/exec_status.h"

void hv_fuzz_run_init(hv_fuzz_run_t *R, const hv_exec_plan_t *plan, const hv_exec_params_t *prm,
                      const hv_exec_progress_t *prog)
{
    memset(R, 0, sizeof *R);
    if (prog)
        for (unsigned i = 0; i < plan->n_picks; i++)
            R->outcome_seen[i] = prog->pick[i] == HV_PROG_DONE;
    if (hv_exec_init(&R->sm, plan, prm, prog) != HV_OK)
        hv_fuzz_fail("init refused the parameters");
    R->now = 1000000000u;
}

/* the executor's replay only (hv_fuzz_on_step); a fuzzer never sets it */
static hv_fuzz_step_hook_t step_hook;
static void *step_hook_ctx;

void hv_fuzz_on_step(hv_fuzz_step_hook_t hook, void *ctx)
{
    step_hook = hook;
    step_hook_ctx = ctx;
}

static void check_actions(hv_fuzz_run_t *R, hv_exec_phase_t before, const hv_exec_actions_t *out)
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

static int final_phase(hv_exec_phase_t ph)
{
    return ph == HV_PH_SAFE || ph == HV_PH_ROW_DONE || ph == HV_PH_STOPPED;
}

void hv_fuzz_step(hv_fuzz_run_t *R, const hv_exec_event_t *ev)
{
    static hv_exec_sm_t before_sm; /* large: off the fuzzer's stack */
    hv_exec_actions_t out;
    out.n = 0;
    hv_exec_phase_t before = R->sm.phase;
    before_sm = R->sm;
    hv_status_t st = hv_exec_step(&R->sm, ev, R->now, &out);
    if (step_hook)
        step_hook(step_hook_ctx, &R->sm, ev, R->now, st, &out);
    if (st == HV_ERR_EXEC_ACTIONS_FULL)
        hv_fuzz_fail("one step overflowed its action list");
    if (st == HV_ERR_EXEC_EVENT && (out.n != 0 || memcmp(&before_sm, &R->sm, sizeof before_sm)))
        hv_fuzz_fail("a refused event (kind %d) changed the state or acted", (int)ev->kind);
    if (st != HV_OK && st != HV_ERR_EXEC_EVENT)
        hv_fuzz_fail("step returned %d", (int)st);
    if ((unsigned)R->sm.phase >= HV_PH_COUNT ||
        (R->sm.phase == HV_PH_WAIT_PLAN && !R->sm.prm.online))
        hv_fuzz_fail("phase %d (online %d)", (int)R->sm.phase, R->sm.prm.online);
    if (final_phase(before) && R->sm.phase != before)
        hv_fuzz_fail("left final phase %s for %s", hv_exec_phase_name(before),
                     hv_exec_phase_name(R->sm.phase));
    if (R->sm.stop < -1 || R->sm.stop > (int)R->sm.plan->n_stops)
        hv_fuzz_fail("stop %d of a plan of %u", R->sm.stop, (unsigned)R->sm.plan->n_stops);
    check_actions(R, before, &out);
    if (R->sm.phase == HV_PH_SAFE && R->sm.safe_reason == HV_SAFE_ESTOP_LATCHED) {
        if (R->commanded)
            hv_fuzz_fail("a latched e-stop found after commands were sent");
        R->latched_without_clear = 1;
    }
}

static void frame_in(hv_fuzz_run_t *R, const hv_can_frame_t *f)
{
    hv_exec_event_t ev;
    hv_exec_arm_sample_t samples[2];
    memset(&ev, 0, sizeof ev);
    if (hv_exec_can_decode(f, &ev, samples) == HV_RX_EVENT)
        hv_fuzz_step(R, &ev);
}

static void tick(hv_fuzz_run_t *R, uint64_t dt_ns)
{
    R->now += dt_ns;
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = HV_EV_TICK;
    hv_fuzz_step(R, &ev);
}

/* ---- frames as the nodes send them (the DBC's generated pack) ---- */

static void send_packed(hv_fuzz_run_t *R, uint32_t id, const uint8_t *buf, int len)
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

static void heartbeat(hv_fuzz_run_t *R, int node, uint8_t health, double scale)
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
static int wanted_cmd_seq(const hv_fuzz_run_t *R, int node)
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

static void status(hv_fuzz_run_t *R, int node, uint8_t state, uint8_t flags, int seq_byte,
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

static void ee_status(hv_fuzz_run_t *R, int node, uint8_t state, uint8_t action, uint8_t flags,
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
static void good_round(hv_fuzz_run_t *R)
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

void hv_fuzz_node_op(hv_fuzz_run_t *R, int op, hv_fuzz_reader_t *r)
{
    switch (op & 7) {
    case 0: tick(R, (uint64_t)hv_fuzz_byte(r) * 5000000u + 1000000u); break;
    case 1: {
        hv_can_frame_t f;
        memset(&f, 0, sizeof f);
        f.id = (uint32_t)((hv_fuzz_byte(r) << 8) | hv_fuzz_byte(r)) & HV_CAN_SFF_MASK;
        f.dlc = hv_fuzz_byte(r) % 9;
        for (unsigned k = 0; k < f.dlc; k++)
            f.data[k] = hv_fuzz_byte(r);
        frame_in(R, &f);
        break;
    }
    case 2: {
        int node = hv_fuzz_byte(r) % 3;
        uint8_t health = hv_fuzz_byte(r) & 3, s = hv_fuzz_byte(r);
        heartbeat(R, node, health, s == 0 ? 10.0 : s / 10.0);
        break;
    }
    case 3: {
        int node = hv_fuzz_byte(r) % 3;
        uint8_t state = hv_fuzz_byte(r) & 7, fl = hv_fuzz_byte(r), seq = hv_fuzz_byte(r);
        uint16_t bits = (uint16_t)(hv_fuzz_byte(r) | (hv_fuzz_byte(r) << 8));
        status(R, node, state, fl, seq, bits);
        break;
    }
    case 4: {
        int node = 1 + hv_fuzz_byte(r) % 2;
        uint8_t state = hv_fuzz_byte(r) & 7, action = hv_fuzz_byte(r) & 3, fl = hv_fuzz_byte(r);
        ee_status(R, node, state, action, fl, hv_fuzz_byte(r));
        break;
    }
    case 5: good_round(R); break;
    case 6:
    case 7: {
        hv_exec_event_t ev;
        memset(&ev, 0, sizeof ev);
        ev.kind = (op & 7) == 6 ? HV_EV_STOP_REQUEST : HV_EV_JOURNAL_FAILED;
        if (ev.kind == HV_EV_STOP_REQUEST)
            ev.u.stop.from_bus = (op >> 3) & 3; /* 2, 3: out of the event's domain */
        hv_fuzz_step(R, &ev);
        break;
    }
    }
}
