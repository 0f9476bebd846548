#define _POSIX_C_SOURCE 200809L /* mkstemp */
/* Plan file: write -> read gives the same plan; the reader refuses malformed JSON and
 * anything that is not the plan format, naming the field. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hv/plan_io.h"

static hv_plan_pick_t pick(const char *id, double y, double cost, double start)
{
    hv_plan_pick_t p;
    memset(&p, 0, sizeof p);
    strcpy(p.id, id);
    p.x_m = 0.4123456789012345;
    p.y_m = y;
    p.z_m = 0.6;
    p.yaw_rad = -0.1;
    p.cost_s = cost;
    p.start_s = start;
    return p;
}

/* A plan with every field set to something distinct. */
static void sample(hv_plan_t *p)
{
    memset(p, 0, sizeof *p);
    strcpy(p->method, "milp");
    strcpy(p->fruit_map, "maps/a \"quoted\" \\ path\twith\ncontrol \x01 and \xc3\xa9");
    strcpy(p->cost_table_left, "L.tab");
    strcpy(p->cost_table_right, "R.tab");
    strcpy(p->config, "config/harvest.cfg");
    p->stop_step_m = 0.01;
    p->row_start_m = 0.0;
    p->row_length_m = 2.0;
    p->stop_penalty_s = 5.0;
    p->vehicle_speed_mps = 0.1;
    p->travel_time_s = 20.0;
    p->stop_margin_m = 0.5;
    strcpy(p->pick_time, "cycle");
    strcpy(p->solver_status, "feasible");
    p->gap = 0.0123;
    p->nodes = 123456;
    p->runtime_s = 1.5;
    p->time_limit_s = 60;
    p->makespan_s = 1.0 / 3.0 + 40.0;
    p->pick_time_s = 1.0 / 3.0;
    p->stop_time_s = 10.0;
    p->total_travel_time_s = 20.0;
    p->n_stops_total = 2;
    p->fruits_planned = 3;
    p->fruits_unreachable = 1;
    p->throughput_fruit_per_s = 3.0 / p->makespan_s;
    p->horizon.used = 1;
    p->horizon.window_m = 2.0;
    p->horizon.commit_m = 1.0;
    p->horizon.windows = 7;
    p->horizon.windows_optimal = 6;
    p->n_stops = 2;
    p->stops = calloc(2, sizeof *p->stops);
    p->stops[0].index = 17;
    p->stops[0].y_m = 0.17;
    p->stops[0].c_left_s = 2.1;
    p->stops[0].c_s = 2.1;
    p->stops[0].idle_right_s = 2.1;
    p->stops[0].n_left = 1;
    p->stops[0].left = calloc(1, sizeof(hv_plan_pick_t));
    p->stops[0].left[0] = pick("a1", 0.2, 2.1, 0.0);
    p->stops[1].index = 120;
    p->stops[1].y_m = 1.2;
    p->stops[1].pass = 1;
    p->stops[1].n_right = 2;
    p->stops[1].right = calloc(2, sizeof(hv_plan_pick_t));
    p->stops[1].right[0] = pick("b-7", 1.25, 2.0, 0.0);
    p->stops[1].right[1] = pick("b_8", 1.3, 2.5e-3, 2.0);
    p->n_unreachable = 1;
    p->unreachable = calloc(1, sizeof *p->unreachable);
    strcpy(p->unreachable[0].id, "u9");
    p->unreachable[0].side = HV_SIDE_RIGHT;
    strcpy(p->unreachable[0].reason, "no stop reaches it");
}

static void assert_same_pick(const hv_plan_pick_t *a, const hv_plan_pick_t *b)
{
    assert_string_equal(a->id, b->id);
    assert_true(a->x_m == b->x_m && a->y_m == b->y_m && a->z_m == b->z_m);
    assert_true(a->yaw_rad == b->yaw_rad && a->cost_s == b->cost_s && a->start_s == b->start_s);
}

static void assert_same_plan(const hv_plan_t *a, const hv_plan_t *b)
{
    assert_string_equal(a->method, b->method);
    assert_string_equal(a->fruit_map, b->fruit_map);
    assert_string_equal(a->cost_table_left, b->cost_table_left);
    assert_string_equal(a->cost_table_right, b->cost_table_right);
    assert_string_equal(a->config, b->config);
    assert_true(a->stop_step_m == b->stop_step_m && a->row_start_m == b->row_start_m);
    assert_true(a->row_length_m == b->row_length_m && a->stop_penalty_s == b->stop_penalty_s);
    assert_true(a->vehicle_speed_mps == b->vehicle_speed_mps &&
                a->travel_time_s == b->travel_time_s);
    assert_true(a->stop_margin_m == b->stop_margin_m);
    assert_string_equal(a->pick_time, b->pick_time);
    assert_string_equal(a->solver_status, b->solver_status);
    assert_true(a->gap == b->gap && a->nodes == b->nodes && a->runtime_s == b->runtime_s);
    assert_true(a->time_limit_s == b->time_limit_s);
    assert_true(a->makespan_s == b->makespan_s && a->pick_time_s == b->pick_time_s);
    assert_true(a->stop_time_s == b->stop_time_s &&
                a->total_travel_time_s == b->total_travel_time_s);
    assert_int_equal(a->n_stops_total, b->n_stops_total);
    assert_int_equal(a->fruits_planned, b->fruits_planned);
    assert_int_equal(a->fruits_unreachable, b->fruits_unreachable);
    assert_true(a->throughput_fruit_per_s == b->throughput_fruit_per_s);
    assert_int_equal(a->horizon.used, b->horizon.used);
    assert_true(a->horizon.window_m == b->horizon.window_m &&
                a->horizon.commit_m == b->horizon.commit_m);
    assert_int_equal(a->horizon.windows, b->horizon.windows);
    assert_int_equal(a->horizon.windows_optimal, b->horizon.windows_optimal);
    assert_int_equal(a->n_stops, b->n_stops);
    for (size_t s = 0; s < a->n_stops; ++s) {
        const hv_plan_stop_t *x = &a->stops[s], *y = &b->stops[s];
        assert_int_equal(x->index, y->index);
        assert_int_equal(x->pass, y->pass);
        assert_true(x->y_m == y->y_m && x->c_left_s == y->c_left_s && x->c_right_s == y->c_right_s);
        assert_true(x->c_s == y->c_s && x->idle_left_s == y->idle_left_s &&
                    x->idle_right_s == y->idle_right_s);
        assert_int_equal(x->n_left, y->n_left);
        assert_int_equal(x->n_right, y->n_right);
        for (size_t k = 0; k < x->n_left; ++k)
            assert_same_pick(&x->left[k], &y->left[k]);
        for (size_t k = 0; k < x->n_right; ++k)
            assert_same_pick(&x->right[k], &y->right[k]);
    }
    assert_int_equal(a->n_unreachable, b->n_unreachable);
    for (size_t u = 0; u < a->n_unreachable; ++u) {
        assert_string_equal(a->unreachable[u].id, b->unreachable[u].id);
        assert_int_equal(a->unreachable[u].side, b->unreachable[u].side);
        assert_string_equal(a->unreachable[u].reason, b->unreachable[u].reason);
    }
}

static void test_round_trip(void **state)
{
    (void)state;
    hv_plan_t a, b;
    sample(&a);
    char *text = NULL;
    size_t len = 0;
    assert_int_equal(hv_plan_to_json(&a, &text, &len), HV_OK);
    assert_int_equal(strlen(text), len);
    assert_non_null(strstr(text, "\"stop_step_m\": 0.01,")); /* short numbers */
    assert_non_null(strstr(text, "a \\\"quoted\\\" \\\\ path\\twith\\ncontrol \\u0001"));
    char err[256] = "";
    assert_int_equal(hv_plan_parse(text, len, "mem", &b, err, sizeof err), HV_OK);
    assert_same_plan(&a, &b);
    hv_plan_free(&b);

    /* unknown gap and no horizon survive too; and through a real file */
    a.gap = -1.0;
    a.horizon.used = 0;
    memset(&a.horizon, 0, sizeof a.horizon);
    char path[] = "/tmp/hv_plan_json_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    assert_int_equal(hv_plan_save(path, &a, err, sizeof err), HV_OK);
    assert_int_equal(hv_plan_load(path, &b, err, sizeof err), HV_OK);
    assert_true(b.gap < 0);
    assert_same_plan(&a, &b);
    unlink(path);
    hv_plan_free(&b);
    free(text);

    a.makespan_s = NAN; /* JSON has no NaN: the writer refuses */
    assert_int_equal(hv_plan_to_json(&a, &text, &len), HV_ERR_NAN);
    hv_plan_free(&a);
}

typedef struct edit {
    const char *from, *to; /* replace the first `from` in the sample's JSON by `to` */
    hv_status_t code;
    const char *in_msg;
} edit_t;

static void test_rejects(void **state)
{
    (void)state;
    static const edit_t edits[] = {
        {"\"version\": 2", "\"version\": 1", HV_ERR_PLAN_FORMAT, "mem: version: unsupported"},
        {"\"method\": \"milp\"", "\"method\": \"greedy\"", HV_ERR_PLAN_FORMAT, "method: expected"},
        {"\"stop_margin_m\": 0.5", "\"stop_margin_m\": -0.5", HV_ERR_PLAN_FORMAT,
         "params.stop_margin_m"},
        {", \"stop_margin_m\": 0.5", "", HV_ERR_PLAN_FORMAT, "params.stop_margin_m: missing"},
        {"\"pick_time\": \"cycle\"", "\"pick_time\": \"two_way\"", HV_ERR_PLAN_FORMAT,
         "params.pick_time: expected cycle, one_way, cycle_flat or one_way_flat"},
        {"\"nodes\": 123456", "\"nodes\": 1.5", HV_ERR_PLAN_FORMAT,
         "solver.nodes: expected an integer"},
        {"\"nodes\": 123456", "\"nodes\": \"many\"", HV_ERR_PLAN_FORMAT,
         "solver.nodes: expected a number"},
        {"\"cost_s\": 2.1, ", "", HV_ERR_PLAN_FORMAT, "stops[0].left[0].cost_s: missing"},
        {"\"pass\": 0", "\"pass\": 0, \"speed\": 3", HV_ERR_PLAN_FORMAT,
         "stops[0].speed: unknown field"},
        {"\"side\": \"R\"", "\"side\": \"X\"", HV_ERR_PLAN_FORMAT, "unreachable[0].side"},
        {"\"format\": \"harvest-plan\"", "\"format\": \"other\"", HV_ERR_PLAN_FORMAT, "format"},
        {"\"status\": \"feasible\"", "\"status\": \"great\"", HV_ERR_PLAN_FORMAT, "solver.status"},
        {"\"gap\": 0.0123", "\"gap\": -0.5", HV_ERR_PLAN_FORMAT, "solver.gap: negative"},
        {"\"gap\": 0.0123", "\"gap\": 0.0123,", HV_ERR_PLAN_JSON, "string or '}' expected"},
        {"\"gap\": 0.0123", "\"gap\": NaN", HV_ERR_PLAN_JSON, "invalid token near 'NaN'"},
        {"\"gap\": 0.0123", "\"gap\": 01", HV_ERR_PLAN_JSON, "invalid token"},
        {"\"gap\": 0.0123", "\"gap\": 1e999", HV_ERR_PLAN_JSON, "real number overflow"},
        {"\"gap\": 0.0123", "\"gap\": 1, \"gap\": 2", HV_ERR_PLAN_JSON, "duplicate object key"},
        {"\"L.tab\"", "\"L\\q.tab\"", HV_ERR_PLAN_JSON, "invalid escape"},
        {"\"L.tab\"", "\"L\\ud800.tab\"", HV_ERR_PLAN_JSON, "invalid Unicode"},
        {"\"L.tab\"", "\"L\\u0000.tab\"", HV_ERR_PLAN_JSON, "\\u0000 is not allowed"},
        {"\"L.tab\"", "\"L\\u00e9\\ud83c\\udf53.tab\"", HV_OK, ""}, /* é, strawberry */
        {"{\n", "[\n", HV_ERR_PLAN_JSON, "line 2, column 11: ']' expected"},
        /* fruit ids outside the id set (hv/fruit_id.h), in picks and in the unreachable list */
        {"\"id\": \"a1\"", "\"id\": \"a\\n1\"", HV_ERR_PLAN_ID,
         "mem: stops[0].left[0].id: character 0x0a at position 2"},
        {"\"id\": \"b_8\"", "\"id\": \"b 8\"", HV_ERR_PLAN_ID,
         "stops[1].right[1].id: character 0x20"},
        {"\"id\": \"u9\"", "\"id\": \"u\\u00e9\"", HV_ERR_PLAN_ID,
         "unreachable[0].id: character 0xc3"},
        {"\"id\": \"a1\"", "\"id\": \"\"", HV_ERR_PLAN_ID, "stops[0].left[0].id: empty"},
        {"\"id\": \"a1\"", "\"id\": \"a123456789012345678901234567890\"", HV_OK, ""},
        {"\"id\": \"a1\"", "\"id\": \"a1234567890123456789012345678901\"", HV_ERR_PLAN_ID,
         "stops[0].left[0].id: 32 characters, more than 31"},
        /* stops out of driving order: a pass's y_m must increase, strictly */
        {"\"y_m\": 1.2, \"pass\": 1", "\"y_m\": 0.1, \"pass\": 0", HV_ERR_PLAN_ORDER,
         "mem: stops[1].y_m: 0.1 not after 0.17 of stops[0] in pass 0"},
        {"\"y_m\": 1.2, \"pass\": 1", "\"y_m\": 0.17, \"pass\": 0", HV_ERR_PLAN_ORDER,
         "stops[1].y_m: 0.17 not after"},
        {"\"y_m\": 1.2, \"pass\": 1", "\"y_m\": 0.1, \"pass\": 1", HV_OK, ""}, /* next pass */
    };
    hv_plan_t a;
    sample(&a);
    char *text = NULL;
    size_t len = 0;
    assert_int_equal(hv_plan_to_json(&a, &text, &len), HV_OK);
    hv_plan_free(&a);
    for (size_t i = 0; i < sizeof edits / sizeof edits[0]; ++i) {
        const char *at = strstr(text, edits[i].from);
        assert_non_null(at);
        size_t nf = strlen(edits[i].from), nt = strlen(edits[i].to);
        char *mod = malloc(len - nf + nt + 1);
        size_t pre = (size_t)(at - text);
        memcpy(mod, text, pre);
        memcpy(mod + pre, edits[i].to, nt);
        memcpy(mod + pre + nt, at + nf, len - pre - nf + 1);
        hv_plan_t b;
        char err[256] = "";
        hv_status_t st = hv_plan_parse(mod, strlen(mod), "mem", &b, err, sizeof err);
        if (st != edits[i].code || strstr(err, edits[i].in_msg) == NULL) {
            print_error("edit %zu: got %s \"%s\", want %s containing \"%s\"\n", i,
                        hv_plan_file_status_name(st), err, hv_plan_file_status_name(edits[i].code),
                        edits[i].in_msg);
            fail();
        }
        if (st == HV_OK && strstr(edits[i].to, ".tab") != NULL) {
            assert_string_equal(b.cost_table_left, "L\xc3\xa9\xf0\x9f\x8d\x93.tab");
        } else if (st != HV_OK) {
            assert_null(b.stops); /* nothing kept */
        }
        hv_plan_free(&b);
        free(mod);
    }
    /* every proper prefix of a plan is refused */
    for (size_t cut = 0; cut + 2 < len; cut += 97) {
        hv_plan_t b;
        char err[256];
        assert_int_equal(hv_plan_parse(text, cut, "mem", &b, err, sizeof err), HV_ERR_PLAN_JSON);
    }
    free(text);
    hv_plan_t b;
    char err[256];
    assert_int_equal(hv_plan_load("/nonexistent/plan.json", &b, err, sizeof err), HV_ERR_IO);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_rejects),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
