/* A stop-and-harvest instance as the solvers see it (DESIGN §1, §5), and a solution.
 *
 * Built from a fruit map and a pick model (pick_model.h) by plan_instance.c; consumed by the MILP
 * (milp.c), the baselines, the checker and the plan writer. Only reachable
 * (fruit, stop) pairs exist; fruits that no stop reaches are flagged with the reason,
 * never fed to a solver.
 */
#ifndef HV_PLAN_INSTANCE_H
#define HV_PLAN_INSTANCE_H

#include <stddef.h>
#include <stdint.h>

#include "hv/config.h"
#include "hv/pick.h"
#include "hv/scara.h"
#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HV_NO_STOP      UINT32_MAX
#define HV_FRUIT_ID_LEN 32

typedef struct hv_fruit {
    char id[HV_FRUIT_ID_LEN];
    hv_side_t side;
    double x_m, y_m, z_m; /* vehicle frame x, z; y along the row */
    double yaw_rad;       /* relative to the side's inward normal */
} hv_fruit_t;

/* One reachable (fruit, stop) pair and its pick cost G. */
typedef struct hv_pair {
    uint32_t fruit;
    uint32_t stop;
    double cost_s;
} hv_pair_t;

typedef struct hv_instance {
    size_t n_fruits;
    hv_fruit_t *fruits;

    size_t n_stops;
    double *stop_y_m; /* candidate stop positions, ascending */

    /* reachable pairs sorted by (fruit, stop); pairs of fruit f are
     * pairs[fruit_begin[f] .. fruit_begin[f + 1]) — empty for unreachable fruits */
    size_t n_pairs;
    hv_pair_t *pairs;
    size_t *fruit_begin; /* n_fruits + 1 entries */

    double stop_penalty_s; /* tau */
    double travel_time_s;  /* T_travel (constant) */

    /* why each fruit with no pair has none (hv_instance_why_name); 0 for the others. May be
     * NULL in instances built by hand (tests, solver sub-instances). */
    unsigned char *why;
} hv_instance_t;

/* Why a fruit has no pair: the hv_pick_why_t values (height, depth, yaw: no vehicle
 * position within the arm's reach span picks it), or HV_WHY_ROW_END: positions beyond the
 * candidate stops would reach it (row.stops_beyond_ends = 0 confines them to the row). */
#define HV_WHY_ROW_END ((unsigned char)HV_PICK_WHY_COUNT)

/* "height", "depth", "yaw", "row_end"; "ok" for 0; "?" otherwise. */
const char *hv_instance_why_name(int why);

/* A solution: the stop of every fruit (HV_NO_STOP for unreachable fruits). */
typedef struct hv_assignment {
    size_t n_fruits;
    uint32_t *fruit_stop;
} hv_assignment_t;

/* ---- Building (added by the instance builder; the fields above are the agreed API) ---- */

/* Candidate stops and time constants of an instance. The fruit row is [row_start_m,
 * row_start_m + row_length_m]; the vehicle's course runs stop_margin_m beyond both ends,
 * and stop p is at row_start_m - stop_margin_m + p * stop_step_m,
 * p = 0 .. round((row_length_m + 2 stop_margin_m) / stop_step_m). */
typedef struct hv_instance_params {
    double row_start_m;
    double row_length_m;
    double stop_step_m;
    double stop_penalty_s; /* tau */
    double travel_time_s;  /* T_travel: the course's length / vehicle speed */
    double stop_margin_m;  /* a whole number of stop steps, >= 0 (last: initialisers that
                              stop before it mean 0) */
} hv_instance_params_t;

struct hv_pick_model;

/* From the configuration: row [0, row.length], grid.step, tau; with row.stops_beyond_ends
 * the margin from the model's reach spans (hv_pick_margin_of_spans), else 0;
 * T_travel = (length + 2 margin) / speed. */
void hv_instance_params_from_config(const hv_config_t *cfg, const struct hv_pick_model *model,
                                    hv_instance_params_t *params);

/* The course's length (m): row_length_m + 2 stop_margin_m. */
double hv_instance_params_course_m(const hv_instance_params_t *params);

/* Number of candidate stops of `params` (0 when the parameters are invalid). */
size_t hv_instance_params_stops(const hv_instance_params_t *params);

/* Build an instance: copies `fruits`, lays out the stops and collects every reachable
 * (fruit, stop) pair, G = model->cost, trying the stops whose y_rel = fruit.y - stop_y
 * lies in the model's span of the fruit's side. Fruits with no pair are unreachable
 * (fruit_begin[f] == fruit_begin[f + 1]) and inst->why[f] says why; positions beyond the
 * candidate stops are tried for that.
 * Errors: HV_ERR_ARG, HV_ERR_PLAN_PARAMS, HV_ERR_PLAN_NOMEM (diag filled). */
hv_status_t hv_instance_build(const hv_instance_params_t *params, const hv_fruit_t *fruits,
                              size_t n_fruits, const struct hv_pick_model *model,
                              hv_instance_t *inst, hv_diag_t *diag);

/* A sub-instance: the stops [stop_begin, stop_end) of `full` and the fruits f with
 * keep_fruit[f] != 0 (all when keep_fruit is NULL) that have at least one pair there when
 * drop_unreachable is set. fruit_of_sub (n_fruits of the sub entries, may be NULL, else
 * at least full->n_fruits entries) receives the full index of each sub fruit; the sub's
 * stop q is full stop stop_begin + q. tau and T_travel are copied from `full`. */
hv_status_t hv_instance_subset(const hv_instance_t *full, size_t stop_begin, size_t stop_end,
                               const unsigned char *keep_fruit, int drop_unreachable,
                               hv_instance_t *sub, uint32_t *fruit_of_sub);

/* Free what hv_instance_build / hv_instance_subset allocated; the struct is zeroed. */
void hv_instance_free(hv_instance_t *inst);

/* Number of fruits with no reachable stop. */
size_t hv_instance_unreachable_count(const hv_instance_t *inst);

/* Allocate an assignment of n fruits, every entry HV_NO_STOP. */
hv_status_t hv_assignment_alloc(hv_assignment_t *a, size_t n_fruits);
void hv_assignment_free(hv_assignment_t *a);

#ifdef __cplusplus
}
#endif
#endif /* HV_PLAN_INSTANCE_H */
