/* Cost table file: round trip, lookup semantics, and every way a file can be bad. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "core_fixture.h"
#include "hv/cost_table.h"

/* A small table built cell by cell from the real arm with direct IK + timing. */
typedef struct fixture {
    hv_config_t cfg;
    hv_arm_t arm;
    hv_grid_t grid;
    uint16_t *costs;
    uint8_t *file;
    size_t file_len;
} fixture_t;

static void index_to_pose(const hv_grid_t *g, size_t i, uint32_t *ix, uint32_t *iy, uint32_t *iz,
                          uint32_t *iyaw)
{
    uint32_t ny = g->axis[HV_AX_Y].count, nyaw = g->axis[HV_AX_YAW].count,
             nz = g->axis[HV_AX_Z].count;
    *iy = (uint32_t)(i % ny);
    i /= ny;
    *iyaw = (uint32_t)(i % nyaw);
    i /= nyaw;
    *iz = (uint32_t)(i % nz);
    *ix = (uint32_t)(i / nz);
}

static double ax_val(const hv_grid_t *g, int a, uint32_t i)
{
    return g->axis[a].origin + g->axis[a].step * i;
}

static int setup(void **state)
{
    fixture_t *f = calloc(1, sizeof *f);
    fixture_config(&f->cfg);
    /* coarse grid so the test stays fast under sanitizers */
    f->cfg.grid_step_m = 0.05;
    f->cfg.grid_yaw_step_rad = 15.0 * M_PI / 180.0;
    hv_config_arm(&f->cfg, HV_SIDE_RIGHT, &f->arm);
    hv_config_grid(&f->cfg, HV_SIDE_RIGHT, &f->grid);
    size_t cells = hv_grid_cells(&f->grid);
    f->costs = calloc(cells, sizeof *f->costs);
    for (size_t i = 0; i < cells; i++) {
        uint32_t ix, iy, iz, iyaw;
        index_to_pose(&f->grid, i, &ix, &iy, &iz, &iyaw);
        hv_pose_t p = {ax_val(&f->grid, HV_AX_X, ix), ax_val(&f->grid, HV_AX_Y, iy),
                       ax_val(&f->grid, HV_AX_Z, iz),
                       ax_val(&f->grid, HV_AX_YAW, iyaw) + hv_side_normal_heading(HV_SIDE_RIGHT)};
        double c;
        f->costs[i] = hv_scara_pick_cost(&f->arm, &p, &c, NULL) == HV_OK
                          ? (uint16_t)lround(c * 1000.0)
                          : (uint16_t)HV_COST_UNREACHABLE;
    }
    f->file_len = hv_costtab_file_bytes(&f->grid);
    f->file = malloc(f->file_len);
    hv_diag_t d;
    assert_int_equal(hv_costtab_write(&f->grid, &f->arm, 7, f->costs, f->file, f->file_len, &d),
                     HV_OK);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture_t *f = *state;
    free(f->costs);
    free(f->file);
    free(f);
    return 0;
}

static void test_roundtrip_and_cells(void **state)
{
    fixture_t *f = *state;
    hv_costtab_t t;
    hv_diag_t d;
    assert_int_equal(hv_costtab_open(&t, f->file, f->file_len, &d), HV_OK);
    assert_int_equal(t.generator_version, 7);
    assert_int_equal(t.cells, hv_grid_cells(&f->grid));
    assert_int_equal(t.arm.side, HV_SIDE_RIGHT);
    assert_memory_equal(t.arm.home, f->arm.home, sizeof t.arm.home);
    assert_float_equal(t.arm.base_yaw_rad, f->arm.base_yaw_rad, 0.0);
    size_t reachable = 0;
    for (size_t i = 0; i < t.cells; i++) {
        uint32_t ix, iy, iz, iyaw;
        index_to_pose(&t.grid, i, &ix, &iy, &iz, &iyaw);
        assert_int_equal(hv_costtab_cell(&t, ix, iy, iz, iyaw), f->costs[i]);
        uint16_t c = 0;
        hv_status_t st =
            hv_costtab_lookup(&t, ax_val(&t.grid, HV_AX_X, ix), ax_val(&t.grid, HV_AX_Y, iy),
                              ax_val(&t.grid, HV_AX_Z, iz), ax_val(&t.grid, HV_AX_YAW, iyaw), &c);
        if (f->costs[i] == HV_COST_UNREACHABLE) {
            assert_int_equal(st, HV_ERR_UNREACHABLE);
        } else {
            assert_int_equal(st, HV_OK);
            assert_int_equal(c, f->costs[i]);
            reachable++;
        }
    }
    assert_true(reachable > 0 && reachable < t.cells);
}

static void test_lookup_nearest_cell_and_row(void **state)
{
    fixture_t *f = *state;
    hv_costtab_t t;
    assert_int_equal(hv_costtab_open(&t, f->file, f->file_len, NULL), HV_OK);
    const hv_grid_t *g = &t.grid;
    /* a value 0.4 step off a grid point rounds to that point */
    uint32_t ix = 1, iy = g->axis[HV_AX_Y].count / 2, iz = 2, iyaw = 1;
    double x = ax_val(g, HV_AX_X, ix) + 0.4 * g->axis[HV_AX_X].step;
    double y = ax_val(g, HV_AX_Y, iy) - 0.4 * g->axis[HV_AX_Y].step;
    assert_int_equal(hv_axis_index(&g->axis[HV_AX_X], x), ix);
    assert_int_equal(hv_axis_index(&g->axis[HV_AX_Y], y), iy);
    const uint8_t *row;
    assert_int_equal(
        hv_costtab_row(&t, x, ax_val(g, HV_AX_Z, iz), ax_val(g, HV_AX_YAW, iyaw), &row), HV_OK);
    for (uint32_t k = 0; k < g->axis[HV_AX_Y].count; k++) {
        assert_int_equal(hv_costtab_row_at(row, k), hv_costtab_cell(&t, ix, k, iz, iyaw));
    }
}

static void test_lookup_outside_grid_and_nan(void **state)
{
    fixture_t *f = *state;
    hv_costtab_t t;
    assert_int_equal(hv_costtab_open(&t, f->file, f->file_len, NULL), HV_OK);
    const hv_grid_t *g = &t.grid;
    uint16_t c;
    double x0 = g->axis[HV_AX_X].origin, z0 = g->axis[HV_AX_Z].origin;
    double xe = x0 + g->axis[HV_AX_X].step * (g->axis[HV_AX_X].count - 1);
    /* just past half a step beyond either end: outside */
    assert_int_equal(hv_costtab_lookup(&t, x0 - 0.51 * g->axis[HV_AX_X].step, 0, z0, 0, &c),
                     HV_ERR_OUT_OF_GRID);
    assert_int_equal(hv_costtab_lookup(&t, xe + 0.51 * g->axis[HV_AX_X].step, 0, z0, 0, &c),
                     HV_ERR_OUT_OF_GRID);
    assert_int_equal(hv_costtab_lookup(&t, x0, 100.0, z0, 0, &c), HV_ERR_OUT_OF_GRID);
    assert_int_equal(hv_costtab_lookup(&t, x0, -100.0, z0, 0, &c), HV_ERR_OUT_OF_GRID);
    assert_int_equal(hv_costtab_lookup(&t, x0, 0, z0, 3.0, &c), HV_ERR_OUT_OF_GRID);
    assert_int_equal(hv_costtab_lookup(&t, x0, 0, 1e300, 0, &c), HV_ERR_OUT_OF_GRID);
    assert_int_equal(hv_costtab_lookup(&t, NAN, 0, z0, 0, &c), HV_ERR_NAN);
    assert_int_equal(hv_costtab_lookup(&t, x0, NAN, z0, 0, &c), HV_ERR_NAN);
    assert_int_equal(hv_costtab_lookup(&t, x0, 0, z0, INFINITY, &c), HV_ERR_NAN);
}

/* Open a damaged copy and check the code and the field named. */
static void expect_bad(const fixture_t *f, size_t len, void (*damage)(uint8_t *, size_t),
                       hv_status_t code, const char *field)
{
    uint8_t *copy = malloc(f->file_len);
    memcpy(copy, f->file, f->file_len);
    if (damage != NULL) {
        damage(copy, len);
    }
    /* exact-size buffer so ASan sees any read past the end */
    uint8_t *exact = malloc(len ? len : 1);
    memcpy(exact, copy, len);
    hv_costtab_t t;
    hv_diag_t d;
    memset(&d, 0, sizeof d);
    assert_int_equal(hv_costtab_open(&t, exact, len, &d), code);
    assert_string_equal(d.field, field);
    assert_true(strlen(d.message) > 0);
    free(exact);
    free(copy);
}

static void fix_header_crc(uint8_t *b)
{
    uint32_t c = hv_crc32(0, b, 468);
    for (int i = 0; i < 4; i++) {
        b[468 + i] = (uint8_t)(c >> (8 * i));
    }
}

static void dmg_magic(uint8_t *b, size_t n)
{
    (void)n;
    b[0] = 'X';
}
static void dmg_version(uint8_t *b, size_t n)
{
    (void)n;
    b[8] = 2;
    fix_header_crc(b);
}
static void dmg_header_size(uint8_t *b, size_t n)
{
    (void)n;
    b[12] = 0;
    b[13] = 1;
    fix_header_crc(b);
}
static void dmg_header_bit(uint8_t *b, size_t n)
{
    (void)n;
    b[100] ^= 0x10;
}
static void dmg_payload_bit(uint8_t *b, size_t n)
{
    b[n - 1] ^= 0x01;
}
static void dmg_grid_step(uint8_t *b, size_t n)
{
    (void)n;
    double neg = -0.05; /* axis y step */
    memcpy(b + 40 + 24 + 8, &neg, 8);
    fix_header_crc(b);
}
static void dmg_grid_count(uint8_t *b, size_t n)
{
    (void)n;
    b[40 + 16] = (uint8_t)(b[40 + 16] + 1); /* x count + 1: payload size no longer fits */
    fix_header_crc(b);
}
static void dmg_side(uint8_t *b, size_t n)
{
    (void)n;
    b[20] = 5;
    fix_header_crc(b);
}

static void test_bad_files(void **state)
{
    fixture_t *f = *state;
    size_t n = f->file_len;
    expect_bad(f, 0, NULL, HV_ERR_TAB_TRUNCATED, "header");
    expect_bad(f, 100, NULL, HV_ERR_TAB_TRUNCATED, "header");
    expect_bad(f, n - 1, NULL, HV_ERR_TAB_TRUNCATED, "payload");
    expect_bad(f, n, dmg_magic, HV_ERR_TAB_MAGIC, "magic");
    expect_bad(f, n, dmg_version, HV_ERR_TAB_VERSION, "version");
    expect_bad(f, n, dmg_header_size, HV_ERR_TAB_HEADER, "header_bytes");
    expect_bad(f, n, dmg_header_bit, HV_ERR_TAB_CRC, "header_crc32");
    expect_bad(f, n, dmg_payload_bit, HV_ERR_TAB_CRC, "payload_crc32");
    expect_bad(f, n, dmg_grid_step, HV_ERR_TAB_GRID, "grid.y.step");
    expect_bad(f, n, dmg_grid_count, HV_ERR_TAB_GRID, "payload_bytes");
    expect_bad(f, n, dmg_side, HV_ERR_TAB_HEADER, "side");
}

static void test_trailing_bytes_rejected(void **state)
{
    fixture_t *f = *state;
    uint8_t *big = calloc(1, f->file_len + 3);
    memcpy(big, f->file, f->file_len);
    hv_costtab_t t;
    hv_diag_t d;
    assert_int_equal(hv_costtab_open(&t, big, f->file_len + 3, &d), HV_ERR_TAB_HEADER);
    assert_string_equal(d.field, "file_size");
    free(big);
}

static void test_every_single_bit_flip_in_header_is_caught(void **state)
{
    fixture_t *f = *state;
    uint8_t *copy = malloc(f->file_len);
    for (size_t byte = 0; byte < 472; byte++) {
        for (int bit = 0; bit < 8; bit++) {
            memcpy(copy, f->file, f->file_len);
            copy[byte] ^= (uint8_t)(1u << bit);
            hv_costtab_t t;
            assert_true(hv_costtab_open(&t, copy, f->file_len, NULL) < 0);
        }
    }
    free(copy);
}

static void test_expect_side_and_grid(void **state)
{
    fixture_t *f = *state;
    hv_costtab_t t;
    hv_diag_t d;
    assert_int_equal(hv_costtab_open(&t, f->file, f->file_len, NULL), HV_OK);
    assert_int_equal(hv_costtab_expect(&t, HV_SIDE_RIGHT, &f->grid, &d), HV_OK);
    assert_int_equal(hv_costtab_expect(&t, HV_SIDE_LEFT, NULL, &d), HV_ERR_TAB_MISMATCH);
    assert_string_equal(d.field, "side");
    hv_grid_t other = f->grid;
    other.axis[HV_AX_Z].count++;
    assert_int_equal(hv_costtab_expect(&t, HV_SIDE_RIGHT, &other, &d), HV_ERR_TAB_MISMATCH);
    assert_string_equal(d.field, "grid.z");
}

/* The table's arm against the configured one: each kind of difference named. */
static void test_expect_arm_names_the_difference(void **state)
{
    fixture_t *f = *state;
    hv_costtab_t t;
    hv_diag_t d;
    assert_int_equal(hv_costtab_open(&t, f->file, f->file_len, NULL), HV_OK);
    assert_int_equal(hv_costtab_expect_arm(&t, &f->arm, &f->grid, &d), HV_OK);
    struct {
        const char *field;
        hv_arm_t arm;
    } cases[6];
    for (int i = 0; i < 6; i++) {
        cases[i].arm = f->arm;
    }
    cases[0].field = "mount.base";
    cases[0].arm.base_m[0] += 0.01;
    cases[1].field = "mount.heading";
    cases[1].arm.base_yaw_rad += 0.001;
    cases[2].field = "elbow_free";
    cases[2].arm.elbow_free = !f->arm.elbow_free;
    cases[3].field = "joint_limits";
    cases[3].arm.limit[1].vmax *= 1.5;
    cases[4].field = "home";
    cases[4].arm.home[0] += 0.05;
    cases[5].field = "link_origins";
    cases[5].arm.origin_m[4][0] += 0.01;
    for (int i = 0; i < 6; i++) {
        memset(&d, 0, sizeof d);
        assert_int_equal(hv_costtab_expect_arm(&t, &cases[i].arm, &f->grid, &d),
                         HV_ERR_TAB_MISMATCH);
        assert_string_equal(d.field, cases[i].field);
    }
    /* a rounding of the same mount is the same arm */
    hv_arm_t near = f->arm;
    near.base_m[1] += 1e-9;
    assert_int_equal(hv_costtab_expect_arm(&t, &near, &f->grid, &d), HV_OK);
    hv_arm_t left = f->arm;
    left.side = HV_SIDE_LEFT;
    assert_int_equal(hv_costtab_expect_arm(&t, &left, &f->grid, &d), HV_ERR_TAB_MISMATCH);
    assert_string_equal(d.field, "side");
}

static void test_writer_rejects_bad_grid_and_small_buffer(void **state)
{
    fixture_t *f = *state;
    hv_diag_t d;
    hv_grid_t g = f->grid;
    g.axis[HV_AX_YAW].count = 0;
    assert_int_equal(hv_costtab_write(&g, &f->arm, 1, f->costs, f->file, f->file_len, &d),
                     HV_ERR_TAB_GRID);
    assert_string_equal(d.field, "grid.yaw.count");
    assert_int_equal(hv_costtab_file_bytes(&g), 0);
    g = f->grid;
    g.axis[HV_AX_X].origin = NAN;
    assert_int_equal(hv_costtab_write(&g, &f->arm, 1, f->costs, f->file, f->file_len, &d),
                     HV_ERR_TAB_GRID);
    assert_int_equal(hv_costtab_write(&f->grid, &f->arm, 1, f->costs, f->file, 600, &d),
                     HV_ERR_NOMEM);
}

static void test_crc32_known_value(void **state)
{
    (void)state;
    /* the standard check value of CRC-32/ISO-HDLC */
    assert_int_equal(hv_crc32(0, "123456789", 9), 0xCBF43926u);
    assert_int_equal(hv_crc32(hv_crc32(0, "1234", 4), "56789", 5), 0xCBF43926u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_roundtrip_and_cells, setup, teardown),
        cmocka_unit_test_setup_teardown(test_lookup_nearest_cell_and_row, setup, teardown),
        cmocka_unit_test_setup_teardown(test_lookup_outside_grid_and_nan, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_files, setup, teardown),
        cmocka_unit_test_setup_teardown(test_trailing_bytes_rejected, setup, teardown),
        cmocka_unit_test_setup_teardown(test_every_single_bit_flip_in_header_is_caught, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_expect_side_and_grid, setup, teardown),
        cmocka_unit_test_setup_teardown(test_expect_arm_names_the_difference, setup, teardown),
        cmocka_unit_test_setup_teardown(test_writer_rejects_bad_grid_and_small_buffer, setup,
                                        teardown),
        cmocka_unit_test(test_crc32_known_value),
    };
    return cmocka_run_group_tests_name("core_cost_table", tests, NULL, NULL);
}
