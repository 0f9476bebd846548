/* The solver's constants (fixed when it is built). Each is a row of the parameter table
 * (milp_options.c: unit, range and meaning; `harvest-plan --help-params`), which takes its
 * value from here: change a value here only. Internal to the MILP solvers. */
#ifndef HV_MILP_TUNABLES_H
#define HV_MILP_TUNABLES_H

#define BIG_MS                1e6
#define RC_EPS_MS             1e-6
#define LAMBDA_EPS            1e-6
#define SMOOTHING             0.8
#define SMOOTH_STEP           0.1
#define SMOOTH_MAX            0.99
#define ASCENT_DEFLECT        0.5
#define CAND_WINDOW           5
#define CENTRE_MIN_PAIRS      9000
#define PRIMAL_ROOT_GAP       2e-3
#define POLISH_MAX_KICKS      1000
#define POLISH_CHUNK          50
#define WORKER_GAP            2e-3
#define DIVE_EVERY            64
#define BALANCE_SHARE         0.2
#define ROUND_EVERY           8
#define ROUND_TIME_SHARE      0.2
#define WINDOW_SHARE          0.25
#define WINDOW_LIMIT_S        0.5
#define RINS_LIMIT_S          0.3
#define RINS_MAX_FREE         60
#define RINS_CALL_S           1.0
#define SR_MAX                512
#define SR_PER_ROUND          64
#define SR_PER_FRUIT          4
#define SR_MIN_VIOL           0.05
#define REGION_AFTER_NODES    16
#define REGION_SHARE          0.5
#define REGION_EPS_MS         1e-3
#define REGION_KICKS          20
#define REGION_GROW           12
#define COUNT_MIN_SCORE       0.05
#define IV_MIN_FRAC           0.1
#define IV_GAP_WEIGHT         0.01
#define IV_EDGE_GAP           1000u
#define IV_PC_FLOOR_MS        1e-3
#define TAIL_ROUNDS           10
#define TAIL_FALL_MS          1e-3
#define BIND_MIN_WEIGHT       1e-3
#define STALL_ITERS_PER_ROW   10
#define HELPER_WINDOW_LIMIT_S 0.5
#define HELPER_KICKS          200
#define HELPER_KICKS_CHUNK    20
#define HELPER_MEMO           1024
#define CLOCK_EVERY_POINTS    4096u
#define WAIT_SLICE_NS         20000000L
#define FRAC_EPS              1e-6
#define HV_CUT_MAX_ROUNDS     8
#define CUT_MIN_VIOLATION_S   1e-3
#define CUT_MIN_VALUE         1e-6

#endif /* HV_MILP_TUNABLES_H */
