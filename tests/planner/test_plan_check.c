/* The independent checker accepts a valid plan and rejects hand-broken ones, each with
 * the code of what was broken. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/baselines.h"
#include "hv/plan_build.h"
#include "hv/plan_check.h"
#include "tiny_tables.h"

/* band model, nothing above z = 0.70 m */
static uint16_t low_band(hv_side_t side, double y_rel, uint32_t ix, uint32_t iz, uint32_t iw,
                         void *ctx)
{
    return iz > 30 ? HV_COST_UNREACHABLE : tt_band_cost(side, y_rel, ix, iz, iw, ctx);
}

typedef struct ctx {
    tt_fixture_t fx;
    hv_fruit_t fruits[8];
    size_t n;
} ctx_t;

static int setup(void **state)
{
    static ctx_t c;
    static tt_band_t band = {0.15, 2000, 15, 10};
    if (tt_fixture_init(&c.fx, low_band, &band) != 0) {
        return -1;
    }
    /* stops with FOV 0.2 from 0.12: 0.22 {r1, r2, l1}, 0.42 {r3, l2}, 0.62 {r4}; u1 is too
     * high to reach */
    c.fruits[0] = tt_fruit("r1", HV_SIDE_RIGHT, 0.12, 0.5);
    c.fruits[1] = tt_fruit("r2", HV_SIDE_RIGHT, 0.25, 0.45);
    c.fruits[2] = tt_fruit("r3", HV_SIDE_RIGHT, 0.33, 0.5);
    c.fruits[3] = tt_fruit("r4", HV_SIDE_RIGHT, 0.62, 0.5);
    c.fruits[4] = tt_fruit("l1", HV_SIDE_LEFT, 0.18, 0.6);
    c.fruits[5] = tt_fruit("l2", HV_SIDE_LEFT, 0.45, 0.5);
    c.fruits[6] = tt_fruit("u1", HV_SIDE_LEFT, 0.45, 0.78);
    c.n = 7;
    *state = &c;
    return 0;
}

static int teardown(void **state)
{
    ctx_t *c = *state;
    tt_fixture_free(&c->fx);
    return 0;
}

/* A valid FOV plan over a 1 m row. */
static void make_plan(ctx_t *c, hv_plan_t *plan, const char *method)
{
    hv_instance_params_t pr = {0.0,
                               1.0,
                               c->fx.cfg.grid_step_m,
                               c->fx.cfg.stop_penalty_s,
                               1.0 / c->fx.cfg.vehicle_speed_mps,
                               0.0};
    hv_instance_t inst;
    hv_diag_t d;
    assert_int_equal(hv_instance_build(&pr, c->fruits, c->n, &c->fx.model, &inst, &d), HV_OK);
    hv_assignment_t a;
    assert_int_equal(hv_assignment_alloc(&a, c->n), HV_OK);
    assert_int_equal(hv_fov_solve(&inst, 0.2, &a, NULL), HV_OK);
    hv_plan_meta_t m;
    memset(&m, 0, sizeof m);
    m.method = method;
    m.fruit_map = "map.csv";
    m.params = pr;
    m.vehicle_speed_mps = c->fx.cfg.vehicle_speed_mps;
    m.solver_status = "heuristic";
    m.gap = -1;
    unsigned char passes[8];
    int serial = strcmp(method, "serial") == 0;
    for (size_t f = 0; f < c->n; ++f) {
        passes[f] = c->fruits[f].side == HV_SIDE_LEFT ? 0 : 1;
    }
    assert_int_equal(hv_plan_build(&inst, &a, serial ? passes : NULL, &m, plan), HV_OK);
    hv_assignment_free(&a);
    hv_instance_free(&inst);
}

static hv_status_t check(ctx_t *c, const hv_plan_t *plan, char *err, size_t errlen)
{
    return hv_plan_check(plan, &c->fx.cfg, c->fruits, c->n, &c->fx.model, err, errlen);
}

static void test_valid_plan_passes(void **state)
{
    ctx_t *c = *state;
    hv_plan_t plan;
    make_plan(c, &plan, "fov");
    char err[512] = "";
    assert_int_equal(check(c, &plan, err, sizeof err), HV_OK);
    assert_int_equal(plan.n_stops, 3);
    assert_int_equal(plan.stops[0].index, 22);
    assert_int_equal(plan.stops[0].n_left, 1);
    assert_int_equal(plan.stops[0].n_right, 2);
    assert_string_equal(plan.stops[0].right[0].id, "r1"); /* by y */
    assert_true(fabs(plan.stops[0].right[1].start_s - plan.stops[0].right[0].cost_s) < 1e-12);
    assert_int_equal(plan.n_unreachable, 1);
    assert_string_equal(plan.unreachable[0].id, "u1");
    assert_true(fabs(plan.makespan_s - (plan.pick_time_s + 3 * 5.0 + 10.0)) < 1e-9);
    hv_plan_free(&plan);

    make_plan(c, &plan, "serial");
    assert_int_equal(check(c, &plan, err, sizeof err), HV_OK);
    assert_int_equal(plan.stops[0].pass, 0);
    assert_int_equal(plan.stops[plan.n_stops - 1].pass, 1);
    assert_true(fabs(plan.total_travel_time_s - 20.0) < 1e-9);
    hv_plan_free(&plan);
}

static void expect_reject(ctx_t *c, hv_plan_t *plan, hv_status_t code, const char *in_msg)
{
    char err[512] = "";
    hv_status_t st = check(c, plan, err, sizeof err);
    if (st != code || strstr(err, in_msg) == NULL) {
        print_error("got %s \"%s\", want %s containing \"%s\"\n", hv_plan_status_name(st), err,
                    hv_plan_status_name(code), in_msg);
        fail();
    }
    hv_plan_free(plan);
}

/* Append a copy of `pk` to a stop's right list. */
static void push_right(hv_plan_stop_t *s, const hv_plan_pick_t *pk)
{
    s->right = realloc(s->right, (s->n_right + 1) * sizeof *s->right);
    assert_non_null(s->right);
    s->right[s->n_right++] = *pk;
}

static void test_fruit_twice(void **state)
{
    ctx_t *c = *state;
    hv_plan_t plan;
    make_plan(c, &plan, "fov");
    hv_plan_pick_t pk = plan.stops[0].right[1]; /* r2 also at stop 0.42 (reachable there) */
    push_right(&plan.stops[1], &pk);
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_DUPLICATE, "stops[1].right[1] (id r2): picked twice");
}

static void test_unreachable_pair(void **state)
{
    ctx_t *c = *state;
    hv_plan_t plan;
    make_plan(c, &plan, "fov");
    /* move r4 (0.62) from the stop at 0.62 to the stop at 0.22: 0.40 m away */
    hv_plan_pick_t pk = plan.stops[2].right[0];
    pk.start_s = plan.stops[0].c_right_s;
    push_right(&plan.stops[0], &pk);
    plan.stops[2].n_right = 0;
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_PAIR, "stops[0].right[2] (id r4): stop 22");
}

static void test_fruit_at_unused_stop(void **state)
{
    ctx_t *c = *state;
    hv_plan_t plan;
    make_plan(c, &plan, "fov");
    /* the last stop moved to a candidate stop that is not in the plan and cannot reach r4 */
    plan.stops[2].index = 90;
    plan.stops[2].y_m = 0.90;
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_PAIR, "cannot reach");

    make_plan(c, &plan, "fov");
    plan.stops[2].n_right = 0; /* a stop listed with nothing to pick */
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_STOP, "stops[2]: a stop with no pick");

    make_plan(c, &plan, "fov");
    plan.stops[1].y_m += 0.004; /* off the candidate grid */
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_STOP, "is not candidate stop 42");

    make_plan(c, &plan, "fov");
    hv_plan_stop_t tmp = plan.stops[0]; /* driving order */
    plan.stops[0] = plan.stops[1];
    plan.stops[1] = tmp;
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_STOP, "driving order");
}

static void test_wrong_numbers(void **state)
{
    ctx_t *c = *state;
    hv_plan_t plan;
    make_plan(c, &plan, "fov");
    plan.makespan_s += 0.01;
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_TOTAL, "totals.makespan_s");

    make_plan(c, &plan, "fov");
    plan.stops[1].left[0].cost_s -= 0.001;
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_COST, "stops[1].left[0] (id l2): cost_s");

    make_plan(c, &plan, "fov");
    plan.stops[0].right[1].start_s = 0.0;
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_COST, "start_s");

    make_plan(c, &plan, "fov");
    plan.stops[0].idle_left_s += 1e-3;
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_TOTAL, "stops[0]: idle_left_s");

    make_plan(c, &plan, "fov");
    plan.n_stops_total = 2;
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_TOTAL, "totals.stops");

    make_plan(c, &plan, "fov");
    plan.stop_penalty_s = 4.0;
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_PARAMS, "params.stop_penalty_s");

    make_plan(c, &plan, "fov");
    plan.travel_time_s = 20.0; /* 1 m at 0.1 m/s is 10 s */
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_PARAMS, "params.travel_time_s");

    /* within 1e-6 s is accepted (values read back from text) */
    make_plan(c, &plan, "fov");
    plan.makespan_s += 5e-7;
    char err[256];
    assert_int_equal(check(c, &plan, err, sizeof err), HV_OK);
    hv_plan_free(&plan);
}

static void test_missing_and_unknown(void **state)
{
    ctx_t *c = *state;
    hv_plan_t plan;
    make_plan(c, &plan, "fov");
    plan.n_unreachable = 0; /* u1 dropped silently */
    plan.fruits_unreachable = 0;
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_MISSING, "\"u1\" is neither picked");

    make_plan(c, &plan, "fov");
    strcpy(plan.stops[2].right[0].id, "zz");
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_UNKNOWN, "(id zz): not in the fruit map");

    make_plan(c, &plan, "fov");
    plan.stops[2].right[0].z_m += 0.01;
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_UNKNOWN, "pose differs");

    make_plan(c, &plan, "fov");
    strcpy(plan.unreachable[0].id, "r1"); /* r1 is also picked */
    plan.unreachable[0].side = HV_SIDE_RIGHT;
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_DUPLICATE, "unreachable[0] (id r1)");

    /* u1 lowered into reach in the map: the plan's "unreachable" is now false */
    make_plan(c, &plan, "fov");
    c->fruits[6].z_m = 0.5;
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_REACHABLE, "listed unreachable, but stop");
    c->fruits[6].z_m = 0.78;

    make_plan(c, &plan, "serial");
    plan.stops[0].pass = 1; /* left picks in the right pass */
    expect_reject(c, &plan, HV_ERR_PLAN_CHECK_STOP, "serial");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_valid_plan_passes), cmocka_unit_test(test_fruit_twice),
        cmocka_unit_test(test_unreachable_pair),  cmocka_unit_test(test_fruit_at_unused_stop),
        cmocka_unit_test(test_wrong_numbers),     cmocka_unit_test(test_missing_and_unknown),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
