/* hv/can_bus.h without traffic: argument checks, closed-bus behaviour, filter matching,
 * open errors with distinct codes, status names. (Traffic is tested by the pytest suites
 * on udp in a namespace and on vcan.) */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "hv/can_bus.h"

static void closed_bus(void **state)
{
    (void)state;
    hv_can_bus_t bus;
    memset(&bus, 0, sizeof bus);
    hv_can_frame_t f = {0x123, 1, 0, {1}, 0};
    assert_int_equal(hv_can_send(&bus, &f, 0), HV_CAN_ERR_CLOSED);
    assert_int_equal(hv_can_recv(&bus, &f, 0), HV_CAN_ERR_CLOSED);
    assert_int_equal(hv_can_fd(&bus), -1);
    assert_string_equal(hv_can_name(&bus), "closed");
    hv_can_stats_t s;
    memset(&s, 0xff, sizeof s);
    assert_int_equal(hv_can_get_stats(&bus, &s), HV_OK);
    assert_true(s.tx_frames == 0 && s.rx_frames == 0);
    hv_can_close(&bus); /* harmless */
    assert_int_equal(hv_can_send(NULL, &f, 0), HV_ERR_ARG);
    assert_int_equal(hv_can_recv(&bus, NULL, 0), HV_ERR_ARG);
}

static void filter_matching(void **state)
{
    (void)state;
    const hv_can_filter_t left_arm = {0x060, 0x7E0, 0};
    const hv_can_filter_t ext_exact = {0x1234567, HV_CAN_EFF_MASK, 1};
    hv_can_frame_t f = {0x064, 8, 0, {0}, 0};
    assert_true(hv_can_filter_match(&left_arm, 1, &f));
    f.id = 0x084;
    assert_false(hv_can_filter_match(&left_arm, 1, &f));
    assert_true(hv_can_filter_match(&left_arm, 0, &f)); /* no filter: everything */
    f.id = 0x064;
    f.flags = HV_CAN_FLAG_EXT; /* same bits, 29-bit id: not a standard-id filter's frame */
    assert_false(hv_can_filter_match(&left_arm, 1, &f));
    f.id = 0x1234567;
    hv_can_filter_t both[2] = {left_arm, ext_exact};
    assert_true(hv_can_filter_match(both, 2, &f));
}

static void open_errors(void **state)
{
    (void)state;
    hv_can_bus_t bus;
    hv_can_filter_t many[HV_CAN_MAX_FILTERS + 1];
    memset(many, 0, sizeof many);
    assert_int_equal(hv_can_udp_open(&bus, "10.0.0.1", 0, NULL, NULL, 0), HV_CAN_ERR_ADDRESS);
    assert_int_equal(hv_can_udp_open(&bus, "not-an-address", 0, NULL, NULL, 0), HV_CAN_ERR_ADDRESS);
    assert_int_equal(hv_can_udp_open(&bus, NULL, 0, "127.0.0.x", NULL, 0), HV_CAN_ERR_ADDRESS);
    assert_int_equal(hv_can_udp_open(&bus, NULL, 0, NULL, many, HV_CAN_MAX_FILTERS + 1),
                     HV_CAN_ERR_FILTERS);
    assert_int_equal(hv_can_udp_open(&bus, NULL, 0, NULL, NULL, 1), HV_ERR_ARG);
    assert_int_equal(hv_can_socketcan_open(&bus, "", NULL, 0), HV_ERR_ARG);
    assert_int_equal(hv_can_socketcan_open(&bus, "a-name-longer-than-ifnamsiz", NULL, 0),
                     HV_ERR_ARG);
    assert_int_equal(hv_can_socketcan_open(&bus, "vcan0", many, HV_CAN_MAX_FILTERS + 1),
                     HV_CAN_ERR_FILTERS);
    /* no such interface: NO_DEVICE where the kernel has CAN, UNSUPPORTED where it has not */
    hv_status_t st = hv_can_socketcan_open(&bus, "hvnosuch0", NULL, 0);
    assert_true(st == HV_CAN_ERR_NO_DEVICE || st == HV_CAN_ERR_UNSUPPORTED);
    assert_int_equal(hv_can_fd(&bus), -1);
    hv_can_close(&bus); /* after a failed open: harmless */
}

static void status_names(void **state)
{
    (void)state;
    assert_string_equal(hv_can_status_name(HV_CAN_ERR_TIMEOUT), "HV_CAN_ERR_TIMEOUT");
    assert_string_equal(hv_can_status_name(HV_CAN_ERR_NOSPACE), "HV_CAN_ERR_NOSPACE");
    assert_string_equal(hv_can_status_name(HV_OK), hv_status_name(HV_OK));
    for (int code = -399; code <= -300; code++)
        assert_non_null(hv_can_status_name(code));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(closed_bus),
        cmocka_unit_test(filter_matching),
        cmocka_unit_test(open_errors),
        cmocka_unit_test(status_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
