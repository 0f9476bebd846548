/* Row-window re-optimisation: a primal heuristic that decomposes a plan along the row
 * (internal to the MILP solvers; milp.h).
 *
 * A window is `width` consecutive stops of the plan. Its fruits are freed and re-planned
 * exactly (hv_milp_solve on the sub-instance) over every candidate stop strictly between
 * the plan's stops on either side of the window, the rest of the plan staying as it is.
 * Since the stops outside stay where they are and keep their fruits, the plan's makespan
 * changes by exactly the window's change, so an improved window is an improved plan.
 * A pass takes the windows starting every half width, the cheapest sub-problem first
 * (candidate stops times fruits); after a better window the pass starts again over the new
 * plan, the windows already solved without gain skipped (hv_window_memo_t), until a pass
 * improves nothing or time runs out.
 */
#ifndef HV_MILP_WINDOW_H
#define HV_MILP_WINDOW_H

#include <stddef.h>
#include <stdint.h>

#include "hv/milp_options.h"
#include "hv/milp_subsolve.h"
#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_window_stats {
    long windows;  /* sub-problems solved */
    long improved; /* of which gave a better window */
    long proven;   /* of which were solved to proven optimality */
    long repeats;  /* windows not solved: the memo held them (hv_window_memo_t) */
} hv_window_stats_t;

/* The windows already solved without gain, so that later passes skip them. A window is its
 * stop range and its fruits with their stops; solved again it gives the same answer (the
 * same sub-problem from the same plan, or one proven optimal). A caller-owned ring of
 * 64-bit keys: a full memo forgets its oldest, and a key collision only skips a window. */
typedef struct hv_window_memo {
    uint64_t *keys;
    size_t cap, n, next;
} hv_window_memo_t;

/* Room for `cap` windows: HV_ERR_ARG for cap 0 or no memo, HV_ERR_PLAN_NOMEM when it cannot
 * be allocated. */
hv_status_t hv_window_memo_init(hv_window_memo_t *memo, size_t cap);
/* Also safe after a failed hv_window_memo_init (it leaves the memo empty). */
void hv_window_memo_free(hv_window_memo_t *memo);

/* Called after each window that improved the plan, with the whole plan and its makespan,
 * so that a caller can use it at once: a pass over a row of 17 stops takes seconds. */
typedef void (*hv_window_better_fn)(void *ctx, const hv_assignment_t *plan, double t_s);

/* Improve `plan` (a complete plan of `inst`, makespan *t_s) window by window, `width`
 * stops each, until a pass improves nothing or the clock (CLOCK_MONOTONIC, s) reaches
 * t_deadline_s; each sub-solve gets at most window_limit_s. `opt` is copied for the
 * sub-solves (through `sub`) with their own limit, no progress output and no window
 * re-optimisation of their own. *t_s is updated with the plan. `memo` holds the windows to
 * skip and receives those solved without gain (NULL: the call keeps one of its own). stats
 * and better (with its ctx) may be NULL.
 * Returns HV_OK, or the first error of a sub-solve (HV_ERR_PLAN_NOMEM, GLPK failure);
 * the plan is left valid either way. */
hv_status_t hv_window_improve(const hv_instance_t *inst, const hv_milp_options_t *opt,
                              const hv_milp_subsolver_t *sub, unsigned width, double window_limit_s,
                              double t_deadline_s, hv_assignment_t *plan, double *t_s,
                              hv_window_stats_t *stats, hv_window_memo_t *memo,
                              hv_window_better_fn better, void *better_ctx);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_WINDOW_H */
