"""The FOV baseline's camera windows: the MILP's throughput gain over FOV as a function of
where each arm's window lies (fov.offset) and how wide it is (fov.width).

The paper gives neither (its camera's view is "smaller than the reachability area"), and
the gain over FOV depends on both. The MILP does not depend on them, so its plans are the
main run's; only FOV is planned again, once per (width, offset), in
OUT/fov_width/w<width>_o<offset>/ (a derived run: same instances, tables and cost model as
the main run).
"""

import json
import os
import statistics

import numpy as np

from . import report
from . import results as results_mod
from .figures import plt, save
from .runner import run
from .subruns import derive, require_main

SUBDIR = "fov_width"
# Widths up to most of an arm's reach along the row (about 0.7 m); offsets from the arm's
# base that keep a 0.4 m window inside that reach (-0.285..+0.415 m of the base,
# docs/FRAMES.md), in steps of 0.05 m.
DEFAULT_WIDTHS_M = (0.2, 0.3, 0.4, 0.5)
DEFAULT_OFFSETS_M = (-0.1, -0.05, 0.0, 0.05, 0.1, 0.15, 0.2)
FIGURE_STEM = "fov_width_gain"


def _parse(text, option, positive):
    try:
        values = sorted({float(w) for w in text.split(",") if w.strip()})
    except ValueError:
        raise ValueError(f"{option}: not a comma-separated list of numbers: {text!r}") from None
    if not values or any(not np.isfinite(w) or (positive and not w > 0) for w in values):
        must = "finite number > 0" if positive else "finite number"
        raise ValueError(f"{option}: every value must be a {must}: {text!r}")
    return tuple(values)


def parse_widths(text):
    """'0.1,0.25' -> (0.1, 0.25), ascending, each > 0; ValueError names what is wrong."""
    return _parse(text, "--fov-widths", True)


def parse_offsets(text):
    """'-0.05,0.1' -> (-0.05, 0.1), ascending, finite; ValueError names what is wrong."""
    return _parse(text, "--fov-offsets", False)


def run_sweep(s, widths, offsets, retry_errors=False):
    """Plan FOV at every (width, offset) on the main run's instances; returns the plans
    computed now."""
    require_main(s)
    ran = 0
    for w in widths:
        for o in offsets:
            sub = derive(
                s,
                os.path.join(SUBDIR, f"w{w:g}_o{o:g}"),
                methods=("fov",),
                fov_width_m=w,
                fov_offset_m=o,
            )
            ran += run(sub, retry_errors=retry_errors)[0]
    return ran


def load(out_dir):
    """{(width m, offset m): typed rows} of every sweep run under out_dir ({} before it)."""
    base = os.path.join(out_dir, SUBDIR)
    sweep = {}
    if not os.path.isdir(base):
        return sweep
    for name in sorted(os.listdir(base)):
        info = os.path.join(base, name, "run.json")
        if not os.path.isfile(info):
            continue
        with open(info, encoding="utf-8") as f:
            meta = json.load(f)
        rows = results_mod.read(os.path.join(base, name, "results.csv"))
        if rows and meta.get("fov_offset_m") is not None:
            sweep[(meta["fov_width_m"], meta["fov_offset_m"])] = rows
    return sweep


def moved_share(rows):
    """Share of the fruits FOV planned that were in view out of their stop's reach and were
    picked at another stop (NaN without FOV rows)."""
    fov = [r for r in rows if r["method"] == "fov" and r["fov_moved"] is not None]
    planned = sum(r["fruits_planned"] for r in fov)
    return sum(r["fov_moved"] for r in fov) / planned if planned else float("nan")


def gain_table(main_rows, sweep):
    """One dict per (width, offset): the MILP (main run) over FOV (that window) throughput
    gain on the instances both planned: median, range, how many inside the paper's band,
    FOV's stops and share of fruits moved."""
    milp = {k: ms["milp"] for k, ms in report.by_instance(main_rows).items() if "milp" in ms}
    table = []
    for w, o in sorted(sweep):
        gains, stops = [], []
        for k, ms in report.by_instance(sweep[(w, o)]).items():
            if k in milp and "fov" in ms:
                fov = ms["fov"]
                gains.append(
                    milp[k]["throughput_fruit_per_s"] / fov["throughput_fruit_per_s"] - 1.0
                )
                stops.append(fov["stops"])
        table.append(
            {
                "width_m": w,
                "offset_m": o,
                "n": len(gains),
                "median_gain": statistics.median(gains) if gains else float("nan"),
                "min_gain": min(gains, default=float("nan")),
                "max_gain": max(gains, default=float("nan")),
                "in_band": sum(report.PAPER_GAIN_LO <= g <= report.PAPER_GAIN_HI for g in gains),
                "fov_stops": statistics.median(stops) if stops else float("nan"),
                "moved_share": moved_share(sweep[(w, o)]),
            }
        )
    return table


def best_at_width(table, width_m):
    """The row of `table` at width_m where FOV does best (the smallest median gain), or None."""
    rows = [t for t in table if t["n"] and abs(t["width_m"] - width_m) < 1e-9]
    return min(rows, key=lambda t: t["median_gain"]) if rows else None


def figure(tables, out_dir, main_window=None):
    """A heat map per cost model swept ({pick_cycle: gain_table(...)}): the median gain over
    FOV by window offset (x) and width (y); main_window = (width, offset) of the main run's
    FOV, marked."""
    tables = {pc: [t for t in table if t["n"]] for pc, table in tables.items()}
    tables = {pc: rows for pc, rows in sorted(tables.items()) if rows}
    if not tables:
        return []
    fig, axes = plt.subplots(1, len(tables), figsize=(5.0 * len(tables), 3.4), squeeze=False)
    for ax, (pc, rows) in zip(axes[0], tables.items()):
        widths = sorted({t["width_m"] for t in rows})
        offsets = sorted({t["offset_m"] for t in rows})
        grid = np.full((len(widths), len(offsets)), np.nan)
        for t in rows:
            grid[widths.index(t["width_m"]), offsets.index(t["offset_m"])] = 100 * t["median_gain"]
        im = ax.imshow(grid, origin="lower", aspect="auto", cmap="viridis")
        for i in range(len(widths)):
            for j in range(len(offsets)):
                if np.isfinite(grid[i, j]):
                    ax.text(
                        j,
                        i,
                        f"{grid[i, j]:.0f}",
                        ha="center",
                        va="center",
                        fontsize=7,
                        color="white",
                    )
        if main_window is not None and main_window[0] in widths and main_window[1] in offsets:
            ax.add_patch(
                plt.Rectangle(
                    (offsets.index(main_window[1]) - 0.5, widths.index(main_window[0]) - 0.5),
                    1,
                    1,
                    fill=False,
                    edgecolor="red",
                    lw=2,
                )
            )
        ax.set_xticks(range(len(offsets)), [f"{o:g}" for o in offsets], fontsize=7)
        ax.set_yticks(range(len(widths)), [f"{w:g}" for w in widths], fontsize=7)
        ax.set_xlabel("window centre from the arm's base, outward (m)")
        ax.set_ylabel("window width (m)")
        ax.set_title(f"plan.pick_cycle = {int(pc)}", fontsize=9)
        fig.colorbar(im, ax=ax, label="median gain (%)")
    fig.tight_layout()
    return save(fig, out_dir, FIGURE_STEM)
