/* Online planning of a row revealed by a camera (online.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hv/baselines.h"
#include "hv/grow_array.h"
#include "hv/online.h"
#include "hv/plan_eval.h"
#include "hv/plan_status.h"

const char *hv_online_verdict_name(int verdict)
{
    static const char *const names[HV_DET_COUNT] = {"accepted", "unreachable", "outside_row",
                                                    "duplicate", "late"};
    return verdict >= 0 && verdict < HV_DET_COUNT ? names[verdict] : "?";
}

void hv_online_options_default(hv_online_options_t *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->window_m = 2.0;
    opt->commit_m = 1.0;
    hv_milp_options_default(&opt->milp);
    opt->milp.time_limit_s = 10.0;
    opt->limit_min_s = 10.0;
    opt->limit_max_s = 60.0;
}

static double stop_y(const hv_online_t *o, size_t p)
{
    return o->params.row_start_m - o->params.stop_margin_m + (double)p * o->params.stop_step_m;
}

static size_t stops_of(const hv_online_t *o, double m)
{
    size_t n = (size_t)floor(m / o->params.stop_step_m + 0.5);
    return n < 1 ? 1 : n;
}

hv_status_t hv_online_init(hv_online_t *o, const hv_instance_params_t *params,
                           const hv_pick_model_t *model, const hv_online_options_t *opt)
{
    if (o == NULL || params == NULL || model == NULL || opt == NULL || !isfinite(opt->window_m) ||
        !isfinite(opt->commit_m) || opt->window_m <= 0 || opt->commit_m <= 0 ||
        opt->commit_m > opt->window_m || !(opt->limit_min_s > 0) ||
        !(opt->limit_max_s >= opt->limit_min_s)) {
        return HV_ERR_ARG;
    }
    memset(o, 0, sizeof *o);
    o->params = *params;
    o->model = model;
    o->opt = *opt;
    o->n_course_stops = hv_instance_params_stops(params);
    if (o->n_course_stops < 2) {
        return HV_ERR_PLAN_PARAMS;
    }
    o->reach_ahead_m = fmax(model->y_rel_max[0], model->y_rel_max[1]);
    o->seen_to_m = stop_y(o, 0);
    return HV_OK;
}

void hv_online_free(hv_online_t *o)
{
    if (o == NULL) {
        return;
    }
    free(o->fruits);
    free(o->fruit_stop);
    free(o->why);
    free(o->stops);
    free(o->fruit_of);
    memset(o, 0, sizeof *o);
}

/* The accepted fruit of this id, or NULL. */
static const hv_fruit_t *fruit_of_id(const hv_online_t *o, const char *id)
{
    for (size_t i = 0; i < o->n_fruits; ++i) {
        if (strcmp(o->fruits[i].id, id) == 0) {
            return &o->fruits[i];
        }
    }
    return NULL;
}

int hv_online_known(const hv_online_t *o, const hv_fruit_t *f)
{
    if (o == NULL || f == NULL || memchr(f->id, '\0', sizeof f->id) == NULL) {
        return 0;
    }
    const hv_fruit_t *k = fruit_of_id(o, f->id);
    return k != NULL && k->side == f->side && k->x_m == f->x_m && k->y_m == f->y_m &&
           k->z_m == f->z_m && k->yaw_rad == f->yaw_rad;
}

hv_status_t hv_online_detect(hv_online_t *o, const hv_fruit_t *fruit, hv_online_verdict_t *verdict)
{
    if (o == NULL || fruit == NULL || verdict == NULL ||
        memchr(fruit->id, '\0', sizeof fruit->id) == NULL) {
        return HV_ERR_ARG;
    }
    double y0 = o->params.row_start_m, y1 = y0 + o->params.row_length_m;
    hv_online_verdict_t v = HV_DET_ACCEPTED;
    if (!isfinite(fruit->x_m) || !isfinite(fruit->y_m) || !isfinite(fruit->z_m) ||
        !isfinite(fruit->yaw_rad) || fruit->y_m < y0 || fruit->y_m > y1 ||
        (fruit->side != HV_SIDE_LEFT && fruit->side != HV_SIDE_RIGHT)) {
        v = HV_DET_OUTSIDE_ROW;
    } else if (fruit_of_id(o, fruit->id) != NULL) {
        v = HV_DET_DUPLICATE;
    }
    unsigned char why = 0;
    if (v == HV_DET_ACCEPTED) {
        /* the fruit alone on the whole course: which stops reach it, or why none does */
        hv_instance_t one;
        hv_diag_t diag;
        hv_status_t st = hv_instance_build(&o->params, fruit, 1, o->model, &one, &diag);
        if (st != HV_OK) {
            return st;
        }
        size_t b = one.fruit_begin[0], e = one.fruit_begin[1];
        if (b == e) {
            v = HV_DET_UNREACHABLE;
            why = one.why != NULL && one.why[0] != 0 ? one.why[0] : HV_WHY_ROW_END;
        } else if (one.pairs[e - 1].stop < o->pos) {
            v = HV_DET_LATE; /* pairs are sorted by stop: its last reaching stop is passed */
        }
        hv_instance_free(&one);
    }
    o->counts[v]++;
    *verdict = v;
    if (v != HV_DET_ACCEPTED && v != HV_DET_UNREACHABLE) {
        return HV_OK;
    }
    size_t cap = o->cap_fruits;
    if (!hv_grow((void **)&o->fruits, &cap, o->n_fruits + 1, sizeof *o->fruits)) {
        return HV_ERR_PLAN_NOMEM;
    }
    size_t cap2 = o->cap_fruits;
    if (!hv_grow((void **)&o->fruit_stop, &cap2, o->n_fruits + 1, sizeof *o->fruit_stop)) {
        return HV_ERR_PLAN_NOMEM;
    }
    size_t cap3 = o->cap_fruits;
    if (!hv_grow((void **)&o->why, &cap3, o->n_fruits + 1, sizeof *o->why)) {
        return HV_ERR_PLAN_NOMEM;
    }
    o->cap_fruits = cap; /* all three grow from the same capacity by the same rule */
    o->fruits[o->n_fruits] = *fruit;
    o->fruit_stop[o->n_fruits] = HV_NO_STOP;
    o->why[o->n_fruits] = why;
    o->n_fruits++;
    return HV_OK;
}

void hv_online_seen(hv_online_t *o, double y_m)
{
    if (o != NULL && isfinite(y_m) && y_m > o->seen_to_m) {
        o->seen_to_m = y_m;
    }
}

static int row_seen(const hv_online_t *o)
{
    return o->seen_to_m >= o->params.row_start_m + o->params.row_length_m;
}

/* Stops [0, n) are safe to commit: no fruit beyond the seen part reaches them. */
static size_t safe_end(const hv_online_t *o)
{
    if (row_seen(o)) {
        return o->n_course_stops;
    }
    double last = (o->seen_to_m - o->reach_ahead_m - stop_y(o, 0)) / o->params.stop_step_m;
    if (last < 0) {
        return 0;
    }
    size_t n = (size_t)floor(last + 1e-9) + 1;
    return n < o->n_course_stops ? n : o->n_course_stops;
}

int hv_online_ready(const hv_online_t *o)
{
    if (o == NULL || o->done) {
        return 0;
    }
    return row_seen(o) || safe_end(o) >= o->pos + stops_of(o, o->opt.commit_m);
}

double hv_online_commit_y(const hv_online_t *o)
{
    return o->pos == 0 ? stop_y(o, 0) : stop_y(o, o->pos - 1);
}

typedef struct pick_key {
    uint32_t stop;
    int side;
    double y;
    uint32_t fruit;
} pick_key_t;

static int by_stop_side_y(const void *a, const void *b)
{
    const pick_key_t *p = a, *q = b;
    if (p->stop != q->stop)
        return p->stop < q->stop ? -1 : 1;
    if (p->side != q->side)
        return p->side < q->side ? -1 : 1;
    if (p->y != q->y)
        return p->y < q->y ? -1 : 1;
    return p->fruit < q->fruit ? -1 : p->fruit > q->fruit;
}

/* Append the committed stops [from, to) with their fruits to o->stops / o->fruit_of. */
static hv_status_t record_stops(hv_online_t *o, const uint32_t *fruits, size_t n)
{
    pick_key_t *k = malloc((n ? n : 1) * sizeof *k);
    if (k == NULL) {
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t i = 0; i < n; ++i) {
        const hv_fruit_t *f = &o->fruits[fruits[i]];
        k[i] = (pick_key_t){o->fruit_stop[fruits[i]], f->side == HV_SIDE_LEFT ? 0 : 1, f->y_m,
                            fruits[i]};
    }
    qsort(k, n, sizeof *k, by_stop_side_y);
    hv_status_t st = HV_OK;
    if (!hv_grow((void **)&o->fruit_of, &o->cap_order, o->n_order + n, sizeof *o->fruit_of)) {
        st = HV_ERR_PLAN_NOMEM;
    }
    for (size_t i = 0; i < n && st == HV_OK; ++i) {
        if (i == 0 || k[i].stop != k[i - 1].stop) {
            if (!hv_grow((void **)&o->stops, &o->cap_stops, o->n_stops + 1, sizeof *o->stops)) {
                st = HV_ERR_PLAN_NOMEM;
                break;
            }
            o->stops[o->n_stops++] =
                (hv_online_stop_t){k[i].stop, stop_y(o, k[i].stop), o->n_order, 0};
        }
        o->fruit_of[o->n_order++] = k[i].fruit;
        o->stops[o->n_stops - 1].count++;
    }
    free(k);
    return st;
}

/* Solve `sub` (the window) within r->limit_s: the MILP's plan, or the FOV plan when it
 * finds none. */
static hv_status_t solve_window(const hv_online_t *o, const hv_instance_t *sub,
                                hv_assignment_t *use, hv_online_step_result_t *r)
{
    hv_milp_options_t mo = o->opt.milp;
    mo.time_limit_s = r->limit_s;
    hv_assignment_t fov = {0, NULL};
    hv_milp_result_t mr;
    memset(&mr, 0, sizeof mr);
    hv_status_t st = hv_assignment_alloc(&fov, sub->n_fruits);
    if (st == HV_OK) {
        st = hv_fov_solve(sub, HV_FOV_DEFAULT_WIDTH_M, &fov, NULL);
    }
    if (st == HV_OK) {
        st = hv_milp_solve(sub, &mo, NULL, use, &mr);
    }
    if (st == HV_OK) {
        r->status = mr.status;
        r->gap = mr.gap;
        r->solve_s = mr.runtime_s;
        if (mr.status != HV_SOLVE_OPTIMAL && mr.status != HV_SOLVE_FEASIBLE) {
            memcpy(use->fruit_stop, fov.fruit_stop, sub->n_fruits * sizeof *use->fruit_stop);
            r->kept_heuristic = 1;
            r->gap = INFINITY;
        }
    }
    hv_assignment_free(&fov);
    return st;
}

double hv_online_horizon_limit_s(const hv_online_t *o, double ahead_s)
{
    double t = HV_ONLINE_AHEAD_SHARE * (isfinite(ahead_s) ? ahead_s : 0.0);
    return fmin(o->opt.limit_max_s, fmax(o->opt.limit_min_s, t));
}

double hv_online_stop_work_s(const hv_online_t *o, size_t k)
{
    const hv_online_stop_t *s = &o->stops[k];
    double c[2] = {0.0, 0.0};
    for (size_t i = 0; i < s->count; ++i) {
        const hv_fruit_t *f = &o->fruits[o->fruit_of[s->first + i]];
        double cost = 0.0;
        hv_pick_why_t why;
        if (o->model->cost(o->model->ctx, f, s->y_m, &cost, &why) == HV_OK) {
            c[f->side == HV_SIDE_LEFT ? 0 : 1] += cost;
        }
    }
    return fmax(c[0], c[1]) + o->params.stop_penalty_s;
}

double hv_online_ahead_s(const hv_online_t *o, size_t from, double y_m, double speed_mps)
{
    double t = 0.0;
    for (size_t k = from; k < o->n_stops; ++k) {
        t += fabs(o->stops[k].y_m - y_m) / speed_mps + hv_online_stop_work_s(o, k);
        y_m = o->stops[k].y_m;
    }
    return t;
}

static hv_status_t step_within(hv_online_t *o, double limit_s, hv_online_step_result_t *r);

hv_status_t hv_online_step(hv_online_t *o, hv_online_step_result_t *r)
{
    if (o == NULL || r == NULL) {
        return HV_ERR_ARG;
    }
    return step_within(o, o->opt.milp.time_limit_s, r);
}

hv_status_t hv_online_step_ahead(hv_online_t *o, double ahead_s, hv_online_step_result_t *r)
{
    if (o == NULL || r == NULL) {
        return HV_ERR_ARG;
    }
    return step_within(o, hv_online_horizon_limit_s(o, ahead_s), r);
}

static hv_status_t step_within(hv_online_t *o, double limit_s, hv_online_step_result_t *r)
{
    memset(r, 0, sizeof *r);
    r->stops_from = r->stops_to = o->n_stops;
    r->status = HV_SOLVE_OPTIMAL;
    r->limit_s = limit_s;
    if (!hv_online_ready(o)) {
        return HV_OK;
    }
    size_t n = o->n_course_stops, pos = o->pos;
    size_t end = pos + stops_of(o, o->opt.window_m) + 1;
    end = end < n ? end : n;
    int final = row_seen(o) && end == n;
    size_t commit_end = pos + stops_of(o, o->opt.commit_m);
    size_t safe = safe_end(o);
    commit_end = final ? n : (commit_end < safe ? commit_end : safe);
    commit_end = commit_end < n ? commit_end : n;

    /* the open fruits on the whole course, then the window's part of them */
    uint32_t *open = malloc((o->n_fruits ? o->n_fruits : 1) * sizeof *open);
    hv_fruit_t *fr = malloc((o->n_fruits ? o->n_fruits : 1) * sizeof *fr);
    uint32_t *back = malloc((o->n_fruits ? o->n_fruits : 1) * sizeof *back);
    uint32_t *done_now = malloc((o->n_fruits ? o->n_fruits : 1) * sizeof *done_now);
    hv_instance_t full, sub;
    memset(&full, 0, sizeof full);
    memset(&sub, 0, sizeof sub);
    hv_assignment_t use = {0, NULL};
    hv_status_t st = open && fr && back && done_now ? HV_OK : HV_ERR_PLAN_NOMEM;
    size_t n_open = 0, n_done = 0;
    for (size_t i = 0; st == HV_OK && i < o->n_fruits; ++i) {
        if (o->fruit_stop[i] == HV_NO_STOP && o->why[i] == 0) {
            open[n_open] = (uint32_t)i;
            fr[n_open++] = o->fruits[i];
        }
    }
    hv_diag_t diag;
    if (st == HV_OK) {
        st = hv_instance_build(&o->params, fr, n_open, o->model, &full, &diag);
    }
    if (st == HV_OK) {
        st = hv_instance_subset(&full, pos, end, NULL, 1, &sub, back);
    }
    if (st == HV_OK) {
        r->window_fruits = sub.n_fruits;
        st = hv_assignment_alloc(&use, sub.n_fruits);
    }
    if (st == HV_OK && sub.n_fruits > 0) {
        st = solve_window(o, &sub, &use, r);
        o->steps++;
        o->steps_optimal += st == HV_OK && r->status == HV_SOLVE_OPTIMAL;
    }
    for (size_t g = 0; st == HV_OK && g < sub.n_fruits; ++g) {
        size_t p = pos + use.fruit_stop[g];
        if (p < commit_end) {
            uint32_t f = open[back[g]];
            o->fruit_stop[f] = (uint32_t)p;
            done_now[n_done++] = f;
        }
    }
    if (st == HV_OK) {
        st = record_stops(o, done_now, n_done);
    }
    if (st == HV_OK) {
        r->fruits = n_done;
        r->stops_to = o->n_stops;
        o->pos = commit_end;
        o->done = commit_end == n;
        /* every open fruit must still have a stop ahead (or have been committed) */
        for (size_t k = 0; k < n_open && st == HV_OK; ++k) {
            size_t b = full.fruit_begin[k], e = full.fruit_begin[k + 1];
            if (o->fruit_stop[open[k]] == HV_NO_STOP &&
                (b == e || full.pairs[e - 1].stop < o->pos)) {
                st = HV_ERR_PLAN_UNASSIGNED;
            }
        }
    }
    hv_assignment_free(&use);
    hv_instance_free(&sub);
    hv_instance_free(&full);
    free(open);
    free(fr);
    free(back);
    free(done_now);
    return st;
}

hv_status_t hv_online_recommit(hv_online_t *o, size_t commit_end, const uint32_t *fruits,
                               const uint32_t *stops, size_t n)
{
    if (o == NULL || (n > 0 && (fruits == NULL || stops == NULL)) || o->done ||
        commit_end <= o->pos || commit_end > o->n_course_stops) {
        return HV_ERR_ARG;
    }
    for (size_t k = 0; k < n; ++k) {
        if (fruits[k] >= o->n_fruits || o->why[fruits[k]] != 0 ||
            o->fruit_stop[fruits[k]] != HV_NO_STOP || stops[k] < o->pos || stops[k] >= commit_end) {
            return HV_ERR_ARG;
        }
        for (size_t i = 0; i < k; ++i) {
            if (fruits[i] == fruits[k]) {
                return HV_ERR_ARG;
            }
        }
        /* the stop must reach the fruit, as a step's solve ensured */
        hv_pick_why_t why;
        double cost = 0.0;
        if (o->model->cost(o->model->ctx, &o->fruits[fruits[k]], stop_y(o, stops[k]), &cost,
                           &why) != HV_OK) {
            return HV_ERR_ARG;
        }
    }
    for (size_t k = 0; k < n; ++k) {
        o->fruit_stop[fruits[k]] = stops[k];
    }
    hv_status_t st = record_stops(o, fruits, n);
    if (st == HV_OK) {
        o->pos = commit_end;
        o->done = commit_end == o->n_course_stops;
    }
    return st;
}

hv_status_t hv_online_assignment(const hv_online_t *o, hv_assignment_t *a)
{
    if (o == NULL || a == NULL || a->n_fruits != o->n_fruits) {
        return HV_ERR_ARG;
    }
    if (o->n_fruits > 0) {
        memcpy(a->fruit_stop, o->fruit_stop, o->n_fruits * sizeof *a->fruit_stop);
    }
    return HV_OK;
}
