"""The experiment runner on the real planner CLI: the quick set, plots, report, resume."""

import csv
import json
import os
import signal
import statistics
import subprocess
import sys
import time

import pytest
from exp_helpers import BUILD_DIR, CONFIG, COSTGEN, PLANNER, assert_checked, harvest, require

from harvest.experiments import results
from harvest.experiments.runner import METHODS, QUICK_ALPHAS, QUICK_SEEDS

# The MILP must not run for ever on a test machine; what the limit cuts short is reported
# by the planner (status and gap) and still has to beat the baselines.
TIME_LIMIT_S = "20"


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory):
    require(PLANNER, "planner/harvest-plan")
    require(COSTGEN, "tools/costgen")
    out = tmp_path_factory.mktemp("quick")
    r = harvest(
        "experiments",
        "all",
        "--quick",
        "--out",
        str(out),
        "--config",
        CONFIG,
        "--time-limit",
        TIME_LIMIT_S,
        "--no-progress",
    )
    assert r.returncode == 0, r.stdout + r.stderr
    return out, r


def test_quick_set_gives_a_complete_results_csv(quick_run):
    out, _ = quick_run
    rows = results.read(str(out / "results.csv"))
    keys = {(r["alpha"], r["seed"], r["method"]) for r in rows}
    want = {(a, s, m) for a in QUICK_ALPHAS for s in QUICK_SEEDS for m in METHODS}
    assert keys == want and len(rows) == len(want)
    for r in rows:
        assert r["status"] != "error", r
        assert r["stops"] >= 1 and r["makespan_s"] > 0 and r["runtime_s"] >= 0
        assert r["n_right"] == round(r["alpha"] * r["n_left"])
        # throughput is fruits planned over the makespan (paper's eq. 6)
        assert r["throughput_fruit_per_s"] == pytest.approx(
            r["fruits_planned"] / r["makespan_s"], rel=1e-6
        )
        assert (out / r["plan"]).is_file()


def test_every_plan_passes_the_planners_independent_check(quick_run):
    out, _ = quick_run
    for r in results.read(str(out / "results.csv")):
        assert_checked(out / r["plan"])


def test_the_paper_experiment_plans_on_the_papers_stops(quick_run):
    """The run gives the planner the paper's N = 201 stops over the row, and the report says
    so and why each unreachable fruit is one."""
    out, _ = quick_run
    cfg = (out / "planner.cfg").read_text()
    assert "row.stops_beyond_ends = 0" in cfg and "plan.pick_cycle = 0" in cfg
    reasons = set()
    for r in results.read(str(out / "results.csv")):
        plan = json.loads((out / r["plan"]).read_text())
        assert plan["params"]["stop_margin_m"] == 0 and plan["params"]["pick_time"] == "one_way"
        assert all(0.0 <= s["y_m"] <= plan["params"]["row_length_m"] for s in plan["stops"])
        reasons |= {u["reason"] for u in plan["unreachable"]}
    text = (out / "report.md").read_text()
    assert "N = 201" in text and "plan.pick_cycle = 0" in text
    for why in reasons:
        assert f" {why} (" in text


def test_milp_never_worse_than_fov_or_serial(quick_run):
    out, _ = quick_run
    by = {}
    for r in results.read(str(out / "results.csv")):
        by.setdefault((r["alpha"], r["seed"]), {})[r["method"]] = r
    for key, m in by.items():
        for other in ("fov", "serial"):
            assert m["milp"]["makespan_s"] <= m[other]["makespan_s"] + 1e-6, (key, other, m)


def test_plots_and_report_are_written(quick_run):
    out, _ = quick_run
    for stem in (
        "boxplot_stops",
        "boxplot_throughput",
        "boxplot_runtime",
        "plan_top_view",
        "cost_G_joint3",
        "coverage_pick_modes",
    ):
        for ext in ("png", "svg"):
            assert (out / "figures" / f"{stem}.{ext}").stat().st_size > 5_000, stem
    text = (out / "report.md").read_text()
    for heading in (
        "Fewest stops",
        "Throughput over FOV",
        "Dual arm vs single arm",
        "Runtime",
        "Verdict",
    ):
        assert heading in text
    assert "figures/boxplot_stops.png" in text
    # every number of the results table is the CSV's, computed here again
    table = _results_table(text)
    rows = results.read(str(out / "results.csv"))
    groups = {}
    for r in rows:
        groups.setdefault((float(r["alpha"]), r["method"]), []).append(r)
    assert table.keys() == groups.keys()
    for key, rs in groups.items():
        plans, stops, span, tput, runtime, status, unreachable = table[key]
        ok = [r for r in rs if r["status"] != "error" and r["makespan_s"] is not None]
        assert ok, key
        assert plans == f"{len(ok)}/{len(rs)}", key
        # each printed to its digits: one unit of the last digit apart at most
        med = statistics.median
        assert float(stops) == pytest.approx(med(r["stops"] for r in ok), abs=0.051), key
        assert float(span) == pytest.approx(med(r["makespan_s"] for r in ok), abs=0.051), key
        assert float(tput) == pytest.approx(
            med(r["throughput_fruit_per_s"] for r in ok), abs=0.00051
        ), key
        rt_med, rt_max = (float(x) for x in runtime.split(" / "))
        assert rt_med == pytest.approx(med(r["runtime_s"] for r in ok), abs=0.0051), key
        assert rt_max == pytest.approx(max(r["runtime_s"] for r in ok), abs=0.0051), key
        counts = {}
        for r in rs:
            counts[r["status"]] = counts.get(r["status"], 0) + 1
        assert (
            dict((k, int(v)) for k, v in (c.rsplit(" ", 1) for c in status.split(", "))) == counts
        ), key
        assert int(unreachable) == sum(r["fruits_unreachable"] or 0 for r in ok), key


def _results_table(text):
    """The report's "Results by alpha and method" table: {(alpha, method): other cells}."""
    lines = text.splitlines()
    head = next(i for i, ln in enumerate(lines) if ln.startswith("| alpha | method | plans |"))
    out = {}
    for ln in lines[head + 2 :]:
        if not ln.startswith("|"):
            break
        cells = [c.strip() for c in ln.strip().strip("|").split("|")]
        assert len(cells) == 9, ln
        out[(float(cells[0]), cells[1])] = cells[2:]
    return out


def _data_rows(path):
    if not os.path.exists(path):
        return 0
    with open(path) as f:
        return max(0, sum(1 for line in f if line.endswith("\n")) - 1)


def _run_args(out, *options):
    """`python -m harvest experiments run` into out, without a progress bar, and its
    environment (the build of $HV_BUILD_DIR)."""
    args = [
        sys.executable,
        "-m",
        "harvest",
        "experiments",
        "run",
        "--out",
        str(out),
        "--config",
        CONFIG,
        "--no-progress",
        *options,
    ]
    return args, dict(os.environ, HV_BUILD_DIR=BUILD_DIR)


def test_interrupted_run_resumes_without_recomputing(tmp_path):
    require(PLANNER, "planner/harvest-plan")
    require(COSTGEN, "tools/costgen")
    out = tmp_path / "resume"
    csv_path = str(out / "results.csv")
    args, env = _run_args(out, "--alphas", "0.25,0.4", "--seeds", "3", "--time-limit", TIME_LIMIT_S)
    total = 2 * 3 * len(METHODS)
    proc = subprocess.Popen(
        args, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True
    )
    try:
        while _data_rows(csv_path) < 2 and proc.poll() is None:
            time.sleep(0.02)
    finally:
        # A hard kill of the runner and any planner it started: no handler runs.
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
    assert proc.returncode == -signal.SIGKILL, "the run ended before it could be interrupted"
    with open(csv_path, "rb") as f:
        before_bytes = f.read()
    before_bytes = before_bytes[: before_bytes.rfind(b"\n") + 1]  # a torn tail is recomputed
    before = list(csv.DictReader(before_bytes.decode().splitlines()))
    kept = len(before)
    assert 2 <= kept < total
    mtimes = {r["plan"]: os.stat(out / r["plan"]).st_mtime_ns for r in before}

    r = subprocess.run(args, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert r.returncode == 0, r.stderr
    assert f"resuming: {kept} of {total} rows already" in r.stderr
    assert f"{total - kept} plan(s) computed now" in r.stdout
    after = results.read(csv_path)
    assert len(after) == total
    assert len({results.row_key(x) for x in after}) == total
    with open(csv_path, "rb") as f:
        assert f.read().startswith(before_bytes)  # finished rows untouched, in place
    for plan, mt in mtimes.items():
        assert os.stat(out / plan).st_mtime_ns == mt, f"{plan} was recomputed"

    # A third run has nothing left to do.
    r = subprocess.run(args, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert r.returncode == 0 and "0 plan(s) computed now" in r.stdout
    assert len(results.read(csv_path)) == total


def _terminate_when(args, env, ready, sig=signal.SIGTERM, group=False):
    """Start the runner in a session of its own, send sig once ready() holds (to the whole
    process group, planners included, as a terminal's Ctrl-C does, when group is set), and
    return (process, stderr). Whatever is left of its group is killed if it never ends."""
    proc = subprocess.Popen(
        args,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        deadline = time.monotonic() + 120
        while not ready() and proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.02)
        assert ready(), "the runner ended or hung before it could be interrupted"
        if group:
            os.killpg(proc.pid, sig)
        else:
            proc.send_signal(sig)
        _, err = proc.communicate(timeout=120)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    return proc, err


def _assert_group_empty(proc):
    """No planner, nor anything a planner started, outlives the runner: its process group
    is empty (anything found there is killed after the check)."""
    try:
        with pytest.raises(ProcessLookupError):
            os.killpg(proc.pid, 0)
    finally:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass


@pytest.mark.parametrize(
    "sig,group",
    [(signal.SIGTERM, False), (signal.SIGINT, True)],
    ids=["sigterm-runner", "ctrl-c-group"],
)
def test_sigterm_stops_the_planners_and_keeps_finished_rows(tmp_path, sig, group):
    """SIGTERM to the runner, or Ctrl-C to the whole group (a planner that sees it first
    stops with exit 5): the run stops, every finished row is kept, none is made of an
    interrupted plan, and no planner outlives the runner."""
    require(PLANNER, "planner/harvest-plan")
    require(COSTGEN, "tools/costgen")
    out = tmp_path / "term"
    csv_path = str(out / "results.csv")
    args, env = _run_args(out, "--alphas", "0.25", "--seeds", "3", "--time-limit", TIME_LIMIT_S)
    proc, err = _terminate_when(args, env, lambda: _data_rows(csv_path) >= 1, sig, group)
    assert proc.returncode == 130, err
    rows = results.read(csv_path)
    assert f"interrupted: {len(rows)} of {3 * len(METHODS)} rows are saved" in err
    assert all(r["status"] != "error" for r in rows), rows
    _assert_group_empty(proc)


def test_sigterm_reaps_what_a_killed_planner_left_behind(tmp_path):
    """A planner killed at the wrong moment can leave a child of its own (the sanitizers'
    leak-check tracer at exit is one): the runner reaps it too, so its group ends empty.
    The stand-in planner starts such a child, says so, and waits to be killed."""
    require(COSTGEN, "tools/costgen")
    out = tmp_path / "orphan"
    marker = tmp_path / "grandchild.pid"
    planner = tmp_path / "planner-with-a-child"
    planner.write_text(
        f"#!/bin/sh\nsleep 300 &\necho $! > {marker}.tmp\n"
        f"mv {marker}.tmp {marker}\nexec sleep 300\n"
    )
    planner.chmod(0o755)
    args, env = _run_args(
        out,
        "--alphas",
        "0.25",
        "--seeds",
        "1",
        "--methods",
        "fov",
        "--planner",
        str(planner),
        "--costgen",
        COSTGEN,
    )
    proc, err = _terminate_when(args, env, marker.exists)
    try:
        assert proc.returncode == 130, err
        assert "would not die" not in err
    finally:
        _assert_group_empty(proc)
