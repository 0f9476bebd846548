/* LCM telemetry of the executor over memq:// (in-process LCM): what the executor publishes
 * decodes with the generated C types and carries the state machine's values. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <lcm/lcm.h>

#include "exec_fixture.h"
#include "harvest_lcm_exec_state_t.h"
#include "harvest_lcm_fruit_event_t.h"
#include "harvest_lcm_plan_t.h"
#include "hv/exec_status.h"
#include "hv/exec_telemetry.h"

typedef struct got {
    int plans, states, fruits;
    int n_picks, n_stops;
    double expected;
    char phase[32], fruit_id[32], event[16], outcome[16], planner[32];
    int picked;
} got_t;

static void on_plan(const lcm_recv_buf_t *rb, const char *ch, const harvest_lcm_plan_t *m, void *u)
{
    (void)rb;
    (void)ch;
    got_t *g = u;
    g->plans++;
    g->n_picks = m->n_picks;
    g->n_stops = m->n_stops;
    g->expected = m->expected_makespan_s;
}

static void on_state(const lcm_recv_buf_t *rb, const char *ch, const harvest_lcm_exec_state_t *m,
                     void *u)
{
    (void)rb;
    (void)ch;
    got_t *g = u;
    g->states++;
    strncpy(g->phase, m->phase, sizeof g->phase - 1);
    strncpy(g->planner, m->planner, sizeof g->planner - 1);
    g->picked = m->picked;
}

static void on_fruit(const lcm_recv_buf_t *rb, const char *ch, const harvest_lcm_fruit_event_t *m,
                     void *u)
{
    (void)rb;
    (void)ch;
    got_t *g = u;
    g->fruits++;
    strncpy(g->fruit_id, m->fruit_id, sizeof g->fruit_id - 1);
    strncpy(g->event, m->event, sizeof g->event - 1);
    strncpy(g->outcome, m->outcome, sizeof g->outcome - 1);
}

static void test_memq_round_trip(void **state)
{
    (void)state;
    fx_t *fx = malloc(sizeof *fx);
    fx_plan(fx, 2, 2);
    fx_start(fx, NULL);
    fx_run(fx, 30.0); /* a finished row: picked = all */
    assert_int_equal(fx->sm.phase, HV_PH_ROW_DONE);

    hv_exec_telemetry_t tm;
    char err[256];
    assert_int_equal(hv_exec_telemetry_lcm_open(&tm, "memq://", err, sizeof err), HV_OK);
    lcm_t *lcm = (lcm_t *)tm.impl; /* memq is per lcm_t: subscribe on the same instance */
    got_t g;
    memset(&g, 0, sizeof g);
    harvest_lcm_plan_t_subscription_t *s1 =
        harvest_lcm_plan_t_subscribe(lcm, "HARVEST_PLAN", on_plan, &g);
    harvest_lcm_exec_state_t_subscription_t *s2 =
        harvest_lcm_exec_state_t_subscribe(lcm, "HARVEST_EXEC_STATE", on_state, &g);
    harvest_lcm_fruit_event_t_subscription_t *s3 =
        harvest_lcm_fruit_event_t_subscribe(lcm, "HARVEST_FRUIT", on_fruit, &g);

    hv_exec_tm_plan(&tm, &fx->plan, "plan.json", &fx->prm, 10.0, 1);
    hv_exec_tm_state(&tm, &fx->sm, "the planner plans", fx->now_ns, 2);
    hv_exec_action_t fe;
    memset(&fe, 0, sizeof fe);
    fe.kind = HV_ACT_FRUIT_EVENT;
    fe.u.fe.kind = HV_FE_OUTCOME;
    fe.u.fe.pick = 3;
    fe.u.fe.outcome = HV_OUT_FAILED;
    fe.u.fe.reason = HV_RSN_TIMEOUT;
    hv_exec_tm_fruit(&tm, &fx->sm, &fe, fx->now_ns, 3);
    for (int i = 0; i < 3; i++)
        assert_true(lcm_handle_timeout(lcm, 100) > 0);
    assert_int_equal(tm.published, 3);
    assert_int_equal(tm.failed, 0);
    assert_int_equal(g.plans, 1);
    assert_int_equal(g.n_picks, fx->plan.n_picks);
    assert_int_equal(g.n_stops, 2);
    assert_float_equal(g.expected, fx->plan.expected_makespan_s, 1e-9);
    assert_string_equal(g.phase, "row_done");
    assert_string_equal(g.planner, "the planner plans"); /* online: the feed's line */
    assert_int_equal(g.picked, (int)fx->plan.n_picks);
    assert_string_equal(g.fruit_id, fx->plan.picks[3].id);
    assert_string_equal(g.event, "outcome");
    assert_string_equal(g.outcome, "failed");
    harvest_lcm_plan_t_unsubscribe(lcm, s1);
    harvest_lcm_exec_state_t_unsubscribe(lcm, s2);
    harvest_lcm_fruit_event_t_unsubscribe(lcm, s3);
    hv_exec_telemetry_close(&tm);
    free(fx);
}

static void test_bad_url(void **state)
{
    (void)state;
    hv_exec_telemetry_t tm;
    char err[256];
    assert_int_equal(hv_exec_telemetry_lcm_open(&tm, "nosuchprovider://x", err, sizeof err),
                     HV_ERR_EXEC_TELEMETRY);
    assert_non_null(strstr(err, "nosuchprovider"));
    /* the null sink takes everything and publishes nothing */
    hv_exec_tm_state(&tm, NULL, NULL, 0, 0);
    assert_int_equal(tm.published, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_memq_round_trip),
        cmocka_unit_test(test_bad_url),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
