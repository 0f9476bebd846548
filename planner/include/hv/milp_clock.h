/* The solvers' clock (internal to the MILP solvers): deadlines and timings in seconds of
 * CLOCK_MONOTONIC, so a wall-clock step never moves a time limit. */
#ifndef HV_MILP_CLOCK_H
#define HV_MILP_CLOCK_H

#ifdef __cplusplus
extern "C" {
#endif

/* Seconds since an unspecified start, monotonic. */
double hv_milp_now_s(void);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_CLOCK_H */
