/* Status codes of the firmware (the range -400..-499; core/include/hv/status.h lists the
 * ranges). Like the executor's, macros with a cast so core's enum stays untouched. */
#ifndef HV_FW_STATUS_H
#define HV_FW_STATUS_H

#include "hv/status.h"

#define HV_ERR_FW_UART_OVERRUN                                                                     \
    ((hv_status_t)(-400)) /* a received byte was lost (UART RX overrun) */
#define HV_ERR_SLCAN_LINE_LONG ((hv_status_t)(-410)) /* a line longer than any SLCAN command */
#define HV_ERR_SLCAN_HEX       ((hv_status_t)(-411)) /* a character that is not a hex digit */
#define HV_ERR_SLCAN_LENGTH    ((hv_status_t)(-412)) /* DLC > 8, or data not 2 x DLC digits */
#define HV_ERR_SLCAN_COMMAND   ((hv_status_t)(-413)) /* a command letter SLCAN does not have */
#define HV_ERR_SLCAN_CLOSED    ((hv_status_t)(-414)) /* a frame to send before the channel opened */
#define HV_ERR_FW_UPLOAD_ORDER                                                                     \
    ((hv_status_t)(-420)) /* plan data not at the offset reached (lost frame) */
#define HV_ERR_FW_UPLOAD_LENGTH ((hv_status_t)(-421)) /* more or fewer bytes than announced */
#define HV_ERR_FW_UPLOAD_FORMAT ((hv_status_t)(-422)) /* a record of the plan image out of range */
#define HV_ERR_FW_UPLOAD_CRC    ((hv_status_t)(-423)) /* the image's CRC-32 does not match */
#define HV_ERR_FW_UPLOAD_BUSY   ((hv_status_t)(-424)) /* an upload while a plan runs */
#define HV_ERR_FW_UPLOAD_TRUNCATED                                                                 \
    ((hv_status_t)(-425)) /* a new upload began before this one ended */
#define HV_ERR_FW_JOURNAL_IO                                                                       \
    ((hv_status_t)(-430)) /* the journal's storage failed to open, read or write */
#define HV_ERR_FW_JOURNAL_PLAN ((hv_status_t)(-431)) /* the journal belongs to another plan */
#define HV_ERR_FW_JOURNAL_CORRUPT                                                                  \
    ((hv_status_t)(-432)) /* a record before the last fails its CRC (damage, not a torn write) */
#define HV_ERR_FW_JOURNAL_FORMAT                                                                   \
    ((hv_status_t)(-433)) /* a record with a good CRC that the plan cannot have */

/* "HV_ERR_SLCAN_HEX" etc., or hv_exec_status_name() for the other codes (the executor's,
 * such as HV_ERR_EXEC_PARAMS for a plan refused for its parameters, then core's). */
const char *hv_fw_status_name(int status);

#endif /* HV_FW_STATUS_H */
