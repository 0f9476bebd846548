/* Plan assembly from an assignment (plan_build.h). */
#include <stdlib.h>
#include <string.h>

#include "hv/plan_build.h"
#include "hv/plan_eval.h"
#include "hv/plan_status.h"

typedef struct slot {
    int pass;
    uint32_t stop;
    uint32_t fruit;
    double y;
    const char *id;
} slot_t;

static int cmp_slot(const void *a, const void *b)
{
    const slot_t *x = a, *y = b;
    if (x->pass != y->pass)
        return x->pass - y->pass;
    if (x->stop != y->stop)
        return x->stop < y->stop ? -1 : 1;
    if (x->y != y->y)
        return x->y < y->y ? -1 : 1;
    return strcmp(x->id, y->id);
}

static hv_status_t copy_meta(hv_plan_t *plan, const hv_plan_meta_t *m)
{
    const char *none = "";
    if (hv_plan_copy_str(plan->method, sizeof plan->method, m->method) != HV_OK ||
        hv_plan_copy_str(plan->fruit_map, sizeof plan->fruit_map,
                         m->fruit_map ? m->fruit_map : none) != HV_OK ||
        hv_plan_copy_str(plan->cost_table_left, sizeof plan->cost_table_left,
                         m->cost_table_left ? m->cost_table_left : none) != HV_OK ||
        hv_plan_copy_str(plan->cost_table_right, sizeof plan->cost_table_right,
                         m->cost_table_right ? m->cost_table_right : none) != HV_OK ||
        hv_plan_copy_str(plan->config, sizeof plan->config, m->config ? m->config : none) !=
            HV_OK ||
        hv_plan_copy_str(plan->solver_status, sizeof plan->solver_status, m->solver_status) !=
            HV_OK ||
        hv_plan_copy_str(plan->pick_time, sizeof plan->pick_time,
                         m->pick_time ? m->pick_time : "one_way") != HV_OK) {
        return HV_ERR_ARG; /* a path longer than HV_PLAN_PATH_LEN - 1 */
    }
    plan->stop_step_m = m->params.stop_step_m;
    plan->row_start_m = m->params.row_start_m;
    plan->row_length_m = m->params.row_length_m;
    plan->stop_penalty_s = m->params.stop_penalty_s;
    plan->travel_time_s = m->params.travel_time_s;
    plan->stop_margin_m = m->params.stop_margin_m;
    plan->vehicle_speed_mps = m->vehicle_speed_mps;
    plan->gap = m->gap;
    plan->nodes = m->nodes;
    plan->runtime_s = m->runtime_s;
    plan->time_limit_s = m->time_limit_s;
    plan->horizon = m->horizon;
    return HV_OK;
}

hv_status_t hv_plan_build(const hv_instance_t *inst, const hv_assignment_t *a,
                          const unsigned char *passes, const hv_plan_meta_t *meta, hv_plan_t *plan)
{
    if (inst == NULL || a == NULL || meta == NULL || plan == NULL || meta->method == NULL ||
        meta->solver_status == NULL || a->n_fruits != inst->n_fruits) {
        return HV_ERR_ARG;
    }
    memset(plan, 0, sizeof *plan);
    hv_eval_t ev;
    hv_status_t st = hv_assignment_eval(inst, a, &ev); /* validates every pair */
    if (st != HV_OK) {
        return st;
    }
    st = copy_meta(plan, meta);
    if (st != HV_OK) {
        return st;
    }

    size_t n_slots = ev.fruits_planned, n_unr = inst->n_fruits - ev.fruits_planned;
    slot_t *slots = malloc((n_slots ? n_slots : 1) * sizeof *slots);
    plan->unreachable = calloc(n_unr ? n_unr : 1, sizeof *plan->unreachable);
    plan->stops = calloc(n_slots ? n_slots : 1, sizeof *plan->stops); /* <= one per fruit */
    if (slots == NULL || plan->unreachable == NULL || plan->stops == NULL) {
        free(slots);
        hv_plan_free(plan);
        return HV_ERR_PLAN_NOMEM;
    }
    size_t k = 0;
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        const hv_fruit_t *fr = &inst->fruits[f];
        if (a->fruit_stop[f] == HV_NO_STOP) {
            hv_plan_unreachable_t *u = &plan->unreachable[plan->n_unreachable++];
            memcpy(u->id, fr->id, sizeof u->id);
            u->side = fr->side;
            /* instances built by hand carry no reasons: nothing in reach, as far as known */
            hv_plan_copy_str(u->reason, sizeof u->reason,
                             hv_instance_why_name(inst->why ? inst->why[f] : HV_PICK_DEPTH));
            continue;
        }
        slots[k].pass = passes ? passes[f] : 0;
        slots[k].stop = a->fruit_stop[f];
        slots[k].fruit = (uint32_t)f;
        slots[k].y = fr->y_m;
        slots[k].id = fr->id;
        ++k;
    }
    qsort(slots, n_slots, sizeof *slots, cmp_slot);

    for (size_t i = 0; i < n_slots && st == HV_OK;) {
        size_t j = i;
        size_t nl = 0, nr = 0;
        while (j < n_slots && slots[j].pass == slots[i].pass && slots[j].stop == slots[i].stop) {
            if (inst->fruits[slots[j].fruit].side == HV_SIDE_LEFT) {
                ++nl;
            } else {
                ++nr;
            }
            ++j;
        }
        hv_plan_stop_t *s = &plan->stops[plan->n_stops++];
        s->index = slots[i].stop;
        s->y_m = inst->stop_y_m[slots[i].stop];
        s->pass = slots[i].pass;
        s->left = calloc(nl ? nl : 1, sizeof *s->left);
        s->right = calloc(nr ? nr : 1, sizeof *s->right);
        if (s->left == NULL || s->right == NULL) {
            st = HV_ERR_PLAN_NOMEM;
            break;
        }
        for (size_t q = i; q < j; ++q) {
            const hv_fruit_t *fr = &inst->fruits[slots[q].fruit];
            double c = 0.0;
            hv_instance_pair_cost(inst, slots[q].fruit, slots[q].stop, &c);
            int left = fr->side == HV_SIDE_LEFT;
            hv_plan_pick_t *pk = left ? &s->left[s->n_left++] : &s->right[s->n_right++];
            double *sum = left ? &s->c_left_s : &s->c_right_s;
            memcpy(pk->id, fr->id, sizeof pk->id);
            pk->x_m = fr->x_m;
            pk->y_m = fr->y_m;
            pk->z_m = fr->z_m;
            pk->yaw_rad = fr->yaw_rad;
            pk->cost_s = c;
            pk->start_s = *sum; /* picks of one arm run back to back */
            *sum += c;
        }
        s->c_s = s->c_left_s > s->c_right_s ? s->c_left_s : s->c_right_s;
        s->idle_left_s = s->c_s - s->c_left_s;
        s->idle_right_s = s->c_s - s->c_right_s;
        plan->pick_time_s += s->c_s;
        i = j;
    }
    free(slots);
    if (st != HV_OK) {
        hv_plan_free(plan);
        return st;
    }
    int n_passes = passes != NULL ? 2 : 1; /* Serial always drives the row twice */
    plan->n_stops_total = plan->n_stops;
    plan->fruits_planned = ev.fruits_planned;
    plan->fruits_unreachable = plan->n_unreachable;
    plan->stop_time_s = meta->params.stop_penalty_s * (double)plan->n_stops;
    plan->total_travel_time_s = meta->params.travel_time_s * n_passes;
    plan->makespan_s = plan->pick_time_s + plan->stop_time_s + plan->total_travel_time_s;
    plan->throughput_fruit_per_s =
        plan->makespan_s > 0 ? (double)plan->fruits_planned / plan->makespan_s : 0.0;
    return HV_OK;
}
