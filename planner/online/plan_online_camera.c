/* harvest-plan-online: the camera's frames (camera_frame_t on HARVEST_CAMERA) into the
 * online module, and its replay (plan_online.h). A planner that starts (fresh or from its
 * journal) or finds a frame lost may have missed fruit the camera revealed: it asks the
 * camera to send again every fruit revealed so far (camera_replay_t), and trusts no view
 * until that came, so that no horizon is committed without the fruit it missed. */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "harvest_lcm_camera_frame_t.h"
#include "harvest_lcm_camera_replay_t.h"
#include "hv/exit_codes.h"
#include "hv/fruit_id.h"
#include "plan_online.h"

#define REPLAY_CHANNEL "HARVEST_CAMERA_REPLAY"

static void journal_failed(po_app_t *a)
{
    a->fatal_rc = po_refuse(a, HV_EXIT_FAILURE, "%s: journal write failed: %s", a->journal->path,
                            strerror(errno));
}

static void ask_replay(po_app_t *a)
{
    harvest_lcm_camera_replay_t m;
    m.utime = po_wall_utime();
    m.requester = (char *)"harvest-plan-online";
    harvest_lcm_camera_replay_t_publish(a->lcm, REPLAY_CHANNEL, &m);
    a->replay.requests++;
    a->last_ask = po_now_s();
}

void po_camera_poll(po_app_t *a)
{
    if (!a->synced && po_now_s() - a->last_ask >= PO_REPLAY_ASK_S)
        ask_replay(a);
}

/* Not synced any more: the view waits for the replay asked for now. */
static void unsync(po_app_t *a, const char *why)
{
    if (!a->quiet)
        fprintf(stderr, "harvest-plan-online: %s: asking the camera to replay what it revealed\n",
                why);
    a->synced = 0;
    a->status_changed = 1;
    ask_replay(a);
}

/* The frame's seq against the ones before: a gap loses what those frames held (replayed). */
static void check_seq(po_app_t *a, const harvest_lcm_camera_frame_t *m)
{
    if (!a->have_seq) {
        a->have_seq = 1;
        if (m->seq == 0 && !a->synced) { /* the camera's first frame: nothing was missed */
            a->synced = 1;
            a->status_changed = 1;
        }
    } else if (m->seq != a->next_seq) {
        char what[96];
        snprintf(what, sizeof what, "camera frame %d after %d: %s", m->seq, a->next_seq - 1,
                 m->seq > a->next_seq ? "frames lost" : "out of order");
        if (m->seq > a->next_seq) {
            a->frames_lost += (unsigned)(m->seq - a->next_seq);
            unsync(a, what);
        } else {
            fprintf(stderr, "harvest-plan-online: %s\n", what);
        }
    }
    if (m->seq >= a->next_seq)
        a->next_seq = m->seq + 1;
}

/* One detection; from a replay (`replayed`), a fruit known already is the camera saying it
 * again: nothing to do. */
static void take(po_app_t *a, const harvest_lcm_detection_t *d, int replayed)
{
    hv_fruit_t f;
    memset(&f, 0, sizeof f);
    size_t len = strlen(d->fruit_id);
    a->replay.replayed += replayed != 0;
    if (len >= sizeof f.id || hv_fruit_id_check(d->fruit_id, len, NULL) != HV_OK ||
        (d->side != 0 && d->side != 1)) {
        char shown[41]; /* printable ASCII only: the line goes to the terminal and LCM */
        size_t k = 0;
        for (; k < sizeof shown - 1 && d->fruit_id[k]; k++)
            shown[k] = d->fruit_id[k] >= 0x20 && d->fruit_id[k] < 0x7f ? d->fruit_id[k] : '?';
        shown[k] = '\0';
        a->bad_id++;
        po_refused_detection(a, "detection \"%s\": refused: bad_id", shown);
        return;
    }
    memcpy(f.id, d->fruit_id, len + 1);
    f.side = d->side ? HV_SIDE_RIGHT : HV_SIDE_LEFT;
    f.x_m = d->x_m;
    f.y_m = d->y_m;
    f.z_m = d->z_m;
    f.yaw_rad = d->yaw_rad;
    if (replayed && hv_online_known(&a->o, &f))
        return;
    hv_online_verdict_t v;
    if (a->journal != NULL && hv_online_journal_detection(a->journal, &f) != HV_OK) {
        journal_failed(a);
        return;
    }
    if (hv_online_detect(&a->o, &f, &v) != HV_OK) {
        a->fatal_rc = po_refuse(a, HV_EXIT_FAILURE, "out of memory");
        return;
    }
    int ok = v == HV_DET_ACCEPTED || v == HV_DET_UNREACHABLE;
    if (replayed && ok) {
        a->replay.recovered++;
        a->status_changed = 1;
    } else if (replayed && v == HV_DET_LATE) {
        a->replay.lost++;
    }
    if (!ok)
        po_refused_detection(a, "detection %s (%c) at y %.3f m: refused: %s%s", f.id,
                             d->side ? 'R' : 'L', f.y_m, hv_online_verdict_name(v),
                             replayed && v == HV_DET_LATE
                                 ? " (revealed while the planner was down or in a lost frame: "
                                   "lost)"
                                 : "");
}

/* The camera has seen up to seen_to_m: journalled (synced) when it is news, then taken. */
static void view(po_app_t *a, double seen_to_m, int news)
{
    if (a->journal != NULL && (news || seen_to_m > a->o.seen_to_m) &&
        hv_online_journal_seen(a->journal, seen_to_m) != HV_OK) {
        journal_failed(a);
        return;
    }
    hv_online_seen(&a->o, seen_to_m);
}

static void on_frame(const lcm_recv_buf_t *rbuf, const char *channel,
                     const harvest_lcm_camera_frame_t *m, void *user)
{
    (void)rbuf;
    (void)channel;
    po_app_t *a = user;
    if (a->fatal_rc)
        return;
    if (m->replay) {
        a->replay.replays++;
        a->status_changed = 1;
    } else {
        a->frames++;
        check_seq(a, m);
    }
    for (int i = 0; i < m->n && !a->fatal_rc; i++)
        take(a, &m->fruits[i], m->replay);
    if (a->fatal_rc)
        return;
    if (!m->replay && !a->synced)
        return; /* its view may pass fruit the replay is still to bring */
    /* a replay that holds every frame seen so far (a stale one answered an earlier request:
     * its fruit is taken, the view waits for the next; the frames held back meanwhile saw
     * no further than a replay that holds them) */
    if (m->replay && !a->synced && (!a->have_seq || m->seq >= a->next_seq - 1)) {
        a->synced = 1;
        a->have_seq = 1;
        a->next_seq = m->seq + 1 > a->next_seq ? m->seq + 1 : a->next_seq;
        if (!a->quiet)
            fprintf(stderr,
                    "harvest-plan-online: the camera replayed %d fruits (to %.2f m): %u "
                    "recovered, %u lost so far\n",
                    m->n, m->seen_to_m, a->replay.recovered, a->replay.lost);
    } else if (m->replay && !a->synced) {
        return;
    }
    /* a standing vehicle's camera repeats its view: synced once per frame with news */
    view(a, m->seen_to_m, m->n > 0);
}

void po_camera_open(po_app_t *a)
{
    a->cam_sub = harvest_lcm_camera_frame_t_subscribe(a->lcm, "HARVEST_CAMERA", on_frame, a);
    /* LCM drops what a subscription has queued beyond its capacity (30 by default); no
     * frame may be lost while a horizon is solved */
    harvest_lcm_camera_frame_t_subscription_set_queue_capacity(a->cam_sub, 0);
    ask_replay(a);
}

void po_camera_close(po_app_t *a)
{
    if (a->cam_sub != NULL)
        harvest_lcm_camera_frame_t_unsubscribe(a->lcm, a->cam_sub);
    a->cam_sub = NULL;
}
