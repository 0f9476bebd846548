/* Receding-horizon planning of a long row (DESIGN §5).
 *
 * From the vehicle's position (a stop index, first the row start): plan the window of
 * candidate stops covering the next window_m metres with the MILP, over every fruit not
 * yet committed that a window stop reaches; commit the stops in the first commit_m metres
 * (and their fruits), move the vehicle to the commit line, and repeat; the window that
 * reaches the end of the row commits everything. A fruit assigned beyond the commit line
 * is planned again in the next window (with the fruits that came into view), so every
 * reachable fruit ends up at exactly one committed stop: a fruit still open always has a
 * reachable stop at or after the vehicle's position.
 * Each window's MILP starts from the solver's own heuristic incumbent (hv_milp_solve with
 * no incumbent). A window whose solve returns no solution keeps an FOV plan of the window
 * instead (counted as not optimal, said in the progress line); an error aborts.
 */
#ifndef HV_HORIZON_H
#define HV_HORIZON_H

#include <stdio.h>

#include "hv/milp.h"
#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HV_HORIZON_DEFAULT_WINDOW_M 2.0

typedef struct hv_horizon_options {
    double window_m;        /* H > 0 */
    double commit_m;        /* (0, H]; default H / 2 */
    hv_milp_options_t milp; /* per window */
    FILE *progress;         /* one line per window when not NULL */
} hv_horizon_options_t;

typedef struct hv_horizon_result {
    unsigned windows; /* windows solved (those with fruit in them) */
    unsigned windows_optimal;
    double worst_gap; /* largest gap of a window */
    long nodes;
    double runtime_s; /* solver time summed over windows */
} hv_horizon_result_t;

void hv_horizon_options_default(hv_horizon_options_t *opt);

/* Plan `full` (the whole row) window by window into `out` (inst->n_fruits entries). */
hv_status_t hv_horizon_solve(const hv_instance_t *full, const hv_horizon_options_t *opt,
                             hv_assignment_t *out, hv_horizon_result_t *res);

#ifdef __cplusplus
}
#endif
#endif /* HV_HORIZON_H */
