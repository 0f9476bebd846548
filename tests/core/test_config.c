/* Configuration parser: the project's file parses to the paper's numbers; each kind of bad
 * input gets its own code, the key at fault and the line. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "core_fixture.h"

static char *g_text;
static size_t g_len;

static int load_text(void **state)
{
    (void)state;
    char err[256];
    void *data;
    assert_int_equal(hv_file_read_all(HV_TEST_CONFIG, &data, &g_len, err, sizeof err), HV_OK);
    g_text = data;
    return 0;
}

static int free_text(void **state)
{
    (void)state;
    free(g_text);
    return 0;
}

/* The project's config with the line holding `key` replaced by `line` (or removed if NULL). */
static char *edited(const char *key, const char *line)
{
    size_t cap = g_len + 512;
    char *out = malloc(cap);
    out[0] = '\0';
    const char *p = g_text;
    size_t klen = strlen(key);
    while (*p) {
        const char *nl = strchr(p, '\n');
        size_t n = nl ? (size_t)(nl - p) + 1 : strlen(p);
        if (strncmp(p, key, klen) == 0 && (p[klen] == ' ' || p[klen] == '=')) {
            if (line != NULL) {
                strcat(out, line);
                strcat(out, "\n");
            }
        } else {
            strncat(out, p, n);
        }
        p += n;
    }
    return out;
}

static void expect(const char *text, hv_status_t code, const char *field)
{
    hv_config_t cfg;
    hv_diag_t d;
    memset(&d, 0, sizeof d);
    assert_int_equal(hv_config_parse(text, strlen(text), &cfg, &d), code);
    assert_string_equal(d.field, field);
    assert_true(strlen(d.message) > 0);
}

static void test_project_config_parses(void **state)
{
    (void)state;
    hv_config_t cfg;
    hv_diag_t d;
    assert_int_equal(hv_config_parse(g_text, g_len, &cfg, &d), HV_OK);
    assert_float_equal(cfg.limit[0].max, 0.5, 0);
    assert_float_equal(cfg.limit[2].max, 2.8, 0);
    assert_float_equal(cfg.origin_m[4][0], 0.53, 0);
    assert_float_equal(cfg.theta_rad[0], 43.5 * M_PI / 180.0, 1e-12);
    assert_float_equal(cfg.stop_penalty_s, 5.0, 0);
    assert_true(cfg.camera_window_m > 0 && cfg.camera_lead_m >= 0);
    assert_true(cfg.fov_width_m > 0 && fabs(cfg.fov_offset_m) < 1.0);
    /* a stop costs the paper's tau, or in the robot's time what the drive loses stopping */
    cfg.pick_cycle = 0;
    assert_float_equal(hv_config_stop_time_s(&cfg), 5.0, 1e-12);
    cfg.pick_cycle = 1;
    assert_float_equal(hv_config_stop_time_s(&cfg), 0.1 / 0.1, 1e-12);
    hv_grid_t gl, gr;
    hv_config_grid(&cfg, HV_SIDE_LEFT, &gl);
    hv_config_grid(&cfg, HV_SIDE_RIGHT, &gr);
    assert_int_equal(gr.axis[HV_AX_X].count, 16);
    assert_int_equal(gr.axis[HV_AX_Y].count, 161);
    assert_int_equal(gr.axis[HV_AX_Z].count, 41);
    assert_int_equal(gr.axis[HV_AX_YAW].count, 19);
    assert_float_equal(gr.axis[HV_AX_X].origin, 0.35, 1e-12);
    assert_float_equal(gl.axis[HV_AX_X].origin, -0.50, 1e-12);
    hv_arm_t l, r;
    hv_config_arm(&cfg, HV_SIDE_LEFT, &l);
    hv_config_arm(&cfg, HV_SIDE_RIGHT, &r);
    assert_float_equal(l.base_m[0], -(0.35 - 0.26), 1e-12);
    assert_float_equal(r.base_m[0], 0.35 - 0.26, 1e-12);
    assert_float_equal(r.base_m[1], -0.235, 1e-12);
    assert_float_equal(l.base_yaw_rad, M_PI - cfg.theta_rad[0], 1e-12);
    assert_float_equal(r.base_yaw_rad, -cfg.theta_rad[1], 1e-12);
}

static void test_missing_key(void **state)
{
    (void)state;
    char *t = edited("joint3.vmax", NULL);
    expect(t, HV_ERR_CFG_MISSING, "joint3.vmax");
    free(t);
    t = edited("camera.window", NULL); /* the online mode's keys are required like any */
    expect(t, HV_ERR_CFG_MISSING, "camera.window");
    free(t);
    t = edited("fov.offset", NULL);
    expect(t, HV_ERR_CFG_MISSING, "fov.offset");
    free(t);
}

static void test_out_of_range_and_nan(void **state)
{
    (void)state;
    char *t = edited("joint2.amax", "joint2.amax = -0.2");
    expect(t, HV_ERR_CFG_RANGE, "joint2.amax");
    free(t);
    t = edited("grid.step", "grid.step = nan");
    expect(t, HV_ERR_CFG_RANGE, "grid.step");
    free(t);
    t = edited("arm.elbow_free", "arm.elbow_free = 0.5");
    expect(t, HV_ERR_CFG_RANGE, "arm.elbow_free");
    free(t);
    t = edited("arm.home", "arm.home = 0.25 0.0 3.0 0.0"); /* joint 3 beyond 2.8 */
    expect(t, HV_ERR_CFG_RANGE, "arm.home");
    free(t);
    t = edited("camera.window", "camera.window = 0");
    expect(t, HV_ERR_CFG_RANGE, "camera.window");
    free(t);
    t = edited("fov.width", "fov.width = 0");
    expect(t, HV_ERR_CFG_RANGE, "fov.width");
    free(t);
    t = edited("joint1.max", "joint1.max = -1");
    expect(t, HV_ERR_CFG_RANGE, "joint1.max");
    free(t);
}

static void test_syntax_unknown_duplicate(void **state)
{
    (void)state;
    char *t = edited("row.length", "row.length = 2.0 3.0");
    expect(t, HV_ERR_CFG_SYNTAX, "row.length");
    free(t);
    t = edited("row.length", "row.length = two");
    expect(t, HV_ERR_CFG_SYNTAX, "row.length");
    free(t);
    t = edited("row.length", "row.length 2.0");
    expect(t, HV_ERR_CFG_SYNTAX, "row.length 2.0");
    free(t);
    t = edited("arm.origin.ee", "arm.origin.ee = 0.53 0.0");
    expect(t, HV_ERR_CFG_SYNTAX, "arm.origin.ee");
    free(t);
    t = edited("row.length", "row.length = 2.0\nrow.lenght = 2.0");
    expect(t, HV_ERR_CFG_UNKNOWN, "row.lenght");
    free(t);
    t = edited("row.length", "row.length = 2.0\nrow.length = 3.0");
    expect(t, HV_ERR_CFG_DUPLICATE, "row.length");
    free(t);
}

static void test_line_number_reported(void **state)
{
    (void)state;
    const char *text = "# comment\n\njoint1.min = oops\n";
    hv_config_t cfg;
    hv_diag_t d;
    assert_int_equal(hv_config_parse(text, strlen(text), &cfg, &d), HV_ERR_CFG_SYNTAX);
    assert_int_equal(d.line, 3);
    /* a truncated (non NUL-terminated) buffer is parsed only up to len */
    assert_int_equal(hv_config_parse(g_text, 40, &cfg, &d), HV_ERR_CFG_MISSING);
}

static void test_load_names_file_and_line(void **state)
{
    (void)state;
    char path[] = "/tmp/hv_cfg_test_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    char *t = edited("vehicle.speed", "vehicle.speed = 0");
    FILE *fp = fdopen(fd, "w");
    fputs(t, fp);
    fclose(fp);
    free(t);
    hv_config_t cfg;
    char err[256];
    assert_int_equal(hv_config_load(path, &cfg, err, sizeof err), HV_ERR_CFG_RANGE);
    assert_non_null(strstr(err, path));
    assert_non_null(strstr(err, "vehicle.speed"));
    unlink(path);
    assert_int_equal(hv_config_load("/nonexistent/harvest.cfg", &cfg, err, sizeof err), HV_ERR_IO);
    assert_non_null(strstr(err, "/nonexistent/harvest.cfg"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_project_config_parses),
        cmocka_unit_test(test_missing_key),
        cmocka_unit_test(test_out_of_range_and_nan),
        cmocka_unit_test(test_syntax_unknown_duplicate),
        cmocka_unit_test(test_line_number_reported),
        cmocka_unit_test(test_load_names_file_and_line),
    };
    return cmocka_run_group_tests_name("core_config", tests, load_text, free_text);
}
