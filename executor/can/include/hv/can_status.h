/* Status codes of the CAN layer (protocol and transports): the -300..-399 range that
 * core/include/hv/status.h reserves for it. Functions of hv/can_bus.h return
 * hv_status_t holding HV_OK or one of these. */
#ifndef HV_CAN_STATUS_H
#define HV_CAN_STATUS_H

#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Macros of type hv_status_t (not a second enum), so they compare and switch against
 * hv_status_t values without enum-compare warnings. */
#define HV_CAN_ERR_TIMEOUT                                                                         \
    ((hv_status_t)(-300)) /* receive/send: nothing happened within timeout_ms */
#define HV_CAN_ERR_UNSUPPORTED                                                                     \
    ((hv_status_t)(-301)) /* kernel lacks AF_CAN (EAFNOSUPPORT) or the feature */
#define HV_CAN_ERR_NO_DEVICE                                                                       \
    ((hv_status_t)(-302)) /* no such network interface (e.g. vcan0 absent) */
#define HV_CAN_ERR_SOCKET                                                                          \
    ((hv_status_t)(-303)) /* socket/bind/setsockopt/join failed; see last_errno */
#define HV_CAN_ERR_SEND        ((hv_status_t)(-304)) /* the kernel refused the frame (not buffer-full) */
#define HV_CAN_ERR_TX_FULL     ((hv_status_t)(-305)) /* send queue still full when timeout_ms ran out */
#define HV_CAN_ERR_RECV        ((hv_status_t)(-306)) /* read/poll failed; see last_errno */
#define HV_CAN_ERR_FRAME       ((hv_status_t)(-307)) /* frame to send is invalid (dlc > 8, id too wide) */
#define HV_CAN_ERR_CLOSED      ((hv_status_t)(-308)) /* the bus is not open (never opened or closed) */
#define HV_CAN_ERR_ADDRESS     ((hv_status_t)(-309)) /* group/interface address bad or not multicast */
#define HV_CAN_ERR_FILTERS     ((hv_status_t)(-310)) /* more than HV_CAN_MAX_FILTERS filters */
#define HV_CAN_ERR_INTERRUPTED ((hv_status_t)(-311)) /* a signal interrupted the wait (EINTR) */
#define HV_CAN_ERR_DECODE                                                                          \
    ((hv_status_t)(-312)) /* protocol: frame id/length does not match the DBC */
#define HV_CAN_ERR_MALFORMED ((hv_status_t)(-313)) /* udp: datagram is not a python-can frame map */
#define HV_CAN_ERR_NOSPACE                                                                         \
    ((hv_status_t)(-314)) /* output buffer too small for the encoded datagram */

/* "HV_CAN_ERR_TIMEOUT" etc.; falls back to hv_status_name() for codes outside the
 * CAN range, so it may be used on any status. Never NULL. */
const char *hv_can_status_name(int status);

#ifdef __cplusplus
}
#endif
#endif /* HV_CAN_STATUS_H */
