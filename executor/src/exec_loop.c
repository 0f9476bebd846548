/* The executor's event loop (see hv/exec_loop.h). */
#define _POSIX_C_SOURCE 200809L
#include "hv/exec_loop.h"

#include <errno.h>
#include <string.h>
#include <time.h>

#include "hv/exec_status.h"

static uint64_t now_ns(const hv_exec_loop_t *L)
{
    return L->port->now_ns(L->port->ctx);
}

/* telemetry's time stamps: wall clock, us (LCM's convention), not the port's clock */
static int64_t wall_utime(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

static void step(hv_exec_loop_t *L, const hv_exec_event_t *ev, uint64_t now);

/* Online: the feed's line on the planner (why no plan comes, in WAIT_PLAN); else NULL. */
static const char *planner_note(const hv_exec_loop_t *L)
{
    return L->feed && L->feed->planner ? L->feed->planner(L->feed->ctx) : NULL;
}

/* Online, at each stop: stops done of those known, fruits picked, and the planner's lead:
 * the robot time of the committed stops still ahead, and how long the vehicle waited. */
static void online_progress(hv_exec_loop_t *L, uint64_t now, double t)
{
    const hv_exec_sm_t *sm = L->sm;
    const hv_exec_plan_t *p = sm->plan;
    double ahead = 0.0, first, row;
    for (int s = sm->stop; s < (int)p->n_stops; s++)
        ahead += p->stops[s].expected_s + (s > sm->stop ? p->stops[s].drive_s : 0.0);
    hv_exec_plan_wait_s(sm, now, &first, &row);
    fprintf(L->progress,
            "harvest-exec: [%8.2f s] stop %d of %u known%s at %.3f m; %u fruits "
            "picked; committed ahead %.1f s; waited for the planner %.1f s (%u times) after "
            "%.1f s at the start\n",
            t, sm->stop + 1, (unsigned)p->n_stops, sm->plan_final ? " (final)" : "",
            p->stops[sm->stop].y_m, sm->picked, ahead, row, sm->waits, first);
}

static void report(hv_exec_loop_t *L, const hv_exec_action_t *a, uint64_t now)
{
    if (!L->progress)
        return;
    const hv_exec_sm_t *sm = L->sm;
    double t = hv_exec_executed_s(sm, now);
    if (a->kind == HV_ACT_PHASE) {
        if (sm->phase == HV_PH_SAFE)
            fprintf(L->progress, "harvest-exec: [%8.2f s] SAFE: %s (node %s)\n", t,
                    hv_exec_safe_reason_name(sm->safe_reason), hv_exec_node_name(sm->safe_node));
        else if (sm->phase == HV_PH_HARVEST && sm->prm.online)
            online_progress(L, now, t);
        else if (sm->phase == HV_PH_HARVEST)
            fprintf(L->progress, "harvest-exec: [%8.2f s] stop %d/%u at %.3f m\n", t, sm->stop + 1,
                    (unsigned)sm->plan->n_stops, sm->plan->stops[sm->stop].y_m);
        else if (sm->phase == HV_PH_WAIT_PLAN)
            fprintf(L->progress,
                    "harvest-exec: [%8.2f s] waiting for the planner: %d stops "
                    "done of %u known, %u fruits picked; %s\n",
                    t, sm->stop + 1, (unsigned)sm->plan->n_stops, sm->picked,
                    planner_note(L) ? planner_note(L) : "no planner");
        else
            fprintf(L->progress, "harvest-exec: [%8.2f s] %s\n", t, hv_exec_phase_name(sm->phase));
    } else if (a->kind == HV_ACT_FRUIT_EVENT && a->u.fe.kind == HV_FE_OUTCOME &&
               a->u.fe.outcome != HV_OUT_PICKED) {
        const hv_exec_pick_t *pk = &sm->plan->picks[a->u.fe.pick];
        fprintf(L->progress, "harvest-exec: [%8.2f s] fruit %s (%c): %s, %s\n", t, pk->id,
                pk->side == HV_SIDE_LEFT ? 'L' : 'R', hv_exec_outcome_name(a->u.fe.outcome),
                hv_exec_reason_name(a->u.fe.reason));
    } else if (a->kind == HV_ACT_JOURNAL && a->u.jr.kind == HV_JR_ESTOP_CLEAR) {
        char nodes[64];
        hv_exec_node_list(a->u.jr.nodes, nodes, sizeof nodes);
        fprintf(L->progress,
                "harvest-exec: [%8.2f s] e-stop of %s cleared by %s (journalled); "
                "waiting for a heartbeat and a status of every node\n",
                t, nodes, L->clear_by ? L->clear_by : "the operator");
    } else if (a->kind == HV_ACT_FRUIT_EVENT && a->u.fe.kind == HV_FE_FAULT) {
        const hv_exec_pick_t *pk = &sm->plan->picks[a->u.fe.pick];
        fprintf(L->progress, "harvest-exec: [%8.2f s] fault at fruit %s (%c): %s, recovering\n", t,
                pk->id, pk->side == HV_SIDE_LEFT ? 'L' : 'R', hv_exec_reason_name(a->u.fe.reason));
    }
    fflush(L->progress);
}

/* err: the errno the failed write left, 0 when it set none (a port without errno, a
 * record refused before any write) */
static void journal_failed(hv_exec_loop_t *L, const char *what, hv_status_t rc, int err,
                           uint64_t now)
{
    if (L->progress)
        fprintf(L->progress, "harvest-exec: %s: journal write%s failed: %s%s%s%s\n",
                L->journal ? L->journal->path : "journal", what, hv_exec_status_name(rc),
                err ? " (" : "", err ? strerror(err) : "", err ? ")" : "");
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = HV_EV_JOURNAL_FAILED;
    step(L, &ev, now);
}

/* The actions through the port, in order; then the telemetry and progress lines of those
 * carried out (another channel than the bus, so after the step's frames). A journal record
 * the port could not store stops the batch there: what comes after it must not happen
 * without it. */
static void carry_out(hv_exec_loop_t *L, const hv_exec_actions_t *out, uint64_t now)
{
    unsigned done = 0;
    errno = 0; /* what a failed journal write leaves here is the message's */
    hv_status_t rc = hv_exec_port_carry_out(L->port, &L->tx, out, hv_exec_executed_s(L->sm, now),
                                            &L->st.io, &done);
    int err = errno;
    for (unsigned i = 0; i < done; i++) {
        const hv_exec_action_t *a = &out->a[i];
        if (a->kind == HV_ACT_FRUIT_EVENT)
            hv_exec_tm_fruit(L->tm, L->sm, a, now, wall_utime());
        else if (a->kind == HV_ACT_PHASE)
            hv_exec_tm_state(L->tm, L->sm, planner_note(L), now, wall_utime());
        else if (a->kind != HV_ACT_JOURNAL)
            continue;
        report(L, a, now);
    }
    if (rc != HV_OK)
        journal_failed(L, "", rc, err, now);
}

static void step(hv_exec_loop_t *L, const hv_exec_event_t *ev, uint64_t now)
{
    hv_exec_actions_t out;
    out.n = 0;
    uint64_t t0 = now_ns(L);
    hv_status_t st = hv_exec_step(L->sm, ev, now, &out);
    uint64_t dt = now_ns(L) - t0;
    L->st.steps++;
    L->st.step_ns_total += dt;
    if (dt > L->st.step_ns_max)
        L->st.step_ns_max = dt;
    if (st != HV_OK && st != HV_ERR_EXEC_ACTIONS_FULL)
        return; /* an event out of its domain: the state machine ignored it */
    carry_out(L, &out, now);
}

static void periodic_telemetry(hv_exec_loop_t *L, uint64_t now)
{
    if (!L->tm)
        return;
    if (now >= L->next_state_pub_ns) {
        hv_exec_tm_state(L->tm, L->sm, planner_note(L), now, wall_utime());
        L->next_state_pub_ns = now + 100000000ull; /* 10 Hz */
    }
    if (L->bus && now >= L->next_stats_pub_ns) {
        hv_can_stats_t cs;
        hv_can_get_stats(L->bus, &cs);
        hv_exec_bus_stats_t s = {hv_can_name(L->bus), cs.tx_frames,       cs.rx_frames,
                                 cs.rx_error_frames,  cs.rx_malformed,    cs.rx_unsupported,
                                 cs.rx_filtered,      cs.rx_kernel_drops, cs.tx_failures};
        hv_exec_tm_can_stats(L->tm, &s, wall_utime());
        L->next_stats_pub_ns = now + 1000000000ull; /* 1 Hz */
    }
}

static void handle_frame(hv_exec_loop_t *L, const hv_can_frame_t *f, uint64_t now)
{
    hv_exec_event_t ev;
    L->st.frames_rx++;
    switch (hv_exec_can_decode(f, &ev, L->samples)) {
    case HV_RX_EVENT: step(L, &ev, now); break;
    case HV_RX_VELOCITIES: {
        /* the velocity frame follows the joint state frame: publish the pair, 20 Hz max */
        int side = ev.node;
        if (now >= L->next_arm_pub_ns[side]) {
            hv_exec_tm_arm(L->tm, L->sm, &L->samples[side], wall_utime());
            L->next_arm_pub_ns[side] = now + 50000000ull;
        }
        break;
    }
    case HV_RX_MALFORMED: L->st.frames_rx_malformed++; break;
    default: break;
    }
}

/* Online: what the planner committed meanwhile. Called on every pass of the loop (the
 * port's wait does not say what woke it), so it costs one non-blocking read when nothing
 * came. Stops are appended only with a message that grows the plan; they are journalled
 * before the state machine hears of them, so a restart rebuilds every stop it may have
 * acted on; a failed write stops the run like any journal failure (and is tried again
 * with the next message, not on every pass). */
static void take_plan(hv_exec_loop_t *L)
{
    hv_exec_event_t ev;
    if (!L->feed->take(L->feed->ctx, &ev))
        return;
    uint64_t now = now_ns(L);
    if (L->journal && L->journal->online) {
        errno = 0;
        hv_status_t rc = hv_exec_journal_stops(L->journal);
        if (rc != HV_OK) {
            journal_failed(L, " of the committed stops", rc, errno, now);
            return;
        }
    }
    step(L, &ev, now);
}

hv_status_t hv_exec_loop_run(hv_exec_loop_t *L)
{
    if (!L || !L->sm || !L->port || !L->port->now_ns || !L->port->can_send || !L->port->can_recv ||
        !L->port->journal_append)
        return HV_ERR_ARG;
    const hv_exec_port_t *port = L->port;
    if (L->tick_s <= 0.0)
        L->tick_s = 0.01;
    uint64_t tick_ns = (uint64_t)(L->tick_s * 1e9);
    uint64_t end_ns = 0;
    uint64_t next_tick = now_ns(L);
    sig_atomic_t stops_sent = 0;
    for (;;) {
        uint64_t now = now_ns(L);
        /* each signal is one request: the first a controlled stop, the next an e-stop */
        if (L->stop && *L->stop > stops_sent) {
            hv_exec_event_t ev;
            memset(&ev, 0, sizeof ev);
            ev.kind = HV_EV_STOP_REQUEST;
            step(L, &ev, now);
            stops_sent++;
        }
        if (hv_exec_finished(L->sm)) {
            if (!end_ns)
                end_ns = now + (uint64_t)(L->linger_s * 1e9);
            else if (now >= end_ns)
                break;
        }
        /* sleep until a frame or the next tick (a signal wakes it early: the stop above) */
        if (port->wait) {
            hv_status_t ws = port->wait(port->ctx, next_tick);
            if (ws != HV_OK)
                return ws;
        }
        if (L->feed)
            take_plan(L);
        /* drain what is waiting; each frame is one event */
        for (int k = 0; k < 256; k++) {
            hv_can_frame_t f;
            if (port->can_recv(port->ctx, &f) != HV_OK)
                break;
            handle_frame(L, &f, now_ns(L));
        }
        now = now_ns(L);
        if (now >= next_tick) {
            hv_exec_event_t tick;
            memset(&tick, 0, sizeof tick);
            tick.kind = HV_EV_TICK;
            step(L, &tick, now);
            periodic_telemetry(L, now);
            next_tick += tick_ns;
            if (next_tick <= now)
                next_tick = now + tick_ns;
        }
    }
    hv_exec_tm_state(L->tm, L->sm, planner_note(L), now_ns(L), wall_utime());
    return HV_OK;
}
