/* The state of the executor's state machine (hv/exec_sm.h): its parameters, the run's
 * phases, what it knows about each node and arm, and the machine itself (hv_exec_sm_t),
 * which the caller allocates, hv_exec_init() sets up and hv_exec_step() alone changes;
 * callers read it (phase, reasons, counts). */
#ifndef HV_EXEC_STATE_H
#define HV_EXEC_STATE_H

#include <stdint.h>

#include "hv/exec_events.h"
#include "hv/exec_outcome.h"
#include "hv/exec_plan.h"
#include "hv/exec_real.h"

#ifdef __cplusplus
extern "C" {
#endif

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

/* Parameters in the executor's real type (hv/exec_real.h); hv_exec_params_default() sets
 * each to its default. */
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

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_STATE_H */
