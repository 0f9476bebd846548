/* What a step sends (exec_ctx.h). */
#include "exec_ctx.h"

#include <string.h>

hv_exec_action_t *exec_push(exec_ctx_t *c, hv_exec_action_kind_t kind, int node)
{
    if (c->out->n >= HV_EXEC_MAX_ACTIONS) {
        c->overflow = 1;
        return NULL;
    }
    hv_exec_action_t *a = &c->out->a[c->out->n++];
    memset(a, 0, sizeof *a);
    a->kind = kind;
    a->node = node;
    return a;
}

void exec_remember(exec_ctx_t *c, int node, const hv_exec_action_t *a)
{
    hv_exec_node_t *n = &c->sm->node[node];
    if (!a)
        return;
    n->resend = *a;
    n->resend_active = 1;
    n->resend_ns = c->now + hv_exec_real_ns(c->sm->prm.resend_s);
}

uint64_t exec_motion_deadline(const exec_ctx_t *c, hv_exec_real_t planned_s)
{
    const hv_exec_params_t *p = &c->sm->prm;
    hv_exec_real_t real =
        (planned_s * (HV_EXEC_REAL(1.0) + p->margin) + p->slack_s) / c->sm->time_scale +
        p->latency_s;
    return c->now + hv_exec_real_ns(real);
}

uint64_t exec_command_deadline(const exec_ctx_t *c)
{
    return c->now + hv_exec_real_ns(c->sm->prm.command_timeout_s);
}

void exec_set_phase(exec_ctx_t *c, hv_exec_phase_t ph)
{
    if (c->sm->phase != ph) {
        c->sm->phase = ph;
        exec_push(c, HV_ACT_PHASE, -1);
    }
}

void exec_heartbeat(exec_ctx_t *c)
{
    hv_exec_action_t *a = exec_push(c, HV_ACT_HEARTBEAT, -1);
    if (a) {
        a->u.hb.health = c->sm->phase == HV_PH_SAFE ? HV_CAN_HEALTH_ESTOP : HV_CAN_HEALTH_OK;
        a->u.hb.time_scale = c->sm->time_scale;
    }
}

void exec_enter_safe(exec_ctx_t *c, hv_exec_safe_reason_t why, int node)
{
    hv_exec_sm_t *sm = c->sm;
    if (sm->phase == HV_PH_SAFE)
        return;
    sm->safe_reason = why;
    sm->safe_node = node;
    for (int i = 0; i < HV_EXEC_NODES; i++)
        sm->node[i].resend_active = 0; /* nothing is repeated once stopped */
    /* e-stop first: every node stops motion at once and latches */
    exec_push(c, HV_ACT_ESTOP, -1);
    exec_set_phase(c, HV_PH_SAFE);
    exec_heartbeat(c);
    sm->next_hb_ns = c->now + hv_exec_real_ns(sm->prm.heartbeat_period_s);
}

void exec_send_command(exec_ctx_t *c, int node, int command)
{
    hv_exec_node_t *n = &c->sm->node[node];
    hv_exec_action_t *a = exec_push(c, HV_ACT_COMMAND, node);
    int seq = n->next_cmd_seq;
    n->next_cmd_seq = (seq + 1) & 0xFF;
    n->wait_cmd_seq = seq;
    if (a) {
        a->u.cmd.command = command;
        a->u.cmd.seq = seq;
    }
    exec_remember(c, node, a);
}

void exec_send_to(exec_ctx_t *c, unsigned nodes, int command)
{
    for (int i = 0; i < HV_EXEC_NODES; i++)
        if (nodes & (1u << i))
            exec_send_command(c, i, command);
}

int exec_echoed(const hv_exec_sm_t *sm, int node)
{
    const hv_exec_node_t *n = &sm->node[node];
    return n->wait_cmd_seq >= 0 && n->cmd_seq == n->wait_cmd_seq;
}

hv_exec_action_t *exec_journal(exec_ctx_t *c, hv_exec_journal_kind_t kind, int pick, int stop,
                               int attempt, int outcome, int reason)
{
    hv_exec_action_t *a = exec_push(c, HV_ACT_JOURNAL, -1);
    if (a) {
        a->u.jr.kind = kind;
        a->u.jr.pick = pick;
        a->u.jr.stop = stop;
        a->u.jr.attempt = attempt;
        a->u.jr.outcome = outcome;
        a->u.jr.reason = reason;
    }
    return a;
}

void exec_fruit_event(exec_ctx_t *c, hv_exec_fruit_event_kind_t kind, int pick, int attempt,
                      int outcome, int reason)
{
    hv_exec_action_t *a = exec_push(c, HV_ACT_FRUIT_EVENT, -1);
    if (a) {
        a->u.fe.kind = kind;
        a->u.fe.pick = pick;
        a->u.fe.attempt = attempt;
        a->u.fe.outcome = outcome;
        a->u.fe.reason = reason;
    }
}

void exec_record_outcome(exec_ctx_t *c, int pick, int attempt, hv_exec_outcome_t outcome,
                         hv_exec_reason_t reason)
{
    hv_exec_sm_t *sm = c->sm;
    /* the journal first: the record must be durable before anything else happens */
    exec_journal(c, HV_JR_OUTCOME, pick, sm->plan->picks[pick].stop, attempt, outcome, reason);
    sm->prog.pick[pick] = HV_PROG_DONE;
    sm->prog.outcome[pick] = (uint8_t)outcome;
    sm->prog.reason[pick] = (uint8_t)reason;
    if (outcome == HV_OUT_PICKED)
        sm->picked++;
    else if (outcome == HV_OUT_FAILED)
        sm->failed++;
    else
        sm->skipped++;
    exec_fruit_event(c, HV_FE_OUTCOME, pick, attempt, outcome, reason);
}
