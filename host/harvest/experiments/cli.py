"""`python -m harvest experiments`: the paper's comparison in one command.

run       plan every (alpha, seed, method) with the planner CLI -> OUT/results.csv
cost-models
          plan the same instances in the other cost model -> OUT/pick_cycle_<0|1>/
          (the dual-arm / single-arm ratio and the gain over FOV in both)
fov-width plan FOV again at each --fov-widths x --fov-offsets on the same instances, in
          each cost model planned -> OUT/fov_width/, OUT/pick_cycle_<0|1>/fov_width/ (the
          MILP's gain over FOV as a function of where FOV's windows lie and how wide)
variants  plan the same instances, every method, under the set-up's other readings:
          the arm bases side by side (mount.base_spacing = 0) -> OUT/mount_side_by_side/,
          the pick costs flat over the stops (plan.pick_cost_flat = 1) -> OUT/flat_costs/
plots     box plots (stops, throughput, runtime) and a top view of one plan
analysis  the cost-G and coverage figures from cost tables made by costgen
report    OUT/report.md: our numbers beside each claim of the paper
all       run, cost-models, fov-width, variants, plots, analysis and report (the default)
"""

import argparse
import json
import math
import os
import platform
import sys

from .. import resources
from ..cmdline import EXIT_FAILURE, EXIT_USAGE, Parser, error, os_error
from ..scenario import fruit_map
from ..scenario.config import Config, ConfigError, Row, default_config_path
from . import (
    analysis_tables,
    box_plots,
    cost_analysis,
    cost_models,
    cost_table,
    plan_file,
    plan_view,
    report,
    sensitivity,
    variants,
)
from . import results as results_mod
from .binaries import COSTGEN, PLANNER, MissingProgram, find
from .runner import (
    METHODS,
    PAPER_ALPHAS,
    PAPER_SEEDS,
    QUICK_ALPHAS,
    QUICK_SEEDS,
    RunError,
    RunInputError,
    Settings,
    run,
)

STEPS = ("run", "cost-models", "fov-width", "variants", "plots", "analysis", "report", "all")
PROG = "harvest-stack experiments"
EXIT_INTERRUPTED = 130  # as a shell reports SIGINT: the run resumes when started again


def build_parser():
    p = Parser(
        prog=PROG,
        description="Reproduce the paper's comparison (FOV, Serial, MILP) on the real planner: "
        "instances, a resumable runner, plots, analysis figures and a report.",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=__doc__.split("\n", 2)[2]
        + "\nAn interrupted run (Ctrl-C, kill) resumes where it stopped when run again with "
        "the same --out:\nfinished rows are never recomputed.",
        exit_codes=(f"{EXIT_INTERRUPTED} interrupted: run again with the same --out to resume",),
    )
    p.add_argument("step", nargs="?", choices=STEPS, default="all")
    p.add_argument("--out", required=True, help="output directory (created; reused to resume)")
    p.add_argument(
        "--config", default=default_config_path(), help="harvest config (default: %(default)s)"
    )
    p.add_argument(
        "--build-dir",
        default=None,
        help="build directory with planner/harvest-plan and tools/costgen (default: $HV_BUILD_DIR)",
    )
    p.add_argument("--planner", default=None, help="path of harvest-plan (overrides --build-dir)")
    p.add_argument("--costgen", default=None, help="path of costgen (overrides --build-dir)")
    p.add_argument(
        "--quick",
        action="store_true",
        help=f"quick set: alphas {', '.join(f'{a:g}' for a in QUICK_ALPHAS)} x "
        f"{len(QUICK_SEEDS)} seeds (the tests use it)",
    )
    p.add_argument(
        "--alphas",
        default=None,
        help="comma-separated alphas (default: the paper's 0.25,0.4,1,2.5,4)",
    )
    p.add_argument("--seeds", type=int, default=None, help="seeds 0..N-1 (default: 10)")
    p.add_argument("--methods", default=",".join(METHODS), help="default: %(default)s")
    p.add_argument(
        "--time-limit",
        type=float,
        default=None,
        help="planner --time-limit in s (default: the planner's own)",
    )
    p.add_argument(
        "--fov-width",
        type=float,
        default=None,
        help="planner --fov-width in m (default: fov.width of the config)",
    )
    p.add_argument(
        "--fov-offset",
        type=float,
        default=None,
        help="planner --fov-offset in m (default: fov.offset of the config)",
    )
    p.add_argument(
        "--fov-widths",
        default=",".join(f"{w:g}" for w in sensitivity.DEFAULT_WIDTHS_M),
        help="fov-width step: FOV window widths in m, comma-separated (default: %(default)s)",
    )
    p.add_argument(
        "--fov-offsets",
        default=",".join(f"{o:g}" for o in sensitivity.DEFAULT_OFFSETS_M),
        help="fov-width step: FOV window centres from the arm's base along the row, outward, "
        "in m, comma-separated; a list starting with a minus sign needs '=' "
        "(--fov-offsets=-0.1,0) (default: %(default)s)",
    )
    p.add_argument(
        "--jobs",
        type=int,
        default=1,
        help="planners run at once (default 1: the MILP runtime is benchmarked)",
    )
    p.add_argument(
        "--distribution",
        choices=("uniform", "clustered", "gradient"),
        default="uniform",
        help="fruit distribution of the instances "
        "(default: the paper's uniform rows; see 'python -m harvest scenario --help')",
    )
    p.add_argument(
        "--stops-beyond-ends",
        action="store_true",
        help="let the vehicle stop beyond the row's ends as far as an arm reaches "
        "into the row (the product's default, row.stops_beyond_ends = 1); "
        "without it the planner gets the paper's N = 201 candidate stops over "
        "the row",
    )
    p.add_argument(
        "--pick-cycle",
        action="store_true",
        help="plan in the robot's time: a pick costs its whole cycle (2 t(home -> "
        "fruit) + cut + release), a stop the drive's v/a (the product's "
        "default, plan.pick_cycle = 1); without it the paper's one-way G and "
        "tau",
    )
    p.add_argument(
        "--retry-errors",
        action="store_true",
        help="run again the rows whose plan failed (they are kept as final otherwise)",
    )
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    return p


def _settings(args, need_planner):
    alphas = QUICK_ALPHAS if args.quick else PAPER_ALPHAS
    if args.alphas:
        try:
            alphas = tuple(float(a) for a in args.alphas.split(","))
        except ValueError:
            raise RunInputError(
                f"--alphas: not a comma-separated list of numbers: {args.alphas!r}"
            ) from None
    seeds = QUICK_SEEDS if args.quick else PAPER_SEEDS
    if args.seeds is not None:
        seeds = tuple(range(args.seeds))
    methods = tuple(m for m in args.methods.split(",") if m)
    unknown = [m for m in methods if m not in METHODS]
    if unknown or not methods:
        raise RunInputError(
            f"--methods: unknown {', '.join(unknown) or '(empty)'}; use {', '.join(METHODS)}"
        )
    if any(a < 0 or not math.isfinite(a) for a in alphas) or not seeds:
        raise RunInputError("--alphas must be >= 0 and --seeds >= 1")
    if args.jobs < 1:
        raise RunInputError("--jobs must be >= 1")
    if args.time_limit is not None and not args.time_limit > 0:
        raise RunInputError("--time-limit must be > 0")
    try:
        sensitivity.parse_widths(args.fov_widths)
        sensitivity.parse_offsets(args.fov_offsets)
    except ValueError as e:
        raise RunInputError(str(e)) from None
    planner = find(PLANNER, args.planner, args.build_dir) if need_planner else ""
    costgen = find(COSTGEN, args.costgen, args.build_dir) if need_planner else ""
    return Settings(
        config=os.path.abspath(args.config),
        out_dir=os.path.abspath(args.out),
        planner=planner,
        costgen=costgen,
        alphas=alphas,
        seeds=seeds,
        methods=methods,
        distribution=args.distribution,
        time_limit_s=args.time_limit,
        fov_width_m=args.fov_width,
        fov_offset_m=args.fov_offset,
        jobs=args.jobs,
        stops_beyond_ends=args.stops_beyond_ends,
        pick_cycle=args.pick_cycle,
        progress=not args.no_progress,
    )


def _rows(out):
    path = os.path.join(out, "results.csv")
    rows = results_mod.read(path)
    if not rows:
        raise RunInputError(f"{path}: no results yet: run 'experiments run --out {out}' first")
    return rows


def _main_window(out):
    """(width, offset) in m of the main run's FOV windows: its options, else its config's."""
    info = _run_info(out)
    cfg = Config.load(info.get("config") or default_config_path())
    width = info.get("fov_width_m")
    offset = info.get("fov_offset_m")
    return (
        cfg.positive("fov.width") if width is None else width,
        cfg.float("fov.offset") if offset is None else offset,
    )


def _worst_fov(out, pick_cycle):
    """(label, median gain over FOV) of FOV's worst window placement at the main run's
    width in the main cost model, None before the fov-width run."""
    width, _ = _main_window(out)
    table = _width_tables(out).get(pick_cycle, [])
    at = [t for t in table if t["n"] and abs(t["width_m"] - width) < 1e-9]
    if not at:
        return None
    worst = max(at, key=lambda t: t["median_gain"])
    return f"offset {worst['offset_m']:g} m at width {width:g} m", worst["median_gain"]


def _pick_plan(out, rows):
    """The plan to draw: MILP at the alpha nearest 1, lowest seed (the balanced case)."""
    cands = [r for r in rows if r["method"] == "milp" and r["plan"] and r["status"] != "error"]
    if not cands:
        cands = [r for r in rows if r["plan"] and r["status"] != "error"]
    if not cands:
        return None
    return min(cands, key=lambda r: (abs(r["alpha"] - 1.0), r["seed"]))


def _width_tables(out):
    """{pick_cycle: gain by FOV window} of each cost model planned and swept."""
    return {
        pc: sensitivity.gain_table(
            results_mod.read(os.path.join(d, "results.csv")), sensitivity.load(d)
        )
        for pc, d in cost_models.dirs(out).items()
    }


def do_plots(args):
    out = os.path.abspath(args.out)
    rows = _rows(out)
    fig_dir = os.path.join(out, "figures")
    paths = box_plots.write_all(rows, fig_dir)
    paths += sensitivity.figure(_width_tables(out), fig_dir, _main_window(out))
    r = _pick_plan(out, rows)
    if r is not None:
        # the plan's own fruit map and config, wherever they were when it was planned
        plan_path = os.path.join(out, r["plan"])
        plan = plan_file.load(plan_path)
        fruits = fruit_map.read(plan_file.input_path(plan_path, plan, "fruit_map"))
        bases = Row(Config.load(plan_file.input_path(plan_path, plan, "config"))).arm_bases()
        paths += plan_view.write(
            plan,
            fruits,
            bases,
            fig_dir,
            "plan_top_view",
            title=f"{r['method'].upper()} plan, alpha {r['alpha']:g}, seed "
            f"{r['seed']}: {r['stops']} stops, makespan "
            f"{r['makespan_s']:.1f} s, status {r['status']}",
        )
    print(f"experiments: {len(paths)} figure files in {fig_dir}")
    return paths


def do_analysis(args, row_cfg):
    out = os.path.abspath(args.out)
    costgen = find(COSTGEN, args.costgen, args.build_dir)
    lim_path, free_path = analysis_tables.ensure(costgen, args.config, row_cfg, out, sys.stderr)
    limited, free = cost_table.load(lim_path), cost_table.load(free_path)
    base_xy = (limited.base[0], limited.base[1])
    fig_dir = os.path.join(out, "figures")
    paths = cost_analysis.write_figures(
        limited, free, row_cfg, row_cfg.yaw_max_rad, base_xy, fig_dir
    )
    g_l = cost_analysis.z_slice(limited)[:, cost_analysis.yaw_index(limited, 0.0), :]
    g_f = cost_analysis.z_slice(free)[:, cost_analysis.yaw_index(free, 0.0), :]
    numbers = {
        "coverage_m2": cost_analysis.coverage_numbers(limited, free, row_cfg, row_cfg.yaw_max_rad),
        "roughness_s": {
            "limited": cost_analysis.roughness(g_l),
            "free": cost_analysis.roughness(g_f),
        },
        "z_m": limited.axes["z"].origin,
    }
    with open(os.path.join(out, "analysis.json"), "w", encoding="utf-8") as f:
        json.dump(numbers, f, indent=1)
    print(f"experiments: analysis figures in {fig_dir}")
    return paths


_DIST_TEXT = {
    "uniform": "the paper's uniform rows",
    "clustered": "clustered rows (trusses; not the paper's data)",
    "gradient": "rows with a ripeness gradient (not the paper's data)",
}


def _show_path(path):
    """A path relative to the source tree when inside it (the report is read there)."""
    src = resources.source_root()
    rel = os.path.relpath(path, src) if src else ".."
    return path if rel.startswith("..") else rel


def _run_info(out):
    """OUT/run.json (what the run was started with), {} before a run."""
    path = os.path.join(out, "run.json")
    if not os.path.exists(path):
        return {}
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def do_report(args, s, row_cfg):
    out = os.path.abspath(args.out)
    rows = _rows(out)
    fig_dir = os.path.join(out, "figures")
    figures = {}
    info = _run_info(out)
    pick_cycle = bool(info.get("pick_cycle"))
    costs = f" (costs: {report.cost_model_text(pick_cycle)})"
    table_costs = " (costs: none, the cost table's G = t(home -> fruit) itself)"
    captions = {
        "boxplot_stops": "Number of stops by alpha and method" + costs,
        "boxplot_throughput": "Throughput by alpha and method" + costs,
        "boxplot_runtime": "Planner runtime by alpha and method" + costs,
        sensitivity.FIGURE_STEM: "Median MILP throughput gain over FOV (%) by FOV window "
        "placement and width, the main run's window framed (costs: per panel, "
        "plan.pick_cycle = 0 the paper's, = 1 the robot's pick cycle)",
        "plan_top_view": "Top view of one plan: fruits, stops, arms, busy and idle time" + costs,
        "cost_G_joint3": "Cost G with joint 3 unlimited and limited" + table_costs,
        "coverage_pick_modes": "Coverage per pick mode; single-sided coverage" + table_costs,
    }
    for stem, cap in captions.items():
        p = os.path.join(fig_dir, stem + ".png")
        if os.path.exists(p):
            figures[cap] = p
    tl = "the planner's default"
    build = ""
    if info:
        if info.get("time_limit_s") is not None:
            tl = f"{info['time_limit_s']:g} s"
        b = info.get("planner_build") or {}
        if b:
            sanitized = b.get("HV_SANITIZE", "OFF").upper() in ("ON", "1", "TRUE", "YES")
            build = f"; planner build {b.get('CMAKE_BUILD_TYPE') or '?'}" + (
                ", **with ASan+UBSan: runtimes are inflated by the sanitizers and not "
                "comparable with the paper's**"
                if sanitized
                else ", no sanitizers"
            )
    alphas = sorted({r["alpha"] for r in rows})
    seeds = sorted({r["seed"] for r in rows})
    settings_text = (
        f"- Instances: {_DIST_TEXT.get(rows[0]['distribution'], rows[0]['distribution'])}, "
        f"m^L = {rows[0]['n_left']}, alpha in "
        f"{{{', '.join(f'{a:g}' for a in alphas)}}}, seeds {seeds[0]}..{seeds[-1]} "
        f"({len(seeds)} per alpha); config `{_show_path(s.config)}`, "
        + (
            "candidate stops beyond the row's ends as far as an arm reaches "
            "(row.stops_beyond_ends = 1)"
            if info.get("stops_beyond_ends")
            else "the paper's candidate stops (N = 201 on a 2 m row): stop p is the vehicle at "
            "y = p x grid.step along the row, its arm bases half mount.base_spacing ahead of "
            "and behind it (row.stops_beyond_ends = 0)"
        )
        + "; costs of the main run: "
        + report.cost_model_text(pick_cycle)
        + ".\n"
        f"- Planner: `harvest-plan` (GLPK), MILP time limit {tl}{build}; {os.cpu_count()} CPU(s), "
        f"{platform.machine()}, Python {platform.python_version()}.\n"
        "- Paper: Gurobi on an AMD 7950, 128 GB."
    )
    reasons = {}
    for r in rows:
        if r["method"] == "milp" and r["plan"] and r["status"] != "error":
            for u in plan_file.load(os.path.join(out, r["plan"])).get("unreachable", []):
                reasons[u.get("reason", "?")] = reasons.get(u.get("reason", "?"), 0) + 1
    fov_width = report.fov_window_section(_width_tables(out), pick_cycle, _main_window(out))
    models_rows = cost_models.load(out)
    models = {pc: cost_models.ratios(rs) for pc, rs in models_rows.items()}
    variant_rows = variants.load(out)
    path = report.write(
        os.path.join(out, "report.md"),
        rows,
        settings_text,
        figures,
        report.analysis_section(os.path.join(out, "analysis.json")),
        unreachable_reasons=reasons,
        pick_cycle=pick_cycle,
        fov_width=fov_width,
        cost_models=report.cost_models_section(models, pick_cycle),
        variants=variants.section(rows, row_cfg.base_spacing_m, variant_rows),
        causes=variants.causes_section(
            rows, variant_rows, models_rows.get(not pick_cycle), _worst_fov(out, pick_cycle)
        ),
    )
    print(f"experiments: report {path}")
    return path


def main(argv):
    args = build_parser().parse_args(argv)
    try:
        row_cfg = Row(Config.load(args.config))
        need_planner = args.step in ("run", "fov-width", "cost-models", "variants", "all")
        s = _settings(args, need_planner)
        os.makedirs(s.out_dir, exist_ok=True)
        if args.step in ("run", "all"):
            ran, total = run(s, retry_errors=args.retry_errors)
            print(
                f"experiments: {ran} plan(s) computed now, {total} in "
                f"{os.path.join(s.out_dir, 'results.csv')}"
            )
        if args.step in ("cost-models", "all"):
            ran = cost_models.run_other(s, retry_errors=args.retry_errors)
            print(
                f"experiments: {ran} plan(s) computed now in "
                f"{os.path.join(s.out_dir, cost_models.subdir(not s.pick_cycle))}"
            )
        if args.step in ("fov-width", "all"):
            for ss in cost_models.planned(s):
                ran = sensitivity.run_sweep(
                    ss,
                    sensitivity.parse_widths(args.fov_widths),
                    sensitivity.parse_offsets(args.fov_offsets),
                    retry_errors=args.retry_errors,
                )
                print(
                    f"experiments: {ran} FOV plan(s) computed now in "
                    f"{os.path.join(ss.out_dir, sensitivity.SUBDIR)}"
                )
        if args.step in ("variants", "all"):
            ran = variants.run_all(s, retry_errors=args.retry_errors)
            print(
                f"experiments: {ran} plan(s) computed now in "
                + ", ".join(os.path.join(s.out_dir, v.subdir) for v in variants.VARIANTS)
            )
        if args.step in ("plots", "all"):
            do_plots(args)
        if args.step in ("analysis", "all"):
            do_analysis(args, row_cfg)
        if args.step in ("report", "all"):
            do_report(args, s, row_cfg)
    except KeyboardInterrupt:
        return EXIT_INTERRUPTED
    except RunInputError as e:
        error(PROG, str(e))
        return EXIT_USAGE
    except (RunError, OSError) as e:
        error(PROG, os_error(e) if isinstance(e, OSError) else str(e))
        return EXIT_FAILURE
    except (
        ConfigError,
        MissingProgram,
        results_mod.ResultsError,
        plan_file.PlanError,
        cost_table.CostTableError,
        fruit_map.FruitMapError,
    ) as e:  # an input file, or a program the options name
        error(PROG, str(e))
        return EXIT_USAGE
    return 0
