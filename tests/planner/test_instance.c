/* Instance building and evaluation on synthetic tables whose every cost is known. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hv/plan_eval.h"
#include "hv/plan_instance.h"
#include "hv/plan_status.h"
#include "hv/pick_model.h"
#include "tiny_tables.h"

typedef struct fx {
    hv_config_t cfg;
    uint8_t *buf[2];
    hv_costtab_t tab[2];
    hv_pick_model_t model;
} fx_t;

/* Band model, but nothing above z = 0.70 m (iz > 30) is reachable. */
static uint16_t low_band(hv_side_t side, double y_rel, uint32_t ix, uint32_t iz, uint32_t iw,
                         void *ctx)
{
    return iz > 30 ? HV_COST_UNREACHABLE : tt_band_cost(side, y_rel, ix, iz, iw, ctx);
}

static int setup(void **state)
{
    static fx_t fx;
    static tt_band_t band = {0.10, 2000, 15, 10};
    if (tt_load_config(&fx.cfg) != 0) {
        return -1;
    }
    for (int s = 0; s < 2; ++s) {
        size_t len;
        if (tt_make_table(&fx.cfg, (hv_side_t)s, low_band, &band, &fx.buf[s], &len, &fx.tab[s]) !=
            0) {
            return -1;
        }
    }
    tt_table_model(fx.tab, &fx.model);
    *state = &fx;
    return 0;
}

static int teardown(void **state)
{
    fx_t *fx = *state;
    free(fx->buf[0]);
    free(fx->buf[1]);
    return 0;
}

static hv_fruit_t fruit(const char *id, hv_side_t side, double y, double z)
{
    hv_fruit_t f;
    memset(&f, 0, sizeof f);
    strcpy(f.id, id);
    f.side = side;
    f.x_m = side == HV_SIDE_LEFT ? -0.42 : 0.42;
    f.y_m = y;
    f.z_m = z;
    f.yaw_rad = 0.0;
    return f;
}

static hv_instance_params_t params_1m(void)
{
    hv_instance_params_t p = {0.0, 1.0, 0.01, 5.0, 10.0, 0.0};
    return p;
}

static void test_pairs(void **state)
{
    fx_t *fx = *state;
    hv_fruit_t fr[4] = {fruit("A", HV_SIDE_LEFT, 0.50, 0.60), fruit("B", HV_SIDE_RIGHT, 0.02, 0.40),
                        fruit("C", HV_SIDE_RIGHT, 0.50, 0.75),
                        fruit("D", HV_SIDE_RIGHT, 0.97, 0.50)};
    hv_instance_params_t pr = params_1m();
    hv_instance_t inst;
    hv_diag_t d;
    assert_int_equal(hv_instance_build(&pr, fr, 4, &fx->model, &inst, &d), HV_OK);
    assert_int_equal(inst.n_stops, 101);
    assert_true(fabs(inst.stop_y_m[100] - 1.0) < 1e-12);
    /* A: stops 0.40..0.60 (21); B: 0.00..0.12 (13); C: none (z too high); D: 0.87..1.00 (14) */
    assert_int_equal(inst.fruit_begin[1] - inst.fruit_begin[0], 21);
    assert_int_equal(inst.fruit_begin[2] - inst.fruit_begin[1], 13);
    assert_int_equal(inst.fruit_begin[3] - inst.fruit_begin[2], 0);
    assert_int_equal(inst.fruit_begin[4] - inst.fruit_begin[3], 14);
    assert_int_equal(hv_instance_unreachable_count(&inst), 1);
    double c;
    assert_int_equal(hv_instance_pair_cost(&inst, 0, 50, &c), HV_OK);
    assert_true(fabs(c - 2.200) < 1e-12); /* 2000 + 20 (iz) * 10 ms */
    assert_int_equal(hv_instance_pair_cost(&inst, 0, 45, &c), HV_OK);
    assert_true(fabs(c - 2.275) < 1e-12); /* + 5 cm * 15 ms */
    assert_int_equal(hv_instance_pair_cost(&inst, 0, 39, &c), HV_ERR_UNREACHABLE);
    assert_int_equal(hv_instance_pair_cost(&inst, 2, 50, &c), HV_ERR_UNREACHABLE);
    /* every pair is sorted by (fruit, stop) and agrees with the table's own lookup */
    for (size_t k = 0; k < inst.n_pairs; ++k) {
        const hv_pair_t *p = &inst.pairs[k];
        if (k > 0) {
            assert_true(inst.pairs[k - 1].fruit < p->fruit ||
                        (inst.pairs[k - 1].fruit == p->fruit && inst.pairs[k - 1].stop < p->stop));
        }
        const hv_fruit_t *f = &fr[p->fruit];
        uint16_t ms;
        assert_int_equal(hv_costtab_lookup(&fx->tab[f->side], f->x_m,
                                           f->y_m - inst.stop_y_m[p->stop], f->z_m, f->yaw_rad,
                                           &ms),
                         HV_OK);
        assert_true(fabs(p->cost_s - ms / 1000.0) < 1e-12);
    }
    hv_instance_free(&inst);
}

static void test_eval(void **state)
{
    fx_t *fx = *state;
    hv_fruit_t fr[4] = {fruit("A", HV_SIDE_LEFT, 0.50, 0.60), fruit("B", HV_SIDE_RIGHT, 0.50, 0.40),
                        fruit("C", HV_SIDE_RIGHT, 0.55, 0.40), fruit("U", HV_SIDE_LEFT, 0.5, 0.79)};
    hv_instance_params_t pr = params_1m();
    hv_instance_t inst;
    hv_diag_t d;
    assert_int_equal(hv_instance_build(&pr, fr, 4, &fx->model, &inst, &d), HV_OK);
    hv_assignment_t a;
    assert_int_equal(hv_assignment_alloc(&a, 4), HV_OK);
    a.fruit_stop[0] = 50; /* A: 2.200 (left) */
    a.fruit_stop[1] = 50; /* B: 2.000 (right) */
    a.fruit_stop[2] = 50; /* C: 2.075 (right, 5 cm off) */
    hv_eval_t ev;
    assert_int_equal(hv_assignment_eval(&inst, &a, &ev), HV_OK);
    /* one stop: max(2.2, 4.075) + tau 5 + T_travel 10 */
    assert_int_equal(ev.stops, 1);
    assert_int_equal(ev.fruits_planned, 3);
    assert_true(fabs(ev.makespan_s - (4.075 + 5.0 + 10.0)) < 1e-9);
    a.fruit_stop[2] = 55; /* C alone at 0.55: 2.000 */
    assert_int_equal(hv_assignment_eval(&inst, &a, &ev), HV_OK);
    assert_int_equal(ev.stops, 2);
    assert_true(fabs(ev.pick_time_s - (2.2 + 2.0)) < 1e-9);
    assert_true(fabs(ev.makespan_s - (4.2 + 10.0 + 10.0)) < 1e-9);
    double t;
    assert_int_equal(hv_assignment_makespan(&inst, &a, &t), HV_OK);
    assert_true(fabs(t - ev.makespan_s) < 1e-12);

    a.fruit_stop[3] = 50; /* the unreachable fruit may not be assigned */
    assert_int_equal(hv_assignment_eval(&inst, &a, &ev), HV_ERR_PLAN_BAD_PAIR);
    a.fruit_stop[3] = HV_NO_STOP;
    a.fruit_stop[0] = 70; /* A is not reachable from 0.70 */
    assert_int_equal(hv_assignment_eval(&inst, &a, &ev), HV_ERR_PLAN_BAD_PAIR);
    a.fruit_stop[0] = HV_NO_STOP; /* A is reachable, so it must be assigned */
    assert_int_equal(hv_assignment_eval(&inst, &a, &ev), HV_ERR_PLAN_UNASSIGNED);
    hv_assignment_free(&a);
    hv_instance_free(&inst);
}

static void test_subset(void **state)
{
    fx_t *fx = *state;
    hv_fruit_t fr[3] = {fruit("A", HV_SIDE_LEFT, 0.20, 0.60), fruit("B", HV_SIDE_RIGHT, 0.50, 0.40),
                        fruit("C", HV_SIDE_RIGHT, 0.80, 0.40)};
    hv_instance_params_t pr = params_1m();
    hv_instance_t inst, sub;
    hv_diag_t d;
    assert_int_equal(hv_instance_build(&pr, fr, 3, &fx->model, &inst, &d), HV_OK);
    uint32_t back[3];
    /* stops 0.25 .. 0.54: A reaches 0.25..0.30, B 0.40..0.54, C none (dropped) */
    assert_int_equal(hv_instance_subset(&inst, 25, 55, NULL, 1, &sub, back), HV_OK);
    assert_int_equal(sub.n_stops, 30);
    assert_int_equal(sub.n_fruits, 2);
    assert_int_equal(back[0], 0);
    assert_int_equal(back[1], 1);
    assert_int_equal(sub.fruit_begin[1] - sub.fruit_begin[0], 6);
    assert_int_equal(sub.fruit_begin[2] - sub.fruit_begin[1], 15);
    double c_full, c_sub;
    assert_int_equal(hv_instance_pair_cost(&inst, 1, 45, &c_full), HV_OK);
    assert_int_equal(hv_instance_pair_cost(&sub, 1, 20, &c_sub), HV_OK);
    assert_true(c_full == c_sub);
    hv_instance_free(&sub);
    unsigned char keep[3] = {0, 1, 1}; /* keep_fruit without dropping: C stays, with no pairs */
    assert_int_equal(hv_instance_subset(&inst, 25, 55, keep, 0, &sub, back), HV_OK);
    assert_int_equal(sub.n_fruits, 2);
    assert_int_equal(back[1], 2);
    assert_int_equal(hv_instance_unreachable_count(&sub), 1);
    hv_instance_free(&sub);
    hv_instance_free(&inst);
}

/* The product's model: every pair is a pick the executor's IK accepts at that stop, with
 * its time; every candidate stop without a pair is one the IK refuses; the stops reach
 * beyond the row's ends, so the fruit at the ends are planned. */
static void test_ik_model_is_the_executors(void **state)
{
    (void)state;
    hv_config_t cfg;
    assert_int_equal(tt_load_config(&cfg), 0);
    cfg.stops_beyond_ends = 1;
    hv_ik_model_t arms;
    hv_pick_model_t m;
    assert_int_equal(hv_pick_model_ik(&cfg, &arms, &m), HV_OK);
    hv_instance_params_t pr;
    hv_instance_params_from_config(&cfg, &m, &pr);
    assert_true(pr.stop_margin_m > 0.5 * cfg.base_spacing_m);
    assert_float_equal(pr.travel_time_s,
                       (cfg.row_length_m + 2 * pr.stop_margin_m) / cfg.vehicle_speed_mps, 1e-9);
    hv_fruit_t fr[6] = {
        fruit("first", HV_SIDE_LEFT, 0.0, 0.6), fruit("last", HV_SIDE_RIGHT, 2.0, 0.6),
        fruit("a", HV_SIDE_LEFT, 1.0, 0.45),    fruit("b", HV_SIDE_RIGHT, 0.7, 0.75),
        fruit("c", HV_SIDE_LEFT, 1.3, 0.6),     fruit("d", HV_SIDE_RIGHT, 1.6, 0.5)};
    fr[4].yaw_rad = 0.7;
    fr[5].yaw_rad = -0.7;
    fr[5].x_m = 0.49;
    hv_instance_t inst;
    hv_diag_t d;
    assert_int_equal(hv_instance_build(&pr, fr, 6, &m, &inst, &d), HV_OK);
    assert_true(inst.stop_y_m[0] < 0.0 && inst.stop_y_m[inst.n_stops - 1] > 2.0);
    assert_int_equal(hv_instance_unreachable_count(&inst), 0);
    size_t k = 0;
    for (size_t f = 0; f < 6; ++f) {
        const hv_arm_t *arm = &arms.arm[fr[f].side];
        for (size_t p = 0; p < inst.n_stops; ++p) {
            double t = 0.0;
            hv_status_t st = hv_pick_solve(arm, fr[f].x_m, fr[f].y_m - inst.stop_y_m[p], fr[f].z_m,
                                           fr[f].yaw_rad, NULL, &t, NULL);
            int pair = k < inst.fruit_begin[f + 1] && inst.pairs[k].stop == p;
            assert_int_equal(pair, st == HV_OK);
            if (pair) {
                /* the executor's time, in the whole ms the solver works in */
                assert_float_equal(inst.pairs[k].cost_s, round(t * 1000.0) / 1000.0, 0.0);
                assert_true(fabs(inst.pairs[k].cost_s - t) <= 0.0005 + 1e-12);
                ++k;
            }
        }
    }
    assert_int_equal(k, inst.n_pairs);
    hv_instance_free(&inst);

    /* the paper's stops over the row only: the end fruit are "row_end" */
    cfg.stops_beyond_ends = 0;
    hv_instance_params_from_config(&cfg, &m, &pr);
    assert_float_equal(pr.stop_margin_m, 0.0, 0.0);
    assert_int_equal(hv_instance_build(&pr, fr, 6, &m, &inst, &d), HV_OK);
    assert_int_equal(inst.n_stops, 201);
    assert_int_equal(hv_instance_unreachable_count(&inst), 2);
    assert_string_equal(hv_instance_why_name(inst.why[0]), "row_end");
    assert_string_equal(hv_instance_why_name(inst.why[1]), "row_end");
    assert_int_equal(inst.why[2], 0);
    hv_instance_free(&inst);
}

/* plan.pick_cost_flat: the same pairs as the IK's, each fruit's cost the same from every
 * stop that reaches it, and that cost its least IK cost over those stops */
static void test_flat_costs_are_each_fruits_best(void **state)
{
    (void)state;
    hv_config_t cfg;
    assert_int_equal(tt_load_config(&cfg), 0);
    hv_fruit_t fr[3] = {fruit("a", HV_SIDE_LEFT, 1.0, 0.45), fruit("b", HV_SIDE_RIGHT, 0.7, 0.75),
                        fruit("end", HV_SIDE_LEFT, 0.0, 0.6)};
    hv_instance_t by_ik, flat;
    hv_ik_model_t ik_arms, flat_arms;
    hv_pick_model_t ik, fl;
    hv_instance_params_t pr;
    hv_diag_t d;
    cfg.stops_beyond_ends = 1; /* "end" is reached from stops before the row only */
    cfg.pick_cost_flat = 0;
    assert_int_equal(hv_pick_model_ik(&cfg, &ik_arms, &ik), HV_OK);
    assert_string_equal(hv_pick_model_name(&cfg), cfg.pick_cycle ? "cycle" : "one_way");
    hv_instance_params_from_config(&cfg, &ik, &pr);
    assert_int_equal(hv_instance_build(&pr, fr, 3, &ik, &by_ik, &d), HV_OK);
    cfg.pick_cost_flat = 1;
    assert_int_equal(hv_pick_model_ik(&cfg, &flat_arms, &fl), HV_OK);
    assert_string_equal(hv_pick_model_name(&cfg), cfg.pick_cycle ? "cycle_flat" : "one_way_flat");
    assert_int_equal(hv_instance_build(&pr, fr, 3, &fl, &flat, &d), HV_OK);
    assert_int_equal(flat.n_pairs, by_ik.n_pairs);
    for (size_t f = 0; f < 3; ++f) {
        uint32_t b = by_ik.fruit_begin[f], e = by_ik.fruit_begin[f + 1];
        assert_true(e - b > 1); /* more than one stop reaches it: the costs could differ */
        double best = INFINITY, worst = 0.0;
        for (uint32_t k = b; k < e; ++k) {
            best = fmin(best, by_ik.pairs[k].cost_s);
            worst = fmax(worst, by_ik.pairs[k].cost_s);
        }
        assert_true(worst > best); /* by the IK, the cost depends on the stop */
        for (uint32_t k = b; k < e; ++k) {
            assert_int_equal(flat.pairs[k].stop, by_ik.pairs[k].stop);
            assert_float_equal(flat.pairs[k].cost_s, best, 0.0);
        }
    }
    hv_instance_free(&flat);
    hv_instance_free(&by_ik);
}

static void test_bad_params(void **state)
{
    fx_t *fx = *state;
    hv_fruit_t fr[1] = {fruit("A", HV_SIDE_LEFT, 0.20, 0.60)};
    hv_instance_params_t pr = params_1m();
    hv_instance_t inst;
    hv_diag_t d;
    pr.stop_step_m = 0.0;
    assert_int_equal(hv_instance_build(&pr, fr, 1, &fx->model, &inst, &d), HV_ERR_PLAN_PARAMS);
    pr = params_1m();
    pr.stop_penalty_s = NAN;
    assert_int_equal(hv_instance_build(&pr, fr, 1, &fx->model, &inst, &d), HV_ERR_PLAN_PARAMS);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pairs),
        cmocka_unit_test(test_eval),
        cmocka_unit_test(test_subset),
        cmocka_unit_test(test_ik_model_is_the_executors),
        cmocka_unit_test(test_flat_costs_are_each_fruits_best),
        cmocka_unit_test(test_bad_params),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
