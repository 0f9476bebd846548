/* python-can udp_multicast wire format (python-can 4.6.1, can/interfaces/udp_multicast/
 * utils.py): every datagram is one msgpack map with the keys of can.Message
 *   timestamp (float s), arbitration_id (uint), is_extended_id, is_remote_frame,
 *   is_error_frame (bool), channel (nil|str|int), dlc (uint), data (bin),
 *   is_fd, bitrate_switch, error_state_indicator (bool).
 * Separate from the socket code so that the codec is unit-tested without a network. */
#ifndef HV_CAN_UDP_WIRE_H
#define HV_CAN_UDP_WIRE_H

#include <stddef.h>
#include <stdint.h>

#include "hv/can_bus.h"

#ifdef __cplusplus
extern "C" {
#endif

struct msgpack_zone; /* msgpack-c's allocation arena (msgpack/zone.h) */

/* A python-can classic frame packs to ~190 bytes; this leaves room for CAN FD (64 data
 * bytes) and a channel name, which we never send but may receive. */
#define HV_CAN_UDP_MAX_DATAGRAM 512

/* Encodes `frame` as python-can does, with `timestamp_s` (Unix seconds) and channel nil.
 * Errors: HV_ERR_ARG, HV_CAN_ERR_FRAME (dlc > 8, id too wide for its kind, RTR with
 * the error flag), HV_CAN_ERR_NOSPACE (cap too small; *len untouched). */
hv_status_t hv_can_udp_wire_encode(const hv_can_frame_t *frame, double timestamp_s, uint8_t *buf,
                                   size_t cap, size_t *len);

/* Decodes one datagram into `frame` (timestamp_ns from the datagram's timestamp).
 * `zone` is a msgpack_zone set up by the caller (msgpack_zone_init); it is cleared
 * before returning, so memory does not grow per datagram.
 * Errors: HV_CAN_ERR_MALFORMED (not exactly one map, unknown, duplicate, missing or
 * mistyped key, dlc/data disagree, id out of range, flags python-can rejects),
 * HV_CAN_ERR_UNSUPPORTED (a valid CAN FD frame: this bus is classic CAN only). */
hv_status_t hv_can_udp_wire_decode(const uint8_t *buf, size_t len, struct msgpack_zone *zone,
                                   hv_can_frame_t *frame);

#ifdef __cplusplus
}
#endif
#endif /* HV_CAN_UDP_WIRE_H */
