/* The scenarios of the recorded-run replay (test_exec_replay.c): runs of the state machine on
 * the fake nodes of exec_fixture.c, each traced (exec_trace.h) from its first step. */
#ifndef HV_EXEC_SCENARIOS_H
#define HV_EXEC_SCENARIOS_H

#include <stddef.h>
#include <stdint.h>

#include "exec_fixture.h"
#include "exec_trace.h"

/* A run on the fake nodes: `run`, which sets up its own; without it, a plan of `stops` x
 * `per_arm` and the faults `f` from the start for at most `max_s`, or with `seed` a seeded
 * run (seeded()). */
typedef struct exec_scenario {
    const char *name, *what;
    void (*run)(fx_t *fx, exec_trace_t *t);
    int stops, per_arm;
    double max_s;
    fx_faults_t f;
    uint32_t seed;
} exec_scenario_t;

extern const exec_scenario_t exec_scenarios[];
extern const size_t exec_n_scenarios;

/* Run scenario sc on fx, every step traced into t. */
void exec_scenario_run(fx_t *fx, exec_trace_t *t, const exec_scenario_t *sc);

#endif /* HV_EXEC_SCENARIOS_H */
