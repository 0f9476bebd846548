/* Raw SocketCAN transport (hv_can_socketcan_open): the deployment path on can0/vcan0. */
#define _GNU_SOURCE /* struct ifreq, SO_RXQ_OVFL, SO_TIMESTAMPNS under -std=c99 */
#include "hv/can_bus.h"

#include <errno.h>
#include <fcntl.h>
#include <net/if.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <unistd.h>

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>

#include "can_wait.h"

static hv_status_t sc_send(hv_can_bus_t *bus, const hv_can_frame_t *frame, int timeout_ms)
{
    struct can_frame cf;
    memset(&cf, 0, sizeof cf);
    cf.can_id = frame->id;
    if (frame->flags & HV_CAN_FLAG_EXT)
        cf.can_id |= CAN_EFF_FLAG;
    if (frame->flags & HV_CAN_FLAG_RTR)
        cf.can_id |= CAN_RTR_FLAG;
    if (frame->flags & HV_CAN_FLAG_ERR)
        cf.can_id |= CAN_ERR_FLAG;
    cf.can_dlc = frame->dlc;
    memcpy(cf.data, frame->data, frame->dlc);

    int64_t deadline = hv_can_deadline(timeout_ms);
    for (;;) {
        ssize_t n = write(bus->tx_fd, &cf, sizeof cf);
        if (n == (ssize_t)sizeof cf)
            return HV_OK;
        if (n >= 0) { /* a raw CAN socket writes whole frames or nothing */
            bus->last_errno = EIO;
            return (hv_status_t)HV_CAN_ERR_SEND;
        }
        int e = errno;
        if (e == EINTR)
            continue;
        hv_status_t st = hv_can_send_backoff(bus, e, deadline);
        if (st != HV_OK)
            return st;
    }
}

/* Reads one frame that is known to be waiting (or returns TIMEOUT on EAGAIN). */
static hv_status_t sc_read_one(hv_can_bus_t *bus, hv_can_frame_t *frame)
{
    struct can_frame cf;
    struct iovec iov = {&cf, sizeof cf};
    union {
        char buf[CMSG_SPACE(sizeof(struct timespec)) + CMSG_SPACE(sizeof(uint32_t))];
        struct cmsghdr align;
    } ctrl;
    struct msghdr msg;
    memset(&msg, 0, sizeof msg);
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = ctrl.buf;
    msg.msg_controllen = sizeof ctrl.buf;
    ssize_t n = recvmsg(bus->rx_fd, &msg, 0);
    if (n < 0) {
        if (errno == EAGAIN || errno == EWOULDBLOCK)
            return (hv_status_t)HV_CAN_ERR_TIMEOUT;
        bus->last_errno = errno;
        return errno == EINTR ? (hv_status_t)HV_CAN_ERR_INTERRUPTED : (hv_status_t)HV_CAN_ERR_RECV;
    }
    int64_t stamp_ns = 0;
    for (struct cmsghdr *c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c)) {
        if (c->cmsg_level != SOL_SOCKET)
            continue;
        if (c->cmsg_type == SO_TIMESTAMPNS) {
            struct timespec ts;
            memcpy(&ts, CMSG_DATA(c), sizeof ts);
            stamp_ns = (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
        } else if (c->cmsg_type == SO_RXQ_OVFL) {
            uint32_t drops;
            memcpy(&drops, CMSG_DATA(c), sizeof drops);
            bus->stats.rx_kernel_drops = drops; /* the kernel's running total */
        }
    }
    if (n != (ssize_t)sizeof cf || cf.can_dlc > HV_CAN_MAX_DLC) {
        bus->stats.rx_malformed++; /* CAN FD frames are never enabled on this socket */
        return (hv_status_t)HV_CAN_ERR_DECODE;
    }
    memset(frame, 0, sizeof *frame);
    frame->timestamp_ns = stamp_ns ? stamp_ns : hv_can_realtime_ns();
    frame->dlc = cf.can_dlc;
    if (cf.can_id & CAN_ERR_FLAG) {
        frame->flags = HV_CAN_FLAG_ERR;
        frame->id = cf.can_id & CAN_ERR_MASK;
        bus->stats.rx_error_frames++;
    } else if (cf.can_id & CAN_EFF_FLAG) {
        frame->flags = HV_CAN_FLAG_EXT;
        frame->id = cf.can_id & CAN_EFF_MASK;
    } else {
        frame->id = cf.can_id & CAN_SFF_MASK;
    }
    if (cf.can_id & CAN_RTR_FLAG)
        frame->flags |= HV_CAN_FLAG_RTR;
    memcpy(frame->data, cf.data, cf.can_dlc);
    bus->stats.rx_frames++;
    return HV_OK;
}

static hv_status_t sc_recv(hv_can_bus_t *bus, hv_can_frame_t *frame, int timeout_ms)
{
    int64_t deadline = hv_can_deadline(timeout_ms);
    for (;;) {
        hv_status_t st = sc_read_one(bus, frame);
        if (st != (hv_status_t)HV_CAN_ERR_TIMEOUT && st != (hv_status_t)HV_CAN_ERR_DECODE)
            return st;
        st = hv_can_wait_readable(bus, deadline);
        if (st != HV_OK)
            return st;
    }
}

static void sc_close(hv_can_bus_t *bus)
{
    if (bus->rx_fd >= 0)
        close(bus->rx_fd);
}

static const hv_can_ops_t socketcan_ops = {"socketcan", sc_send, sc_recv, sc_close};

/* Socket options of a raw CAN socket; on failure the errno is kept and -1 returned. */
static int sc_configure(int fd, const hv_can_filter_t *filters, size_t n)
{
    if (n > 0) {
        struct can_filter kf[HV_CAN_MAX_FILTERS];
        for (size_t i = 0; i < n; i++) {
            /* the EFF bit in the mask makes a filter match only its own id width */
            kf[i].can_id = filters[i].id | (filters[i].ext ? CAN_EFF_FLAG : 0u);
            kf[i].can_mask = filters[i].mask | CAN_EFF_FLAG;
        }
        if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, kf, (socklen_t)(n * sizeof kf[0])) < 0)
            return -1;
    }
    can_err_mask_t err_mask = CAN_ERR_MASK;
    int one = 1;
    if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) < 0 ||
        setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &one, sizeof one) < 0 ||
        setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one) < 0)
        return -1;
    int flags = fcntl(fd, F_GETFL, 0);
    if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0)
        return -1;
    return 0;
}

hv_status_t hv_can_socketcan_open(hv_can_bus_t *bus, const char *ifname,
                                  const hv_can_filter_t *filters, size_t n_filters)
{
    if (!bus)
        return HV_ERR_ARG;
    memset(bus, 0, sizeof *bus);
    bus->rx_fd = bus->tx_fd = -1;
    if (!ifname || !*ifname || strlen(ifname) >= IFNAMSIZ || (n_filters && !filters))
        return HV_ERR_ARG;
    if (n_filters > HV_CAN_MAX_FILTERS)
        return (hv_status_t)HV_CAN_ERR_FILTERS;

    int fd = socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (fd < 0) {
        bus->last_errno = errno;
        return (errno == EAFNOSUPPORT || errno == EPROTONOSUPPORT)
                   ? (hv_status_t)HV_CAN_ERR_UNSUPPORTED
                   : (hv_status_t)HV_CAN_ERR_SOCKET;
    }
    unsigned idx = if_nametoindex(ifname);
    if (idx == 0) {
        bus->last_errno = errno;
        close(fd);
        return (hv_status_t)HV_CAN_ERR_NO_DEVICE;
    }
    struct sockaddr_can addr;
    memset(&addr, 0, sizeof addr);
    addr.can_family = AF_CAN;
    addr.can_ifindex = (int)idx;
    if (sc_configure(fd, filters, n_filters) < 0 ||
        bind(fd, (struct sockaddr *)&addr, sizeof addr) < 0) {
        bus->last_errno = errno;
        close(fd);
        return (hv_status_t)HV_CAN_ERR_SOCKET;
    }
    bus->rx_fd = bus->tx_fd = fd;
    if (n_filters)
        memcpy(bus->filters, filters, n_filters * sizeof *filters);
    bus->n_filters = n_filters;
    snprintf(bus->name, sizeof bus->name, "socketcan:%s", ifname);
    bus->ops = &socketcan_ops;
    return HV_OK;
}
