"""A Gantt chart of both arms, planned against actual, from an executor telemetry log.

Rows (top to bottom): left planned, left actual, right planned, right actual. Each bar is
one pick cycle (planned: the executor's expected cycle; actual: first approach -> outcome,
coloured by outcome). Shaded bands are the stops (planned above the axis labels, actual
arrivals as dashed lines), numbered in driving order.
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

COLORS = {"planned": "#9ecae1", "picked": "#31a354", "failed": "#de2d26", "skipped": "#969696"}


def plot(tl, out_path, title=None):
    rows = [
        ("left planned", 0, "planned"),
        ("left actual", 0, "actual"),
        ("right planned", 1, "planned"),
        ("right actual", 1, "actual"),
    ]
    ypos = {(side, kind): len(rows) - 1 - i for i, (_, side, kind) in enumerate(rows)}
    fig, ax = plt.subplots(figsize=(14, 4.6))
    for p, arrive, leave in tl.planned_stops:
        ax.axvspan(arrive, leave, color="#f0f0f0", zorder=0)
        ax.text(
            (arrive + leave) / 2,
            len(rows) - 0.35,
            str(p + 1),
            ha="center",
            va="bottom",
            fontsize=7,
            color="#636363",
        )
    for p, t in sorted(tl.actual_stops.items()):
        ax.axvline(t, color="#636363", lw=0.6, ls="--", zorder=1)
    for side, p, fid, start, end in tl.planned:
        ax.barh(
            ypos[(side, "planned")],
            end - start,
            left=start,
            height=0.6,
            color=COLORS["planned"],
            edgecolor="white",
            lw=0.4,
        )
    for a in tl.actual.values():
        if a["start"] is None or a["end"] is None:
            continue
        ax.barh(
            ypos[(a["side"], "actual")],
            max(a["end"] - a["start"], 0.05),
            left=a["start"],
            height=0.6,
            color=COLORS.get(a["outcome"], "#fd8d3c"),
            edgecolor="white",
            lw=0.4,
        )
    for t, side, fid, reason in tl.faults:
        ax.plot([t], [ypos[(side, "actual")] + 0.38], marker="v", color="#de2d26", ms=4)
    ax.set_yticks([ypos[(s, k)] for _, s, k in rows])
    ax.set_yticklabels([name for name, _, _ in rows])
    ax.set_xlabel("time from the row start (s, simulated)")
    ax.set_ylim(-0.6, len(rows) - 0.1)
    s = summary_line(tl)
    ax.set_title(title or s, fontsize=9)
    handles = [plt.Rectangle((0, 0), 1, 1, color=c) for c in COLORS.values()]
    ax.legend(
        handles,
        list(COLORS.keys()),
        loc="upper center",
        bbox_to_anchor=(0.5, -0.16),
        fontsize=7,
        ncol=4,
        frameon=False,
    )
    fig.tight_layout()
    fig.savefig(out_path)
    plt.close(fig)
    return out_path


def summary_line(tl):
    picked = len(tl.fruits("picked"))
    planned = tl.plan.n_picks if tl.plan else "?"
    exp = f"{tl.plan.expected_makespan_s:.1f}" if tl.plan else "?"
    exe = f"{tl.final.executed_s:.1f}" if tl.final else "?"
    return f"picked {picked}/{planned}; executed {exe} s vs expected {exp} s"
