// costgen: build the pick-cost table of one or both arms from the harvest configuration
// and write it in the file format of DESIGN §4 (core/include/hv/cost_table.h).
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <random>
#include <string>
#include <vector>

#include "cli_args.hpp"
#include "cost_table_builder.hpp"
#include "hv/exit_codes.h"
#include "hv/file_io.h"
#include "hv/version.h"
#include "progress.hpp"
#include "tool_config.hpp"

namespace
{

using namespace hv::tools;

const char kUsage[] =
    "usage: costgen [options]\n"
    "Build the pick-cost table G(x, y, z, yaw) of each arm from the configuration: every\n"
    "cell is the slowest joint's time (ms) from the home pose to the IK solution of the\n"
    "cell's pose, or 'unreachable'. Prints cells, reachable fraction, bytes and time.\n"
    "\n"
    "  --config FILE     configuration (default: %s)\n"
    "  --side S          left | right | both (default: both)\n"
    "  --out-dir DIR     write DIR/costtab_left.bin and/or DIR/costtab_right.bin (default: .)\n"
    "  --out FILE        output file; only with --side left or --side right\n"
    "  --elbow-free      lift the elbow limit (arm.elbow_free = 1): joint 3 in [-max, max],\n"
    "                    both IK solutions considered (the paper's comparison)\n"
    "  --offset M        override mount.offset (the paper's D, m)\n"
    "  --theta-deg DEG   override mount.theta_left_deg and mount.theta_right_deg\n"
    "  --threads N       worker threads (default: 2)\n"
    "  --check N         after writing, reload the file and compare N random cells\n"
    "                    (looked up by pose) with a direct IK + timing computation\n"
    "  --seed S          seed of --check's random cells (default: 1)\n"
    "  --quiet           no progress line\n"
    "  --help            this text\n"
    "  --version         the version and exit\n"
    "\n" HV_EXIT_CODES_HELP ")\n";

struct Options {
    std::string config = default_config_path();
    std::vector<hv_side_t> sides = {HV_SIDE_LEFT, HV_SIDE_RIGHT};
    std::string out_dir = ".";
    std::string out;
    bool elbow_free = false;
    bool has_offset = false, has_theta = false;
    double offset_m = 0.0, theta_deg = 0.0;
    unsigned threads = 2;
    long check = 0;
    unsigned long long seed = 1;
    bool quiet = false;
};

Options parse(int argc, char **argv, bool *help)
{
    Options o;
    ArgReader r(argc, argv);
    while (!r.done()) {
        std::string opt = r.next_option();
        if (opt == "--help" || opt == "-h") {
            *help = true;
            return o;
        } else if (opt == "--version") {
            std::printf("%s %s\n", "costgen", HV_VERSION);
            std::exit(0);
        } else if (opt == "--config") {
            o.config = r.value();
        } else if (opt == "--side") {
            o.sides = parse_sides(opt, r.value());
        } else if (opt == "--out-dir") {
            o.out_dir = r.value();
        } else if (opt == "--out") {
            o.out = r.value();
        } else if (opt == "--elbow-free") {
            o.elbow_free = true;
        } else if (opt == "--offset") {
            o.offset_m = r.value_double();
            o.has_offset = true;
            if (o.offset_m < 0.0 || o.offset_m > 2.0) {
                throw UsageError("--offset: must be in [0, 2] m");
            }
        } else if (opt == "--theta-deg") {
            o.theta_deg = r.value_double();
            o.has_theta = true;
            if (o.theta_deg < -180.0 || o.theta_deg > 180.0) {
                throw UsageError("--theta-deg: must be in [-180, 180] deg");
            }
        } else if (opt == "--threads") {
            o.threads = static_cast<unsigned>(r.value_long(1, 64));
        } else if (opt == "--check") {
            o.check = r.value_long(0, 100000000);
        } else if (opt == "--seed") {
            o.seed = static_cast<unsigned long long>(r.value_long(0, 0x7fffffffL));
        } else if (opt == "--quiet") {
            o.quiet = true;
        } else {
            throw UsageError(opt + ": unknown option (see --help)");
        }
    }
    if (!o.out.empty() && o.sides.size() != 1) {
        throw UsageError("--out: needs --side left or --side right");
    }
    return o;
}

std::string out_path(const Options &o, hv_side_t side)
{
    if (!o.out.empty()) {
        return o.out;
    }
    return o.out_dir + "/costtab_" + side_name(side) + ".bin";
}

// Reload the written file and compare `n` random cells, looked up by pose through the
// loader's own lookup, with the direct computation. Returns the number of mismatches.
long check_file(const std::string &path, const CostTable &t, long n, unsigned long long seed)
{
    hv_costtab_file_t f;
    char err[512] = {0};
    if (hv_costtab_load(path.c_str(), &f, err, sizeof err) != HV_OK) {
        std::fprintf(stderr, "costgen: %s\n", err);
        return n > 0 ? n : 1;
    }
    hv_diag_t diag{};
    long bad = 0;
    if (hv_costtab_expect(&f.tab, t.arm.side, &t.grid, &diag) != HV_OK) {
        std::fprintf(stderr, "costgen: %s: %s: %s\n", path.c_str(), diag.field, diag.message);
        bad = 1;
    }
    std::mt19937_64 rng(seed);
    const hv_axis_t *a = t.grid.axis;
    auto pick = [&rng](std::uint32_t count) { return static_cast<std::uint32_t>(rng() % count); };
    for (long i = 0; i < n && bad == 0; i++) {
        std::uint32_t ix = pick(a[HV_AX_X].count), iy = pick(a[HV_AX_Y].count);
        std::uint32_t iz = pick(a[HV_AX_Z].count), iyaw = pick(a[HV_AX_YAW].count);
        hv_pose_t p = cell_pose(t.grid, t.arm.side, ix, iy, iz, iyaw);
        bool clamped = false;
        std::uint16_t want = cell_cost_ms(t.arm, p, &clamped);
        std::uint16_t got = HV_COST_UNREACHABLE;
        double yaw = axis_value(a[HV_AX_YAW], iyaw);
        hv_status_t st = hv_costtab_lookup(&f.tab, p.x_m, p.y_m, p.z_m, yaw, &got);
        if (st == HV_ERR_UNREACHABLE) {
            got = HV_COST_UNREACHABLE;
        } else if (st != HV_OK) {
            std::fprintf(stderr, "costgen: %s: lookup of cell (%u,%u,%u,%u) failed: %s\n",
                         path.c_str(), ix, iy, iz, iyaw, hv_status_name(st));
            bad++;
            continue;
        }
        if (got != want) {
            std::fprintf(stderr,
                         "costgen: %s: cell (%u,%u,%u,%u) holds %u, direct computation %u\n",
                         path.c_str(), ix, iy, iz, iyaw, got, want);
            bad++;
        }
    }
    hv_costtab_unload(&f);
    return bad;
}

int run(const Options &o)
{
    hv_config_t cfg = load_config(o.config);
    if (o.elbow_free) {
        cfg.elbow_free = 1;
    }
    if (o.has_offset) {
        cfg.offset_m = o.offset_m;
    }
    if (o.has_theta) {
        cfg.theta_rad[0] = cfg.theta_rad[1] = o.theta_deg * 3.14159265358979323846 / 180.0;
    }
    std::printf("costgen: config %s, elbow %s, D = %.3f m, theta L/R = %.2f/%.2f deg, "
                "%u thread(s)\n",
                o.config.c_str(), cfg.elbow_free ? "free" : "one-sided", cfg.offset_m,
                cfg.theta_rad[0] * 180.0 / 3.14159265358979323846,
                cfg.theta_rad[1] * 180.0 / 3.14159265358979323846, o.threads);
    int status = HV_EXIT_OK;
    auto fail = [&status](int code) { // the first side's problem gives the exit code
        status = status == HV_EXIT_OK ? code : status;
    };
    for (hv_side_t side : o.sides) {
        hv_arm_t arm;
        hv_grid_t grid;
        hv_config_arm(&cfg, side, &arm);
        hv_config_grid(&cfg, side, &grid);
        hv_diag_t diag{};
        if (hv_grid_check(&grid, &diag) != HV_OK) {
            throw InputError(o.config + ": grid (from grid.step, grid.yaw_step_deg, row.*): " +
                             diag.field + ": " + diag.message);
        }
        std::string path = out_path(o, side);
        auto t0 = std::chrono::steady_clock::now();
        Progress progress(std::string("costgen: ") + side_name(side), hv_grid_cells(&grid),
                          o.quiet);
        CostTable t = build_cost_table(arm, grid, o.threads, &progress);
        std::vector<std::uint8_t> image = serialise_cost_table(t);
        double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::size_t cells = t.costs_ms.size();
        if (t.reachable == 0) {
            std::fprintf(stderr,
                         "costgen: %s: no cell of the %s arm's table is reachable "
                         "(mount.offset / mount.theta_*_deg / row.*?): nothing written\n",
                         o.config.c_str(), side_name(side));
            fail(HV_EXIT_USAGE); // the configuration (or an override) is at fault
            continue;
        }
        if (t.clamped > 0) {
            std::fprintf(stderr,
                         "costgen: warning: %zu cell(s) of the %s arm cost more than "
                         "%u ms and were clamped to it\n",
                         t.clamped, side_name(side), static_cast<unsigned>(HV_COST_MAX_MS));
        }
        char err[512] = {0};
        if (hv_file_write_atomic(path.c_str(), image.data(), image.size(), err, sizeof err) !=
            HV_OK) {
            std::fprintf(stderr, "costgen: %s\n", err);
            fail(HV_EXIT_FAILURE);
            continue;
        }
        const hv_axis_t *a = grid.axis;
        std::printf("costgen: %s arm -> %s: %zu cells (x %u, y %u, z %u, yaw %u), "
                    "reachable %zu (%.2f %%), %zu bytes, %.2f s\n",
                    side_name(side), path.c_str(), cells, a[HV_AX_X].count, a[HV_AX_Y].count,
                    a[HV_AX_Z].count, a[HV_AX_YAW].count, t.reachable,
                    100.0 * static_cast<double>(t.reachable) / static_cast<double>(cells),
                    image.size(), secs);
        if (o.check > 0) {
            long bad = check_file(path, t, o.check, o.seed);
            if (bad > 0) {
                std::fprintf(stderr, "costgen: %s: --check: %ld of %ld cells disagree\n",
                             path.c_str(), bad, o.check);
                fail(HV_EXIT_FAILURE);
            } else {
                std::printf("costgen: %s: --check: %ld random cells agree with direct "
                            "IK + timing\n",
                            path.c_str(), o.check);
            }
        }
        std::fflush(stdout);
    }
    return status;
}

} // namespace

int main(int argc, char **argv)
{
    bool help = false;
    Options o;
    try {
        o = parse(argc, argv, &help);
        if (help) {
            std::printf(kUsage, default_config_path().c_str());
            return HV_EXIT_OK;
        }
        return run(o);
    } catch (const UsageError &e) { // and InputError
        std::fprintf(stderr, "costgen: %s\n", e.what());
        return HV_EXIT_USAGE;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "costgen: %s\n", e.what());
        return HV_EXIT_FAILURE;
    }
}
