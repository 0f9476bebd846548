"""The paper's two analysis figures from our own cost tables (paper Fig. 5 and Fig. 6).

Both are drawn on one horizontal slice (the SCARA workspace is a cylinder, so one height
shows it) of tables made by costgen from a derived config whose only changes widen the
grid: x over the whole reach instead of the canopy depth, yaw over the full circle, and
z around mid-canopy. The arm, mount, limits and home pose are the project's.
"""

import math

import numpy as np
from matplotlib.colors import ListedColormap

from .figures import plt, save

# CHOICE: the lateral band of the analysis grid (m, right arm): wide enough to show the
# whole reach of the arm, without the other arm's side.
ANALYSIS_X_NEAR_M = 0.10
ANALYSIS_X_FAR_M = 0.85
FULL_CIRCLE_DEG = 180


def analysis_overrides(row):
    """Config keys to override for the analysis tables (see the module comment)."""
    z_mid = row.canopy_z_min_m + row.canopy_height_m / 2.0
    # mount.offset is measured from the canopy's near face (docs/FRAMES.md): moving that
    # face to ANALYSIS_X_NEAR_M must not move the arm, so the offset moves with it.
    offset = row.mount_offset_m + ANALYSIS_X_NEAR_M - row.x_near_m
    return {
        "mount.offset": f"{offset:.12g}",
        "row.aisle_width": f"{2.0 * ANALYSIS_X_NEAR_M:g}",
        "row.canopy_depth": f"{ANALYSIS_X_FAR_M - ANALYSIS_X_NEAR_M:g}",
        "row.canopy_z_min": f"{z_mid:g}",
        "row.canopy_height": f"{row.grid_step_m:g}",
        "row.pick_yaw_max_deg": f"{FULL_CIRCLE_DEG}",
    }


def z_slice(table):
    """Costs (s, NaN unreachable) at the lowest z of the table: [x][yaw][y]."""
    return table.seconds()[:, 0, :, :]


def yaw_index(table, yaw_rad):
    i = table.axes["yaw"].index(yaw_rad)
    if i is None:
        raise ValueError(f"{table.path}: yaw {math.degrees(yaw_rad):g} deg is outside the table")
    return i


def yaw_range(table, yaw_max_rad):
    """Indices of the yaw cells within [-yaw_max, yaw_max] (small tolerance for rounding)."""
    vals = table.axes["yaw"].values()
    return np.nonzero(np.abs(vals) <= yaw_max_rad + 1e-9)[0]


def coverage_modes(table, yaw_max_rad):
    """Boolean [x][y] maps of the paper's pick modes on the slice."""
    ok = table.reachable()[:, 0, :, :]  # [x][yaw][y]
    band = yaw_range(table, yaw_max_rad)
    return {
        "position only": ok.any(axis=1),
        f"some yaw in +-{math.degrees(yaw_max_rad):g} deg": ok[:, band, :].any(axis=1),
        "yaw 0": ok[:, yaw_index(table, 0.0), :],
        f"every yaw in +-{math.degrees(yaw_max_rad):g} deg": ok[:, band, :].all(axis=1),
    }


def fpa_mask(table, row):
    """[x][y] cells inside the canopy depth band (the fruit-planted area seen from a stop)."""
    xs = np.abs(table.axes["x"].values())
    inside = (xs >= row.x_near_m - 1e-9) & (xs <= row.x_far_m + 1e-9)
    return np.repeat(inside[:, None], table.axes["y"].count, axis=1)


def roughness(g):
    """Mean |difference| (s) between reachable neighbouring cells along x and y."""
    dx = np.abs(np.diff(g, axis=0))
    dy = np.abs(np.diff(g, axis=1))
    vals = np.concatenate([dx[np.isfinite(dx)], dy[np.isfinite(dy)]])
    return float(vals.mean()) if vals.size else math.nan


def _extent(table):
    ys, xs = table.axes["y"], table.axes["x"]
    return [
        ys.origin - ys.step / 2,
        ys.origin + ys.step * (ys.count - 0.5),
        xs.origin - xs.step / 2,
        xs.origin + xs.step * (xs.count - 0.5),
    ]


def _fpa_lines(ax, row):
    for x in (row.x_near_m, row.x_far_m):
        ax.axhline(x, color="black", ls="--", lw=0.8)


def cost_figure(limited, free, row, base_xy):
    """G at yaw 0 on the slice, joint 3 limited (paper's setting) and unlimited."""
    gl = z_slice(limited)[:, yaw_index(limited, 0.0), :]
    gf = z_slice(free)[:, yaw_index(free, 0.0), :]
    both = np.concatenate([gl[np.isfinite(gl)], gf[np.isfinite(gf)]])
    vmax = float(both.max()) if both.size else 1.0
    fig, axes = plt.subplots(1, 2, figsize=(10.0, 4.2), sharey=True, layout="constrained")
    for ax, g, t, name in (
        (axes[0], gf, free, "(a) joint 3 unlimited (elbow free)"),
        (axes[1], gl, limited, "(b) joint 3 limited to [0, 2.8] rad"),
    ):
        im = ax.imshow(
            g,
            origin="lower",
            extent=_extent(t),
            aspect="equal",
            cmap="viridis",
            vmin=0.0,
            vmax=vmax,
            interpolation="nearest",
        )
        _fpa_lines(ax, row)
        ax.plot([base_xy[1]], [base_xy[0]], "r^", ms=7)
        ax.set_title(f"{name}\nroughness {roughness(g):.3f} s/cell", fontsize=9)
        ax.set_xlabel("fruit y - stop y (m)")
    axes[0].set_ylabel("x (m), right arm")
    fig.colorbar(im, ax=axes, label="G (s), yaw 0, white = unreachable", shrink=0.8)
    z = limited.axes["z"].origin
    fig.suptitle(
        f"Pick cost G on the slice z = {z:.2f} m (dashed: canopy depth; triangle: arm base)",
        fontsize=10,
    )
    return fig


MODE_COLORS = ("#d62728", "#ffd92f", "#1f77b4", "#2ca02c")


def coverage_figure(limited, free, row, yaw_max_rad, base_xy):
    """(a) layered pick modes with joint 3 limited; (b) yaw 0: both elbows vs single-sided."""
    modes = coverage_modes(limited, yaw_max_rad)
    fig, axes = plt.subplots(1, 2, figsize=(10.0, 4.6), sharey=True, layout="constrained")
    layer = np.zeros(modes["yaw 0"].shape)
    # The modes nest (every yaw within yaw 0 within some yaw within position): paint the
    # wider ones first, as the paper's figure does.
    for k, m in enumerate(modes.values(), 1):
        layer[m] = np.maximum(layer[m], k)
    cmap = ListedColormap(["white"] + list(MODE_COLORS))
    axes[0].imshow(
        layer,
        origin="lower",
        extent=_extent(limited),
        aspect="equal",
        cmap=cmap,
        vmin=-0.5,
        vmax=4.5,
        interpolation="nearest",
    )
    for name, c in zip(modes, MODE_COLORS):
        axes[0].plot([], [], "s", color=c, label=name)
    axes[0].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.25), ncol=2)
    axes[0].set_title("(a) pick modes, joint 3 limited", fontsize=9)
    single = limited.reachable()[:, 0, yaw_index(limited, 0.0), :]
    both = free.reachable()[:, 0, yaw_index(free, 0.0), :]
    b = np.zeros(single.shape)
    b[both] = 1
    b[single] = 2
    cmap2 = ListedColormap(["white", "#1f77b4", "#ff7f0e"])
    axes[1].imshow(
        b,
        origin="lower",
        extent=_extent(limited),
        aspect="equal",
        cmap=cmap2,
        vmin=-0.5,
        vmax=2.5,
        interpolation="nearest",
    )
    axes[1].plot([], [], "s", color="#1f77b4", label="yaw 0, either elbow (joint 3 free)")
    axes[1].plot([], [], "s", color="#ff7f0e", label="yaw 0, single-sided (joint 3 limited)")
    axes[1].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.25), ncol=1)
    axes[1].set_title("(b) yaw 0: single-sided coverage", fontsize=9)
    for ax in axes:
        _fpa_lines(ax, row)
        ax.plot([base_xy[1]], [base_xy[0]], "k^", ms=7)
        ax.set_xlabel("fruit y - stop y (m)")
    axes[0].set_ylabel("x (m), right arm")
    return fig


def coverage_numbers(limited, free, row, yaw_max_rad):
    """Area (m^2) of the canopy band one stop covers in each mode (for the report)."""
    cell = limited.axes["x"].step * limited.axes["y"].step
    fpa = fpa_mask(limited, row)
    out = {
        name: float((m & fpa).sum() * cell)
        for name, m in coverage_modes(limited, yaw_max_rad).items()
    }
    out["yaw 0, joint 3 free"] = float(
        (free.reachable()[:, 0, yaw_index(free, 0.0), :] & fpa).sum() * cell
    )
    return out


def write_figures(limited, free, row, yaw_max_rad, base_xy, out_dir):
    paths = save(cost_figure(limited, free, row, base_xy), out_dir, "cost_G_joint3")
    paths += save(
        coverage_figure(limited, free, row, yaw_max_rad, base_xy), out_dir, "coverage_pick_modes"
    )
    return paths
