/* Plan file -> hv_exec_plan_t (see exec_plan_json.h).
 *
 * The JSON is read by plan/'s strict plan reader (hv_plan, no GLPK); this file
 * only maps its result onto the executor's static plan and checks what the executor
 * needs beyond the format: its capacity, one pick per fruit and side, and totals that
 * agree with the stops. Fruit ids and the stops' driving order are the reader's checks. */
#include "hv/exec_plan_json.h"

#include <stdio.h>
#include <string.h>

#include "hv/exec_status.h"
#include "hv/plan_io.h"
#include "hv/plan_file_status.h"

static hv_status_t plan_err(char *err, size_t errlen, const char *name, hv_status_t code,
                            const char *field, const char *msg)
{
    snprintf(err, errlen, "%s: %s: %s", name, field, msg);
    return code;
}

static hv_status_t add_picks(const char *name, const hv_plan_pick_t *src, size_t n, hv_side_t side,
                             uint16_t stop, hv_exec_plan_t *plan, char *err, size_t errlen)
{
    static const char *const side_key[2] = {"left", "right"};
    for (size_t k = 0; k < n; k++) {
        char field[96];
        snprintf(field, sizeof field, "stops[%u].%s[%zu].id", (unsigned)stop, side_key[side], k);
        if (plan->n_picks >= HV_EXEC_MAX_PICKS) {
            return plan_err(err, errlen, name, HV_ERR_EXEC_PLAN_CAPACITY, field,
                            "more picks than the executor holds (HV_EXEC_MAX_PICKS)");
        }
        if (hv_exec_plan_find(plan, side, src[k].id) >= 0) {
            return plan_err(err, errlen, name, HV_ERR_EXEC_PLAN_RANGE, field,
                            "fruit planned twice");
        }
        hv_exec_pick_t *pk = &plan->picks[plan->n_picks++];
        memset(pk, 0, sizeof *pk);
        snprintf(pk->id, sizeof pk->id, "%s", src[k].id);
        pk->side = side;
        pk->stop = stop;
        pk->x_m = src[k].x_m;
        pk->y_m = src[k].y_m;
        pk->z_m = src[k].z_m;
        pk->yaw_rad = src[k].yaw_rad;
        pk->cost_s = src[k].cost_s;
        pk->start_s = src[k].start_s;
    }
    return HV_OK;
}

static hv_status_t from_plan(const char *name, const hv_plan_t *p, hv_exec_plan_t *plan, char *err,
                             size_t errlen)
{
    if (p->n_stops > HV_EXEC_MAX_STOPS) {
        return plan_err(err, errlen, name, HV_ERR_EXEC_PLAN_CAPACITY, "stops",
                        "more stops than the executor holds (HV_EXEC_MAX_STOPS)");
    }
    plan->row_start_m = p->row_start_m;
    plan->row_length_m = p->row_length_m;
    plan->stop_margin_m = p->stop_margin_m;
    plan->planned_makespan_s = p->makespan_s;
    plan->planned_pick_s = p->pick_time_s;
    for (size_t s = 0; s < p->n_stops; s++) {
        const hv_plan_stop_t *ps = &p->stops[s];
        hv_exec_stop_t *st = &plan->stops[s];
        memset(st, 0, sizeof *st);
        st->plan_index = ps->index;
        st->y_m = ps->y_m;
        /* the vehicle's course: the row and the plan's margin beyond each end (1 um for
         * the decimal round trip) */
        if (!(ps->y_m >= hv_exec_course_start(plan) - 1e-6 &&
              ps->y_m <= hv_exec_course_end(plan) + 1e-6)) {
            char field[32], msg[128];
            snprintf(field, sizeof field, "stops[%zu].y_m", s);
            snprintf(msg, sizeof msg,
                     "%g m is outside the course [%g, %g] m (the row and "
                     "params.stop_margin_m beyond each end)",
                     ps->y_m, hv_exec_course_start(plan), hv_exec_course_end(plan));
            return plan_err(err, errlen, name, HV_ERR_EXEC_PLAN_RANGE, field, msg);
        }
        st->first[HV_SIDE_LEFT] = plan->n_picks;
        hv_status_t r =
            add_picks(name, ps->left, ps->n_left, HV_SIDE_LEFT, (uint16_t)s, plan, err, errlen);
        if (r != HV_OK) {
            return r;
        }
        st->count[HV_SIDE_LEFT] = (uint16_t)ps->n_left;
        st->first[HV_SIDE_RIGHT] = plan->n_picks;
        r = add_picks(name, ps->right, ps->n_right, HV_SIDE_RIGHT, (uint16_t)s, plan, err, errlen);
        if (r != HV_OK) {
            return r;
        }
        st->count[HV_SIDE_RIGHT] = (uint16_t)ps->n_right;
        plan->n_stops = (uint16_t)(s + 1);
    }
    if (p->fruits_planned != plan->n_picks) {
        char msg[96];
        snprintf(msg, sizeof msg, "says %zu, the stops list %u picks", p->fruits_planned,
                 (unsigned)plan->n_picks);
        return plan_err(err, errlen, name, HV_ERR_EXEC_PLAN_RANGE, "totals.fruits_planned", msg);
    }
    return HV_OK;
}

/* The executor's code for a refusal of the planner's reader (others, e.g. HV_ERR_IO, pass). */
static hv_status_t exec_code(hv_status_t planner_code)
{
    switch ((int)planner_code) {
    case HV_ERR_PLAN_JSON: return HV_ERR_EXEC_PLAN_SYNTAX;
    case HV_ERR_PLAN_FORMAT: return HV_ERR_EXEC_PLAN_FIELD;
    case HV_ERR_PLAN_ID: return HV_ERR_EXEC_PLAN_ID;
    case HV_ERR_PLAN_ORDER: return HV_ERR_EXEC_PLAN_ORDER;
    default: return planner_code;
    }
}

hv_status_t hv_exec_plan_parse_json(const char *name, const char *text, size_t len,
                                    hv_exec_plan_t *plan, char *err, size_t errlen)
{
    if (!name || !text || !plan || !err || errlen == 0) {
        return HV_ERR_ARG;
    }
    memset(plan, 0, sizeof *plan);
    hv_plan_t p;
    hv_status_t st = hv_plan_parse(text, len, name, &p, err, errlen);
    if (st != HV_OK) {
        return exec_code(st);
    }
    st = from_plan(name, &p, plan, err, errlen);
    hv_plan_free(&p);
    return st;
}

hv_status_t hv_exec_plan_load_json(const char *path, hv_exec_plan_t *plan, char *err, size_t errlen)
{
    if (!path || !plan || !err || errlen == 0) {
        return HV_ERR_ARG;
    }
    memset(plan, 0, sizeof *plan);
    hv_plan_t p;
    hv_status_t st = hv_plan_load(path, &p, err, errlen);
    if (st != HV_OK) {
        return exec_code(st);
    }
    st = from_plan(path, &p, plan, err, errlen);
    hv_plan_free(&p);
    return st;
}
