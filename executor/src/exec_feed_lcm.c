/* The online planner's committed stops and its status over LCM (exec_feed.h). */
#define _POSIX_C_SOURCE 200809L
#include "hv/exec_feed.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lcm/lcm.h>

#include "harvest_lcm_plan_commit_t.h"
#include "harvest_lcm_planner_status_t.h"
#include "hv/exec_status.h"

#define COMMIT_CHANNEL "HARVEST_PLAN_COMMIT"
#define STATUS_CHANNEL "HARVEST_PLANNER_STATUS"
/* wall s without a status: the planner is taken as silent (it sends one every 2 s) */
#define SILENT_S       5.0

typedef struct feed_lcm {
    FILE *log;
    lcm_t *lcm;
    harvest_lcm_plan_commit_t_subscription_t *sub;
    harvest_lcm_planner_status_t_subscription_t *status_sub;
    double status_at; /* monotonic wall s of the last status */
    int last_refused; /* the last plan message was refused here */
    char note[HV_EXEC_PLANNER_REASON_LEN + 96];
    hv_exec_plan_t *plan;
    hv_arm_t arm[2];
    hv_exec_timing_t timing;
    double max_margin_m;
    int course_set;
    int pending, final;
    double advance_m;
    hv_exec_feed_stats_t st;
    char why[160];
    hv_exec_pick_t picks[HV_EXEC_MAX_PICKS]; /* one stop's, being appended */
} feed_lcm_t;

static double mono_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void refuse(feed_lcm_t *f, const char *why)
{
    f->st.refused++;
    f->last_refused = 1;
    if (f->log && strcmp(why, f->st.last_refusal) != 0)
        fprintf(f->log, "harvest-exec: the planner's committed plan refused: %s\n", why);
    snprintf(f->st.last_refusal, sizeof f->st.last_refusal, "%s", why);
}

static int same_course(const hv_exec_plan_t *p, const harvest_lcm_plan_commit_t *m)
{
    return fabs(p->row_start_m - m->row_start_m) < 1e-9 &&
           fabs(p->row_length_m - m->row_length_m) < 1e-9 &&
           fabs(p->stop_margin_m - m->stop_margin_m) < 1e-9;
}

/* Stop s of the message (its picks from offset off) into f->picks; its left count. */
static hv_status_t read_stop(feed_lcm_t *f, const harvest_lcm_plan_commit_t *m, int s, int off,
                             int *n_left)
{
    int n = m->stop_picks[s], nl = m->stop_left[s];
    if (n < 0 || nl < 0 || nl > n || off + n > m->n_picks || n > (int)HV_EXEC_MAX_PICKS)
        return HV_ERR_EXEC_PLAN_RANGE;
    for (int k = 0; k < n; k++) {
        const harvest_lcm_detection_t *d = &m->picks[off + k];
        hv_exec_pick_t *pk = &f->picks[k];
        memset(pk, 0, sizeof *pk);
        if (strlen(d->fruit_id) >= sizeof pk->id || (d->side != 0 && d->side != 1))
            return HV_ERR_EXEC_PLAN_RANGE;
        memcpy(pk->id, d->fruit_id, strlen(d->fruit_id) + 1);
        pk->side = d->side ? HV_SIDE_RIGHT : HV_SIDE_LEFT;
        pk->x_m = d->x_m;
        pk->y_m = d->y_m;
        pk->z_m = d->z_m;
        pk->yaw_rad = d->yaw_rad;
        pk->cost_s = m->cost_s[off + k];
    }
    *n_left = nl;
    return HV_OK;
}

/* Stop s of the message: appended (s beyond the plan's last), or, for a stop the plan holds
 * already (from an earlier message or the journal of a run before a restart), checked to be
 * the very same: HV_ERR_EXEC_PLAN_CONFLICT when not. */
static hv_status_t take_stop(feed_lcm_t *f, const harvest_lcm_plan_commit_t *m, int s, int off)
{
    int nl = 0;
    hv_status_t st = read_stop(f, m, s, off, &nl);
    if (st != HV_OK)
        return st;
    uint16_t left = (uint16_t)nl, right = (uint16_t)(m->stop_picks[s] - nl);
    if (s < f->plan->n_stops)
        return hv_exec_plan_stop_matches(f->plan, (uint16_t)s, (uint32_t)m->stop_index[s],
                                         m->stop_y_m[s], f->picks, left, right)
                   ? HV_OK
                   : HV_ERR_EXEC_PLAN_CONFLICT;
    return hv_exec_plan_append(f->plan, (uint32_t)m->stop_index[s], m->stop_y_m[s], f->picks, left,
                               right);
}

static void on_commit(const lcm_recv_buf_t *rbuf, const char *channel,
                      const harvest_lcm_plan_commit_t *m, void *user)
{
    (void)rbuf;
    (void)channel;
    feed_lcm_t *f = user;
    hv_exec_plan_t *p = f->plan;
    f->st.messages++;
    f->last_refused = 0; /* until refuse() says otherwise */
    if (!f->course_set) {
        if (!(m->row_length_m > 0) || !isfinite(m->row_start_m) || !(m->stop_margin_m >= 0) ||
            m->stop_margin_m > f->max_margin_m + 1e-9) {
            refuse(f, "the course: a stop margin beyond the arms' reach, or no row");
            return;
        }
        p->row_start_m = m->row_start_m;
        p->row_length_m = m->row_length_m;
        p->stop_margin_m = m->stop_margin_m;
        f->course_set = 1;
    } else if (!same_course(p, m)) {
        refuse(f, "another course than the first message's");
        return;
    }
    if (m->n_stops < p->n_stops) {
        refuse(f, "HV_ERR_EXEC_PLAN_CONFLICT: fewer stops than the plan (journal) holds");
        return;
    }
    int off = 0, grew = 0;
    for (int s = 0; s < m->n_stops; s++) {
        int had = s < p->n_stops;
        hv_status_t st = take_stop(f, m, s, off);
        if (st != HV_OK) {
            snprintf(f->why, sizeof f->why, "%s: stop %d (candidate %d at %.3f m): %s",
                     hv_exec_status_name(st), s + 1, (int)m->stop_index[s], m->stop_y_m[s],
                     st == HV_ERR_EXEC_PLAN_CONFLICT ? "not the stop the plan (journal) holds there"
                     : st == HV_ERR_EXEC_PLAN_CAPACITY
                         ? "more stops or picks than the tables hold"
                         : "a stop that does not follow, or a fruit planned twice");
            refuse(f, f->why);
            if (st == HV_ERR_EXEC_PLAN_CONFLICT)
                return; /* nothing of a plan that contradicts the journal */
            break;
        }
        off += m->stop_picks[s];
        if (!had) {
            f->st.appended_stops++;
            grew = 1;
        }
    }
    if (grew && hv_exec_plan_prepare(p, f->arm, &f->timing) != HV_OK)
        refuse(f, "the grown plan could not be prepared");
    f->pending = 1;
    f->final = m->final && m->n_stops == p->n_stops;
    f->advance_m = m->commit_y_m;
}

static int ends(const char *state)
{
    return strcmp(state, "refused") == 0 || strcmp(state, "failed") == 0 ||
           strcmp(state, "ended") == 0;
}

/* The planner's status: kept, and what is new in it said at once (its end and why, a
 * detection it refused, what a replay of the camera gave back). */
static void on_status(const lcm_recv_buf_t *rbuf, const char *channel,
                      const harvest_lcm_planner_status_t *m, void *user)
{
    (void)rbuf;
    (void)channel;
    feed_lcm_t *f = user;
    hv_exec_planner_heard_t *h = &f->st.planner, was = *h;
    f->status_at = mono_s();
    h->heard = 1;
    snprintf(h->state, sizeof h->state, "%s", m->state);
    snprintf(h->reason, sizeof h->reason, "%s", m->reason);
    snprintf(h->last_refusal, sizeof h->last_refusal, "%s", m->last_refusal);
    h->refused = m->refused > 0 ? (unsigned)m->refused : 0;
    h->replays = m->replays > 0 ? (unsigned)m->replays : 0;
    h->replayed = m->replayed > 0 ? (unsigned)m->replayed : 0;
    h->recovered = m->recovered > 0 ? (unsigned)m->recovered : 0;
    h->lost = m->lost > 0 ? (unsigned)m->lost : 0;
    h->seen_to_m = m->seen_to_m;
    h->commit_y_m = m->commit_y_m;
    if (!f->log)
        return;
    if (ends(h->state) && (strcmp(h->state, was.state) != 0 || strcmp(h->reason, was.reason) != 0))
        fprintf(f->log, "harvest-exec: the planner %s: %s\n", h->state,
                h->reason[0] ? h->reason : "(no reason given)");
    if (h->last_refusal[0] && strcmp(h->last_refusal, was.last_refusal) != 0)
        fprintf(f->log, "harvest-exec: from the planner: %s\n", h->last_refusal);
    if (h->replays != was.replays || h->lost != was.lost)
        fprintf(f->log,
                "harvest-exec: the camera replayed to the planner (%u times): %u detections, "
                "%u fruits recovered, %u lost\n",
                h->replays, h->replayed, h->recovered, h->lost);
}

static const char *planner_note(void *ctx)
{
    feed_lcm_t *f = ctx;
    const hv_exec_planner_heard_t *h = &f->st.planner;
    double quiet = h->heard ? mono_s() - f->status_at : 0.0;
    /* a planner that ended only because this executor stopped says less than the refusal
     * of its plan that made the executor wait */
    int ended_after_refusal = f->last_refused && strcmp(h->state, "ended") == 0;
    if (h->heard && ends(h->state) && !ended_after_refusal)
        snprintf(f->note, sizeof f->note, "the planner %s: %s", h->state,
                 h->reason[0] ? h->reason : "(no reason given)");
    else if (f->last_refused)
        snprintf(f->note, sizeof f->note, "the planner's committed plan refused here: %s",
                 f->st.last_refusal);
    else if (!h->heard)
        snprintf(f->note, sizeof f->note, "%s",
                 f->st.messages ? "no status from the planner (its plan comes)"
                                : "no word from the planner");
    else if (quiet > SILENT_S)
        snprintf(f->note, sizeof f->note, "no word from the planner for %.0f s (it said: %s)",
                 quiet, h->state);
    else if (strcmp(h->state, "camera_sync") == 0)
        snprintf(f->note, sizeof f->note, "the planner waits for the camera's replay");
    else if (strcmp(h->state, "camera_wait") == 0)
        snprintf(f->note, sizeof f->note, "the planner waits for the camera's first frame");
    else
        snprintf(f->note, sizeof f->note,
                 "the planner %s: the camera seen to %.2f m, committed to %.2f m",
                 strcmp(h->state, "done") == 0 ? "committed the whole row" : "plans", h->seen_to_m,
                 h->commit_y_m);
    return f->note;
}

static int take(void *ctx, hv_exec_event_t *ev)
{
    feed_lcm_t *f = ctx;
    while (lcm_handle_timeout(f->lcm, 0) > 0)
        ;
    if (!f->pending)
        return 0;
    f->pending = 0;
    memset(ev, 0, sizeof *ev);
    ev->kind = HV_EV_PLAN_GROWN;
    ev->u.plan.final = f->final;
    ev->u.plan.advance_m = isfinite(f->advance_m) ? f->advance_m : 0.0;
    return 1;
}

hv_status_t hv_exec_feed_lcm_open(hv_exec_feed_t *feed, const char *url, hv_exec_plan_t *plan,
                                  const hv_arm_t arm[2], const hv_exec_timing_t *timing,
                                  double max_margin_m, char *err, size_t errlen)
{
    if (!feed || !url || !plan || !arm || !timing)
        return HV_ERR_ARG;
    feed_lcm_t *f = calloc(1, sizeof *f);
    if (!f)
        return HV_ERR_EXEC_TELEMETRY;
    f->lcm = lcm_create(url);
    if (!f->lcm) {
        snprintf(err, errlen, "--lcm-url %s: LCM could not be opened", url);
        free(f);
        return HV_ERR_EXEC_TELEMETRY;
    }
    f->sub = harvest_lcm_plan_commit_t_subscribe(f->lcm, COMMIT_CHANNEL, on_commit, f);
    f->status_sub = harvest_lcm_planner_status_t_subscribe(f->lcm, STATUS_CHANNEL, on_status, f);
    f->plan = plan;
    memcpy(f->arm, arm, sizeof f->arm);
    f->timing = *timing;
    f->max_margin_m = max_margin_m;
    f->course_set = plan->row_length_m > 0; /* rebuilt from the journal of an earlier start */
    feed->fd = lcm_get_fileno(f->lcm);
    feed->take = take;
    feed->planner = planner_note;
    feed->ctx = f;
    f->log = feed->log;
    return HV_OK;
}

const hv_exec_feed_stats_t *hv_exec_feed_lcm_stats(const hv_exec_feed_t *feed)
{
    return &((const feed_lcm_t *)feed->ctx)->st;
}

void hv_exec_feed_lcm_close(hv_exec_feed_t *feed)
{
    if (!feed || !feed->ctx)
        return;
    feed_lcm_t *f = feed->ctx;
    harvest_lcm_plan_commit_t_unsubscribe(f->lcm, f->sub);
    harvest_lcm_planner_status_t_unsubscribe(f->lcm, f->status_sub);
    lcm_destroy(f->lcm);
    free(f);
    feed->ctx = NULL;
}
