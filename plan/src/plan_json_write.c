/* Plan -> JSON text (docs/PLAN_FORMAT.md), with a small writer of our own: a growable
 * buffer, escaped strings, and numbers in the shortest form that reads back exactly. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/file_io.h"
#include "hv/plan_io.h"

typedef struct jw {
    char *buf;
    size_t len, cap;
    int failed; /* sticky: out of memory or a non-finite number */
    hv_status_t why;
} jw_t;

static void jw_put(jw_t *w, const char *s, size_t n)
{
    if (w->failed) {
        return;
    }
    if (w->len + n + 1 > w->cap) {
        size_t cap = w->cap ? w->cap : 4096;
        while (w->len + n + 1 > cap) {
            cap *= 2;
        }
        char *nb = realloc(w->buf, cap);
        if (nb == NULL) {
            w->failed = 1;
            w->why = HV_ERR_PLAN_NOMEM;
            return;
        }
        w->buf = nb;
        w->cap = cap;
    }
    memcpy(w->buf + w->len, s, n);
    w->len += n;
    w->buf[w->len] = '\0';
}

static void jw_raw(jw_t *w, const char *s)
{
    jw_put(w, s, strlen(s));
}

static void jw_str(jw_t *w, const char *s)
{
    jw_put(w, "\"", 1);
    for (const unsigned char *p = (const unsigned char *)s; *p; ++p) {
        char esc[8];
        switch (*p) {
        case '"': jw_put(w, "\\\"", 2); break;
        case '\\': jw_put(w, "\\\\", 2); break;
        case '\n': jw_put(w, "\\n", 2); break;
        case '\r': jw_put(w, "\\r", 2); break;
        case '\t': jw_put(w, "\\t", 2); break;
        case '\b': jw_put(w, "\\b", 2); break;
        case '\f': jw_put(w, "\\f", 2); break;
        default:
            if (*p < 0x20) { /* other control characters must be \u-escaped in JSON */
                snprintf(esc, sizeof esc, "\\u%04x", (unsigned)*p);
                jw_put(w, esc, 6);
            } else {
                jw_put(w, (const char *)p, 1); /* UTF-8 bytes pass through */
            }
        }
    }
    jw_put(w, "\"", 1);
}

/* Shortest of %.15g..%.17g that parses back to the same double, so files stay readable
 * (0.01, not 0.010000000000000000208) and round trips stay exact. */
static void jw_num(jw_t *w, double v)
{
    if (!isfinite(v)) {
        if (!w->failed) {
            w->failed = 1;
            w->why = HV_ERR_NAN;
        }
        return;
    }
    char tmp[40];
    for (int prec = 15; prec <= 17; ++prec) {
        snprintf(tmp, sizeof tmp, "%.*g", prec, v);
        if (strtod(tmp, NULL) == v) {
            break;
        }
    }
    jw_raw(w, tmp);
}

static void jw_key(jw_t *w, const char *k)
{
    jw_str(w, k);
    jw_put(w, ": ", 2);
}

static void jw_fmt(jw_t *w, const char *fmt, ...)
{
    char tmp[64];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n > 0) {
        jw_put(w, tmp, (size_t)n < sizeof tmp ? (size_t)n : sizeof tmp - 1);
    }
}

static void jw_picks(jw_t *w, const hv_plan_pick_t *picks, size_t n)
{
    jw_raw(w, "[");
    for (size_t k = 0; k < n; ++k) {
        const hv_plan_pick_t *pk = &picks[k];
        jw_raw(w, k ? ",\n       {" : "\n       {");
        jw_key(w, "id");
        jw_str(w, pk->id);
        jw_raw(w, ", ");
        jw_key(w, "x");
        jw_num(w, pk->x_m);
        jw_raw(w, ", ");
        jw_key(w, "y");
        jw_num(w, pk->y_m);
        jw_raw(w, ", ");
        jw_key(w, "z");
        jw_num(w, pk->z_m);
        jw_raw(w, ", ");
        jw_key(w, "yaw");
        jw_num(w, pk->yaw_rad);
        jw_raw(w, ", ");
        jw_key(w, "cost_s");
        jw_num(w, pk->cost_s);
        jw_raw(w, ", ");
        jw_key(w, "start_s");
        jw_num(w, pk->start_s);
        jw_raw(w, "}");
    }
    jw_raw(w, "]");
}

hv_status_t hv_plan_to_json(const hv_plan_t *plan, char **text, size_t *len)
{
    if (plan == NULL || text == NULL || len == NULL) {
        return HV_ERR_ARG;
    }
    jw_t w = {0};
    jw_raw(&w, "{\n  \"format\": \"harvest-plan\", \"version\": ");
    jw_fmt(&w, "%d", HV_PLAN_FORMAT_VERSION);
    jw_raw(&w, ",\n  ");
    jw_key(&w, "method");
    jw_str(&w, plan->method);

    jw_raw(&w, ",\n  ");
    jw_key(&w, "inputs");
    jw_raw(&w, "{");
    jw_key(&w, "fruit_map");
    jw_str(&w, plan->fruit_map);
    jw_raw(&w, ", ");
    jw_key(&w, "cost_table_left");
    jw_str(&w, plan->cost_table_left);
    jw_raw(&w, ", ");
    jw_key(&w, "cost_table_right");
    jw_str(&w, plan->cost_table_right);
    jw_raw(&w, ", ");
    jw_key(&w, "config");
    jw_str(&w, plan->config);
    jw_raw(&w, "}");

    jw_raw(&w, ",\n  ");
    jw_key(&w, "params");
    jw_raw(&w, "{");
    jw_key(&w, "stop_step_m");
    jw_num(&w, plan->stop_step_m);
    jw_raw(&w, ", ");
    jw_key(&w, "row_start_m");
    jw_num(&w, plan->row_start_m);
    jw_raw(&w, ", ");
    jw_key(&w, "row_length_m");
    jw_num(&w, plan->row_length_m);
    jw_raw(&w, ", ");
    jw_key(&w, "stop_penalty_s");
    jw_num(&w, plan->stop_penalty_s);
    jw_raw(&w, ", ");
    jw_key(&w, "vehicle_speed_mps");
    jw_num(&w, plan->vehicle_speed_mps);
    jw_raw(&w, ", ");
    jw_key(&w, "travel_time_s");
    jw_num(&w, plan->travel_time_s);
    jw_raw(&w, ", ");
    jw_key(&w, "stop_margin_m");
    jw_num(&w, plan->stop_margin_m);
    jw_raw(&w, ", ");
    jw_key(&w, "pick_time");
    jw_str(&w, plan->pick_time);
    jw_raw(&w, "}");

    jw_raw(&w, ",\n  ");
    jw_key(&w, "solver");
    jw_raw(&w, "{");
    jw_key(&w, "status");
    jw_str(&w, plan->solver_status);
    jw_raw(&w, ", ");
    jw_key(&w, "gap");
    if (plan->gap < 0) {
        jw_raw(&w, "null");
    } else {
        jw_num(&w, plan->gap);
    }
    jw_raw(&w, ", ");
    jw_key(&w, "nodes");
    jw_fmt(&w, "%ld", plan->nodes);
    jw_raw(&w, ", ");
    jw_key(&w, "runtime_s");
    jw_num(&w, plan->runtime_s);
    jw_raw(&w, ", ");
    jw_key(&w, "time_limit_s");
    jw_num(&w, plan->time_limit_s);
    jw_raw(&w, "}");

    jw_raw(&w, ",\n  ");
    jw_key(&w, "totals");
    jw_raw(&w, "{");
    jw_key(&w, "makespan_s");
    jw_num(&w, plan->makespan_s);
    jw_raw(&w, ", ");
    jw_key(&w, "pick_time_s");
    jw_num(&w, plan->pick_time_s);
    jw_raw(&w, ", ");
    jw_key(&w, "stop_time_s");
    jw_num(&w, plan->stop_time_s);
    jw_raw(&w, ", ");
    jw_key(&w, "travel_time_s");
    jw_num(&w, plan->total_travel_time_s);
    jw_raw(&w, ", ");
    jw_key(&w, "stops");
    jw_fmt(&w, "%zu", plan->n_stops_total);
    jw_raw(&w, ", ");
    jw_key(&w, "fruits_planned");
    jw_fmt(&w, "%zu", plan->fruits_planned);
    jw_raw(&w, ", ");
    jw_key(&w, "fruits_unreachable");
    jw_fmt(&w, "%zu", plan->fruits_unreachable);
    jw_raw(&w, ", ");
    jw_key(&w, "throughput_fruit_per_s");
    jw_num(&w, plan->throughput_fruit_per_s);
    jw_raw(&w, "}");

    if (plan->horizon.used) {
        jw_raw(&w, ",\n  ");
        jw_key(&w, "horizon");
        jw_raw(&w, "{");
        jw_key(&w, "window_m");
        jw_num(&w, plan->horizon.window_m);
        jw_raw(&w, ", ");
        jw_key(&w, "commit_m");
        jw_num(&w, plan->horizon.commit_m);
        jw_raw(&w, ", ");
        jw_key(&w, "windows");
        jw_fmt(&w, "%u", (unsigned)plan->horizon.windows);
        jw_raw(&w, ", ");
        jw_key(&w, "windows_optimal");
        jw_fmt(&w, "%u", (unsigned)plan->horizon.windows_optimal);
        jw_raw(&w, "}");
    }

    jw_raw(&w, ",\n  ");
    jw_key(&w, "stops");
    jw_raw(&w, "[");
    for (size_t s = 0; s < plan->n_stops; ++s) {
        const hv_plan_stop_t *st = &plan->stops[s];
        jw_raw(&w, s ? ",\n    {" : "\n    {");
        jw_key(&w, "index");
        jw_fmt(&w, "%u", (unsigned)st->index);
        jw_raw(&w, ", ");
        jw_key(&w, "y_m");
        jw_num(&w, st->y_m);
        jw_raw(&w, ", ");
        jw_key(&w, "pass");
        jw_fmt(&w, "%d", st->pass);
        jw_raw(&w, ",\n     ");
        jw_key(&w, "C_left_s");
        jw_num(&w, st->c_left_s);
        jw_raw(&w, ", ");
        jw_key(&w, "C_right_s");
        jw_num(&w, st->c_right_s);
        jw_raw(&w, ", ");
        jw_key(&w, "C_s");
        jw_num(&w, st->c_s);
        jw_raw(&w, ", ");
        jw_key(&w, "idle_left_s");
        jw_num(&w, st->idle_left_s);
        jw_raw(&w, ", ");
        jw_key(&w, "idle_right_s");
        jw_num(&w, st->idle_right_s);
        jw_raw(&w, ",\n     ");
        jw_key(&w, "left");
        jw_picks(&w, st->left, st->n_left);
        jw_raw(&w, ",\n     ");
        jw_key(&w, "right");
        jw_picks(&w, st->right, st->n_right);
        jw_raw(&w, "}");
    }
    jw_raw(&w, plan->n_stops ? "\n  ]" : "]");

    jw_raw(&w, ",\n  ");
    jw_key(&w, "unreachable");
    jw_raw(&w, "[");
    for (size_t u = 0; u < plan->n_unreachable; ++u) {
        const hv_plan_unreachable_t *ur = &plan->unreachable[u];
        jw_raw(&w, u ? ",\n    {" : "\n    {");
        jw_key(&w, "id");
        jw_str(&w, ur->id);
        jw_raw(&w, ", ");
        jw_key(&w, "side");
        jw_str(&w, ur->side == HV_SIDE_LEFT ? "L" : "R");
        jw_raw(&w, ", ");
        jw_key(&w, "reason");
        jw_str(&w, ur->reason);
        jw_raw(&w, "}");
    }
    jw_raw(&w, plan->n_unreachable ? "\n  ]\n}\n" : "]\n}\n");

    if (w.failed) {
        free(w.buf);
        return w.why;
    }
    *text = w.buf;
    *len = w.len;
    return HV_OK;
}

hv_status_t hv_plan_save(const char *path, const hv_plan_t *plan, char *err, size_t errlen)
{
    char *text = NULL;
    size_t len = 0;
    hv_status_t st = hv_plan_to_json(plan, &text, &len);
    if (st != HV_OK) {
        if (err != NULL && errlen > 0) {
            snprintf(err, errlen, "%s: plan: cannot serialise (%s)", path ? path : "(null)",
                     hv_plan_file_status_name(st));
        }
        return st;
    }
    st = hv_file_write_atomic(path, text, len, err, errlen);
    free(text);
    return st;
}
