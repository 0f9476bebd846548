/* Fuzz target: the firmware's SLCAN codec (firmware/slcan.c), the serial line a host's
 * slcan driver or adapter writes to it.
 *
 * Input: the bytes of the serial stream, fed one by one (hv_slcan_feed; a byte 0xFF stands
 * for an overrun there instead, hv_slcan_lost); every completed line is parsed
 * (hv_slcan_parse), and a frame that parses is formatted again (hv_slcan_format). The same bytes, 14 at a time, are also taken as frames to send
 * (id: 4 bytes, dlc, flags, 8 data bytes) and formatted.
 *
 * Properties: no crash or undefined behaviour; the line buffer never overflows; feed returns
 * 0, 1 or HV_ERR_SLCAN_LINE_LONG, and nothing but 0 up to the CR of a line that lost a
 * byte; parse HV_OK or a named SLCAN code; a line that parses to a frame formats to the
 * same line (hex digits in either case) and that line parses to the same frame; a frame
 * formats to 0 bytes or to a line that parses to the same frame. */
#include <string.h>
#include <strings.h>

#include "fuzz_support.h"
#include "fw_status.h"
#include "slcan.h"

static int same_frame(const hv_can_frame_t *a, const hv_can_frame_t *b)
{
    const uint8_t kind = HV_CAN_FLAG_EXT | HV_CAN_FLAG_RTR;
    return a->id == b->id && a->dlc == b->dlc && (a->flags & kind) == (b->flags & kind) &&
           ((a->flags & HV_CAN_FLAG_RTR) || memcmp(a->data, b->data, a->dlc) == 0);
}

/* a formatted line of len bytes: CR-terminated, parses back to exactly f */
static void check_line(const hv_can_frame_t *f, const char *line, size_t len)
{
    if (len < 2 || len > HV_SLCAN_LINE_MAX + 1 || line[len - 1] != '\r' ||
        memchr(line, '\r', len - 1))
        hv_fuzz_fail("format gave %zu bytes, not one CR-terminated line", len);
    hv_slcan_rx_t rx;
    hv_slcan_reset(&rx);
    for (size_t i = 0; i < len; i++)
        if (hv_slcan_feed(&rx, (uint8_t)line[i]) != (i + 1 == len))
            hv_fuzz_fail("a formatted line is not one line to feed");
    hv_slcan_cmd_t cmd;
    hv_can_frame_t back;
    hv_status_t st = hv_slcan_parse(rx.line, rx.done, &cmd, &back);
    if (st != HV_OK || cmd != HV_SLCAN_FRAME)
        hv_fuzz_fail("formatted line '%.*s' parses to %s", (int)(len - 1), line,
                     hv_fw_status_name(st));
    if (!same_frame(f, &back))
        hv_fuzz_fail("'%.*s' parses to id %x dlc %u flags %x, formatted from id %x dlc %u flags %x",
                     (int)(len - 1), line, (unsigned)back.id, back.dlc, back.flags, (unsigned)f->id,
                     f->dlc, f->flags);
}

static void check_parsed(const char *line, size_t len)
{
    hv_slcan_cmd_t cmd;
    hv_can_frame_t f;
    hv_status_t st = hv_slcan_parse(line, len, &cmd, &f);
    if (st != HV_OK && st != HV_ERR_SLCAN_HEX && st != HV_ERR_SLCAN_LENGTH &&
        st != HV_ERR_SLCAN_COMMAND)
        hv_fuzz_fail("parse returned %d", (int)st);
    if (st != HV_OK || cmd != HV_SLCAN_FRAME)
        return;
    char out[HV_SLCAN_LINE_MAX + 1];
    size_t n = hv_slcan_format(&f, out, sizeof out);
    check_line(&f, out, n);
    if (n - 1 != len || strncasecmp(out, line, len) != 0)
        hv_fuzz_fail("'%.*s' formats again as '%.*s'", (int)len, line, (int)(n - 1), out);
}

static void check_frame(const uint8_t *b)
{
    hv_can_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
    f.dlc = b[4];
    f.flags = b[5];
    memcpy(f.data, b + 6, 8);
    char out[HV_SLCAN_LINE_MAX + 1];
    size_t n = hv_slcan_format(&f, out, sizeof out);
    if (n > 0)
        check_line(&f, out, n);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hv_slcan_rx_t rx;
    hv_slcan_reset(&rx);
    int lost = 0; /* a byte 0xFF stands for a UART overrun: hv_slcan_lost */
    for (size_t i = 0; i < size; i++) {
        if (data[i] == 0xFF) {
            hv_slcan_lost(&rx);
            lost = 1;
            continue;
        }
        int r = hv_slcan_feed(&rx, data[i]);
        if (lost && r != 0)
            hv_fuzz_fail("a line that lost a byte gave %d", r);
        lost &= data[i] != '\r';
        if (rx.len > HV_SLCAN_LINE_MAX || rx.done > HV_SLCAN_LINE_MAX)
            hv_fuzz_fail("line buffer at %u/%u of %u", rx.len, rx.done, HV_SLCAN_LINE_MAX);
        if (r == 1)
            check_parsed(rx.line, rx.done);
        else if (r != 0 && r != HV_ERR_SLCAN_LINE_LONG)
            hv_fuzz_fail("feed returned %d", r);
    }
    for (size_t i = 0; i + 14 <= size; i += 14)
        check_frame(data + i);
    return 0;
}
