// The installation-pose search of paper §III.C: for every base offset D and rotation theta
// of the search range, count the FPA points (x, y, z, yaw) the arm reaches (IK valid within
// the joint limits), and pick the pose that reaches the most.
//
// Pick modes (paper §III.C, Fig. 6):
//   points     every reachable (x, y, z, yaw) with yaw on the stem-cutting grid: the
//              paper's objective ("maximize the number of reachable points").
//   stem       stem cutting, strict: a position (x, y, z) counts only if EVERY yaw of the
//              range [-pick_yaw_max, pick_yaw_max] (on its grid) is reachable (green).
//   any_yaw    a position reachable with at least one yaw of the range (yellow).
//   yaw0       a position reachable straight into the row, yaw 0 (blue).
//   suction    bottom suction, position only: reachable with some heading of the whole
//              circle, sampled at grid.yaw_step (red). No collision model (see README).
#ifndef HV_TOOLS_MOUNT_SEARCH_HPP
#define HV_TOOLS_MOUNT_SEARCH_HPP

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fpa_grid.hpp"
#include "hv/config.h"
#include "progress.hpp"

namespace hv::tools
{

struct Coverage {
    std::int64_t points = 0;
    std::int64_t stem_positions = 0;
    std::int64_t any_yaw_positions = 0;
    std::int64_t yaw0_positions = 0;
    std::int64_t suction_positions = -1; // -1: not computed
};

enum class Objective { Points, Stem, Suction };

// "points" | "stem" | "suction"; throws UsageError naming `option` otherwise.
Objective parse_objective(const std::string &option, const std::string &value);
const char *objective_name(Objective o);
// The count an objective maximises.
std::int64_t objective_value(const Coverage &c, Objective o);

struct EvalOptions {
    // false: the SCARA's workspace is a vertical cylinder (joint 1 alone sets z), so the
    // cross-section is evaluated once and multiplied by the number of z levels inside joint
    // 1's stroke; true: run the IK at every z level (slower, the same result; for checks).
    bool full_z = false;
    bool suction = false; // also compute suction_positions (more IK calls)
};

// Coverage of the FPA `fpa` by the arm of fpa.side mounted at (offset_m, theta_rad).
Coverage evaluate_pose(const hv_config_t &cfg, const FpaGrid &fpa, double offset_m,
                       double theta_rad, const EvalOptions &opt);

// The search range of the configuration: search.offset_* and search.theta_*, endpoints
// included when they fall on a step.
struct SweepAxes {
    Eigen::ArrayXd offset_m;
    Eigen::ArrayXd theta_rad;
};
SweepAxes make_sweep_axes(const hv_config_t &cfg);

// Coverage of every (D, theta) of one side: rows D, columns theta.
struct SideSweep {
    hv_side_t side;
    std::vector<Coverage> cov; // row-major, offset index * theta count + theta index
    const Coverage &at(Eigen::Index i_off, Eigen::Index i_theta, Eigen::Index n_theta) const
    {
        return cov[static_cast<std::size_t>(i_off * n_theta + i_theta)];
    }
};

// Evaluate every candidate of every given side on `threads` workers (deterministic).
std::vector<SideSweep> sweep(const hv_config_t &cfg, const std::vector<FpaGrid> &fpas,
                             const SweepAxes &axes, const EvalOptions &opt, unsigned threads,
                             Progress *progress);

// The best installation: one D shared by both arms, each arm its own theta. Because the two
// arms' coverages add up, the best (D, theta_L, theta_R) is, for each D, the best theta of
// each side, then the best D. Ties go to the smaller D, then the smaller theta.
struct BestPose {
    Eigen::Index i_offset = -1;
    double offset_m = 0.0;
    std::vector<Eigen::Index> i_theta; // per swept side
    std::vector<double> theta_rad;     // per swept side
    std::int64_t objective = -1;       // summed over the swept sides
};
BestPose best_pose(const std::vector<SideSweep> &sweeps, const SweepAxes &axes, Objective o);

} // namespace hv::tools

#endif
