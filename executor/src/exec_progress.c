/* Journal records -> progress (see hv/exec_progress.h). */
#include "hv/exec_progress.h"

#include "hv/exec_status.h"

static int pick_in_plan(const hv_exec_plan_t *plan, int pick)
{
    return pick >= 0 && pick < (int)plan->n_picks;
}

hv_status_t hv_exec_progress_apply(hv_exec_progress_t *progress, const hv_exec_plan_t *plan,
                                   const hv_exec_action_t *record)
{
    if (!progress || !plan || !record || record->kind != HV_ACT_JOURNAL)
        return HV_ERR_ARG;
    int pick = record->u.jr.pick;
    switch (record->u.jr.kind) {
    case HV_JR_STOP: {
        int stop = record->u.jr.stop;
        if (stop < 0 || stop >= (int)plan->n_stops)
            return HV_ERR_EXEC_JOURNAL_FORMAT;
        progress->stop_reached[stop] = 1;
        return HV_OK;
    }
    case HV_JR_CUT:
    case HV_JR_RELEASE:
        if (!pick_in_plan(plan, pick))
            return HV_ERR_EXEC_JOURNAL_UNKNOWN;
        /* a cut or release announced again after the outcome (a retry's record) changes
         * nothing: the outcome stands */
        if (progress->pick[pick] != HV_PROG_DONE)
            progress->pick[pick] =
                (uint8_t)(record->u.jr.kind == HV_JR_CUT ? HV_PROG_CUT : HV_PROG_RELEASE);
        return HV_OK;
    case HV_JR_OUTCOME: {
        int outcome = record->u.jr.outcome, reason = record->u.jr.reason;
        if (!pick_in_plan(plan, pick))
            return HV_ERR_EXEC_JOURNAL_UNKNOWN;
        if (outcome < 0 || outcome >= HV_OUT_COUNT || reason < 0 || reason >= HV_RSN_COUNT ||
            progress->pick[pick] == HV_PROG_DONE)
            return HV_ERR_EXEC_JOURNAL_FORMAT;
        progress->pick[pick] = HV_PROG_DONE;
        progress->outcome[pick] = (uint8_t)outcome;
        progress->reason[pick] = (uint8_t)reason;
        return HV_OK;
    }
    case HV_JR_DONE: progress->row_done = 1; return HV_OK;
    case HV_JR_HALT: /* the run stopped under control: nothing to undo, the next resumes */
        return record->u.jr.reason > HV_STOP_NONE && record->u.jr.reason < HV_STOP_COUNT
                   ? HV_OK
                   : HV_ERR_EXEC_JOURNAL_FORMAT;
    case HV_JR_ESTOP_CLEAR:
        if (record->u.jr.nodes == 0 || (record->u.jr.nodes & ~HV_EXEC_ALL_NODES) != 0)
            return HV_ERR_EXEC_JOURNAL_FORMAT;
        progress->estop_clears++;
        return HV_OK;
    default: return HV_ERR_EXEC_JOURNAL_FORMAT;
    }
}
