"""End-to-end tests of tools/: costgen and mountopt driven as programs.

Coarse grids (derived from config/harvest.cfg at test time) keep the suite fast under
ASan; one table is built from the real configuration at the paper's 0.01 m grid.
"""

import json
import os
import re
import subprocess

import pytest

SOURCE_DIR = os.environ.get("HV_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
BUILD_DIR = os.environ.get("HV_BUILD_DIR", os.path.join(SOURCE_DIR, "build"))
REAL_CONFIG = os.path.join(SOURCE_DIR, "config", "harvest.cfg")
COSTGEN = os.path.join(BUILD_DIR, "tools", "costgen")
MOUNTOPT = os.path.join(BUILD_DIR, "tools", "mountopt")
SPOTCHECK = os.path.join(BUILD_DIR, "tests", "tools", "costtab_spotcheck")

COARSE = {
    "grid.step": "0.05",
    "grid.yaw_step_deg": "15",
    "grid.y_half_span": "0.6",
    "search.offset_step": "0.05",
    "search.theta_step_deg": "30",
}


def _need(path):
    if not os.path.exists(path):
        pytest.skip(f"SKIPPED: {path} not built (HV_BUILD_DIR={BUILD_DIR})")


def run(args, check=False):
    p = subprocess.run(args, capture_output=True, text=True, timeout=600)
    if check and p.returncode != 0:
        raise AssertionError(
            f"{args} exited {p.returncode}\nstdout:\n{p.stdout}\nstderr:\n{p.stderr}"
        )
    return p


def derived_config(tmp_path, changes=None, drop=(), extra_lines=(), name="harvest.cfg"):
    """The real config with some keys replaced (value None: the line removed)."""
    changes = dict(COARSE, **(changes or {}))
    out = []
    with open(REAL_CONFIG) as f:
        for line in f:
            key = (
                line.split("=", 1)[0].strip()
                if "=" in line and not line.lstrip().startswith("#")
                else None
            )
            if key in drop:
                continue
            if key in changes:
                line = f"{key} = {changes[key]}\n"
            out.append(line)
    out.extend(extra_lines)
    path = tmp_path / name
    path.write_text("".join(out))
    return str(path)


@pytest.fixture(autouse=True)
def _built():
    for p in (COSTGEN, MOUNTOPT, SPOTCHECK):
        _need(p)


# ---------------------------------------------------------------- help and usage


@pytest.mark.parametrize("prog", [COSTGEN, MOUNTOPT])
def test_help(prog):
    p = run([prog, "--help"], check=True)
    assert "usage:" in p.stdout and "--config" in p.stdout and "Exit codes" in p.stdout


@pytest.mark.parametrize(
    "args, needle",
    [
        ([COSTGEN, "--side", "up"], "--side"),
        ([COSTGEN, "--threads", "0"], "--threads"),
        ([COSTGEN, "--offset", "nan"], "--offset"),
        ([COSTGEN, "--out", "x.bin"], "--out"),
        ([COSTGEN, "--bogus"], "--bogus"),
        ([MOUNTOPT, "--objective", "max"], "--objective"),
        ([MOUNTOPT, "stray"], "stray"),
    ],
)
def test_bad_command_line(args, needle):
    p = run(args)
    assert p.returncode == 2, p.stderr
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0], p.stderr


# ---------------------------------------------------------------- costgen


def parse_costgen(stdout):
    rows = {}
    for m in re.finditer(
        r"costgen: (left|right) arm -> (\S+): (\d+) cells .*?reachable (\d+) "
        r"\(([\d.]+) %\), (\d+) bytes",
        stdout,
    ):
        rows[m.group(1)] = dict(
            path=m.group(2), cells=int(m.group(3)), reachable=int(m.group(4)), bytes=int(m.group(6))
        )
    return rows


def test_costgen_coarse_tables_agree_with_direct_ik(tmp_path):
    cfg = derived_config(tmp_path)
    p = run([COSTGEN, "--config", cfg, "--out-dir", str(tmp_path), "--check", "300"], check=True)
    rows = parse_costgen(p.stdout)
    assert set(rows) == {"left", "right"}
    assert p.stdout.count("--check: 300 random cells agree") == 2
    for side, r in rows.items():
        assert os.path.getsize(r["path"]) == r["bytes"] == 512 + 2 * r["cells"]
        assert 0 < r["reachable"] < r["cells"]
        s = run([SPOTCHECK, cfg, r["path"], side, "2000", "7"], check=True)
        m = re.search(
            r"cells (\d+) reachable (\d+) fraction ([\d.]+) checked 2000 mismatches 0", s.stdout
        )
        assert m, s.stdout
        assert int(m.group(1)) == r["cells"] and int(m.group(2)) == r["reachable"]
        assert float(m.group(3)) > 0.0
    # The layout is symmetric under a half turn about z: both arms reach as many cells.
    assert rows["left"]["reachable"] == rows["right"]["reachable"]
    assert "costgen: left:" in p.stderr  # progress line


def test_costgen_deterministic_across_threads(tmp_path):
    cfg = derived_config(tmp_path)
    a, b = tmp_path / "a.bin", tmp_path / "b.bin"
    run(
        [COSTGEN, "--config", cfg, "--side", "right", "--out", str(a), "--threads", "1", "--quiet"],
        check=True,
    )
    run(
        [COSTGEN, "--config", cfg, "--side", "right", "--out", str(b), "--threads", "3", "--quiet"],
        check=True,
    )
    assert a.read_bytes() == b.read_bytes()


def test_costgen_elbow_free_reaches_no_less(tmp_path):
    cfg = derived_config(tmp_path)
    one = tmp_path / "one.bin"
    free = tmp_path / "free.bin"
    p1 = run([COSTGEN, "--config", cfg, "--side", "left", "--out", str(one), "--quiet"], check=True)
    p2 = run(
        [
            COSTGEN,
            "--config",
            cfg,
            "--side",
            "left",
            "--out",
            str(free),
            "--elbow-free",
            "--quiet",
            "--check",
            "200",
        ],
        check=True,
    )
    r1, r2 = parse_costgen(p1.stdout)["left"], parse_costgen(p2.stdout)["left"]
    # lifting the limit only adds solutions: never fewer reachable cells
    assert r2["reachable"] >= r1["reachable"]
    run([SPOTCHECK, cfg, str(free), "left", "1000", "3", "--elbow-free"], check=True)
    # The checker refuses a table built for another elbow setting.
    bad = run([SPOTCHECK, cfg, str(free), "left", "10", "3"])
    assert bad.returncode == 1 and "elbow_free" in bad.stderr


def test_costgen_offset_override_changes_the_table(tmp_path):
    cfg = derived_config(tmp_path)
    a, b = tmp_path / "a.bin", tmp_path / "b.bin"
    run([COSTGEN, "--config", cfg, "--side", "right", "--out", str(a), "--quiet"], check=True)
    run(
        [
            COSTGEN,
            "--config",
            cfg,
            "--side",
            "right",
            "--out",
            str(b),
            "--offset",
            "0.15",
            "--theta-deg",
            "-40",
            "--quiet",
            "--check",
            "200",
        ],
        check=True,
    )
    assert a.read_bytes() != b.read_bytes()
    # The checker, given the config without the override, finds the cells that moved.
    p = run([SPOTCHECK, cfg, str(b), "right", "2000", "5"])
    assert p.returncode == 1 and re.search(r"mismatches [1-9]", p.stdout), p.stdout


def test_costgen_real_config_table_loads(tmp_path):
    """The paper's 0.01 m grid from the real config: one side, spot-checked."""
    out = tmp_path / "right.bin"
    p = run(
        [COSTGEN, "--config", REAL_CONFIG, "--side", "right", "--out", str(out), "--check", "200"],
        check=True,
    )
    r = parse_costgen(p.stdout)["right"]
    # grid of config/harvest.cfg: x 16, y 161, z 41, yaw 19
    assert r["cells"] == 16 * 161 * 41 * 19
    assert 0.0 < r["reachable"] / r["cells"] < 1.0
    run([SPOTCHECK, REAL_CONFIG, str(out), "right", "500", "11"], check=True)


def test_corrupted_table_is_refused(tmp_path):
    cfg = derived_config(tmp_path)
    out = tmp_path / "t.bin"
    run([COSTGEN, "--config", cfg, "--side", "left", "--out", str(out), "--quiet"], check=True)
    data = bytearray(out.read_bytes())
    data[600] ^= 0x01
    out.write_bytes(bytes(data))
    p = run([SPOTCHECK, cfg, str(out), "left", "10", "1"])
    assert p.returncode == 1
    assert p.stderr.startswith(str(out) + ": ") and "crc" in p.stderr.lower()
    out.write_bytes(bytes(data[:700]))
    p = run([SPOTCHECK, cfg, str(out), "left", "10", "1"])
    assert p.returncode == 1 and p.stderr.startswith(str(out) + ": ")


def test_costgen_unwritable_output(tmp_path):
    cfg = derived_config(tmp_path)
    p = run([COSTGEN, "--config", cfg, "--out-dir", str(tmp_path / "missing" / "dir"), "--quiet"])
    assert p.returncode == 1
    assert str(tmp_path / "missing" / "dir") in p.stderr
    assert not list(tmp_path.glob("missing*"))


def test_costgen_nothing_reachable_is_an_error(tmp_path):
    cfg = derived_config(tmp_path)
    p = run(
        [
            COSTGEN,
            "--config",
            cfg,
            "--side",
            "right",
            "--out",
            str(tmp_path / "x.bin"),
            "--offset",
            "2.0",
            "--quiet",
        ]
    )
    assert p.returncode == 2 and "no cell" in p.stderr  # the config (and --offset) at fault
    assert not (tmp_path / "x.bin").exists()


# ---------------------------------------------------------------- mountopt


def mountopt_json(tmp_path, *extra, cfg=None):
    cfg = cfg or derived_config(tmp_path)
    js = tmp_path / ("m%d.json" % len(list(tmp_path.glob("m*.json"))))
    p = run([MOUNTOPT, "--config", cfg, "--json", str(js), *extra], check=True)
    return p, json.loads(js.read_text())


def totals_by_pose(doc, key):
    """Every (D, theta_L, theta_R) installation's total, from the per-side candidates."""
    per = {}
    for c in doc["candidates"]:
        per.setdefault((round(c["offset_m"], 9), c["side"]), []).append((c["theta_deg"], c[key]))
    out = {}
    for (d, side), lst in per.items():
        if side != "left":
            continue
        for tl, vl in lst:
            for tr, vr in per[(d, "right")]:
                out[(d, tl, tr)] = vl + vr
    return out


def test_mountopt_best_is_the_maximum(tmp_path):
    p, doc = mountopt_json(tmp_path)
    n_off, n_th = len(doc["offsets_m"]), len(doc["thetas_deg"])
    assert n_off == 6 and n_th == 7  # 0.10..0.35 by 0.05, -90..90 by 30
    assert len(doc["candidates"]) == 2 * n_off * n_th
    totals = totals_by_pose(doc, "points")
    best = doc["best"]
    assert best["objective_total"] == max(totals.values()) > 0
    key = (round(best["offset_m"], 9), best["theta_deg"]["left"], best["theta_deg"]["right"])
    assert totals[key] == best["objective_total"]
    # The report of the best pose re-evaluates it: the same counts, suction computed too.
    ours = doc["reports"][0]
    assert ours["label"].startswith("ours")
    assert sum(s["points"] for s in ours["sides"]) == best["objective_total"]
    for s in ours["sides"]:
        assert 0 <= s["stem_positions"] <= s["any_yaw_positions"] <= s["suction_positions"]
        assert s["yaw0_positions"] <= s["any_yaw_positions"]
    labels = [r["label"] for r in doc["reports"]]
    assert "paper (43.5 deg)" in labels
    paper = doc["reports"][labels.index("paper (43.5 deg)")]
    assert paper["offset_m"] == pytest.approx(0.26)
    assert all(s["theta_deg"] == pytest.approx(43.5) for s in paper["sides"])
    # Printed beside ours, with a progress line on stderr.
    assert "paper (43.5 deg)" in p.stdout and "best (points): D =" in p.stdout
    assert "mountopt: candidates" in p.stderr
    assert "left/right symmetry: 0 of 42 candidates differ" in p.stdout


def test_mountopt_stem_objective(tmp_path):
    _, doc = mountopt_json(tmp_path, "--objective", "stem", "--quiet")
    totals = totals_by_pose(doc, "stem_positions")
    assert doc["best"]["objective_total"] == max(totals.values())


def test_mountopt_suction_objective_one_side(tmp_path):
    _, doc = mountopt_json(tmp_path, "--objective", "suction", "--side", "right", "--quiet")
    vals = [c["suction_positions"] for c in doc["candidates"]]
    assert all(v >= 0 for v in vals) and len(vals) == 42
    assert doc["best"]["objective_total"] == max(vals)
    assert list(doc["best"]["theta_deg"]) == ["right"]


def test_mountopt_full_z_gives_the_same_counts(tmp_path):
    cfg = derived_config(tmp_path, {"search.offset_step": "0.1", "search.theta_step_deg": "45"})
    _, fast = mountopt_json(tmp_path, "--side", "left", "--quiet", cfg=cfg)
    _, full = mountopt_json(tmp_path, "--side", "left", "--quiet", "--full-z", cfg=cfg)
    assert fast["candidates"] == full["candidates"]


# ---------------------------------------------------------------- bad configurations

BAD_CONFIGS = [
    # (changes, drop, extra lines, key named, line given?)
    ({}, ("joint2.vmax",), (), "joint2.vmax", False),  # missing
    ({"grid.step": "0"}, (), (), "grid.step", True),  # out of range
    ({"mount.offset": "-0.1"}, (), (), "mount.offset", True),  # out of range
    ({"row.pick_yaw_max_deg": "abc"}, (), (), "row.pick_yaw_max_deg", True),  # not a number
    ({"arm.home": "0.25 0.0 1.4"}, (), (), "arm.home", True),  # too few values
    ({}, (), ("grid.colour = 3\n",), "grid.colour", True),  # unknown key
    ({}, (), ("joint1.max = 0.5\n",), "joint1.max", True),  # duplicate
    ({"search.offset_max": "0.05"}, (), (), "search.offset_max", False),  # relation
    ({"arm.home": "0.9 0.0 1.4 0.0"}, (), (), "arm.home", False),  # home outside limits
]


@pytest.mark.parametrize("prog", ["costgen", "mountopt"])
@pytest.mark.parametrize("changes, drop, extra, key, has_line", BAD_CONFIGS)
def test_bad_config(tmp_path, prog, changes, drop, extra, key, has_line):
    cfg = derived_config(tmp_path, changes, drop, extra)
    exe = COSTGEN if prog == "costgen" else MOUNTOPT
    args = [exe, "--config", cfg, "--quiet"]
    if prog == "costgen":
        args += ["--out-dir", str(tmp_path)]
    p = run(args)
    assert p.returncode == 2, (p.stdout, p.stderr)
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1, p.stderr
    where = f"{prog}: {cfg}"
    pattern = re.escape(where) + (r":\d+: " if has_line else r": ") + re.escape(key) + r": \S"
    assert re.match(pattern, lines[0]), lines[0]
    if has_line:
        # The line number points at the offending line (or the appended one).
        n = int(lines[0][len(where) + 1 :].split(":", 1)[0])
        text = open(cfg).read().splitlines()[n - 1]
        assert text.split("=")[0].strip() == key
    assert not list(tmp_path.glob("costtab_*.bin"))


@pytest.mark.parametrize("exe", [COSTGEN, MOUNTOPT])
def test_missing_config_file(tmp_path, exe):
    path = str(tmp_path / "nope.cfg")
    p = run([exe, "--config", path])
    assert p.returncode == 2
    assert p.stderr.startswith(f"{os.path.basename(exe)}: {path}: ")
    assert len(p.stderr.strip().splitlines()) == 1
