"""The paper's comparison in both cost models: the paper's one-way G with tau
(plan.pick_cycle = 0) and the robot's pick cycle, 2 t(home -> fruit) + cut + release with
the drive's v/a per stop (plan.pick_cycle = 1).

The main run plans in one of them; this plans the same instances in the other, in
OUT/pick_cycle_<0|1>/ (a derived run), so the dual-arm / single-arm ratio (MILP over
Serial) and the gain over FOV can be read in both.
"""

import json
import os
import statistics

from . import report
from . import results as results_mod
from .runner import run
from .subruns import derive, require_main


def subdir(pick_cycle):
    return f"pick_cycle_{int(bool(pick_cycle))}"


def run_other(s, retry_errors=False):
    """Plan the main run's instances in the other cost model; returns the plans computed now."""
    require_main(s)
    return run(other_settings(s), retry_errors=retry_errors)[0]


def other_settings(s):
    other = not s.pick_cycle
    return derive(s, subdir(other), pick_cycle=other)


def planned(s):
    """Settings of the main run and, once it has been run, of the other cost model's."""
    done = os.path.isfile(os.path.join(s.out_dir, subdir(not s.pick_cycle), "run.json"))
    return [s, other_settings(s)] if done else [s]


def _pick_cycle_of(out_dir):
    with open(os.path.join(out_dir, "run.json"), encoding="utf-8") as f:
        return bool(json.load(f)["pick_cycle"])


def dirs(out_dir):
    """{pick_cycle (bool): output directory} of the main run and, when run, the other model's."""
    main = _pick_cycle_of(out_dir)
    found = {main: out_dir}
    other = os.path.join(out_dir, subdir(not main))
    if os.path.isfile(os.path.join(other, "run.json")):
        found[not main] = other
    return found


def load(out_dir):
    """{pick_cycle (bool): typed rows} of each cost model planned (main run first)."""
    models = {}
    for pc, d in dirs(out_dir).items():
        rows = results_mod.read(os.path.join(d, "results.csv"))
        if rows:
            models[pc] = rows
    return models


def _median(v):
    return statistics.median(v) if v else float("nan")


def ratios(rows):
    """Per alpha: MILP / Serial throughput (the dual-arm / single-arm ratio) and MILP / FOV
    throughput - 1 over the instances each pair of methods planned, with median makespans."""
    per = {}
    for key, ms in report.by_instance(rows).items():
        d = per.setdefault(key[1], {"dual": [], "gain": [], "milp": [], "serial": []})
        if "milp" in ms:
            d["milp"].append(ms["milp"]["makespan_s"])
            thr = ms["milp"]["throughput_fruit_per_s"]
            if "serial" in ms:
                d["dual"].append(thr / ms["serial"]["throughput_fruit_per_s"])
            if "fov" in ms:
                d["gain"].append(thr / ms["fov"]["throughput_fruit_per_s"] - 1.0)
        if "serial" in ms:
            d["serial"].append(ms["serial"]["makespan_s"])
    return [
        {
            "alpha": a,
            "n": len(d["dual"]),
            "dual_median": _median(d["dual"]),
            "dual_min": min(d["dual"], default=float("nan")),
            "dual_max": max(d["dual"], default=float("nan")),
            "milp_makespan_s": _median(d["milp"]),
            "serial_makespan_s": _median(d["serial"]),
            "fov_gain_median": _median(d["gain"]),
        }
        for a, d in sorted(per.items())
    ]
