/* The heuristic plan handed to the MILP as its first incumbent (milp.h).
 *
 * Seeds: FOV plans at several window widths (a wide window means few stops, a narrow one
 * cheap picks; which wins depends on the fruit density), each improved by the local search;
 * the best result is kept. Deterministic.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hv/fov.h"
#include "hv/milp.h"
#include "hv/milp_local_search.h"
#include "hv/plan_status.h"

static const double seed_widths_m[] = {0.20, 0.40};

hv_status_t hv_heuristic_solve(const hv_instance_t *inst, hv_assignment_t *out)
{
    if (inst == NULL || out == NULL || out->fruit_stop == NULL || out->n_fruits != inst->n_fruits) {
        return HV_ERR_ARG;
    }
    hv_assignment_t cand;
    hv_status_t st = hv_assignment_alloc(&cand, inst->n_fruits);
    if (st != HV_OK) {
        return st;
    }
    double best = INFINITY;
    hv_ls_options_t lso;
    hv_ls_options_default(&lso);
    /* a descent costs about n^2 (exchanges): keep this first search near 0.1 s; the MILP
     * polishes further only where the root gap says it is worth it */
    size_t n = inst->n_fruits ? inst->n_fruits : 1;
    lso.kicks = (unsigned)(8000 / n < 10 ? 10 : (8000 / n > 200 ? 200 : 8000 / n));
    size_t n_seeds = sizeof seed_widths_m / sizeof seed_widths_m[0];
    for (size_t i = 0; i < n_seeds && st == HV_OK; ++i) {
        st = hv_fov_solve(inst, seed_widths_m[i], &cand, NULL);
        if (st != HV_OK) {
            break;
        }
        lso.seed += 0x632be59bd9b4e019ull; /* different kicks per seed */
        double t;
        st = hv_local_search(inst, &lso, &cand, &t);
        if (st == HV_OK && t < best) {
            best = t;
            memcpy(out->fruit_stop, cand.fruit_stop, inst->n_fruits * sizeof *cand.fruit_stop);
        }
    }
    hv_assignment_free(&cand);
    return st;
}
