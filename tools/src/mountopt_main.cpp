// mountopt: the installation-pose search of paper §III.C. Sweeps the base offset D and the
// rotations theta_L, theta_R over the configured search range, counts the reachable points
// of the fruit-planted area, and reports the best pose beside the paper's (D = 0.26 m,
// 43.5 deg). See tools/README.md for the model and how our result compares.
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "cli_args.hpp"
#include "fpa_grid.hpp"
#include "hv/exit_codes.h"
#include "hv/file_io.h"
#include "hv/version.h"
#include "json_writer.hpp"
#include "mount_search.hpp"
#include "progress.hpp"
#include "tool_config.hpp"

namespace
{

using namespace hv::tools;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
// The paper's result (§IV.B): offset 0.26 m, rotation 43.5 deg.
constexpr double kPaperOffsetM = 0.26;
constexpr double kPaperThetaDeg = 43.5;

// Metres for the JSON summary, rounded to 1e-12 m (0.29, not 0.29000000000000004).
double json_m(double m)
{
    return std::round(m * 1e12) / 1e12;
}

// Degrees for the JSON summary, rounded to 1e-9 so 40 deg reads 40, not 40.00000000000001.
double json_deg(double rad)
{
    return std::round(rad / kDeg * 1e9) / 1e9;
}

const char kUsage[] =
    "usage: mountopt [options]\n"
    "Search the arms' installation pose (paper §III.C): for every base offset D in\n"
    "[search.offset_min, search.offset_max] and rotation theta in [search.theta_min_deg,\n"
    "search.theta_max_deg] (configured steps), count the fruit-planted-area points\n"
    "(x, y, z, yaw) the arm reaches within its joint limits; report the best pose, its\n"
    "coverage in each pick mode, and the paper's pose (D = 0.26 m, 43.5 deg) under our model.\n"
    "\n"
    "  --config FILE       configuration (default: %s)\n"
    "  --side S            left | right | both (default: both)\n"
    "  --objective O       what the search maximises (default: points):\n"
    "                        points   reachable (x, y, z, yaw) points, yaw on the stem-\n"
    "                                 cutting grid (the paper's objective)\n"
    "                        stem     positions reachable with EVERY yaw of the range\n"
    "                        suction  positions reachable with any heading (bottom suction)\n"
    "  --elbow-free        lift the elbow limit (arm.elbow_free = 1)\n"
    "  --full-z            run the IK at every z level instead of once per cross-section\n"
    "                      (same counts, slower; a check of the cylinder argument)\n"
    "  --threads N         worker threads (default: 2)\n"
    "  --json FILE         write a machine-readable summary with every candidate\n"
    "  --quiet             no progress line\n"
    "  --help              this text\n"
    "  --version           the version and exit\n"
    "\n" HV_EXIT_CODES_HELP ")\n";

struct Options {
    std::string config = default_config_path();
    std::vector<hv_side_t> sides = {HV_SIDE_LEFT, HV_SIDE_RIGHT};
    Objective objective = Objective::Points;
    bool elbow_free = false;
    bool full_z = false;
    unsigned threads = 2;
    std::string json;
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
            std::printf("%s %s\n", "mountopt", HV_VERSION);
            std::exit(0);
        } else if (opt == "--config") {
            o.config = r.value();
        } else if (opt == "--side") {
            o.sides = parse_sides(opt, r.value());
        } else if (opt == "--objective") {
            o.objective = parse_objective(opt, r.value());
        } else if (opt == "--elbow-free") {
            o.elbow_free = true;
        } else if (opt == "--full-z") {
            o.full_z = true;
        } else if (opt == "--threads") {
            o.threads = static_cast<unsigned>(r.value_long(1, 64));
        } else if (opt == "--json") {
            o.json = r.value();
        } else if (opt == "--quiet") {
            o.quiet = true;
        } else {
            throw UsageError(opt + ": unknown option (see --help)");
        }
    }
    return o;
}

// One installation evaluated on every swept side.
struct Report {
    std::string label;
    double offset_m;
    std::vector<double> theta_rad; // per side
    std::vector<Coverage> cov;     // per side
};

Report evaluate_report(const hv_config_t &cfg, const std::vector<FpaGrid> &fpas,
                       const std::string &label, double offset_m,
                       const std::vector<double> &theta_rad, bool full_z)
{
    Report r{label, offset_m, theta_rad, {}};
    EvalOptions opt;
    opt.full_z = full_z;
    opt.suction = true;
    for (std::size_t s = 0; s < fpas.size(); s++) {
        r.cov.push_back(evaluate_pose(cfg, fpas[s], offset_m, theta_rad[s], opt));
    }
    return r;
}

double pct(std::int64_t n, std::size_t of)
{
    return of == 0 ? 0.0 : 100.0 * static_cast<double>(n) / static_cast<double>(of);
}

// Positions expressed as metres of row fully covered: positions / (x levels * z levels)
// times the y step. Independent of the y window.
double row_equiv_m(std::int64_t positions, const FpaGrid &f)
{
    return static_cast<double>(positions) / static_cast<double>(f.x.size() * f.z.size()) * f.step_m;
}

void print_report(const Report &r, const std::vector<FpaGrid> &fpas)
{
    for (std::size_t s = 0; s < fpas.size(); s++) {
        const Coverage &c = r.cov[s];
        const FpaGrid &f = fpas[s];
        std::printf("  %-22s %-5s %5.3f %7.1f  %8" PRId64 " %5.1f%%  %7" PRId64 " %5.3f  %7" PRId64
                    " %5.3f  %7" PRId64 " %5.3f  %7" PRId64 " %5.3f\n",
                    r.label.c_str(), side_name(f.side), r.offset_m, r.theta_rad[s] / kDeg, c.points,
                    pct(c.points, f.points()), c.stem_positions, row_equiv_m(c.stem_positions, f),
                    c.any_yaw_positions, row_equiv_m(c.any_yaw_positions, f), c.yaw0_positions,
                    row_equiv_m(c.yaw0_positions, f), c.suction_positions,
                    row_equiv_m(c.suction_positions, f));
    }
}

void json_coverage(JsonWriter &j, const Coverage &c)
{
    j.key("points").value(c.points);
    j.key("stem_positions").value(c.stem_positions);
    j.key("any_yaw_positions").value(c.any_yaw_positions);
    j.key("yaw0_positions").value(c.yaw0_positions);
    j.key("suction_positions").value(c.suction_positions);
}

void json_report(JsonWriter &j, const Report &r, const std::vector<FpaGrid> &fpas)
{
    j.begin_object();
    j.key("label").value(r.label);
    j.key("offset_m").value(json_m(r.offset_m));
    j.key("sides").begin_array();
    for (std::size_t s = 0; s < fpas.size(); s++) {
        j.begin_object();
        j.key("side").value(side_name(fpas[s].side));
        j.key("theta_deg").value(json_deg(r.theta_rad[s]));
        json_coverage(j, r.cov[s]);
        j.key("stem_row_equiv_m").value(row_equiv_m(r.cov[s].stem_positions, fpas[s]));
        j.key("suction_row_equiv_m").value(row_equiv_m(r.cov[s].suction_positions, fpas[s]));
        j.end_object();
    }
    j.end_array();
    j.end_object();
}

std::string json_summary(const Options &o, const hv_config_t &cfg, const std::vector<FpaGrid> &fpas,
                         const SweepAxes &axes, const std::vector<SideSweep> &sweeps,
                         const BestPose &best, const std::vector<Report> &reports)
{
    JsonWriter j;
    j.begin_object();
    j.key("tool").value("mountopt");
    j.key("config").value(o.config);
    j.key("objective").value(objective_name(o.objective));
    j.key("elbow_free").value(cfg.elbow_free != 0);
    j.key("full_z").value(o.full_z);
    j.key("fpa").begin_array();
    for (const FpaGrid &f : fpas) {
        j.begin_object();
        j.key("side").value(side_name(f.side));
        j.key("x_m").begin_array().value(f.x[0]).value(f.x[f.x.size() - 1]).end_array();
        j.key("y_m").begin_array().value(f.y[0]).value(f.y[f.y.size() - 1]).end_array();
        j.key("z_m").begin_array().value(f.z[0]).value(f.z[f.z.size() - 1]).end_array();
        j.key("yaw_deg")
            .begin_array()
            .value(json_deg(f.yaw[0]))
            .value(json_deg(f.yaw[f.yaw.size() - 1]))
            .end_array();
        j.key("counts")
            .begin_array()
            .value(static_cast<std::int64_t>(f.x.size()))
            .value(static_cast<std::int64_t>(f.y.size()))
            .value(static_cast<std::int64_t>(f.z.size()))
            .value(static_cast<std::int64_t>(f.yaw.size()))
            .end_array();
        j.key("step_m").value(f.step_m);
        j.key("yaw_step_deg").value(json_deg(f.yaw_step_rad));
        j.key("positions").value(static_cast<std::int64_t>(f.positions()));
        j.key("points").value(static_cast<std::int64_t>(f.points()));
        j.end_object();
    }
    j.end_array();
    j.key("offsets_m").begin_array();
    for (Eigen::Index i = 0; i < axes.offset_m.size(); i++) {
        j.value(json_m(axes.offset_m[i]));
    }
    j.end_array();
    j.key("thetas_deg").begin_array();
    for (Eigen::Index i = 0; i < axes.theta_rad.size(); i++) {
        j.value(json_deg(axes.theta_rad[i]));
    }
    j.end_array();
    j.key("best").begin_object();
    j.key("offset_m").value(json_m(best.offset_m));
    j.key("objective_total").value(best.objective);
    j.key("theta_deg").begin_object();
    for (std::size_t s = 0; s < sweeps.size(); s++) {
        j.key(side_name(sweeps[s].side)).value(json_deg(best.theta_rad[s]));
    }
    j.end_object();
    j.end_object();
    j.key("reports").begin_array();
    for (const Report &r : reports) {
        json_report(j, r, fpas);
    }
    j.end_array();
    // Every evaluated candidate, per side: the total of an installation (D, theta_L,
    // theta_R) is the sum of its two sides' entries at the same D.
    j.key("candidates").begin_array();
    const Eigen::Index n_theta = axes.theta_rad.size();
    for (const SideSweep &sw : sweeps) {
        for (Eigen::Index d = 0; d < axes.offset_m.size(); d++) {
            for (Eigen::Index t = 0; t < n_theta; t++) {
                j.begin_object();
                j.key("side").value(side_name(sw.side));
                j.key("offset_m").value(json_m(axes.offset_m[d]));
                j.key("theta_deg").value(json_deg(axes.theta_rad[t]));
                json_coverage(j, sw.at(d, t, n_theta));
                j.end_object();
            }
        }
    }
    j.end_array();
    j.end_object();
    return j.str() + "\n";
}

int run(const Options &o)
{
    hv_config_t cfg = load_config(o.config);
    if (o.elbow_free) {
        cfg.elbow_free = 1;
    }
    std::vector<FpaGrid> fpas;
    for (hv_side_t s : o.sides) {
        fpas.push_back(make_fpa_grid(cfg, s));
    }
    const FpaGrid &f0 = fpas.front();
    SweepAxes axes = make_sweep_axes(cfg);
    std::printf("mountopt: config %s, elbow %s, objective %s%s\n", o.config.c_str(),
                cfg.elbow_free ? "free" : "one-sided", objective_name(o.objective),
                o.full_z ? ", IK at every z level" : "");
    std::printf("FPA per side: |x| %.3f..%.3f m (%ld), y base %+.3f +- %.3f m (%ld), "
                "z %.3f..%.3f m (%ld), yaw %.1f..%.1f deg (%ld): %zu positions, %zu points\n",
                std::abs(f0.x[0]), std::abs(f0.x[f0.x.size() - 1]), static_cast<long>(f0.x.size()),
                f0.y[f0.y.size() / 2], f0.y_half_window_m, static_cast<long>(f0.y.size()), f0.z[0],
                f0.z[f0.z.size() - 1], static_cast<long>(f0.z.size()), f0.yaw[0] / kDeg,
                f0.yaw[f0.yaw.size() - 1] / kDeg, static_cast<long>(f0.yaw.size()), f0.positions(),
                f0.points());
    std::printf("search: D %.3f..%.3f m (%ld values), theta %.1f..%.1f deg (%ld values), "
                "%ld candidates per side\n",
                axes.offset_m[0], axes.offset_m[axes.offset_m.size() - 1],
                static_cast<long>(axes.offset_m.size()), axes.theta_rad[0] / kDeg,
                axes.theta_rad[axes.theta_rad.size() - 1] / kDeg,
                static_cast<long>(axes.theta_rad.size()),
                static_cast<long>(axes.offset_m.size() * axes.theta_rad.size()));
    std::fflush(stdout);

    EvalOptions eo;
    eo.full_z = o.full_z;
    eo.suction = o.objective == Objective::Suction;
    Progress progress("mountopt: candidates",
                      static_cast<std::size_t>(axes.offset_m.size() * axes.theta_rad.size()) *
                          fpas.size(),
                      o.quiet);
    std::vector<SideSweep> sweeps = sweep(cfg, fpas, axes, eo, o.threads, &progress);
    BestPose best = best_pose(sweeps, axes, o.objective);
    BestPose best_stem = best_pose(sweeps, axes, Objective::Stem);

    std::vector<Report> reports;
    reports.push_back(
        evaluate_report(cfg, fpas, std::string("ours (best ") + objective_name(o.objective) + ")",
                        best.offset_m, best.theta_rad, o.full_z));
    if (o.objective != Objective::Stem) {
        reports.push_back(evaluate_report(cfg, fpas, "ours (best stem)", best_stem.offset_m,
                                          best_stem.theta_rad, o.full_z));
    }
    std::vector<double> paper(fpas.size(), kPaperThetaDeg * kDeg);
    std::vector<double> paper_mirror(fpas.size(), -kPaperThetaDeg * kDeg);
    reports.push_back(
        evaluate_report(cfg, fpas, "paper (43.5 deg)", kPaperOffsetM, paper, o.full_z));
    reports.push_back(
        evaluate_report(cfg, fpas, "paper (-43.5 deg)", kPaperOffsetM, paper_mirror, o.full_z));
    // The other reading of the paper (README, docs/FRAMES.md): D measured from the aisle
    // centre line rather than from the canopy face, and theta counter-clockwise.
    std::vector<double> paper_face(fpas.size(), -kPaperThetaDeg * kDeg);
    reports.push_back(evaluate_report(cfg, fpas, "paper (centre, ccw)",
                                      0.5 * cfg.aisle_width_m - kPaperOffsetM, paper_face,
                                      o.full_z));
    std::vector<double> configured;
    for (const FpaGrid &f : fpas) {
        configured.push_back(cfg.theta_rad[f.side]);
    }
    reports.push_back(
        evaluate_report(cfg, fpas, "config (mount.*)", cfg.offset_m, configured, o.full_z));

    std::printf("\ncoverage per arm (%% of the FPA window; 'row m' = positions / (x levels * "
                "z levels) * y step: metres of row covered in full)\n");
    std::printf("  %-22s %-5s %5s %7s  %15s  %13s  %13s  %13s  %13s\n", "pose", "side", "D m",
                "th deg", "points (%)", "stem pos/row m", "anyyaw/row m", "yaw0/row m",
                "suction/row m");
    for (const Report &r : reports) {
        print_report(r, fpas);
    }
    std::printf("\nbest (%s): D = %.3f m", objective_name(o.objective), best.offset_m);
    for (std::size_t s = 0; s < sweeps.size(); s++) {
        std::printf(", theta_%c = %.1f deg", sweeps[s].side == HV_SIDE_LEFT ? 'L' : 'R',
                    best.theta_rad[s] / kDeg);
    }
    std::printf(", total %s = %" PRId64 "\n", objective_name(o.objective), best.objective);

    if (sweeps.size() == 2) {
        // The layout is symmetric under a half turn about z (docs/FRAMES.md): both sides
        // must count the same. A difference would point at a frame error.
        std::size_t differ = 0;
        for (std::size_t i = 0; i < sweeps[0].cov.size(); i++) {
            const Coverage &a = sweeps[0].cov[i], &b = sweeps[1].cov[i];
            differ += a.points != b.points || a.stem_positions != b.stem_positions;
        }
        std::printf("left/right symmetry: %zu of %zu candidates differ\n", differ,
                    sweeps[0].cov.size());
    }
    if (!o.json.empty()) {
        std::string text = json_summary(o, cfg, fpas, axes, sweeps, best, reports);
        char err[512] = {0};
        if (hv_file_write_atomic(o.json.c_str(), text.data(), text.size(), err, sizeof err) !=
            HV_OK) {
            std::fprintf(stderr, "mountopt: %s\n", err);
            return HV_EXIT_FAILURE;
        }
        std::printf("summary: %s\n", o.json.c_str());
    }
    return HV_EXIT_OK;
}

} // namespace

int main(int argc, char **argv)
{
    bool help = false;
    try {
        Options o = parse(argc, argv, &help);
        if (help) {
            std::printf(kUsage, default_config_path().c_str());
            return HV_EXIT_OK;
        }
        return run(o);
    } catch (const UsageError &e) { // and InputError
        std::fprintf(stderr, "mountopt: %s\n", e.what());
        return HV_EXIT_USAGE;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "mountopt: %s\n", e.what());
        return HV_EXIT_FAILURE;
    }
}
