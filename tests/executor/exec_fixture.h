/* Test fixture for the executor's state machine: a plan built from the project config,
 * a fake clock and a fake bus that plays the vehicle and both arms. The fake nodes answer
 * the state machine's actions like the DBC says (echo sequence numbers, report reached /
 * done / arrived after a delay) and can be told to misbehave in each way the state
 * machine must handle. */
#ifndef HV_EXEC_FIXTURE_H
#define HV_EXEC_FIXTURE_H

#include <stdint.h>

#include "hv/exec_sm.h"

#define FX_MAX_EVENTS 64
#define FX_MAX_LOG    4096

typedef struct fx_node {
    int alive; /* sends heartbeats */
    double time_scale;
    int state, homed, reached, sp_seq, cmd_seq, fault_bits;
    int move_seq, arrived;
    double pos_m;
    int ee_state, ee_action, ee_seq, held;
    uint64_t busy_until_ns; /* pending motion / action completes then */
    int pending;            /* 0 none, 1 setpoint, 2 ee, 3 move, 4 home */
    int pending_ee_action;
    int estop;
} fx_node_t;

typedef struct fx_faults {
    int reject_setpoints[2];   /* reject the next n approach setpoints of the arm */
    int joint_fault_at[2];     /* raise a joint fault at the n-th setpoint (1-based), 0 never */
    int joint_fault_every[2];  /* raise a joint fault on every approach setpoint */
    int stall[2];              /* setpoints never reach */
    int cut_fail[2];           /* the next n cuts fail */
    int drop[2];               /* the next n cut fruits fall while returning */
    int home_never[2];         /* HOME never completes */
    int home_faults[2];        /* HOME puts the arm in FAULT (after start-up's homing) */
    int move_never;            /* the vehicle never arrives */
    int vehicle_fault_on_move; /* the vehicle faults on its n-th move */
    int comm_fault_arm;        /* >0: the left arm reports comm timeout on setpoint n */
    int estop_at_cut;          /* >0: the right arm reports ESTOP on its n-th cut */
    int drop_next[16];         /* the bus loses the next n frames of this action kind */
} fx_faults_t;

typedef struct fx_log_entry {
    hv_exec_action_t a;
    uint64_t t_ns;
} fx_log_entry_t;

typedef struct fx {
    hv_exec_plan_t plan;
    hv_exec_params_t prm;
    hv_exec_sm_t sm;
    uint64_t now_ns;
    uint64_t motion_ns; /* every fake motion and action takes this long (real) */
    fx_node_t node[HV_EXEC_NODES];
    fx_faults_t f;
    int setpoints_sent[2], cuts_sent[2], moves_sent;
    int cuts_done[2][HV_EXEC_MAX_PICKS]; /* cuts executed per pick (never more than 1) */
    int cur_pick[2];                     /* pick the arm is working on (from the log) */
    int estop_clears[HV_EXEC_NODES];     /* CLEAR_ESTOPs each node accepted */
    hv_exec_event_t q[FX_MAX_EVENTS];
    int nq;
    fx_log_entry_t log[FX_MAX_LOG];
    int nlog;
    hv_status_t last_status;
    /* called after every step when set (after fx_plan): the replay's trace (exec_replay.c) */
    void (*on_step)(void *ctx, const hv_exec_sm_t *sm, const hv_exec_event_t *ev, uint64_t now_ns,
                    hv_status_t st, const hv_exec_actions_t *out);
    void *on_step_ctx;
} fx_t;

/* A plan of `n_stops` stops with `per_arm` reachable picks per arm per stop. */
void fx_plan(fx_t *fx, int n_stops, int per_arm);
/* Init the state machine (progress may be NULL) and healthy nodes at time scale 10. */
void fx_start(fx_t *fx, const hv_exec_progress_t *progress);
/* A new state machine (fx->prm as it is now) resuming from the old one's progress, with the
 * nodes as the old one left them: a restart on the journal. Returns the log index where the
 * new run's actions start. */
int fx_restart(fx_t *fx);
/* The node's own e-stop trips: ESTOP with the e-stop fault bit, until CLEAR_ESTOP. */
void fx_latch_estop(fx_t *fx, int node);
/* Run for up to `seconds` of fake real time in 10 ms ticks; stops early when finished. */
void fx_run(fx_t *fx, double seconds);
/* Count log entries of one kind (and journal kind when kind is HV_ACT_JOURNAL, else -1). */
int fx_count(const fx_t *fx, hv_exec_action_kind_t kind, int jr_kind);
/* Index in the log of the first action matching, from `from`; -1 when none. */
int fx_find(const fx_t *fx, int from, hv_exec_action_kind_t kind, int sub);

/* Step one event now (the fake nodes react to its actions). */
void fx_event(fx_t *fx, const hv_exec_event_t *ev);
/* Online: the plan emptied (its stops come by fx_append_stop) and params.online set. */
void fx_online(fx_t *fx);
/* Online: step HV_EV_PLAN_GROWN (final: no stop will follow; advance_m: the commit line). */
void fx_grown(fx_t *fx, int final, double advance_m);
/* Online: append stop s of `src` (built by fx_plan: each stop's left then right picks
 * contiguous) to fx->plan and prepare it again; hv_exec_plan_append's status. */
hv_status_t fx_append_stop(fx_t *fx, const hv_exec_plan_t *src, int s);

#endif
