/* The plan upload on the bus (DBC ExecutorPlanBegin / ExecutorPlanData, answered by
 * ExecutorPlanStatus): frames in, the plan image decoded into the firmware's plan and
 * parameters (plan_image.h), a status frame out. */
#ifndef HV_FW_UPLOAD_H
#define HV_FW_UPLOAD_H

#include "hv/can_bus.h"
#include "hv/can_enums.h"
#include "plan_image.h"

/* ExecutorPlanStatus.State: the DBC's value table (hv/can_enums.h, generated) */
typedef enum hv_fw_upload_state {
    HV_UPLOAD_IDLE = HV_CAN_PLAN_STATE_IDLE,
    HV_UPLOAD_RECEIVING = HV_CAN_PLAN_STATE_RECEIVING,
    HV_UPLOAD_ACCEPTED = HV_CAN_PLAN_STATE_ACCEPTED,
    HV_UPLOAD_REFUSED = HV_CAN_PLAN_STATE_REFUSED,
    HV_UPLOAD_RUNNING = HV_CAN_PLAN_STATE_RUNNING
} hv_fw_upload_state_t;

typedef struct hv_fw_upload {
    hv_fw_image_reader_t rd;
    hv_fw_upload_state_t state;
    hv_status_t error; /* of the last upload that failed, HV_OK otherwise */
} hv_fw_upload_t;

/* Take a frame. Returns 0 when it is not an upload frame, 1 when it was taken; *answer is
 * then set to 1 when the state or the error changed (send the status). A plan whose last
 * byte arrived with a good CRC leaves the state ACCEPTED: the caller starts it and sets
 * RUNNING (or REFUSED with its error). While RUNNING every upload frame is refused with
 * HV_ERR_FW_UPLOAD_BUSY and the plan in use is not touched. */
int hv_fw_upload_frame(hv_fw_upload_t *u, const hv_can_frame_t *f, hv_exec_plan_t *plan,
                       hv_exec_params_t *prm, int *answer);

/* The ExecutorPlanStatus frame of the current state. */
void hv_fw_upload_status(const hv_fw_upload_t *u, hv_can_frame_t *f);

#endif /* HV_FW_UPLOAD_H */
