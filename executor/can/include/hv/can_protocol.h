/* Id layout of the harvest CAN protocol (executor/can/harvest.dbc, DESIGN §6):
 * standard 11-bit ids (node_id << 5) | command, in the spirit of ODrive's CANSimple.
 * The frame layouts themselves come from the DBC through the cantools-generated
 * "harvest_can.h" (harvest_can_<message>_pack/_unpack, HARVEST_CAN_<MESSAGE>_FRAME_ID),
 * which this header includes. tests/can checks these numbers against the DBC. */
#ifndef HV_CAN_PROTOCOL_H
#define HV_CAN_PROTOCOL_H

#include "harvest_can.h"

#define HV_CAN_PROTOCOL_VERSION 1 /* ProtocolVersion carried by every heartbeat */

/* node ids (6 bits) */
enum hv_can_node {
    HV_CAN_NODE_BROADCAST = 0,
    HV_CAN_NODE_EXECUTOR = 1,
    HV_CAN_NODE_VEHICLE = 2,
    HV_CAN_NODE_ARM_LEFT = 3,
    HV_CAN_NODE_ARM_RIGHT = 4
};

/* command numbers (5 bits), the same meaning on every node that has them */
enum hv_can_cmd {
    HV_CAN_CMD_ESTOP = 0, /* broadcast node only */
    HV_CAN_CMD_HEARTBEAT = 1,
    HV_CAN_CMD_COMMAND = 2, /* enable/disable/home/e-stop/clear fault/clear e-stop */
    HV_CAN_CMD_STATUS = 3,
    HV_CAN_CMD_SETPOINT = 4, /* arms: joint setpoint; vehicle: move */
    HV_CAN_CMD_JOINT_STATE = 5,
    HV_CAN_CMD_JOINT_VELOCITY = 6,
    HV_CAN_CMD_EE_COMMAND = 7,
    HV_CAN_CMD_EE_STATUS = 8,
    HV_CAN_CMD_PLAN_BEGIN = 9,  /* executor: a plan upload starts (firmware/) */
    HV_CAN_CMD_PLAN_DATA = 10,  /* executor: 6 bytes of it */
    HV_CAN_CMD_PLAN_STATUS = 11 /* executor: how the upload stands */
};

#define HV_CAN_ID(node, cmd) ((((unsigned)(node)) << 5) | ((unsigned)(cmd)&0x1Fu))
#define HV_CAN_ID_NODE(id)   (((unsigned)(id) >> 5) & 0x3Fu)
#define HV_CAN_ID_CMD(id)    ((unsigned)(id)&0x1Fu)

#endif /* HV_CAN_PROTOCOL_H */
