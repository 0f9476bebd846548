/* Receding-horizon planning (horizon.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hv/baselines.h"
#include "hv/horizon.h"
#include "hv/plan_eval.h"
#include "hv/plan_status.h"

void hv_horizon_options_default(hv_horizon_options_t *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->window_m = HV_HORIZON_DEFAULT_WINDOW_M;
    opt->commit_m = HV_HORIZON_DEFAULT_WINDOW_M / 2.0;
    hv_milp_options_default(&opt->milp);
}

static const char *solve_name(hv_solve_status_t s)
{
    switch (s) {
    case HV_SOLVE_OPTIMAL: return "optimal";
    case HV_SOLVE_FEASIBLE: return "feasible";
    case HV_SOLVE_INFEASIBLE: return "infeasible";
    case HV_SOLVE_NO_SOLUTION: return "no solution";
    default: return "error";
    }
}

hv_status_t hv_horizon_solve(const hv_instance_t *full, const hv_horizon_options_t *opt,
                             hv_assignment_t *out, hv_horizon_result_t *res)
{
    if (full == NULL || opt == NULL || out == NULL || res == NULL ||
        out->n_fruits != full->n_fruits || full->n_stops < 2 || !isfinite(opt->window_m) ||
        !isfinite(opt->commit_m) || opt->window_m <= 0 || opt->commit_m <= 0 ||
        opt->commit_m > opt->window_m) {
        return HV_ERR_ARG;
    }
    memset(res, 0, sizeof *res);
    double step = full->stop_y_m[1] - full->stop_y_m[0];
    size_t win = (size_t)floor(opt->window_m / step + 0.5);
    size_t commit = (size_t)floor(opt->commit_m / step + 0.5);
    if (commit < 1) {
        commit = 1;
    }
    if (win < commit) {
        win = commit;
    }
    unsigned char *open = malloc(full->n_fruits ? full->n_fruits : 1);
    uint32_t *back = malloc((full->n_fruits ? full->n_fruits : 1) * sizeof *back);
    if (open == NULL || back == NULL) {
        free(open);
        free(back);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t f = 0; f < full->n_fruits; ++f) {
        out->fruit_stop[f] = HV_NO_STOP;
        open[f] = full->fruit_begin[f] != full->fruit_begin[f + 1];
    }
    hv_status_t st = HV_OK;
    size_t pos = 0;
    for (;;) {
        size_t end = pos + win + 1 < full->n_stops ? pos + win + 1 : full->n_stops;
        int last = end == full->n_stops;
        size_t commit_end = last ? end : pos + commit;
        hv_instance_t sub;
        st = hv_instance_subset(full, pos, end, open, 1, &sub, back);
        if (st != HV_OK) {
            break;
        }
        size_t committed = 0, stops = 0;
        if (sub.n_fruits > 0) {
            hv_assignment_t warm = {0, NULL}, best = {0, NULL};
            hv_milp_result_t r;
            memset(&r, 0, sizeof r);
            st = hv_assignment_alloc(&warm, sub.n_fruits);
            if (st == HV_OK) {
                st = hv_assignment_alloc(&best, sub.n_fruits);
            }
            if (st == HV_OK) {
                st = hv_fov_solve(&sub, HV_FOV_DEFAULT_WIDTH_M, &warm, NULL);
            }
            if (st == HV_OK) {
                /* no incumbent passed: the solver then starts from its own heuristic plan,
                 * much stronger than FOV (which stays the fallback below) */
                st = hv_milp_solve(&sub, &opt->milp, NULL, &best, &r);
            }
            const hv_assignment_t *use = &best;
            if (st == HV_OK && r.status != HV_SOLVE_OPTIMAL && r.status != HV_SOLVE_FEASIBLE) {
                use = &warm; /* reported below and counted as not optimal */
                r.gap = INFINITY;
            }
            if (st == HV_OK) {
                double t;
                st = hv_assignment_makespan(&sub, use, &t);
            }
            if (st == HV_OK) {
                unsigned char *seen = calloc(sub.n_stops ? sub.n_stops : 1, 1);
                for (size_t g = 0; g < sub.n_fruits && seen != NULL; ++g) {
                    uint32_t q = use->fruit_stop[g];
                    if (pos + q < commit_end) {
                        out->fruit_stop[back[g]] = (uint32_t)(pos + q);
                        open[back[g]] = 0;
                        ++committed;
                        stops += !seen[q];
                        seen[q] = 1;
                    }
                }
                if (seen == NULL) {
                    st = HV_ERR_PLAN_NOMEM;
                }
                free(seen);
                res->windows++;
                res->windows_optimal += r.status == HV_SOLVE_OPTIMAL;
                if (r.gap > res->worst_gap) {
                    res->worst_gap = r.gap;
                }
                res->nodes += r.nodes;
                res->runtime_s += r.runtime_s;
                if (opt->progress != NULL) {
                    fprintf(opt->progress,
                            "horizon: window %u y [%.2f, %.2f] m: %zu fruits, %s%s gap %.2f%%, "
                            "%.2f s; committed %zu fruits at %zu stops up to y %.2f m\n",
                            res->windows, full->stop_y_m[pos], full->stop_y_m[end - 1],
                            sub.n_fruits, solve_name(r.status),
                            use == &warm ? " (kept the FOV plan)" : "",
                            isfinite(r.gap) ? 100.0 * r.gap : 100.0, r.runtime_s, committed, stops,
                            full->stop_y_m[commit_end - 1]);
                    fflush(opt->progress);
                }
            }
            hv_assignment_free(&warm);
            hv_assignment_free(&best);
        }
        hv_instance_free(&sub);
        if (st != HV_OK || last) {
            break;
        }
        pos = commit_end;
    }
    free(open);
    free(back);
    if (st == HV_OK) {
        double t;
        st = hv_assignment_makespan(full, out, &t); /* every reachable fruit exactly once */
    }
    return st;
}
