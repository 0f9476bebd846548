/* Fuzz target: the executor's plan reader (hv_exec_plan_parse_json) and the preparation
 * of an accepted plan (hv_exec_plan_prepare: IK of every pick, expected times).
 * Properties: no crash or undefined behaviour; a refusal names the file; an accepted plan
 * fits the fixed tables (every pick's stop exists, the stops' pick ranges tile the picks)
 * and prepares with finite expected times. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_plan.h"
#include "fuzz_support.h"
#include "hv/exec_plan_json.h"

static void check_tables(const hv_exec_plan_t *p)
{
    if (p->n_stops > HV_EXEC_MAX_STOPS || p->n_picks > HV_EXEC_MAX_PICKS)
        hv_fuzz_fail("plan beyond the fixed tables");
    unsigned next = 0;
    for (unsigned s = 0; s < p->n_stops; s++)
        for (int side = 0; side < 2; side++) {
            if (p->stops[s].first[side] != next)
                hv_fuzz_fail("stop %u side %d: picks not contiguous", s, side);
            next += p->stops[s].count[side];
            for (unsigned k = p->stops[s].first[side]; k < next; k++)
                if (p->picks[k].stop != s || (int)p->picks[k].side != side)
                    hv_fuzz_fail("pick %u: wrong stop or side", k);
        }
    if (next != p->n_picks)
        hv_fuzz_fail("the stops list %u picks, the plan %u", next, (unsigned)p->n_picks);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* ~200 KB: on the heap, not the fuzzer's stack */
    hv_exec_plan_t *plan = malloc(sizeof *plan);
    if (!plan)
        abort();
    char err[512] = "";
    hv_status_t st =
        hv_exec_plan_parse_json("in.json", (const char *)data, size, plan, err, sizeof err);
    if (st != HV_OK) {
        if (strncmp(err, "in.json", 7) != 0)
            hv_fuzz_fail("refused (%s) without naming the file: '%s'", hv_status_name(st), err);
        free(plan);
        return 0;
    }
    check_tables(plan);
    if (hv_fuzz_prepare(plan) == HV_OK && !isfinite(plan->expected_makespan_s))
        hv_fuzz_fail("expected makespan not finite: %g", plan->expected_makespan_s);
    free(plan);
    return 0;
}
