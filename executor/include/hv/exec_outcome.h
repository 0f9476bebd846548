/* What happened to each fruit: outcomes, reasons, and the per-pick progress the journal
 * replays into the state machine on a restart. */
#ifndef HV_EXEC_OUTCOME_H
#define HV_EXEC_OUTCOME_H

#include <stdint.h>

#include "hv/exec_plan.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum hv_exec_outcome {
    HV_OUT_PICKED = 0,
    HV_OUT_FAILED = 1,  /* tried and given up (fault, timeout, cut failure) */
    HV_OUT_SKIPPED = 2, /* not tried or refused (unreachable, setpoint rejected) */
    HV_OUT_COUNT
} hv_exec_outcome_t;

typedef enum hv_exec_reason {
    HV_RSN_OK = 0,
    HV_RSN_RESUMED,        /* picked: cut before a restart, released after it */
    HV_RSN_IK_UNREACHABLE, /* the IK has no solution within the joint limits */
    HV_RSN_REJECTED,       /* the arm rejected the setpoint on every attempt */
    HV_RSN_JOINT_FAULT,    /* joint limit / following error on every attempt */
    HV_RSN_EE_FAULT,       /* end-effector fault on every attempt */
    HV_RSN_TIMEOUT,        /* a motion or end-effector action did not finish in time */
    HV_RSN_CUT_FAILED,     /* the end effector reported the cut failed on every attempt */
    HV_RSN_DROPPED,        /* cut confirmed, fruit no longer held: never cut twice */
    HV_RSN_COUNT
} hv_exec_reason_t;

/* Why a run made a controlled stop (journalled "H <name>"; the run is resumable). */
typedef enum hv_exec_stop_reason {
    HV_STOP_NONE = 0,
    HV_STOP_OPERATOR,     /* SIGTERM / SIGINT, or the bus's ExecutorStopRequest */
    HV_STOP_PLAN_TIMEOUT, /* online: no stop from the planner within wait_plan_timeout_s */
    HV_STOP_COUNT
} hv_exec_stop_reason_t;

/* Progress of one pick, as known from the journal and the running state machine. */
typedef enum hv_exec_pick_progress {
    HV_PROG_PENDING = 0, /* nothing recorded */
    HV_PROG_CUT,         /* "cut issued" recorded, no outcome yet */
    HV_PROG_RELEASE,     /* "release issued" recorded, no outcome yet */
    HV_PROG_DONE         /* an outcome is recorded */
} hv_exec_pick_progress_t;

typedef struct hv_exec_progress {
    uint8_t pick[HV_EXEC_MAX_PICKS];    /* hv_exec_pick_progress_t */
    uint8_t outcome[HV_EXEC_MAX_PICKS]; /* hv_exec_outcome_t when DONE */
    uint8_t reason[HV_EXEC_MAX_PICKS];  /* hv_exec_reason_t when DONE */
    uint8_t stop_reached[HV_EXEC_MAX_STOPS];
    int row_done;
    unsigned estop_clears; /* operator e-stop clears journalled (E records) */
} hv_exec_progress_t;

const char *hv_exec_outcome_name(int outcome); /* "picked", "failed", "skipped" */
const char *hv_exec_reason_name(int reason);   /* "ok", "ik_unreachable", ... */
/* Parse the names back; -1 when unknown. */
int hv_exec_outcome_parse(const char *name);
int hv_exec_reason_parse(const char *name);
const char *hv_exec_stop_reason_name(int reason); /* "none", "operator", "plan_timeout" */
int hv_exec_stop_reason_parse(const char *name);  /* -1 when unknown */

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_OUTCOME_H */
