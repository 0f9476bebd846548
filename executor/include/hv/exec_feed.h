/* Online mode's input (DESIGN §5, §7): the planner's committed stops, appended to the plan
 * while the row runs, and what the planner says of itself. A small interface, polled by the
 * event loop beside the bus; the LCM implementation (exec_feed_lcm.c) reads plan_commit_t on
 * HARVEST_PLAN_COMMIT and planner_status_t on HARVEST_PLANNER_STATUS. */
#ifndef HV_EXEC_FEED_H
#define HV_EXEC_FEED_H

#include <stdio.h>

#include "hv/exec_plan.h"
#include "hv/exec_sm.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_exec_feed {
    int fd; /* readable when input waits */
    /* Take what arrived without blocking, append it to the plan; 1 with *ev (a
     * HV_EV_PLAN_GROWN) when the state machine must hear of it, else 0. */
    int (*take)(void *ctx, hv_exec_event_t *ev);
    /* One line on the planner as last heard, never NULL; in WAIT_PLAN the reason no plan
     * comes: its refusal, a plan refused here, its wait for the camera's replay, silence. */
    const char *(*planner)(void *ctx);
    void *ctx;
    FILE *log; /* a refused message, the planner's refusals and the camera's replays are
                  said here at once (each new one), or NULL */
} hv_exec_feed_t;

#define HV_EXEC_PLANNER_REASON_LEN 640

/* The planner's status as last heard (planner_status_t). */
typedef struct hv_exec_planner_heard {
    int heard;      /* a status came */
    char state[16]; /* camera_wait, camera_sync, planning, done, refused, failed, ended */
    char reason[HV_EXEC_PLANNER_REASON_LEN];     /* refused, failed, ended: its line */
    char last_refusal[256];                      /* the last detection it refused */
    unsigned refused;                            /* detections it refused */
    unsigned replays, replayed, recovered, lost; /* the camera's replays (its run) */
    double seen_to_m, commit_y_m;
} hv_exec_planner_heard_t;

/* What the LCM feed counts. */
typedef struct hv_exec_feed_stats {
    unsigned messages;       /* plan_commit_t received */
    unsigned appended_stops; /* stops appended to the plan */
    unsigned refused;        /* messages refused (another course, a stop that does not
                                follow, a fruit planned twice, the tables full) */
    char last_refusal[160];  /* why the last one was refused */
    hv_exec_planner_heard_t planner;
} hv_exec_feed_stats_t;

/* The LCM feed. `plan` starts empty (n_stops = 0): the first message sets its course,
 * refused when its stop margin exceeds max_margin_m (hv_pick_stop_margin). arms and timing
 * prepare each grown plan. Opaque state in *ctx (hv_exec_feed_lcm_close frees it). */
hv_status_t hv_exec_feed_lcm_open(hv_exec_feed_t *feed, const char *url, hv_exec_plan_t *plan,
                                  const hv_arm_t arm[2], const hv_exec_timing_t *timing,
                                  double max_margin_m, char *err, size_t errlen);
const hv_exec_feed_stats_t *hv_exec_feed_lcm_stats(const hv_exec_feed_t *feed);
void hv_exec_feed_lcm_close(hv_exec_feed_t *feed);

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_FEED_H */
