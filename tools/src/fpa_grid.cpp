// The discretised fruit-planted area of one side.
#include "fpa_grid.hpp"

#include <cmath>

namespace hv::tools
{

namespace
{

Eigen::ArrayXd axis_values(const hv_axis_t &a)
{
    Eigen::ArrayXd v(static_cast<Eigen::Index>(a.count));
    for (Eigen::Index i = 0; i < v.size(); i++) {
        v[i] = a.origin + a.step * static_cast<double>(i);
    }
    return v;
}

} // namespace

double planar_reach_m(const hv_config_t &cfg)
{
    const double(*o)[3] = cfg.origin_m;
    double reach = std::hypot(o[1][0], o[1][1]);
    for (int i = 1; i < 4; i++) {
        reach += std::hypot(o[i + 1][0] - o[i][0], o[i + 1][1] - o[i][1]);
    }
    return reach;
}

FpaGrid make_fpa_grid(const hv_config_t &cfg, hv_side_t side)
{
    hv_grid_t g;
    hv_config_grid(&cfg, side, &g);
    hv_arm_t arm;
    hv_config_arm(&cfg, side, &arm); // only its base y is used: it does not depend on D, theta
    FpaGrid f;
    f.side = side;
    f.step_m = cfg.grid_step_m;
    f.yaw_step_rad = cfg.grid_yaw_step_rad;
    f.x = axis_values(g.axis[HV_AX_X]);
    f.z = axis_values(g.axis[HV_AX_Z]);
    f.yaw = axis_values(g.axis[HV_AX_YAW]);
    // Whole steps out to (and including) the reach bound: nothing reachable lies outside.
    auto k = static_cast<Eigen::Index>(std::ceil(planar_reach_m(cfg) / f.step_m - 1e-9));
    f.y_half_window_m = static_cast<double>(k) * f.step_m;
    f.y = Eigen::ArrayXd::LinSpaced(2 * k + 1, -static_cast<double>(k), static_cast<double>(k)) *
              f.step_m +
          arm.base_m[1];
    return f;
}

} // namespace hv::tools
