/* cantools-generated pack/unpack of harvest.dbc at the limits of each range: the joint
 * limits of DESIGN §2 survive the 0.1 mm / 0.0001 rad encoding, sign and width of every
 * packed field, range checks, and rejection of short payloads. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "harvest_can.h"
#include "hv/can_enums.h"
#include "hv/can_messages.h"

static void setpoint_at_joint_limits(void **state)
{
    (void)state;
    const double lo[4] = {0.0, -1.5708, 0.0, -3.1416};
    const double hi[4] = {0.5, 1.5708, 2.8, 3.1416};
    for (int corner = 0; corner < 2; corner++) {
        const double *q = corner ? hi : lo;
        struct harvest_can_left_arm_setpoint_t sp, back;
        harvest_can_left_arm_setpoint_init(&sp);
        sp.joint1_position = harvest_can_left_arm_setpoint_joint1_position_encode(q[0]);
        sp.joint2_position = harvest_can_left_arm_setpoint_joint2_position_encode(q[1]);
        sp.joint3_position = harvest_can_left_arm_setpoint_joint3_position_encode(q[2]);
        sp.joint4_position = harvest_can_left_arm_setpoint_joint4_position_encode(q[3]);
        sp.setpoint_seq = corner ? 31 : 0;
        assert_true(harvest_can_left_arm_setpoint_joint1_position_is_in_range(sp.joint1_position));
        assert_true(harvest_can_left_arm_setpoint_joint4_position_is_in_range(sp.joint4_position));
        uint8_t buf[8];
        assert_int_equal(harvest_can_left_arm_setpoint_pack(buf, &sp, sizeof buf), 8);
        assert_int_equal(harvest_can_left_arm_setpoint_unpack(&back, buf, sizeof buf), 0);
        assert_memory_equal(&sp, &back, sizeof sp);
        /* within half a step of the commanded value: 0.05 mm, 0.00005 rad */
        assert_float_equal(
            harvest_can_left_arm_setpoint_joint1_position_decode(back.joint1_position), q[0],
            0.5e-4);
        assert_float_equal(
            harvest_can_left_arm_setpoint_joint2_position_decode(back.joint2_position), q[1],
            0.5e-4);
        assert_float_equal(
            harvest_can_left_arm_setpoint_joint3_position_decode(back.joint3_position), q[2],
            0.5e-4);
        assert_float_equal(
            harvest_can_left_arm_setpoint_joint4_position_decode(back.joint4_position), q[3],
            0.5e-4);
        assert_int_equal(back.setpoint_seq, corner ? 31 : 0);
    }
}

static void setpoint_rounds_not_truncates(void **state)
{
    (void)state;
    /* 0.5 / 0.0001 is 4999.999... in binary: truncation would lose a step; cantools'
     * Python encoder rounds, and the build generates with --use-round to match */
    assert_int_equal(harvest_can_left_arm_setpoint_joint1_position_encode(0.5), 5000);
    assert_int_equal(harvest_can_left_arm_setpoint_joint2_position_encode(-1.5708), -15708);
    assert_int_equal(harvest_can_left_arm_setpoint_joint4_position_encode(3.1416), 31416);
}

static void setpoint_range_checks(void **state)
{
    (void)state;
    assert_true(harvest_can_left_arm_setpoint_joint1_position_is_in_phys_range(0.5));
    assert_false(harvest_can_left_arm_setpoint_joint1_position_is_in_phys_range(0.5002));
    assert_false(harvest_can_left_arm_setpoint_joint1_position_is_in_phys_range(-0.0002));
    assert_false(harvest_can_left_arm_setpoint_joint3_position_is_in_phys_range(2.8002));
    assert_false(harvest_can_left_arm_setpoint_joint2_position_is_in_range(-15709));
    assert_true(harvest_can_right_arm_setpoint_joint4_position_is_in_range(-31416));
}

static void vehicle_status_signed_fields(void **state)
{
    (void)state;
    struct harvest_can_vehicle_status_t vs, back;
    harvest_can_vehicle_status_init(&vs);
    vs.position = harvest_can_vehicle_status_position_encode(-838.8608); /* 24-bit minimum */
    vs.velocity = harvest_can_vehicle_status_velocity_encode(-2.048);    /* 12-bit minimum */
    vs.state = HARVEST_CAN_VEHICLE_STATUS_STATE_ESTOP_CHOICE;
    vs.arrived = 1;
    vs.fault_bits = 63;
    vs.move_seq = 255;
    vs.command_seq = 255;
    uint8_t buf[8];
    assert_int_equal(harvest_can_vehicle_status_pack(buf, &vs, sizeof buf), 8);
    /* position occupies bytes 0..2, two's complement little-endian: -8388608 = 0x800000 */
    assert_int_equal(buf[0], 0x00);
    assert_int_equal(buf[1], 0x00);
    assert_int_equal(buf[2], 0x80);
    assert_int_equal(harvest_can_vehicle_status_unpack(&back, buf, sizeof buf), 0);
    assert_int_equal(back.position, -8388608);
    assert_int_equal(back.velocity, -2048);
    assert_float_equal(harvest_can_vehicle_status_position_decode(back.position), -838.8608, 1e-9);
    assert_int_equal(back.state, HARVEST_CAN_VEHICLE_STATUS_STATE_ESTOP_CHOICE);
    assert_int_equal(back.fault_bits, 63);
    assert_int_equal(back.move_seq, 255);
    assert_int_equal(back.command_seq, 255);

    vs.position = harvest_can_vehicle_status_position_encode(838.8607);
    vs.velocity = harvest_can_vehicle_status_velocity_encode(2.047);
    assert_int_equal(harvest_can_vehicle_status_pack(buf, &vs, sizeof buf), 8);
    assert_int_equal(harvest_can_vehicle_status_unpack(&back, buf, sizeof buf), 0);
    assert_int_equal(back.position, 8388607);
    assert_int_equal(back.velocity, 2047);
}

static void heartbeat_time_scale_limits(void **state)
{
    (void)state;
    struct harvest_can_left_arm_heartbeat_t hb, back;
    harvest_can_left_arm_heartbeat_init(&hb);
    hb.time_scale = harvest_can_left_arm_heartbeat_time_scale_encode(655.35);
    hb.protocol_version = HV_CAN_PROTOCOL_VERSION;
    hb.health = HARVEST_CAN_LEFT_ARM_HEARTBEAT_HEALTH_ESTOP_CHOICE;
    hb.counter = 255;
    uint8_t buf[5];
    assert_int_equal(harvest_can_left_arm_heartbeat_pack(buf, &hb, sizeof buf), 5);
    assert_int_equal(harvest_can_left_arm_heartbeat_unpack(&back, buf, sizeof buf), 0);
    assert_int_equal(back.time_scale, 65535);
    assert_float_equal(harvest_can_left_arm_heartbeat_time_scale_decode(back.time_scale), 655.35,
                       1e-9);
    assert_false(harvest_can_left_arm_heartbeat_time_scale_is_in_range(0)); /* 0x is not a scale */
}

static void short_buffers_rejected(void **state)
{
    (void)state;
    struct harvest_can_right_arm_status_t st;
    uint8_t buf[8] = {0};
    harvest_can_right_arm_status_init(&st);
    assert_true(harvest_can_right_arm_status_pack(buf, &st, 4) < 0); /* DBC length 5 */
    assert_true(harvest_can_right_arm_status_unpack(&st, buf, 4) < 0);
    assert_int_equal(harvest_can_right_arm_status_pack(buf, &st, 5), 5);
}

/* The generated names (hv/can_enums.h, from the DBC's attributes) against cantools' own
 * reading of the same DBC (harvest_can.h): frame ids and cycle times. */
static void ids_follow_layout(void **state)
{
    (void)state;
    assert_int_equal(HARVEST_CAN_ESTOP_FRAME_ID,
                     HV_CAN_ID(HV_CAN_NODE_BROADCAST, HV_CAN_KIND_ESTOP));
    assert_int_equal(HARVEST_CAN_EXECUTOR_HEARTBEAT_FRAME_ID,
                     HV_CAN_ID(HV_CAN_NODE_EXECUTOR, HV_CAN_KIND_HEARTBEAT));
    assert_int_equal(HARVEST_CAN_VEHICLE_MOVE_FRAME_ID,
                     HV_CAN_ID(HV_CAN_NODE_VEHICLE, HV_CAN_KIND_MOVE));
    assert_int_equal(HARVEST_CAN_LEFT_ARM_SETPOINT_FRAME_ID,
                     HV_CAN_ID(HV_CAN_NODE_LEFT_ARM, HV_CAN_KIND_SETPOINT));
    assert_int_equal(HARVEST_CAN_RIGHT_ARM_EE_STATUS_FRAME_ID,
                     HV_CAN_ID(HV_CAN_NODE_RIGHT_ARM, HV_CAN_KIND_EE_STATUS));
    assert_int_equal(HARVEST_CAN_EXECUTOR_PLAN_STATUS_FRAME_ID,
                     HV_CAN_ID(HV_CAN_NODE_EXECUTOR, HV_CAN_KIND_PLAN_STATUS));
    assert_int_equal(HV_CAN_ID_NODE(HARVEST_CAN_RIGHT_ARM_STATUS_FRAME_ID), HV_CAN_NODE_RIGHT_ARM);
    assert_int_equal(HV_CAN_ID_KIND(HARVEST_CAN_RIGHT_ARM_STATUS_FRAME_ID), HV_CAN_KIND_STATUS);
}

static void cycle_times_match_cantools(void **state)
{
    (void)state;
    assert_int_equal(HV_CAN_ESTOP_CYCLE_MS, HARVEST_CAN_ESTOP_CYCLE_TIME_MS);
    assert_int_equal(HV_CAN_HEARTBEAT_CYCLE_MS, HARVEST_CAN_EXECUTOR_HEARTBEAT_CYCLE_TIME_MS);
    assert_int_equal(HV_CAN_HEARTBEAT_CYCLE_MS, HARVEST_CAN_RIGHT_ARM_HEARTBEAT_CYCLE_TIME_MS);
    assert_int_equal(HV_CAN_STATUS_CYCLE_MS, HARVEST_CAN_VEHICLE_STATUS_CYCLE_TIME_MS);
    assert_int_equal(HV_CAN_JOINT_STATE_CYCLE_MS, HARVEST_CAN_LEFT_ARM_JOINT_STATE_CYCLE_TIME_MS);
    assert_int_equal(HV_CAN_EE_STATUS_CYCLE_MS, HARVEST_CAN_RIGHT_ARM_EE_STATUS_CYCLE_TIME_MS);
    assert_int_equal(HV_CAN_PLAN_STATUS_CYCLE_MS, HARVEST_CAN_EXECUTOR_PLAN_STATUS_CYCLE_TIME_MS);
    /* a lost heartbeat is several missed ones, not one late frame */
    assert_true(HV_CAN_HEARTBEAT_TIMEOUT_MS >= 2 * HV_CAN_HEARTBEAT_CYCLE_MS);
}

static void message_table_matches_typed_code(void **state)
{
    (void)state;
    const hv_can_message_desc_t *m = hv_can_message_by_name("RightArmSetpoint");
    assert_non_null(m);
    assert_int_equal(m->id, HARVEST_CAN_RIGHT_ARM_SETPOINT_FRAME_ID);
    assert_ptr_equal(hv_can_message_by_id(m->id), m);
    assert_null(hv_can_message_by_name("NoSuchMessage"));
    assert_null(hv_can_message_by_id(0x7FF));
    const double v[5] = {0.25, -1.0, 2.5, 3.0, 17};
    uint8_t a[8], b[8];
    assert_int_equal(m->pack(a, v), 8);
    struct harvest_can_right_arm_setpoint_t sp;
    harvest_can_right_arm_setpoint_init(&sp);
    sp.joint1_position = harvest_can_right_arm_setpoint_joint1_position_encode(0.25);
    sp.joint2_position = harvest_can_right_arm_setpoint_joint2_position_encode(-1.0);
    sp.joint3_position = harvest_can_right_arm_setpoint_joint3_position_encode(2.5);
    sp.joint4_position = harvest_can_right_arm_setpoint_joint4_position_encode(3.0);
    sp.setpoint_seq = 17;
    assert_int_equal(harvest_can_right_arm_setpoint_pack(b, &sp, 8), 8);
    assert_memory_equal(a, b, 8);
    double back[HV_CAN_MAX_SIGNALS];
    assert_int_equal(m->unpack(a, 8, back), 0);
    for (int i = 0; i < 5; i++)
        assert_float_equal(back[i], v[i], 0.5e-4);

    hv_can_frame_t f = {m->id, 8, 0, {0}, 0};
    assert_int_equal(hv_can_message_check(&f), HV_OK);
    f.dlc = 7;
    assert_int_equal(hv_can_message_check(&f), HV_CAN_ERR_DECODE);
    f.dlc = 8;
    f.flags = HV_CAN_FLAG_EXT;
    assert_int_equal(hv_can_message_check(&f), HV_CAN_ERR_DECODE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(setpoint_at_joint_limits),
        cmocka_unit_test(setpoint_rounds_not_truncates),
        cmocka_unit_test(setpoint_range_checks),
        cmocka_unit_test(vehicle_status_signed_fields),
        cmocka_unit_test(heartbeat_time_scale_limits),
        cmocka_unit_test(short_buffers_rejected),
        cmocka_unit_test(ids_follow_layout),
        cmocka_unit_test(cycle_times_match_cantools),
        cmocka_unit_test(message_table_matches_typed_code),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
