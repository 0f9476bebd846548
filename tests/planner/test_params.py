"""The solver's parameter table: `harvest-plan --help-params` prints it, planner/SOLVER.md
holds that very text, and it has a row for every option field of hv_milp_options_t and
every constant of planner/src/milp_tunables.h, with the constant's value."""

import os
import re
import subprocess

import pytest

SRC = os.environ.get(
    "HV_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
BUILD = os.environ.get("HV_BUILD_DIR", os.path.join(SRC, "build"))
PLAN = os.path.join(BUILD, "planner", "harvest-plan")

pytestmark = pytest.mark.skipif(
    not os.access(PLAN, os.X_OK), reason="SKIPPED: harvest-plan not built in HV_BUILD_DIR"
)


@pytest.fixture(scope="module")
def table():
    p = subprocess.run([PLAN, "--help-params"], capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr
    return p.stdout


def rows(text):
    out = {}
    for line in text.splitlines()[2:]:
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        assert len(cells) == 6, line
        out[cells[0]] = cells
    return out


def read(*path):
    with open(os.path.join(SRC, *path)) as f:
        return f.read()


def test_solver_md_holds_the_table(table):
    md = read("planner", "SOLVER.md")
    m = re.search(
        r"<!-- harvest-plan --help-params: begin -->\n(.*?)"
        r"<!-- harvest-plan --help-params: end -->",
        md,
        re.S,
    )
    assert m, "planner/SOLVER.md has no parameter block"
    assert m.group(1) == table, "planner/SOLVER.md's table differs from harvest-plan --help-params"


def test_every_constant_is_a_row_with_its_value(table):
    r = rows(table)
    defines = re.findall(
        r"^#define (\w+)\s+([0-9.eE+-]+)[uUlL]*\s*$",
        read("planner", "src", "milp_tunables.h"),
        re.M,
    )
    assert len(defines) > 20
    for name, value in defines:
        assert name in r, name + " is not in the table"
        assert r[name][1] == "constant"
        assert float(r[name][2]) == pytest.approx(float(value), rel=1e-5), name


def test_every_option_field_is_a_row(table):
    r = rows(table)
    header = read("planner", "include", "hv", "milp_options.h")
    body = re.search(
        r"typedef struct hv_milp_options \{(.*?)\} hv_milp_options_t;", header, re.S
    ).group(1)
    body = re.sub(r"/\*.*?\*/", "", body, flags=re.S)
    fields = []
    for decl in re.findall(r"\b(?:int|double)\s+([^;(]+);", body):
        fields += [f.strip() for f in decl.split(",")]
    assert len(fields) > 30
    for f in fields:
        assert f in r and r[f][1] == "option", f + " is not an option row"
    assert sum(1 for v in r.values() if v[1] == "option") == len(fields)


def test_an_option_out_of_range_is_refused_by_bench_milp():
    bench = os.path.join(BUILD, "bench", "planner", "bench_milp")
    if not os.access(bench, os.X_OK):
        pytest.skip("SKIPPED: bench_milp not built in HV_BUILD_DIR")
    for bad in ("tree_threads=3", "no_such_option=1", "rel_gap=x", "sr_keep_gain=2"):
        p = subprocess.run(
            [bench, "--set", bad, "--seeds", "0"], capture_output=True, text=True, timeout=60
        )
        assert p.returncode == 2, bad
        assert "--set" in p.stderr
