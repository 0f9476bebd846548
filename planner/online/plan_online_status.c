/* harvest-plan-online: its status on LCM (planner_status_t on HARVEST_PLANNER_STATUS), so
 * that harvest-exec --online can say why no plan comes: the planner's refusal and its
 * reason, its wait for the camera's replay, what the replay recovered (plan_online.h). */
#include <stdarg.h>
#include <stdio.h>
#include <time.h>

#include "harvest_lcm_planner_status_t.h"
#include "hv/exit_codes.h"
#include "plan_online.h"

double po_now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int64_t po_wall_utime(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

static const char *state_of(const po_app_t *a)
{
    if (a->end_state != NULL)
        return a->end_state;
    if (a->o.done)
        return "done";
    if (!a->synced)
        return a->have_seq ? "camera_sync" : "camera_wait";
    return "planning";
}

void po_status_publish(po_app_t *a)
{
    a->status_changed = 0;
    if (a->lcm == NULL)
        return;
    const hv_online_t *o = &a->o;
    harvest_lcm_planner_status_t m;
    m.utime = po_wall_utime();
    m.state = (char *)state_of(a);
    m.reason = a->reason;
    m.last_refusal = a->last_refusal;
    m.refused = (int32_t)(o->counts[HV_DET_OUTSIDE_ROW] + o->counts[HV_DET_DUPLICATE] +
                          o->counts[HV_DET_LATE] + a->bad_id);
    m.frames_lost = (int32_t)a->frames_lost;
    m.replays = (int32_t)a->replay.replays;
    m.replayed = (int32_t)a->replay.replayed;
    m.recovered = (int32_t)a->replay.recovered;
    m.lost = (int32_t)a->replay.lost;
    m.seen_to_m = o->seen_to_m;
    m.commit_y_m = o->params.row_length_m > 0 ? hv_online_commit_y(o) : 0.0;
    harvest_lcm_planner_status_t_publish(a->lcm, "HARVEST_PLANNER_STATUS", &m);
}

/* "harvest-plan-online: " and the message into buf, then the line on stderr. */
static void say(char *buf, size_t size, const char *fmt, va_list ap)
{
    int n = snprintf(buf, size, "harvest-plan-online: ");
    vsnprintf(buf + n, size - (size_t)n, fmt, ap);
    fprintf(stderr, "%s\n", buf);
}

int po_refuse(po_app_t *a, int rc, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    say(a->reason, sizeof a->reason, fmt, ap);
    va_end(ap);
    a->end_state = rc == HV_EXIT_USAGE ? "refused" : "failed";
    po_status_publish(a);
    return rc;
}

void po_refused_detection(po_app_t *a, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    say(a->last_refusal, sizeof a->last_refusal, fmt, ap);
    va_end(ap);
    po_status_publish(a);  /* at once: each refusal is said, not only a frame's last */
    a->status_changed = 1; /* and again with the frame's view */
}
