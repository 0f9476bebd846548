"""`experiments fov-width`, `cost-models` and `variants`: runs derived from the main run
(FOV at other window placements and widths, the other cost model, the arm bases side by
side, flat pick costs), on the quick set with the real planner, and the report's tables
made from them."""

import filecmp
import json
import os
import re
import statistics

import pytest
from exp_helpers import CONFIG, COSTGEN, PLANNER, assert_checked, harvest, require

from harvest.experiments import cost_models, report, results, sensitivity, variants
from harvest.experiments.runner import METHODS, QUICK_ALPHAS, QUICK_SEEDS

TIME_LIMIT_S = "20"
WIDTHS = (0.2, 0.4)
# -0.235: the window centred on the vehicle (the bases are 0.235 m ahead and behind it);
# 0.065: inside each arm's reach
OFFSETS = (-0.235, 0.065)
MAIN_WIDTH, MAIN_OFFSET = "0.4", "0.065"
WINDOWS = [(w, o) for w in WIDTHS for o in OFFSETS]


def _exp(step, out, *extra):
    r = harvest(
        "experiments",
        step,
        "--quick",
        "--out",
        str(out),
        "--config",
        CONFIG,
        "--time-limit",
        TIME_LIMIT_S,
        "--fov-width",
        MAIN_WIDTH,
        "--fov-offset",
        MAIN_OFFSET,
        "--no-progress",
        *extra,
    )
    return r


@pytest.fixture(scope="module")
def derived(tmp_path_factory):
    require(PLANNER, "planner/harvest-plan")
    require(COSTGEN, "tools/costgen")
    out = tmp_path_factory.mktemp("derived")
    for step, extra in (
        ("run", ()),
        ("cost-models", ()),
        (
            "fov-width",
            (
                "--fov-widths",
                ",".join(map(str, WIDTHS)),
                # "=": a list starting with a minus sign is not an option
                "--fov-offsets=" + ",".join(map(str, OFFSETS)),
            ),
        ),
        ("variants", ()),
        ("report", ()),
    ):
        r = _exp(step, out, *extra)
        assert r.returncode == 0, (step, r.stdout + r.stderr)
    return out


def _by_key(rows, method):
    return {(r["alpha"], r["seed"]): r for r in rows if r["method"] == method}


def _model_dirs(derived):
    return ((0, derived), (1, derived / cost_models.subdir(True)))


@pytest.mark.parametrize("pc", (0, 1))
def test_fov_is_planned_at_every_window_on_each_models_inputs(derived, pc):
    model = dict(_model_dirs(derived))[pc]
    sweep = sensitivity.load(str(model))
    assert sorted(sweep) == WINDOWS
    want = {(a, s) for a in QUICK_ALPHAS for s in QUICK_SEEDS}
    for (w, o), rows in sweep.items():
        assert {r["method"] for r in rows} == {"fov"}
        assert {(r["alpha"], r["seed"]) for r in rows} == want
        assert all(r["status"] != "error" and r["fov_moved"] is not None for r in rows), rows
        d = model / sensitivity.SUBDIR / f"w{w:g}_o{o:g}"
        # that model's config, and the main run's tables and fruit maps
        assert filecmp.cmp(d / "planner.cfg", model / "planner.cfg", shallow=False)
        assert f"plan.pick_cycle = {pc}" in (d / "planner.cfg").read_text()
        for sub in ("tables", "instances"):
            names = sorted(os.listdir(derived / sub))
            assert names and sorted(os.listdir(d / sub)) == names
            for n in names:
                assert filecmp.cmp(d / sub / n, derived / sub / n, shallow=False)


def test_the_main_window_reproduces_the_main_runs_fov_plans(derived):
    main = _by_key(results.read(str(derived / "results.csv")), "fov")
    again = _by_key(sensitivity.load(str(derived))[(float(MAIN_WIDTH), float(MAIN_OFFSET))], "fov")
    assert main.keys() == again.keys()
    for k in main:
        assert again[k]["stops"] == main[k]["stops"], k
        assert again[k]["makespan_s"] == pytest.approx(main[k]["makespan_s"], rel=1e-12), k
        assert again[k]["fov_moved"] == main[k]["fov_moved"], k


@pytest.mark.parametrize("pc", (0, 1))
def test_the_window_changes_fov_and_a_proven_milp_beats_it_at_every_window(derived, pc):
    model = dict(_model_dirs(derived))[pc]
    milp = _by_key(results.read(str(model / "results.csv")), "milp")
    sweep = sensitivity.load(str(model))
    spans = {
        w: sorted((r["alpha"], r["seed"], r["stops"]) for r in rows) for w, rows in sweep.items()
    }
    assert spans[(0.2, 0.065)] != spans[(0.4, 0.065)], "FOV's plans do not depend on the width"
    for w in WIDTHS:
        # a window centred on the vehicle sees mostly fruit its stop's arms cannot reach
        centred = sensitivity.moved_share(sweep[(w, -0.235)])
        assert centred > 2 * sensitivity.moved_share(sweep[(w, 0.065)]), w
    for w, rows in sweep.items():
        proven = 0
        for r in rows:
            m = milp[(r["alpha"], r["seed"])]
            if m["status"] == "optimal":  # same instance and costs: the optimum is never worse
                proven += 1
                assert m["makespan_s"] <= r["makespan_s"] + 1e-6, (w, r, m)
        # a run without a single proven optimum would compare nothing
        assert proven > 0, f"width {w}: no MILP result of the {len(rows)} instances is optimal"


def test_the_reports_window_table_is_the_csvs(derived):
    text = (derived / "report.md").read_text()
    assert "#### The gain over FOV by FOV window placement and width" in text
    for pc, model in _model_dirs(derived):
        milp = _by_key(results.read(str(model / "results.csv")), "milp")
        sweep = sensitivity.load(str(model))
        for w in WIDTHS:
            med = {}
            for o in OFFSETS:
                gains = [
                    milp[(r["alpha"], r["seed"])]["throughput_fruit_per_s"]
                    / r["throughput_fruit_per_s"]
                    - 1.0
                    for r in sweep[(w, o)]
                ]
                med[o] = 100.0 * statistics.median(gains)
            best = min(med, key=med.get)
            moved = 100.0 * sensitivity.moved_share(sweep[(w, best)])
            row = (
                rf"^\| plan\.pick_cycle = {pc} \| {re.escape(f'{w:g}')} \| "
                rf"{re.escape(f'{best:g}')} \| [0-9.]+ \| {re.escape(f'{moved:.1f}')} % \| "
                rf"{re.escape(f'{med[best]:+.1f}')} % \|"
            )
            assert re.search(row, text, re.M), row
    assert (
        f"The main run's FOV uses {MAIN_WIDTH} m wide windows {MAIN_OFFSET} m from the base" in text
    )
    assert "With plan.pick_cycle = 0, FOV does best at width" in text
    assert "With plan.pick_cycle = 1, FOV does best at width" in text
    fov = [r for r in results.read(str(derived / "results.csv")) if r["method"] == "fov"]
    moved = sum(r["fov_moved"] for r in fov)
    assert f"FOV moved {moved} of its {sum(r['fruits_planned'] for r in fov)} fruits" in text


def test_the_other_cost_model_plans_the_same_instances_in_the_robots_time(derived):
    other = derived / cost_models.subdir(True)
    assert "plan.pick_cycle = 1" in (other / "planner.cfg").read_text()
    rows = results.read(str(other / "results.csv"))
    want = {(a, s, m) for a in QUICK_ALPHAS for s in QUICK_SEEDS for m in METHODS}
    assert {(r["alpha"], r["seed"], r["method"]) for r in rows} == want
    main = {
        (r["alpha"], r["seed"], r["method"]): r for r in results.read(str(derived / "results.csv"))
    }
    for r in rows:
        assert r["status"] != "error", r
        plan = json.loads((other / r["plan"]).read_text())
        assert plan["params"]["pick_time"] == "cycle"
        assert main[(r["alpha"], r["seed"], r["method"])]["fruits_planned"] == r["fruits_planned"]
        assert_checked(other / r["plan"])


def test_the_reports_dual_arm_table_has_both_cost_models_from_the_csvs(derived):
    text = (derived / "report.md").read_text()
    assert "#### Dual arm / single arm in both cost models" in text
    for pc, d in _model_dirs(derived):
        rows = results.read(str(d / "results.csv"))
        milp, serial = _by_key(rows, "milp"), _by_key(rows, "serial")
        for a in QUICK_ALPHAS:
            ratios = [
                milp[(a, s)]["throughput_fruit_per_s"] / serial[(a, s)]["throughput_fruit_per_s"]
                for s in QUICK_SEEDS
            ]
            row = (
                rf"^\| plan\.pick_cycle = {pc} \| {re.escape(f'{a:g}')} \| {len(ratios)} \| "
                rf"{re.escape(f'{statistics.median(ratios):.2f}')}x \|"
            )
            assert re.search(row, text, re.M), row
    assert re.search(
        r"At alpha = 1 \(paper: nearly 2x\): [0-9.]+x with the paper's.*; "
        r"[0-9.]+x with the robot's time",
        text,
    )


def test_the_report_names_the_cost_model_of_each_table_and_figure(derived):
    text = (derived / "report.md").read_text()
    # the results table: the main run's costs; the width and dual-arm tables: per row
    assert text.count(f"*Costs: {report.cost_model_text(False)}.*") == 1
    assert text.count(report.costs_per_row_line()) == 2
    for caption in re.findall(r"^\*(.+)\*$", text, re.M):
        if not caption.startswith("Costs:"):
            assert "(costs: " in caption, caption


def test_derived_runs_need_the_main_run_with_the_same_options(tmp_path):
    require(PLANNER, "planner/harvest-plan")
    require(COSTGEN, "tools/costgen")
    r = _exp("fov-width", tmp_path / "none")
    assert r.returncode == 2 and "no main run yet" in r.stderr, r.stderr  # bad input
    out = tmp_path / "main"
    r = _exp("run", out, "--alphas", "0.25", "--seeds", "1", "--methods", "fov")
    assert r.returncode == 0, r.stderr
    r = _exp(
        "cost-models", out, "--alphas", "0.25", "--seeds", "1", "--methods", "fov", "--pick-cycle"
    )
    assert r.returncode == 2 and "different pick_cycle" in r.stderr, r.stderr
    assert not (out / cost_models.subdir(False)).exists()


@pytest.mark.parametrize(
    "option, text",
    [
        ("--fov-widths", "0,0.25"),
        ("--fov-widths", "abc"),
        ("--fov-widths", ""),
        ("--fov-widths", "0.1,inf"),
        ("--fov-offsets", "0.1,nan"),
        ("--fov-offsets", ""),
    ],
)
def test_bad_windows_are_refused_before_anything_runs(tmp_path, option, text):
    r = harvest(
        "experiments",
        "fov-width",
        "--out",
        str(tmp_path / "x"),
        "--config",
        CONFIG,
        option,
        text,
        "--planner",
        "/bin/true",
        "--costgen",
        "/bin/true",
    )
    assert r.returncode == 2 and r.stderr.startswith(f"harvest-stack experiments: {option}: ")
    assert not (tmp_path / "x").exists()


def _row(alpha, seed, method, thr, stops=3, moved=None):
    return {
        "distribution": "uniform",
        "alpha": alpha,
        "seed": seed,
        "method": method,
        "status": "optimal",
        "makespan_s": 10.0 / thr,
        "throughput_fruit_per_s": thr,
        "stops": stops,
        "fruits_planned": 10,
        "fov_moved": moved,
    }


def test_gain_table_and_its_verdict_on_known_numbers():
    main = [_row(1.0, s, "milp", 1.2) for s in range(3)]
    sweep = {
        (0.2, 0.0): [_row(1.0, s, "fov", 0.6, moved=1) for s in range(3)],  # +100 %
        (0.2, 0.1): [_row(1.0, s, "fov", t, moved=0) for s, t in enumerate((1.05, 1.07, 0.96))],
        (0.4, 0.1): [_row(1.0, s, "fov", 0.8, moved=2) for s in range(3)],  # +50 %
    }
    table = sensitivity.gain_table(main, sweep)
    assert [(t["width_m"], t["offset_m"]) for t in table] == sorted(sweep)
    assert table[0]["median_gain"] == pytest.approx(1.0) and table[0]["in_band"] == 0
    assert table[0]["moved_share"] == pytest.approx(0.1)
    assert table[1]["median_gain"] == pytest.approx(1.2 / 1.05 - 1.0) and table[1]["in_band"] == 2
    assert table[1]["min_gain"] == pytest.approx(1.2 / 1.07 - 1.0)
    assert table[1]["max_gain"] == pytest.approx(0.25)
    assert sensitivity.best_at_width(table, 0.2)["offset_m"] == 0.1
    assert sensitivity.best_at_width(table, 0.3) is None
    text = report.fov_window_section({False: table}, False, (0.2, 0.0))
    assert "FOV does best at width 0.2 m, offset 0.1 m (median gain +14.3 %)" in text
    assert "inside the paper's band at 1 of 3 windows" in text
    assert "the main run's window (0.2 m wide, 0 m from the base) gives +100.0 %" in text
    assert re.search(r"^\| plan\.pick_cycle = 0 \| 0\.4 \| 0\.1 \| 3\.0 \| 20\.0 % \|", text, re.M)


def test_the_side_by_side_mount_plans_the_same_instances_with_its_own_tables(derived):
    other = derived / variants.SIDE_BY_SIDE.subdir
    cfg = (other / "variant.cfg").read_text()
    assert "mount.base_spacing = 0\n" in cfg
    assert "mount.base_spacing = 0\n" in (other / "planner.cfg").read_text()
    # the same fruit maps; cost tables of its own, made for bases side by side
    names = sorted(os.listdir(derived / "instances"))
    assert names and sorted(os.listdir(other / "instances")) == names
    for n in names:
        assert filecmp.cmp(other / "instances" / n, derived / "instances" / n, shallow=False)
    tables = sorted(os.listdir(derived / "tables"))
    assert sorted(os.listdir(other / "tables")) == tables
    assert any(
        not filecmp.cmp(other / "tables" / n, derived / "tables" / n, shallow=False) for n in tables
    ), "the side-by-side run planned on the main run's tables"
    rows = results.read(str(other / "results.csv"))
    want = {(a, s, m) for a in QUICK_ALPHAS for s in QUICK_SEEDS for m in METHODS}
    assert {(r["alpha"], r["seed"], r["method"]) for r in rows} == want
    for r in rows:
        assert r["status"] != "error", r
        assert_checked(other / r["plan"])
    # the fruits a reading leaves out of reach are the MILP plans' own count
    main = variants.figures(results.read(str(derived / "results.csv")))
    side = variants.figures(rows)
    unreachable = sum(r["fruits_unreachable"] for r in rows if r["method"] == "milp")
    assert side["unreachable"] == unreachable
    # side by side, each arm reaches the stretch of row the other reaches
    assert side["unreachable"] <= main["unreachable"], (side, main)


def test_flat_costs_plan_the_same_picks_no_dearer(derived):
    """Flat costs are each fruit's least IK cost: a proven flat optimum is never longer
    than the main run's plan of the same instance and method, and the checker accepts each
    plan under the flat model its config names."""
    other = derived / variants.FLAT_COSTS.subdir
    assert "plan.pick_cost_flat = 1\n" in (other / "planner.cfg").read_text()
    rows = results.read(str(other / "results.csv"))
    main = {
        (r["alpha"], r["seed"], r["method"]): r for r in results.read(str(derived / "results.csv"))
    }
    assert {(r["alpha"], r["seed"], r["method"]) for r in rows} == set(main)
    proven = 0
    for r in rows:
        assert r["status"] != "error", r
        plan = json.loads((other / r["plan"]).read_text())
        assert plan["params"]["pick_time"].endswith("_flat")
        m = main[(r["alpha"], r["seed"], r["method"])]
        assert r["fruits_planned"] == m["fruits_planned"]
        if r["method"] == "milp" and r["status"] == "optimal":
            proven += 1
            assert r["makespan_s"] <= m["makespan_s"] + 1e-6, (r, m)
        assert_checked(other / r["plan"])
    assert proven > 0, "no flat MILP plan is optimal: the comparison checked nothing"


def test_the_reports_readings_and_causes_are_the_csvs(derived):
    text = (derived / "report.md").read_text()
    assert "## The set-up's readings side by side" in text
    assert "## What each cause accounts for" in text
    main = results.read(str(derived / "results.csv"))
    found = variants.load(str(derived))
    assert sorted(found) == sorted(v.subdir for v in variants.VARIANTS)
    labels = [("main run: bases 0.47 m apart along the row", main)] + [
        (v.label, found[v.subdir]) for v in variants.VARIANTS
    ]
    for label, rows in labels:
        milp, serial, fov = (_by_key(rows, m) for m in ("milp", "serial", "fov"))
        gain = statistics.median(
            milp[k]["throughput_fruit_per_s"] / fov[k]["throughput_fruit_per_s"] - 1.0 for k in milp
        )
        dual = statistics.median(
            milp[k]["throughput_fruit_per_s"] / serial[k]["throughput_fruit_per_s"] for k in milp
        )
        stops = [statistics.median(r["stops"] for r in m.values()) for m in (fov, serial, milp)]
        unreachable = sum(r["fruits_unreachable"] for r in milp.values())
        proven = sum(1 for r in milp.values() if r["status"] == "optimal")
        row = (
            rf"^\| {re.escape(label)} \| {len(milp)} \| "
            + " / ".join(re.escape(f"{v:.1f}") for v in stops)
            + rf" \| {re.escape(f'{100 * gain:+.1f}')} %; [^|]+ \| "
            rf"{re.escape(f'{dual:.2f}')}x; [^|]+ \| {unreachable} \| [^|]+ \| "
            rf"{proven}/{len(milp)} \|$"
        )
        assert re.search(row, text, re.M), row
        if label != labels[0][0]:
            # the causes table: the reading's gain, and its change from the main run's
            base = variants.figures(main)["gain"]
            cause = (
                rf"^\| {re.escape(label)} \| {re.escape(f'{100 * gain:+.1f}')} % \| "
                rf"{re.escape(f'{100 * (gain - base):+.1f}')} points \|"
            )
            assert re.search(cause, text, re.M), cause
    # the bound row: each MILP plan's makespan at its solver's bound, never below the plan's gain
    bound = variants.figures(variants.milp_at_bound(main))
    assert bound["gain"] >= variants.figures(main)["gain"]
    assert re.search(
        rf"^\| every MILP plan at its bound [^|]*\| {re.escape(report.pct(bound['gain']))} \|",
        text,
        re.M,
    )
