/* The executor's port on Linux (see hv/exec_port_linux.h). */
#define _POSIX_C_SOURCE 200809L
#include "hv/exec_port_linux.h"

#include <errno.h>
#include <poll.h>
#include <time.h>

hv_status_t hv_exec_journal_action(hv_exec_journal_t *j, const hv_exec_action_t *a,
                                   const char *clear_by, double t_s)
{
    switch (a->u.jr.kind) {
    case HV_JR_STOP: return hv_exec_journal_stop(j, a->u.jr.stop, t_s);
    case HV_JR_CUT: return hv_exec_journal_cut(j, a->u.jr.pick, a->u.jr.attempt, t_s);
    case HV_JR_RELEASE: return hv_exec_journal_release(j, a->u.jr.pick, a->u.jr.attempt, t_s);
    case HV_JR_OUTCOME:
        return hv_exec_journal_outcome(j, a->u.jr.pick, a->u.jr.outcome, a->u.jr.reason,
                                       a->u.jr.attempt, t_s);
    case HV_JR_DONE: return hv_exec_journal_done(j, t_s);
    case HV_JR_ESTOP_CLEAR: return hv_exec_journal_estop_clear(j, clear_by, a->u.jr.nodes, t_s);
    case HV_JR_HALT: return hv_exec_journal_halt(j, a->u.jr.reason, t_s);
    }
    return HV_ERR_ARG;
}

static uint64_t linux_now_ns(void *ctx)
{
    (void)ctx;
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000ull + (uint64_t)ts.tv_nsec;
}

static hv_status_t linux_send(void *ctx, const hv_can_frame_t *f)
{
    hv_exec_port_linux_t *L = ctx;
    return hv_can_send(L->bus, f, L->send_timeout_ms);
}

static hv_status_t linux_recv(void *ctx, hv_can_frame_t *f)
{
    hv_exec_port_linux_t *L = ctx;
    return hv_can_recv(L->bus, f, 0);
}

/* poll() on the bus and wake_fd; a signal (EINTR) returns early, so SIGTERM is seen at once */
static hv_status_t linux_wait(void *ctx, uint64_t until_ns)
{
    hv_exec_port_linux_t *L = ctx;
    uint64_t now = linux_now_ns(ctx);
    uint64_t ms = until_ns > now ? (until_ns - now + 999999u) / 1000000u : 0;
    struct pollfd pfd[2] = {{hv_can_fd(L->bus), POLLIN, 0}, {L->wake_fd, POLLIN, 0}};
    if (ms > 1000)
        ms = 1000; /* returning early is allowed; an int timeout is not unbounded */
    if (poll(pfd, L->wake_fd >= 0 ? 2 : 1, (int)ms) < 0 && errno != EINTR)
        return HV_ERR_IO;
    return HV_OK;
}

static hv_status_t linux_journal(void *ctx, const hv_exec_action_t *a, double t_s)
{
    hv_exec_port_linux_t *L = ctx;
    return L->journal ? hv_exec_journal_action(L->journal, a, L->clear_by, t_s) : HV_OK;
}

void hv_exec_port_linux(hv_exec_port_t *port, hv_exec_port_linux_t *ctx)
{
    if (ctx->send_timeout_ms <= 0)
        ctx->send_timeout_ms = 10;
    port->ctx = ctx;
    port->now_ns = linux_now_ns;
    port->can_send = linux_send;
    port->can_recv = linux_recv;
    port->wait = linux_wait;
    port->journal_append = linux_journal;
}
