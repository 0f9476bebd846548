/* See exec_trace.h. */
#define _POSIX_C_SOURCE 200809L
#include "exec_trace.h"

#include <stdlib.h>
#include <string.h>

#include "hv/exec_status.h"
#include "hv/file_io.h"

/* a real with the digits that bring it back exactly: 9 for a float, 17 for a double */
static void real(FILE *f, hv_exec_real_t x)
{
    fprintf(f, "%.*g", sizeof x == sizeof(float) ? 9 : 17, (double)x);
}

void exec_trace_begin(exec_trace_t *t, FILE *f, const char *title)
{
    memset(t, 0, sizeof *t);
    t->f = f;
    fprintf(f, "# %s\n", title);
}

static void event_line(FILE *f, const hv_exec_event_t *ev)
{
    const char *node = hv_exec_node_name(ev->node);
    switch (ev->kind) {
    case HV_EV_TICK: fprintf(f, "tick"); break;
    case HV_EV_HEARTBEAT:
        fprintf(f, "heartbeat %s health=%d protocol=%d scale=", node, ev->u.hb.health,
                ev->u.hb.protocol);
        real(f, ev->u.hb.time_scale);
        break;
    case HV_EV_VEHICLE_STATUS:
        fprintf(f, "vehicle_status %s state=%d arrived=%d faults=0x%x move=%d cmd=%d pos=", node,
                ev->u.veh.state, ev->u.veh.arrived, (unsigned)ev->u.veh.fault_bits,
                ev->u.veh.move_seq, ev->u.veh.cmd_seq);
        real(f, ev->u.veh.position_m);
        break;
    case HV_EV_ARM_STATUS:
        fprintf(f, "arm_status %s state=%d reached=%d homed=%d sp=%d cmd=%d faults=0x%x", node,
                ev->u.arm.state, ev->u.arm.reached, ev->u.arm.homed, ev->u.arm.sp_seq,
                ev->u.arm.cmd_seq, (unsigned)ev->u.arm.fault_bits);
        break;
    case HV_EV_EE_STATUS:
        fprintf(f, "ee_status %s state=%d action=%d ee=%d held=%d", node, ev->u.ee.state,
                ev->u.ee.action, ev->u.ee.ee_seq, ev->u.ee.fruit_held);
        break;
    case HV_EV_STOP_REQUEST: fprintf(f, "stop_request from_bus=%d", ev->u.stop.from_bus); break;
    case HV_EV_JOURNAL_FAILED: fprintf(f, "journal_failed"); break;
    case HV_EV_PLAN_GROWN:
        fprintf(f, "plan_grown final=%d advance=", ev->u.plan.final);
        real(f, ev->u.plan.advance_m);
        break;
    default: fprintf(f, "event kind=%d node=%d", (int)ev->kind, ev->node); break;
    }
}

static void action_line(FILE *f, const hv_exec_action_t *a)
{
    const char *node = hv_exec_node_name(a->node);
    fprintf(f, "  > ");
    switch (a->kind) {
    case HV_ACT_HEARTBEAT:
        fprintf(f, "heartbeat health=%d scale=", a->u.hb.health);
        real(f, a->u.hb.time_scale);
        break;
    case HV_ACT_ESTOP: fprintf(f, "estop"); break;
    case HV_ACT_COMMAND:
        fprintf(f, "command %s %d seq=%d", node, a->u.cmd.command, a->u.cmd.seq);
        break;
    case HV_ACT_SETPOINT:
        fprintf(f, "setpoint %s seq=%d q=", node, a->u.sp.seq);
        for (int j = 0; j < HV_NJOINTS; j++) {
            fprintf(f, j ? "," : "");
            real(f, a->u.sp.q[j]);
        }
        break;
    case HV_ACT_EE: fprintf(f, "ee %s action=%d seq=%d", node, a->u.ee.action, a->u.ee.seq); break;
    case HV_ACT_MOVE:
        fprintf(f, "move %s seq=%d target=", node, a->u.move.seq);
        real(f, a->u.move.target_m);
        fprintf(f, " speed=");
        real(f, a->u.move.speed_mps);
        break;
    case HV_ACT_JOURNAL:
        fprintf(f, "journal %d pick=%d stop=%d attempt=%d outcome=%d reason=%d nodes=0x%x",
                (int)a->u.jr.kind, a->u.jr.pick, a->u.jr.stop, a->u.jr.attempt, a->u.jr.outcome,
                a->u.jr.reason, a->u.jr.nodes);
        break;
    case HV_ACT_FRUIT_EVENT:
        fprintf(f, "fruit %d pick=%d attempt=%d outcome=%d reason=%d", (int)a->u.fe.kind,
                a->u.fe.pick, a->u.fe.attempt, a->u.fe.outcome, a->u.fe.reason);
        break;
    case HV_ACT_PHASE: fprintf(f, "phase"); break;
    default: fprintf(f, "action kind=%d node=%d", (int)a->kind, a->node); break;
    }
    fprintf(f, "\n");
}

/* what the machine is doing: its phase and step, the stop, each arm, the stop and safe
 * state, the counts */
static void state_line(char *buf, size_t len, const hv_exec_sm_t *sm)
{
    const hv_exec_arm_t *l = &sm->arm[0], *r = &sm->arm[1];
    snprintf(buf, len,
             "%s/%d stop=%d latched=0x%x left=%s:%d:%u:%u right=%s:%d:%u:%u safe=%d:%d "
             "halt=%d:%d counts=%u,%u,%u,%u,%u",
             hv_exec_phase_name(sm->phase), sm->sub, sm->stop, sm->latched,
             hv_exec_arm_phase_name(l->phase), l->pick, l->next, l->attempt,
             hv_exec_arm_phase_name(r->phase), r->pick, r->next, r->attempt, (int)sm->safe_reason,
             sm->safe_node, sm->stop_requested, (int)sm->stop_reason, sm->picked, sm->failed,
             sm->skipped, sm->faults, sm->resends);
}

void exec_trace_step(exec_trace_t *t, const hv_exec_sm_t *sm, const hv_exec_event_t *ev,
                     uint64_t now_ns, hv_status_t st, const hv_exec_actions_t *out)
{
    char state[sizeof t->state];
    if (t->steps++ == 0)
        t->t0_ns = now_ns;
    t->sm = sm;
    t->now_ns = now_ns;
    state_line(state, sizeof state, sm);
    if (out->n == 0 && st == HV_OK && strcmp(state, t->state) == 0)
        return; /* a quiet step: nothing sent, nothing changed that the state line shows */
    uint64_t dt = now_ns - t->t0_ns;
    fprintf(t->f, "#%llu %llu.%09llu ", (unsigned long long)(t->steps - 1),
            (unsigned long long)(dt / 1000000000u), (unsigned long long)(dt % 1000000000u));
    event_line(t->f, ev);
    fprintf(t->f, "%s%s\n", st == HV_OK ? "" : " -> ", st == HV_OK ? "" : hv_exec_status_name(st));
    for (unsigned i = 0; i < out->n; i++)
        action_line(t->f, &out->a[i]);
    if (strcmp(state, t->state) != 0) {
        fprintf(t->f, "  = %s\n", state);
        memcpy(t->state, state, sizeof state);
    }
}

void exec_trace_hook(void *ctx, const hv_exec_sm_t *sm, const hv_exec_event_t *ev, uint64_t now_ns,
                     hv_status_t st, const hv_exec_actions_t *out)
{
    exec_trace_step(ctx, sm, ev, now_ns, st, out);
}

void exec_trace_end(exec_trace_t *t)
{
    const hv_exec_sm_t *sm = t->sm;
    if (!sm) {
        fprintf(t->f, "end: no step\n");
        return;
    }
    fprintf(t->f, "end: %llu steps, %s\n", (unsigned long long)t->steps, t->state);
    for (unsigned i = 0; i < sm->plan->n_picks; i++)
        fprintf(t->f, "pick %u: progress=%d outcome=%d reason=%d\n", i, sm->prog.pick[i],
                sm->prog.outcome[i], sm->prog.reason[i]);
    fprintf(t->f, "stops reached:");
    for (unsigned s = 0; s < sm->plan->n_stops; s++)
        fprintf(t->f, " %d", sm->prog.stop_reached[s]);
    hv_exec_real_t first, row;
    hv_exec_plan_wait_s(sm, t->now_ns, &first, &row);
    fprintf(t->f, "\nrow_done=%d waits=%u finished=%d executed=", sm->prog.row_done, sm->waits,
            hv_exec_finished(sm));
    real(t->f, hv_exec_executed_s(sm, t->now_ns));
    fprintf(t->f, " wait_first=");
    real(t->f, first);
    fprintf(t->f, " wait_row=");
    real(t->f, row);
    fprintf(t->f, "\n");
}

/* the number of the first line where a and b differ (1-based), and where it starts in each */
static size_t first_difference(const char *a, size_t na, const char *b, size_t nb, size_t *at_a,
                               size_t *at_b)
{
    size_t line = 1, start = 0, i = 0;
    while (i < na && i < nb && a[i] == b[i]) {
        if (a[i] == '\n') {
            line++;
            start = i + 1;
        }
        i++;
    }
    *at_a = *at_b = start;
    return line;
}

static void print_line(const char *label, const char *s, size_t n, size_t at)
{
    size_t end = at;
    while (end < n && s[end] != '\n')
        end++;
    fprintf(stderr, "  %s: %.*s%s\n", label, (int)(end - at), s + at, at >= n ? "(end)" : "");
}

static int write_file(const char *path, const char *text, size_t len)
{
    char err[512];
    if (hv_file_write_atomic(path, text, len, err, sizeof err) != HV_OK) {
        fprintf(stderr, "exec_trace: %s\n", err);
        return -1;
    }
    return 1;
}

int exec_trace_golden(const char *dir, const char *name, const char *text, size_t len, int write)
{
    char path[4096], err[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (write)
        return write_file(path, text, len);
    void *data;
    size_t n;
    if (hv_file_read_all(path, &data, &n, err, sizeof err) != HV_OK) {
        fprintf(stderr, "exec_trace: %s (write it with --write)\n", err);
        return -1;
    }
    int same = n == len && memcmp(data, text, len) == 0;
    if (!same) {
        size_t at_g, at_t;
        size_t line = first_difference(data, n, text, len, &at_g, &at_t);
        char actual[4096];
        snprintf(actual, sizeof actual, "%s.actual", name);
        fprintf(stderr, "%s: differs from the recorded trace at line %zu (this build's: %s)\n",
                path, line, actual);
        print_line("recorded", data, n, at_g);
        print_line("now     ", text, len, at_t);
        write_file(actual, text, len);
    }
    free(data);
    return same;
}
