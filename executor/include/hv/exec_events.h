/* What goes into the executor's step function (hv/exec_sm.h) and what comes out of it:
 * events (a decoded frame, a tick, a request of the program) and actions (frames to send,
 * journal records to append, telemetry). hv/exec_can.h turns frames into events and actions
 * into frames. */
#ifndef HV_EXEC_EVENTS_H
#define HV_EXEC_EVENTS_H

#include "hv/can_enums.h"
#include "hv/exec_real.h"

#ifdef __cplusplus
extern "C" {
#endif

/* our index of the three remote nodes */
enum { HV_EXEC_VEHICLE = 0, HV_EXEC_LEFT = 1, HV_EXEC_RIGHT = 2, HV_EXEC_NODES = 3 };
/* a set of them: 1 << HV_EXEC_* */
#define HV_EXEC_ALL_NODES ((1u << HV_EXEC_NODES) - 1u)

/* Node commands, states, health, fault bits and end-effector values (HV_CAN_CMD_*,
 * HV_CAN_STATE_*, HV_CAN_HEALTH_*, HV_CAN_ARM_FAULT_*, HV_CAN_VEHICLE_FAULT_*,
 * HV_CAN_EE_ACTION_*, HV_CAN_EE_STATE_*) and the protocol version are hv/can_enums.h,
 * generated from the DBC by the build. */

typedef enum hv_exec_event_kind {
    HV_EV_TICK = 0,  /* time passed */
    HV_EV_HEARTBEAT, /* a node's heartbeat */
    HV_EV_VEHICLE_STATUS,
    HV_EV_ARM_STATUS,
    HV_EV_EE_STATUS,
    HV_EV_STOP_REQUEST,   /* operator: a controlled stop (SIGTERM, SIGINT, the bus) (u.stop) */
    HV_EV_JOURNAL_FAILED, /* the program could not write a journal record */
    HV_EV_PLAN_GROWN      /* online: the program appended stops to the plan (u.plan) */
} hv_exec_event_kind_t;

typedef struct hv_exec_event {
    hv_exec_event_kind_t kind;
    int node; /* HV_EXEC_VEHICLE / _LEFT / _RIGHT (arm and ee events: the arm) */
    union {
        struct {
            int health;
            hv_exec_real_t time_scale;
            int protocol;
        } hb;
        struct {
            hv_exec_real_t position_m;
            int state;
            int arrived;
            int fault_bits;
            int move_seq;
            int cmd_seq;
        } veh;
        struct {
            int state;
            int reached;
            int homed;
            int sp_seq;
            int cmd_seq;
            int fault_bits;
        } arm;
        struct {
            int state;
            int action;
            int ee_seq;
            int fruit_held;
        } ee;
        /* final: no stop will follow; advance_m: the planner has committed the course up
         * to here, so the vehicle may drive this far when no stop with work is ahead */
        struct {
            int final;
            hv_exec_real_t advance_m;
        } plan;
        /* HV_EV_STOP_REQUEST: 1 from the bus (ExecutorStopRequest): its repeats are the
         * same request; 0 a signal: a second one before the stop ends is an e-stop */
        struct {
            int from_bus;
        } stop;
    } u;
} hv_exec_event_t;

typedef enum hv_exec_action_kind {
    HV_ACT_HEARTBEAT = 0, /* our heartbeat: u.hb */
    HV_ACT_ESTOP,         /* e-stop frame (EstopActive = 1) */
    HV_ACT_COMMAND,       /* u.cmd to node */
    HV_ACT_SETPOINT,      /* u.sp to arm node */
    HV_ACT_EE,            /* u.ee to arm node */
    HV_ACT_MOVE,          /* u.move to the vehicle */
    HV_ACT_JOURNAL,       /* u.jr: append + flush before the next action */
    HV_ACT_FRUIT_EVENT,   /* telemetry: u.fe */
    HV_ACT_PHASE          /* telemetry: the run's phase changed (read the state) */
} hv_exec_action_kind_t;

typedef enum hv_exec_journal_kind {
    HV_JR_STOP = 0,    /* stop reached */
    HV_JR_CUT,         /* cut issued for a pick */
    HV_JR_RELEASE,     /* release issued for a pick */
    HV_JR_OUTCOME,     /* a pick's outcome */
    HV_JR_DONE,        /* row done */
    HV_JR_ESTOP_CLEAR, /* the operator's e-stop clear, of the nodes in u.jr.nodes */
    HV_JR_HALT         /* a controlled stop, why in u.jr.reason (hv_exec_stop_reason_t) */
} hv_exec_journal_kind_t;

typedef enum hv_exec_fruit_event_kind {
    HV_FE_APPROACH = 0,
    HV_FE_CUT,
    HV_FE_RETURN,
    HV_FE_RELEASE,
    HV_FE_OUTCOME,
    HV_FE_FAULT
} hv_exec_fruit_event_kind_t;

typedef struct hv_exec_action {
    hv_exec_action_kind_t kind;
    int node; /* HV_EXEC_* for commands, setpoints, ee */
    union {
        struct {
            int health;
            hv_exec_real_t time_scale;
        } hb;
        struct {
            int command;
            int seq;
        } cmd;
        struct {
            hv_exec_real_t q[HV_NJOINTS];
            int seq;
        } sp;
        struct {
            int action;
            int seq;
        } ee;
        struct {
            hv_exec_real_t target_m;
            hv_exec_real_t speed_mps;
            int seq;
        } move;
        struct {
            hv_exec_journal_kind_t kind;
            int pick;
            int stop;
            int attempt;
            int outcome;
            int reason;
            unsigned nodes;
        } jr; /* nodes: 1 << HV_EXEC_* */
        struct {
            hv_exec_fruit_event_kind_t kind;
            int pick;
            int attempt;
            int outcome;
            int reason;
        } fe;
    } u;
} hv_exec_action_t;

#define HV_EXEC_MAX_ACTIONS 32

typedef struct hv_exec_actions {
    unsigned n;
    hv_exec_action_t a[HV_EXEC_MAX_ACTIONS];
} hv_exec_actions_t;

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_EVENTS_H */
