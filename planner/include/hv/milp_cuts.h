/* Stop-pattern cuts for the stop-and-harvest MILP (internal; planner/SOLVER.md).
 *
 * At one stop p the model only says C_p >= C^L_p and C_p >= C^R_p, which an LP meets by
 * splitting fruits between stops so both arms finish together. For binary picks the stop
 * time is max(C^L(S), C^R(S)) of the picked set S, so for any weights w, w0 with
 *     sum_{i in S} w_i + w0 <= max(C^L(S), C^R(S))   for every subset S of a set K,
 *     w0 <= 0,
 * the inequality C_p >= sum_{i in K} w_i a_ip + w0 b_p is valid (fruits outside K only
 * raise C_p). The cut separating an LP point is found by a small LP over the subsets of K
 * (the fruits with a fractional or positive a_ip at p, at most HV_CUT_MAX_ITEMS of them).
 */
#ifndef HV_MILP_CUTS_H
#define HV_MILP_CUTS_H

#include <glpk.h>

#include "hv/milp_model.h"
#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HV_CUT_MAX_ITEMS 10

typedef struct hv_cut_sep {
    const hv_instance_t *inst;
    const hv_milp_model_t *model;
    size_t *stop_begin; /* CSR over stops: pairs of stop p are stop_pairs[stop_begin[p]..) */
    size_t *stop_pairs;
    long cuts_added;
} hv_cut_sep_t;

hv_status_t hv_cut_sep_init(hv_cut_sep_t *s, const hv_instance_t *inst,
                            const hv_milp_model_t *model);
void hv_cut_sep_free(hv_cut_sep_t *s);

/* Separate at the current node of `tree` (GLP_ICUTGEN): adds violated cuts with
 * glp_ios_add_row. Returns the number added. */
int hv_cut_separate(hv_cut_sep_t *s, glp_tree *tree);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_CUTS_H */
