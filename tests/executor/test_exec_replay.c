/* The executor's recorded-run replay: runs of the state machine on fixed inputs, each
 * written as a trace (exec_trace.h) and compared with the trace recorded from an earlier
 * build (tests/executor/replay/). A change of the executor's code that should not change
 * its behaviour must leave every trace the same, byte for byte.
 *
 * The runs: the scenarios of exec_scenarios.c on the fake nodes of exec_fixture.c and, in
 * the build with the fuzz targets (HV_REPLAY_FUZZ),
 * every input of the corpora of fuzz/exec_step and fuzz/exec_online run through those
 * targets. Each run is one test; `--write DIR` records the traces of this build instead
 * (for a change that is meant to change the behaviour, or a new run). */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "exec_fixture.h"
#include "exec_scenarios.h"
#include "exec_trace.h"
#include "hv/file_io.h"

#ifndef HV_REPLAY_SUFFIX
#define HV_REPLAY_SUFFIX ".trace"
#endif

/* ---- the runs, traced and compared ---------------------------------------------------- */

/* One run: a scenario, or an input of a fuzz corpus through its target. */
typedef struct replay_run {
    char name[256]; /* its trace is <dir>/<name>HV_REPLAY_SUFFIX */
    char title[1024];
    const exec_scenario_t *sc;
    char path[4096];
    int (*entry)(const uint8_t *data, size_t size);
} replay_run_t;

#define MAX_RUNS 256
static replay_run_t runs[MAX_RUNS];
static size_t n_runs;
static const char *trace_dir; /* the recorded traces */

#ifdef HV_REPLAY_FUZZ
#include "fuzz_nodes.h"

/* the targets' entry points, renamed in this build (tests/executor/CMakeLists.txt) */
int hv_replay_fuzz_exec_step(const uint8_t *data, size_t size);
int hv_replay_fuzz_exec_online(const uint8_t *data, size_t size);

static void run_input(const replay_run_t *r, exec_trace_t *t)
{
    void *data;
    size_t n;
    char err[512];
    if (hv_file_read_all(r->path, &data, &n, err, sizeof err) != HV_OK) {
        fprintf(t->f, "unreadable: %s\n", err);
        return;
    }
    hv_fuzz_on_step(exec_trace_hook, t);
    r->entry(data, n);
    hv_fuzz_on_step(NULL, NULL);
    free(data);
}
#endif

/* The trace of run r (malloc'd text, *len bytes); *steps: the steps it took. */
static char *trace_run(const replay_run_t *r, size_t *len, uint64_t *steps)
{
    static fx_t fx; /* large: off the stack */
    char *text = NULL;
    FILE *f = open_memstream(&text, len);
    if (!f) {
        perror("open_memstream");
        exit(2);
    }
    exec_trace_t t;
    exec_trace_begin(&t, f, r->title);
    if (r->sc) {
        exec_scenario_run(&fx, &t, r->sc);
    } else {
#ifdef HV_REPLAY_FUZZ
        run_input(r, &t);
#endif
    }
    exec_trace_end(&t);
    fclose(f);
    *steps = t.steps;
    return text;
}

static const char *golden_file(const replay_run_t *r, char *buf, size_t len)
{
    snprintf(buf, len, "%s%s", r->name, HV_REPLAY_SUFFIX);
    return buf;
}

static void test_replay(void **state)
{
    const replay_run_t *r = *state;
    char file[512];
    size_t len;
    uint64_t steps;
    char *text = trace_run(r, &len, &steps);
    int same = exec_trace_golden(trace_dir, golden_file(r, file, sizeof file), text, len, 0);
    free(text);
    assert_int_equal(same, 1);
}

static replay_run_t *add_run(const char *name)
{
    if (n_runs == MAX_RUNS) {
        fprintf(stderr, "exec-replay: more than %d runs: raise MAX_RUNS\n", MAX_RUNS);
        exit(2);
    }
    replay_run_t *r = &runs[n_runs++];
    memset(r, 0, sizeof *r);
    snprintf(r->name, sizeof r->name, "%s", name);
    return r;
}

#ifdef HV_REPLAY_FUZZ
static int visible(const struct dirent *d)
{
    return d->d_name[0] != '.';
}

/* Every input of fuzz/corpus/<target>, in name order; when comparing, those with a
 * recorded trace (an input added since is named, not compared). */
static void add_corpus(const char *target, int (*entry)(const uint8_t *, size_t), int write)
{
    char dir[2048], name[512], golden[8192];
    snprintf(dir, sizeof dir, "%s/fuzz/corpus/%s", HV_SOURCE_DIR, target);
    struct dirent **names;
    int n = scandir(dir, &names, visible, alphasort);
    if (n <= 0) {
        fprintf(stderr, "exec-replay: %s: no inputs\n", dir);
        exit(2);
    }
    for (int i = 0; i < n; i++) {
        snprintf(name, sizeof name, "fuzz-%s-%s", target, names[i]->d_name);
        snprintf(golden, sizeof golden, "%s/%s%s", trace_dir, name, HV_REPLAY_SUFFIX);
        if (!write && access(golden, F_OK) != 0) {
            printf("exec-replay: %s: no recorded trace, not compared (record with --write)\n",
                   name);
        } else {
            replay_run_t *r = add_run(name);
            snprintf(r->path, sizeof r->path, "%s/%s", dir, names[i]->d_name);
            snprintf(r->title, sizeof r->title, "fuzz/corpus/%s/%s through fuzz_%s", target,
                     names[i]->d_name, target);
            r->entry = entry;
        }
        free(names[i]);
    }
    free(names);
}
#endif

static void add_runs(int write)
{
    for (size_t i = 0; i < exec_n_scenarios; i++) {
        replay_run_t *r = add_run(exec_scenarios[i].name);
        snprintf(r->title, sizeof r->title, "%s: %s", exec_scenarios[i].name,
                 exec_scenarios[i].what);
        r->sc = &exec_scenarios[i];
    }
#ifdef HV_REPLAY_FUZZ
    add_corpus("exec_step", hv_replay_fuzz_exec_step, write);
    add_corpus("exec_online", hv_replay_fuzz_exec_online, write);
#else
    (void)write;
#endif
}

/* --write: every run's trace into the folder */
static int record(void)
{
    uint64_t total = 0;
    for (size_t i = 0; i < n_runs; i++) {
        char file[512];
        size_t len;
        uint64_t steps;
        char *text = trace_run(&runs[i], &len, &steps);
        int ok =
            exec_trace_golden(trace_dir, golden_file(&runs[i], file, sizeof file), text, len, 1);
        free(text);
        if (ok != 1)
            return 1;
        total += steps;
    }
    printf("exec-replay: %zu traces, %llu steps, recorded in %s\n", n_runs,
           (unsigned long long)total, trace_dir);
    return 0;
}

static int usage(const char *prog, int code)
{
    fprintf(code ? stderr : stdout,
            "usage: %s [--write] DIR\n"
            "Replays the executor's state machine on fixed inputs (scenarios on fake nodes%s)\n"
            "and compares the trace of each run with DIR/<run>%s, recorded from an\n"
            "earlier build: one test per run; one that differs prints its first differing\n"
            "line and leaves this build's trace in ./<run>%s.actual.\n"
            "  --write  record this build's traces into DIR instead\n",
            prog,
#ifdef HV_REPLAY_FUZZ
            ", the corpora of fuzz_exec_step and fuzz_exec_online",
#else
            "",
#endif
            HV_REPLAY_SUFFIX, HV_REPLAY_SUFFIX);
    return code;
}

int main(int argc, char **argv)
{
    int write = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0)
            return usage(argv[0], 0);
        if (strcmp(argv[i], "--write") == 0)
            write = 1;
        else if (argv[i][0] == '-' || trace_dir)
            return usage(argv[0], 2);
        else
            trace_dir = argv[i];
    }
    if (!trace_dir)
        return usage(argv[0], 2);
    add_runs(write);
    if (write)
        return record();
    static struct CMUnitTest tests[MAX_RUNS];
    for (size_t i = 0; i < n_runs; i++) {
        tests[i].name = runs[i].name;
        tests[i].test_func = test_replay;
        tests[i].initial_state = &runs[i];
    }
    return _cmocka_run_group_tests("exec_replay", tests, n_runs, NULL, NULL);
}
