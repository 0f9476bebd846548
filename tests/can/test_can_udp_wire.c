/* The python-can udp_multicast codec: encode/decode round trips, the exact bytes of a
 * known frame, and every kind of malformed datagram rejected without crashing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>
#include <msgpack.h>

#include "hv/can_udp_wire.h"

typedef struct fixture {
    msgpack_zone zone;
} fixture_t;

static int setup(void **state)
{
    static fixture_t f; /* cmocka state: one per group run */
    if (!msgpack_zone_init(&f.zone, 2048))
        return -1;
    *state = &f;
    return 0;
}

static int teardown(void **state)
{
    fixture_t *f = *state;
    msgpack_zone_destroy(&f->zone);
    return 0;
}

static hv_status_t decode(void **state, const uint8_t *buf, size_t len, hv_can_frame_t *out)
{
    fixture_t *f = *state;
    return hv_can_udp_wire_decode(buf, len, &f->zone, out);
}

static void round_trip_all_kinds(void **state)
{
    const hv_can_frame_t frames[] = {
        {0x000, 0, 0, {0}, 0},
        {0x7FF, 8, 0, {1, 2, 3, 4, 5, 6, 7, 8}, 0},
        {0x1FFFFFFF, 3, HV_CAN_FLAG_EXT, {0xAA, 0xBB, 0xCC}, 0},
        {0x123, 4, HV_CAN_FLAG_RTR, {0}, 0},
        {0x004, 8, HV_CAN_FLAG_ERR, {0, 4, 0, 0, 0, 0, 0, 0}, 0},
    };
    for (size_t i = 0; i < sizeof frames / sizeof frames[0]; i++) {
        uint8_t buf[HV_CAN_UDP_MAX_DATAGRAM];
        size_t len = 0;
        hv_can_frame_t back;
        assert_int_equal(hv_can_udp_wire_encode(&frames[i], 1234.5, buf, sizeof buf, &len), HV_OK);
        assert_int_equal(decode(state, buf, len, &back), HV_OK);
        assert_int_equal(back.id, frames[i].id);
        assert_int_equal(back.dlc, frames[i].dlc);
        assert_int_equal(back.flags, frames[i].flags);
        if (!(frames[i].flags & HV_CAN_FLAG_RTR))
            assert_memory_equal(back.data, frames[i].data, frames[i].dlc);
        assert_true(back.timestamp_ns == (int64_t)1234500000000LL);
    }
}

static void encode_rejects_bad_frames(void **state)
{
    (void)state;
    uint8_t buf[HV_CAN_UDP_MAX_DATAGRAM];
    size_t len = 0;
    hv_can_frame_t f = {0x800, 0, 0, {0}, 0}; /* 12-bit id without EXT */
    assert_int_equal(hv_can_udp_wire_encode(&f, 0.0, buf, sizeof buf, &len), HV_CAN_ERR_FRAME);
    f.id = 1;
    f.dlc = 9;
    assert_int_equal(hv_can_udp_wire_encode(&f, 0.0, buf, sizeof buf, &len), HV_CAN_ERR_FRAME);
    f.dlc = 8;
    assert_int_equal(hv_can_udp_wire_encode(&f, 0.0, buf, 20, &len), HV_CAN_ERR_NOSPACE);
    assert_int_equal(hv_can_udp_wire_encode(&f, -1.0, buf, sizeof buf, &len), HV_ERR_ARG);
    assert_int_equal(hv_can_udp_wire_encode(NULL, 0.0, buf, sizeof buf, &len), HV_ERR_ARG);
}

/* A datagram as python-can 4.6.1 packs can.Message(arbitration_id=0x64, data=b"\x01\x02",
 * is_extended_id=False, timestamp=0.0): the keys in pack_message's order. */
static void decodes_python_can_bytes(void **state)
{
    msgpack_sbuffer sb;
    msgpack_packer pk;
    msgpack_sbuffer_init(&sb);
    msgpack_packer_init(&pk, &sb, msgpack_sbuffer_write);
    static const char *const keys[] = {"timestamp",
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
    msgpack_pack_map(&pk, 11);
    for (int i = 0; i < 11; i++) {
        msgpack_pack_str(&pk, strlen(keys[i]));
        msgpack_pack_str_body(&pk, keys[i], strlen(keys[i]));
        switch (i) {
        case 0: msgpack_pack_double(&pk, 0.0); break;
        case 1: msgpack_pack_int(&pk, 0x64); break;
        case 5: msgpack_pack_nil(&pk); break;
        case 6: msgpack_pack_int(&pk, 2); break;
        case 7:
            msgpack_pack_bin(&pk, 2);
            msgpack_pack_bin_body(&pk, "\x01\x02", 2);
            break;
        default: msgpack_pack_false(&pk); break;
        }
    }
    hv_can_frame_t f;
    assert_int_equal(decode(state, (const uint8_t *)sb.data, sb.size, &f), HV_OK);
    assert_int_equal(f.id, 0x64);
    assert_int_equal(f.dlc, 2);
    assert_int_equal(f.flags, 0);
    assert_int_equal(f.data[1], 2);

    /* our encoder writes the very same bytes for the same frame and timestamp */
    uint8_t buf[HV_CAN_UDP_MAX_DATAGRAM];
    size_t len = 0;
    hv_can_frame_t g = {0x64, 2, 0, {1, 2}, 0};
    assert_int_equal(hv_can_udp_wire_encode(&g, 0.0, buf, sizeof buf, &len), HV_OK);
    assert_int_equal(len, sb.size);
    assert_memory_equal(buf, sb.data, len);
    msgpack_sbuffer_destroy(&sb);
}

/* Found by fuzz/fuzz_udp_wire: a timestamp too late for int64 ns (here 4.7e27 s, a
 * uint64) was converted with undefined behaviour; it is refused as malformed. */
static void timestamp_beyond_int64_ns_rejected(void **state)
{
    const hv_can_frame_t g = {0x64, 0, 0, {0}, 0};
    const double stamps[] = {9.3e9, 4.7e27};
    for (int i = 0; i < 2; i++) {
        uint8_t buf[HV_CAN_UDP_MAX_DATAGRAM];
        size_t len = 0;
        hv_can_frame_t f;
        assert_int_equal(hv_can_udp_wire_encode(&g, stamps[i], buf, sizeof buf, &len), HV_OK);
        assert_int_equal(decode(state, buf, len, &f), HV_CAN_ERR_MALFORMED);
    }
    uint8_t buf[HV_CAN_UDP_MAX_DATAGRAM];
    size_t len = 0;
    hv_can_frame_t f;
    assert_int_equal(hv_can_udp_wire_encode(&g, 9.1e9, buf, sizeof buf, &len), HV_OK);
    assert_int_equal(decode(state, buf, len, &f), HV_OK);
    assert_true(f.timestamp_ns == (int64_t)9100000000000000000LL);
}

static void malformed_datagrams_rejected(void **state)
{
    hv_can_frame_t f;
    static const uint8_t empty[1] = {0};
    static const uint8_t never_used[] = {0xc1};
    static const uint8_t huge_map[] = {0xdf, 0xff, 0xff, 0xff, 0xff};
    static const uint8_t huge_str_key[] = {0x81, 0xdb, 0xff, 0xff, 0xff, 0xff, 'a'};
    static const uint8_t huge_array[] = {0xdd, 0x7f, 0xff, 0xff, 0xff, 0, 0, 0};
    static const uint8_t not_a_map[] = {0x93, 1, 2, 3};
    static const uint8_t id_only_negative[] = {0x81, 0xae, 'a', 'r', 'b', 'i', 't', 'r', 'a',
                                               't',  'i',  'o', 'n', '_', 'i', 'd', 0xff};
    static const uint8_t id_only_ok[] = {0x81, 0xae, 'a', 'r', 'b', 'i', 't', 'r', 'a',
                                         't',  'i',  'o', 'n', '_', 'i', 'd', 0x05};
    uint8_t trailing[sizeof id_only_ok + 1];
    memcpy(trailing, id_only_ok, sizeof id_only_ok);
    trailing[sizeof id_only_ok] = 0xc0;

    assert_int_equal(decode(state, empty, 0, &f), HV_CAN_ERR_MALFORMED);
    assert_int_equal(decode(state, never_used, sizeof never_used, &f), HV_CAN_ERR_MALFORMED);
    assert_int_equal(decode(state, huge_map, sizeof huge_map, &f), HV_CAN_ERR_MALFORMED);
    assert_int_equal(decode(state, huge_str_key, sizeof huge_str_key, &f), HV_CAN_ERR_MALFORMED);
    assert_int_equal(decode(state, huge_array, sizeof huge_array, &f), HV_CAN_ERR_MALFORMED);
    assert_int_equal(decode(state, not_a_map, sizeof not_a_map, &f), HV_CAN_ERR_MALFORMED);
    assert_int_equal(decode(state, id_only_negative, sizeof id_only_negative, &f),
                     HV_CAN_ERR_MALFORMED);
    assert_int_equal(decode(state, trailing, sizeof trailing, &f), HV_CAN_ERR_MALFORMED);
    assert_int_equal(decode(state, id_only_ok, sizeof id_only_ok - 1, &f), HV_CAN_ERR_MALFORMED);
    /* python-can's defaults: a map with only arbitration_id is an extended, empty frame */
    assert_int_equal(decode(state, id_only_ok, sizeof id_only_ok, &f), HV_OK);
    assert_int_equal(f.id, 5);
    assert_int_equal(f.flags, HV_CAN_FLAG_EXT);
    assert_int_equal(f.dlc, 0);
}

static void every_prefix_and_bit_flip_is_safe(void **state)
{
    /* no datagram derived from a valid one may crash, read out of bounds (ASan) or be
     * accepted with fields outside their domain */
    uint8_t buf[HV_CAN_UDP_MAX_DATAGRAM];
    size_t len = 0;
    hv_can_frame_t g = {0x1ABCDEF, 8, HV_CAN_FLAG_EXT, {1, 2, 3, 4, 5, 6, 7, 8}, 0};
    assert_int_equal(hv_can_udp_wire_encode(&g, 99.0, buf, sizeof buf, &len), HV_OK);
    hv_can_frame_t f;
    for (size_t n = 0; n < len; n++)
        assert_int_equal(decode(state, buf, n, &f), HV_CAN_ERR_MALFORMED);
    for (size_t i = 0; i < len; i++) {
        for (int bit = 0; bit < 8; bit++) {
            uint8_t copy[HV_CAN_UDP_MAX_DATAGRAM];
            memcpy(copy, buf, len);
            copy[i] ^= (uint8_t)(1u << bit);
            hv_status_t st = decode(state, copy, len, &f);
            if (st == HV_OK) {
                assert_true(f.dlc <= 8);
                assert_true(f.id <=
                            ((f.flags & HV_CAN_FLAG_EXT) ? HV_CAN_EFF_MASK : HV_CAN_SFF_MASK));
            } else {
                assert_true(st == HV_CAN_ERR_MALFORMED || st == HV_CAN_ERR_UNSUPPORTED);
            }
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(round_trip_all_kinds),
        cmocka_unit_test(encode_rejects_bad_frames),
        cmocka_unit_test(decodes_python_can_bytes),
        cmocka_unit_test(timestamp_beyond_int64_ns_rejected),
        cmocka_unit_test(malformed_datagrams_rejected),
        cmocka_unit_test(every_prefix_and_bit_flip_is_safe),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
