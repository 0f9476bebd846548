"""The paper's Fig. 7: number of stops, throughput and runtime by alpha and method."""

from .figures import METHOD_COLORS, METHOD_LABELS, plt, save

METRICS = (
    ("stops", "Number of stops", "boxplot_stops", False),
    ("throughput_fruit_per_s", "Throughput (fruit/s)", "boxplot_throughput", False),
    ("runtime_s", "Planner runtime (s)", "boxplot_runtime", True),
)


def _groups(rows, metric):
    """{alpha: {method: [values]}} over rows that produced a plan."""
    out = {}
    for r in rows:
        if r["status"] == "error" or r[metric] is None:
            continue
        out.setdefault(r["alpha"], {}).setdefault(r["method"], []).append(r[metric])
    return out


def box_plot(rows, metric, ylabel, log_y=False, methods=("fov", "serial", "milp")):
    groups = _groups(rows, metric)
    alphas = sorted(groups)
    fig, ax = plt.subplots(figsize=(7.0, 3.6))
    width = 0.8 / len(methods)
    for j, m in enumerate(methods):
        data, pos = [], []
        for i, a in enumerate(alphas):
            vals = groups[a].get(m)
            if vals:
                data.append(vals)
                pos.append(i + (j - (len(methods) - 1) / 2.0) * width)
        if not data:
            continue
        bp = ax.boxplot(
            data,
            positions=pos,
            widths=width * 0.85,
            patch_artist=True,
            manage_ticks=False,
            medianprops={"color": "black"},
        )
        for box in bp["boxes"]:
            box.set_facecolor(METHOD_COLORS[m])
        ax.plot([], [], "s", color=METHOD_COLORS[m], label=METHOD_LABELS[m])
    ax.set_xticks(range(len(alphas)))
    ax.set_xticklabels([f"{a:g}" for a in alphas])
    ax.set_xlabel(r"$\alpha$ = right / left fruits")
    ax.set_ylabel(ylabel)
    if log_y:
        ax.set_yscale("log")
    ax.grid(axis="y", alpha=0.3)
    ax.legend(ncol=len(methods), fontsize=8, loc="best")
    return fig


def write_all(rows, out_dir):
    paths = []
    for metric, label, stem, log_y in METRICS:
        paths += save(box_plot(rows, metric, label, log_y), out_dir, stem)
    return paths
