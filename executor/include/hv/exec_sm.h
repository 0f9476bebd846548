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
 *     e-stop frame at once and then with each of our heartbeats (heartbeat_period_s, the
 *     DBC's cycle), which say Health = ESTOP. Every node stops motion and latches; the
 *     journal keeps what was done.
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
 *
 * The types are hv/exec_events.h (what goes in and out of a step) and hv/exec_state.h (the
 * machine and its parameters). Inside, src/exec_sm.c dispatches each step to rooms, one
 * concern each: the nodes' supervision, start-up, the run's stops, an arm's pick cycle
 * (executor/README.md lists them).
 */
#ifndef HV_EXEC_SM_H
#define HV_EXEC_SM_H

#include <stddef.h>
#include <stdint.h>

#include "hv/exec_events.h"
#include "hv/exec_outcome.h"
#include "hv/exec_plan.h"
#include "hv/exec_state.h"
#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Every field set to its default (src/exec_params.c says each and why). home_max_s is the
 * arm's business: set it (hv_exec_home_max_s). */
void hv_exec_params_default(hv_exec_params_t *p);

/* The longest rest-to-rest move of an arm to its home pose from anywhere in its range. */
double hv_exec_home_max_s(const hv_arm_t *arm);

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
