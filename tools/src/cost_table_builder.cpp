// Building the pick-cost table of one arm.
#include "cost_table_builder.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>

namespace hv::tools
{

std::size_t cell_index(const hv_grid_t &grid, std::uint32_t ix, std::uint32_t iy, std::uint32_t iz,
                       std::uint32_t iyaw)
{
    const hv_axis_t *a = grid.axis;
    return ((static_cast<std::size_t>(ix) * a[HV_AX_Z].count + iz) * a[HV_AX_YAW].count + iyaw) *
               a[HV_AX_Y].count +
           iy;
}

hv_pose_t cell_pose(const hv_grid_t &grid, hv_side_t side, std::uint32_t ix, std::uint32_t iy,
                    std::uint32_t iz, std::uint32_t iyaw)
{
    hv_pose_t p;
    p.x_m = axis_value(grid.axis[HV_AX_X], ix);
    p.y_m = axis_value(grid.axis[HV_AX_Y], iy);
    p.z_m = axis_value(grid.axis[HV_AX_Z], iz);
    p.heading_rad = hv_side_normal_heading(side) + axis_value(grid.axis[HV_AX_YAW], iyaw);
    return p;
}

std::uint16_t cell_cost_ms(const hv_arm_t &arm, const hv_pose_t &pose, bool *clamped)
{
    *clamped = false;
    double cost_s = 0.0;
    hv_status_t st = hv_scara_pick_cost(&arm, &pose, &cost_s, nullptr);
    if (st == HV_ERR_UNREACHABLE || st == HV_ERR_JOINT_LIMIT) {
        return HV_COST_UNREACHABLE;
    }
    if (st != HV_OK) {
        throw std::runtime_error(std::string("pick cost failed: ") + hv_status_name(st));
    }
    double ms = std::round(cost_s * 1000.0);
    if (!(ms <= static_cast<double>(HV_COST_MAX_MS))) {
        *clamped = true;
        return HV_COST_MAX_MS;
    }
    return static_cast<std::uint16_t>(ms);
}

CostTable build_cost_table(const hv_arm_t &arm, const hv_grid_t &grid, unsigned threads,
                           Progress *progress)
{
    hv_diag_t diag{};
    if (hv_grid_check(&grid, &diag) != HV_OK) {
        throw std::runtime_error(std::string("grid: ") + diag.field + ": " + diag.message);
    }
    CostTable t;
    t.grid = grid;
    t.arm = arm;
    t.costs_ms.assign(hv_grid_cells(&grid), HV_COST_UNREACHABLE);

    const hv_axis_t *a = grid.axis;
    const std::uint32_t ny = a[HV_AX_Y].count;
    // A "row" is the ny cells of one (x, z, yaw): workers take rows from a shared counter,
    // each writes only its own rows, so the result is the same for any thread count.
    const std::size_t rows =
        static_cast<std::size_t>(a[HV_AX_X].count) * a[HV_AX_Z].count * a[HV_AX_YAW].count;
    std::atomic<std::size_t> next_row{0}, rows_done{0}, reachable{0}, clamped{0};
    std::atomic<bool> failed{false};
    std::string failure;
    std::atomic_flag failure_set = ATOMIC_FLAG_INIT;

    auto worker = [&]() {
        std::size_t my_reachable = 0, my_clamped = 0;
        for (;;) {
            std::size_t r = next_row.fetch_add(1);
            if (r >= rows || failed.load()) {
                break;
            }
            auto iyaw = static_cast<std::uint32_t>(r % a[HV_AX_YAW].count);
            auto iz = static_cast<std::uint32_t>((r / a[HV_AX_YAW].count) % a[HV_AX_Z].count);
            auto ix = static_cast<std::uint32_t>(r / a[HV_AX_YAW].count / a[HV_AX_Z].count);
            std::uint16_t *row = &t.costs_ms[cell_index(grid, ix, 0, iz, iyaw)];
            try {
                for (std::uint32_t iy = 0; iy < ny; iy++) {
                    bool c = false;
                    row[iy] = cell_cost_ms(arm, cell_pose(grid, arm.side, ix, iy, iz, iyaw), &c);
                    my_reachable += row[iy] != HV_COST_UNREACHABLE;
                    my_clamped += c;
                }
            } catch (const std::exception &e) {
                if (!failure_set.test_and_set()) {
                    failure = e.what();
                }
                failed.store(true);
                break;
            }
            rows_done.fetch_add(1);
        }
        reachable.fetch_add(my_reachable);
        clamped.fetch_add(my_clamped);
    };

    unsigned n = threads == 0 ? 1 : threads;
    std::vector<std::thread> pool;
    for (unsigned i = 0; i < n; i++) {
        pool.emplace_back(worker);
    }
    while (progress != nullptr && rows_done.load() < rows && !failed.load()) {
        progress->update(rows_done.load() * ny);
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
    t.reachable = reachable.load();
    t.clamped = clamped.load();
    return t;
}

std::vector<std::uint8_t> serialise_cost_table(const CostTable &table)
{
    std::size_t bytes = hv_costtab_file_bytes(&table.grid);
    if (bytes == 0) {
        throw std::runtime_error("invalid grid: no file size");
    }
    std::vector<std::uint8_t> out(bytes);
    hv_diag_t diag{};
    hv_status_t st = hv_costtab_write(&table.grid, &table.arm, kGeneratorVersion,
                                      table.costs_ms.data(), out.data(), out.size(), &diag);
    if (st != HV_OK) {
        throw std::runtime_error(std::string("cost table: ") + diag.field + ": " + diag.message +
                                 " (" + hv_status_name(st) + ")");
    }
    return out;
}

} // namespace hv::tools
