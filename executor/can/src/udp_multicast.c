/* CAN over UDP multicast, wire-compatible with python-can's udp_multicast interface
 * (hv_can_udp_open). Two sockets: one bound to the group port that receives (shared
 * with every python-can process via SO_REUSEADDR/SO_REUSEPORT, as python-can does), and
 * one with an ephemeral port that sends, so our own looped-back datagrams are recognised
 * by their source address and dropped, like a SocketCAN socket that does not see its
 * own frames. */
#define _GNU_SOURCE /* SO_REUSEPORT, ip_mreq under -std=c99 */
#include "hv/can_bus.h"
#include "hv/can_udp_wire.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include <msgpack.h>

#include "can_wait.h"

/* The msgpack zone lives in bus->impl so the bus stays caller-allocated. */
typedef char hv_can_zone_fits[(sizeof(msgpack_zone) <= sizeof(((hv_can_bus_t *)0)->impl)) ? 1 : -1];

static msgpack_zone *bus_zone(hv_can_bus_t *bus)
{
    return (msgpack_zone *)(void *)bus->impl;
}

static hv_status_t udp_send(hv_can_bus_t *bus, const hv_can_frame_t *frame, int timeout_ms)
{
    uint8_t buf[HV_CAN_UDP_MAX_DATAGRAM];
    size_t len = 0;
    double now_s = (double)hv_can_realtime_ns() * 1e-9;
    hv_status_t st = hv_can_udp_wire_encode(frame, now_s, buf, sizeof buf, &len);
    if (st != HV_OK)
        return st;
    struct sockaddr_in to;
    memset(&to, 0, sizeof to);
    to.sin_family = AF_INET;
    to.sin_addr.s_addr = bus->group_be;
    to.sin_port = htons(bus->port);
    int64_t deadline = hv_can_deadline(timeout_ms);
    for (;;) {
        ssize_t n = sendto(bus->tx_fd, buf, len, 0, (struct sockaddr *)&to, sizeof to);
        if (n == (ssize_t)len)
            return HV_OK;
        int e = n < 0 ? errno : EIO;
        if (e == EINTR)
            continue;
        st = hv_can_send_backoff(bus, e, deadline);
        if (st != HV_OK)
            return st;
    }
}

/* One waiting datagram: HV_OK with a frame for the caller, HV_CAN_ERR_TIMEOUT when
 * nothing is queued, HV_CAN_ERR_DECODE when it was dropped (own, malformed, filtered). */
static hv_status_t udp_read_one(hv_can_bus_t *bus, hv_can_frame_t *frame)
{
    struct sockaddr_in from;
    socklen_t from_len = sizeof from;
    ssize_t n = recvfrom(bus->rx_fd, bus->rx_buf, sizeof bus->rx_buf, MSG_TRUNC,
                         (struct sockaddr *)&from, &from_len);
    if (n < 0) {
        if (errno == EAGAIN || errno == EWOULDBLOCK)
            return (hv_status_t)HV_CAN_ERR_TIMEOUT;
        bus->last_errno = errno;
        return errno == EINTR ? (hv_status_t)HV_CAN_ERR_INTERRUPTED : (hv_status_t)HV_CAN_ERR_RECV;
    }
    int64_t stamp_ns = hv_can_realtime_ns();
    if (from.sin_port == bus->tx_port_be && from.sin_addr.s_addr == bus->tx_addr_be)
        return (hv_status_t)HV_CAN_ERR_DECODE; /* our own frame, looped back */
    if ((size_t)n > sizeof bus->rx_buf) {
        bus->stats.rx_malformed++; /* MSG_TRUNC: longer than any python-can frame */
        return (hv_status_t)HV_CAN_ERR_DECODE;
    }
    hv_status_t st = hv_can_udp_wire_decode(bus->rx_buf, (size_t)n, bus_zone(bus), frame);
    if (st == (hv_status_t)HV_CAN_ERR_UNSUPPORTED) {
        bus->stats.rx_unsupported++;
        return (hv_status_t)HV_CAN_ERR_DECODE;
    }
    if (st != HV_OK) {
        bus->stats.rx_malformed++;
        return (hv_status_t)HV_CAN_ERR_DECODE;
    }
    /* python-can replaces the sender's timestamp by the receive time; so do we */
    frame->timestamp_ns = stamp_ns;
    if (frame->flags & HV_CAN_FLAG_ERR) {
        bus->stats.rx_error_frames++; /* error frames bypass filters, as in SocketCAN */
    } else if (!hv_can_filter_match(bus->filters, bus->n_filters, frame)) {
        bus->stats.rx_filtered++;
        return (hv_status_t)HV_CAN_ERR_DECODE;
    }
    bus->stats.rx_frames++;
    return HV_OK;
}

static hv_status_t udp_recv(hv_can_bus_t *bus, hv_can_frame_t *frame, int timeout_ms)
{
    int64_t deadline = hv_can_deadline(timeout_ms);
    for (;;) {
        hv_status_t st = udp_read_one(bus, frame);
        if (st == (hv_status_t)HV_CAN_ERR_DECODE)
            continue; /* dropped one; the queue may hold more */
        if (st != (hv_status_t)HV_CAN_ERR_TIMEOUT)
            return st;
        st = hv_can_wait_readable(bus, deadline);
        if (st != HV_OK)
            return st;
    }
}

static void udp_close(hv_can_bus_t *bus)
{
    if (bus->rx_fd >= 0)
        close(bus->rx_fd);
    if (bus->tx_fd >= 0)
        close(bus->tx_fd);
    msgpack_zone_destroy(bus_zone(bus));
}

static const hv_can_ops_t udp_ops = {"udp", udp_send, udp_recv, udp_close};

static int set_nonblocking(int fd)
{
    int flags = fcntl(fd, F_GETFL, 0);
    return (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) ? -1 : 0;
}

/* Receiving socket: bound to group:port, member of the group on the interface. */
static int open_rx(uint32_t group_be, uint16_t port, uint32_t if_be)
{
    int fd = socket(AF_INET, SOCK_DGRAM, 0);
    if (fd < 0)
        return -1;
    int one = 1;
    int rcvbuf = 4 << 20; /* bursts of frames; the kernel caps it at rmem_max */
    struct sockaddr_in addr;
    memset(&addr, 0, sizeof addr);
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = group_be; /* only datagrams to the group, not unicast to port */
    addr.sin_port = htons(port);
    struct ip_mreq mreq;
    mreq.imr_multiaddr.s_addr = group_be;
    mreq.imr_interface.s_addr = if_be;
    if (setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) < 0 ||
        setsockopt(fd, SOL_SOCKET, SO_REUSEPORT, &one, sizeof one) < 0 ||
        setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf) < 0 ||
        bind(fd, (struct sockaddr *)&addr, sizeof addr) < 0 ||
        setsockopt(fd, IPPROTO_IP, IP_ADD_MEMBERSHIP, &mreq, sizeof mreq) < 0 ||
        set_nonblocking(fd) < 0) {
        int e = errno;
        close(fd);
        errno = e;
        return -1;
    }
    return fd;
}

/* Sending socket: TTL 0 (never routed off the host), loopback on, out via if_be,
 * bound to an ephemeral port whose address we remember to recognise our own frames. */
static int open_tx(uint32_t if_be, uint32_t *src_addr_be, uint16_t *src_port_be)
{
    int fd = socket(AF_INET, SOCK_DGRAM, 0);
    if (fd < 0)
        return -1;
    unsigned char ttl = 0, loop = 1;
    struct in_addr ifa;
    ifa.s_addr = if_be;
    struct sockaddr_in addr;
    memset(&addr, 0, sizeof addr);
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = if_be;
    addr.sin_port = 0;
    socklen_t len = sizeof addr;
    if (setsockopt(fd, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl) < 0 ||
        setsockopt(fd, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop) < 0 ||
        setsockopt(fd, IPPROTO_IP, IP_MULTICAST_IF, &ifa, sizeof ifa) < 0 ||
        bind(fd, (struct sockaddr *)&addr, sizeof addr) < 0 ||
        getsockname(fd, (struct sockaddr *)&addr, &len) < 0 || set_nonblocking(fd) < 0) {
        int e = errno;
        close(fd);
        errno = e;
        return -1;
    }
    *src_addr_be = addr.sin_addr.s_addr;
    *src_port_be = addr.sin_port;
    return fd;
}

hv_status_t hv_can_udp_open(hv_can_bus_t *bus, const char *group, uint16_t port,
                            const char *if_addr, const hv_can_filter_t *filters, size_t n_filters)
{
    if (!bus)
        return HV_ERR_ARG;
    memset(bus, 0, sizeof *bus);
    bus->rx_fd = bus->tx_fd = -1;
    if (n_filters && !filters)
        return HV_ERR_ARG;
    if (n_filters > HV_CAN_MAX_FILTERS)
        return (hv_status_t)HV_CAN_ERR_FILTERS;
    if (!group)
        group = HV_CAN_UDP_DEFAULT_GROUP;
    if (!if_addr)
        if_addr = "127.0.0.1";
    if (port == 0)
        port = HV_CAN_UDP_DEFAULT_PORT;
    struct in_addr g, ifa;
    if (inet_pton(AF_INET, group, &g) != 1 || !IN_MULTICAST(ntohl(g.s_addr)) ||
        inet_pton(AF_INET, if_addr, &ifa) != 1)
        return (hv_status_t)HV_CAN_ERR_ADDRESS;

    if (!msgpack_zone_init(bus_zone(bus), 2048))
        return HV_ERR_NOMEM;
    bus->rx_fd = open_rx(g.s_addr, port, ifa.s_addr);
    if (bus->rx_fd >= 0)
        bus->tx_fd = open_tx(ifa.s_addr, &bus->tx_addr_be, &bus->tx_port_be);
    if (bus->rx_fd < 0 || bus->tx_fd < 0) {
        bus->last_errno = errno;
        udp_close(bus);
        bus->rx_fd = bus->tx_fd = -1;
        return (hv_status_t)HV_CAN_ERR_SOCKET;
    }
    bus->group_be = g.s_addr;
    bus->port = port;
    if (n_filters)
        memcpy(bus->filters, filters, n_filters * sizeof *filters);
    bus->n_filters = n_filters;
    snprintf(bus->name, sizeof bus->name, "udp:%s:%u", group, (unsigned)port);
    bus->ops = &udp_ops;
    return HV_OK;
}
