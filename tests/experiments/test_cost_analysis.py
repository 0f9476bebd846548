"""Cost tables read with numpy, and the paper's two analysis figures, from the real costgen."""

import json
import subprocess

import numpy as np
import pytest
from exp_helpers import CONFIG, COSTGEN, harvest, require

from harvest.experiments import cost_table


@pytest.fixture(scope="module")
def tables(tmp_path_factory):
    require(COSTGEN, "tools/costgen")
    d = tmp_path_factory.mktemp("tables")
    r = subprocess.run(
        [COSTGEN, "--config", CONFIG, "--side", "both", "--out-dir", str(d), "--quiet"],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    assert r.returncode == 0, r.stdout
    return {s: str(d / f"costtab_{n}.bin") for s, n in (("L", "left"), ("R", "right"))}


@pytest.fixture(scope="module")
def analysis_dir(tmp_path_factory):
    require(COSTGEN, "tools/costgen")
    out = tmp_path_factory.mktemp("analysis")
    r = harvest(
        "experiments", "analysis", "--out", str(out), "--config", CONFIG, "--costgen", COSTGEN
    )
    assert r.returncode == 0, r.stderr
    return out


def test_tables_load_with_the_configured_grid(tables):
    left, right = cost_table.load(tables["L"]), cost_table.load(tables["R"])
    assert (left.side, right.side) == ("L", "R") and not right.elbow_free
    assert right.axes["x"].values()[0] == pytest.approx(0.35)
    assert left.axes["x"].values()[-1] == pytest.approx(-0.35)
    assert right.axes["y"].count == 161 and right.axes["yaw"].count == 19
    assert right.costs.shape == (16, 41, 19, 161)
    ok = right.reachable()
    assert 0 < ok.mean() < 1
    assert np.all(right.costs[ok] > 0)
    # The two arms are mirror images under a half turn: the same number of reachable cells.
    assert ok.sum() == left.reachable().sum()


def test_corrupt_or_short_tables_are_refused(tables, tmp_path):
    data = bytearray(open(tables["R"], "rb").read())
    bad = tmp_path / "bad.bin"
    data[600] ^= 0x01
    bad.write_bytes(bytes(data))
    with pytest.raises(cost_table.CostTableError, match="'payload_crc'"):
        cost_table.load(str(bad))
    bad.write_bytes(bytes(data[:300]))
    with pytest.raises(cost_table.CostTableError, match="'header'"):
        cost_table.load(str(bad))
    data[600] ^= 0x01
    data[0] = ord("X")
    bad.write_bytes(bytes(data))
    with pytest.raises(cost_table.CostTableError, match="'magic'"):
        cost_table.load(str(bad))


def test_analysis_table_agrees_with_the_experiment_table(tables, analysis_dir):
    """The widened analysis grid holds exactly the experiment table's costs where they overlap."""
    exp = cost_table.load(tables["R"])
    wide = cost_table.load(str(analysis_dir / "analysis_tables" / "right_limited.bin"))
    ix = [wide.axes["x"].index(x) for x in exp.axes["x"].values()]
    iyaw = [wide.axes["yaw"].index(v) for v in exp.axes["yaw"].values()]
    iz = exp.axes["z"].index(wide.axes["z"].origin)
    assert None not in ix and None not in iyaw and iz is not None
    assert wide.axes["y"].count == exp.axes["y"].count
    np.testing.assert_array_equal(wide.costs[ix][:, 0][:, iyaw, :], exp.costs[:, iz, :, :])


def test_analysis_figures_and_numbers(analysis_dir):
    for stem in ("cost_G_joint3", "coverage_pick_modes"):
        for ext in ("png", "svg"):
            p = analysis_dir / "figures" / f"{stem}.{ext}"
            assert p.stat().st_size > 10_000, p
    a = json.loads((analysis_dir / "analysis.json").read_text())
    cov = a["coverage_m2"]
    # The pick modes nest: every yaw <= yaw 0 <= some yaw <= position only; lifting the
    # elbow limit can only add reachable poses.
    assert 0 < cov["every yaw in +-45 deg"] <= cov["yaw 0"] <= cov["some yaw in +-45 deg"]
    assert cov["some yaw in +-45 deg"] <= cov["position only"]
    assert cov["yaw 0, joint 3 free"] >= cov["yaw 0"]
    assert a["roughness_s"]["limited"] > 0 and a["roughness_s"]["free"] > 0
