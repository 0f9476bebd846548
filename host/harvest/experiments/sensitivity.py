"""The FOV baseline's window width: the MILP's throughput gain over FOV as a function of it.

The paper does not give its camera window's width (the planner's default is 0.25 m), and
the gain over FOV depends on it. The MILP does not depend on the width, so its plans are
the main run's; only FOV is planned again, once per width, in OUT/fov_width/w<width>/ (a
derived run: same instances, tables and cost model as the main run).
"""

import json
import os
import statistics

from . import report
from . import results as results_mod
from .figures import METHOD_COLORS, plt, save
from .runner import run
from .subruns import derive, require_main

SUBDIR = "fov_width"
# From a tenth of a stop's reach to the whole 2 m row in one window.
DEFAULT_WIDTHS_M = (0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5, 0.6, 0.8, 1.0, 1.5, 2.0)
FIGURE_STEM = "fov_width_gain"


def parse_widths(text):
    """'0.1,0.25' -> (0.1, 0.25), ascending, each > 0; ValueError names what is wrong."""
    try:
        widths = sorted({float(w) for w in text.split(",") if w.strip()})
    except ValueError:
        raise ValueError(f"--fov-widths: not a comma-separated list of numbers: {text!r}") from None
    if not widths or any(not w > 0 or w == float("inf") for w in widths):
        raise ValueError(f"--fov-widths: every width must be a finite number > 0: {text!r}")
    return tuple(widths)


def run_sweep(s, widths, retry_errors=False):
    """Plan FOV at every width on the main run's instances; returns the plans computed now."""
    require_main(s)
    ran = 0
    for w in widths:
        sub = derive(s, os.path.join(SUBDIR, f"w{w:g}"), methods=("fov",), fov_width_m=w)
        ran += run(sub, retry_errors=retry_errors)[0]
    return ran


def load(out_dir):
    """{width m: typed rows} of every sweep run under out_dir ({} before the sweep)."""
    base = os.path.join(out_dir, SUBDIR)
    sweep = {}
    if not os.path.isdir(base):
        return sweep
    for name in sorted(os.listdir(base)):
        info = os.path.join(base, name, "run.json")
        if not os.path.isfile(info):
            continue
        with open(info, encoding="utf-8") as f:
            width = json.load(f)["fov_width_m"]
        rows = results_mod.read(os.path.join(base, name, "results.csv"))
        if rows:
            sweep[width] = rows
    return sweep


def gain_by_width(main_rows, sweep):
    """One dict per width: the MILP (main run) over FOV (that width) throughput gain on the
    instances both planned: median, range, how many inside the paper's band, FOV's stops."""
    milp = {k: ms["milp"] for k, ms in report.by_instance(main_rows).items() if "milp" in ms}
    table = []
    for w in sorted(sweep):
        gains, stops = [], []
        for k, ms in report.by_instance(sweep[w]).items():
            if k in milp and "fov" in ms:
                fov = ms["fov"]
                gains.append(
                    milp[k]["throughput_fruit_per_s"] / fov["throughput_fruit_per_s"] - 1.0
                )
                stops.append(fov["stops"])
        table.append(
            {
                "width_m": w,
                "n": len(gains),
                "median_gain": statistics.median(gains) if gains else float("nan"),
                "min_gain": min(gains, default=float("nan")),
                "max_gain": max(gains, default=float("nan")),
                "in_band": sum(report.PAPER_GAIN_LO <= g <= report.PAPER_GAIN_HI for g in gains),
                "fov_stops": statistics.median(stops) if stops else float("nan"),
            }
        )
    return table


def figure(tables, out_dir, default_width_m=None):
    """Median gain (and its range) against the width per cost model swept
    ({pick_cycle: gain_by_width(...)}), the paper's band shaded."""
    tables = {pc: [t for t in table if t["n"]] for pc, table in tables.items()}
    tables = {pc: rows for pc, rows in tables.items() if rows}
    if not tables:
        return []
    fig, ax = plt.subplots(figsize=(6.0, 3.4))
    ax.axhspan(
        100 * report.PAPER_GAIN_LO,
        100 * report.PAPER_GAIN_HI,
        color="#cccccc",
        alpha=0.6,
        label="paper's band",
    )
    for pc, rows in sorted(tables.items()):
        color = METHOD_COLORS["milp" if pc else "serial"]
        w = [t["width_m"] for t in rows]
        ax.fill_between(
            w,
            [100 * t["min_gain"] for t in rows],
            [100 * t["max_gain"] for t in rows],
            color=color,
            alpha=0.15,
        )
        ax.plot(
            w,
            [100 * t["median_gain"] for t in rows],
            "o-",
            color=color,
            ms=3,
            label=f"median, plan.pick_cycle = {int(pc)} (shaded: range)",
        )
    if default_width_m is not None:
        ax.axvline(default_width_m, color="black", ls=":", lw=1, label="main run's width")
    ax.set_xlabel("FOV window width (m)")
    ax.set_ylabel("MILP throughput gain over FOV (%)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    return save(fig, out_dir, FIGURE_STEM)
