/* The executor's state machine: a pure step function (DESIGN §7).
 *
 *   hv_exec_step(sm, &event, now_ns, &actions)
 *
 * takes one event (a decoded CAN frame or a timer tick) and the monotonic time, updates
 * the state and appends the actions to carry out, in order. No I/O, no heap, no clock:
 * the program (harvest_exec.c) feeds it and performs the actions; the tests drive it with
 * a fake clock and a fake bus.
 *
 * The run: WAIT_NODES (heartbeats + a status from each node, same time scale) -> ENABLE
 * (DISABLE, CLEAR_FAULT, ENABLE to all three nodes, each echoes the command) -> HOMING
 * (HOME to both arms, wait Homed) -> per stop: DRIVING (VehicleMove, wait Arrived with the move's sequence number)
 * -> HARVEST (both arms run their pick cycles independently; the stop ends when the slower
 * arm is done) -> ... -> FINAL_DRIVE (to the course end) -> ROW_DONE (arms and drive
 * disabled).
 *
 * Pick cycle of one arm: APPROACH (setpoint = IK of the fruit, wait TargetReached echoing
 * its SetpointSeq) -> CUT (journal "cut issued", EeCommand CUT, wait EeStatus DONE with the
 * EeSeq) -> RETURN (setpoint = home) -> RELEASE (journal "release issued", EeCommand
 * RELEASE, wait DONE) -> journal "picked" -> next pick.
 *
 * E-stop latch: a node that reports an e-stop when every node has been seen keeps the
 * executor from starting: SAFE (estop_latched), nothing but e-stops and heartbeats sent,
 * unless the operator cleared the e-stop for this run (params.clear_estop). Then the clear
 * is journalled, CLEAR_ESTOP goes to the latched nodes, and nothing more is sent before a
 * heartbeat and a status of every node, received after the last CLEAR_ESTOP was echoed,
 * show no e-stop (what a node reported before its clear no longer says anything). Only
 * CLEAR_ESTOP releases a latch (DBC): the CLEAR_FAULTs of start-up and recovery never do.
 *
 * Faults and their safe states:
 *   - e-stop reported by a node, lost heartbeat (heartbeat_timeout_s), a node reporting
 *     that it lost ours, a vehicle fault or move timeout, a fault during start-up or
 *     recovery, a journal write failure, a second operator stop: SAFE (terminal). Actions: an
 *     e-stop frame at once and every 100 ms, heartbeats with Health = ESTOP. Every node
 *     stops motion and latches; the journal keeps what was done.
 *   - on one arm, during its cycle: a joint fault, an end-effector fault, a rejected
 *     setpoint, a cut that failed, or a motion/action timeout: that arm goes through
 *     RECOVER (DISABLE to stop its motion -> CLEAR_FAULT -> ENABLE -> HOME, each echoed),
 *     then retries the fruit (at most max_retries more attempts) or records it failed /
 *     skipped and goes on with its next fruit; the other arm keeps working. A fruit whose
 *     cut was confirmed is never approached again (still held: released and picked; not
 *     held: failed, "dropped").
 * The operator's stop (HV_EV_STOP_REQUEST: SIGTERM, SIGINT) is a controlled stop, not an
 * e-stop: no new pick, drive or homing starts; what is under way ends as it would (an arm
 * finishes the pick in progress through its release; a fault in it recovers to home and the
 * fruit stays for the next run; the vehicle arrives where it was sent); then DISABLE to every
 * node and STOPPED (terminal). Nothing latches: a plain restart resumes from the journal. A
 * second signal before STOPPED is an e-stop (SAFE, operator); the bus's ExecutorStopRequest,
 * repeated, stays one request. Online, a wait for the planner's next stop longer than
 * wait_plan_timeout_s ends the same way (plan_timeout). The stop is journalled with its
 * reason (HV_JR_HALT) before the DISABLEs.
 * Timeouts: planned time * (1 + margin) + slack, in plan time, divided by the time scale,
 * plus latency_s of real time for the bus.
 */
#ifndef HV_EXEC_SM_H
#define HV_EXEC_SM_H

#include <stddef.h>
#include <stdint.h>

#include "hv/can_enums.h"
#include "hv/exec_outcome.h"
#include "hv/exec_plan.h"
#include "hv/exec_real.h"
#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* CAN nodes (the DBC's node ids) */
enum { HV_NODE_EXECUTOR = 1, HV_NODE_VEHICLE = 2, HV_NODE_ARM_L = 3, HV_NODE_ARM_R = 4 };
/* our index of the three remote nodes */
enum { HV_EXEC_VEHICLE = 0, HV_EXEC_LEFT = 1, HV_EXEC_RIGHT = 2, HV_EXEC_NODES = 3 };
/* a set of them: 1 << HV_EXEC_* */
#define HV_EXEC_ALL_NODES ((1u << HV_EXEC_NODES) - 1u)

/* Node commands, states, health and end-effector values (HV_CAN_CMD_*, HV_CAN_STATE_*,
 * HV_CAN_HEALTH_*, HV_CAN_EE_ACTION_*, HV_CAN_EE_STATE_*) are hv/can_enums.h, generated
 * from the DBC's value tables by the build. */

/* Arm FaultBits (DBC) */
#define HV_ARM_FAULT_JOINTS   0x00FFu /* bits 0..7: joint limit, following error (stall) */
#define HV_ARM_FAULT_EE       0x0100u /* bit 8 */
#define HV_ARM_FAULT_COMM     0x0200u /* bit 9: the arm lost our heartbeat */
#define HV_ARM_FAULT_ESTOP    0x0400u /* bit 10 */
#define HV_ARM_FAULT_REJECTED 0x0800u /* bit 11: setpoint out of range */
/* Vehicle FaultBits (DBC) */
#define HV_VEH_FAULT_COMM     0x08u
#define HV_VEH_FAULT_ESTOP    0x10u

#define HV_PROTOCOL_VERSION 1

typedef enum hv_exec_phase {
    HV_PH_WAIT_NODES = 0,
    HV_PH_ENABLE,
    HV_PH_HOMING,
    HV_PH_DRIVING,
    HV_PH_HARVEST,
    HV_PH_FINAL_DRIVE,
    HV_PH_ROW_DONE,
    HV_PH_SAFE,
    HV_PH_WAIT_PLAN, /* online: every committed stop done, waiting for the planner's next */
    HV_PH_STOPPED,   /* the operator's controlled stop is complete (terminal, resumable) */
    HV_PH_COUNT
} hv_exec_phase_t;

/* The steps of the ENABLE phase (sm->sub), in order; the e-stop clear only with a latch
 * and the operator's clear. */
typedef enum hv_exec_enable_step {
    HV_EN_DISABLE = 0, /* DISABLE sent to all: what a previous run left moving stops */
    HV_EN_CLEAR_ESTOP, /* the clear journalled, CLEAR_ESTOP sent to the latched nodes */
    HV_EN_FRESH,       /* waiting for a heartbeat and a status of every node after the clear */
    HV_EN_CLEAR_FAULT, /* CLEAR_FAULT sent to all */
    HV_EN_ENABLE       /* ENABLE sent to all, IDLE expected */
} hv_exec_enable_step_t;

typedef enum hv_exec_arm_phase {
    HV_ARM_IDLE = 0, /* no pick at this stop yet / between stops */
    HV_ARM_APPROACH,
    HV_ARM_CUT,
    HV_ARM_RETURN,
    HV_ARM_RELEASE,
    HV_ARM_RECOVER, /* DISABLE -> CLEAR_FAULT -> ENABLE -> HOME */
    HV_ARM_DONE,    /* all picks of this stop finished */
    HV_ARM_PHASE_COUNT
} hv_exec_arm_phase_t;

/* Why the executor went to SAFE. */
typedef enum hv_exec_safe_reason {
    HV_SAFE_NONE = 0,
    HV_SAFE_ESTOP,        /* a node reports e-stop */
    HV_SAFE_HEARTBEAT,    /* lost heartbeat of a node */
    HV_SAFE_NODES_ABSENT, /* not every node appeared within startup_timeout_s */
    HV_SAFE_TIME_SCALE,   /* nodes disagree on the time scale (or with ours) */
    HV_SAFE_COMM,         /* a node reports it lost our heartbeat */
    HV_SAFE_VEHICLE_FAULT,
    HV_SAFE_TIMEOUT,       /* start-up, vehicle move or recovery did not finish in time */
    HV_SAFE_FAULT,         /* a node faulted during start-up or recovery */
    HV_SAFE_JOURNAL,       /* the journal could not be written */
    HV_SAFE_OPERATOR,      /* a second stop request before the controlled stop ended */
    HV_SAFE_ESTOP_LATCHED, /* a node reports a latched e-stop at start-up, no operator clear */
    HV_SAFE_COUNT
} hv_exec_safe_reason_t;

/* Parameters in the executor's real type (hv/exec_real.h). */
typedef struct hv_exec_params {
    hv_exec_real_t time_scale;          /* expected node time scale; 0 = take the nodes' */
    hv_exec_real_t margin;              /* timeout = planned * (1 + margin) + slack (>= 0) */
    hv_exec_real_t slack_s;             /* plan time (>= 0) */
    hv_exec_real_t latency_s;           /* real time added to every timeout for the bus (>= 0) */
    hv_exec_real_t heartbeat_timeout_s; /* real time without a node's heartbeat = lost (> 0) */
    hv_exec_real_t heartbeat_period_s;  /* our heartbeat and e-stop repeat period, real (> 0) */
    hv_exec_real_t startup_timeout_s;   /* real time to see every node (> 0) */
    hv_exec_real_t command_timeout_s;   /* real time for a command echo (> 0) */
    hv_exec_real_t home_max_s;          /* plan time of the longest possible move to home (> 0) */
    hv_exec_real_t cut_s, release_s;    /* plan time of the end-effector actions (> 0) */
    hv_exec_real_t vehicle_speed_mps;   /* sent with each move (> 0) */
    hv_exec_real_t vehicle_accel_mps2;  /* for the move timeouts (> 0) */
    unsigned max_retries;               /* further attempts of a fruit after a recoverable fault */
    hv_exec_real_t resend_s;            /* real time before an unacknowledged frame is sent again
                                           (> 0; several status periods, so a status was missed) */
    int clear_estop;                    /* 1: an operator cleared the e-stop for this run: a latch
                                           found at start-up is released; 0: it keeps us in SAFE */
    int online;                         /* 1: the plan grows while the row runs (HV_EV_PLAN_GROWN)
                                           until an event says it is final; 0: the plan is whole */
    hv_exec_real_t wait_plan_timeout_s; /* online: real time in WAIT_PLAN with no new stop before
                                           a controlled stop, plan_timeout (> 0) */
} hv_exec_params_t;

/* Defaults: margin 0.5, slack 1 s, latency 0.3 s, heartbeat 0.5 s / 0.1 s, start-up 10 s,
 * command 1 s, cut 1 s, release 0.5 s, 0.1 m/s, 0.1 m/s^2, 2 retries, resend 0.25 s,
 * time scale 0, no e-stop clear, whole plan (not online), wait for the plan 120 s; every
 * field is set; home_max_s is the arm's business: set it (hv_exec_home_max_s). */
void hv_exec_params_default(hv_exec_params_t *p);

/* The longest rest-to-rest move of an arm to its home pose from anywhere in its range. */
double hv_exec_home_max_s(const hv_arm_t *arm);

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

/* What the executor knows about one remote node. */
typedef struct hv_exec_node {
    int seen;              /* a heartbeat with our protocol version arrived */
    int status_seen;       /* a status frame arrived */
    uint64_t hb_rx, st_rx; /* arrival order (hv_exec_sm_t.rx) of the last heartbeat, status */
    uint64_t last_hb_ns;
    hv_exec_real_t time_scale;
    int health;
    int state, fault_bits, homed, reached, sp_seq, cmd_seq; /* last status */
    int move_seq, arrived;
    hv_exec_real_t position_m;                            /* vehicle */
    int ee_seen, ee_state, ee_action, ee_seq, fruit_held; /* arms: last EeStatus */
    /* what we sent */
    int next_cmd_seq, next_sp_seq, next_ee_seq, next_move_seq;
    int wait_cmd_seq; /* command awaiting its echo, -1 none */
    /* the last command/setpoint/ee/move sent to this node, repeated every resend_s until
     * the node echoes its sequence number (a lost frame is not a fault) */
    int resend_active;
    hv_exec_action_t resend;
    uint64_t resend_ns;
} hv_exec_node_t;

typedef struct hv_exec_arm {
    hv_exec_arm_phase_t phase;
    int pick;           /* current pick (plan index), -1 none */
    unsigned next;      /* next pick of this arm at this stop, 0..count */
    unsigned attempt;   /* attempts of the current pick so far (1 on the first) */
    int sp_seq, ee_seq; /* what the current phase waits for */
    uint64_t deadline_ns;
    int cut_confirmed; /* the end effector reported the cut of the current pick done */
    int recover_step;  /* RECOVER: 0 DISABLE, 1 CLEAR_FAULT, 2 ENABLE, 3 HOME */
    int fault_reason;  /* hv_exec_reason_t that started the recovery */
    uint64_t pick_start_ns;
} hv_exec_arm_t;

typedef struct hv_exec_sm {
    const hv_exec_plan_t *plan;
    hv_exec_params_t prm;
    hv_exec_progress_t prog; /* per-pick progress (journal replay + this run) */
    hv_exec_phase_t phase;
    int sub;           /* ENABLE: the hv_exec_enable_step_t reached */
    unsigned latched;  /* nodes (1 << HV_EXEC_*) that reported an e-stop at start-up */
    uint64_t rx;       /* heartbeats and statuses received so far (their order) */
    uint64_t clear_rx; /* rx when the last CLEAR_ESTOP was echoed: later is fresh */
    hv_exec_safe_reason_t safe_reason;
    int safe_node;             /* node of the safe reason, -1 when none */
    hv_exec_real_t time_scale; /* in use (from the nodes once they agree) */
    hv_exec_node_t node[HV_EXEC_NODES];
    hv_exec_arm_t arm[2];
    int stop;             /* current stop (plan position), -1 before the first */
    uint64_t t_start_ns;  /* step 0 */
    uint64_t deadline_ns; /* phase deadline (start-up, drive) */
    uint64_t next_hb_ns;
    uint64_t t_row_start_ns;          /* first move sent; 0 = not yet */
    uint64_t t_row_end_ns;            /* row done; 0 = not yet */
    unsigned picked, failed, skipped; /* outcomes recorded in this run */
    unsigned faults;                  /* recoverable arm faults seen in this run */
    unsigned resends;                 /* frames sent again for want of an acknowledgement */
    int started;                      /* first step done */
    int stop_requested;               /* a controlled stop is under way (why: stop_reason) */
    hv_exec_stop_reason_t stop_reason;
    /* online (params.online) */
    int plan_final;           /* the planner said no stop will follow */
    hv_exec_real_t advance_m; /* the course is committed up to here (m) */
    int advancing;            /* WAIT_PLAN: a move to advance_m is under way */
    uint64_t wait_from_ns;    /* WAIT_PLAN entered */
    int wait_first;           /* this wait came before the row started */
    uint64_t wait_first_ns;   /* real time waited for the first stop (before the row) */
    uint64_t wait_row_ns;     /* real time waited for the planner once the row started */
    unsigned waits;           /* times the vehicle waited for the planner in the row */
} hv_exec_sm_t;

/* Set up for `plan` (prepared) with `params`; `progress` from the journal, or NULL for a
 * fresh run. The plan must outlive the state machine. HV_ERR_EXEC_PARAMS on bad params. */
hv_status_t hv_exec_init(hv_exec_sm_t *sm, const hv_exec_plan_t *plan,
                         const hv_exec_params_t *params, const hv_exec_progress_t *progress);

/* One step. Appends to `out` (not cleared: the caller empties it after carrying it out).
 * HV_ERR_EXEC_EVENT for an event out of its domain, HV_ERR_EXEC_ACTIONS_FULL if `out`
 * overflowed (the state machine then is in SAFE and the e-stop is the first action). */
hv_status_t hv_exec_step(hv_exec_sm_t *sm, const hv_exec_event_t *ev, uint64_t now_ns,
                         hv_exec_actions_t *out);

/* Plan time (s) elapsed between the first move and row done (or now when not done). */
hv_exec_real_t hv_exec_executed_s(const hv_exec_sm_t *sm, uint64_t now_ns);

/* Online: plan time (s) the vehicle waited for the planner before its first stop (*first_s)
 * and once the row had started (*row_s), the current wait included. */
void hv_exec_plan_wait_s(const hv_exec_sm_t *sm, uint64_t now_ns, hv_exec_real_t *first_s,
                         hv_exec_real_t *row_s);

/* 1 once the run ended (ROW_DONE or SAFE). */
int hv_exec_finished(const hv_exec_sm_t *sm);

const char *hv_exec_phase_name(int phase);
const char *hv_exec_arm_phase_name(int phase);
const char *hv_exec_safe_reason_name(int reason);
/* "vehicle", "left_arm", "right_arm" for HV_EXEC_*, "none" for -1, else "unknown". */
const char *hv_exec_node_name(int node);
/* The names of the nodes in `nodes` (1 << HV_EXEC_*), comma-separated, into buf ("" for
 * none); HV_ERR_ARG when a bit names no node or buf is too small (> 27 bytes is enough). */
hv_status_t hv_exec_node_list(unsigned nodes, char *buf, size_t len);

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_SM_H */
