/* The solvers' monotonic clock (milp_clock.h). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#endif

#include <math.h>
#include <time.h>

#include "hv/milp_clock.h"

double hv_milp_now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int hv_milp_limit_ms(double left_s)
{
    return (int)fmax(1.0, fmin(left_s * 1000.0, 2e9));
}
