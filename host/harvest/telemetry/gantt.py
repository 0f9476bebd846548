"""A Gantt chart of the vehicle and both arms, planned against actual, from an executor
telemetry log.

Lanes (top to bottom): vehicle planned, vehicle actual, left planned, left actual, right
planned, right actual. An arm's bar is one pick cycle (planned: the executor's expected
cycle; actual: first approach -> outcome, coloured by outcome); the vehicle's are its drives
and, actual, the time it stood (timeline.py). Shaded bands are the planned stops, numbered
in driving order; actual arrivals are dashed lines. Faults are marked where and when they
happened, with their name: an arm's on its actual lane, the executor's halt (safe, or a
controlled stop) as a line across every lane.
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)
from matplotlib.lines import Line2D  # noqa: E402

from . import timeline  # noqa: E402

COLORS = {"planned": "#9ecae1", "picked": "#31a354", "failed": "#de2d26", "skipped": "#969696"}
VEHICLE = {"drive": "#756bb1", "stopped": "#dadaeb"}
FAULT = "#de2d26"
HALT = {"safe": FAULT, "stopped": "#e6550d"}  # latched stop, controlled stop
LANES = [
    ("vehicle planned", "vehicle", "planned"),
    ("vehicle actual", "vehicle", "actual"),
    ("left planned", 0, "planned"),
    ("left actual", 0, "actual"),
    ("right planned", 1, "planned"),
    ("right actual", 1, "actual"),
]


def _bar(ax, y, start, end, color):
    ax.barh(y, end - start, left=start, height=0.6, color=color, edgecolor="white", lw=0.4)


def figure(tl, title=None):
    """The chart of Timeline `tl` as a matplotlib figure (the caller closes it)."""
    ypos = {(who, kind): len(LANES) - 1 - i for i, (_, who, kind) in enumerate(LANES)}
    fig, ax = plt.subplots(figsize=(14, 5.6))
    for p, arrive, leave in tl.planned_stops:
        ax.axvspan(arrive, leave, color="#f0f0f0", zorder=0)
        ax.text(
            (arrive + leave) / 2,
            len(LANES) - 0.35,
            str(p + 1),
            ha="center",
            va="bottom",
            fontsize=7,
            color="#636363",
        )
    for p, t in sorted(tl.actual_stops.items()):
        ax.axvline(t, color="#636363", lw=0.6, ls="--", zorder=1)
    for start, end in timeline.planned_drives(tl):
        _bar(ax, ypos[("vehicle", "planned")], start, end, COLORS["planned"])
    for start, end, kind in tl.vehicle:
        _bar(ax, ypos[("vehicle", "actual")], start, end, VEHICLE[kind])
    for side, p, fid, start, end in tl.planned:
        _bar(ax, ypos[(side, "planned")], start, end, COLORS["planned"])
    for a in tl.actual.values():
        if a["start"] is None or a["end"] is None:
            continue
        end = a["start"] + max(a["end"] - a["start"], 0.05)
        _bar(ax, ypos[(a["side"], "actual")], a["start"], end, COLORS.get(a["outcome"], "#fd8d3c"))
    for t, side, fid, reason in tl.faults:
        y = ypos[(side, "actual")] + 0.38
        ax.plot([t], [y], marker="v", color=FAULT, ms=6, zorder=4)
        ax.text(t, y + 0.06, f" {reason}", fontsize=6, color=FAULT, va="bottom", zorder=4)
    for t, phase, reason in tl.halts:
        c = HALT[phase]
        ax.axvline(t, color=c, lw=1.2, zorder=4)
        label = f"{phase}: {reason}" if phase == "safe" else phase
        ax.text(t, len(LANES) - 0.35, f" {label}", fontsize=7, color=c, va="bottom", zorder=4)
    ax.set_yticks([ypos[(w, k)] for _, w, k in LANES])
    ax.set_yticklabels([name for name, _, _ in LANES])
    ax.set_xlabel("time from the row start (s, simulated)")
    ax.set_ylim(-0.6, len(LANES) - 0.1)
    ax.set_title(title or summary_line(tl), fontsize=9)
    handles = [plt.Rectangle((0, 0), 1, 1, color=c) for c in COLORS.values()]
    handles += [plt.Rectangle((0, 0), 1, 1, color=c) for c in VEHICLE.values()]
    handles += [
        Line2D([], [], color=FAULT, marker="v", ls="none"),
        Line2D([], [], color=HALT["safe"]),
        Line2D([], [], color=HALT["stopped"]),
    ]
    labels = list(COLORS) + ["vehicle drives", "vehicle stands"]
    labels += ["arm fault", "safe (latched)", "controlled stop"]
    ax.legend(
        handles,
        labels,
        loc="upper center",
        bbox_to_anchor=(0.5, -0.13),
        fontsize=7,
        ncol=len(labels),
        frameon=False,
    )
    fig.tight_layout()
    return fig


def plot(tl, out_path, title=None):
    fig = figure(tl, title)
    try:
        fig.savefig(out_path)
    finally:
        plt.close(fig)
    return out_path


def summary_line(tl):
    picked = len(tl.fruits("picked"))
    planned = tl.plan.n_picks if tl.plan else "?"
    exp = f"{tl.plan.expected_makespan_s:.1f}" if tl.plan else "?"
    exe = f"{tl.final.executed_s:.1f}" if tl.final else "?"
    return f"picked {picked}/{planned}; executed {exe} s vs expected {exp} s"
