/* Fruit map CSV: good input parses; each bad input has its own code and names the line; a
 * saved map reads back the same. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hv/fruit_map.h"
#include "tiny_tables.h"

static hv_fruitmap_limits_t g_lim;

static int setup(void **state)
{
    (void)state;
    hv_config_t cfg;
    if (tt_load_config(&cfg) != 0) {
        return -1;
    }
    hv_fruitmap_limits_from_config(&cfg, 0.0, cfg.row_length_m, &g_lim);
    return 0;
}

static hv_status_t parse(const char *text, hv_fruitmap_t *map, char *err, size_t errlen)
{
    return hv_fruitmap_parse(text, strlen(text), "map.csv", &g_lim, map, err, errlen);
}

static void test_good_map(void **state)
{
    (void)state;
    const char *text = "id,side,x,y,z,yaw\n"
                       "17,L,-0.40,0.50,0.60,0.1\r\n"
                       "\n"
                       " a-2 , R , 0.45 , 1.25 , 0.55 , -0.2 \n";
    hv_fruitmap_t map;
    char err[256] = "";
    assert_int_equal(parse(text, &map, err, sizeof err), HV_OK);
    assert_int_equal(map.n, 2);
    assert_string_equal(map.fruits[0].id, "17");
    assert_int_equal(map.fruits[0].side, HV_SIDE_LEFT);
    assert_true(map.fruits[0].x_m == -0.40 && map.fruits[0].y_m == 0.50);
    assert_true(map.fruits[0].z_m == 0.60 && map.fruits[0].yaw_rad == 0.1);
    assert_string_equal(map.fruits[1].id, "a-2");
    assert_int_equal(map.fruits[1].side, HV_SIDE_RIGHT);
    assert_true(map.fruits[1].y_m == 1.25 && map.fruits[1].yaw_rad == -0.2);
    hv_fruitmap_free(&map);
    assert_null(map.fruits);
}

typedef struct bad_case {
    const char *text;
    hv_status_t code;
    const char *in_msg; /* a substring the one-line message must contain */
} bad_case_t;

static void test_bad_maps(void **state)
{
    (void)state;
    static const bad_case_t cases[] = {
        {"", HV_ERR_PLAN_MAP_EMPTY, "map.csv: map: empty"},
        {"id,side,x,y,z,yaw\n", HV_ERR_PLAN_MAP_EMPTY, "no fruit"},
        {"id,side,x,y,z,yaw\n\n\n", HV_ERR_PLAN_MAP_EMPTY, "no fruit"},
        {"id,side,x,y,z\n1,L,-0.4,0.5,0.6\n", HV_ERR_PLAN_MAP_HEADER, "map.csv:1: header"},
        {"id,side,x,y,z,yaw\n1,L,-0.4,0.5,0.6\n", HV_ERR_PLAN_MAP_SYNTAX, "map.csv:2: line"},
        {"id,side,x,y,z,yaw\n1,L,-0.4,0.5,0.6,0,7\n", HV_ERR_PLAN_MAP_SYNTAX, "found 7"},
        {"id,side,x,y,z,yaw\n1,L,-0.4,abc,0.6,0\n", HV_ERR_PLAN_MAP_SYNTAX, ":2: y: not a number"},
        {"id,side,x,y,z,yaw\n1,L,-0.4,,0.6,0\n", HV_ERR_PLAN_MAP_SYNTAX, ":2: y: empty"},
        {"id,side,x,y,z,yaw\n1,L,-0.4,0.5,0.6,0\n2,R,0.4,0.5,0.6,0\n1,R,0.4,0.7,0.6,0\n",
         HV_ERR_PLAN_MAP_DUPLICATE, "map.csv:4: id: duplicate id \"1\" (first on line 2)"},
        {"id,side,x,y,z,yaw\n1,X,-0.4,0.5,0.6,0\n", HV_ERR_PLAN_MAP_SIDE, ":2: side"},
        {"id,side,x,y,z,yaw\n1,left,-0.4,0.5,0.6,0\n", HV_ERR_PLAN_MAP_SIDE, "got \"left\""},
        {"id,side,x,y,z,yaw\n1,L,nan,0.5,0.6,0\n", HV_ERR_PLAN_MAP_NAN, ":2: x: not finite"},
        {"id,side,x,y,z,yaw\n1,L,-0.4,inf,0.6,0\n", HV_ERR_PLAN_MAP_NAN, ":2: y"},
        {"id,side,x,y,z,yaw\n1,L,-0.4,0.5,0.6,-Infinity\n", HV_ERR_PLAN_MAP_NAN, "yaw"},
        /* a left fruit on the right side of the aisle is outside the left table's x grid */
        {"id,side,x,y,z,yaw\n1,L,0.4,0.5,0.6,0\n", HV_ERR_PLAN_MAP_RANGE, ":2: x: 0.4 outside"},
        {"id,side,x,y,z,yaw\n1,R,0.4,0.5,1.6,0\n", HV_ERR_PLAN_MAP_RANGE, ":2: z"},
        {"id,side,x,y,z,yaw\n1,R,0.4,0.5,0.6,1.2\n", HV_ERR_PLAN_MAP_RANGE, ":2: yaw"},
        {"id,side,x,y,z,yaw\n1,R,0.4,2.5,0.6,0\n", HV_ERR_PLAN_MAP_RANGE,
         ":2: y: 2.5 outside the row"},
        {"id,side,x,y,z,yaw\n1,R,0.4,-0.01,0.6,0\n", HV_ERR_PLAN_MAP_RANGE, "outside the row"},
        {"id,side,x,y,z,yaw\n,R,0.4,0.5,0.6,0\n", HV_ERR_PLAN_MAP_ID, ":2: id: empty"},
        {"id,side,x,y,z,yaw\nthis-id-is-far-too-long-for-a-fruit-id,R,0.4,0.5,0.6,0\n",
         HV_ERR_PLAN_MAP_ID, ":2: id: 38 characters, more than 31"},
        {"id,side,x,y,z,yaw\na\"b,R,0.4,0.5,0.6,0\n", HV_ERR_PLAN_MAP_ID, "not allowed"},
        /* outside the id set (hv/fruit_id.h): a CR inside the id, a space, a '#', UTF-8 */
        {"id,side,x,y,z,yaw\n1,L,-0.4,0.5,0.6,0\nr\rx,R,0.4,0.5,0.6,0\n", HV_ERR_PLAN_MAP_ID,
         "map.csv:3: id: character 0x0d at position 2"},
        {"id,side,x,y,z,yaw\nfruit 7,R,0.4,0.5,0.6,0\n", HV_ERR_PLAN_MAP_ID, "0x20 at position 6"},
        {"id,side,x,y,z,yaw\nrow#7,R,0.4,0.5,0.6,0\n", HV_ERR_PLAN_MAP_ID, "0x23"},
        {"id,side,x,y,z,yaw\nfr\xc3\xa9,R,0.4,0.5,0.6,0\n", HV_ERR_PLAN_MAP_ID, "0xc3"},
        /* a newline inside a quoted id leaves a line of one field: refused, never joined */
        {"id,side,x,y,z,yaw\n\"a\nb\",R,0.4,0.5,0.6,0\n", HV_ERR_PLAN_MAP_SYNTAX,
         "map.csv:2: line: expected 6 fields"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        hv_fruitmap_t map = {99, (hv_fruit_t *)&map};
        char err[256] = "";
        hv_status_t st = parse(cases[i].text, &map, err, sizeof err);
        if (st != cases[i].code || strstr(err, cases[i].in_msg) == NULL) {
            print_error("case %zu: got %s \"%s\", want %s containing \"%s\"\n", i,
                        hv_plan_status_name(st), err, hv_plan_status_name(cases[i].code),
                        cases[i].in_msg);
            fail();
        }
        assert_int_equal(map.n, 0); /* nothing kept on error */
        assert_null(map.fruits);
        assert_null(strchr(err, '\n')); /* one line */
    }
}

static void test_missing_file(void **state)
{
    (void)state;
    hv_fruitmap_t map;
    char err[256] = "";
    assert_int_equal(hv_fruitmap_load("/nonexistent/map.csv", &g_lim, &map, err, sizeof err),
                     HV_ERR_IO);
    assert_non_null(strstr(err, "/nonexistent/map.csv"));
}

/* Numbers that print differently at fewer digits (0.1, 1/3, a long fraction) read back as
 * the same doubles: a saved map is the same instance when it is loaded again. */
static void test_save_reads_back_exactly(void **state)
{
    (void)state;
    hv_fruit_t fr[3];
    memset(fr, 0, sizeof fr);
    const double v[3][4] = {{-0.4, 0.1, 0.6, 0.1},
                            {0.45, 1.0 / 3.0, 0.55, -0.2},
                            {0.4123456789012345, 1.9999999999999998, 0.7, -0.7853981633974483}};
    for (int i = 0; i < 3; ++i) {
        snprintf(fr[i].id, sizeof fr[i].id, i == 2 ? "R_0.long-id-%d" : "L%d", i);
        fr[i].side = i == 0 ? HV_SIDE_LEFT : HV_SIDE_RIGHT;
        fr[i].x_m = v[i][0];
        fr[i].y_m = v[i][1];
        fr[i].z_m = v[i][2];
        fr[i].yaw_rad = v[i][3];
    }
    char dir[] = "/tmp/hv_test_fruit_map_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[256];
    snprintf(path, sizeof path, "%s/map.csv", dir);
    char err[256] = "";
    assert_int_equal(hv_fruitmap_save(path, fr, 3, err, sizeof err), HV_OK);
    hv_fruitmap_t map;
    assert_int_equal(hv_fruitmap_load(path, &g_lim, &map, err, sizeof err), HV_OK);
    assert_int_equal(map.n, 3);
    for (int i = 0; i < 3; ++i) {
        const hv_fruit_t *a = &fr[i], *b = &map.fruits[i];
        assert_string_equal(a->id, b->id);
        assert_int_equal(a->side, b->side);
        assert_true(a->x_m == b->x_m && a->y_m == b->y_m);
        assert_true(a->z_m == b->z_m && a->yaw_rad == b->yaw_rad);
    }
    hv_fruitmap_free(&map);
    /* a folder that is not there: refused, naming the file */
    char bad[300];
    snprintf(bad, sizeof bad, "%s/none/map.csv", dir);
    assert_int_equal(hv_fruitmap_save(bad, fr, 3, err, sizeof err), HV_ERR_IO);
    assert_non_null(strstr(err, bad));
    unlink(path);
    rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_good_map),
        cmocka_unit_test(test_bad_maps),
        cmocka_unit_test(test_missing_file),
        cmocka_unit_test(test_save_reads_back_exactly),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
