/* The run's start-up (private to src/exec_*.c): WAIT_NODES (every node there, one time
 * scale, no e-stop latched without the operator's clear) -> ENABLE (DISABLE; with a latch
 * and the clear, CLEAR_ESTOP to the latched nodes and a fresh report of every node; then
 * CLEAR_FAULT and ENABLE, each echoed) -> HOMING (HOME to both arms), each step within its
 * timeout, else SAFE. */
#ifndef HV_EXEC_STARTUP_H
#define HV_EXEC_STARTUP_H

#include "exec_ctx.h"

/* One step of start-up (phase WAIT_NODES, ENABLE or HOMING); 1 when both arms are homed:
 * the run goes on to its first stop. */
int exec_startup_step(exec_ctx_t *c);

#endif /* HV_EXEC_STARTUP_H */
