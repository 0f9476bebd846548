"""Top view of one plan: fruits, stops, which arm picks what, and each stop's idle time."""

import numpy as np
from matplotlib.lines import Line2D

from .figures import plt, save

# a legend to the right of its axes, outside them (save() crops to what is drawn)
OUTSIDE = {"loc": "upper left", "bbox_to_anchor": (1.01, 1.0), "fontsize": 8, "frameon": False}


def plan_figure(plan, fruits, bases, title=""):
    """plan: the planner's JSON; fruits: the map's Fruit list (unpicked ones stay grey);
    bases: where the config puts the arm bases, Row.arm_bases() of scenario.config.

    Each picked fruit is joined to the arm base that picks it, coloured by stop.
    """
    stops = plan["stops"]
    fig, (top, bars) = plt.subplots(
        2, 1, figsize=(10.0, 6.0), sharex=True, gridspec_kw={"height_ratios": [2.2, 1.0]}
    )
    cmap = plt.get_cmap("tab10")
    picked = set()
    for k, st in enumerate(stops):
        c = cmap(k % 10)
        y = st["y_m"]
        top.axvline(y, color=c, lw=0.8, alpha=0.5)
        top.plot([y], [0.0], marker="v", color=c, ms=8)
        for arm in ("left", "right"):
            dy, bx = bases[arm]
            if st.get(arm):
                top.plot([y + dy], [bx], marker="^", color=c, ms=6)
            for f in st.get(arm, []):
                picked.add(str(f["id"]))
                top.plot([y + dy, f["y"]], [bx, f["x"]], color=c, lw=0.6, alpha=0.6)
                top.plot(
                    [f["y"]],
                    [f["x"]],
                    linestyle="none",
                    color=c,
                    ms=4,
                    marker="o" if arm == "left" else "s",
                )
    rest = [f for f in fruits if f.id not in picked]
    if rest:
        top.plot([f.y for f in rest], [f.x for f in rest], "x", color="grey", ms=5)
    top.axhline(0.0, color="black", lw=0.5)
    top.set_ylabel("x (m): left < 0 < right")
    top.set_title(
        title
        or f"{plan.get('method', '?').upper()} plan: "
        f"{len(stops)} stops, makespan {plan['totals']['makespan_s']:.1f} s"
    )
    # the key beside the axes, where it covers no fruit, base or stop (colours are stops)
    key = [
        ("o", "left arm's fruit"),
        ("s", "right arm's fruit"),
        ("^", "arm base"),
        ("v", "stop"),
        ("x", "not picked"),
    ]
    handles = [
        Line2D([], [], marker=m, ls="none", color="grey" if m == "x" else "#404040") for m, _ in key
    ]
    top.legend(handles, [t for _, t in key], **OUTSIDE)
    ys = np.array([st["y_m"] for st in stops])
    cl = np.array([st.get("C_left_s", 0.0) for st in stops])
    cr = np.array([st.get("C_right_s", 0.0) for st in stops])
    il = np.array([st.get("idle_left_s", 0.0) for st in stops])
    ir = np.array([st.get("idle_right_s", 0.0) for st in stops])
    w = 0.03
    bars.bar(ys - w / 2, cl, w, color="#0072b2", label="left arm busy")
    bars.bar(
        ys - w / 2, il, w, bottom=cl, color="#0072b2", alpha=0.25, hatch="//", label="left arm idle"
    )
    bars.bar(ys + w / 2, cr, w, color="#d55e00", label="right arm busy")
    bars.bar(
        ys + w / 2,
        ir,
        w,
        bottom=cr,
        color="#d55e00",
        alpha=0.25,
        hatch="//",
        label="right arm idle",
    )
    bars.set_ylim(0.0, 1.15 * max(1.0, float(np.max(np.maximum(cl + il, cr + ir), initial=0.0))))
    bars.set_xlabel("y along the row (m)")
    bars.set_ylabel("time at stop (s)")
    bars.legend(**OUTSIDE)
    bars.grid(axis="y", alpha=0.3)
    return fig


def write(plan, fruits, bases, out_dir, stem, title=""):
    return save(plan_figure(plan, fruits, bases, title), out_dir, stem)
