/* Names of the firmware's status codes (fw_status.h). */
#include "fw_status.h"

#include "hv/exec_status.h"

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
    case HV_ERR_FW_UPLOAD_ORDER: return "HV_ERR_FW_UPLOAD_ORDER";
    case HV_ERR_FW_UPLOAD_LENGTH: return "HV_ERR_FW_UPLOAD_LENGTH";
    case HV_ERR_FW_UPLOAD_FORMAT: return "HV_ERR_FW_UPLOAD_FORMAT";
    case HV_ERR_FW_UPLOAD_CRC: return "HV_ERR_FW_UPLOAD_CRC";
    case HV_ERR_FW_UPLOAD_BUSY: return "HV_ERR_FW_UPLOAD_BUSY";
    case HV_ERR_FW_UPLOAD_TRUNCATED: return "HV_ERR_FW_UPLOAD_TRUNCATED";
    case HV_ERR_FW_JOURNAL_IO: return "HV_ERR_FW_JOURNAL_IO";
    case HV_ERR_FW_JOURNAL_PLAN: return "HV_ERR_FW_JOURNAL_PLAN";
    case HV_ERR_FW_JOURNAL_CORRUPT: return "HV_ERR_FW_JOURNAL_CORRUPT";
    case HV_ERR_FW_JOURNAL_FORMAT: return "HV_ERR_FW_JOURNAL_FORMAT";
    default: return hv_exec_status_name(status); /* the executor's, then core's */
    }
}
