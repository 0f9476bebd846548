/* Plan file -> hv_exec_plan_t (see exec_plan_json.h). */
#include "hv/exec_plan_json.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/exec_status.h"
#include "hv/file_io.h"
#include "json_dom.h"

typedef struct ctx {
    const char *name;
    json_doc_t doc;
    char *err;
    size_t errlen;
} ctx_t;

static hv_status_t field_err(ctx_t *c, hv_status_t code, const char *field, const char *msg)
{
    snprintf(c->err, c->errlen, "%s: %s: %s", c->name, field, msg);
    return code;
}

static hv_status_t get_num(ctx_t *c, int obj, const char *key, const char *path, double min,
                           double *out)
{
    char field[160];
    snprintf(field, sizeof field, "%s%s%s", path, path[0] ? "." : "", key);
    int n = json_get(&c->doc, obj, key);
    if (n < 0)
        return field_err(c, HV_ERR_EXEC_PLAN_FIELD, field, "missing");
    if (json_number(&c->doc, n, out) != 0)
        return field_err(c, HV_ERR_EXEC_PLAN_FIELD, field, "expected a number");
    if (!isfinite(*out) || *out < min) {
        char msg[96];
        snprintf(msg, sizeof msg, "expected a finite number >= %g", min);
        return field_err(c, HV_ERR_EXEC_PLAN_RANGE, field, msg);
    }
    return HV_OK;
}

static hv_status_t get_obj(ctx_t *c, int obj, const char *key, json_type_t type, int *out)
{
    *out = json_get(&c->doc, obj, key);
    if (*out < 0)
        return field_err(c, HV_ERR_EXEC_PLAN_FIELD, key, "missing");
    if (c->doc.nodes[*out].type != type)
        return field_err(c, HV_ERR_EXEC_PLAN_FIELD, key,
                         type == JSON_ARRAY ? "expected an array" : "expected an object");
    return HV_OK;
}

static hv_status_t read_pick(ctx_t *c, int node, const char *path, hv_side_t side,
                             uint16_t stop, hv_exec_plan_t *plan)
{
    if (c->doc.nodes[node].type != JSON_OBJECT)
        return field_err(c, HV_ERR_EXEC_PLAN_FIELD, path, "expected an object");
    if (plan->n_picks >= HV_EXEC_MAX_PICKS)
        return field_err(c, HV_ERR_EXEC_PLAN_CAPACITY, path,
                         "more picks than the executor holds (HV_EXEC_MAX_PICKS)");
    hv_exec_pick_t *pk = &plan->picks[plan->n_picks];
    memset(pk, 0, sizeof *pk);
    char field[160];
    snprintf(field, sizeof field, "%s.id", path);
    int id = json_get(&c->doc, node, "id");
    if (id < 0)
        return field_err(c, HV_ERR_EXEC_PLAN_FIELD, field, "missing");
    if (json_string(&c->doc, id, pk->id, sizeof pk->id) != 0 || pk->id[0] == '\0')
        return field_err(c, HV_ERR_EXEC_PLAN_FIELD, field,
                         "expected a non-empty ASCII string of at most 31 characters");
    for (const char *s = pk->id; *s; s++)
        if (*s <= ' ' || *s == 0x7f)
            return field_err(c, HV_ERR_EXEC_PLAN_RANGE, field,
                             "control characters or spaces are not allowed in ids");
    if (hv_exec_plan_find(plan, side, pk->id) >= 0)
        return field_err(c, HV_ERR_EXEC_PLAN_RANGE, field, "fruit planned twice");
    hv_status_t st;
    if ((st = get_num(c, node, "x", path, -INFINITY, &pk->x_m)) != HV_OK ||
        (st = get_num(c, node, "y", path, -INFINITY, &pk->y_m)) != HV_OK ||
        (st = get_num(c, node, "z", path, -INFINITY, &pk->z_m)) != HV_OK ||
        (st = get_num(c, node, "yaw", path, -INFINITY, &pk->yaw_rad)) != HV_OK ||
        (st = get_num(c, node, "cost_s", path, 0.0, &pk->cost_s)) != HV_OK ||
        (st = get_num(c, node, "start_s", path, 0.0, &pk->start_s)) != HV_OK)
        return st;
    pk->side = side;
    pk->stop = stop;
    plan->n_picks++;
    return HV_OK;
}

static hv_status_t read_stop(ctx_t *c, int node, int p, hv_exec_plan_t *plan)
{
    char path[64];
    snprintf(path, sizeof path, "stops[%d]", p);
    if (c->doc.nodes[node].type != JSON_OBJECT)
        return field_err(c, HV_ERR_EXEC_PLAN_FIELD, path, "expected an object");
    hv_exec_stop_t *st = &plan->stops[p];
    memset(st, 0, sizeof *st);
    double idx;
    hv_status_t s;
    if ((s = get_num(c, node, "index", path, 0.0, &idx)) != HV_OK ||
        (s = get_num(c, node, "y_m", path, -INFINITY, &st->y_m)) != HV_OK)
        return s;
    if (idx != floor(idx) || idx > 1e9) {
        char field[96];
        snprintf(field, sizeof field, "%s.index", path);
        return field_err(c, HV_ERR_EXEC_PLAN_RANGE, field, "expected a whole number");
    }
    st->plan_index = (uint32_t)idx;
    static const char *const side_key[2] = {"left", "right"};
    for (int side = 0; side < 2; side++) {
        char field[96];
        snprintf(field, sizeof field, "%s.%s", path, side_key[side]);
        int arr = json_get(&c->doc, node, side_key[side]);
        if (arr < 0)
            return field_err(c, HV_ERR_EXEC_PLAN_FIELD, field, "missing");
        if (c->doc.nodes[arr].type != JSON_ARRAY)
            return field_err(c, HV_ERR_EXEC_PLAN_FIELD, field, "expected an array");
        st->first[side] = plan->n_picks;
        int k = 0;
        for (int e = c->doc.nodes[arr].first; e >= 0; e = c->doc.nodes[e].next, k++) {
            char pp[128];
            snprintf(pp, sizeof pp, "%s[%d]", field, k);
            if ((s = read_pick(c, e, pp, (hv_side_t)side, (uint16_t)p, plan)) != HV_OK)
                return s;
        }
        st->count[side] = (uint16_t)k;
    }
    return HV_OK;
}

hv_status_t hv_exec_plan_parse_json(const char *name, const char *text, size_t len,
                                    hv_exec_plan_t *plan, char *err, size_t errlen)
{
    if (!name || !text || !plan || !err || errlen == 0)
        return HV_ERR_ARG;
    ctx_t c = {name, {0}, err, errlen};
    /* every value takes at least one byte of text: len + 1 nodes always suffice */
    int cap = (int)(len < 16u * 1024u * 1024u ? len + 1 : 16u * 1024u * 1024u);
    json_node_t *nodes = malloc((size_t)cap * sizeof *nodes);
    if (!nodes)
        return field_err(&c, HV_ERR_NOMEM, "(file)", "out of memory");
    char jerr[160];
    hv_status_t st = HV_OK;
    memset(plan, 0, sizeof *plan);
    if (json_parse(&c.doc, text, len, nodes, cap, jerr, sizeof jerr) != 0) {
        st = field_err(&c, HV_ERR_EXEC_PLAN_SYNTAX, "(json)", jerr);
        goto out;
    }
    int root = 0;
    if (c.doc.nodes[root].type != JSON_OBJECT) {
        st = field_err(&c, HV_ERR_EXEC_PLAN_FIELD, "(root)", "expected an object");
        goto out;
    }
    int fmt = json_get(&c.doc, root, "format");
    if (fmt < 0 || !json_string_is(&c.doc, fmt, "harvest-plan")) {
        st = field_err(&c, HV_ERR_EXEC_PLAN_FIELD, "format", "expected \"harvest-plan\"");
        goto out;
    }
    double version;
    if ((st = get_num(&c, root, "version", "", 0.0, &version)) != HV_OK)
        goto out;
    if (version != 1.0) {
        st = field_err(&c, HV_ERR_EXEC_PLAN_RANGE, "version", "only version 1 is supported");
        goto out;
    }
    int params, totals, stops;
    if ((st = get_obj(&c, root, "params", JSON_OBJECT, &params)) != HV_OK ||
        (st = get_obj(&c, root, "totals", JSON_OBJECT, &totals)) != HV_OK ||
        (st = get_obj(&c, root, "stops", JSON_ARRAY, &stops)) != HV_OK)
        goto out;
    if ((st = get_num(&c, params, "row_start_m", "params", -INFINITY, &plan->row_start_m)) !=
            HV_OK ||
        (st = get_num(&c, params, "row_length_m", "params", 0.0, &plan->row_length_m)) != HV_OK ||
        (st = get_num(&c, totals, "makespan_s", "totals", 0.0, &plan->planned_makespan_s)) !=
            HV_OK ||
        (st = get_num(&c, totals, "pick_time_s", "totals", 0.0, &plan->planned_pick_s)) != HV_OK)
        goto out;
    if (c.doc.nodes[stops].count > (int)HV_EXEC_MAX_STOPS) {
        st = field_err(&c, HV_ERR_EXEC_PLAN_CAPACITY, "stops",
                       "more stops than the executor holds (HV_EXEC_MAX_STOPS)");
        goto out;
    }
    int p = 0;
    for (int e = c.doc.nodes[stops].first; e >= 0; e = c.doc.nodes[e].next, p++) {
        if ((st = read_stop(&c, e, p, plan)) != HV_OK)
            goto out;
        plan->n_stops = (uint16_t)(p + 1);
    }
    double fruits_planned;
    if ((st = get_num(&c, totals, "fruits_planned", "totals", 0.0, &fruits_planned)) != HV_OK)
        goto out;
    if (fruits_planned != (double)plan->n_picks) {
        char msg[96];
        snprintf(msg, sizeof msg, "says %g, the stops list %u picks", fruits_planned,
                 (unsigned)plan->n_picks);
        st = field_err(&c, HV_ERR_EXEC_PLAN_RANGE, "totals.fruits_planned", msg);
        goto out;
    }
out:
    free(nodes);
    return st;
}

hv_status_t hv_exec_plan_load_json(const char *path, hv_exec_plan_t *plan, char *err,
                                   size_t errlen)
{
    void *data = NULL;
    size_t len = 0;
    char ioerr[160];
    if (hv_file_read_all(path, &data, &len, ioerr, sizeof ioerr) != HV_OK) {
        snprintf(err, errlen, "%s", ioerr);
        return HV_ERR_IO;
    }
    hv_status_t st = hv_exec_plan_parse_json(path, data, len, plan, err, errlen);
    free(data);
    return st;
}
