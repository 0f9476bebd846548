// The installation-pose search of paper §III.C.
#include "mount_search.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "cli_args.hpp"

namespace hv::tools
{

namespace
{

constexpr double kPi = 3.14159265358979323846;
constexpr double kLimitTol = 1e-9; // the IK's own joint-limit tolerance (core/src/scara.c)

// IK within limits? Unreachable and joint-limit failures are "no"; anything else is a bug.
bool reaches(const hv_arm_t &arm, double x, double y, double z, double heading)
{
    hv_pose_t p{x, y, z, heading};
    double q[HV_NJOINTS];
    hv_status_t st = hv_scara_ik(&arm, &p, q);
    if (st == HV_OK) {
        return true;
    }
    if (st == HV_ERR_UNREACHABLE || st == HV_ERR_JOINT_LIMIT) {
        return false;
    }
    throw std::runtime_error(std::string("IK failed: ") + hv_status_name(st));
}

Eigen::ArrayXd range_values(double min, double max, double step)
{
    // Endpoints included when on a step; the small slack keeps 0.35 in [0.10, 0.35] / 0.01.
    auto n = static_cast<Eigen::Index>(std::floor((max - min) / step + 1e-9)) + 1;
    Eigen::ArrayXd v(n);
    for (Eigen::Index i = 0; i < n; i++) {
        v[i] = min + step * static_cast<double>(i);
    }
    return v;
}

} // namespace

Objective parse_objective(const std::string &option, const std::string &value)
{
    if (value == "points") {
        return Objective::Points;
    }
    if (value == "stem") {
        return Objective::Stem;
    }
    if (value == "suction") {
        return Objective::Suction;
    }
    throw UsageError(option + ": expected points, stem or suction, got '" + value + "'");
}

const char *objective_name(Objective o)
{
    switch (o) {
    case Objective::Stem: return "stem";
    case Objective::Suction: return "suction";
    case Objective::Points: break;
    }
    return "points";
}

std::int64_t objective_value(const Coverage &c, Objective o)
{
    switch (o) {
    case Objective::Stem: return c.stem_positions;
    case Objective::Suction: return c.suction_positions;
    case Objective::Points: break;
    }
    return c.points;
}

Coverage evaluate_pose(const hv_config_t &cfg, const FpaGrid &fpa, double offset_m,
                       double theta_rad, const EvalOptions &opt)
{
    hv_arm_t arm;
    hv_config_arm_mounted(&cfg, fpa.side, offset_m, theta_rad, &arm);
    const double normal = hv_side_normal_heading(fpa.side);
    const Eigen::Index nyaw = fpa.yaw.size();

    // z levels evaluated, each standing for `weight` levels of the grid.
    std::vector<double> zs;
    std::int64_t weight = 1;
    if (opt.full_z) {
        zs.assign(fpa.z.data(), fpa.z.data() + fpa.z.size());
    } else {
        // Joint 1 alone sets the height: z = base z + ee z at zero joints + q1 (FRAMES.md).
        weight = 0;
        for (Eigen::Index i = 0; i < fpa.z.size(); i++) {
            double q1 = fpa.z[i] - arm.base_m[2] - arm.origin_m[4][2];
            if (q1 >= arm.limit[0].min - kLimitTol && q1 <= arm.limit[0].max + kLimitTol) {
                if (weight++ == 0) {
                    zs.push_back(fpa.z[i]);
                }
            }
        }
    }
    // Bottom suction samples the whole circle of headings at the yaw step.
    const auto n_circle = static_cast<int>(std::lround(2.0 * kPi / fpa.yaw_step_rad));

    Coverage c;
    c.suction_positions = opt.suction ? 0 : -1;
    for (Eigen::Index ix = 0; ix < fpa.x.size(); ix++) {
        for (Eigen::Index iy = 0; iy < fpa.y.size(); iy++) {
            const double x = fpa.x[ix], y = fpa.y[iy];
            for (double z : zs) {
                std::int64_t n_ok = 0;
                for (Eigen::Index k = 0; k < nyaw; k++) {
                    n_ok += reaches(arm, x, y, z, normal + fpa.yaw[k]);
                }
                c.points += weight * n_ok;
                c.stem_positions += weight * (n_ok == nyaw);
                c.any_yaw_positions += weight * (n_ok > 0);
                c.yaw0_positions += weight * reaches(arm, x, y, z, normal);
                if (opt.suction) {
                    bool any = n_ok > 0;
                    for (int k = 0; k < n_circle && !any; k++) {
                        any = reaches(arm, x, y, z,
                                      normal - kPi + fpa.yaw_step_rad * static_cast<double>(k));
                    }
                    c.suction_positions += weight * any;
                }
            }
        }
    }
    return c;
}

SweepAxes make_sweep_axes(const hv_config_t &cfg)
{
    SweepAxes a;
    a.offset_m =
        range_values(cfg.search_offset_min_m, cfg.search_offset_max_m, cfg.search_offset_step_m);
    a.theta_rad =
        range_values(cfg.search_theta_min_rad, cfg.search_theta_max_rad, cfg.search_theta_step_rad);
    return a;
}

std::vector<SideSweep> sweep(const hv_config_t &cfg, const std::vector<FpaGrid> &fpas,
                             const SweepAxes &axes, const EvalOptions &opt, unsigned threads,
                             Progress *progress)
{
    const auto n_off = static_cast<std::size_t>(axes.offset_m.size());
    const auto n_theta = static_cast<std::size_t>(axes.theta_rad.size());
    const std::size_t per_side = n_off * n_theta;
    std::vector<SideSweep> out(fpas.size());
    for (std::size_t s = 0; s < fpas.size(); s++) {
        out[s].side = fpas[s].side;
        out[s].cov.resize(per_side);
    }
    const std::size_t total = per_side * fpas.size();
    std::atomic<std::size_t> next{0}, done{0};
    std::atomic<bool> failed{false};
    std::atomic_flag failure_set = ATOMIC_FLAG_INIT;
    std::string failure;

    // Workers take candidates from a shared counter; each result has its own slot.
    auto worker = [&]() {
        for (;;) {
            std::size_t i = next.fetch_add(1);
            if (i >= total || failed.load()) {
                return;
            }
            std::size_t s = i / per_side, j = i % per_side;
            try {
                out[s].cov[j] = evaluate_pose(
                    cfg, fpas[s], axes.offset_m[static_cast<Eigen::Index>(j / n_theta)],
                    axes.theta_rad[static_cast<Eigen::Index>(j % n_theta)], opt);
            } catch (const std::exception &e) {
                if (!failure_set.test_and_set()) {
                    failure = e.what();
                }
                failed.store(true);
                return;
            }
            done.fetch_add(1);
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < (threads == 0 ? 1u : threads); t++) {
        pool.emplace_back(worker);
    }
    while (progress != nullptr && done.load() < total && !failed.load()) {
        progress->update(done.load());
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    for (auto &th : pool) {
        th.join();
    }
    if (failed.load()) {
        throw std::runtime_error(failure);
    }
    if (progress != nullptr) {
        progress->finish();
    }
    return out;
}

BestPose best_pose(const std::vector<SideSweep> &sweeps, const SweepAxes &axes, Objective o)
{
    const Eigen::Index n_theta = axes.theta_rad.size();
    BestPose best;
    for (Eigen::Index d = 0; d < axes.offset_m.size(); d++) {
        std::int64_t total = 0;
        std::vector<Eigen::Index> arg(sweeps.size(), 0);
        for (std::size_t s = 0; s < sweeps.size(); s++) {
            std::int64_t side_best = -1;
            for (Eigen::Index t = 0; t < n_theta; t++) {
                std::int64_t v = objective_value(sweeps[s].at(d, t, n_theta), o);
                if (v > side_best) { // strict: ties keep the smaller theta
                    side_best = v;
                    arg[s] = t;
                }
            }
            total += side_best;
        }
        if (total > best.objective) { // strict: ties keep the smaller D
            best.objective = total;
            best.i_offset = d;
            best.offset_m = axes.offset_m[d];
            best.i_theta = arg;
            best.theta_rad.clear();
            for (Eigen::Index t : arg) {
                best.theta_rad.push_back(axes.theta_rad[t]);
            }
        }
    }
    return best;
}

} // namespace hv::tools
