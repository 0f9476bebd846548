/* Deadline helpers shared by the transports (internal). */
#ifndef HV_CAN_WAIT_H
#define HV_CAN_WAIT_H

#include <stdint.h>
#include <time.h>

/* Monotonic now in ms. */
static inline int64_t hv_can_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* Wall-clock now in ns since the epoch (python-can's timestamps use the same clock). */
static inline int64_t hv_can_realtime_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

/* Absolute deadline for a timeout (negative timeout: none, returned as -1). */
static inline int64_t hv_can_deadline(int timeout_ms)
{
    return timeout_ms < 0 ? -1 : hv_can_now_ms() + timeout_ms;
}

/* poll() timeout left until `deadline` (-1: forever, 0: expired). */
static inline int hv_can_left_ms(int64_t deadline)
{
    if (deadline < 0)
        return -1;
    int64_t left = deadline - hv_can_now_ms();
    return left <= 0 ? 0 : (left > 1000000 ? 1000000 : (int)left);
}

#endif /* HV_CAN_WAIT_H */
