/* Online planning of a row whose fruit a camera reveals ahead of the vehicle (DESIGN §5).
 *
 * A step API, no I/O and no clock, so tests and the benchmark drive it directly and the
 * program `harvest-plan online` feeds it from the bus:
 *   hv_online_detect(o, fruit)  one detection: accepted, or refused with a named reason
 *   hv_online_seen(o, y)        the camera has looked at everything up to y (m)
 *   hv_online_ready(o)          whether hv_online_step would commit something
 *   hv_online_step(o, &r)       solve the next horizon window, commit its first part
 *
 * Horizon: the candidate stops [pos, pos + window) with every open fruit they reach are
 * solved by the MILP (hv_milp_solve); the stops in the first `commit` metres are committed
 * with their fruits, never to change again, and pos moves past them. A stop is committed
 * only once every fruit it could reach has been in view: its y plus the arms' reach ahead
 * (the pick model's largest y_rel) lies within the seen part of the row. A fruit detected
 * in order therefore always finds a stop not yet committed; the window that reaches the
 * course's end, once the whole row has been seen, commits everything.
 *
 * Bad input is refused, counted per reason and never planned: a detection outside the row
 * (`outside_row`: y off [row start, row end], or not finite), a second detection of a
 * fruit id already known (`duplicate`: the first one stands, so nothing is picked twice),
 * and one whose every reaching stop is committed already (`late`: the vehicle has been
 * sent past it). A fruit no stop reaches is listed unreachable with its reason as in an
 * offline plan (`unreachable`), which is not bad input.
 */
#ifndef HV_ONLINE_H
#define HV_ONLINE_H

#include <stddef.h>
#include <stdint.h>

#include "hv/milp.h"
#include "hv/pick_model.h"
#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum hv_online_verdict {
    HV_DET_ACCEPTED = 0,
    HV_DET_UNREACHABLE, /* accepted, but no candidate stop reaches it (listed, not planned) */
    HV_DET_OUTSIDE_ROW,
    HV_DET_DUPLICATE,
    HV_DET_LATE,
    HV_DET_COUNT
} hv_online_verdict_t;

/* "accepted", "unreachable", "outside_row", "duplicate", "late"; "?" otherwise. */
const char *hv_online_verdict_name(int verdict);

typedef struct hv_online_options {
    double window_m;        /* horizon H solved per step, > 0 */
    double commit_m;        /* (0, H]: committed per step */
    hv_milp_options_t milp; /* per window (hv_online_step: its time_limit_s) */
    /* hv_online_step_ahead: a window's limit is HV_ONLINE_AHEAD_SHARE of the robot time
     * committed ahead when it starts, within [limit_min_s, limit_max_s]
     * (online.horizon_limit_min / _max) */
    double limit_min_s, limit_max_s;
} hv_online_options_t;

/* The share of the robot's committed work ahead a window may take to solve: the next
 * window then still finds the other half, plus what this one commits, ahead of the
 * robot, so the vehicle never waits on the planner once it has work. */
#define HV_ONLINE_AHEAD_SHARE 0.5

/* H = 2 m, commit 1 m, the MILP's defaults with a 10 s limit per window; limits by the
 * work ahead within [10, 60] s. */
void hv_online_options_default(hv_online_options_t *opt);

/* What one step did. */
typedef struct hv_online_step_result {
    size_t stops_from, stops_to; /* new committed stops: hv_online_t.stops[from .. to) */
    size_t fruits;               /* fruits committed by this step */
    size_t window_fruits;        /* fruits in the solved window */
    hv_solve_status_t status;    /* the window's solve; OPTIMAL when it had no fruit */
    double gap;
    double solve_s;     /* the solver's runtime */
    double limit_s;     /* the window's time limit */
    int kept_heuristic; /* 1: the solve found nothing, the window's FOV plan was kept */
} hv_online_step_result_t;

/* A committed stop with work: its fruits are fruit_of[first .. first + count) (indices
 * into hv_online_t.fruits), left before right, in y order per side. */
typedef struct hv_online_stop {
    uint32_t index; /* candidate stop index over the course */
    double y_m;
    size_t first, count;
} hv_online_stop_t;

typedef struct hv_online {
    hv_instance_params_t params;
    const hv_pick_model_t *model;
    hv_online_options_t opt;
    size_t n_course_stops;
    double reach_ahead_m; /* largest fruit y - stop y any arm reaches */
    double seen_to_m;     /* everything up to here has been in view */
    size_t pos;           /* first candidate stop not committed */
    int done;             /* every stop committed: the row is planned to its end */

    size_t n_fruits, cap_fruits;
    hv_fruit_t *fruits;   /* accepted detections, in arrival order */
    uint32_t *fruit_stop; /* committed candidate stop, or HV_NO_STOP */
    unsigned char *why;   /* 0, or why no stop reaches it (hv_instance_why_name) */

    size_t n_stops, cap_stops;
    hv_online_stop_t *stops; /* committed stops with work, in driving order */
    size_t n_order, cap_order;
    uint32_t *fruit_of; /* fruits of the committed stops, stop by stop */

    unsigned counts[HV_DET_COUNT]; /* detections per verdict */
    unsigned steps;                /* windows solved */
    unsigned steps_optimal;
} hv_online_t;

/* Start a row with the given course (hv_instance_params_from_config) and pick model (must
 * outlive `o`). HV_ERR_ARG on bad options, HV_ERR_PLAN_PARAMS on a bad course. */
hv_status_t hv_online_init(hv_online_t *o, const hv_instance_params_t *params,
                           const hv_pick_model_t *model, const hv_online_options_t *opt);
void hv_online_free(hv_online_t *o);

/* One detection; *verdict says what became of it. HV_OK unless out of memory or bad
 * arguments: refused input is a verdict, not an error. */
hv_status_t hv_online_detect(hv_online_t *o, const hv_fruit_t *fruit, hv_online_verdict_t *verdict);

/* 1 when a fruit of f's id was accepted with f's side and pose exactly: the camera saying
 * again what it said (its replay), which is not a duplicate and must not be detected
 * again; else 0. */
int hv_online_known(const hv_online_t *o, const hv_fruit_t *f);

/* The camera has seen the row up to y_m (monotone: a smaller value changes nothing). */
void hv_online_seen(hv_online_t *o, double y_m);

/* 1 when hv_online_step would commit at least `commit` metres, or the rest of the row
 * once all of it has been seen; 0 while the camera must see further first, or when done. */
int hv_online_ready(const hv_online_t *o);

/* Solve the next window and commit (nothing when not ready: r->stops_from == stops_to). */
hv_status_t hv_online_step(hv_online_t *o, hv_online_step_result_t *r);

/* The same with the window's limit taken from the robot time committed ahead of the robot
 * when the step starts, ahead_s (hv_online_ahead_s; 0 when it has none):
 * HV_ONLINE_AHEAD_SHARE of it, within [opt.limit_min_s, opt.limit_max_s]. */
hv_status_t hv_online_step_ahead(hv_online_t *o, double ahead_s, hv_online_step_result_t *r);

/* The limit hv_online_step_ahead gives a window when ahead_s of work is committed ahead. */
double hv_online_horizon_limit_s(const hv_online_t *o, double ahead_s);

/* Robot time (s) the vehicle stands at committed stop k (< o->n_stops): its slower arm's
 * pick costs plus the stop's own cost (tau). */
double hv_online_stop_work_s(const hv_online_t *o, size_t k);

/* Robot time (s) of the committed stops [from, o->n_stops) for a vehicle at y_m driving at
 * speed_mps: the drives between them and their work. 0 when from >= o->n_stops. */
double hv_online_ahead_s(const hv_online_t *o, size_t from, double y_m, double speed_mps);

/* Restore a horizon committed before a restart, from the planner's own record of it
 * (harvest-plan-online --journal): fruit fruits[k] (an index into o->fruits) at candidate
 * stop stops[k], and the course committed up to candidate stop commit_end (exclusive), as
 * hv_online_step left them; no solve. The detections and views before it must have been
 * replayed first, in their order, so that o->fruits is what it was. HV_ERR_ARG when it
 * cannot be what a step committed: commit_end not beyond the committed part or past the
 * course's end, a fruit unknown, unreachable or committed already, or a stop outside
 * [committed part, commit_end) or that does not reach the fruit. */
hv_status_t hv_online_recommit(hv_online_t *o, size_t commit_end, const uint32_t *fruits,
                               const uint32_t *stops, size_t n);

/* The y up to which the course is committed: the vehicle may drive this far (m). */
double hv_online_commit_y(const hv_online_t *o);

/* The committed plan as an assignment over the accepted fruits (a->n_fruits ==
 * o->n_fruits; HV_NO_STOP for the unreachable and the not yet committed). */
hv_status_t hv_online_assignment(const hv_online_t *o, hv_assignment_t *a);

#ifdef __cplusplus
}
#endif
#endif /* HV_ONLINE_H */
