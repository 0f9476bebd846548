/* One arm's pick cycle at a stop (private to src/exec_*.c), run for each side on its own:
 * APPROACH -> CUT -> RETURN -> RELEASE per pick, in plan order, each confirmed by the arm;
 * on a fault of that arm, RECOVER (DISABLE, CLEAR_FAULT, ENABLE, HOME) and a retry of the
 * fruit, or its outcome. The arm is DONE when the stop has nothing more for it (or a
 * controlled stop is under way); the stop ends when both are (exec_arms_done). */
#ifndef HV_EXEC_ARM_H
#define HV_EXEC_ARM_H

#include "exec_ctx.h"

/* The stop was reached (HARVEST): each arm starts its first unfinished pick, the left one
 * first. */
void exec_arms_begin_stop(exec_ctx_t *c);

/* The arm's node reported (status or end effector), or it recovers: its cycle goes on. */
void exec_arm_update(exec_ctx_t *c, int side);

/* The arm's deadline passed: a motion or action recovers, a recovery goes to SAFE. */
void exec_arm_timers(exec_ctx_t *c, int side);

/* Both arms are done with the stop. */
int exec_arms_done(const hv_exec_sm_t *sm);

#endif /* HV_EXEC_ARM_H */
