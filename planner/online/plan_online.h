/* harvest-plan-online's own parts, shared by its files (not a library; po_ names): the
 * program's state, the camera's input with its replay (plan_online_camera.c) and the
 * status it publishes, refusals included (plan_online_status.c). */
#ifndef PLAN_ONLINE_H
#define PLAN_ONLINE_H

#include <stddef.h>
#include <stdint.h>

#include <lcm/lcm.h>

#include "harvest_lcm_camera_frame_t.h"
#include "hv/online.h"
#include "hv/online_journal.h"

#define PO_MAX_HORIZONS 4096
#define PO_REPLAY_ASK_S 1.0 /* wall s between requests while the camera has not replayed */
#define PO_REASON_LEN   640

/* What the camera's replay did (camera_replay_t, DESIGN §5), in this run. */
typedef struct po_replay_counts {
    unsigned requests;  /* camera_replay_t sent */
    unsigned replays;   /* replay frames received */
    unsigned replayed;  /* detections in them */
    unsigned recovered; /* of those, fruit not heard of before and taken */
    unsigned lost;      /* of those, fruit not heard of before and late: never planned */
} po_replay_counts_t;

typedef struct po_app {
    hv_online_t o;
    lcm_t *lcm; /* NULL until opened: nothing is published */
    int quiet;
    /* the camera: frames in seq order; synced once nothing it revealed can be missing
     * (its first frame seen, or a replay that holds every frame up to the last seen) */
    int have_seq, synced;
    int32_t next_seq;
    double last_ask; /* wall s of the last replay request */
    harvest_lcm_camera_frame_t_subscription_t *cam_sub;
    unsigned frames, frames_lost, bad_id;
    po_replay_counts_t replay;
    /* the executor, as its state says */
    int exec_seen, exec_stop, exec_picked;
    double exec_vehicle_m;
    char exec_phase[32];
    double solve_s[PO_MAX_HORIZONS];
    size_t n_solves;
    hv_online_journal_t *journal; /* or NULL */
    /* a fatal error met in a handler (journal write, memory): the run ends with this code */
    int fatal_rc;
    /* the status (planner_status_t): published when changed and every 2 s */
    int status_changed;
    const char *end_state; /* NULL while running; refused, failed, ended, done */
    char reason[PO_REASON_LEN];
    char last_refusal[256];
} po_app_t;

/* Wall clock: monotonic s, and microseconds since the Unix epoch (LCM's utime). */
double po_now_s(void);
int64_t po_wall_utime(void);

/* Subscribe to the camera's frames (HARVEST_CAMERA, none dropped while a horizon is
 * solved) and ask it to replay what it revealed (the planner may have missed some). */
void po_camera_open(po_app_t *a);
void po_camera_close(po_app_t *a);
/* While not synced: ask the camera again, every PO_REPLAY_ASK_S. */
void po_camera_poll(po_app_t *a);

/* The status as it is now (planner_status_t on HARVEST_PLANNER_STATUS). */
void po_status_publish(po_app_t *a);
/* The run ends on an error: the line "harvest-plan-online: <fmt ...>" on stderr, and as the
 * status's reason, state `refused` (rc HV_EXIT_USAGE: bad input) or `failed` (else);
 * returns rc. */
int po_refuse(po_app_t *a, int rc, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* A detection refused: the line on stderr, and published at once as the status's
 * last_refusal. */
void po_refused_detection(po_app_t *a, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#endif /* PLAN_ONLINE_H */
