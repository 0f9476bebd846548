/* bench_exec_step: time of one hv_exec_step (ns) in the states a run spends its time in,
 * against baselines measured in the same run: an empty call through a function pointer
 * with the same arguments, and a memcpy of the whole state (what a copy-in/copy-out step
 * would cost at least). The state machine is driven to mid-harvest by the unit tests'
 * fake bus (tests/executor/exec_fixture.c), then stepped in place.
 * Usage: bench_exec_step [iterations]   (default 200000) */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "exec_fixture.h"

static uint64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000ull + (uint64_t)ts.tv_nsec;
}

typedef hv_status_t (*step_fn)(hv_exec_sm_t *, const hv_exec_event_t *, uint64_t,
                               hv_exec_actions_t *);

static hv_status_t empty_step(hv_exec_sm_t *sm, const hv_exec_event_t *ev, uint64_t now,
                              hv_exec_actions_t *out)
{
    (void)sm;
    (void)ev;
    (void)now;
    out->n = 0;
    return HV_OK;
}

/* ns per call of `fn` on a private copy of the state, restored every 64 calls so the state
 * stays mid-harvest and no heartbeat deadline expires; the restore is inside every
 * measurement alike (the empty-call baseline pays it too). Best of 3 runs. */
static double time_steps(step_fn fn, const hv_exec_sm_t *start, const hv_exec_event_t *ev,
                         uint64_t t0, long iters, hv_exec_sm_t *work)
{
    double best = 1e30;
    for (int rep = 0; rep < 3; rep++) {
        hv_exec_actions_t out;
        memcpy(work, start, sizeof *work);
        uint64_t begin = now_ns();
        for (long i = 0; i < iters; i++) {
            out.n = 0;
            fn(work, ev, t0 + (uint64_t)(i & 63) * 1000u, &out);
            if ((i & 63) == 63)
                memcpy(work, start, sizeof *work);
        }
        double ns = (double)(now_ns() - begin) / (double)iters;
        if (ns < best)
            best = ns;
    }
    return best;
}

int main(int argc, char **argv)
{
    long iters = argc > 1 ? atol(argv[1]) : 200000;
    if (iters < 1000) {
        fprintf(stderr, "bench_exec_step: iterations must be >= 1000\n");
        return 2;
    }
    fx_t *fx = malloc(sizeof *fx);
    hv_exec_sm_t *start = malloc(sizeof *start), *work = malloc(sizeof *work);
    if (!fx || !start || !work)
        return 1;
    fx_plan(fx, 4, 6);
    fx->motion_ns = 400000000ull;
    fx_start(fx, NULL);
    fx_run(fx, 1.2); /* through start-up into the first stop's pick cycles */
    if (fx->sm.phase != HV_PH_HARVEST) {
        fprintf(stderr, "bench_exec_step: fixture not harvesting (phase %s)\n",
                hv_exec_phase_name(fx->sm.phase));
        return 1;
    }
    memcpy(start, &fx->sm, sizeof *start);
    uint64_t t0 = fx->now_ns;

    hv_exec_event_t tick, status, hb;
    memset(&tick, 0, sizeof tick);
    tick.kind = HV_EV_TICK;
    memset(&status, 0, sizeof status);
    status.kind = HV_EV_ARM_STATUS;
    status.node = HV_EXEC_LEFT;
    status.u.arm.state = HV_CAN_STATE_MOVING;
    status.u.arm.sp_seq = start->arm[0].sp_seq; /* the awaited setpoint, not reached yet */
    status.u.arm.cmd_seq = start->node[HV_EXEC_LEFT].cmd_seq;
    status.u.arm.homed = 1;
    memset(&hb, 0, sizeof hb);
    hb.kind = HV_EV_HEARTBEAT;
    hb.node = HV_EXEC_RIGHT;
    hb.u.hb.time_scale = start->time_scale;
    hb.u.hb.protocol = HV_CAN_PROTOCOL_VERSION;

    volatile step_fn empty = empty_step; /* volatile: the call is not optimised away */
    double base_call = time_steps(empty, start, &tick, t0, iters, work);
    uint64_t m0 = now_ns();
    for (long i = 0; i < iters; i++) {
        memcpy(work, start, sizeof *work);
        __asm__ __volatile__("" ::"r"(work) : "memory");
    }
    double base_copy = (double)(now_ns() - m0) / (double)iters;
    double t_tick = time_steps(hv_exec_step, start, &tick, t0, iters, work);
    double t_status = time_steps(hv_exec_step, start, &status, t0, iters, work);
    double t_hb = time_steps(hv_exec_step, start, &hb, t0, iters, work);

    printf("bench_exec_step: %ld iterations each, state %zu bytes, mid-harvest (stop 1, both "
           "arms approaching)\n",
           iters, sizeof *start);
    printf("  baseline  empty call through a pointer   %8.1f ns\n", base_call);
    printf("  baseline  memcpy of the state            %8.1f ns\n", base_copy);
    printf("  step      timer tick                     %8.1f ns  (%+.1f ns over the empty call)\n",
           t_tick, t_tick - base_call);
    printf("  step      arm status (awaited, moving)   %8.1f ns  (%+.1f ns over the empty call)\n",
           t_status, t_status - base_call);
    printf("  step      heartbeat                      %8.1f ns  (%+.1f ns over the empty call)\n",
           t_hb, t_hb - base_call);
    printf("  (the call timings include restoring the state every 64 calls; the memcpy line is\n"
           "   one full copy of the state per call, the cost a copy-in/copy-out step would add)\n");
    free(fx);
    free(start);
    free(work);
    return 0;
}
