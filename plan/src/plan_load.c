/* JSON tree -> hv_plan_t, checking the schema of docs/PLAN_FORMAT.md field by field.
 * Every field is required (except "horizon"), every unknown field is an error.
 * The JSON itself is parsed by jansson (strict: RFC 8259, duplicate keys and NUL in
 * strings refused); this file is the schema. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <jansson.h>

#include "hv/file_io.h"
#include "hv/fruit_id.h"
#include "hv/plan_io.h"

/* What the schema asks a value to be (jansson's integer and real are both numbers). */
typedef enum rd_kind { RD_NULL, RD_BOOL, RD_NUMBER, RD_STRING, RD_ARRAY, RD_OBJECT } rd_kind_t;

static rd_kind_t rd_kind_of(const json_t *v)
{
    switch (json_typeof(v)) {
    case JSON_OBJECT: return RD_OBJECT;
    case JSON_ARRAY: return RD_ARRAY;
    case JSON_STRING: return RD_STRING;
    case JSON_INTEGER:
    case JSON_REAL: return RD_NUMBER;
    case JSON_TRUE:
    case JSON_FALSE: return RD_BOOL;
    case JSON_NULL: break;
    }
    return RD_NULL;
}

typedef struct rd {
    const char *name; /* file name for messages */
    char *err;
    size_t errlen;
    int failed;
    hv_status_t code; /* of the first failure */
} rd_t;

/* snprintf through a va_list: field paths are diagnostics, cut short if ever too long. */
static void fmt_path(char *dst, size_t cap, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(dst, cap, fmt, ap);
    va_end(ap);
}

static void rd_vfail(rd_t *r, hv_status_t code, const char *path, const char *fmt, va_list ap)
{
    if (r->failed) {
        return;
    }
    r->failed = 1;
    r->code = code;
    if (r->err == NULL || r->errlen == 0) {
        return;
    }
    char msg[256];
    vsnprintf(msg, sizeof msg, fmt, ap);
    snprintf(r->err, r->errlen, "%s: %s: %s", r->name, path, msg);
}

/* A field missing, of the wrong type or value: HV_ERR_PLAN_FORMAT. */
static void rd_fail(rd_t *r, const char *path, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    rd_vfail(r, HV_ERR_PLAN_FORMAT, path, fmt, ap);
    va_end(ap);
}

/* A failure with its own code (a bad fruit id, stops out of order). */
static void rd_fail_code(rd_t *r, hv_status_t code, const char *path, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    rd_vfail(r, code, path, fmt, ap);
    va_end(ap);
}

/* Reject members of `obj` not in the NULL-terminated `allowed` list. */
static void rd_only(rd_t *r, const json_t *obj, const char *path, const char *const *allowed)
{
    /* jansson's iterators take a mutable object; nothing here changes it */
    for (void *it = json_object_iter((json_t *)obj); it != NULL && !r->failed;
         it = json_object_iter_next((json_t *)obj, it)) {
        const char *key = json_object_iter_key(it);
        int ok = 0;
        for (const char *const *a = allowed; *a != NULL; ++a) {
            if (strcmp(*a, key) == 0) {
                ok = 1;
                break;
            }
        }
        if (!ok) {
            char p[160];
            fmt_path(p, sizeof p, "%s%s%s", path, *path ? "." : "", key);
            rd_fail(r, p, "unknown field");
        }
    }
}

static const json_t *rd_field(rd_t *r, const json_t *obj, const char *path, const char *key,
                              rd_kind_t type, char *full, size_t fullcap)
{
    fmt_path(full, fullcap, "%s%s%s", path, *path ? "." : "", key);
    if (r->failed) {
        return NULL;
    }
    const json_t *v = json_object_get(obj, key);
    if (v == NULL) {
        rd_fail(r, full, "missing");
        return NULL;
    }
    if (rd_kind_of(v) != type) {
        static const char *const names[] = {"null",     "a boolean", "a number",
                                            "a string", "an array",  "an object"};
        rd_fail(r, full, "expected %s", names[type]);
        return NULL;
    }
    return v;
}

static double rd_num(rd_t *r, const json_t *obj, const char *path, const char *key)
{
    char full[224];
    const json_t *v = rd_field(r, obj, path, key, RD_NUMBER, full, sizeof full);
    return v ? json_number_value(v) : 0.0;
}

/* A number >= 0 (times and costs). */
static double rd_nonneg(rd_t *r, const json_t *obj, const char *path, const char *key)
{
    char full[224];
    const json_t *v = rd_field(r, obj, path, key, RD_NUMBER, full, sizeof full);
    if (v == NULL) {
        return 0.0;
    }
    if (!(json_number_value(v) >= 0.0)) {
        rd_fail(r, full, "expected a number >= 0");
        return 0.0;
    }
    return json_number_value(v);
}

/* A non-negative integer no larger than `max`. */
static double rd_count(rd_t *r, const json_t *obj, const char *path, const char *key, double max)
{
    char full[224];
    const json_t *v = rd_field(r, obj, path, key, RD_NUMBER, full, sizeof full);
    if (v == NULL) {
        return 0.0;
    }
    /* an integer literal only (jansson keeps 1.0 a real) */
    double x = json_number_value(v);
    if (!json_is_integer(v) || x < 0 || x > max) {
        rd_fail(r, full, "expected an integer in [0, %.0f]", max);
        return 0.0;
    }
    return json_number_value(v);
}

static void rd_str(rd_t *r, const json_t *obj, const char *path, const char *key, char *dst,
                   size_t cap)
{
    char full[224];
    const json_t *v = rd_field(r, obj, path, key, RD_STRING, full, sizeof full);
    if (v == NULL) {
        return;
    }
    if (hv_plan_copy_str(dst, cap, json_string_value(v)) != HV_OK) {
        rd_fail(r, full, "longer than %zu bytes", cap - 1);
    }
}

/* A fruit id: a string inside the id set (hv/fruit_id.h), so that what the executor
 * journals reads back as the same fruit. */
static void rd_id(rd_t *r, const json_t *obj, const char *path, char *dst, size_t cap)
{
    char full[224];
    const json_t *v = rd_field(r, obj, path, "id", RD_STRING, full, sizeof full);
    if (v == NULL) {
        return;
    }
    hv_diag_t d;
    if (hv_fruit_id_check(json_string_value(v), strlen(json_string_value(v)), &d) != HV_OK) {
        rd_fail_code(r, HV_ERR_PLAN_ID, full, "%s", d.message);
    } else if (hv_plan_copy_str(dst, cap, json_string_value(v)) != HV_OK) {
        rd_fail(r, full, "longer than %zu bytes", cap - 1);
    }
}

static const json_t *rd_obj(rd_t *r, const json_t *obj, const char *path, const char *key,
                            const char *const *allowed)
{
    char full[224];
    const json_t *v = rd_field(r, obj, path, key, RD_OBJECT, full, sizeof full);
    if (v != NULL) {
        rd_only(r, v, full, allowed);
    }
    return r->failed ? NULL : v;
}

static int one_of(const char *s, const char *const *list)
{
    for (; *list != NULL; ++list) {
        if (strcmp(s, *list) == 0) {
            return 1;
        }
    }
    return 0;
}

static hv_plan_pick_t *rd_picks(rd_t *r, const json_t *stop, const char *path, const char *key,
                                size_t *n_out)
{
    char full[192];
    const json_t *arr = rd_field(r, stop, path, key, RD_ARRAY, full, sizeof full);
    *n_out = 0;
    if (arr == NULL || json_array_size(arr) == 0) {
        return NULL;
    }
    hv_plan_pick_t *picks = calloc(json_array_size(arr), sizeof *picks);
    if (picks == NULL) {
        rd_fail(r, full, "out of memory");
        return NULL;
    }
    static const char *const allowed[] = {"id", "x", "y", "z", "yaw", "cost_s", "start_s", NULL};
    for (size_t k = 0; k < json_array_size(arr) && !r->failed; ++k) {
        char p[224];
        fmt_path(p, sizeof p, "%s[%zu]", full, k);
        const json_t *o = json_array_get(arr, k);
        if (!json_is_object(o)) {
            rd_fail(r, p, "expected an object");
            break;
        }
        rd_only(r, o, p, allowed);
        rd_id(r, o, p, picks[k].id, sizeof picks[k].id);
        picks[k].x_m = rd_num(r, o, p, "x");
        picks[k].y_m = rd_num(r, o, p, "y");
        picks[k].z_m = rd_num(r, o, p, "z");
        picks[k].yaw_rad = rd_num(r, o, p, "yaw");
        picks[k].cost_s = rd_nonneg(r, o, p, "cost_s");
        picks[k].start_s = rd_nonneg(r, o, p, "start_s");
    }
    *n_out = json_array_size(arr);
    return picks;
}

/* Stop s against the one before it: docs/PLAN_FORMAT.md lists stops in driving order, by
 * pass, then strictly increasing y_m (a stop listed twice is out of order too). */
static void rd_stop_order(rd_t *r, const hv_plan_stop_t *stops, size_t s)
{
    const hv_plan_stop_t *st = &stops[s], *prev = &stops[s - 1];
    char f[64];
    if (r->failed) {
        return;
    }
    if (st->pass < prev->pass) {
        fmt_path(f, sizeof f, "stops[%zu].pass", s);
        rd_fail_code(r, HV_ERR_PLAN_ORDER, f,
                     "%d after pass %d of stops[%zu] (stops are listed by pass, then "
                     "increasing y_m)",
                     st->pass, prev->pass, s - 1);
    } else if (st->pass == prev->pass && !(st->y_m > prev->y_m)) {
        fmt_path(f, sizeof f, "stops[%zu].y_m", s);
        rd_fail_code(r, HV_ERR_PLAN_ORDER, f,
                     "%.9g not after %.9g of stops[%zu] in pass %d (stops are listed by "
                     "pass, then increasing y_m)",
                     st->y_m, prev->y_m, s - 1, st->pass);
    }
}

static void rd_plan(rd_t *r, const json_t *root, hv_plan_t *plan)
{
    static const char *const top[] = {"format", "version",     "method", "inputs",
                                      "params", "solver",      "totals", "horizon",
                                      "stops",  "unreachable", NULL};
    static const char *const methods[] = {"milp", "fov", "serial", NULL};
    static const char *const statuses[] = {"optimal", "feasible",  "infeasible", "time_limit",
                                           "error",   "heuristic", NULL};
    char full[192];
    if (!json_is_object(root)) {
        rd_fail(r, "(top)", "expected an object");
        return;
    }
    rd_only(r, root, "", top);
    const json_t *f = rd_field(r, root, "", "format", RD_STRING, full, sizeof full);
    if (f != NULL && strcmp(json_string_value(f), "harvest-plan") != 0) {
        rd_fail(r, "format", "expected \"harvest-plan\", got \"%s\"", json_string_value(f));
    }
    double version = rd_count(r, root, "", "version", 1e9);
    if (!r->failed && version != HV_PLAN_FORMAT_VERSION) {
        rd_fail(r, "version", "unsupported version %.0f (this reader knows %d)", version,
                HV_PLAN_FORMAT_VERSION);
    }
    rd_str(r, root, "", "method", plan->method, sizeof plan->method);
    if (!r->failed && !one_of(plan->method, methods)) {
        rd_fail(r, "method", "expected milp, fov or serial, got \"%s\"", plan->method);
    }

    static const char *const inputs_keys[] = {"fruit_map", "cost_table_left", "cost_table_right",
                                              "config", NULL};
    const json_t *in = rd_obj(r, root, "", "inputs", inputs_keys);
    if (in != NULL) {
        rd_str(r, in, "inputs", "fruit_map", plan->fruit_map, sizeof plan->fruit_map);
        rd_str(r, in, "inputs", "cost_table_left", plan->cost_table_left,
               sizeof plan->cost_table_left);
        rd_str(r, in, "inputs", "cost_table_right", plan->cost_table_right,
               sizeof plan->cost_table_right);
        rd_str(r, in, "inputs", "config", plan->config, sizeof plan->config);
    }

    static const char *const params_keys[] = {
        "stop_step_m",    "row_start_m",       "row_length_m",
        "stop_penalty_s", "vehicle_speed_mps", "travel_time_s",
        "stop_margin_m",  "pick_time",         NULL};
    const json_t *pa = rd_obj(r, root, "", "params", params_keys);
    if (pa != NULL) {
        plan->stop_step_m = rd_num(r, pa, "params", "stop_step_m");
        plan->row_start_m = rd_num(r, pa, "params", "row_start_m");
        plan->row_length_m = rd_num(r, pa, "params", "row_length_m");
        plan->stop_penalty_s = rd_num(r, pa, "params", "stop_penalty_s");
        plan->vehicle_speed_mps = rd_num(r, pa, "params", "vehicle_speed_mps");
        plan->travel_time_s = rd_num(r, pa, "params", "travel_time_s");
        plan->stop_margin_m = rd_nonneg(r, pa, "params", "stop_margin_m");
        rd_str(r, pa, "params", "pick_time", plan->pick_time, sizeof plan->pick_time);
        static const char *const pick_times[] = {"cycle", "one_way", "cycle_flat", "one_way_flat",
                                                 NULL};
        if (!r->failed && !one_of(plan->pick_time, pick_times)) {
            rd_fail(r, "params.pick_time",
                    "expected cycle, one_way, cycle_flat or one_way_flat, got \"%s\"",
                    plan->pick_time);
        }
    }

    static const char *const solver_keys[] = {"status",    "gap",          "nodes",
                                              "runtime_s", "time_limit_s", NULL};
    const json_t *so = rd_obj(r, root, "", "solver", solver_keys);
    if (so != NULL) {
        rd_str(r, so, "solver", "status", plan->solver_status, sizeof plan->solver_status);
        if (!r->failed && !one_of(plan->solver_status, statuses)) {
            rd_fail(r, "solver.status", "unknown status \"%s\"", plan->solver_status);
        }
        const json_t *g = json_object_get(so, "gap");
        if (!r->failed && g == NULL) {
            rd_fail(r, "solver.gap", "missing");
        } else if (!r->failed && json_is_null(g)) {
            plan->gap = -1.0; /* unknown (heuristic plans) */
        } else if (!r->failed) {
            plan->gap = rd_num(r, so, "solver", "gap");
            if (!r->failed && plan->gap < 0) {
                rd_fail(r, "solver.gap", "negative");
            }
        }
        plan->nodes = (long)rd_count(r, so, "solver", "nodes", 9e15);
        plan->runtime_s = rd_num(r, so, "solver", "runtime_s");
        plan->time_limit_s = rd_num(r, so, "solver", "time_limit_s");
    }

    static const char *const totals_keys[] = {
        "makespan_s", "pick_time_s",    "stop_time_s",        "travel_time_s",
        "stops",      "fruits_planned", "fruits_unreachable", "throughput_fruit_per_s",
        NULL};
    const json_t *to = rd_obj(r, root, "", "totals", totals_keys);
    if (to != NULL) {
        plan->makespan_s = rd_num(r, to, "totals", "makespan_s");
        plan->pick_time_s = rd_num(r, to, "totals", "pick_time_s");
        plan->stop_time_s = rd_num(r, to, "totals", "stop_time_s");
        plan->total_travel_time_s = rd_num(r, to, "totals", "travel_time_s");
        plan->n_stops_total = (size_t)rd_count(r, to, "totals", "stops", 4e9);
        plan->fruits_planned = (size_t)rd_count(r, to, "totals", "fruits_planned", 4e9);
        plan->fruits_unreachable = (size_t)rd_count(r, to, "totals", "fruits_unreachable", 4e9);
        plan->throughput_fruit_per_s = rd_num(r, to, "totals", "throughput_fruit_per_s");
    }

    if (!r->failed && json_object_get(root, "horizon") != NULL) {
        static const char *const hz_keys[] = {"window_m", "commit_m", "windows", "windows_optimal",
                                              NULL};
        const json_t *hz = rd_obj(r, root, "", "horizon", hz_keys);
        if (hz != NULL) {
            plan->horizon.used = 1;
            plan->horizon.window_m = rd_num(r, hz, "horizon", "window_m");
            plan->horizon.commit_m = rd_num(r, hz, "horizon", "commit_m");
            plan->horizon.windows = (uint32_t)rd_count(r, hz, "horizon", "windows", 4e9);
            plan->horizon.windows_optimal =
                (uint32_t)rd_count(r, hz, "horizon", "windows_optimal", 4e9);
        }
    }

    const json_t *stops = rd_field(r, root, "", "stops", RD_ARRAY, full, sizeof full);
    if (stops != NULL && json_array_size(stops) > 0) {
        plan->stops = calloc(json_array_size(stops), sizeof *plan->stops);
        if (plan->stops == NULL) {
            rd_fail(r, "stops", "out of memory");
            return;
        }
        plan->n_stops = json_array_size(stops);
        static const char *const stop_keys[] = {"index",     "y_m",   "pass",        "C_left_s",
                                                "C_right_s", "C_s",   "idle_left_s", "idle_right_s",
                                                "left",      "right", NULL};
        for (size_t s = 0; s < json_array_size(stops) && !r->failed; ++s) {
            char p[64];
            fmt_path(p, sizeof p, "stops[%zu]", s);
            const json_t *o = json_array_get(stops, s);
            if (!json_is_object(o)) {
                rd_fail(r, p, "expected an object");
                break;
            }
            rd_only(r, o, p, stop_keys);
            hv_plan_stop_t *st = &plan->stops[s];
            st->index = (uint32_t)rd_count(r, o, p, "index", 4294967294.0);
            st->y_m = rd_num(r, o, p, "y_m");
            st->pass = (int)rd_count(r, o, p, "pass", 1);
            st->c_left_s = rd_num(r, o, p, "C_left_s");
            st->c_right_s = rd_num(r, o, p, "C_right_s");
            st->c_s = rd_num(r, o, p, "C_s");
            st->idle_left_s = rd_num(r, o, p, "idle_left_s");
            st->idle_right_s = rd_num(r, o, p, "idle_right_s");
            st->left = rd_picks(r, o, p, "left", &st->n_left);
            st->right = rd_picks(r, o, p, "right", &st->n_right);
            if (s > 0) {
                rd_stop_order(r, plan->stops, s);
            }
        }
    }

    const json_t *un = rd_field(r, root, "", "unreachable", RD_ARRAY, full, sizeof full);
    if (un != NULL && json_array_size(un) > 0) {
        plan->unreachable = calloc(json_array_size(un), sizeof *plan->unreachable);
        if (plan->unreachable == NULL) {
            rd_fail(r, "unreachable", "out of memory");
            return;
        }
        plan->n_unreachable = json_array_size(un);
        static const char *const un_keys[] = {"id", "side", "reason", NULL};
        for (size_t u = 0; u < json_array_size(un) && !r->failed; ++u) {
            char p[64];
            fmt_path(p, sizeof p, "unreachable[%zu]", u);
            const json_t *o = json_array_get(un, u);
            if (!json_is_object(o)) {
                rd_fail(r, p, "expected an object");
                break;
            }
            rd_only(r, o, p, un_keys);
            hv_plan_unreachable_t *ur = &plan->unreachable[u];
            rd_id(r, o, p, ur->id, sizeof ur->id);
            char side[4] = "";
            rd_str(r, o, p, "side", side, sizeof side);
            if (!r->failed) {
                if (strcmp(side, "L") == 0) {
                    ur->side = HV_SIDE_LEFT;
                } else if (strcmp(side, "R") == 0) {
                    ur->side = HV_SIDE_RIGHT;
                } else {
                    char fp[80];
                    fmt_path(fp, sizeof fp, "%s.side", p);
                    rd_fail(r, fp, "expected \"L\" or \"R\"");
                }
            }
            rd_str(r, o, p, "reason", ur->reason, sizeof ur->reason);
        }
    }
}

hv_status_t hv_plan_parse(const char *text, size_t len, const char *name, hv_plan_t *plan,
                          char *err, size_t errlen)
{
    if (plan == NULL || text == NULL) {
        return HV_ERR_ARG;
    }
    memset(plan, 0, sizeof *plan);
    if (name == NULL) {
        name = "(plan)";
    }
    json_error_t jerr;
    json_t *root = json_loadb(text, len, JSON_REJECT_DUPLICATES, &jerr);
    if (root == NULL) {
        if (err != NULL && errlen > 0) {
            snprintf(err, errlen, "%s: JSON: line %d, column %d: %s", name, jerr.line, jerr.column,
                     jerr.text);
        }
        return HV_ERR_PLAN_JSON;
    }
    rd_t r = {name, err, errlen, 0, HV_OK};
    rd_plan(&r, root, plan);
    json_decref(root);
    if (r.failed) {
        hv_plan_free(plan);
        return r.code;
    }
    return HV_OK;
}

hv_status_t hv_plan_load(const char *path, hv_plan_t *plan, char *err, size_t errlen)
{
    if (path == NULL || plan == NULL) {
        return HV_ERR_ARG;
    }
    memset(plan, 0, sizeof *plan);
    void *data = NULL;
    size_t len = 0;
    hv_status_t st = hv_file_read_all(path, &data, &len, err, errlen);
    if (st != HV_OK) {
        return st;
    }
    st = hv_plan_parse(data, len, path, plan, err, errlen);
    free(data);
    return st;
}
