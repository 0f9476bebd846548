/* SLCAN lines <-> CAN frames (see slcan.h). */
#include "slcan.h"

#include <string.h>

#include "fw_status.h"

static const char hex_digit[] = "0123456789ABCDEF";

int hv_slcan_feed(hv_slcan_rx_t *rx, uint8_t b)
{
    if (b == '\r') {
        int long_line = rx->too_long, lost = rx->lost;
        if (lost)
            rx->len = 0; /* nothing of a damaged line is shown */
        rx->line[rx->len] = '\0';
        rx->done = rx->len;
        rx->len = 0;
        rx->too_long = 0;
        rx->lost = 0;
        return lost ? 0 : long_line ? HV_ERR_SLCAN_LINE_LONG : 1;
    }
    if (b == '\a' || b == '\n' || rx->too_long || rx->lost)
        return 0;
    if (rx->len >= HV_SLCAN_LINE_MAX) {
        rx->too_long = 1;
        return 0;
    }
    rx->line[rx->len++] = (char)b;
    return 0;
}

void hv_slcan_reset(hv_slcan_rx_t *rx)
{
    rx->len = 0;
    rx->done = 0;
    rx->too_long = 0;
    rx->lost = 0;
    rx->line[0] = '\0';
}

void hv_slcan_lost(hv_slcan_rx_t *rx)
{
    rx->len = 0;
    rx->lost = 1;
}

static int hex_value(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    return -1;
}

/* n hex digits at s into *out; HV_ERR_SLCAN_HEX at the first that is not one */
static hv_status_t hex_field(const char *s, unsigned n, uint32_t *out)
{
    uint32_t v = 0;
    for (unsigned i = 0; i < n; i++) {
        int d = hex_value(s[i]);
        if (d < 0)
            return HV_ERR_SLCAN_HEX;
        v = (v << 4) | (uint32_t)d;
    }
    *out = v;
    return HV_OK;
}

static hv_status_t parse_frame(const char *line, size_t len, hv_can_frame_t *f)
{
    char kind = line[0];
    int ext = kind == 'T' || kind == 'R';
    int rtr = kind == 'r' || kind == 'R';
    unsigned id_digits = ext ? 8u : 3u;
    if (len < 1u + id_digits + 1u)
        return HV_ERR_SLCAN_LENGTH;
    uint32_t id, dlc;
    hv_status_t st = hex_field(line + 1, id_digits, &id);
    if (st != HV_OK)
        return st;
    if ((ext && id > HV_CAN_EFF_MASK) || (!ext && id > HV_CAN_SFF_MASK))
        return HV_ERR_SLCAN_LENGTH;
    st = hex_field(line + 1 + id_digits, 1, &dlc);
    if (st != HV_OK)
        return st;
    if (dlc > HV_CAN_MAX_DLC)
        return HV_ERR_SLCAN_LENGTH;
    size_t data_at = 2u + id_digits;
    if (len != data_at + (rtr ? 0u : 2u * dlc))
        return HV_ERR_SLCAN_LENGTH;
    memset(f, 0, sizeof *f);
    f->id = id;
    f->dlc = (uint8_t)dlc;
    f->flags = (uint8_t)((ext ? HV_CAN_FLAG_EXT : 0u) | (rtr ? HV_CAN_FLAG_RTR : 0u));
    for (unsigned i = 0; !rtr && i < dlc; i++) {
        uint32_t byte;
        st = hex_field(line + data_at + 2u * i, 2, &byte);
        if (st != HV_OK)
            return st;
        f->data[i] = (uint8_t)byte;
    }
    return HV_OK;
}

hv_status_t hv_slcan_parse(const char *line, size_t len, hv_slcan_cmd_t *cmd, hv_can_frame_t *frame)
{
    if (!line || !cmd || !frame)
        return HV_ERR_ARG;
    *cmd = HV_SLCAN_NONE;
    if (len == 0)
        return HV_OK;
    switch (line[0]) {
    case 't':
    case 'T':
    case 'r':
    case 'R': {
        hv_status_t st = parse_frame(line, len, frame);
        if (st == HV_OK)
            *cmd = HV_SLCAN_FRAME;
        return st;
    }
    case 'O':
    case 'L':
    case 'C':
    case 'V':
    case 'N':
    case 'F':
        if (len != 1)
            return HV_ERR_SLCAN_LENGTH;
        *cmd = line[0] == 'C'   ? HV_SLCAN_CLOSE
               : line[0] == 'V' ? HV_SLCAN_VERSION
               : line[0] == 'N' ? HV_SLCAN_SERIAL
               : line[0] == 'F' ? HV_SLCAN_FLAGS
                                : HV_SLCAN_OPEN;
        return HV_OK;
    case 'S':
        if (len != 2)
            return HV_ERR_SLCAN_LENGTH;
        if (line[1] < '0' || line[1] > '8')
            return HV_ERR_SLCAN_HEX;
        *cmd = HV_SLCAN_BITRATE;
        return HV_OK;
    case 's': { /* BTR0 BTR1 of an SJA1000: 4 hex digits */
        uint32_t btr;
        if (len != 5)
            return HV_ERR_SLCAN_LENGTH;
        hv_status_t st = hex_field(line + 1, 4, &btr);
        if (st == HV_OK)
            *cmd = HV_SLCAN_BITRATE;
        return st;
    }
    case 'Z':
        if (len != 2)
            return HV_ERR_SLCAN_LENGTH;
        if (line[1] != '0' && line[1] != '1')
            return HV_ERR_SLCAN_HEX;
        *cmd = HV_SLCAN_TIMESTAMP;
        return HV_OK;
    default: return HV_ERR_SLCAN_COMMAND;
    }
}

size_t hv_slcan_format(const hv_can_frame_t *f, char *buf, size_t len)
{
    if (!f || !buf || f->dlc > HV_CAN_MAX_DLC || (f->flags & HV_CAN_FLAG_ERR))
        return 0;
    int ext = (f->flags & HV_CAN_FLAG_EXT) != 0;
    /* the line holds 3 or 8 hex digits: a larger id would go out as another frame's */
    if (f->id > (ext ? HV_CAN_EFF_MASK : HV_CAN_SFF_MASK))
        return 0;
    int rtr = (f->flags & HV_CAN_FLAG_RTR) != 0;
    unsigned id_digits = ext ? 8u : 3u;
    size_t need = 1u + id_digits + 1u + (rtr ? 0u : 2u * f->dlc) + 1u;
    if (len < need)
        return 0;
    size_t k = 0;
    buf[k++] = rtr ? (ext ? 'R' : 'r') : (ext ? 'T' : 't');
    for (unsigned i = id_digits; i-- > 0;)
        buf[k++] = hex_digit[(f->id >> (4u * i)) & 0xFu];
    buf[k++] = hex_digit[f->dlc];
    for (unsigned i = 0; !rtr && i < f->dlc; i++) {
        buf[k++] = hex_digit[f->data[i] >> 4];
        buf[k++] = hex_digit[f->data[i] & 0xFu];
    }
    buf[k++] = '\r';
    return k;
}
