/* Regional bounds of the branch-and-price (milp_region.h). */
#include <math.h>
#include <stdlib.h>

#include "hv/milp_region.h"
#include "hv/plan_status.h"

hv_status_t hv_region_rise(const hv_instance_t *inst, uint32_t s0, uint32_t s1, const double *pi_ms,
                           const double *v_ms, double need_ms, const hv_milp_options_t *opt,
                           const hv_milp_subsolver_t *solver, double t_deadline_s, uint32_t *plan,
                           hv_region_result_t *res)
{
    *res = (hv_region_result_t){0.0, 0.0, 0, 1, 0}; /* no fruit: a rise of 0, exactly */
    if (s0 > s1 || s1 >= inst->n_stops) {
        return HV_ERR_ARG;
    }
    size_t nf = inst->n_fruits;
    unsigned char *keep = calloc(nf + 1, 1), *shared = calloc(nf + 1, 1);
    uint32_t *full_of = malloc((nf + 1) * sizeof *full_of);
    uint32_t *sub_plan = malloc((nf + 1) * sizeof *sub_plan);
    double *skip = NULL;
    hv_instance_t sub = {0};
    hv_status_t st = keep != NULL && shared != NULL && full_of != NULL && sub_plan != NULL
                         ? HV_OK
                         : HV_ERR_PLAN_NOMEM;
    for (size_t f = 0; st == HV_OK && f < nf; ++f) {
        int in = 0, out = 0;
        for (size_t k = inst->fruit_begin[f]; k < inst->fruit_begin[f + 1]; ++k) {
            uint32_t p = inst->pairs[k].stop;
            *(p >= s0 && p <= s1 ? &in : &out) = 1;
        }
        shared[f] = (unsigned char)out;
        /* a fruit another stop can take is worth covering here only for a positive dual:
         * dropping it from a pattern never makes the pattern dearer */
        keep[f] = (unsigned char)(in && (!out || pi_ms[f] > 0.0));
    }
    if (st == HV_OK) {
        st = hv_instance_subset(inst, s0, (size_t)s1 + 1, keep, 1, &sub, full_of);
    }
    if (st == HV_OK && sub.n_fruits > 0) {
        sub.travel_time_s = 0.0;
        skip = malloc(sub.n_fruits * sizeof *skip);
        st = skip != NULL ? HV_OK : HV_ERR_PLAN_NOMEM;
        double base_ms = 0.0; /* the stretch's reduced costs = its sub-solve's value - base */
        for (size_t g = 0; st == HV_OK && g < sub.n_fruits; ++g) {
            uint32_t f = full_of[g];
            skip[g] = shared[f] ? pi_ms[f] : INFINITY;
            base_ms += pi_ms[f];
        }
        for (uint32_t p = s0; p <= s1; ++p) {
            base_ms += v_ms[p];
        }
        hv_price_bound_result_t br;
        if (st == HV_OK) {
            st = solver->bound(solver, &sub, opt, skip, base_ms + need_ms, t_deadline_s, sub_plan,
                               &br);
        }
        if (st == HV_OK) {
            res->rise_ms = isfinite(br.lb_ms) ? fmax(0.0, br.lb_ms - base_ms) : 0.0;
            res->root_rise_ms = isfinite(br.root_lb_ms) ? fmax(0.0, br.root_lb_ms - base_ms) : 0.0;
            res->nodes = br.nodes;
            res->finished = br.finished;
            res->has_plan = br.has_plan && plan != NULL;
        }
        for (size_t f = 0; res->has_plan && f < nf; ++f) {
            plan[f] = HV_NO_STOP;
        }
        for (size_t g = 0; res->has_plan && g < sub.n_fruits; ++g) {
            plan[full_of[g]] = sub_plan[g] == HV_NO_STOP ? HV_NO_STOP : s0 + sub_plan[g];
        }
    }
    hv_instance_free(&sub);
    free(skip);
    free(keep);
    free(shared);
    free(full_of);
    free(sub_plan);
    return st;
}
