/* The executor's plan reader: a well-formed plan, and each kind of bad input rejected with
 * a message naming the file and the field. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "hv/exec_plan_json.h"
#include "hv/exec_status.h"

static const char *good =
    "{\"format\": \"harvest-plan\", \"version\": 2, \"method\": \"milp\",\n"
    " \"inputs\": {\"fruit_map\": \"f.csv\", \"cost_table_left\": \"l.bin\",\n"
    "            \"cost_table_right\": \"r.bin\", \"config\": \"h.cfg\"},\n"
    " \"params\": {\"stop_step_m\": 0.01, \"row_start_m\": 0.0, \"row_length_m\": 2.0,\n"
    "            \"stop_penalty_s\": 5, \"vehicle_speed_mps\": 0.1, \"travel_time_s\": 20,\n"
    "            \"stop_margin_m\": 0, \"pick_time\": \"one_way\"},\n"
    " \"solver\": {\"status\": \"optimal\", \"gap\": 0.0, \"nodes\": 1, \"runtime_s\": 0.1,\n"
    "            \"time_limit_s\": 60},\n"
    " \"totals\": {\"makespan_s\": 61.5, \"pick_time_s\": 31.5, \"stop_time_s\": 10,\n"
    "            \"travel_time_s\": 20, \"stops\": 2, \"fruits_planned\": 3,\n"
    "            \"fruits_unreachable\": 0, \"throughput_fruit_per_s\": 0.0487804878},\n"
    " \"stops\": [\n"
    "  {\"index\": 40, \"y_m\": 0.4, \"pass\": 0, \"C_left_s\": 9.5, \"C_right_s\": 0,\n"
    "   \"C_s\": 9.5, \"idle_left_s\": 0, \"idle_right_s\": 9.5, \"left\": [\n"
    "     {\"id\": \"a\\u0031\", \"x\": -0.4, \"y\": 0.45, \"z\": 0.5, \"yaw\": 0.1, \"cost_s\": "
    "4.5, \"start_s\": 0},\n"
    "     {\"id\": \"17\", \"x\": -0.41, \"y\": 0.35, \"z\": 0.6, \"yaw\": -0.2e0, \"cost_s\": 5, "
    "\"start_s\": 4.5}],\n"
    "   \"right\": []},\n"
    "  {\"index\": 120, \"y_m\": 1.2, \"pass\": 0, \"C_left_s\": 0, \"C_right_s\": 3.25,\n"
    "   \"C_s\": 3.25, \"idle_left_s\": 3.25, \"idle_right_s\": 0, \"left\": [], \"right\": [\n"
    "     {\"id\": \"17\", \"x\": 0.4, \"y\": 1.1, \"z\": 0.55, \"yaw\": 0, \"cost_s\": 3.25, "
    "\"start_s\": 0}]}\n"
    " ],\n"
    " \"unreachable\": []}\n";

static hv_exec_plan_t plan;

static hv_status_t parse(const char *text, char *err, size_t n)
{
    return hv_exec_plan_parse_json("p.json", text, strlen(text), &plan, err, n);
}

static void test_good(void **state)
{
    (void)state;
    char err[256] = "";
    assert_int_equal(parse(good, err, sizeof err), HV_OK);
    assert_int_equal(plan.n_stops, 2);
    assert_int_equal(plan.n_picks, 3);
    assert_int_equal(plan.stops[0].plan_index, 40);
    assert_int_equal(plan.stops[0].first[0], 0);
    assert_int_equal(plan.stops[0].count[0], 2);
    assert_int_equal(plan.stops[0].count[1], 0);
    assert_int_equal(plan.stops[1].first[1], 2);
    assert_int_equal(plan.stops[1].count[1], 1);
    assert_string_equal(plan.picks[0].id, "a1"); /* \u0031 decoded */
    assert_float_equal(plan.picks[1].yaw_rad, -0.2, 1e-12);
    assert_int_equal(plan.picks[2].side, HV_SIDE_RIGHT);
    assert_int_equal(plan.picks[2].stop, 1);
    assert_float_equal(plan.planned_makespan_s, 61.5, 1e-12);
    /* the same id on both sides is two fruits */
    assert_int_equal(hv_exec_plan_find(&plan, HV_SIDE_LEFT, "17"), 1);
    assert_int_equal(hv_exec_plan_find(&plan, HV_SIDE_RIGHT, "17"), 2);
    assert_int_equal(hv_exec_plan_find(&plan, HV_SIDE_RIGHT, "a1"), -1);
}

/* Replace the first occurrence of `from` in the good plan by `to`, parse, expect `code`
 * and a message containing `field`. */
static void expect(const char *from, const char *to, hv_status_t code, const char *field)
{
    char text[4096];
    const char *at = strstr(good, from);
    assert_non_null(at);
    size_t pre = (size_t)(at - good);
    snprintf(text, sizeof text, "%.*s%s%s", (int)pre, good, to, at + strlen(from));
    char err[256] = "";
    assert_int_equal(parse(text, err, sizeof err), code);
    if (!strstr(err, field) || strncmp(err, "p.json: ", 8) != 0) {
        print_error("message '%s' does not name '%s'\n", err, field);
        fail();
    }
}

static void test_bad(void **state)
{
    (void)state;
    expect("\"harvest-plan\"", "\"other\"", HV_ERR_EXEC_PLAN_FIELD, "format");
    expect("\"version\": 2", "\"version\": 1", HV_ERR_EXEC_PLAN_FIELD, "version");
    expect("\"row_length_m\": 2.0", "\"row_length\": 2.0", HV_ERR_EXEC_PLAN_FIELD,
           "params.row_length");
    expect("\"cost_s\": 5,", "\"cost_s\": \"5\",", HV_ERR_EXEC_PLAN_FIELD,
           "stops[0].left[1].cost_s");
    expect("\"cost_s\": 3.25", "\"cost_s\": -1", HV_ERR_EXEC_PLAN_FIELD,
           "stops[1].right[0].cost_s");
    expect("\"id\": \"17\", \"x\": -0.41", "\"id\": \"a1\", \"x\": -0.41", HV_ERR_EXEC_PLAN_RANGE,
           "stops[0].left[1].id");
    expect("\"id\": \"17\", \"x\": 0.4", "\"id\": \"\", \"x\": 0.4", HV_ERR_EXEC_PLAN_ID,
           "stops[1].right[0].id: empty");
    /* an id the journal could not read back: a newline (as the user wrote), a space */
    expect("\"id\": \"17\", \"x\": 0.4", "\"id\": \"1\\n7\", \"x\": 0.4", HV_ERR_EXEC_PLAN_ID,
           "stops[1].right[0].id: character 0x0a at position 2");
    expect("\"id\": \"17\", \"x\": -0.41", "\"id\": \"1 7\", \"x\": -0.41", HV_ERR_EXEC_PLAN_ID,
           "stops[0].left[1].id: character 0x20");
    /* stops out of driving order: swapped y_m, a stop listed twice, a pass going back */
    expect("\"y_m\": 1.2", "\"y_m\": 0.3", HV_ERR_EXEC_PLAN_ORDER,
           "stops[1].y_m: 0.3 not after 0.4 of stops[0] in pass 0");
    expect("\"y_m\": 1.2", "\"y_m\": 0.4", HV_ERR_EXEC_PLAN_ORDER, "stops[1].y_m: 0.4 not after");
    expect("\"y_m\": 0.4, \"pass\": 0", "\"y_m\": 0.4, \"pass\": 1", HV_ERR_EXEC_PLAN_ORDER,
           "stops[1].pass: 0 after pass 1 of stops[0]");
    expect("\"right\": []}", "\"right\": {}}", HV_ERR_EXEC_PLAN_FIELD, "stops[0].right");
    expect("\"index\": 120", "\"index\": 1.5", HV_ERR_EXEC_PLAN_FIELD, "stops[1].index");
    /* stops on the course only: the row and the plan's margin beyond each end */
    expect("\"y_m\": 1.2,", "\"y_m\": 50,", HV_ERR_EXEC_PLAN_RANGE, "stops[1].y_m");
    expect("\"y_m\": 0.4,", "\"y_m\": -0.01,", HV_ERR_EXEC_PLAN_RANGE, "stops[0].y_m");
    expect("\"stop_margin_m\": 0", "\"stop_margin_m\": -0.1", HV_ERR_EXEC_PLAN_FIELD,
           "params.stop_margin_m");
    expect("\"fruits_planned\": 3", "\"fruits_planned\": 4", HV_ERR_EXEC_PLAN_RANGE,
           "totals.fruits_planned");
    expect("\"y_m\": 1.2,", "\"y_m\": 1.2,,", HV_ERR_EXEC_PLAN_SYNTAX, "line 18");
    expect("\"z\": 0.5,", "\"z\": 05,", HV_ERR_EXEC_PLAN_SYNTAX, "invalid token");
    expect("\"unreachable\": []}", "\"unreachable\": []} x", HV_ERR_EXEC_PLAN_SYNTAX,
           "end of file expected");
    expect("\"f.csv\"", "\"f\x01\"", HV_ERR_EXEC_PLAN_SYNTAX, "control character");
    expect("\"stops\": [", "\"stops\": 7, \"x\": [", HV_ERR_EXEC_PLAN_FIELD, "unknown field");
}

static void test_capacity_and_io(void **state)
{
    (void)state;
    /* more stops than the static table holds: the good plan's header, then empty stops
     * (in driving order, so that capacity is what refuses them) */
    const char *stops_at = strstr(good, " \"stops\": [");
    assert_non_null(stops_at);
    size_t cap = 4096 + (HV_EXEC_MAX_STOPS + 1) * 200;
    char *text = malloc(cap);
    size_t n = (size_t)snprintf(text, cap, "%.*s \"stops\": [", (int)(stops_at - good), good);
    for (unsigned i = 0; i <= HV_EXEC_MAX_STOPS; i++)
        n += (size_t)snprintf(text + n, cap - n,
                              "%s{\"index\": %u, \"y_m\": %g, \"pass\": 0, \"C_left_s\": 0, "
                              "\"C_right_s\": 0, \"C_s\": 0, \"idle_left_s\": 0, "
                              "\"idle_right_s\": 0, \"left\": [], \"right\": []}",
                              i ? "," : "", i, 0.01 * i);
    snprintf(text + n, cap - n, "], \"unreachable\": []}");
    char err[256];
    assert_int_equal(parse(text, err, sizeof err), HV_ERR_EXEC_PLAN_CAPACITY);
    assert_non_null(strstr(err, "stops"));
    free(text);
    assert_int_equal(hv_exec_plan_load_json("/nonexistent/plan.json", &plan, err, sizeof err),
                     HV_ERR_IO);
    assert_non_null(strstr(err, "/nonexistent/plan.json"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_good),
        cmocka_unit_test(test_bad),
        cmocka_unit_test(test_capacity_and_io),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
