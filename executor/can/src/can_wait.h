/* Deadline helpers shared by the transports (internal). */
#ifndef HV_CAN_WAIT_H
#define HV_CAN_WAIT_H

#include <errno.h>
#include <poll.h>
#include <stdint.h>
#include <time.h>

#include "hv/can_bus.h"
#include "hv/can_status.h"

/* Monotonic now in ms. */
static inline int64_t hv_can_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* Wall-clock now in ns since the epoch (python-can's timestamps use the same clock). */
static inline int64_t hv_can_realtime_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

/* Absolute deadline for a timeout (negative timeout: none, returned as -1). */
static inline int64_t hv_can_deadline(int timeout_ms)
{
    return timeout_ms < 0 ? -1 : hv_can_now_ms() + timeout_ms;
}

/* poll() timeout left until `deadline` (-1: forever, 0: expired). */
static inline int hv_can_left_ms(int64_t deadline)
{
    if (deadline < 0)
        return -1;
    int64_t left = deadline - hv_can_now_ms();
    return left <= 0 ? 0 : (left > 1000000 ? 1000000 : (int)left);
}

/* After a send failed with errno `e` (EINTR already retried by the caller): wait until the
 * socket may take the frame, within `deadline`. HV_OK: try again; else the code to return. */
static inline hv_status_t hv_can_send_backoff(hv_can_bus_t *bus, int e, int64_t deadline)
{
    bus->last_errno = e;
    if (e != EAGAIN && e != EWOULDBLOCK && e != ENOBUFS)
        return (hv_status_t)HV_CAN_ERR_SEND;
    int left = hv_can_left_ms(deadline);
    if (left == 0)
        return (hv_status_t)HV_CAN_ERR_TX_FULL;
    /* ENOBUFS is the device queue, which poll() does not report: retry after 1 ms */
    struct pollfd p = {bus->tx_fd, POLLOUT, 0};
    int wait = (e == ENOBUFS && (left < 0 || left > 1)) ? 1 : left;
    if (poll(&p, 1, wait) < 0 && errno != EINTR) {
        bus->last_errno = errno;
        return (hv_status_t)HV_CAN_ERR_SEND;
    }
    return HV_OK;
}

/* Nothing to read: wait for input on the receive socket until `deadline`. HV_OK: read
 * again; else the code to return (TIMEOUT, INTERRUPTED or RECV). */
static inline hv_status_t hv_can_wait_readable(hv_can_bus_t *bus, int64_t deadline)
{
    int left = hv_can_left_ms(deadline);
    if (left == 0)
        return (hv_status_t)HV_CAN_ERR_TIMEOUT;
    struct pollfd p = {bus->rx_fd, POLLIN, 0};
    int r = poll(&p, 1, left);
    if (r < 0) {
        bus->last_errno = errno;
        return errno == EINTR ? (hv_status_t)HV_CAN_ERR_INTERRUPTED : (hv_status_t)HV_CAN_ERR_RECV;
    }
    return r == 0 ? (hv_status_t)HV_CAN_ERR_TIMEOUT : HV_OK;
}

#endif /* HV_CAN_WAIT_H */
