/* hv_json_quote: quotes, backslashes and control characters escaped, other bytes kept, and
 * a buffer too small cut between escapes, never inside one. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "hv/json_quote.h"

static void test_escapes(void **state)
{
    (void)state;
    char out[128];
    assert_string_equal(hv_json_quote("plain", out, sizeof out), "\"plain\"");
    assert_string_equal(hv_json_quote("a \"b\" c\\d", out, sizeof out), "\"a \\\"b\\\" c\\\\d\"");
    assert_string_equal(hv_json_quote("tab\there\n", out, sizeof out), "\"tab\\u0009here\\u000a\"");
    assert_string_equal(hv_json_quote("§ y", out, sizeof out), "\"§ y\"");
    assert_string_equal(hv_json_quote(NULL, out, sizeof out), "\"\"");
}

static void test_cut_short(void **state)
{
    (void)state;
    char out[8];
    /* "ab\"c": the escape of the quote does not fit with its closing quote after "ab */
    assert_string_equal(hv_json_quote("ab\"cdef", out, 6), "\"ab\"");
    assert_string_equal(hv_json_quote("abcdefgh", out, sizeof out), "\"abcde\"");
    assert_int_equal(strlen(hv_json_quote("x", out, 1)), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_escapes),
        cmocka_unit_test(test_cut_short),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
