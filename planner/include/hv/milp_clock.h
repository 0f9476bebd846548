/* The solvers' clock (internal to the MILP solvers): deadlines and timings in seconds of
 * CLOCK_MONOTONIC, so a wall-clock step never moves a time limit. */
#ifndef HV_MILP_CLOCK_H
#define HV_MILP_CLOCK_H

#ifdef __cplusplus
extern "C" {
#endif

/* Seconds since an unspecified start, monotonic. */
double hv_milp_now_s(void);

/* left_s seconds as a GLPK time limit (tm_lim): whole ms, at least 1 (GLPK reads 0 or less
 * as no limit), at most 2e9. */
int hv_milp_limit_ms(double left_s);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_CLOCK_H */
