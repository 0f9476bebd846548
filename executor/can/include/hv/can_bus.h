/* One small C interface to a CAN bus, two transports behind it (DESIGN §6):
 *   socketcan  raw AF_CAN socket on can0/vcan0 (the deployment path);
 *   udp        python-can's udp_multicast wire format (one msgpack map per datagram,
 *              IPv4 multicast, TTL 0), so the executor and a python-can process share a
 *              bus on machines whose kernel has no CAN.
 *
 * The caller owns the hv_can_bus_t (static or on the stack): open fills it, nothing is
 * allocated on the heap by the transports themselves (msgpack-c's unpack zone is set up
 * at open and reused). A bus is used by one thread at a time.
 *
 *   hv_can_bus_t bus;
 *   hv_can_filter_t only_left = { 0x060, 0x7E0 };          // node 3, all commands
 *   if (hv_can_socketcan_open(&bus, "vcan0", &only_left, 1) != HV_OK) ...
 *   hv_can_frame_t f;
 *   hv_status_t st = hv_can_recv(&bus, &f, 100);            // HV_CAN_ERR_TIMEOUT after 100 ms
 *   hv_can_close(&bus);
 *
 * Both transports behave alike: a bus does not receive the frames it sent itself (like
 * SocketCAN's default), filters are applied before a frame is returned and the receive
 * timeout is in milliseconds (0 = poll once, negative = wait forever).
 */
#ifndef HV_CAN_BUS_H
#define HV_CAN_BUS_H

#include <stddef.h>
#include <stdint.h>

#include "hv/can_status.h"
#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HV_CAN_MAX_DLC     8
#define HV_CAN_MAX_FILTERS 16
#define HV_CAN_SFF_MASK    0x7FFu      /* standard 11-bit id */
#define HV_CAN_EFF_MASK    0x1FFFFFFFu /* extended 29-bit id */

/* python-can's udp_multicast defaults (can/interfaces/udp_multicast/bus.py) */
#define HV_CAN_UDP_DEFAULT_GROUP "239.74.163.2"
#define HV_CAN_UDP_DEFAULT_PORT  43113

/* hv_can_frame_t.flags */
#define HV_CAN_FLAG_EXT 0x01u /* 29-bit id */
#define HV_CAN_FLAG_RTR 0x02u /* remote transmission request (no data) */
#define HV_CAN_FLAG_ERR 0x04u /* error frame: id holds the error class bits */

typedef struct hv_can_frame {
    uint32_t id;   /* 11-bit (or 29-bit with HV_CAN_FLAG_EXT), no flag bits in it */
    uint8_t dlc;   /* payload length in bytes, 0..8 */
    uint8_t flags; /* HV_CAN_FLAG_* */
    uint8_t data[HV_CAN_MAX_DLC];
    int64_t timestamp_ns; /* receive: kernel receive time, ns since the Unix epoch
                             (CLOCK_REALTIME, same clock as python-can's timestamps);
                             send: ignored (udp puts the send time on the wire) */
} hv_can_frame_t;

/* A frame passes when (frame.id & mask) == (id & mask); an extended-id frame passes
 * only a filter whose id has HV_CAN_FLAG_EXT in ext. No filters = receive everything. */
typedef struct hv_can_filter {
    uint32_t id;
    uint32_t mask;
    uint8_t ext; /* 1: match 29-bit ids, 0: match 11-bit ids */
} hv_can_filter_t;

typedef struct hv_can_stats {
    uint64_t tx_frames;       /* frames handed to the kernel */
    uint64_t rx_frames;       /* frames returned by hv_can_recv (after filtering) */
    uint64_t rx_error_frames; /* error frames seen (socketcan: CAN_ERR_FLAG; udp:
                                  is_error_frame); also returned, flagged HV_CAN_FLAG_ERR */
    uint64_t rx_malformed;    /* datagrams/frames dropped because they do not parse
                                  (bad msgpack, missing or mistyped keys, dlc > 8, ...) */
    uint64_t rx_unsupported;  /* well-formed but unusable here, dropped: CAN FD frames */
    uint64_t rx_filtered;     /* dropped by the software filter (udp only: socketcan
                                  filters in the kernel, those never reach us) */
    uint64_t rx_kernel_drops; /* socketcan: frames the kernel dropped on a full receive
                                  queue (SO_RXQ_OVFL), 0 where unknown */
    uint64_t tx_failures;     /* sends that returned an error (incl. timeouts) */
} hv_can_stats_t;

typedef struct hv_can_bus hv_can_bus_t;

/* The transport behind a bus. Callers use the hv_can_* functions below, not these. */
typedef struct hv_can_ops {
    const char *kind; /* "socketcan" or "udp" */
    hv_status_t (*send)(hv_can_bus_t *bus, const hv_can_frame_t *frame, int timeout_ms);
    hv_status_t (*recv)(hv_can_bus_t *bus, hv_can_frame_t *frame, int timeout_ms);
    void (*close)(hv_can_bus_t *bus);
} hv_can_ops_t;

/* Storage of one open bus. Fields are the transports' business: read them through the
 * functions below. Zero-initialise before the first open is not needed. */
struct hv_can_bus {
    const hv_can_ops_t *ops; /* NULL when closed */
    int rx_fd;               /* the descriptor to poll for reception */
    int tx_fd;               /* = rx_fd for socketcan; udp sends from its own socket */
    int last_errno;          /* errno of the last failing system call, 0 if none */
    hv_can_stats_t stats;
    hv_can_filter_t filters[HV_CAN_MAX_FILTERS];
    size_t n_filters;
    char name[64]; /* "socketcan:vcan0", "udp:239.74.163.2:43113" */
    /* udp only */
    uint32_t group_be;    /* group address, network byte order */
    uint16_t port;        /* host byte order */
    uint16_t tx_port_be;  /* source port of our own datagrams (to drop them) */
    uint32_t tx_addr_be;  /* source address of our own datagrams */
    uint64_t impl[8];     /* transport state with no public meaning (msgpack zone) */
    uint8_t rx_buf[2048]; /* one datagram; python-can frames are ~200 bytes */
};

/* Opens raw CAN on `ifname` ("vcan0", "can0"), non-blocking, with the kernel receive
 * filters given (n_filters == 0: all frames) and error frames enabled (counted and
 * returned with HV_CAN_FLAG_ERR). Errors: HV_ERR_ARG, HV_CAN_ERR_UNSUPPORTED (kernel
 * without AF_CAN), HV_CAN_ERR_NO_DEVICE, HV_CAN_ERR_FILTERS, HV_CAN_ERR_SOCKET. */
hv_status_t hv_can_socketcan_open(hv_can_bus_t *bus, const char *ifname,
                                  const hv_can_filter_t *filters, size_t n_filters);

/* Joins the IPv4 multicast `group` (NULL: HV_CAN_UDP_DEFAULT_GROUP) on `port`
 * (0: HV_CAN_UDP_DEFAULT_PORT) through the interface with address `if_addr` (NULL:
 * "127.0.0.1", loopback), TTL 0 and multicast loopback on, so nothing leaves the host.
 * Filters are applied in software. Errors: HV_ERR_ARG, HV_CAN_ERR_ADDRESS,
 * HV_CAN_ERR_FILTERS, HV_CAN_ERR_SOCKET (e.g. no route to the group: run in a namespace
 * with `ip route add 224.0.0.0/4 dev lo`). */
hv_status_t hv_can_udp_open(hv_can_bus_t *bus, const char *group, uint16_t port,
                            const char *if_addr, const hv_can_filter_t *filters, size_t n_filters);

/* Sends one frame. Waits up to timeout_ms for room when the send queue is full (0: do
 * not wait, negative: wait forever). Errors: HV_CAN_ERR_CLOSED, HV_CAN_ERR_FRAME,
 * HV_CAN_ERR_TX_FULL, HV_CAN_ERR_SEND; each error counts in tx_failures. */
hv_status_t hv_can_send(hv_can_bus_t *bus, const hv_can_frame_t *frame, int timeout_ms);

/* Receives the next frame passing the filters, waiting up to timeout_ms. Malformed input
 * is counted and skipped, never returned. Errors: HV_CAN_ERR_TIMEOUT, HV_CAN_ERR_CLOSED,
 * HV_CAN_ERR_RECV, HV_CAN_ERR_INTERRUPTED. */
hv_status_t hv_can_recv(hv_can_bus_t *bus, hv_can_frame_t *frame, int timeout_ms);

/* Closes the sockets; safe to call twice or on a bus whose open failed. */
void hv_can_close(hv_can_bus_t *bus);

/* Copy of the counters (all zero for a closed bus). */
hv_status_t hv_can_get_stats(const hv_can_bus_t *bus, hv_can_stats_t *out);

/* Descriptor that becomes readable when a datagram/frame is waiting (for poll() in an
 * event loop; a readable fd may still yield HV_CAN_ERR_TIMEOUT with timeout 0 if what
 * arrived was filtered or malformed). -1 when closed. */
int hv_can_fd(const hv_can_bus_t *bus);

/* "socketcan:vcan0" / "udp:239.74.163.2:43113", "closed" when closed. */
const char *hv_can_name(const hv_can_bus_t *bus);

/* errno of the last failing system call on this bus (0: none), for messages. */
int hv_can_last_errno(const hv_can_bus_t *bus);

/* 1 when `frame` passes `filters` (n == 0 passes everything), else 0. */
int hv_can_filter_match(const hv_can_filter_t *filters, size_t n, const hv_can_frame_t *frame);

#ifdef __cplusplus
}
#endif
#endif /* HV_CAN_BUS_H */
