/* The executor's CAN adapter: every action it sends packs to the DBC's frame, and every
 * status the nodes send decodes into the right event (round trips through the generated
 * pack/unpack of executor/can). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "harvest_can.h"
#include "hv/exec_can.h"
#include "hv/exec_status.h"

static void test_encode_actions(void **state)
{
    (void)state;
    hv_exec_can_tx_t tx = {0, 0};
    hv_can_frame_t f;
    int has;
    hv_exec_action_t a;

    memset(&a, 0, sizeof a);
    a.kind = HV_ACT_SETPOINT;
    a.node = HV_EXEC_RIGHT;
    double q[4] = {0.25, -0.5, 1.4, 3.0};
    memcpy(a.u.sp.q, q, sizeof q);
    a.u.sp.seq = 31;
    assert_int_equal(hv_exec_can_encode(&a, &tx, &f, &has), HV_OK);
    assert_int_equal(has, 1);
    assert_int_equal(f.id, HARVEST_CAN_RIGHT_ARM_SETPOINT_FRAME_ID);
    struct harvest_can_right_arm_setpoint_t sp;
    assert_int_equal(harvest_can_right_arm_setpoint_unpack(&sp, f.data, f.dlc), 0);
    assert_float_equal(harvest_can_right_arm_setpoint_joint2_position_decode(sp.joint2_position),
                       -0.5, 1e-4);
    assert_float_equal(harvest_can_right_arm_setpoint_joint4_position_decode(sp.joint4_position),
                       3.0, 1e-4);
    assert_int_equal(sp.setpoint_seq, 31);
    a.u.sp.q[2] = 3.5; /* beyond joint 3's range: refused, never sent clipped */
    assert_int_equal(hv_exec_can_encode(&a, &tx, &f, &has), HV_ERR_EXEC_CAN_FRAME);

    memset(&a, 0, sizeof a);
    a.kind = HV_ACT_COMMAND;
    a.node = HV_EXEC_VEHICLE;
    a.u.cmd.command = HV_CAN_CMD_CLEAR_FAULT;
    a.u.cmd.seq = 200;
    assert_int_equal(hv_exec_can_encode(&a, &tx, &f, &has), HV_OK);
    assert_int_equal(f.id, (2u << 5) | 2u);
    struct harvest_can_vehicle_command_t vc;
    assert_int_equal(harvest_can_vehicle_command_unpack(&vc, f.data, f.dlc), 0);
    assert_int_equal(vc.command, HV_CAN_CMD_CLEAR_FAULT);
    assert_int_equal(vc.command_seq, 200);

    memset(&a, 0, sizeof a);
    a.kind = HV_ACT_MOVE;
    a.node = HV_EXEC_VEHICLE;
    a.u.move.target_m = 1.2345;
    a.u.move.speed_mps = 0.1;
    a.u.move.seq = 9;
    assert_int_equal(hv_exec_can_encode(&a, &tx, &f, &has), HV_OK);
    struct harvest_can_vehicle_move_t mv;
    assert_int_equal(harvest_can_vehicle_move_unpack(&mv, f.data, f.dlc), 0);
    assert_float_equal(harvest_can_vehicle_move_target_position_decode(mv.target_position), 1.2345,
                       1e-4);
    assert_int_equal(mv.move_seq, 9);

    memset(&a, 0, sizeof a);
    a.kind = HV_ACT_EE;
    a.node = HV_EXEC_LEFT;
    a.u.ee.action = HV_CAN_EE_ACTION_CUT;
    a.u.ee.seq = 77;
    assert_int_equal(hv_exec_can_encode(&a, &tx, &f, &has), HV_OK);
    assert_int_equal(f.id, HARVEST_CAN_LEFT_ARM_EE_COMMAND_FRAME_ID);

    /* heartbeats and e-stops count up */
    memset(&a, 0, sizeof a);
    a.kind = HV_ACT_HEARTBEAT;
    a.u.hb.time_scale = 20.0;
    a.u.hb.health = HV_CAN_HEALTH_ESTOP;
    for (int i = 0; i < 2; i++)
        assert_int_equal(hv_exec_can_encode(&a, &tx, &f, &has), HV_OK);
    struct harvest_can_executor_heartbeat_t hb;
    assert_int_equal(harvest_can_executor_heartbeat_unpack(&hb, f.data, f.dlc), 0);
    assert_int_equal(hb.counter, 1);
    assert_int_equal(hb.health, HV_CAN_HEALTH_ESTOP);
    assert_int_equal(hb.protocol_version, 1);
    assert_float_equal(harvest_can_executor_heartbeat_time_scale_decode(hb.time_scale), 20.0, 1e-9);
    a.kind = HV_ACT_ESTOP;
    assert_int_equal(hv_exec_can_encode(&a, &tx, &f, &has), HV_OK);
    assert_int_equal(f.id, 0u);
    struct harvest_can_estop_t es;
    assert_int_equal(harvest_can_estop_unpack(&es, f.data, f.dlc), 0);
    assert_int_equal(es.estop_active, 1);

    /* journal and telemetry actions are not frames */
    a.kind = HV_ACT_JOURNAL;
    assert_int_equal(hv_exec_can_encode(&a, &tx, &f, &has), HV_OK);
    assert_int_equal(has, 0);
}

static void test_decode_statuses(void **state)
{
    (void)state;
    hv_can_frame_t f;
    hv_exec_event_t ev;
    hv_exec_arm_sample_t samples[2];
    memset(samples, 0, sizeof samples);

    memset(&f, 0, sizeof f);
    struct harvest_can_left_arm_status_t st;
    harvest_can_left_arm_status_init(&st);
    st.state = HV_CAN_STATE_IDLE;
    st.target_reached = 1;
    st.homed = 1;
    st.setpoint_seq = 17;
    st.command_seq = 250;
    st.fault_bits = 0x0800;
    f.id = HARVEST_CAN_LEFT_ARM_STATUS_FRAME_ID;
    f.dlc = (uint8_t)harvest_can_left_arm_status_pack(f.data, &st, sizeof f.data);
    assert_int_equal(hv_exec_can_decode(&f, &ev, samples), HV_RX_EVENT);
    assert_int_equal(ev.kind, HV_EV_ARM_STATUS);
    assert_int_equal(ev.node, HV_EXEC_LEFT);
    assert_int_equal(ev.u.arm.reached, 1);
    assert_int_equal(ev.u.arm.sp_seq, 17);
    assert_int_equal(ev.u.arm.cmd_seq, 250);
    assert_int_equal(ev.u.arm.fault_bits, HV_CAN_ARM_FAULT_SETPOINT_REJECTED);

    struct harvest_can_vehicle_status_t vs;
    harvest_can_vehicle_status_init(&vs);
    vs.position = harvest_can_vehicle_status_position_encode(1.75);
    vs.arrived = 1;
    vs.move_seq = 4;
    memset(&f, 0, sizeof f);
    f.id = HARVEST_CAN_VEHICLE_STATUS_FRAME_ID;
    f.dlc = (uint8_t)harvest_can_vehicle_status_pack(f.data, &vs, sizeof f.data);
    assert_int_equal(hv_exec_can_decode(&f, &ev, samples), HV_RX_EVENT);
    assert_int_equal(ev.kind, HV_EV_VEHICLE_STATUS);
    assert_float_equal(ev.u.veh.position_m, 1.75, 1e-4);
    assert_int_equal(ev.u.veh.move_seq, 4);

    struct harvest_can_right_arm_heartbeat_t hb;
    harvest_can_right_arm_heartbeat_init(&hb);
    hb.time_scale = harvest_can_right_arm_heartbeat_time_scale_encode(12.5);
    hb.protocol_version = 1;
    memset(&f, 0, sizeof f);
    f.id = HARVEST_CAN_RIGHT_ARM_HEARTBEAT_FRAME_ID;
    f.dlc = (uint8_t)harvest_can_right_arm_heartbeat_pack(f.data, &hb, sizeof f.data);
    assert_int_equal(hv_exec_can_decode(&f, &ev, samples), HV_RX_EVENT);
    assert_int_equal(ev.kind, HV_EV_HEARTBEAT);
    assert_int_equal(ev.node, HV_EXEC_RIGHT);
    assert_float_equal(ev.u.hb.time_scale, 12.5, 1e-9);

    struct harvest_can_right_arm_ee_status_t ee;
    harvest_can_right_arm_ee_status_init(&ee);
    ee.state = HV_CAN_EE_STATE_DONE;
    ee.ee_seq = 201;
    ee.fruit_held = 1;
    memset(&f, 0, sizeof f);
    f.id = HARVEST_CAN_RIGHT_ARM_EE_STATUS_FRAME_ID;
    f.dlc = (uint8_t)harvest_can_right_arm_ee_status_pack(f.data, &ee, sizeof f.data);
    assert_int_equal(hv_exec_can_decode(&f, &ev, samples), HV_RX_EVENT);
    assert_int_equal(ev.kind, HV_EV_EE_STATUS);
    assert_int_equal(ev.u.ee.ee_seq, 201);
    assert_int_equal(ev.u.ee.fruit_held, 1);

    struct harvest_can_right_arm_joint_state_t js;
    harvest_can_right_arm_joint_state_init(&js);
    js.joint3_position = harvest_can_right_arm_joint_state_joint3_position_encode(1.4);
    memset(&f, 0, sizeof f);
    f.id = HARVEST_CAN_RIGHT_ARM_JOINT_STATE_FRAME_ID;
    f.dlc = (uint8_t)harvest_can_right_arm_joint_state_pack(f.data, &js, sizeof f.data);
    assert_int_equal(hv_exec_can_decode(&f, &ev, samples), HV_RX_JOINTS);
    assert_int_equal(ev.node, HV_SIDE_RIGHT);
    assert_float_equal(samples[1].q[2], 1.4, 1e-4);

    /* a DBC id with a length other than the DBC's is malformed; others and our own frames are ignored */
    f.dlc = 3;
    assert_int_equal(hv_exec_can_decode(&f, &ev, samples), HV_RX_MALFORMED);
    /* longer than the DBC's length is malformed too: the ee status is 3 bytes long */
    f.id = HARVEST_CAN_RIGHT_ARM_EE_STATUS_FRAME_ID;
    f.dlc = (uint8_t)harvest_can_right_arm_ee_status_pack(f.data, &ee, sizeof f.data);
    assert_int_equal(hv_exec_can_decode(&f, &ev, samples), HV_RX_EVENT);
    f.dlc++;
    assert_int_equal(hv_exec_can_decode(&f, &ev, samples), HV_RX_MALFORMED);
    f.id = HARVEST_CAN_LEFT_ARM_SETPOINT_FRAME_ID;
    f.dlc = 8;
    assert_int_equal(hv_exec_can_decode(&f, &ev, samples), HV_RX_NONE);
    f.id = 0x7FF;
    assert_int_equal(hv_exec_can_decode(&f, &ev, samples), HV_RX_NONE);
    f.id = HARVEST_CAN_LEFT_ARM_STATUS_FRAME_ID;
    f.flags = HV_CAN_FLAG_EXT;
    assert_int_equal(hv_exec_can_decode(&f, &ev, samples), HV_RX_NONE);
}

/* ExecutorStopRequest: the bus's controlled stop; StopRequested=0 says nothing. */
static void test_decode_the_stop_request(void **state)
{
    (void)state;
    hv_can_frame_t f;
    hv_exec_event_t ev;
    hv_exec_arm_sample_t samples[2];
    struct harvest_can_executor_stop_request_t m;
    harvest_can_executor_stop_request_init(&m);
    m.stop_requested = 1;
    memset(&f, 0, sizeof f);
    f.id = HARVEST_CAN_EXECUTOR_STOP_REQUEST_FRAME_ID;
    f.dlc = (uint8_t)harvest_can_executor_stop_request_pack(f.data, &m, sizeof f.data);
    assert_int_equal(f.dlc, 1);
    assert_int_equal(hv_exec_can_decode(&f, &ev, samples), HV_RX_EVENT);
    assert_int_equal(ev.kind, HV_EV_STOP_REQUEST);
    assert_int_equal(ev.u.stop.from_bus, 1);
    f.data[0] = 0;
    assert_int_equal(hv_exec_can_decode(&f, &ev, samples), HV_RX_NONE);
    f.dlc = 2;
    assert_int_equal(hv_exec_can_decode(&f, &ev, samples), HV_RX_MALFORMED);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_encode_actions),
        cmocka_unit_test(test_decode_statuses),
        cmocka_unit_test(test_decode_the_stop_request),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
