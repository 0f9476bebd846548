/* Names of the firmware's status codes (fw_status.h). */
#include "fw_status.h"

/* the codes below -34 are cast to hv_status_t: it must hold them (status.h) */
typedef char hv_fw_status_holds_int[sizeof(hv_status_t) == sizeof(int) ? 1 : -1];

const char *hv_fw_status_name(int status)
{
    switch (status) {
    case HV_ERR_FW_UART_OVERRUN: return "HV_ERR_FW_UART_OVERRUN";
    case HV_ERR_SLCAN_LINE_LONG: return "HV_ERR_SLCAN_LINE_LONG";
    case HV_ERR_SLCAN_HEX: return "HV_ERR_SLCAN_HEX";
    case HV_ERR_SLCAN_LENGTH: return "HV_ERR_SLCAN_LENGTH";
    case HV_ERR_SLCAN_COMMAND: return "HV_ERR_SLCAN_COMMAND";
    case HV_ERR_SLCAN_CLOSED: return "HV_ERR_SLCAN_CLOSED";
    default: return hv_status_name(status);
    }
}
