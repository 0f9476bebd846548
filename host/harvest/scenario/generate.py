"""Fruit distributions over the fruit-planted area of config/harvest.cfg.

Every generator takes a numpy Generator, so a scenario is a pure function of its seed; the
counts per side are exact (m^L left, round(alpha * m^L) right, as in the paper). Positions
are always inside the canopy box: |x| in [aisle/2, aisle/2 + depth], y in [0, length],
z in [z_min, z_min + height], yaw in [-yaw_max, yaw_max].
"""

import math

import numpy as np

from .fruit_map import Fruit

DISTRIBUTIONS = ("uniform", "clustered", "gradient", "long")

# Fruit density of the paper's left row: 50 fruits over its 2 m (used to scale long rows).
PAPER_LEFT_FRUITS = 50

# CHOICE (clustered): trusses of 1-7 fruits (mean ~4), spread about the truss point by
# these standard deviations, fruits hanging below it; yaws vary little within a truss.
TRUSS_MEAN_FRUITS = 4.0
TRUSS_SIGMA_Y_M = 0.03
TRUSS_SIGMA_X_M = 0.02
TRUSS_DROP_SIGMA_M = 0.04
TRUSS_SIGMA_YAW_RAD = math.radians(8.0)


def rng_for(seed, alpha, distribution="uniform"):
    """The generator of one instance: seed, alpha and distribution all select the stream."""
    code = DISTRIBUTIONS.index(distribution)
    return np.random.default_rng([int(seed), int(round(alpha * 1000)), code])


def right_count(n_left, alpha):
    return int(round(alpha * n_left))


def _make(side, xs, ys, zs, yaws):
    sign = -1.0 if side == "L" else 1.0
    order = np.argsort(ys, kind="stable")  # ids in driving order make plans easier to read
    return [
        Fruit(
            f"{side}{k:03d}", side, sign * float(xs[i]), float(ys[i]), float(zs[i]), float(yaws[i])
        )
        for k, i in enumerate(order)
    ]


def _uniform_side(row, side, n, rng, length_m):
    xs = rng.uniform(row.x_near_m, row.x_far_m, n)
    ys = rng.uniform(0.0, length_m, n)
    zs = rng.uniform(row.canopy_z_min_m, row.z_max_m, n)
    yaws = rng.uniform(-row.yaw_max_rad, row.yaw_max_rad, n)
    return _make(side, xs, ys, zs, yaws)


def uniform(row, n_left, alpha, rng, length_m=None):
    """The paper's data generation (§IV.A.1): uniform position and yaw on both sides."""
    length_m = row.length_m if length_m is None else length_m
    return _uniform_side(row, "L", n_left, rng, length_m) + _uniform_side(
        row, "R", right_count(n_left, alpha), rng, length_m
    )


def _inside(lo, hi, draw):
    """Redraw until inside [lo, hi]: trusses near an edge are cut, never piled on it."""
    for _ in range(1000):
        v = draw()
        if lo <= v <= hi:
            return v
    raise RuntimeError(
        "cluster spread too wide for the canopy box"
    )  # not reachable with the spreads above


def _clustered_side(row, side, n, rng, length_m):
    xs, ys, zs, yaws = [], [], [], []
    while len(xs) < n:
        cy = rng.uniform(0.0, length_m)
        cx = rng.uniform(row.x_near_m, row.x_far_m)
        cz = rng.uniform(row.canopy_z_min_m, row.z_max_m)
        cyaw = rng.uniform(-row.yaw_max_rad, row.yaw_max_rad)
        k = min(7, 1 + int(rng.poisson(TRUSS_MEAN_FRUITS - 1.0)))
        for _ in range(min(k, n - len(xs))):
            xs.append(_inside(row.x_near_m, row.x_far_m, lambda: rng.normal(cx, TRUSS_SIGMA_X_M)))
            ys.append(_inside(0.0, length_m, lambda: rng.normal(cy, TRUSS_SIGMA_Y_M)))
            zs.append(
                _inside(
                    row.canopy_z_min_m,
                    row.z_max_m,
                    lambda: cz - abs(rng.normal(0.0, TRUSS_DROP_SIGMA_M)),
                )
            )
            yaws.append(
                _inside(
                    -row.yaw_max_rad, row.yaw_max_rad, lambda: rng.normal(cyaw, TRUSS_SIGMA_YAW_RAD)
                )
            )
    return _make(side, np.array(xs), np.array(ys), np.array(zs), np.array(yaws))


def clustered(row, n_left, alpha, rng, length_m=None):
    """Fruits in trusses: a few fruits close together, hanging below a common point."""
    length_m = row.length_m if length_m is None else length_m
    return _clustered_side(row, "L", n_left, rng, length_m) + _clustered_side(
        row, "R", right_count(n_left, alpha), rng, length_m
    )


def gradient_positions(rng, n, length_m, g):
    """y with a density rising linearly along the row: (1 - g) at y = 0 to (1 + g) at the end.

    Inverse CDF of f(u) = 1 - g + 2 g u on u in [0, 1]: F(u) = (1 - g) u + g u^2.
    """
    r = rng.uniform(0.0, 1.0, n)
    if g == 0.0:
        u = r
    else:
        a = 1.0 - g
        u = (-a + np.sqrt(a * a + 4.0 * g * r)) / (2.0 * g)
    return np.clip(u, 0.0, 1.0) * length_m


def gradient(row, n_left, alpha, rng, length_m=None, g=0.8):
    """Ripeness gradient: more ripe fruit towards the row's end (g in [-1, 1], 0 = uniform)."""
    if not -1.0 <= g <= 1.0:
        raise ValueError(f"gradient must be in [-1, 1], got {g}")
    length_m = row.length_m if length_m is None else length_m
    out = []
    for side, n in (("L", n_left), ("R", right_count(n_left, alpha))):
        xs = rng.uniform(row.x_near_m, row.x_far_m, n)
        ys = gradient_positions(rng, n, length_m, g)
        zs = rng.uniform(row.canopy_z_min_m, row.z_max_m, n)
        yaws = rng.uniform(-row.yaw_max_rad, row.yaw_max_rad, n)
        out += _make(side, xs, ys, zs, yaws)
    return out


def long_row_left_count(row, length_m):
    """The paper's left density (50 fruits per configured row length) over a longer row."""
    return int(round(PAPER_LEFT_FRUITS * length_m / row.length_m))


def generate(distribution, row, n_left, alpha, seed, length_m=None, gradient_g=0.8):
    rng = rng_for(seed, alpha, distribution)
    if distribution == "uniform":
        return uniform(row, n_left, alpha, rng, length_m)
    if distribution == "long":
        return uniform(row, n_left, alpha, rng, length_m)
    if distribution == "clustered":
        return clustered(row, n_left, alpha, rng, length_m)
    if distribution == "gradient":
        return gradient(row, n_left, alpha, rng, length_m, gradient_g)
    raise ValueError(f"unknown distribution '{distribution}' (one of {', '.join(DISTRIBUTIONS)})")
