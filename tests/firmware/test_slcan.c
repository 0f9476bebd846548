/* SLCAN lines <-> CAN frames (firmware/slcan.c): every frame formats to a line that parses
 * back to it, and every kind of bad line gets its named error. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "fw_status.h"
#include "slcan.h"

static hv_status_t parse(const char *line, hv_slcan_cmd_t *cmd, hv_can_frame_t *f)
{
    return hv_slcan_parse(line, strlen(line), cmd, f);
}

static void test_round_trip(void **state)
{
    (void)state;
    const struct {
        uint32_t id;
        uint8_t dlc, flags;
    } cases[] = {{0x021, 5, 0},
                 {0x7FF, 8, 0},
                 {0x000, 0, 0},
                 {0x1ABCDEF0, 3, HV_CAN_FLAG_EXT},
                 {0x064, 2, HV_CAN_FLAG_RTR},
                 {0x1FFFFFFF, 0, HV_CAN_FLAG_EXT | HV_CAN_FLAG_RTR}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        hv_can_frame_t f, g;
        memset(&f, 0, sizeof f);
        f.id = cases[i].id;
        f.dlc = cases[i].dlc;
        f.flags = cases[i].flags;
        for (unsigned k = 0; k < f.dlc && !(f.flags & HV_CAN_FLAG_RTR); k++)
            f.data[k] = (uint8_t)(0x5Au ^ (17u * k + i));
        char line[HV_SLCAN_LINE_MAX + 1];
        size_t n = hv_slcan_format(&f, line, sizeof line);
        assert_true(n > 1 && n <= sizeof line);
        assert_int_equal(line[n - 1], '\r');
        hv_slcan_cmd_t cmd;
        assert_int_equal(hv_slcan_parse(line, n - 1, &cmd, &g), HV_OK);
        assert_int_equal(cmd, HV_SLCAN_FRAME);
        assert_int_equal(g.id, f.id);
        assert_int_equal(g.dlc, f.dlc);
        assert_int_equal(g.flags, f.flags);
        assert_memory_equal(g.data, f.data, f.dlc);
    }
}

/* A frame with no SLCAN line is refused, never sent as another frame (found by fuzz_slcan:
 * a 12-bit id went out as its low 3 hex digits). */
static void test_frames_without_a_line(void **state)
{
    (void)state;
    static const struct {
        uint32_t id;
        uint8_t dlc, flags;
    } cases[] = {{0x800, 1, 0},
                 {0xABCDEF00, 1, 0},
                 {0x20000000, 0, HV_CAN_FLAG_EXT},
                 {0x021, 9, 0},
                 {0x021, 0, HV_CAN_FLAG_ERR}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        hv_can_frame_t f;
        memset(&f, 0, sizeof f);
        f.id = cases[i].id;
        f.dlc = cases[i].dlc;
        f.flags = cases[i].flags;
        char line[HV_SLCAN_LINE_MAX + 1];
        assert_int_equal(hv_slcan_format(&f, line, sizeof line), 0);
    }
}

static void test_known_line(void **state)
{
    (void)state;
    hv_slcan_cmd_t cmd;
    hv_can_frame_t f;
    /* lower-case hex is accepted (python-can sends upper case, other hosts do not) */
    assert_int_equal(parse("t0215a1b2C3d4E5", &cmd, &f), HV_OK);
    assert_int_equal(f.id, 0x021);
    assert_int_equal(f.dlc, 5);
    const uint8_t want[5] = {0xA1, 0xB2, 0xC3, 0xD4, 0xE5};
    assert_memory_equal(f.data, want, 5);
}

static void test_bad_lines_are_named(void **state)
{
    (void)state;
    hv_slcan_cmd_t cmd;
    hv_can_frame_t f;
    assert_int_equal(parse("t02G1AA", &cmd, &f), HV_ERR_SLCAN_HEX);        /* id */
    assert_int_equal(parse("t021XAA", &cmd, &f), HV_ERR_SLCAN_HEX);        /* DLC */
    assert_int_equal(parse("t0211AZ", &cmd, &f), HV_ERR_SLCAN_HEX);        /* data */
    assert_int_equal(parse("t0219", &cmd, &f), HV_ERR_SLCAN_LENGTH);       /* DLC > 8 */
    assert_int_equal(parse("t0212AA", &cmd, &f), HV_ERR_SLCAN_LENGTH);     /* short data */
    assert_int_equal(parse("t0211AABB", &cmd, &f), HV_ERR_SLCAN_LENGTH);   /* long data */
    assert_int_equal(parse("t02", &cmd, &f), HV_ERR_SLCAN_LENGTH);         /* no DLC */
    assert_int_equal(parse("T2000000000", &cmd, &f), HV_ERR_SLCAN_LENGTH); /* id > 29 bits */
    assert_int_equal(parse("Q", &cmd, &f), HV_ERR_SLCAN_COMMAND);
    assert_int_equal(parse("S9", &cmd, &f), HV_ERR_SLCAN_HEX);
    assert_int_equal(parse("OO", &cmd, &f), HV_ERR_SLCAN_LENGTH);
    assert_string_equal(hv_fw_status_name(HV_ERR_SLCAN_HEX), "HV_ERR_SLCAN_HEX");
    assert_string_equal(hv_fw_status_name(HV_ERR_FW_UART_OVERRUN), "HV_ERR_FW_UART_OVERRUN");
}

static void test_commands(void **state)
{
    (void)state;
    hv_slcan_cmd_t cmd;
    hv_can_frame_t f;
    assert_int_equal(parse("O", &cmd, &f), HV_OK);
    assert_int_equal(cmd, HV_SLCAN_OPEN);
    assert_int_equal(parse("C", &cmd, &f), HV_OK);
    assert_int_equal(cmd, HV_SLCAN_CLOSE);
    assert_int_equal(parse("S6", &cmd, &f), HV_OK);
    assert_int_equal(cmd, HV_SLCAN_BITRATE);
    assert_int_equal(parse("", &cmd, &f), HV_OK);
    assert_int_equal(cmd, HV_SLCAN_NONE);
}

static void test_feed_lines(void **state)
{
    (void)state;
    hv_slcan_rx_t rx;
    memset(&rx, 0, sizeof rx);
    const char *in = "O\rt0210\r";
    int lines = 0;
    for (const char *p = in; *p; p++) {
        int r = hv_slcan_feed(&rx, (uint8_t)*p);
        assert_true(r == 0 || r == 1);
        if (r == 1) {
            assert_string_equal(rx.line, lines == 0 ? "O" : "t0210");
            assert_int_equal(rx.done, lines == 0 ? 1 : 5);
            lines++;
        }
    }
    assert_int_equal(lines, 2);
    /* a line longer than any command: dropped at its CR with a named error, then the next
     * line is read whole */
    for (int i = 0; i < 40; i++)
        assert_int_equal(hv_slcan_feed(&rx, 'A'), 0);
    assert_int_equal(hv_slcan_feed(&rx, '\r'), HV_ERR_SLCAN_LINE_LONG);
    assert_int_equal(hv_slcan_feed(&rx, 'C'), 0);
    assert_int_equal(hv_slcan_feed(&rx, '\r'), 1);
    assert_string_equal(rx.line, "C");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),          cmocka_unit_test(test_known_line),
        cmocka_unit_test(test_bad_lines_are_named), cmocka_unit_test(test_commands),
        cmocka_unit_test(test_feed_lines),          cmocka_unit_test(test_frames_without_a_line),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
