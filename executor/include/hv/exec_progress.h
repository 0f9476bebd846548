/* What a journal record means for the run's progress: the one mapping from a record
 * (an HV_ACT_JOURNAL action of the state machine) to hv_exec_progress_t that every
 * journal's replay uses, whatever its format (the Linux text journal, exec_journal.c; the
 * firmware's binary records, firmware/fw_journal.c), so a restart resumes the same way on
 * every board. Pure: no I/O. */
#ifndef HV_EXEC_PROGRESS_H
#define HV_EXEC_PROGRESS_H

#include "hv/exec_sm.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Apply one journal record, in journal order, to `progress` (zeroed before the first):
 *   stop reached      stop_reached[stop] = 1
 *   cut / release     the pick's progress becomes CUT / RELEASE, unless it has an outcome
 *   outcome           the pick is DONE with its outcome and reason
 *   row done          row_done = 1
 *   e-stop clear      estop_clears + 1
 * HV_OK; HV_ERR_EXEC_JOURNAL_UNKNOWN for a pick the plan does not have;
 * HV_ERR_EXEC_JOURNAL_FORMAT for a stop outside the plan, an outcome or reason out of
 * range, a second outcome for one pick, or an e-stop clear of no node or an unknown one;
 * HV_ERR_ARG when `record` is not a journal record. */
hv_status_t hv_exec_progress_apply(hv_exec_progress_t *progress, const hv_exec_plan_t *plan,
                                   const hv_exec_action_t *record);

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_PROGRESS_H */
