/* Status codes of the executor (the range -200..-299 reserved by core/include/hv/status.h).
 *
 * Kept here, not in status.h, so the executor can add codes without touching core.
 * hv_exec_status_name() names these and falls back to hv_status_name() for the rest.
 */
#ifndef HV_EXEC_STATUS_H
#define HV_EXEC_STATUS_H

#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* macros with a cast: hv_status_t is core's enum, these extend its value range */
#define HV_ERR_EXEC_PLAN_SYNTAX ((hv_status_t)(-200)) /* plan file is not well-formed JSON */
#define HV_ERR_EXEC_PLAN_FIELD                                                                     \
    ((hv_status_t)(-201)) /* a required field is missing or has the wrong type */
#define HV_ERR_EXEC_PLAN_RANGE                                                                     \
    ((hv_status_t)(-202)) /* a field's value is outside its allowed range */
#define HV_ERR_EXEC_PLAN_CAPACITY                                                                  \
    ((hv_status_t)(-203)) /* more stops or picks than the static tables hold */
#define HV_ERR_EXEC_PLAN_ID                                                                        \
    ((hv_status_t)(-204)) /* a fruit id outside the id set (hv/fruit_id.h) */
#define HV_ERR_EXEC_PLAN_ORDER ((hv_status_t)(-205)) /* stops not by pass, then increasing y_m */
#define HV_ERR_EXEC_PLAN_CONFLICT                                                                  \
    ((hv_status_t)(-206)) /* online: committed stops that contradict those already in the plan (journalled) */
#define HV_ERR_EXEC_JOURNAL_IO                                                                     \
    ((hv_status_t)(-210)) /* journal could not be opened, written or synced */
#define HV_ERR_EXEC_JOURNAL_FORMAT ((hv_status_t)(-211)) /* a complete journal line is corrupt */
#define HV_ERR_EXEC_JOURNAL_PLAN   ((hv_status_t)(-212)) /* the journal belongs to another plan */
#define HV_ERR_EXEC_JOURNAL_UNKNOWN                                                                \
    ((hv_status_t)(-213)) /* the journal names a fruit the plan does not have */
#define HV_ERR_EXEC_JOURNAL_ID                                                                     \
    ((hv_status_t)(-214)) /* a record would carry a fruit id it could not read back */
#define HV_ERR_EXEC_ACTIONS_FULL                                                                   \
    ((hv_status_t)(-220)) /* a step produced more actions than the buffer holds */
#define HV_ERR_EXEC_EVENT     ((hv_status_t)(-221)) /* an event with a field outside its domain */
#define HV_ERR_EXEC_PARAMS    ((hv_status_t)(-222)) /* executor parameters out of range */
#define HV_ERR_EXEC_TELEMETRY ((hv_status_t)(-230)) /* the telemetry sink could not be opened */
#define HV_ERR_EXEC_CAN_FRAME ((hv_status_t)(-240)) /* a CAN frame could not be packed */

/* Name of an executor code ("HV_ERR_EXEC_PLAN_FIELD") or of any other hv_status_t. */
const char *hv_exec_status_name(int status);

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_STATUS_H */
