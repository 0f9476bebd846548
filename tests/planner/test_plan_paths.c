/* A plan's input paths: relative ones resolve against the plan file's folder, and the
 * writer's rewrite of a path given relative to the current directory resolves, from the
 * plan's folder, to the same file (also through a symbolic link to that folder). */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, symlink, chdir */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hv/plan_paths.h"

static char g_tmp[64];
static char g_cwd[4096];

/* A tree of its own, entered: a/b (the plan's folder), c (an input's), link -> a/b. */
static int setup(void **state)
{
    (void)state;
    snprintf(g_tmp, sizeof g_tmp, "/tmp/hv_plan_paths_XXXXXX");
    if (getcwd(g_cwd, sizeof g_cwd) == NULL || mkdtemp(g_tmp) == NULL || chdir(g_tmp) != 0) {
        return -1;
    }
    if (mkdir("a", 0755) != 0 || mkdir("a/b", 0755) != 0 || mkdir("c", 0755) != 0 ||
        symlink("a/b", "link") != 0) {
        return -1;
    }
    const char *files[] = {"c/map.csv", "a/b/here.csv", "a/up.cfg"};
    for (size_t i = 0; i < 3; ++i) {
        FILE *f = fopen(files[i], "w");
        if (f == NULL) {
            return -1;
        }
        fprintf(f, "%s\n", files[i]); /* each file says what it is */
        fclose(f);
    }
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_tmp);
    return chdir(g_cwd) == 0 && system(cmd) == 0 ? 0 : -1;
}

static void test_resolve(void **state)
{
    (void)state;
    char out[64];
    assert_int_equal(hv_plan_input_resolve("d/e/plan.json", "m.csv", out, sizeof out), HV_OK);
    assert_string_equal(out, "d/e/m.csv");
    assert_int_equal(hv_plan_input_resolve("d/e/plan.json", "../t/l.tab", out, sizeof out), HV_OK);
    assert_string_equal(out, "d/e/../t/l.tab");
    assert_int_equal(hv_plan_input_resolve("plan.json", "m.csv", out, sizeof out), HV_OK);
    assert_string_equal(out, "m.csv");
    assert_int_equal(hv_plan_input_resolve("/plan.json", "m.csv", out, sizeof out), HV_OK);
    assert_string_equal(out, "/m.csv");
    assert_int_equal(hv_plan_input_resolve("d/plan.json", "/abs/m.csv", out, sizeof out), HV_OK);
    assert_string_equal(out, "/abs/m.csv");
    assert_int_equal(hv_plan_input_resolve("d/plan.json", "m.csv", out, 5), HV_ERR_NOMEM);
    assert_int_equal(hv_plan_input_resolve("d/plan.json", "", out, sizeof out), HV_ERR_ARG);
}

/* The first line of the file at `path`. */
static void first_line(const char *path, char *out, size_t cap)
{
    FILE *f = fopen(path, "r");
    if (f == NULL) {
        print_error("cannot open %s\n", path);
        fail();
    }
    assert_non_null(fgets(out, (int)cap, f));
    out[strcspn(out, "\n")] = '\0';
    fclose(f);
}

/* Written for a plan at plan_path, then read back from there: the same file as `input`. */
static void round_trip(const char *plan_path, const char *input)
{
    char rel[256], back[512], err[256] = "", want[64], got[64];
    assert_int_equal(hv_plan_input_relative(plan_path, input, rel, sizeof rel, err, sizeof err),
                     HV_OK);
    assert_int_equal(hv_plan_input_resolve(plan_path, rel, back, sizeof back), HV_OK);
    first_line(input, want, sizeof want);
    first_line(back, got, sizeof got);
    assert_string_equal(got, want);
}

static void test_relative(void **state)
{
    (void)state;
    char rel[256], err[256] = "";
    round_trip("a/b/plan.json", "c/map.csv");
    round_trip("a/b/plan.json", "a/b/here.csv");
    round_trip("a/b/plan.json", "a/up.cfg");
    round_trip("link/plan.json", "c/map.csv");
    round_trip("plan.json", "./a/up.cfg");
    /* beside the plan: the name alone; an absolute path stays as it is */
    assert_int_equal(
        hv_plan_input_relative("a/b/p.json", "a/b/here.csv", rel, sizeof rel, err, sizeof err),
        HV_OK);
    assert_string_equal(rel, "here.csv");
    assert_int_equal(
        hv_plan_input_relative("a/b/p.json", "/x/y.tab", rel, sizeof rel, err, sizeof err), HV_OK);
    assert_string_equal(rel, "/x/y.tab");
    /* the plan's folder must exist, and the result fit */
    assert_int_equal(
        hv_plan_input_relative("nowhere/p.json", "c/map.csv", rel, sizeof rel, err, sizeof err),
        HV_ERR_IO);
    assert_non_null(strstr(err, "nowhere/p.json: cannot resolve its folder"));
    assert_int_equal(hv_plan_input_relative("a/b/p.json", "c/map.csv", rel, 8, err, sizeof err),
                     HV_ERR_NOMEM);
    assert_non_null(strstr(err, "c/map.csv: longer than 7 bytes"));
    assert_int_equal(hv_plan_input_relative("a/b/p.json", "c/..", rel, sizeof rel, err, sizeof err),
                     HV_ERR_ARG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_resolve),
        cmocka_unit_test(test_relative),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
