/* The executor's real type: the one place that says in what precision it computes.
 *
 * hv_exec_real_t carries what the state machine computes with at every step: its
 * parameters, the prepared plan's setpoints, move times and positions, the values of
 * events and actions (time scales, positions, joint setpoints), durations. It is double,
 * except in a build that defines HV_EXEC_SINGLE_PRECISION=1 (the firmware's cross build,
 * top-level CMakeLists.txt; host builds keep double): there it is float, because the M4F's
 * FPU does single precision only and every double operation is a call into libgcc's
 * software routines (firmware/README.md). Such a build also generates the DBC's
 * pack/unpack with float (cantools --use-float, executor/can/CMakeLists.txt).
 *
 * Absolute times never go into it: they stay uint64_t ns (a float holds ~16000 s only to
 * ~2 ms). What the host prepares once (IK, expected times) stays double and is converted
 * to this type once, when the plan is loaded, never per step.
 *
 * HV_EXEC_REAL(1.5) writes a constant of this type (1.5f or 1.5), so a float build never
 * promotes to double (-Wdouble-promotion is an error there).
 */
#ifndef HV_EXEC_REAL_H
#define HV_EXEC_REAL_H

#include <float.h>
#include <math.h>
#include <stdint.h>

#include "hv/scara.h"

#if defined(HV_EXEC_SINGLE_PRECISION) && HV_EXEC_SINGLE_PRECISION
typedef float hv_exec_real_t;
#define HV_EXEC_REAL(c)   c##f
#define HV_EXEC_REAL_MAX  FLT_MAX
#define hv_exec_fabs      fabsf
#define hv_exec_trap_time hv_trap_timef

/* Seconds (>= 0) to ns. The FPU converts to 32-bit integers only (a float to uint64_t is
 * libgcc's, through double): whole seconds and the fraction apart. */
static inline uint64_t hv_exec_real_ns(hv_exec_real_t s)
{
    if (!(s > 0.0f))
        return 0u;
    if (s >= 4294967040.0f) /* the largest float below 2^32 */
        s = 4294967040.0f;
    uint32_t whole = (uint32_t)s;
    return (uint64_t)whole * 1000000000u + (uint32_t)((s - (float)whole) * 1e9f);
}

/* ns to seconds, likewise through 32-bit integers (whole seconds, then the rest). */
static inline hv_exec_real_t hv_exec_ns_real(uint64_t ns)
{
    return (float)(uint32_t)(ns / 1000000000u) + (float)(uint32_t)(ns % 1000000000u) * 1e-9f;
}
#else
typedef double hv_exec_real_t;
#define HV_EXEC_REAL(c)   c
#define HV_EXEC_REAL_MAX  DBL_MAX
#define hv_exec_fabs      fabs
#define hv_exec_trap_time hv_trap_time

/* Seconds to ns (0 for s <= 0). */
static inline uint64_t hv_exec_real_ns(hv_exec_real_t s)
{
    return s <= 0.0 ? 0u : (uint64_t)(s * 1e9);
}

/* ns to seconds. */
static inline hv_exec_real_t hv_exec_ns_real(uint64_t ns)
{
    return (double)ns * 1e-9;
}
#endif

#endif /* HV_EXEC_REAL_H */
