/* Every message of harvest.dbc by name, for code that handles frames generically
 * (hv-can-tool, logging, tests): a table generated from the DBC at build time by
 * gen_message_table.py, wrapping the cantools-generated harvest_can_<msg>_pack/_unpack
 * and the per-signal _encode/_decode conversions. The executor's control paths use the
 * typed harvest_can_* functions directly. */
#ifndef HV_CAN_MESSAGES_H
#define HV_CAN_MESSAGES_H

#include <stddef.h>
#include <stdint.h>

#include "hv/can_bus.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HV_CAN_MAX_SIGNALS 16

typedef struct hv_can_message_desc {
    const char *name; /* DBC message name, e.g. "LeftArmSetpoint" */
    uint32_t id;      /* 11-bit frame id */
    uint8_t length;   /* DLC the DBC gives */
    size_t n_signals;
    const char *const *signals; /* DBC signal names, in DBC order */
    const double *minimum;      /* DBC range of each signal, physical units */
    const double *maximum;
    /* physical values (SI units of the DBC) in signal order -> payload of `length` bytes;
     * returns the generated pack's result (length, or negative) */
    int (*pack)(uint8_t *dst, const double *values);
    /* payload -> physical values in signal order; returns the generated unpack's result
     * (0, or negative when the payload is shorter than the DBC length) */
    int (*unpack)(const uint8_t *src, size_t len, double *values);
} hv_can_message_desc_t;

extern const hv_can_message_desc_t hv_can_messages[];
extern const size_t hv_can_n_messages;

/* Descriptor by name or by frame id; NULL when the DBC has no such message. */
const hv_can_message_desc_t *hv_can_message_by_name(const char *name);
const hv_can_message_desc_t *hv_can_message_by_id(uint32_t id);

/* HV_OK when `frame` is a standard-id data frame whose id is in the DBC and whose DLC
 * is the DBC length; HV_CAN_ERR_DECODE otherwise (unknown id, wrong length, RTR/EXT). */
hv_status_t hv_can_message_check(const hv_can_frame_t *frame);

#ifdef __cplusplus
}
#endif
#endif /* HV_CAN_MESSAGES_H */
