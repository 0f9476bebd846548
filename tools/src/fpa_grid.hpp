// The discretised fruit-planted area (FPA) of one side, as the installation-pose search
// samples it (paper §III.C): x over the canopy depth, z over the canopy height and yaw over
// the stem-cutting range exactly as the cost table's grid (hv_config_grid), and y over a
// window along the row centred on the arm's base, wide enough to hold every point the arm
// can reach, so the count of reachable points does not depend on the window.
#ifndef HV_TOOLS_FPA_GRID_HPP
#define HV_TOOLS_FPA_GRID_HPP

#include <cstddef>

#include <Eigen/Core>

#include "hv/config.h"

namespace hv::tools
{

struct FpaGrid {
    hv_side_t side;
    Eigen::ArrayXd x;   // vehicle frame, m (negative on the left side)
    Eigen::ArrayXd y;   // vehicle frame, m: base y + k * step, |k * step| <= y_half_window_m
    Eigen::ArrayXd z;   // m above the floor
    Eigen::ArrayXd yaw; // pick heading relative to the side's inward normal, rad
    double step_m;      // spacing of x, y, z
    double yaw_step_rad;
    double y_half_window_m;

    std::size_t positions() const
    {
        return static_cast<std::size_t>(x.size() * y.size() * z.size());
    }
    std::size_t points() const
    {
        return positions() * static_cast<std::size_t>(yaw.size());
    }
};

// Upper bound (m) of the end effector's horizontal distance from the arm's base axis:
// |joint 2 offset| + the three horizontal link lengths (config arm.origin.*).
double planar_reach_m(const hv_config_t &cfg);

// The FPA of `side` at the configuration's grid.step and grid.yaw_step_deg.
FpaGrid make_fpa_grid(const hv_config_t &cfg, hv_side_t side);

} // namespace hv::tools

#endif
