/* The paper's baselines (DESIGN §1, §5; paper §IV.B), on the same instance as the MILP, so
 * the plans compare on equal terms.
 *
 * FOV ("non-optimised"): one camera window per arm inside that arm's reach; the vehicle
 * advances exactly the window's width between stops (fov.h has the details).
 *
 * Serial ("optimised single arm"): one arm; the left side is harvested in a first pass
 * along the row and the right side in a second, each side planned optimally on its own:
 * min sum_p C_p + tau * stops for that side alone, solved with hv_milp_solve on a one-side
 * instance (warm-started with FOV, as the paper does). T_travel counts twice.
 */
#ifndef HV_BASELINES_H
#define HV_BASELINES_H

#include <stddef.h>

#include "hv/fov.h"
#include "hv/milp.h"
#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_serial_result {
    hv_milp_result_t side[2]; /* per pass: [HV_SIDE_LEFT], [HV_SIDE_RIGHT] */
    int optimal;              /* both passes proven optimal */
    double gap;               /* the larger of the two gaps */
    long nodes;
    double runtime_s;
    double makespan_s; /* both passes: sum C + tau * stops + 2 T_travel */
} hv_serial_result_t;

/* Serial plan: `out` gets each fruit's stop, `passes` (n_fruits entries) 0 for left fruit,
 * 1 for right fruit. HV_ERR_PLAN_NO_SOLUTION when a side's solve returned nothing. */
hv_status_t hv_serial_solve(const hv_instance_t *inst, const hv_milp_options_t *opt,
                            hv_assignment_t *out, unsigned char *passes, hv_serial_result_t *res);

#ifdef __cplusplus
}
#endif
#endif /* HV_BASELINES_H */
