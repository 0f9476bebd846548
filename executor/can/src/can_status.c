/* Names of the CAN layer's status codes (hv/can_status.h). */
#include "hv/can_status.h"

#include "hv/status.h"

const char *hv_can_status_name(int status)
{
    switch (status) {
    case HV_CAN_ERR_TIMEOUT: return "HV_CAN_ERR_TIMEOUT";
    case HV_CAN_ERR_UNSUPPORTED: return "HV_CAN_ERR_UNSUPPORTED";
    case HV_CAN_ERR_NO_DEVICE: return "HV_CAN_ERR_NO_DEVICE";
    case HV_CAN_ERR_SOCKET: return "HV_CAN_ERR_SOCKET";
    case HV_CAN_ERR_SEND: return "HV_CAN_ERR_SEND";
    case HV_CAN_ERR_TX_FULL: return "HV_CAN_ERR_TX_FULL";
    case HV_CAN_ERR_RECV: return "HV_CAN_ERR_RECV";
    case HV_CAN_ERR_FRAME: return "HV_CAN_ERR_FRAME";
    case HV_CAN_ERR_CLOSED: return "HV_CAN_ERR_CLOSED";
    case HV_CAN_ERR_ADDRESS: return "HV_CAN_ERR_ADDRESS";
    case HV_CAN_ERR_FILTERS: return "HV_CAN_ERR_FILTERS";
    case HV_CAN_ERR_INTERRUPTED: return "HV_CAN_ERR_INTERRUPTED";
    case HV_CAN_ERR_DECODE: return "HV_CAN_ERR_DECODE";
    case HV_CAN_ERR_MALFORMED: return "HV_CAN_ERR_MALFORMED";
    case HV_CAN_ERR_NOSPACE: return "HV_CAN_ERR_NOSPACE";
    default: return hv_status_name(status);
    }
}
