"""harvest-plan end to end: plans written and checked, bad input refused with one line,
tampered plans caught by `harvest-plan check`. Every pick is the real arm's exact IK; the
cost tables given are synthetic (band model, tests/planner/support) on the configuration's
arm and grid, so they pass the planner's table check without being used for costs."""

import json
import os
import random
import signal
import subprocess

import pytest

from harvest.scenario.config import derived_config_text

SRC = os.environ.get(
    "HV_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
BUILD = os.environ.get("HV_BUILD_DIR", os.path.join(SRC, "build"))
PLAN = os.path.join(BUILD, "planner", "harvest-plan")
SYNTH = os.path.join(BUILD, "tests", "planner", "planner_synth_tables")
CONFIG = os.path.join(SRC, "config", "harvest.cfg")

pytestmark = pytest.mark.skipif(
    not (os.access(PLAN, os.X_OK) and os.access(SYNTH, os.X_OK)),
    reason="SKIPPED: harvest-plan or planner_synth_tables not built in HV_BUILD_DIR",
)


def run(*args, check=None):
    p = subprocess.run([PLAN, *map(str, args)], capture_output=True, text=True, timeout=600)
    if check is not None:
        assert p.returncode == check, (p.returncode, p.stdout, p.stderr)
    return p


@pytest.fixture(scope="module")
def tables(tmp_path_factory):
    d = tmp_path_factory.mktemp("tables")
    subprocess.run([SYNTH, CONFIG, str(d), "0.30"], check=True)
    return str(d / "left.bin"), str(d / "right.bin")


def write_map(path, fruits):
    with open(path, "w") as f:
        f.write("id,side,x,y,z,yaw\n")
        for fr in fruits:
            f.write(",".join(str(v) for v in fr) + "\n")
    return str(path)


def random_fruits(n_left, n_right, length=2.0, seed=1):
    rnd = random.Random(seed)
    out = []
    for side, n in (("L", n_left), ("R", n_right)):
        for i in range(n):
            x = rnd.uniform(0.36, 0.49) * (-1 if side == "L" else 1)
            out.append(
                (
                    f"{side}{i}",
                    side,
                    round(x, 4),
                    round(rnd.uniform(0, length), 4),
                    round(rnd.uniform(0.41, 0.74), 4),
                    round(rnd.uniform(-0.7, 0.7), 4),
                )
            )
    return out


def plan_args(tables, fruits, out, method, *extra):
    return [
        "--config",
        CONFIG,
        "--left",
        tables[0],
        "--right",
        tables[1],
        "--fruits",
        fruits,
        "--method",
        method,
        "--out",
        out,
        *extra,
    ]


def test_help():
    p = run("--help", check=0)
    for flag in (
        "--config",
        "--left",
        "--right",
        "--fruits",
        "--method",
        "--out",
        "--time-limit",
        "--gap",
        "--fov-width",
        "--horizon",
        "--export-lp",
        "--quiet",
        "--algorithm",
        "--threads",
        "check",
    ):
        assert flag in p.stdout
    assert run("check", "--help", check=0).stdout.startswith("usage")


def test_usage_errors(tables, tmp_path):
    fruits = write_map(tmp_path / "m.csv", random_fruits(3, 3))
    out = str(tmp_path / "p.json")
    for args, needle in (
        (plan_args(tables, fruits, out, "greedy"), "--method"),
        (plan_args(tables, fruits, out, "fov", "--fov-width", "-1"), "--fov-width"),
        (plan_args(tables, fruits, out, "fov", "--horizon", "2"), "--horizon"),
        (plan_args(tables, fruits, out, "milp", "--gap", "abc"), "--gap"),
        (["--config", CONFIG], "harvest-plan: --fruits: required (see --help)"),
        (plan_args(tables, fruits, out, "milp", "--bogus"), "--bogus: unknown option"),
        (plan_args(tables, fruits, out, "milp", "--algorithm", "cplex"), "--algorithm"),
        (plan_args(tables, fruits, out, "fov", "--algorithm", "price"), "--algorithm"),
        (plan_args(tables, fruits, out, "milp", "--threads", "4"), "--threads"),
        (plan_args(tables, fruits, out, "fov", "--threads", "1"), "--threads"),
    ):
        p = run(*args, check=2)
        assert needle in p.stderr
        assert len(p.stderr.strip().splitlines()) == 1, p.stderr
    assert not os.path.exists(out)


def test_options_in_both_gnu_forms(tables, tmp_path):
    """getopt_long: `--opt=value` and `--opt value` give the same plan, in any order."""
    fruits = write_map(tmp_path / "m.csv", random_fruits(4, 4, seed=7))
    a, b = str(tmp_path / "a.json"), str(tmp_path / "b.json")
    run(*plan_args(tables, fruits, a, "fov", "--fov-width", "0.3", "--quiet"), check=0)
    run(
        "--quiet",
        f"--out={b}",
        "--fov-width=0.3",
        "--method=fov",
        f"--fruits={fruits}",
        f"--config={CONFIG}",
        f"--left={tables[0]}",
        f"--right={tables[1]}",
        check=0,
    )
    pa, pb = (json.load(open(p)) for p in (a, b))
    assert pa["stops"] == pb["stops"] and pa["totals"] == pb["totals"]
    assert (
        "--time-limit: expected a positive number"
        in run(*plan_args(tables, fruits, a, "milp", "--time-limit=0"), check=2).stderr
    )
    assert "OK" in run("check", f"--config={CONFIG}", f"--fruits={fruits}", a, check=0).stdout


@pytest.mark.parametrize("method", ["fov", "serial", "milp"])
def test_methods_write_checked_plans(tables, tmp_path, method):
    fr = random_fruits(8, 8, seed=3)
    fr.append(("far", "R", 0.45, 1.0, 0.6, 0.0))
    fruits = write_map(tmp_path / "m.csv", fr)
    out = str(tmp_path / "plan.json")
    p = run(*plan_args(tables, fruits, out, method, "--time-limit", "60"), check=0)
    assert "makespan" in p.stderr
    plan = json.load(open(out))
    assert plan["format"] == "harvest-plan" and plan["method"] == method
    picked = [pk["id"] for s in plan["stops"] for arm in ("left", "right") for pk in s[arm]]
    assert sorted(picked) == sorted(f[0] for f in fr)  # all reachable here
    t = plan["totals"]
    assert t["fruits_planned"] == len(fr) and t["stops"] == len(plan["stops"])
    assert abs(t["makespan_s"] - (t["pick_time_s"] + t["stop_time_s"] + t["travel_time_s"])) < 1e-6
    if method == "fov":
        assert plan["solver"]["status"] == "heuristic" and plan["solver"]["gap"] is None
    else:
        assert plan["solver"]["status"] in ("optimal", "feasible")
    pa = plan["params"]
    course = pa["row_length_m"] + 2 * pa["stop_margin_m"]
    assert pa["stop_margin_m"] > 0.2  # the arm bases alone sit 0.235 m off the stop
    assert pa["travel_time_s"] == pytest.approx(course / pa["vehicle_speed_mps"])
    # the robot's time (plan.pick_cycle = 1): a stop costs v / a, a pick its whole cycle
    assert pa["pick_time"] == "cycle" and pa["stop_penalty_s"] == pytest.approx(0.1 / 0.1)
    assert (
        min(pk["cost_s"] for s in plan["stops"] for arm in ("left", "right") for pk in s[arm])
        > 1.0 + 0.5
    )
    if method == "serial":
        assert t["travel_time_s"] == pytest.approx(2 * pa["travel_time_s"])
        assert {s["pass"] for s in plan["stops"]} == {0, 1}
    q = run("check", out, check=0)
    assert "OK" in q.stdout


def test_milp_no_worse_than_fov(tables, tmp_path):
    fr = random_fruits(10, 10, seed=5)
    fruits = write_map(tmp_path / "m.csv", fr)
    res = {}
    for m in ("fov", "milp"):
        out = str(tmp_path / f"{m}.json")
        run(*plan_args(tables, fruits, out, m, "--quiet"), check=0)
        res[m] = json.load(open(out))["totals"]["makespan_s"]
    assert res["milp"] <= res["fov"] + 1e-6


def test_algorithms_agree(tables, tmp_path):
    # branch-and-price and GLPK's branch-and-cut on the paper's model: one optimum
    fruits = write_map(tmp_path / "m.csv", random_fruits(12, 12, seed=11))
    res = {}
    for alg, threads in (("price", "2"), ("price", "1"), ("compact", "1")):
        out = str(tmp_path / f"{alg}{threads}.json")
        run(
            *plan_args(
                tables,
                fruits,
                out,
                "milp",
                "--quiet",
                "--algorithm",
                alg,
                "--threads",
                threads,
                "--time-limit",
                "120",
            ),
            check=0,
        )
        plan = json.load(open(out))
        assert plan["solver"]["status"] == "optimal", plan["solver"]
        res[alg + threads] = plan["totals"]["makespan_s"]
    assert res["price2"] == pytest.approx(res["compact1"], abs=1e-6)
    assert res["price1"] == pytest.approx(res["compact1"], abs=1e-6)


def derived_config(tmp_path, name, **overrides):
    path = tmp_path / name
    path.write_text(
        derived_config_text(CONFIG, {k.replace("__", "."): v for k, v in overrides.items()})
    )
    return str(path)


@pytest.mark.parametrize(
    "overrides,fruit,why",
    [
        # the paper's stops over the row only: a fruit at the row's start is behind both bases
        ({"row__stops_beyond_ends": 0}, ("end", "L", -0.42, 0.0, 0.6, 0.0), "row_end"),
        # joint 1's stroke ends at z = 0.84 m: a canopy reaching higher holds a fruit no
        # vehicle position helps with
        ({"row__canopy_height": 0.5}, ("high", "L", -0.42, 1.0, 0.88, 0.0), "height"),
        # a canopy 0.6 m deep: its far part is beyond the arm from every vehicle position
        ({"row__canopy_depth": 0.6}, ("deep", "R", 0.93, 1.0, 0.6, 0.0), "depth"),
        # joint 4 held near its home: the far fruit's -45 deg stem is in reach, but the wrist
        # cannot turn to it from any vehicle position
        ({"joint4__min": -0.1, "joint4__max": 0.1}, ("askew", "R", 0.5, 1.0, 0.6, -0.785), "yaw"),
    ],
)
def test_unreachable_listed_with_reason(tmp_path, overrides, fruit, why):
    cfg = derived_config(tmp_path, "h.cfg", **overrides)
    fr = random_fruits(3, 3, seed=7)
    fr = [f for f in fr if 0.3 < f[3] < 1.7] + [fruit]
    fruits = write_map(tmp_path / "m.csv", fr)
    out = str(tmp_path / "p.json")
    for method in ("fov", "milp"):
        p = run("--config", cfg, "--fruits", fruits, "--method", method, "--out", out)
        assert p.returncode == 0, p.stderr
        plan = json.load(open(out))
        assert plan["unreachable"] == [{"id": fruit[0], "side": fruit[1], "reason": why}]
        assert plan["totals"]["fruits_unreachable"] == 1
        assert f"1 {why}" in p.stderr  # the instance line counts the reasons
        run("check", out, check=0)


def test_stops_beyond_the_row_ends(tmp_path):
    """The fruit at both ends are planned from vehicle positions beyond the row, and the
    same map on the paper's stops leaves them unreachable."""
    fr = [
        ("first", "L", -0.42, 0.0, 0.6, 0.0),
        ("last", "R", 0.42, 2.0, 0.6, 0.0),
        ("mid", "R", 0.42, 1.0, 0.6, 0.0),
    ]
    fruits = write_map(tmp_path / "m.csv", fr)
    out = str(tmp_path / "p.json")
    run("--config", CONFIG, "--fruits", fruits, "--method", "milp", "--out", out, check=0)
    plan = json.load(open(out))
    assert plan["totals"]["fruits_planned"] == 3
    ys = [s["y_m"] for s in plan["stops"]]
    assert min(ys) < 0.0 and max(ys) > 2.0
    paper = derived_config(tmp_path, "paper.cfg", row__stops_beyond_ends=0)
    run("--config", paper, "--fruits", fruits, "--method", "milp", "--out", out, check=0)
    plan = json.load(open(out))
    assert plan["params"]["stop_margin_m"] == 0
    assert sorted(u["id"] for u in plan["unreachable"]) == ["first", "last"]
    assert {u["reason"] for u in plan["unreachable"]} == {"row_end"}


BAD_MAPS = [
    ("", "empty"),
    ("id,side,x,y,z,yaw\n", "no fruit"),
    ("id,side,x,y,z,yaw\n1,L,-0.4,0.5,0.6,0\n1,R,0.4,0.6,0.6,0\n", "m.csv:3: id: duplicate"),
    ("id,side,x,y,z,yaw\n1,Q,-0.4,0.5,0.6,0\n", "m.csv:2: side"),
    ("id,side,x,y,z,yaw\n1,L,-0.4,nan,0.6,0\n", "m.csv:2: y: not finite"),
    ("id,side,x,y,z,yaw\n1,L,-0.4,0.5,0.6,0.9\n", "m.csv:2: yaw"),
    ("id,side,x,y,z,yaw\n1,L,-0.4,2.5,0.6,0\n", "m.csv:2: y: 2.5 outside the row"),
    ("id,side,x,y,z,yaw\n1,R,-0.4,0.5,0.6,0\n", "m.csv:2: x"),
]


@pytest.mark.parametrize("text,needle", BAD_MAPS)
def test_bad_map(tables, tmp_path, text, needle):
    path = tmp_path / "m.csv"
    path.write_text(text)
    out = str(tmp_path / "p.json")
    p = run(*plan_args(tables, str(path), out, "fov"), check=2)
    assert needle in p.stderr, p.stderr
    assert len(p.stderr.strip().splitlines()) == 1, p.stderr
    assert not os.path.exists(out)


def test_bad_tables(tables, tmp_path):
    fruits = write_map(tmp_path / "m.csv", random_fruits(2, 2))
    out = str(tmp_path / "p.json")
    swapped = (tables[1], tables[0])
    p = run(*plan_args(swapped, fruits, out, "fov"), check=2)
    assert tables[1] in p.stderr and "side" in p.stderr
    broken = tmp_path / "broken.bin"
    data = bytearray(open(tables[0], "rb").read())
    data[-1] ^= 0xFF
    broken.write_bytes(bytes(data))
    p = run(*plan_args((str(broken), tables[1]), fruits, out, "fov"), check=2)
    assert str(broken) in p.stderr
    p = run(*plan_args((str(tmp_path / "none.bin"), tables[1]), fruits, out, "fov"), check=2)
    assert "none.bin" in p.stderr
    assert not os.path.exists(out)


EXEC = os.path.join(BUILD, "executor", "harvest-exec")


@pytest.mark.parametrize(
    "overrides,field",
    [
        ({"mount__offset": 0.20}, "mount.base"),
        ({"arm__elbow_free": 1}, "elbow_free"),
        ({"joint2__vmax": 0.3}, "joint_limits"),
        ({"arm__home": "0.2 0.0 1.4 0.0"}, "home"),
        ({"grid__y_half_span": 0.7}, "grid.y"),
    ],
)
def test_table_for_another_arm_refused(tmp_path, overrides, field):
    """A table built for another mount, elbow mode, joint limits, home pose or grid: the
    planner refuses it with the same one line as the executor."""
    other = tmp_path / "other"
    other.mkdir()
    subprocess.run([SYNTH, derived_config(tmp_path, "o.cfg", **overrides), str(other)], check=True)
    left = str(other / "left.bin")
    fruits = write_map(tmp_path / "m.csv", random_fruits(2, 2))
    out = str(tmp_path / "p.json")
    p = run(
        "--config",
        CONFIG,
        "--fruits",
        fruits,
        "--method",
        "fov",
        "--out",
        out,
        "--left",
        left,
        check=2,
    )
    line = p.stderr.strip()
    assert f"{left}: {field}:" in line and "HV_ERR_TAB_MISMATCH" in line, line
    assert not os.path.exists(out)
    if os.access(EXEC, os.X_OK):  # the executor's check is the same function
        run("--config", CONFIG, "--fruits", fruits, "--method", "fov", "--out", out, check=0)
        e = subprocess.run(
            [
                EXEC,
                "--plan",
                out,
                "--config",
                CONFIG,
                "--journal",
                str(tmp_path / "j"),
                "--cost-table-left",
                left,
            ],
            capture_output=True,
            text=True,
            timeout=60,
        )
        assert e.returncode == 2
        assert line.replace("harvest-plan:", "harvest-exec:") == e.stderr.strip()


def test_check_catches_tampering(tables, tmp_path):
    fr = random_fruits(6, 6, seed=11)
    fruits = write_map(tmp_path / "m.csv", fr)
    out = tmp_path / "p.json"
    run(*plan_args(tables, fruits, str(out), "fov", "--quiet"), check=0)
    good = json.loads(out.read_text())

    def tampered(edit):
        plan = json.loads(json.dumps(good))
        edit(plan)
        path = tmp_path / "t.json"
        path.write_text(json.dumps(plan))
        return run("check", str(path))

    p = tampered(lambda pl: pl["totals"].__setitem__("makespan_s", pl["totals"]["makespan_s"] + 1))
    assert p.returncode == 4 and "totals.makespan_s" in p.stderr
    p = tampered(lambda pl: pl["stops"][0]["right" if pl["stops"][0]["right"] else "left"].pop())
    assert p.returncode == 4
    # a stop listed twice, or two stops swapped: the reader refuses the file itself
    p = tampered(lambda pl: pl["stops"].append(dict(pl["stops"][-1])))
    last = len(good["stops"])
    assert p.returncode == 2 and f"t.json: stops[{last}].y_m: " in p.stderr, p.stderr
    if len(good["stops"]) >= 2:
        p = tampered(lambda pl: pl["stops"].reverse())
        assert p.returncode == 2 and "t.json: stops[1].y_m: " in p.stderr, p.stderr
        assert "not after" in p.stderr
    p = tampered(lambda pl: pl.__setitem__("extra", 1))
    assert p.returncode == 2 and "extra: unknown field" in p.stderr
    # the same plan checked against another map: fruits missing / unknown
    other = write_map(tmp_path / "other.csv", random_fruits(6, 6, seed=12))
    p = run("check", str(out), "--fruits", other)
    assert p.returncode == 4


def test_bad_fruit_id_in_plan_refused(tables, tmp_path):
    fruits = write_map(tmp_path / "m.csv", random_fruits(3, 3, seed=13))
    out = tmp_path / "p.json"
    run(*plan_args(tables, fruits, str(out), "fov", "--quiet"), check=0)
    plan = json.loads(out.read_text())
    arm = "left" if plan["stops"][0]["left"] else "right"
    plan["stops"][0][arm][0]["id"] = "L0\nS 0 t=0"  # a newline, then a journal record
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(plan))
    p = run("check", str(bad), check=2)
    assert f"bad.json: stops[0].{arm}[0].id: character 0x0a at position 3" in p.stderr, p.stderr


def test_check_finds_inputs_from_any_directory(tables, tmp_path):
    """Inputs given relative to the current directory are written relative to the plan's
    folder; `check` resolves them against that folder wherever it is run from."""
    work = tmp_path / "work"
    (work / "in").mkdir(parents=True)
    (work / "out").mkdir()
    write_map(work / "in" / "m.csv", random_fruits(4, 4, seed=17))
    rel = [os.path.relpath(p, work) for p in (CONFIG, tables[0], tables[1])]
    args = [
        "--config",
        rel[0],
        "--left",
        rel[1],
        "--right",
        rel[2],
        "--fruits",
        "in/m.csv",
        "--method",
        "fov",
        "--out",
        "out/p.json",
        "--quiet",
    ]
    p = subprocess.run([PLAN, *args], cwd=work, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    plan = json.loads((work / "out" / "p.json").read_text())
    out_dir = os.path.realpath(work / "out")
    for key, given in (
        ("config", CONFIG),
        ("cost_table_left", tables[0]),
        ("cost_table_right", tables[1]),
        ("fruit_map", work / "in" / "m.csv"),
    ):
        written = plan["inputs"][key]
        assert not os.path.isabs(written), (key, written)
        assert os.path.samefile(os.path.join(out_dir, written), given), (key, written)
    # from the plan's folder, from its parent, from elsewhere: the same inputs found
    for cwd in (work / "out", work, tmp_path, "/"):
        target = (
            os.path.relpath(work / "out" / "p.json", cwd)
            if cwd != "/"
            else str(work / "out" / "p.json")
        )
        q = subprocess.run(
            [PLAN, "check", target], cwd=cwd, capture_output=True, text=True, timeout=600
        )
        assert q.returncode == 0 and "OK" in q.stdout, (cwd, q.stderr)
    # the folder moved as a whole still finds the map beside its relative path
    moved = tmp_path / "moved"
    os.rename(work, moved)
    plan_moved = json.loads((moved / "out" / "p.json").read_text())
    assert os.path.isfile(os.path.join(moved / "out", plan_moved["inputs"]["fruit_map"]))


def test_export_lp(tables, tmp_path):
    fruits = write_map(tmp_path / "m.csv", random_fruits(4, 4, seed=2))
    out, lp = str(tmp_path / "p.json"), tmp_path / "model.lp"
    run(*plan_args(tables, fruits, out, "milp", "--export-lp", str(lp), "--quiet"), check=0)
    text = lp.read_text()
    assert "Minimize" in text or "minimize" in text.lower()


def test_out_dir_missing(tables, tmp_path):
    fruits = write_map(tmp_path / "m.csv", random_fruits(2, 2))
    out = str(tmp_path / "no" / "such" / "dir" / "p.json")
    p = run(*plan_args(tables, fruits, out, "fov"), check=1)
    assert "p.json" in p.stderr


def test_horizon_long_row(tables, tmp_path):
    length = 8.0
    fr = random_fruits(40, 40, length=length, seed=21)
    fruits = write_map(tmp_path / "m.csv", fr)
    out = str(tmp_path / "p.json")
    p = run(
        *plan_args(
            tables,
            fruits,
            out,
            "milp",
            "--row-length",
            length,
            "--horizon",
            "2",
            "--time-limit",
            "5",
            "--gap",
            "0.01",
        ),
        check=0,
    )
    assert p.stderr.count("horizon: window") >= 7  # progress, one line per window
    plan = json.load(open(out))
    assert plan["horizon"]["windows"] >= 7 and plan["solver"]["status"] == "heuristic"
    picked = [pk["id"] for s in plan["stops"] for arm in ("left", "right") for pk in s[arm]]
    assert sorted(picked) == sorted(f[0] for f in fr)  # every fruit exactly once
    run("check", out, check=0)


COSTGEN = os.path.join(BUILD, "tools", "costgen")


@pytest.fixture(scope="module")
def real_tables(tmp_path_factory):
    if not os.access(COSTGEN, os.X_OK):
        pytest.skip("SKIPPED: tools/costgen not built (HV_WITH_TOOLS=OFF)")
    d = tmp_path_factory.mktemp("real")
    subprocess.run(
        [COSTGEN, "--config", CONFIG, "--side", "both", "--out-dir", str(d)],
        check=True,
        capture_output=True,
        timeout=600,
    )
    return str(d / "costtab_left.bin"), str(d / "costtab_right.bin")


def test_real_tables_all_methods(real_tables, tmp_path):
    """The arm's real cost tables (costgen): every method writes a plan that passes the
    checker, unreachable fruit are listed, and the MILP is no worse than either baseline."""
    rnd = random.Random(8)
    fr = []
    for side, n in (("L", 12), ("R", 4)):
        for i in range(n):
            x = rnd.uniform(0.35, 0.50) * (-1 if side == "L" else 1)
            fr.append(
                (
                    f"{side}{i}",
                    side,
                    round(x, 4),
                    round(rnd.uniform(0, 2), 4),
                    round(rnd.uniform(0.40, 0.80), 4),
                    round(rnd.uniform(-0.78, 0.78), 4),
                )
            )
    fruits = write_map(tmp_path / "m.csv", fr)
    makespan = {}
    for method in ("fov", "serial", "milp"):
        out = str(tmp_path / f"{method}.json")
        run(*plan_args(real_tables, fruits, out, method, "--quiet", "--time-limit", "120"), check=0)
        plan = json.load(open(out))
        t = plan["totals"]
        assert t["fruits_planned"] + t["fruits_unreachable"] == len(fr)
        makespan[method] = t["makespan_s"]
        run("check", out, check=0)
    assert makespan["milp"] <= makespan["fov"] + 1e-6
    assert makespan["milp"] <= makespan["serial"] + 1e-6


def test_horizon_compare_single(tables, tmp_path):
    fruits = write_map(tmp_path / "m.csv", random_fruits(12, 12, seed=31))
    out = str(tmp_path / "p.json")
    p = run(
        *plan_args(
            tables,
            fruits,
            out,
            "milp",
            "--horizon",
            "1",
            "--compare-single",
            "--time-limit",
            "60",
            "--quiet",
        ),
        check=0,
    )
    line = [ln for ln in p.stdout.splitlines() if ln.startswith("compare:")]
    assert len(line) == 1, p.stdout
    horizon = float(line[0].split("horizon makespan ")[1].split(" s")[0])
    assert horizon == pytest.approx(json.load(open(out))["totals"]["makespan_s"], abs=1e-3)
    if "(optimal" in line[0]:
        single = float(line[0].split("single window ")[1].split(" s")[0])
        assert horizon >= single - 1e-3  # a window plan cannot beat the row's optimum
    run(*plan_args(tables, fruits, out, "milp", "--compare-single"), check=2)


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_interrupt_writes_the_best_plan_so_far(tables, tmp_path, sig):
    """Ctrl-C / SIGTERM during a long solve: the solver stops as at its time limit, and the
    best plan so far is checked and written with an honest status (exit 5)."""
    fr = random_fruits(60, 240, seed=41)
    fruits = write_map(tmp_path / "m.csv", fr)
    out = tmp_path / "p.json"
    p = subprocess.Popen(
        [PLAN, *plan_args(tables, fruits, str(out), "milp", "--time-limit", "600")],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        seen = []
        for line in p.stderr:  # the solve is under way once it has a first plan
            seen.append(line)
            if line.startswith("milp: incumbent"):
                break
        assert p.poll() is None, "".join(seen)
        p.send_signal(sig)
        _, rest = p.communicate(timeout=120)
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
    err = "".join(seen) + rest
    assert p.returncode == 5, err
    assert "interrupted after" in err and "writing the best plan so far" in err
    plan = json.load(open(out))
    assert plan["solver"]["status"] == "feasible" and plan["solver"]["gap"] > 0
    picked = [pk["id"] for s in plan["stops"] for arm in ("left", "right") for pk in s[arm]]
    assert len(picked) == len(set(picked)) == plan["totals"]["fruits_planned"]
    assert plan["totals"]["fruits_planned"] + plan["totals"]["fruits_unreachable"] == len(fr)
    run("check", str(out), check=0)
