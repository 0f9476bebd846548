"""Shared matplotlib set-up: the Agg backend (no display) and saving as PNG and SVG."""

import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)

METHOD_LABELS = {"fov": "FOV", "serial": "Serial", "milp": "MILP"}
METHOD_COLORS = {"fov": "#9e9e9e", "serial": "#e69f00", "milp": "#0072b2"}


def save(fig, out_dir, stem):
    """Write stem.png and stem.svg; returns both paths."""
    os.makedirs(out_dir, exist_ok=True)
    paths = []
    for ext in ("png", "svg"):
        p = os.path.join(out_dir, f"{stem}.{ext}")
        fig.savefig(p, dpi=150, bbox_inches="tight")
        paths.append(p)
    plt.close(fig)
    return paths
