/* msgpack codec of python-can's udp_multicast datagrams (see hv/can_udp_wire.h).
 * Decoding mirrors can.Message(check=True): what python-can would reject we reject. */
#include "hv/can_udp_wire.h"

#include <math.h>
#include <string.h>

#include <msgpack.h>

/* msgpack_packer writes through a callback; this one fills a bounded buffer. */
typedef struct wire_sink {
    uint8_t *buf;
    size_t cap;
    size_t len;
    int overflow;
} wire_sink_t;

static int sink_write(void *data, const char *bytes, size_t n)
{
    wire_sink_t *sink = data;
    if (sink->overflow || n > sink->cap - sink->len) {
        sink->overflow = 1;
        return -1;
    }
    memcpy(sink->buf + sink->len, bytes, n);
    sink->len += n;
    return 0;
}

static void pack_key(msgpack_packer *pk, const char *key)
{
    size_t n = strlen(key);
    msgpack_pack_str(pk, n);
    msgpack_pack_str_body(pk, key, n);
}

static void pack_bool(msgpack_packer *pk, const char *key, int value)
{
    pack_key(pk, key);
    if (value)
        msgpack_pack_true(pk);
    else
        msgpack_pack_false(pk);
}

hv_status_t hv_can_udp_wire_encode(const hv_can_frame_t *frame, double timestamp_s, uint8_t *buf,
                                   size_t cap, size_t *len)
{
    if (!frame || !buf || !len || !isfinite(timestamp_s) || timestamp_s < 0.0)
        return HV_ERR_ARG;
    int ext = (frame->flags & HV_CAN_FLAG_EXT) != 0;
    int rtr = (frame->flags & HV_CAN_FLAG_RTR) != 0;
    int err = (frame->flags & HV_CAN_FLAG_ERR) != 0;
    if (frame->dlc > HV_CAN_MAX_DLC || frame->id > (ext ? HV_CAN_EFF_MASK : HV_CAN_SFF_MASK) ||
        (rtr && err))
        return (hv_status_t)HV_CAN_ERR_FRAME;

    wire_sink_t sink = {buf, cap, 0, 0};
    msgpack_packer pk;
    msgpack_packer_init(&pk, &sink, sink_write);
    /* Same keys and order as python-can's pack_message. */
    msgpack_pack_map(&pk, 11);
    pack_key(&pk, "timestamp");
    msgpack_pack_double(&pk, timestamp_s);
    pack_key(&pk, "arbitration_id");
    msgpack_pack_uint32(&pk, frame->id);
    pack_bool(&pk, "is_extended_id", ext);
    pack_bool(&pk, "is_remote_frame", rtr);
    pack_bool(&pk, "is_error_frame", err);
    pack_key(&pk, "channel");
    msgpack_pack_nil(&pk);
    pack_key(&pk, "dlc");
    msgpack_pack_uint8(&pk, frame->dlc);
    pack_key(&pk, "data");
    /* python-can: a remote frame carries no data, its dlc is the requested length */
    size_t n_data = rtr ? 0 : frame->dlc;
    msgpack_pack_bin(&pk, n_data);
    msgpack_pack_bin_body(&pk, frame->data, n_data);
    pack_bool(&pk, "is_fd", 0);
    pack_bool(&pk, "bitrate_switch", 0);
    pack_bool(&pk, "error_state_indicator", 0);
    if (sink.overflow)
        return (hv_status_t)HV_CAN_ERR_NOSPACE;
    *len = sink.len;
    return HV_OK;
}

/* Parsed keys; `seen` has one bit per key so duplicates and absences are caught. */
enum wire_key {
    K_TIMESTAMP,
    K_ID,
    K_EXT,
    K_RTR,
    K_ERR,
    K_CHANNEL,
    K_DLC,
    K_DATA,
    K_FD,
    K_BRS,
    K_ESI,
    K_COUNT
};
static const char *const wire_key_names[K_COUNT] = {"timestamp",
                                                    "arbitration_id",
                                                    "is_extended_id",
                                                    "is_remote_frame",
                                                    "is_error_frame",
                                                    "channel",
                                                    "dlc",
                                                    "data",
                                                    "is_fd",
                                                    "bitrate_switch",
                                                    "error_state_indicator"};

static int key_index(const msgpack_object *key)
{
    if (key->type != MSGPACK_OBJECT_STR)
        return -1;
    for (int i = 0; i < K_COUNT; i++) {
        size_t n = strlen(wire_key_names[i]);
        if (key->via.str.size == n && memcmp(key->via.str.ptr, wire_key_names[i], n) == 0)
            return i;
    }
    return -1;
}

/* The largest timestamp (s since the epoch) whose ns fit hv_can_frame_t.timestamp_ns. */
#define WIRE_MAX_TIMESTAMP_S 9.2e9

typedef struct wire_fields {
    double timestamp_s;
    uint64_t id;
    int ext, rtr, err, fd, brs, esi;
    uint64_t dlc;
    int have_dlc;
    const uint8_t *data;
    size_t n_data;
} wire_fields_t;

static int get_bool(const msgpack_object *v, int *out)
{
    if (v->type != MSGPACK_OBJECT_BOOLEAN)
        return -1;
    *out = v->via.boolean ? 1 : 0;
    return 0;
}

static int get_uint(const msgpack_object *v, uint64_t *out)
{
    if (v->type != MSGPACK_OBJECT_POSITIVE_INTEGER)
        return -1; /* negative ids and dlcs are invalid in python-can too */
    *out = v->via.u64;
    return 0;
}

/* One key/value pair into `f`; -1 when the value's type is not what python-can sends. */
static int take_field(int k, const msgpack_object *v, wire_fields_t *f)
{
    switch (k) {
    case K_TIMESTAMP:
        if (v->type == MSGPACK_OBJECT_FLOAT32 || v->type == MSGPACK_OBJECT_FLOAT64)
            f->timestamp_s = v->via.f64;
        else if (v->type == MSGPACK_OBJECT_POSITIVE_INTEGER)
            f->timestamp_s = (double)v->via.u64;
        else
            return -1;
        /* the frame keeps int64 ns: a later time (past 2262) would overflow it */
        return (isfinite(f->timestamp_s) && f->timestamp_s >= 0.0 &&
                f->timestamp_s < WIRE_MAX_TIMESTAMP_S)
                   ? 0
                   : -1;
    case K_ID: return get_uint(v, &f->id);
    case K_EXT: return get_bool(v, &f->ext);
    case K_RTR: return get_bool(v, &f->rtr);
    case K_ERR: return get_bool(v, &f->err);
    case K_FD: return get_bool(v, &f->fd);
    case K_BRS: return get_bool(v, &f->brs);
    case K_ESI: return get_bool(v, &f->esi);
    case K_CHANNEL: /* informational only */
        return (v->type == MSGPACK_OBJECT_NIL || v->type == MSGPACK_OBJECT_STR ||
                v->type == MSGPACK_OBJECT_POSITIVE_INTEGER)
                   ? 0
                   : -1;
    case K_DLC:
        if (v->type == MSGPACK_OBJECT_NIL)
            return 0; /* python-can: dlc None means len(data) */
        f->have_dlc = 1;
        return get_uint(v, &f->dlc);
    case K_DATA:
        if (v->type == MSGPACK_OBJECT_NIL)
            return 0;
        if (v->type != MSGPACK_OBJECT_BIN)
            return -1;
        f->data = (const uint8_t *)v->via.bin.ptr;
        f->n_data = v->via.bin.size;
        return 0;
    default: return -1;
    }
}

/* can.Message._check, for the fields we parsed. */
static hv_status_t check_fields(wire_fields_t *f)
{
    if (!f->have_dlc)
        f->dlc = f->n_data;
    if (f->rtr && (f->err || f->fd))
        return (hv_status_t)HV_CAN_ERR_MALFORMED;
    if (f->id >= (f->ext ? 0x20000000u : 0x800u))
        return (hv_status_t)HV_CAN_ERR_MALFORMED;
    if (f->dlc > (f->fd ? 64u : 8u))
        return (hv_status_t)HV_CAN_ERR_MALFORMED;
    if (f->rtr ? f->n_data != 0 : f->dlc != f->n_data)
        return (hv_status_t)HV_CAN_ERR_MALFORMED;
    if (!f->fd && (f->brs || f->esi))
        return (hv_status_t)HV_CAN_ERR_MALFORMED;
    if (f->fd)
        return (hv_status_t)HV_CAN_ERR_UNSUPPORTED;
    return HV_OK;
}

static hv_status_t decode_object(const msgpack_object *root, hv_can_frame_t *frame)
{
    if (root->type != MSGPACK_OBJECT_MAP)
        return (hv_status_t)HV_CAN_ERR_MALFORMED;
    /* can.Message's defaults for absent keys: note is_extended_id defaults to True */
    wire_fields_t f = {0.0, 0, 1, 0, 0, 0, 0, 0, 0, 0, NULL, 0};
    unsigned seen = 0;
    for (uint32_t i = 0; i < root->via.map.size; i++) {
        const msgpack_object_kv *kv = &root->via.map.ptr[i];
        int k = key_index(&kv->key);
        if (k < 0 || (seen & (1u << k)))
            return (hv_status_t)HV_CAN_ERR_MALFORMED; /* unknown or duplicate key */
        seen |= 1u << k;
        if (take_field(k, &kv->val, &f) != 0)
            return (hv_status_t)HV_CAN_ERR_MALFORMED;
    }
    if (!(seen & (1u << K_ID)))
        return (hv_status_t)HV_CAN_ERR_MALFORMED; /* the one key without a default */
    hv_status_t st = check_fields(&f);
    if (st != HV_OK)
        return st;

    memset(frame, 0, sizeof *frame);
    frame->id = (uint32_t)f.id;
    frame->dlc = (uint8_t)f.dlc;
    frame->flags = (uint8_t)((f.ext ? HV_CAN_FLAG_EXT : 0u) | (f.rtr ? HV_CAN_FLAG_RTR : 0u) |
                             (f.err ? HV_CAN_FLAG_ERR : 0u));
    if (f.n_data)
        memcpy(frame->data, f.data, f.n_data);
    frame->timestamp_ns = (int64_t)(f.timestamp_s * 1e9);
    return HV_OK;
}

/* Big-endian length field of `width` bytes at p. */
static uint64_t be_len(const uint8_t *p, unsigned width)
{
    uint64_t v = 0;
    for (unsigned i = 0; i < width; i++)
        v = (v << 8) | p[i];
    return v;
}

/* Walks the msgpack items of buf without building them and checks that every declared
 * length and element count fits in what is left. msgpack-c sizes its allocations from
 * the declared counts, so a 6-byte datagram claiming a 2^32-entry map would otherwise
 * make it ask for tens of gigabytes. 0 when sane, -1 otherwise. */
static int wire_sane(const uint8_t *buf, size_t len)
{
    size_t pos = 0;
    uint64_t pending = 1; /* items still to read: the root */
    while (pending > 0) {
        if (pos >= len)
            return -1;
        uint8_t b = buf[pos++];
        pending--;
        uint64_t skip = 0, items = 0;
        unsigned width = 0; /* bytes of a length/count field that follows b */
        int is_count = 0, pairs = 0;
        if (b <= 0x7f || b >= 0xe0 || b == 0xc0 || b == 0xc2 || b == 0xc3) {
            /* fixint, nil, bool: nothing follows */
        } else if (b >= 0x80 && b <= 0x8f) {
            items = 2u * (b & 0x0fu);
        } else if (b >= 0x90 && b <= 0x9f) {
            items = b & 0x0fu;
        } else if (b >= 0xa0 && b <= 0xbf) {
            skip = b & 0x1fu;
        } else {
            switch (b) {
            case 0xc4:
            case 0xd9: width = 1; break; /* bin8, str8 */
            case 0xc5:
            case 0xda: width = 2; break; /* bin16, str16 */
            case 0xc6:
            case 0xdb: width = 4; break; /* bin32, str32 */
            case 0xc7:
                width = 1;
                skip = 1;
                break; /* ext8: + type byte */
            case 0xc8:
                width = 2;
                skip = 1;
                break;
            case 0xc9:
                width = 4;
                skip = 1;
                break;
            case 0xca: skip = 4; break;
            case 0xcb: skip = 8; break;
            case 0xcc:
            case 0xd0: skip = 1; break;
            case 0xcd:
            case 0xd1: skip = 2; break;
            case 0xce:
            case 0xd2: skip = 4; break;
            case 0xcf:
            case 0xd3: skip = 8; break;
            case 0xd4: skip = 2; break; /* fixext 1..16 + type */
            case 0xd5: skip = 3; break;
            case 0xd6: skip = 5; break;
            case 0xd7: skip = 9; break;
            case 0xd8: skip = 17; break;
            case 0xdc:
                width = 2;
                is_count = 1;
                break; /* array16 */
            case 0xdd:
                width = 4;
                is_count = 1;
                break;
            case 0xde:
                width = 2;
                is_count = 1;
                pairs = 1;
                break; /* map16 */
            case 0xdf:
                width = 4;
                is_count = 1;
                pairs = 1;
                break;
            default: return -1; /* 0xc1: never used */
            }
        }
        if (width) {
            if (len - pos < width)
                return -1;
            uint64_t n = be_len(buf + pos, width);
            pos += width;
            if (is_count)
                items = pairs ? 2u * n : n;
            else
                skip += n;
        }
        if (skip > len - pos)
            return -1;
        pos += (size_t)skip;
        /* every item takes at least one byte, so more items than bytes left is a lie */
        if (items > len - pos || pending + items > len - pos)
            return -1;
        pending += items;
    }
    return pos == len ? 0 : -1; /* trailing bytes: not exactly one object */
}

hv_status_t hv_can_udp_wire_decode(const uint8_t *buf, size_t len, struct msgpack_zone *zone,
                                   hv_can_frame_t *frame)
{
    if (!buf || !zone || !frame)
        return HV_ERR_ARG;
    if (len == 0 || wire_sane(buf, len) != 0)
        return (hv_status_t)HV_CAN_ERR_MALFORMED;
    size_t off = 0;
    msgpack_object root;
    msgpack_unpack_return ret = msgpack_unpack((const char *)buf, len, &off, zone, &root);
    hv_status_t st;
    if (ret != MSGPACK_UNPACK_SUCCESS) /* parse error, truncated, or trailing bytes */
        st = (hv_status_t)HV_CAN_ERR_MALFORMED;
    else
        st = decode_object(&root, frame);
    msgpack_zone_clear(zone);
    return st;
}
