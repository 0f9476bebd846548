/* Status codes of the plan contract library (plan/): reading and writing plan files.
 * Range -110 and -120..-129 (the planner's own codes surround them, planner/ plan_status.h).
 * Returned through hv_status_t (core/include/hv/status.h).
 */
#ifndef HV_PLAN_FILE_STATUS_H
#define HV_PLAN_FILE_STATUS_H

#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Macros of type hv_status_t, like every module's codes, so they return without casts. */
#define HV_ERR_PLAN_NOMEM ((hv_status_t)-110) /* malloc failed */
#define HV_ERR_PLAN_JSON  ((hv_status_t)-120) /* not well-formed JSON */
#define HV_ERR_PLAN_FORMAT                                                                         \
    ((hv_status_t)-121) /* JSON, but not the plan format (field missing/wrong) */
#define HV_ERR_PLAN_ID    ((hv_status_t)-122) /* a fruit id outside the id set (hv/fruit_id.h) */
#define HV_ERR_PLAN_ORDER ((hv_status_t)-123) /* stops not by pass, then increasing y_m */

/* Name of a plan-file code ("HV_ERR_PLAN_JSON"), or of a core code. Never NULL. */
const char *hv_plan_file_status_name(int status);

#ifdef __cplusplus
}
#endif
#endif /* HV_PLAN_FILE_STATUS_H */
