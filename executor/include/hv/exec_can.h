/* CAN frames <-> state machine events and actions, through the DBC's generated
 * pack/unpack (executor/can). Pure functions: no I/O. */
#ifndef HV_EXEC_CAN_H
#define HV_EXEC_CAN_H

#include <stdint.h>

#include "hv/can_bus.h"
#include "hv/exec_sm.h"
#include "hv/exec_telemetry.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum hv_exec_rx_kind {
    HV_RX_NONE = 0,   /* not for the executor (our own frames, other ids) */
    HV_RX_EVENT,      /* *ev filled */
    HV_RX_JOINTS,     /* sample of arm `side` updated: positions (JointState) */
    HV_RX_VELOCITIES, /* sample updated: velocities (JointVelocity) */
    HV_RX_MALFORMED   /* an id of the DBC with a length other than the DBC's */
} hv_exec_rx_kind_t;

/* Decode a received frame. `samples` (2, by side) receive joint state / velocity; then
 * ev->node holds the side (the rest of *ev is not meaningful). */
hv_exec_rx_kind_t hv_exec_can_decode(const hv_can_frame_t *f, hv_exec_event_t *ev,
                                     hv_exec_arm_sample_t samples[2]);

/* Rolling counters of our periodic frames. */
typedef struct hv_exec_can_tx {
    uint8_t hb_counter, estop_counter;
} hv_exec_can_tx_t;

/* Encode an action as a frame. *has_frame = 0 for actions that are not CAN (journal,
 * telemetry). HV_ERR_EXEC_CAN_FRAME when a value does not fit its signal. */
hv_status_t hv_exec_can_encode(const hv_exec_action_t *a, hv_exec_can_tx_t *tx, hv_can_frame_t *f,
                               int *has_frame);

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_CAN_H */
