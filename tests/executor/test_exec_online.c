/* The executor's online mode: the plan grows while the row runs. Stops already there never
 * change, the vehicle waits where it is (or drives on to the commit line) while no stop is
 * committed ahead, and the row completes with every fruit cut once. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "exec_fixture.h"
#include "hv/exec_status.h"

/* A planner that never commits (refused, dead without its journal): WAIT_PLAN ends after
 * wait_plan_timeout_s in a controlled stop journalled as plan_timeout, no e-stop. */
static void test_a_silent_planner_ends_in_a_controlled_stop(void **state)
{
    (void)state;
    fx_t *fx = malloc(sizeof *fx);
    assert_non_null(fx);
    fx_plan(fx, 1, 1);
    fx_online(fx);
    fx->prm.wait_plan_timeout_s = 3.0;
    fx_start(fx, NULL);
    fx_run(fx, 2.0);
    assert_int_equal(fx->sm.phase, HV_PH_WAIT_PLAN);
    fx_run(fx, 10.0);
    assert_int_equal(fx->sm.phase, HV_PH_STOPPED);
    assert_int_equal(fx->sm.stop_reason, HV_STOP_PLAN_TIMEOUT);
    int h = fx_find(fx, 0, HV_ACT_JOURNAL, HV_JR_HALT);
    assert_true(h >= 0);
    assert_int_equal(fx->log[h].a.u.jr.reason, HV_STOP_PLAN_TIMEOUT);
    assert_int_equal(fx_count(fx, HV_ACT_ESTOP, -1), 0);
    assert_true(fx_find(fx, h, HV_ACT_COMMAND, HV_CAN_CMD_DISABLE) > h);
    /* a timeout of 0 is no timeout at all: refused */
    fx->prm.wait_plan_timeout_s = 0.0;
    assert_int_equal(hv_exec_init(&fx->sm, &fx->plan, &fx->prm, NULL), HV_ERR_EXEC_PARAMS);
    free(fx);
}

static void test_plan_grows_while_running(void **state)
{
    (void)state;
    fx_t *src = malloc(sizeof *src), *fx = malloc(sizeof *fx); /* large: off the stack */
    assert_non_null(src);
    assert_non_null(fx);
    fx_plan(src, 3, 2); /* what the planner will commit, stop by stop */
    fx_plan(fx, 3, 2);
    fx_online(fx);
    fx_start(fx, NULL);
    fx_run(fx, 5.0);
    /* homed, nothing committed: waiting where it stands, no move */
    assert_int_equal(fx->sm.phase, HV_PH_WAIT_PLAN);
    assert_int_equal(fx->moves_sent, 0);
    assert_int_equal(fx_append_stop(fx, &src->plan, 0), HV_OK);
    fx_grown(fx, 0, 0.7);
    fx_run(fx, 30.0);
    assert_int_equal(fx->sm.phase, HV_PH_WAIT_PLAN);
    assert_int_equal(fx->sm.picked, 4);
    /* the commit line lies beyond the last stop: the vehicle drives on to it and waits */
    assert_int_equal(fx->moves_sent, 2);
    assert_float_equal(fx->node[HV_EXEC_VEHICLE].pos_m, 0.7, 1e-9);
    double first, row;
    hv_exec_plan_wait_s(&fx->sm, fx->now_ns, &first, &row);
    assert_true(first > 0.0 && row > 0.0);
    assert_int_equal(fx->sm.waits, 1);
    /* a stop behind the last, or a fruit already planned, is refused; the plan unchanged */
    assert_int_equal(fx_append_stop(fx, &src->plan, 0), HV_ERR_EXEC_PLAN_RANGE);
    assert_int_equal(fx->plan.n_stops, 1);
    /* the rest, then the planner says the plan is final */
    assert_int_equal(fx_append_stop(fx, &src->plan, 1), HV_OK);
    assert_int_equal(fx_append_stop(fx, &src->plan, 2), HV_OK);
    fx_grown(fx, 1, 1.9);
    fx_run(fx, 60.0);
    assert_int_equal(fx->sm.phase, HV_PH_ROW_DONE);
    assert_int_equal(fx->sm.picked, 12);
    assert_int_equal(fx_count(fx, HV_ACT_JOURNAL, HV_JR_STOP), 3);
    for (int p = 0; p < fx->plan.n_picks; p++)
        assert_int_equal(fx->cuts_done[fx->plan.picks[p].side][p], 1);
    free(src);
    free(fx);
}

static void test_offline_never_waits(void **state)
{
    (void)state;
    fx_t *fx = malloc(sizeof *fx);
    assert_non_null(fx);
    fx_plan(fx, 2, 1);
    fx_start(fx, NULL);
    fx_grown(fx, 0, 5.0); /* ignored without params.online */
    fx_run(fx, 30.0);
    assert_int_equal(fx->sm.phase, HV_PH_ROW_DONE);
    assert_int_equal(fx->sm.waits, 0);
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = HV_EV_PLAN_GROWN;
    ev.u.plan.final = 2;
    fx_event(fx, &ev);
    assert_int_equal(fx->last_status, HV_ERR_EXEC_EVENT);
    free(fx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_plan_grows_while_running),
        cmocka_unit_test(test_a_silent_planner_ends_in_a_controlled_stop),
        cmocka_unit_test(test_offline_never_waits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
