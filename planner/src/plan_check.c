/* Independent plan checker (plan_check.h). Deliberately shares nothing with the instance
 * builder or the evaluator: costs come straight from the pick model. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/file_io.h"
#include "hv/fruit_map.h"
#include "hv/plan_check.h"
#include "hv/plan_paths.h"

typedef struct ck {
    char *err;
    size_t errlen;
} ck_t;

static hv_status_t ck_fail(ck_t *c, hv_status_t code, const char *field, const char *fmt, ...)
{
    if (c->err != NULL && c->errlen > 0) {
        char msg[256];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, sizeof msg, fmt, ap);
        va_end(ap);
        snprintf(c->err, c->errlen, "plan check: %s: %s", field, msg);
    }
    return code;
}

static int near(double a, double b, double tol)
{
    return fabs(a - b) <= tol;
}

typedef struct id_ref {
    const char *id;
    size_t fruit;
} id_ref_t;

static int cmp_ref(const void *a, const void *b)
{
    return strcmp(((const id_ref_t *)a)->id, ((const id_ref_t *)b)->id);
}

static long find_fruit(const id_ref_t *refs, size_t n, const char *id)
{
    id_ref_t key = {id, 0};
    const id_ref_t *r = bsearch(&key, refs, n, sizeof *refs, cmp_ref);
    return r ? (long)r->fruit : -1;
}

/* The reason an unreachable fruit may be listed with (hv_instance_why_name). */
static int why_known(const char *reason)
{
    static const char *const names[] = {"height", "depth", "yaw", "row_end"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i) {
        if (strcmp(reason, names[i]) == 0) {
            return 1;
        }
    }
    return 0;
}

/* One check of a plan: its inputs, what it derives from the configuration, and what it has
 * seen and summed so far. */
typedef struct ck_run {
    ck_t c;
    const hv_plan_t *plan;
    const hv_fruit_t *fruits;
    size_t n_fruits;
    const hv_pick_model_t *model;
    double tau;      /* the stop penalty, s */
    double travel;   /* one pass over the course, s */
    double y0;       /* candidate stop 0, m */
    uint32_t n_cand; /* candidate stops */
    int serial;
    id_ref_t *refs;      /* the fruit ids, sorted */
    unsigned char *seen; /* per fruit: picked or listed unreachable */
    double pick_sum;     /* the stops' C so far */
    size_t planned;
} ck_run_t;

/* The plan's parameters against the configuration; sets what the rest derives from them. */
static hv_status_t ck_params(ck_run_t *k, const hv_config_t *cfg)
{
    const hv_plan_t *plan = k->plan;
    ck_t *c = &k->c;
    if (!(plan->stop_step_m > 0) || !isfinite(plan->stop_step_m) ||
        !near(plan->stop_step_m, cfg->grid_step_m, 1e-12)) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_PARAMS, "params.stop_step_m",
                       "%g, configuration grid.step is %g", plan->stop_step_m, cfg->grid_step_m);
    }
    k->tau = hv_config_stop_time_s(cfg);
    if (!near(plan->stop_penalty_s, k->tau, 1e-12)) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_PARAMS, "params.stop_penalty_s",
                       "%g, the configuration gives %g (plan.pick_cycle = %d)",
                       plan->stop_penalty_s, k->tau, cfg->pick_cycle);
    }
    if (strcmp(plan->pick_time, hv_pick_model_name(cfg)) != 0) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_PARAMS, "params.pick_time",
                       "\"%s\", the configuration gives \"%s\" (plan.pick_cycle = %d)",
                       plan->pick_time, hv_pick_model_name(cfg), cfg->pick_cycle);
    }
    if (!near(plan->vehicle_speed_mps, cfg->vehicle_speed_mps, 1e-12)) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_PARAMS, "params.vehicle_speed_mps",
                       "%g, configuration vehicle.speed is %g", plan->vehicle_speed_mps,
                       cfg->vehicle_speed_mps);
    }
    if (!isfinite(plan->row_start_m) || !isfinite(plan->row_length_m) || plan->row_length_m < 0 ||
        plan->row_length_m / plan->stop_step_m > 1e7) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_PARAMS, "params.row_length_m", "invalid (%g)",
                       plan->row_length_m);
    }
    double margin =
        cfg->stops_beyond_ends
            ? hv_pick_margin_of_spans(k->model->y_rel_min, k->model->y_rel_max, cfg->grid_step_m)
            : 0.0;
    if (!near(plan->stop_margin_m, margin, 1e-9)) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_PARAMS, "params.stop_margin_m",
                       "%.9g, the configuration gives %.9g (row.stops_beyond_ends = %d)",
                       plan->stop_margin_m, margin, cfg->stops_beyond_ends);
    }
    double course = plan->row_length_m + 2.0 * margin;
    k->travel = course / cfg->vehicle_speed_mps;
    if (!near(plan->travel_time_s, k->travel, HV_CHECK_TOL_S)) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_PARAMS, "params.travel_time_s",
                       "%.9g, (row length + 2 stop margin) / speed is %.9g", plan->travel_time_s,
                       k->travel);
    }
    k->y0 = plan->row_start_m - margin;
    k->serial = strcmp(plan->method, "serial") == 0;
    if (!k->serial && strcmp(plan->method, "milp") != 0 && strcmp(plan->method, "fov") != 0) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_PARAMS, "method", "unknown \"%s\"", plan->method);
    }
    k->n_cand = (uint32_t)floor(course / plan->stop_step_m + 0.5) + 1u;
    return HV_OK;
}

/* The fruit map's ids, sorted for lookup, and a seen flag per fruit. */
static hv_status_t ck_index(ck_run_t *k)
{
    size_t n = k->n_fruits ? k->n_fruits : 1;
    k->refs = malloc(n * sizeof *k->refs);
    k->seen = calloc(n, 1);
    if (k->refs == NULL || k->seen == NULL) {
        return ck_fail(&k->c, HV_ERR_PLAN_NOMEM, "checker", "out of memory");
    }
    for (size_t f = 0; f < k->n_fruits; ++f) {
        k->refs[f].id = k->fruits[f].id;
        k->refs[f].fruit = f;
    }
    qsort(k->refs, k->n_fruits, sizeof *k->refs, cmp_ref);
    return HV_OK;
}

/* Stop s itself: on the candidate grid, in driving order after (*prev_pass, *prev_y), with
 * a pick, and Serial's sides by pass. Its y is in *y. */
static hv_status_t ck_stop(ck_run_t *k, size_t s, int *prev_pass, double *prev_y, double *y)
{
    const hv_plan_stop_t *sp = &k->plan->stops[s];
    ck_t *c = &k->c;
    char field[96];
    snprintf(field, sizeof field, "stops[%zu]", s);
    if (sp->index >= k->n_cand) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_STOP, field, "index %u beyond the row's %u stops",
                       (unsigned)sp->index, (unsigned)k->n_cand);
    }
    *y = k->y0 + (double)sp->index * k->plan->stop_step_m;
    if (!near(sp->y_m, *y, 1e-9)) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_STOP, field,
                       "y_m %.9g is not candidate stop %u (y %.9g)", sp->y_m, (unsigned)sp->index,
                       *y);
    }
    if (sp->pass < 0 || sp->pass > (k->serial ? 1 : 0)) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_STOP, field, "pass %d not allowed for method %s",
                       sp->pass, k->plan->method);
    }
    if (sp->pass < *prev_pass || (sp->pass == *prev_pass && !(*y > *prev_y))) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_STOP, field,
                       "not in driving order (pass, then increasing y) or listed twice");
    }
    *prev_pass = sp->pass;
    *prev_y = *y;
    if (sp->n_left + sp->n_right == 0) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_STOP, field, "a stop with no pick (unused stop)");
    }
    if (k->serial && ((sp->pass == 0 && sp->n_right > 0) || (sp->pass == 1 && sp->n_left > 0))) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_STOP, field,
                       "serial: pass 0 picks only left fruit, pass 1 only right fruit");
    }
    return HV_OK;
}

/* Pick pk of `side`'s arm at stop s (at y): a map fruit of that side and pose, picked once,
 * reached from the stop at the model's cost, starting when the picks before it end
 * (*arm_sum, which it then extends). */
static hv_status_t ck_pick(ck_run_t *k, size_t s, int side, size_t i, double y, double *arm_sum)
{
    const hv_plan_stop_t *sp = &k->plan->stops[s];
    const hv_plan_pick_t *pk = side == 0 ? &sp->left[i] : &sp->right[i];
    ck_t *c = &k->c;
    char field[96];
    snprintf(field, sizeof field, "stops[%zu].%s[%zu] (id %s)", s, side == 0 ? "left" : "right", i,
             pk->id);
    long f = find_fruit(k->refs, k->n_fruits, pk->id);
    if (f < 0) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_UNKNOWN, field, "not in the fruit map");
    }
    const hv_fruit_t *fr = &k->fruits[f];
    if ((int)fr->side != side) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_UNKNOWN, field, "the map puts it on the other side");
    }
    if (!near(pk->x_m, fr->x_m, 1e-9) || !near(pk->y_m, fr->y_m, 1e-9) ||
        !near(pk->z_m, fr->z_m, 1e-9) || !near(pk->yaw_rad, fr->yaw_rad, 1e-9)) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_UNKNOWN, field, "pose differs from the fruit map");
    }
    if (k->seen[f]) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_DUPLICATE, field, "picked twice");
    }
    k->seen[f] = 1;
    double cost = 0.0;
    hv_pick_why_t why = HV_PICK_OK;
    hv_status_t ls = k->model->cost(k->model->ctx, fr, y, &cost, &why);
    if (ls != HV_OK) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_PAIR, field,
                       "stop %u (y %.3f) cannot reach it (%s: %s)", (unsigned)sp->index, y,
                       hv_pick_why_name(why), hv_status_name(ls));
    }
    if (!near(pk->cost_s, cost, HV_CHECK_TOL_S)) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_COST, field, "cost_s %.9g, the pick model says %.9g",
                       pk->cost_s, cost);
    }
    if (!near(pk->start_s, *arm_sum, HV_CHECK_TOL_S)) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_COST, field,
                       "start_s %.9g, the picks before it end at %.9g", pk->start_s, *arm_sum);
    }
    *arm_sum += cost;
    ++k->planned;
    return HV_OK;
}

/* Stop s's picks, then its per-arm sums, C and idle times as recomputed. */
static hv_status_t ck_stop_picks(ck_run_t *k, size_t s, double y)
{
    const hv_plan_stop_t *sp = &k->plan->stops[s];
    double arm_sum[2] = {0.0, 0.0};
    for (int side = 0; side < 2; ++side) {
        size_t np = side == 0 ? sp->n_left : sp->n_right;
        for (size_t i = 0; i < np; ++i) {
            hv_status_t st = ck_pick(k, s, side, i, y, &arm_sum[side]);
            if (st != HV_OK) {
                return st;
            }
        }
    }
    char field[96];
    snprintf(field, sizeof field, "stops[%zu]", s);
    double cs = arm_sum[0] > arm_sum[1] ? arm_sum[0] : arm_sum[1];
    const struct {
        const char *name;
        double have, want;
    } vals[5] = {{"C_left_s", sp->c_left_s, arm_sum[0]},
                 {"C_right_s", sp->c_right_s, arm_sum[1]},
                 {"C_s", sp->c_s, cs},
                 {"idle_left_s", sp->idle_left_s, cs - arm_sum[0]},
                 {"idle_right_s", sp->idle_right_s, cs - arm_sum[1]}};
    hv_status_t st = HV_OK;
    for (int v = 0; v < 5 && st == HV_OK; ++v) {
        if (!near(vals[v].have, vals[v].want, HV_CHECK_TOL_S)) {
            st = ck_fail(&k->c, HV_ERR_PLAN_CHECK_TOTAL, field, "%s %.9g, recomputed %.9g",
                         vals[v].name, vals[v].have, vals[v].want);
        }
    }
    k->pick_sum += cs;
    return st;
}

/* Unreachable fruit u: a map fruit of that side, not also picked, with a known reason, and
 * reached by no candidate stop. */
static hv_status_t ck_unreachable(ck_run_t *k, size_t u)
{
    const hv_plan_unreachable_t *ur = &k->plan->unreachable[u];
    ck_t *c = &k->c;
    char field[96];
    snprintf(field, sizeof field, "unreachable[%zu] (id %s)", u, ur->id);
    long f = find_fruit(k->refs, k->n_fruits, ur->id);
    if (f < 0) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_UNKNOWN, field, "not in the fruit map");
    }
    const hv_fruit_t *fr = &k->fruits[f];
    if (fr->side != ur->side) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_UNKNOWN, field, "the map puts it on the other side");
    }
    if (k->seen[f]) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_DUPLICATE, field, "also picked or listed twice");
    }
    k->seen[f] = 1;
    if (!why_known(ur->reason)) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_REACHABLE, field,
                       "reason \"%s\" is not height, depth, yaw or row_end", ur->reason);
    }
    for (uint32_t p = 0; p < k->n_cand; ++p) {
        double y = k->y0 + (double)p * k->plan->stop_step_m, cost = 0.0;
        hv_pick_why_t why = HV_PICK_OK;
        if (k->model->cost(k->model->ctx, fr, y, &cost, &why) == HV_OK) {
            return ck_fail(c, HV_ERR_PLAN_CHECK_REACHABLE, field,
                           "listed unreachable, but stop %u (y %.3f) reaches it in %.3f s",
                           (unsigned)p, y, cost);
        }
    }
    return HV_OK;
}

/* The totals against the sums of the stops and the lists. */
static hv_status_t ck_totals(ck_run_t *k)
{
    const hv_plan_t *plan = k->plan;
    ck_t *c = &k->c;
    size_t stops = plan->n_stops;
    double stop_time = k->tau * (double)stops;
    double travel_total = k->travel * (k->serial ? 2.0 : 1.0);
    double makespan = k->pick_sum + stop_time + travel_total;
    double thr = makespan > 0 ? (double)k->planned / makespan : 0.0;
    const struct {
        const char *name;
        double have, want;
    } tot[5] = {{"totals.pick_time_s", plan->pick_time_s, k->pick_sum},
                {"totals.stop_time_s", plan->stop_time_s, stop_time},
                {"totals.travel_time_s", plan->total_travel_time_s, travel_total},
                {"totals.makespan_s", plan->makespan_s, makespan},
                {"totals.throughput_fruit_per_s", plan->throughput_fruit_per_s, thr}};
    for (int v = 0; v < 5; ++v) {
        if (!near(tot[v].have, tot[v].want, HV_CHECK_TOL_S)) {
            return ck_fail(c, HV_ERR_PLAN_CHECK_TOTAL, tot[v].name, "%.9g, recomputed %.9g",
                           tot[v].have, tot[v].want);
        }
    }
    if (plan->n_stops_total != stops) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_TOTAL, "totals.stops", "%zu, the plan lists %zu",
                       plan->n_stops_total, stops);
    }
    if (plan->fruits_planned != k->planned) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_TOTAL, "totals.fruits_planned",
                       "%zu, the plan picks %zu", plan->fruits_planned, k->planned);
    }
    if (plan->fruits_unreachable != plan->n_unreachable) {
        return ck_fail(c, HV_ERR_PLAN_CHECK_TOTAL, "totals.fruits_unreachable",
                       "%zu, the plan lists %zu", plan->fruits_unreachable, plan->n_unreachable);
    }
    return HV_OK;
}

/* Every stop and its picks, every unreachable fruit, every map fruit accounted for, then
 * the totals; the first violation. */
static hv_status_t ck_lists(ck_run_t *k)
{
    hv_status_t st = HV_OK;
    int prev_pass = -1;
    double prev_y = 0.0, y = 0.0;
    for (size_t s = 0; s < k->plan->n_stops && st == HV_OK; ++s) {
        st = ck_stop(k, s, &prev_pass, &prev_y, &y);
        if (st == HV_OK) {
            st = ck_stop_picks(k, s, y);
        }
    }
    for (size_t u = 0; u < k->plan->n_unreachable && st == HV_OK; ++u) {
        st = ck_unreachable(k, u);
    }
    for (size_t f = 0; f < k->n_fruits && st == HV_OK; ++f) {
        if (!k->seen[f]) {
            st = ck_fail(&k->c, HV_ERR_PLAN_CHECK_MISSING, "fruit",
                         "\"%s\" is neither picked nor listed unreachable", k->fruits[f].id);
        }
    }
    return st == HV_OK ? ck_totals(k) : st;
}

hv_status_t hv_plan_check(const hv_plan_t *plan, const hv_config_t *cfg, const hv_fruit_t *fruits,
                          size_t n_fruits, const hv_pick_model_t *model, char *err, size_t errlen)
{
    ck_run_t k;
    memset(&k, 0, sizeof k);
    k.c.err = err;
    k.c.errlen = errlen;
    if (plan == NULL || cfg == NULL || (fruits == NULL && n_fruits > 0) || model == NULL ||
        model->cost == NULL) {
        return ck_fail(&k.c, HV_ERR_ARG, "arguments", "NULL");
    }
    k.plan = plan;
    k.fruits = fruits;
    k.n_fruits = n_fruits;
    k.model = model;
    hv_status_t st = ck_params(&k, cfg);
    if (st == HV_OK) {
        st = ck_index(&k);
    }
    if (st == HV_OK) {
        st = ck_lists(&k);
    }
    free(k.refs);
    free(k.seen);
    return st;
}

/* `given` when not NULL, else the plan's `input` resolved against the plan's folder. */
static hv_status_t input_path(const char *given, const char *plan_path, const char *input,
                              const char *field, char *buf, size_t cap, const char **out, char *err,
                              size_t errlen)
{
    ck_t c = {err, errlen};
    if (given != NULL) {
        *out = given;
        return HV_OK;
    }
    if (plan_path == NULL) {
        return ck_fail(&c, HV_ERR_ARG, field,
                       "no path given and no plan file to resolve "
                       "\"%s\" against",
                       input);
    }
    hv_status_t st = hv_plan_input_resolve(plan_path, input, buf, cap);
    if (st != HV_OK) {
        return ck_fail(&c, st, field, "\"%s\" in the folder of %s: %s", input, plan_path,
                       st == HV_ERR_NOMEM ? "path too long" : "empty path");
    }
    *out = buf;
    return HV_OK;
}

hv_status_t hv_plan_check_files(const hv_plan_t *plan, const char *plan_path,
                                const char *config_path, const char *left_path,
                                const char *right_path, const char *fruits_path, char *err,
                                size_t errlen)
{
    if (plan == NULL) {
        return HV_ERR_ARG;
    }
    char bufs[4][2 * HV_PLAN_PATH_LEN];
    hv_status_t st = input_path(config_path, plan_path, plan->config, "inputs.config", bufs[0],
                                sizeof bufs[0], &config_path, err, errlen);
    if (st == HV_OK) {
        st = input_path(fruits_path, plan_path, plan->fruit_map, "inputs.fruit_map", bufs[1],
                        sizeof bufs[1], &fruits_path, err, errlen);
    }
    /* tables are optional: none given here and "" in the plan means none */
    const char *tables[2] = {left_path, right_path};
    const char *in_plan[2] = {plan->cost_table_left, plan->cost_table_right};
    static const char *const fields[2] = {"inputs.cost_table_left", "inputs.cost_table_right"};
    for (int side = 0; side < 2 && st == HV_OK; ++side) {
        if (tables[side] == NULL && in_plan[side][0] != '\0') {
            st = input_path(NULL, plan_path, in_plan[side], fields[side], bufs[2 + side],
                            sizeof bufs[2 + side], &tables[side], err, errlen);
        }
    }
    if (st != HV_OK) {
        return st;
    }

    hv_config_t cfg;
    st = hv_config_load(config_path, &cfg, err, errlen);
    for (int side = 0; side < 2 && st == HV_OK; ++side) {
        if (tables[side] != NULL) {
            st = hv_costtab_check_for(tables[side], &cfg, (hv_side_t)side, err, errlen);
        }
    }
    hv_ik_model_t ik;
    hv_pick_model_t model;
    if (st == HV_OK && (st = hv_pick_model_ik(&cfg, &ik, &model)) != HV_OK && err != NULL &&
        errlen > 0) {
        snprintf(err, errlen, "%s: an arm reaches none of its fruit area (%s)", config_path,
                 hv_status_name(st));
    }
    hv_fruitmap_t map = {0, NULL};
    if (st == HV_OK) {
        hv_fruitmap_limits_t lim;
        hv_fruitmap_limits_from_config(&cfg, plan->row_start_m, plan->row_length_m, &lim);
        st = hv_fruitmap_load(fruits_path, &lim, &map, err, errlen);
    }
    if (st == HV_OK) {
        st = hv_plan_check(plan, &cfg, map.fruits, map.n, &model, err, errlen);
    }
    hv_fruitmap_free(&map);
    return st;
}
