/* The executor's parameters: their defaults and their check (exec_params.h). */
#include "exec_params.h"

#include <math.h>
#include <string.h>

#include "hv/exec_sm.h"

/* The defaults; the bus's timing is the DBC's (hv/can_enums.h). */
void hv_exec_params_default(hv_exec_params_t *p)
{
    memset(p, 0, sizeof *p); /* a field added later is 0, not the caller's stack */
    p->time_scale = 0.0;     /* take the nodes' */
    /* a motion's timeout: planned * (1 + margin) + slack (plan time), over the time scale,
     * + latency (real) */
    p->margin = 0.5;
    p->slack_s = 1.0;
    p->latency_s = 0.3;
    p->heartbeat_timeout_s = HV_CAN_HEARTBEAT_TIMEOUT_MS / 1000.0; /* a node is lost */
    p->heartbeat_period_s = HV_CAN_HEARTBEAT_CYCLE_MS / 1000.0;    /* ours, and SAFE's e-stop */
    p->startup_timeout_s = 10.0;                                   /* to see every node */
    p->command_timeout_s = 1.0;                                    /* for a command's echo */
    p->home_max_s = 30.0; /* a placeholder: the arm's (hv_exec_home_max_s) is the caller's */
    p->cut_s = 1.0;       /* the simulator's defaults */
    p->release_s = 0.5;
    p->vehicle_speed_mps = 0.1;
    p->vehicle_accel_mps2 = 0.1;
    p->max_retries = 2; /* more attempts of a fruit after a recoverable fault */
    /* 5 status cycles at time scale 1 without the echo: the frame was missed */
    p->resend_s = 5 * HV_CAN_STATUS_CYCLE_MS / 1000.0;
    p->clear_estop = 0; /* only an operator clears an e-stop */
    /* twice online.horizon_limit_max's default: a horizon's solve plus as much again */
    p->wait_plan_timeout_s = 120.0;
}

double hv_exec_home_max_s(const hv_arm_t *arm)
{
    double worst = 0.0;
    for (int j = 0; j < HV_NJOINTS; j++) {
        const hv_joint_limit_t *l = &arm->limit[j];
        double d = fabs(arm->home[j] - l->min) > fabs(l->max - arm->home[j])
                       ? fabs(arm->home[j] - l->min)
                       : fabs(l->max - arm->home[j]);
        double t = hv_trap_time(d, l->vmax, l->amax);
        if (t > worst)
            worst = t;
    }
    return worst;
}

int exec_params_ok(const hv_exec_params_t *p)
{
    const hv_exec_real_t pos[] = {p->heartbeat_timeout_s, p->heartbeat_period_s,
                                  p->startup_timeout_s,   p->command_timeout_s,
                                  p->home_max_s,          p->cut_s,
                                  p->release_s,           p->vehicle_speed_mps,
                                  p->vehicle_accel_mps2,  p->resend_s};
    for (size_t i = 0; i < sizeof pos / sizeof pos[0]; i++)
        if (!(pos[i] > HV_EXEC_REAL(0.0)) || !isfinite(pos[i]))
            return 0;
    const hv_exec_real_t zero = HV_EXEC_REAL(0.0);
    return p->time_scale >= zero && isfinite(p->time_scale) && p->margin >= zero &&
           isfinite(p->margin) && p->slack_s >= zero && isfinite(p->slack_s) &&
           p->latency_s >= zero && isfinite(p->latency_s) && p->max_retries < 100 &&
           (p->clear_estop == 0 || p->clear_estop == 1) &&
           (p->online == 0 ||
            (p->online == 1 && p->wait_plan_timeout_s > zero && isfinite(p->wait_plan_timeout_s)));
}
