/* Telemetry out of the executor (DESIGN §8): a small interface with two sinks, LCM
 * (hv_exec_telemetry_lcm_open, when built with HV_WITH_LCM) and null (embedded builds,
 * tests). Publishing never blocks the run: a failed publish is counted, not fatal.
 *
 * Channels: HARVEST_PLAN (plan_t, once), HARVEST_EXEC_STATE (exec_state_t, phase changes
 * and 10 Hz), HARVEST_FRUIT (fruit_event_t), HARVEST_ARM_LEFT / HARVEST_ARM_RIGHT
 * (arm_joint_state_t), HARVEST_CAN_STATS (can_stats_t, 1 Hz).
 */
#ifndef HV_EXEC_TELEMETRY_H
#define HV_EXEC_TELEMETRY_H

#include <stddef.h>
#include <stdint.h>

#include "hv/exec_sm.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HV_TM_CH_PLAN      "HARVEST_PLAN"
#define HV_TM_CH_STATE     "HARVEST_EXEC_STATE"
#define HV_TM_CH_FRUIT     "HARVEST_FRUIT"
#define HV_TM_CH_ARM_LEFT  "HARVEST_ARM_LEFT"
#define HV_TM_CH_ARM_RIGHT "HARVEST_ARM_RIGHT"
#define HV_TM_CH_CAN_STATS "HARVEST_CAN_STATS"

/* One arm's joint state as the CAN layer decoded it. */
typedef struct hv_exec_arm_sample {
    int side;
    hv_exec_real_t q[HV_NJOINTS];  /* m, rad */
    hv_exec_real_t qd[HV_NJOINTS]; /* m/s, rad/s */
} hv_exec_arm_sample_t;

/* Bus counters (a copy of the CAN layer's, so telemetry does not depend on it). */
typedef struct hv_exec_bus_stats {
    const char *bus;
    uint64_t tx_frames, rx_frames, rx_error_frames, rx_malformed, rx_unsupported, rx_filtered,
        rx_kernel_drops, tx_failures;
} hv_exec_bus_stats_t;

typedef struct hv_exec_telemetry hv_exec_telemetry_t;

typedef struct hv_exec_telemetry_ops {
    int (*plan)(hv_exec_telemetry_t *t, const hv_exec_plan_t *plan, const char *path,
                const hv_exec_params_t *prm, double time_scale, int64_t utime);
    /* planner: online, the feed's line on the planner (hv_exec_feed_t.planner); or NULL */
    int (*state)(hv_exec_telemetry_t *t, const hv_exec_sm_t *sm, const char *planner,
                 uint64_t now_ns, int64_t utime);
    int (*fruit)(hv_exec_telemetry_t *t, const hv_exec_sm_t *sm, const hv_exec_action_t *fe,
                 uint64_t now_ns, int64_t utime);
    int (*arm)(hv_exec_telemetry_t *t, const hv_exec_sm_t *sm, const hv_exec_arm_sample_t *s,
               int64_t utime);
    int (*can_stats)(hv_exec_telemetry_t *t, const hv_exec_bus_stats_t *s, int64_t utime);
    void (*close)(hv_exec_telemetry_t *t);
} hv_exec_telemetry_ops_t;

struct hv_exec_telemetry {
    const hv_exec_telemetry_ops_t *ops;
    void *impl;         /* the sink's handle (lcm_t *) */
    unsigned published; /* messages handed to the sink */
    unsigned failed;    /* publishes the sink refused */
};

/* A sink that drops everything (counts nothing as failed). */
void hv_exec_telemetry_null(hv_exec_telemetry_t *t);

/* LCM sink on `url` ("memq://", "udpm://239.255.76.67:7667?ttl=0", ...).
 * HV_ERR_EXEC_TELEMETRY with `err` when LCM cannot be set up or was not built in. */
hv_status_t hv_exec_telemetry_lcm_open(hv_exec_telemetry_t *t, const char *url, char *err,
                                       size_t errlen);

/* Convenience wrappers: count, and ignore a NULL sink. */
void hv_exec_tm_plan(hv_exec_telemetry_t *t, const hv_exec_plan_t *plan, const char *path,
                     const hv_exec_params_t *prm, double time_scale, int64_t utime);
void hv_exec_tm_state(hv_exec_telemetry_t *t, const hv_exec_sm_t *sm, const char *planner,
                      uint64_t now_ns, int64_t utime);
void hv_exec_tm_fruit(hv_exec_telemetry_t *t, const hv_exec_sm_t *sm, const hv_exec_action_t *fe,
                      uint64_t now_ns, int64_t utime);
void hv_exec_tm_arm(hv_exec_telemetry_t *t, const hv_exec_sm_t *sm, const hv_exec_arm_sample_t *s,
                    int64_t utime);
void hv_exec_tm_can_stats(hv_exec_telemetry_t *t, const hv_exec_bus_stats_t *s, int64_t utime);
void hv_exec_telemetry_close(hv_exec_telemetry_t *t);

/* Picks without an outcome yet (journal included). */
unsigned hv_exec_remaining(const hv_exec_sm_t *sm);

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_TELEMETRY_H */
