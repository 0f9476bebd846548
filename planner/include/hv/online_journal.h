/* The online planner's journal (hv_planner; harvest-plan-online --journal): what the
 * planner saw and committed, so that a restart commits nothing different from what the
 * executor may already run (DESIGN §5).
 *
 * Append-only text, one checksummed record per line (hv/record_line.h):
 *   HVP 1 start=<m> length=<m> margin=<m> step=<m>   (first line: the course)
 *   D <L|R> <fruit id> x=<m> y=<m> z=<m> yaw=<rad>   a detection, as it was given to
 *                                                    hv_online_detect (whatever its verdict)
 *   V <m>                                            the camera has seen up to here
 *   F <fruit> <stop>                                 a fruit (index in arrival order among the
 *                                                    accepted) committed at a candidate stop
 *   H <commit end> n=<fruits>                        a horizon committed: the n F records just
 *                                                    before it, the course up to that stop
 * Numbers have 17 significant digits (they read back to the same double). A frame's
 * records are synced at its V; a horizon's F and H records are synced before the plan is
 * published, so the executor never runs a stop this journal lacks.
 *
 * Replay, in file order, feeds the detections and views to hv_online_detect / _seen and
 * restores each horizon with hv_online_recommit, so the planner is where it was, without
 * solving again. A torn last line, and F records with no H after them at the end, are cut
 * off (never published); anything else that does not read is an error naming the line.
 */
#ifndef HV_ONLINE_JOURNAL_H
#define HV_ONLINE_JOURNAL_H

#include <stddef.h>

#include "hv/online.h"

typedef struct hv_online_journal {
    int fd; /* -1 when closed */
    char path[512];
    unsigned detections; /* D records replayed */
    unsigned horizons;   /* H records replayed */
    unsigned torn_bytes; /* bytes cut off at the end */
} hv_online_journal_t;

/* Open (create when absent) the journal at `path` for the row `o` plans (just initialised);
 * replay an existing one into `o`. HV_ERR_IO (open, read, write), HV_ERR_PLAN_FORMAT (a record
 * that does not read, another course), HV_ERR_ARG (a horizon hv_online_recommit refuses);
 * `err`: "<path>: line <n>: <what>". */
hv_status_t hv_online_journal_open(hv_online_journal_t *j, const char *path, hv_online_t *o,
                                   char *err, size_t errlen);

/* A detection, before it goes to hv_online_detect (written, synced by the next view). */
hv_status_t hv_online_journal_detection(hv_online_journal_t *j, const hv_fruit_t *f);

/* The camera's view after a frame's detections: written and synced. */
hv_status_t hv_online_journal_seen(hv_online_journal_t *j, double seen_to_m);

/* The horizon hv_online_step just committed: its fruits (o->stops[stops_from ..]) and the
 * course up to o->pos; synced. Call it before publishing the plan. */
hv_status_t hv_online_journal_horizon(hv_online_journal_t *j, const hv_online_t *o,
                                      size_t stops_from);

void hv_online_journal_close(hv_online_journal_t *j);

#endif
