/* Supervision of the three nodes (private to src/exec_*.c): what they report, whether they
 * are all there and agree, whether one is lost, e-stopped or lost us, the e-stop latch found
 * at start-up, and the frames they have not acknowledged yet, sent again. */
#ifndef HV_EXEC_NODES_H
#define HV_EXEC_NODES_H

#include <stdint.h>

#include "exec_ctx.h"

/* Take a node's report (heartbeat, status, end-effector status) into what we know of it;
 * other events are none of the nodes' business. */
void exec_nodes_apply(hv_exec_sm_t *sm, const hv_exec_event_t *ev, uint64_t now_ns);

/* Every node has sent a heartbeat of our protocol and a status (an arm also its end
 * effector's). */
int exec_nodes_ready(const hv_exec_sm_t *sm);

/* Every node there (exec_nodes_ready): their time scale taken (SAFE when they disagree, or
 * differ from params.time_scale), the nodes that report an e-stop latched (SAFE unless the
 * operator cleared it for this run), our sequence numbers continued after theirs. 1 when
 * start-up may go on. */
int exec_nodes_take(exec_ctx_t *c);

/* Node i sent a heartbeat and a status after the last CLEAR_ESTOP was echoed. */
int exec_nodes_fresh(const hv_exec_sm_t *sm, int i);

/* After WAIT_NODES, every step: SAFE when a node's heartbeat is lost, its time scale
 * changed, it reports an e-stop (not the latch being cleared), it lost our heartbeat (once
 * its faults were cleared), or the vehicle faults (from HOMING on). */
void exec_nodes_check(exec_ctx_t *c);

/* Send again, every resend_s, each node's last command, setpoint, end-effector request or
 * move that it has not echoed yet. */
void exec_nodes_resend(exec_ctx_t *c);

#endif /* HV_EXEC_NODES_H */
