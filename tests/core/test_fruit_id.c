/* Fruit ids: every byte value is allowed or refused as the documented set says, lengths
 * 1..31 pass, and a refusal names the byte and its position. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "hv/fruit_id.h"

/* The set as docs/PLAN_FORMAT.md spells it, written out rather than as ranges. */
static const char k_allowed[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                "0123456789_.-";

static void every_byte_value(void **state)
{
    (void)state;
    for (int b = 0; b < 256; ++b) {
        char id[3] = {'a', (char)b, 'z'};
        hv_diag_t d;
        memset(&d, 0, sizeof d);
        int want_ok = b != 0 && strchr(k_allowed, b) != NULL;
        hv_status_t st = hv_fruit_id_check(id, sizeof id, &d);
        if ((st == HV_OK) != want_ok) {
            print_error("byte 0x%02x: got %s, want %s\n", b, hv_status_name(st),
                        want_ok ? "HV_OK" : "HV_ERR_FRUIT_ID");
            fail();
        }
        if (!want_ok) {
            char needle[32];
            snprintf(needle, sizeof needle, "0x%02x at position 2", b);
            assert_int_equal(st, HV_ERR_FRUIT_ID);
            assert_string_equal(d.field, "id");
            assert_non_null(strstr(d.message, needle));
        }
    }
}

static void lengths(void **state)
{
    (void)state;
    char id[HV_FRUIT_ID_MAX_CHARS + 2];
    memset(id, 'x', sizeof id);
    hv_diag_t d;
    assert_int_equal(hv_fruit_id_check(id, 1, &d), HV_OK);
    assert_int_equal(hv_fruit_id_check(id, HV_FRUIT_ID_MAX_CHARS, &d), HV_OK);
    assert_int_equal(hv_fruit_id_check(id, HV_FRUIT_ID_MAX_CHARS + 1, &d), HV_ERR_FRUIT_ID);
    assert_non_null(strstr(d.message, "more than"));
    assert_int_equal(hv_fruit_id_check(id, 0, &d), HV_ERR_FRUIT_ID);
    assert_non_null(strstr(d.message, "empty"));
    /* the length is what counts, not a NUL: an embedded NUL is a refused byte */
    assert_int_equal(hv_fruit_id_check("a\0b", 3, NULL), HV_ERR_FRUIT_ID);
    assert_int_equal(hv_fruit_id_check(NULL, 1, NULL), HV_ERR_ARG);
    assert_string_equal(hv_status_name(HV_ERR_FRUIT_ID), "HV_ERR_FRUIT_ID");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_byte_value),
        cmocka_unit_test(lengths),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
