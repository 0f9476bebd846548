// bench_costtab: cost-table figures at the configured grid (the paper's 0.01 m):
// generation time and size, and the time per query of a table lookup against the direct
// computation it replaces (IK + trapezoid timing, hv_scara_pick_cost), both measured in
// this run over the same random poses. Prints figures; asserts nothing about time.
#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "cost_table_builder.hpp"
#include "hv/config.h"
#include "hv/file_io.h"
#include "tool_config.hpp"

namespace
{

using Clock = std::chrono::steady_clock;
using namespace hv::tools;

double seconds_since(Clock::time_point t0)
{
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Best of `reps` runs of f(), in seconds: the machine is shared, the minimum is the least
// disturbed figure.
template <typename F> double best_of(int reps, F f)
{
    double best = 1e300;
    for (int i = 0; i < reps; i++) {
        auto t0 = Clock::now();
        f();
        best = std::min(best, seconds_since(t0));
    }
    return best;
}

const char kUsage[] =
    "usage: bench_costtab [--config FILE] [--queries N] [--side left|right]\n"
    "Generate one arm's cost table at the configured grid (1 and 2 threads), then time\n"
    "N lookups (default 1000000) and N direct IK + timing computations over the same\n"
    "random poses (cell centres, so both must agree), best of 3 runs each.\n";

} // namespace

int main(int argc, char **argv)
{
    std::string config = "config/harvest.cfg";
    long queries = 1000000;
    hv_side_t side = HV_SIDE_RIGHT;
    for (int i = 1; i < argc; i++) {
        std::string a = argv[i];
        if (a == "--help") {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (a == "--config" && i + 1 < argc) {
            config = argv[++i];
        } else if (a == "--queries" && i + 1 < argc) {
            queries = std::atol(argv[++i]);
            if (queries < 1) {
                std::fprintf(stderr, "bench_costtab: --queries: must be >= 1\n");
                return 2;
            }
        } else if (a == "--side" && i + 1 < argc) {
            std::vector<hv_side_t> s = parse_sides("--side", argv[++i]);
            if (s.size() != 1) {
                std::fprintf(stderr, "bench_costtab: --side: left or right\n");
                return 2;
            }
            side = s[0];
        } else {
            std::fprintf(stderr, "bench_costtab: unknown argument '%s' (see --help)\n", a.c_str());
            return 2;
        }
    }
    hv_config_t cfg;
    try {
        cfg = load_config(config);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
    hv_arm_t arm;
    hv_grid_t grid;
    hv_config_arm(&cfg, side, &arm);
    hv_config_grid(&cfg, side, &grid);
    const hv_axis_t *ax = grid.axis;

    // 1. Generation.
    CostTable table;
    double gen1 = best_of(1, [&] { table = build_cost_table(arm, grid, 1, nullptr); });
    double gen2 = best_of(1, [&] { table = build_cost_table(arm, grid, 2, nullptr); });
    std::vector<std::uint8_t> image;
    double ser = best_of(1, [&] { image = serialise_cost_table(table); });
    std::printf("bench_costtab: config %s, %s arm, grid step %.3f m, yaw step %.1f deg\n",
                config.c_str(), side == HV_SIDE_LEFT ? "left" : "right", cfg.grid_step_m,
                cfg.grid_yaw_step_rad * 180.0 / 3.14159265358979323846);
    std::printf("generate: %zu cells (x %u, y %u, z %u, yaw %u), reachable %.2f %%, "
                "%zu bytes (%.2f MiB)\n",
                table.costs_ms.size(), ax[HV_AX_X].count, ax[HV_AX_Y].count, ax[HV_AX_Z].count,
                ax[HV_AX_YAW].count,
                100.0 * static_cast<double>(table.reachable) /
                    static_cast<double>(table.costs_ms.size()),
                image.size(), static_cast<double>(image.size()) / 1048576.0);
    std::printf("generate: %.3f s with 1 thread, %.3f s with 2 threads (%.0f ns/cell), "
                "serialise + CRC %.3f s\n",
                gen1, gen2, 1e9 * gen1 / static_cast<double>(table.costs_ms.size()), ser);

    hv_costtab_t tab;
    hv_diag_t diag{};
    if (hv_costtab_open(&tab, image.data(), image.size(), &diag) != HV_OK) {
        std::fprintf(stderr, "bench_costtab: table does not open: %s: %s\n", diag.field,
                     diag.message);
        return 1;
    }

    // 2. The same random poses for both: cell centres (table yaw relative to the normal).
    std::mt19937_64 rng(42);
    struct Q {
        double x, y, z, yaw;
    };
    std::vector<Q> qs(static_cast<std::size_t>(queries));
    for (Q &q : qs) {
        q.x = axis_value(ax[HV_AX_X], static_cast<std::uint32_t>(rng() % ax[HV_AX_X].count));
        q.y = axis_value(ax[HV_AX_Y], static_cast<std::uint32_t>(rng() % ax[HV_AX_Y].count));
        q.z = axis_value(ax[HV_AX_Z], static_cast<std::uint32_t>(rng() % ax[HV_AX_Z].count));
        q.yaw = axis_value(ax[HV_AX_YAW], static_cast<std::uint32_t>(rng() % ax[HV_AX_YAW].count));
    }
    const double normal = hv_side_normal_heading(side);

    // Both loops fold every result into a checksum that is printed, so neither can be
    // optimised away; lookup misses count as the sentinel in both.
    std::uint64_t sum_lookup = 0, sum_direct = 0;
    double t_lookup = best_of(3, [&] {
        std::uint64_t s = 0;
        for (const Q &q : qs) {
            std::uint16_t c = HV_COST_UNREACHABLE;
            if (hv_costtab_lookup(&tab, q.x, q.y, q.z, q.yaw, &c) != HV_OK) {
                c = HV_COST_UNREACHABLE;
            }
            s += c;
        }
        sum_lookup = s;
    });
    double t_direct = best_of(3, [&] {
        std::uint64_t s = 0;
        for (const Q &q : qs) {
            hv_pose_t p{q.x, q.y, q.z, normal + q.yaw};
            double g = 0.0;
            std::uint16_t c = HV_COST_UNREACHABLE;
            if (hv_scara_pick_cost(&arm, &p, &g, nullptr) == HV_OK) {
                c = static_cast<std::uint16_t>(std::lround(g * 1000.0));
            }
            s += c;
        }
        sum_direct = s;
    });
    // The same poses in payload order: separates the lookup's arithmetic from the cache
    // misses of random access into a table larger than L2.
    std::vector<Q> sorted = qs;
    std::sort(sorted.begin(), sorted.end(), [](const Q &a, const Q &b) {
        return std::tie(a.x, a.z, a.yaw, a.y) < std::tie(b.x, b.z, b.yaw, b.y);
    });
    std::uint64_t sum_sorted = 0;
    double t_sorted = best_of(3, [&] {
        std::uint64_t s = 0;
        for (const Q &q : sorted) {
            std::uint16_t c = HV_COST_UNREACHABLE;
            if (hv_costtab_lookup(&tab, q.x, q.y, q.z, q.yaw, &c) != HV_OK) {
                c = HV_COST_UNREACHABLE;
            }
            s += c;
        }
        sum_sorted = s;
    });
    // The planner's hot loop: one fruit, every stop = one contiguous y-row.
    std::uint64_t sum_row = 0;
    std::size_t row_cells = 0;
    double t_row = best_of(3, [&] {
        std::uint64_t s = 0;
        std::size_t n = 0;
        for (const Q &q : qs) {
            const std::uint8_t *row = nullptr;
            if (hv_costtab_row(&tab, q.x, q.z, q.yaw, &row) == HV_OK) {
                for (std::uint32_t iy = 0; iy < ax[HV_AX_Y].count; iy++) {
                    s += hv_costtab_row_at(row, iy);
                }
                n += ax[HV_AX_Y].count;
            }
        }
        sum_row = s;
        row_cells = n;
    });
    double n = static_cast<double>(queries);
    std::printf("query: %ld random cell-centre poses, best of 3\n", queries);
    std::printf("  table lookup (hv_costtab_lookup)     %8.1f ns/query\n", 1e9 * t_lookup / n);
    std::printf("  table lookup, poses in table order   %8.1f ns/query\n", 1e9 * t_sorted / n);
    std::printf("  direct IK + timing (baseline)        %8.1f ns/query\n", 1e9 * t_direct / n);
    std::printf("  lookup speed-up over direct          %8.1f x\n", t_direct / t_lookup);
    std::printf("  row scan (hv_costtab_row, %u stops)  %8.2f ns/cell\n", ax[HV_AX_Y].count,
                1e9 * t_row / static_cast<double>(row_cells));
    std::printf("checksums: lookup %" PRIu64 ", direct %" PRIu64 " (%s), rows %" PRIu64 "\n",
                sum_lookup, sum_direct,
                sum_lookup == sum_direct && sum_sorted == sum_lookup ? "agree" : "DISAGREE",
                sum_row);

    // 3. Why the planner does not plan from the table: at poses between cell centres (as
    // fruit are) the nearest cell and the exact IK disagree near the workspace's edge.
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    auto span = [&](int a) {
        return axis_value(ax[a], 0) +
               unit(rng) * (axis_value(ax[a], ax[a].count - 1) - axis_value(ax[a], 0));
    };
    long table_only = 0, ik_only = 0, both = 0;
    double dg_max = 0.0;
    for (long i = 0; i < queries; i++) {
        double x = span(HV_AX_X), y = span(HV_AX_Y), z = span(HV_AX_Z), yaw = span(HV_AX_YAW);
        std::uint16_t c = 0;
        bool by_table = hv_costtab_lookup(&tab, x, y, z, yaw, &c) == HV_OK;
        hv_pose_t p{x, y, z, normal + yaw};
        double g = 0.0;
        bool by_ik = hv_scara_pick_cost(&arm, &p, &g, nullptr) == HV_OK;
        table_only += by_table && !by_ik;
        ik_only += by_ik && !by_table;
        if (by_table && by_ik) {
            both++;
            dg_max = std::max(dg_max, std::fabs(g - c / 1000.0));
        }
    }
    std::printf("agreement: %ld uniform poses between the cells: the table says reachable and "
                "the IK refuses %ld (%.3f %%), the other way %ld (%.3f %%); G differs by up "
                "to %.3f s over the %ld both reach\n",
                queries, table_only, 100.0 * static_cast<double>(table_only) / n, ik_only,
                100.0 * static_cast<double>(ik_only) / n, dg_max, both);
    return sum_lookup == sum_direct && sum_sorted == sum_lookup ? 0 : 1;
}
