/* SLCAN (the Lawicel CAN232/CANUSB serial-line protocol), the firmware's CAN port: one
 * ASCII line per command or frame, ended by CR. Pure code, no I/O: built into the image
 * and into the host's unit test.
 *
 *   tIIILDD..   standard frame: 3 hex id, 1 digit DLC (0..8), 2 x DLC hex data
 *   TIIIIIIIILDD..  extended frame: 8 hex id
 *   rIIIL / RIIIIIIIIL  remote frames (no data)
 *   O open, L open listen-only, C close, Sn bitrate (n 0..8), V version, N serial number,
 *   F status flags, Z0/Z1 timestamps off/on (accepted, timestamps never sent)
 *
 * Replies (Lawicel): CR for a command done, BELL (0x07) for an error; a frame the host
 * transmits is answered "z" CR (extended "Z" CR). Frames the firmware sends go out as t/T
 * lines while the channel is open. */
#ifndef HV_SLCAN_H
#define HV_SLCAN_H

#include <stddef.h>
#include <stdint.h>

#include "hv/can_bus.h"
#include "hv/status.h"

/* the longest line: 'T' + 8 id + 1 DLC + 16 data, then CR */
#define HV_SLCAN_LINE_MAX 27u

typedef struct hv_slcan_rx {
    char line[HV_SLCAN_LINE_MAX + 1]; /* the line under way; once complete NUL-terminated */
    unsigned len;                     /* bytes of the line under way */
    unsigned done;                    /* length of the line completed by the last CR */
    int too_long; /* the line outgrew line[]: its bytes are dropped up to the CR */
    int lost;     /* a byte of the line was lost: its bytes are dropped up to the CR */
} hv_slcan_rx_t;

typedef enum hv_slcan_cmd {
    HV_SLCAN_NONE = 0, /* empty line (a bare CR: hosts send it to flush) */
    HV_SLCAN_FRAME,    /* a frame the host transmits onto our bus: *frame filled */
    HV_SLCAN_OPEN,     /* O or L */
    HV_SLCAN_CLOSE,    /* C */
    HV_SLCAN_BITRATE,  /* Sn or s...: the bus is emulated, accepted and ignored */
    HV_SLCAN_VERSION,  /* V */
    HV_SLCAN_SERIAL,   /* N */
    HV_SLCAN_FLAGS,    /* F */
    HV_SLCAN_TIMESTAMP /* Z0 / Z1 */
} hv_slcan_cmd_t;

/* Take one byte. Returns 1 when a line is complete (the CR seen): rx->line, rx->done
 * bytes, valid until the next byte is fed; 0 while it is not (or the CR ended a line that
 * lost a byte: hv_slcan_lost), HV_ERR_SLCAN_LINE_LONG when the CR ends a line that outgrew
 * the buffer (the line is dropped). A BELL or LF is ignored (not part of any command). */
int hv_slcan_feed(hv_slcan_rx_t *rx, uint8_t b);

/* Forget the line under way: the state of a fresh receiver. */
void hv_slcan_reset(hv_slcan_rx_t *rx);

/* A byte of the line under way was lost (a UART overrun): the line is dropped up to its CR,
 * which then returns 0, so nothing of it is ever taken for a command ("C" would close the
 * channel). Feed the bytes after the loss as they come. */
void hv_slcan_lost(hv_slcan_rx_t *rx);

/* Parse a complete line (without its CR). HV_ERR_SLCAN_HEX for a non-hex digit in an id,
 * DLC or data, HV_ERR_SLCAN_LENGTH for DLC > 8 or a data field that is not 2 x DLC
 * digits (or a line of the wrong length), HV_ERR_SLCAN_COMMAND for a letter Lawicel does
 * not define. */
hv_status_t hv_slcan_parse(const char *line, size_t len, hv_slcan_cmd_t *cmd,
                           hv_can_frame_t *frame);

/* The t/T (r/R) line of a frame, CR included, into buf; returns its length, 0 when buf is
 * too small (HV_SLCAN_LINE_MAX + 1 is always enough) or the frame has no line: a DLC
 * above 8, an id beyond 11 bits (29 with HV_CAN_FLAG_EXT), an error frame. */
size_t hv_slcan_format(const hv_can_frame_t *frame, char *buf, size_t len);

#endif /* HV_SLCAN_H */
