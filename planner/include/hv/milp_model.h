/* The stop-and-harvest MILP as a GLPK problem object (internal to the MILP solver).
 *
 * Columns: a_k (binary, one per reachable pair k, columns 1..n_pairs), then for every stop
 * some fruit can use: b_p (binary) and C_p (>= 0). Rows: each reachable fruit assigned
 * once; C_p - sum_{left k at p} G_k a_k >= 0 and the same for the right arm; linking
 * a_k <= b_p (or the aggregated sum_k a_k <= n_p b_p); optional side floors.
 * Objective: sum_p C_p + tau sum_p b_p + travel_s, the last a column fixed at T_travel.
 */
#ifndef HV_MILP_MODEL_H
#define HV_MILP_MODEL_H

#include <glpk.h>

#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_milp_model_opts {
    int link_disaggregated;
} hv_milp_model_opts_t;

typedef struct hv_milp_model {
    glp_prob *lp;
    int n_cols;
    int *col_b; /* per stop: column of b_p, 0 when no fruit can use the stop */
    int *col_c; /* per stop: column of C_p, 0 likewise */
    int col_travel;
    int *ia, *ja;
    double *ar;
    size_t ne;
} hv_milp_model_t;

/* Build the model; `names` set: name every row and column (for --export-lp). */
hv_status_t hv_milp_model_build(const hv_instance_t *inst, const hv_milp_model_opts_t *mo,
                                int names, hv_milp_model_t *m);
void hv_milp_model_free(hv_milp_model_t *m);

/* The model's point (x[1..n_cols]) of an assignment (a feasible one gives a feasible x). */
hv_status_t hv_milp_model_point(const hv_instance_t *inst, const hv_milp_model_t *m,
                                const uint32_t *fruit_stop, double *x);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_MODEL_H */
