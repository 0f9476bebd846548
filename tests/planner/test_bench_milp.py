"""bench_milp's smoke run (`--quick`): both models side by side with HiGHS beside the MILP,
and each model built as harvest-plan builds it: harvest-plan, given the fruit map the bench
exports, writes the very model file HiGHS solved (the product's with the shipped config, the
paper's with row.stops_beyond_ends = 0 and plan.pick_cycle = 0). No timing is asserted."""

import os
import re
import subprocess

import pytest

SRC = os.environ.get(
    "HV_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
BUILD = os.environ.get("HV_BUILD_DIR", os.path.join(SRC, "build"))
BENCH = os.path.join(BUILD, "bench", "planner", "bench_milp")
PLAN = os.path.join(BUILD, "planner", "harvest-plan")
CONFIG = os.path.join(SRC, "config", "harvest.cfg")

pytestmark = pytest.mark.skipif(
    not (os.access(BENCH, os.X_OK) and os.access(PLAN, os.X_OK)),
    reason="SKIPPED: bench_milp or harvest-plan not built in HV_BUILD_DIR",
)


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    out = tmp_path_factory.mktemp("bench")
    p = subprocess.run(
        [BENCH, "--quick", "--export", str(out)], capture_output=True, text=True, timeout=300
    )
    assert p.returncode == 0, p.stdout + p.stderr
    return out, p


def test_both_models_side_by_side_with_highs(quick):
    _, p = quick
    assert "SKIPPED" not in p.stderr, p.stderr  # highspy is pinned in host/requirements.txt
    side = p.stdout.split("# Side by side")[1].splitlines()
    assert re.search(r"\bproduct\b.*\bpaper\b", side[1]), side[1]
    row = next(line for line in side if line.startswith("all"))
    # per model: the MILP's proven of run, then HiGHS's
    counts = re.findall(r"(\d+)/\s*(\d+)", row)
    assert [n for _, n in counts] == ["1", "1", "1", "1"], row
    assert "proved different optima" not in p.stdout
    assert p.stdout.count("# slowest: alpha 0.25 seed 1 ") == 2


def paper_config(tmp_path):
    text = open(CONFIG).read()
    for key in ("row.stops_beyond_ends", "plan.pick_cycle"):
        text, n = re.subn(rf"^{re.escape(key)} = 1$", f"{key} = 0", text, flags=re.M)
        assert n == 1, key
    path = tmp_path / "paper.cfg"
    path.write_text(text)
    return str(path)


@pytest.mark.parametrize("model", ["product", "paper"])
def test_the_model_is_the_one_harvest_plan_builds(quick, tmp_path, model):
    out, _ = quick
    cfg = CONFIG if model == "product" else paper_config(tmp_path)
    lp = tmp_path / "harvest-plan.lp"
    p = subprocess.run(
        [
            PLAN,
            "--config",
            cfg,
            "--fruits",
            str(out / f"{model}-a0.25-s1.csv"),
            "--method",
            "milp",
            "--out",
            str(tmp_path / "plan.json"),
            "--export-lp",
            str(lp),
            "--time-limit",
            "5",
            "--quiet",
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert p.returncode == 0, p.stderr
    bench_lp = (out / f"{model}-a0.25-s1.lp").read_text()
    assert "Minimize" in bench_lp
    assert lp.read_text() == bench_lp


def test_export_to_a_missing_folder_is_refused(tmp_path):
    p = subprocess.run(
        [BENCH, "--quick", "--export", str(tmp_path / "none")],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert p.returncode == 2
    assert "--export" in p.stderr and str(tmp_path / "none") in p.stderr
