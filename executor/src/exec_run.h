/* The run's stops (private to src/exec_*.c): from the first stop to the course end, each
 * stop with work driven to (DRIVING), harvested by both arms (HARVEST, exec_arm.h), then
 * the next; online, waiting for the planner's next stops (WAIT_PLAN), driving on to its
 * commit line meanwhile; the final drive and ROW_DONE; and the operator's controlled stop,
 * which lets what is under way end and then disables every node (STOPPED). */
#ifndef HV_EXEC_RUN_H
#define HV_EXEC_RUN_H

#include "exec_ctx.h"

/* Go on to the next stop with work (DRIVING), wait for the plan to grow (WAIT_PLAN), drive
 * to the course end (FINAL_DRIVE), or end a controlled stop under way (STOPPED). */
void exec_run_next_stop(exec_ctx_t *c);

/* One step of phase DRIVING, FINAL_DRIVE, HARVEST or WAIT_PLAN (`ev`: the step's event). */
void exec_run_step(exec_ctx_t *c, const hv_exec_event_t *ev);

/* HV_EV_STOP_REQUEST: a controlled stop, at once where nothing moves; a second signal
 * before it ended is an e-stop (SAFE, operator), the bus's repeats are the same request. */
void exec_run_request_stop(exec_ctx_t *c, const hv_exec_event_t *ev);

/* HV_EV_PLAN_GROWN: whether the plan is final, how far the course is committed. */
void exec_run_plan_grown(hv_exec_sm_t *sm, const hv_exec_event_t *ev);

#endif /* HV_EXEC_RUN_H */
