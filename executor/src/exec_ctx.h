/* Inside the executor's step (private to src/exec_*.c): the context of one step and what
 * every room sends through it. Actions are appended to the step's list in the order they
 * must be carried out; a command is kept for resending until its node echoes it; SAFE is
 * the e-stop, entered from wherever a fault is found. */
#ifndef HV_EXEC_CTX_H
#define HV_EXEC_CTX_H

#include <stdint.h>

#include "hv/exec_events.h"
#include "hv/exec_outcome.h"
#include "hv/exec_state.h"

/* One step: the machine, the time (ns), the actions so far. */
typedef struct exec_ctx {
    hv_exec_sm_t *sm;
    uint64_t now;
    hv_exec_actions_t *out;
    int overflow; /* an action did not fit in out (hv_exec_step then goes to SAFE) */
} exec_ctx_t;

/* The node of an arm (hv_side_t): HV_EXEC_LEFT or HV_EXEC_RIGHT. */
static inline int exec_arm_node(int side)
{
    return side == HV_SIDE_LEFT ? HV_EXEC_LEFT : HV_EXEC_RIGHT;
}

/* A new action of `kind` for `node` (-1: none) at the end of the list, zeroed but for
 * those two; NULL when the list is full (c->overflow set). */
hv_exec_action_t *exec_push(exec_ctx_t *c, hv_exec_action_kind_t kind, int node);

/* The run's phase, and a telemetry action when it changed. */
void exec_set_phase(exec_ctx_t *c, hv_exec_phase_t ph);

/* Our heartbeat: health ESTOP in SAFE, else OK, with the time scale in use. */
void exec_heartbeat(exec_ctx_t *c);

/* SAFE (once): the e-stop frame first, nothing repeated any more, a heartbeat saying so. */
void exec_enter_safe(exec_ctx_t *c, hv_exec_safe_reason_t why, int node);

/* Keep action a (just sent to `node`; NULL: lost to an overflow, nothing kept) for sending
 * again every resend_s until the node echoes it (exec_nodes_resend); it replaces what was
 * kept for that node. */
void exec_remember(exec_ctx_t *c, int node, const hv_exec_action_t *a);

/* A command with the node's next sequence number, awaited (its echo: exec_echoed). */
void exec_send_command(exec_ctx_t *c, int node, int command);
/* The command to each node of `nodes` (1 << HV_EXEC_*), in node order. */
void exec_send_to(exec_ctx_t *c, unsigned nodes, int command);
/* The node echoed the command it was sent last. */
int exec_echoed(const hv_exec_sm_t *sm, int node);

/* A journal record (NULL when the list is full); the journal's records come before what
 * they announce. */
hv_exec_action_t *exec_journal(exec_ctx_t *c, hv_exec_journal_kind_t kind, int pick, int stop,
                               int attempt, int outcome, int reason);
/* A fruit's telemetry event. */
void exec_fruit_event(exec_ctx_t *c, hv_exec_fruit_event_kind_t kind, int pick, int attempt,
                      int outcome, int reason);
/* A pick's outcome: journalled first, then counted, its progress done, and told. */
void exec_record_outcome(exec_ctx_t *c, int pick, int attempt, hv_exec_outcome_t outcome,
                         hv_exec_reason_t reason);

/* The deadline (ns) of a motion or action planned to take `planned_s` of plan time:
 * planned * (1 + margin) + slack, over the time scale, plus the bus's latency. */
uint64_t exec_motion_deadline(const exec_ctx_t *c, hv_exec_real_t planned_s);
/* The deadline (ns) of a command's echo: command_timeout_s from now. */
uint64_t exec_command_deadline(const exec_ctx_t *c);

#endif /* HV_EXEC_CTX_H */
