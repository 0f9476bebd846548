/* The plan image (firmware/plan_image.c): a plan written by the host's writer arrives
 * whole through the firmware's reader, 6 bytes a frame; damage gets its named error. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fw_status.h"
#include "hv/cost_table.h"
#include "plan_image.h"

typedef struct fixture {
    hv_exec_plan_t plan, got;
    hv_exec_params_t prm, got_prm;
    uint8_t image[4096];
    size_t size;
} fixture_t;

static int setup(void **state)
{
    fixture_t *f = calloc(1, sizeof *f);
    hv_exec_params_default(&f->prm);
    f->prm.time_scale = 2.5;
    f->plan.n_stops = 2;
    f->plan.n_picks = 3;
    f->plan.row_start_m = 0.25;
    f->plan.expected_makespan_s = 61.125;
    f->plan.home[1][2] = -0.75;
    const hv_side_t side[3] = {HV_SIDE_LEFT, HV_SIDE_RIGHT, HV_SIDE_LEFT};
    const uint16_t stop[3] = {0, 0, 1};
    f->plan.stops[0] = (hv_exec_stop_t){7, 0.5, {0, 1}, {1, 1}, {3.0, 4.0}, 4.0, 1.5};
    f->plan.stops[1] = (hv_exec_stop_t){9, 0.9, {2, 3}, {1, 0}, {3.5, 0.0}, 3.5, 2.0};
    for (unsigned k = 0; k < 3; k++) {
        hv_exec_pick_t *p = &f->plan.picks[k];
        p->id[0] = 'f';
        p->id[1] = (char)('a' + k);
        p->side = side[k];
        p->stop = stop[k];
        p->reachable = k != 1;
        p->q[3] = 0.125 * k;
        p->move_s = 1.0 + k;
    }
    f->size = hv_fw_image_write(&f->plan, &f->prm, f->image, sizeof f->image);
    *state = f;
    return f->size == hv_fw_image_size(2, 3) ? 0 : -1;
}

static int teardown(void **state)
{
    free(*state);
    return 0;
}

/* the image through the reader in frames of 6; the status of the first failure */
static hv_status_t feed(fixture_t *f, uint32_t crc, size_t skip_frame)
{
    hv_fw_image_reader_t r;
    hv_fw_image_begin(&r, &f->got, &f->got_prm, (uint32_t)f->size, crc);
    for (size_t off = 0, n = 0; off < f->size; off += 6, n++) {
        uint8_t chunk[6] = {0};
        memcpy(chunk, f->image + off, f->size - off < 6 ? f->size - off : 6);
        if (n == skip_frame)
            continue;
        hv_status_t st = hv_fw_image_data(&r, (uint32_t)off, chunk, 6);
        if (st != HV_OK)
            return st;
    }
    return hv_fw_image_finish(&r);
}

static void test_round_trip(void **state)
{
    fixture_t *f = *state;
    assert_int_equal(feed(f, hv_crc32(0, f->image, f->size), (size_t)-1), HV_OK);
    assert_int_equal(f->got.n_stops, 2);
    assert_int_equal(f->got.n_picks, 3);
    assert_true(f->got_prm.time_scale == 2.5 && f->got.row_start_m == 0.25);
    assert_true(f->got.expected_makespan_s == 61.125 && f->got.home[1][2] == -0.75);
    assert_memory_equal(&f->got.stops[1], &f->plan.stops[1], sizeof f->plan.stops[1]);
    assert_string_equal(f->got.picks[2].id, "fc");
    assert_true(f->got.picks[2].q[3] == 0.25 && f->got.picks[1].reachable == 0);
    assert_int_equal(f->got.n_unreachable, 1);
}

static void test_damage_is_named(void **state)
{
    fixture_t *f = *state;
    uint32_t crc = hv_crc32(0, f->image, f->size);
    assert_int_equal(feed(f, crc ^ 1u, (size_t)-1), HV_ERR_FW_UPLOAD_CRC);
    assert_int_equal(feed(f, crc, 5), HV_ERR_FW_UPLOAD_ORDER);
    f->image[0] ^= 0xFF; /* magic */
    assert_int_equal(feed(f, crc, (size_t)-1), HV_ERR_FW_UPLOAD_FORMAT);
    f->image[0] ^= 0xFF;
    /* a pick outside its stop's range of its arm */
    size_t pick1 = HV_FW_IMAGE_HEADER + 2 * HV_FW_IMAGE_STOP + HV_FW_IMAGE_PICK;
    f->image[pick1 + 2] = 1; /* stop 1 has no right-arm pick */
    assert_int_equal(feed(f, crc, (size_t)-1), HV_ERR_FW_UPLOAD_FORMAT);
    f->image[pick1 + 2] = 0;
    /* more picks announced than the length carries */
    f->image[8] = 4;
    assert_int_equal(feed(f, crc, (size_t)-1), HV_ERR_FW_UPLOAD_LENGTH);
    f->image[8] = 3;
}

static void put_f64_le(uint8_t *b, double v)
{
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    for (unsigned i = 0; i < 8; i++)
        b[i] = (uint8_t)(u >> (8u * i));
}

/* A number finite as a double but not in the executor's real type refuses the plan where
 * that type is float (the firmware's; firmware_plan_image_single_test builds this file so);
 * the plan's own double fields take it in either build. */
static void test_number_beyond_the_real_type(void **state)
{
    fixture_t *f = *state;
    const double big = 1e300;
    int single = sizeof(hv_exec_real_t) == sizeof(float);
    put_f64_le(f->image + 12 + 8 * 18, big); /* header f64 18: planned_pick_s, double */
    assert_int_equal(feed(f, hv_crc32(0, f->image, f->size), (size_t)-1), HV_OK);
    assert_true(f->got.planned_pick_s == big);
    put_f64_le(f->image + 12 + 8 * 8, big); /* header f64 8: home_max_s, real */
    assert_int_equal(feed(f, hv_crc32(0, f->image, f->size), (size_t)-1),
                     single ? HV_ERR_FW_UPLOAD_FORMAT : HV_OK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_round_trip, setup, teardown),
        cmocka_unit_test_setup_teardown(test_damage_is_named, setup, teardown),
        cmocka_unit_test_setup_teardown(test_number_beyond_the_real_type, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
