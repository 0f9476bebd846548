// Building the pick-cost table G(x, y, z, yaw) of one arm (DESIGN §4): every cell is
// hv_scara_pick_cost of the cell's pose, in milliseconds, computed on several threads.
#ifndef HV_TOOLS_COST_TABLE_BUILDER_HPP
#define HV_TOOLS_COST_TABLE_BUILDER_HPP

#include <cstddef>
#include <cstdint>
#include <vector>

#include "hv/cost_table.h"
#include "hv/scara.h"
#include "progress.hpp"

namespace hv::tools
{

// Written into every table header; bump when the meaning of a cell changes.
constexpr std::uint32_t kGeneratorVersion = 1;

// Axis value (m or rad) at index i.
inline double axis_value(const hv_axis_t &axis, std::uint32_t i)
{
    return axis.origin + axis.step * static_cast<double>(i);
}

// Payload index of a cell (y innermost, cost_table.h).
std::size_t cell_index(const hv_grid_t &grid, std::uint32_t ix, std::uint32_t iy, std::uint32_t iz,
                       std::uint32_t iyaw);

// The vehicle-frame pose of a cell for a stop at y = 0: the table's yaw is relative to
// the side's inward normal, the IK wants an absolute heading.
hv_pose_t cell_pose(const hv_grid_t &grid, hv_side_t side, std::uint32_t ix, std::uint32_t iy,
                    std::uint32_t iz, std::uint32_t iyaw);

// One cell's value: round(G * 1000) ms, HV_COST_UNREACHABLE when the IK has no solution
// within the limits, HV_COST_MAX_MS with *clamped = true when G is too large to encode.
// Any other IK status (NaN, bad argument) is a bug in the inputs: throws runtime_error.
std::uint16_t cell_cost_ms(const hv_arm_t &arm, const hv_pose_t &pose, bool *clamped);

struct CostTable {
    hv_grid_t grid;
    hv_arm_t arm;
    std::vector<std::uint16_t> costs_ms; // payload order
    std::size_t reachable = 0;           // cells != HV_COST_UNREACHABLE
    std::size_t clamped = 0;             // cells whose cost exceeded HV_COST_MAX_MS
};

// Compute every cell with `threads` workers (>= 1). The result does not depend on the
// number of threads. `progress` may be null. Throws runtime_error on an invalid grid.
CostTable build_cost_table(const hv_arm_t &arm, const hv_grid_t &grid, unsigned threads,
                           Progress *progress);

// The file image (header + payload) of a table. Throws runtime_error on failure.
std::vector<std::uint8_t> serialise_cost_table(const CostTable &table);

} // namespace hv::tools

#endif
