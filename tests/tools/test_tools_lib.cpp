// Unit tests of the tools library (hv_tools): cell values, thread-independence of the
// table, the mount search's cross-section shortcut, the best-pose selection, JSON and
// argument parsing. The configuration is the project's own, made coarse in memory.
#include <cmath>
#include <cstdarg>
#include <cstddef>
#include <csetjmp>
#include <cstdint>
#include <string>
#include <vector>

#include "cli_args.hpp"
#include "cost_table_builder.hpp"
#include "fpa_grid.hpp"
#include "json_writer.hpp"
#include "mount_search.hpp"
#include "tool_config.hpp"

// cmocka last: it defines macros (fail, ...) that clash with the C++ library headers.
extern "C" {
#include <cmocka.h>
}

using namespace hv::tools;

namespace
{

constexpr double kDeg = 3.14159265358979323846 / 180.0;

hv_config_t coarse_config()
{
    hv_config_t cfg = load_config(HV_TEST_CONFIG);
    cfg.grid_step_m = 0.05;
    cfg.grid_yaw_step_rad = 15.0 * kDeg;
    cfg.grid_y_half_span_m = 0.6;
    cfg.search_offset_step_m = 0.05;
    cfg.search_theta_step_rad = 30.0 * kDeg;
    return cfg;
}

void cell_values_follow_pick_cost(void **)
{
    hv_config_t cfg = load_config(HV_TEST_CONFIG);
    hv_arm_t arm;
    hv_config_arm(&cfg, HV_SIDE_RIGHT, &arm);
    bool clamped = true;
    // The end effector at the home pose costs nothing.
    hv_pose_t home;
    assert_int_equal(hv_scara_fk(&arm, arm.home, &home), HV_OK);
    assert_int_equal(cell_cost_ms(arm, home, &clamped), 0);
    assert_false(clamped);
    // A pose far outside the workspace is unreachable.
    hv_pose_t far = {5.0, 0.0, 0.6, 0.0};
    assert_int_equal(cell_cost_ms(arm, far, &clamped), HV_COST_UNREACHABLE);
    // A reachable pose: round(G in ms).
    double q[HV_NJOINTS] = {0.1, 0.3, 1.0, -0.4};
    hv_pose_t p;
    assert_int_equal(hv_scara_fk(&arm, q, &p), HV_OK);
    double g = 0.0;
    assert_int_equal(hv_scara_pick_cost(&arm, &p, &g, nullptr), HV_OK);
    assert_int_equal(cell_cost_ms(arm, p, &clamped), static_cast<int>(std::lround(g * 1000.0)));
    assert_true(g > 0.5);
    // Joint speeds so slow that G exceeds the 16-bit range: clamped and flagged.
    hv_arm_t slow = arm;
    for (auto &l : slow.limit) {
        l.vmax = 1e-4;
        l.amax = 1e-4;
    }
    assert_int_equal(cell_cost_ms(slow, p, &clamped), HV_COST_MAX_MS);
    assert_true(clamped);
    // NaN is an input bug, not "unreachable".
    hv_pose_t nan_pose = {std::nan(""), 0.0, 0.6, 0.0};
    bool threw = false;
    try {
        cell_cost_ms(arm, nan_pose, &clamped);
    } catch (const std::runtime_error &) {
        threw = true;
    }
    assert_true(threw);
}

void table_independent_of_threads(void **)
{
    hv_config_t cfg = coarse_config();
    for (hv_side_t side : {HV_SIDE_LEFT, HV_SIDE_RIGHT}) {
        hv_arm_t arm;
        hv_grid_t grid;
        hv_config_arm(&cfg, side, &arm);
        hv_config_grid(&cfg, side, &grid);
        CostTable one = build_cost_table(arm, grid, 1, nullptr);
        CostTable two = build_cost_table(arm, grid, 3, nullptr);
        assert_int_equal(one.costs_ms.size(), hv_grid_cells(&grid));
        assert_true(one.costs_ms == two.costs_ms);
        assert_int_equal(one.reachable, two.reachable);
        assert_true(one.reachable > 0 && one.reachable < one.costs_ms.size());
        // Spot cells against the direct computation, by payload index.
        for (std::uint32_t ix = 0; ix < grid.axis[HV_AX_X].count; ix += 2) {
            for (std::uint32_t iz = 0; iz < grid.axis[HV_AX_Z].count; iz += 3) {
                std::uint32_t iy = grid.axis[HV_AX_Y].count / 2, iyaw = 1;
                bool c = false;
                std::uint16_t want = cell_cost_ms(arm, cell_pose(grid, side, ix, iy, iz, iyaw), &c);
                assert_int_equal(one.costs_ms[cell_index(grid, ix, iy, iz, iyaw)], want);
            }
        }
        // The file image opens with the core loader and holds the same cells.
        std::vector<std::uint8_t> img = serialise_cost_table(one);
        hv_costtab_t tab;
        hv_diag_t d{};
        assert_int_equal(hv_costtab_open(&tab, img.data(), img.size(), &d), HV_OK);
        assert_int_equal(hv_costtab_expect(&tab, side, &grid, &d), HV_OK);
        assert_int_equal(hv_costtab_cell(&tab, 1, 3, 2, 0),
                         one.costs_ms[cell_index(grid, 1, 3, 2, 0)]);
    }
}

void cross_section_equals_full_z(void **)
{
    hv_config_t cfg = coarse_config();
    // A lower canopy so some z levels fall outside joint 1's stroke (z >= 0.34 m).
    cfg.canopy_z_min_m = 0.2;
    for (hv_side_t side : {HV_SIDE_LEFT, HV_SIDE_RIGHT}) {
        FpaGrid fpa = make_fpa_grid(cfg, side);
        assert_true(fpa.y_half_window_m >= planar_reach_m(cfg));
        for (double d : {0.1, 0.2, 0.3}) {
            for (double th : {-60.0, 0.0, 45.0}) {
                EvalOptions fast, full;
                fast.suction = full.suction = true;
                full.full_z = true;
                Coverage a = evaluate_pose(cfg, fpa, d, th * kDeg, fast);
                Coverage b = evaluate_pose(cfg, fpa, d, th * kDeg, full);
                assert_int_equal(a.points, b.points);
                assert_int_equal(a.stem_positions, b.stem_positions);
                assert_int_equal(a.any_yaw_positions, b.any_yaw_positions);
                assert_int_equal(a.yaw0_positions, b.yaw0_positions);
                assert_int_equal(a.suction_positions, b.suction_positions);
                // Mode ordering: all yaws <= some yaw <= any heading; yaw 0 <= some yaw.
                assert_true(b.stem_positions <= b.any_yaw_positions);
                assert_true(b.any_yaw_positions <= b.suction_positions);
                assert_true(b.yaw0_positions <= b.any_yaw_positions);
                assert_true(b.points <= b.any_yaw_positions * fpa.yaw.size());
            }
        }
    }
}

void some_pose_covers_something(void **)
{
    hv_config_t cfg = coarse_config();
    FpaGrid fpa = make_fpa_grid(cfg, HV_SIDE_RIGHT);
    Coverage c = evaluate_pose(cfg, fpa, cfg.offset_m, cfg.theta_rad[1], EvalOptions{});
    assert_true(c.points > 0);
    assert_int_equal(c.suction_positions, -1); // not asked for
    // Base moved 2 m away from the canopy: nothing reachable.
    Coverage none = evaluate_pose(cfg, fpa, -2.0, 0.0, EvalOptions{});
    assert_int_equal(none.points, 0);
    assert_int_equal(none.any_yaw_positions, 0);
}

void best_pose_is_the_maximum(void **)
{
    SweepAxes axes;
    axes.offset_m = Eigen::ArrayXd::LinSpaced(3, 0.1, 0.3);
    axes.theta_rad = Eigen::ArrayXd::LinSpaced(4, -1.0, 1.0);
    // Hand-made coverages: at D index 1 the left side peaks at theta 2, the right at
    // theta 0 and 3 (tie: the smaller theta wins); D index 2 ties D index 1 in total.
    const std::int64_t left[3][4] = {{1, 2, 3, 4}, {5, 6, 9, 1}, {9, 5, 5, 5}};
    const std::int64_t right[3][4] = {{1, 1, 1, 1}, {7, 2, 3, 7}, {7, 6, 0, 0}};
    std::vector<SideSweep> sw(2);
    sw[0].side = HV_SIDE_LEFT;
    sw[1].side = HV_SIDE_RIGHT;
    for (int d = 0; d < 3; d++) {
        for (int t = 0; t < 4; t++) {
            Coverage l, r;
            l.points = left[d][t];
            r.points = right[d][t];
            l.stem_positions = 10 - left[d][t];
            r.stem_positions = 10 - right[d][t];
            sw[0].cov.push_back(l);
            sw[1].cov.push_back(r);
        }
    }
    BestPose b = best_pose(sw, axes, Objective::Points);
    assert_int_equal(b.objective, 16);
    assert_int_equal(b.i_offset, 1);
    assert_int_equal(b.i_theta[0], 2);
    assert_int_equal(b.i_theta[1], 0);
    assert_true(std::fabs(b.offset_m - 0.2) < 1e-12);
    // Exhaustive: no (D, theta_L, theta_R) beats it.
    for (int d = 0; d < 3; d++) {
        for (int tl = 0; tl < 4; tl++) {
            for (int tr = 0; tr < 4; tr++) {
                assert_true(left[d][tl] + right[d][tr] <= b.objective);
            }
        }
    }
    BestPose s = best_pose(sw, axes, Objective::Stem);
    assert_int_equal(s.objective, 9 + 9);
    assert_int_equal(s.i_offset, 0);
    assert_int_equal(s.i_theta[0], 0);
}

void sweep_axes_include_endpoints(void **)
{
    hv_config_t cfg = load_config(HV_TEST_CONFIG);
    SweepAxes a = make_sweep_axes(cfg);
    assert_int_equal(a.offset_m.size(), 26);  // 0.10 .. 0.35 by 0.01
    assert_int_equal(a.theta_rad.size(), 37); // -90 .. 90 by 5 deg
    assert_true(std::fabs(a.offset_m[25] - 0.35) < 1e-9);
    assert_true(std::fabs(a.theta_rad[36] - 90.0 * kDeg) < 1e-9);
}

void json_and_args(void **)
{
    JsonWriter j;
    j.begin_object()
        .key("a\"b")
        .value(std::int64_t{3})
        .key("l")
        .begin_array()
        .value(1.5)
        .value("x\n")
        .value(std::nan(""))
        .end_array()
        .end_object();
    assert_string_equal(j.str().c_str(), "{\"a\\\"b\":3,\"l\":[1.5,\"x\\u000a\",null]}");

    char a0[] = "t", a1[] = "--threads=0", a2[] = "--offset", a3[] = "abc";
    char *argv[] = {a0, a1, a2, a3};
    ArgReader r(4, argv);
    assert_string_equal(r.next_option().c_str(), "--threads");
    bool threw = false;
    try {
        r.value_long(1, 64);
    } catch (const UsageError &e) {
        threw = std::string(e.what()).find("--threads") != std::string::npos;
    }
    assert_true(threw);
    assert_string_equal(r.next_option().c_str(), "--offset");
    threw = false;
    try {
        r.value_double();
    } catch (const UsageError &e) {
        threw = std::string(e.what()).find("--offset: 'abc'") != std::string::npos;
    }
    assert_true(threw);
    threw = false;
    try {
        parse_sides("--side", "up");
    } catch (const UsageError &) {
        threw = true;
    }
    assert_true(threw);
}

void bad_config_names_file_and_key(void **)
{
    bool threw = false;
    try {
        load_config("/nonexistent/harvest.cfg");
    } catch (const InputError &e) {
        threw = std::string(e.what()).find("/nonexistent/harvest.cfg: ") == 0;
    }
    assert_true(threw);
}

} // namespace

int main()
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(cell_values_follow_pick_cost),
        cmocka_unit_test(table_independent_of_threads),
        cmocka_unit_test(cross_section_equals_full_z),
        cmocka_unit_test(some_pose_covers_something),
        cmocka_unit_test(best_pose_is_the_maximum),
        cmocka_unit_test(sweep_axes_include_endpoints),
        cmocka_unit_test(json_and_args),
        cmocka_unit_test(bad_config_names_file_and_key),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
