/* Fuzz target: the executor's online run (params.online), the plan growing while the row
 * runs: committed stops arrive in pieces, repeated, contradicting the plan or each other,
 * interleaved with the nodes' frames, as the program takes them (exec_feed_lcm.c: a stop the
 * plan holds must be the very same, a new one is appended, then the plan is prepared and
 * HV_EV_PLAN_GROWN stepped).
 *
 * Input: one flag byte (bit 0: the operator cleared the e-stop), then operations, each an
 * opcode byte and its arguments; opcode & 15:
 *   0-7   the nodes' operations of fuzz_exec_step.c (opcode & 7; bits 4-5: from_bus of a
 *         stop request)
 *   8     the planner's message: the first n stops of fuzz/data/plan.json (n: 1 byte), then
 *         HV_EV_PLAN_GROWN (1 byte: bit 0 final, bits 1-7 the commit line, x 2 cm past the
 *         course start)
 *   9     one stop of the input's making (stop index, y x 1 cm, then per arm a count (mod 3)
 *         and per pick a byte: < 128 a fruit of the source plan, else a new id), then
 *         HV_EV_PLAN_GROWN as in 8
 *   10    HV_EV_PLAN_GROWN of any final (1 byte) and commit line (1 byte: 253 NaN, 254
 *         infinity, 255 minus infinity, else x 2 cm less 1 m)
 *   11-15 a tick of 50 ms
 *
 * Properties: hv_fuzz_step's (fuzz_nodes.h) after every step, and of the plan: a stop the
 * plan holds is the one the planner commits again (the same message matches); a refused
 * append leaves the plan as it was, an accepted one and the preparation after it change no
 * stop or pick already there. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_nodes.h"
#include "fuzz_plan.h"
#include "fuzz_support.h"
#include "hv/exec_status.h"

typedef struct online {
    hv_fuzz_run_t R;
    hv_exec_plan_t plan; /* grows; the state machine reads it */
    hv_exec_stop_t stops_before[HV_EXEC_MAX_STOPS];
    hv_exec_pick_t picks_before[HV_EXEC_MAX_PICKS];
    uint16_t n_stops_before, n_picks_before;
    uint8_t from_source[HV_EXEC_MAX_STOPS]; /* stop s was appended by op 8 */
} online_t;

static void snapshot(online_t *O)
{
    O->n_stops_before = O->plan.n_stops;
    O->n_picks_before = O->plan.n_picks;
    memcpy(O->stops_before, O->plan.stops, O->plan.n_stops * sizeof O->plan.stops[0]);
    memcpy(O->picks_before, O->plan.picks, O->plan.n_picks * sizeof O->plan.picks[0]);
}

/* the stops and picks of the snapshot are still there, unchanged (and nothing else when
 * `same`) */
static void check_kept(const online_t *O, int same, const char *what)
{
    const hv_exec_plan_t *p = &O->plan;
    if (p->n_stops < O->n_stops_before || p->n_picks < O->n_picks_before ||
        (same && (p->n_stops != O->n_stops_before || p->n_picks != O->n_picks_before)))
        hv_fuzz_fail("%s: the plan went from %u/%u to %u/%u stops/picks", what,
                     (unsigned)O->n_stops_before, (unsigned)O->n_picks_before, (unsigned)p->n_stops,
                     (unsigned)p->n_picks);
    if (memcmp(O->stops_before, p->stops, O->n_stops_before * sizeof p->stops[0]) ||
        memcmp(O->picks_before, p->picks, O->n_picks_before * sizeof p->picks[0]))
        hv_fuzz_fail("%s: a stop or pick already in the plan changed", what);
}

static void grown(online_t *O, int final, double advance_m)
{
    hv_exec_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = HV_EV_PLAN_GROWN;
    ev.u.plan.final = final;
    ev.u.plan.advance_m = advance_m;
    hv_fuzz_step(&O->R, &ev);
}

static void grown_byte(online_t *O, uint8_t b)
{
    grown(O, b & 1, hv_exec_course_start(&O->plan) + 0.02 * (b >> 1));
}

/* Stop s of a message: checked against the plan when it holds it (1: the same), else
 * appended; the plan's promises checked either way. Returns the append's status, HV_OK
 * for a stop that matched, HV_ERR_EXEC_PLAN_CONFLICT for one that did not. */
static hv_status_t take_stop(online_t *O, uint16_t s, uint32_t index, double y_m,
                             const hv_exec_pick_t *picks, uint16_t n_left, uint16_t n_right)
{
    if (s < O->plan.n_stops)
        return hv_exec_plan_stop_matches(&O->plan, s, index, y_m, picks, n_left, n_right)
                   ? HV_OK
                   : HV_ERR_EXEC_PLAN_CONFLICT;
    snapshot(O);
    hv_status_t st = hv_exec_plan_append(&O->plan, index, y_m, picks, n_left, n_right);
    if (st != HV_OK && st != HV_ERR_EXEC_PLAN_RANGE && st != HV_ERR_EXEC_PLAN_CAPACITY)
        hv_fuzz_fail("append returned %s", hv_exec_status_name(st));
    check_kept(O, st != HV_OK, st != HV_OK ? "a refused append" : "an append");
    if (st == HV_OK && !hv_exec_plan_stop_matches(&O->plan, s, index, y_m, picks, n_left, n_right))
        hv_fuzz_fail("stop %u appended is not the stop committed", (unsigned)s);
    return st;
}

static void prepare(online_t *O)
{
    if (hv_fuzz_prepare(&O->plan) != HV_OK)
        hv_fuzz_fail("a grown plan of %u stops was not prepared", (unsigned)O->plan.n_stops);
}

/* op 8: the source plan's first n stops, as the planner sends its committed part */
static void commit_source(online_t *O, unsigned n, uint8_t ev_byte)
{
    const hv_exec_plan_t *src = hv_fuzz_plan(0);
    uint16_t before = O->plan.n_stops;
    int consistent = 1; /* every stop the plan holds came from the source */
    for (uint16_t s = 0; s < O->plan.n_stops; s++)
        consistent &= O->from_source[s];
    for (uint16_t s = 0; s < n && s < src->n_stops; s++) {
        const hv_exec_stop_t *st = &src->stops[s];
        hv_status_t r =
            take_stop(O, s, st->plan_index, st->y_m, &src->picks[st->first[HV_SIDE_LEFT]],
                      st->count[HV_SIDE_LEFT], st->count[HV_SIDE_RIGHT]);
        if (r == HV_ERR_EXEC_PLAN_CONFLICT && consistent)
            hv_fuzz_fail("stop %u committed again does not match the plan's", (unsigned)s);
        if (r != HV_OK)
            break; /* the program refuses the rest of the message */
        O->from_source[s] = 1;
    }
    if (O->plan.n_stops != before)
        prepare(O);
    grown_byte(O, ev_byte);
}

/* op 9: a stop of the input's making */
static void commit_made(online_t *O, hv_fuzz_reader_t *r)
{
    const hv_exec_plan_t *src = hv_fuzz_plan(0);
    hv_exec_pick_t picks[4];
    uint16_t n[2];
    uint32_t index = hv_fuzz_byte(r);
    double y_m = 0.01 * hv_fuzz_byte(r);
    unsigned k = 0;
    memset(picks, 0, sizeof picks);
    for (int side = 0; side < 2; side++) {
        n[side] = hv_fuzz_byte(r) % 3;
        for (unsigned j = 0; j < n[side]; j++, k++) {
            uint8_t b = hv_fuzz_byte(r);
            picks[k] = src->picks[b % src->n_picks];
            if (b >= 128)
                snprintf(picks[k].id, sizeof picks[k].id, "new-%u", (unsigned)b);
            picks[k].side = (hv_side_t)side;
        }
    }
    uint16_t before = O->plan.n_stops;
    take_stop(O, O->plan.n_stops, index, y_m, picks, n[0], n[1]);
    if (O->plan.n_stops != before)
        O->from_source[before] = 0;
    if (O->plan.n_stops != before)
        prepare(O);
    grown_byte(O, hv_fuzz_byte(r));
}

static double advance_of(uint8_t b)
{
    if (b == 253)
        return NAN;
    if (b >= 254)
        return b == 254 ? INFINITY : -INFINITY;
    return 0.02 * b - 1.0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static online_t O; /* large: off the fuzzer's stack */
    hv_fuzz_reader_t r = {data, size};
    uint8_t flags = hv_fuzz_byte(&r);
    hv_fuzz_plan_empty(&O.plan);
    memset(O.from_source, 0, sizeof O.from_source);
    prepare(&O);
    hv_exec_params_t prm;
    hv_exec_params_default(&prm);
    prm.home_max_s = 20.0;
    prm.clear_estop = flags & 1;
    prm.online = 1;
    hv_fuzz_run_init(&O.R, &O.plan, &prm, NULL);
    int op;
    unsigned ops = 0;
    while ((op = hv_fuzz_next(&r)) >= 0 && ops++ < 4096) {
        static const uint8_t ten = 10; /* op 0's argument: 10 x 5 ms */
        hv_fuzz_reader_t tick_50ms = {&ten, 1};
        switch (op & 15) {
        case 8: {
            uint8_t n = hv_fuzz_byte(&r);
            commit_source(&O, n, hv_fuzz_byte(&r));
            break;
        }
        case 9: commit_made(&O, &r); break;
        case 10: {
            uint8_t final = hv_fuzz_byte(&r);
            grown(&O, final, advance_of(hv_fuzz_byte(&r)));
            break;
        }
        default:
            if ((op & 15) < 8)
                hv_fuzz_node_op(&O.R, (op & 7) | (((op >> 4) & 3) << 3), &r);
            else
                hv_fuzz_node_op(&O.R, 0, &tick_50ms);
            break;
        }
    }
    if (getenv("HV_FUZZ_TRACE"))
        fprintf(stderr, "fuzz_exec_online: %u ops, %u stops, phase %s, stop %d, picked %u\n", ops,
                (unsigned)O.plan.n_stops, hv_exec_phase_name(O.R.sm.phase), O.R.sm.stop,
                O.R.sm.picked);
    return 0;
}
