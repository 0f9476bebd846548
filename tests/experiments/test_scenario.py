"""The scenario generator: bounds of the fruit-planted area, seeds, counts, distributions."""

import math
import os

import numpy as np
import pytest
from exp_helpers import CONFIG, harvest

from harvest.scenario import fruit_map, generate
from harvest.scenario.config import Config, ConfigError, Row

ROW = Row(Config.load(CONFIG))
EPS = 1e-4  # the CSV keeps 0.1 mm


def check_bounds(fruits, length_m):
    for f in fruits:
        assert f.side in ("L", "R")
        assert (f.x < 0) == (f.side == "L"), f
        assert ROW.x_near_m - EPS <= abs(f.x) <= ROW.x_far_m + EPS, f
        assert -EPS <= f.y <= length_m + EPS, f
        assert ROW.canopy_z_min_m - EPS <= f.z <= ROW.z_max_m + EPS, f
        assert abs(f.yaw) <= ROW.yaw_max_rad + 1e-5, f
    assert len({f.id for f in fruits}) == len(fruits)


def test_config_numbers_come_from_the_file():
    assert ROW.length_m == 2.0 and ROW.x_near_m == pytest.approx(0.35)
    assert ROW.x_far_m == pytest.approx(0.50) and ROW.z_max_m == pytest.approx(0.80)
    assert ROW.yaw_max_rad == pytest.approx(math.radians(45))


def test_config_errors_name_file_and_key(tmp_path):
    text = open(CONFIG).read().replace("row.canopy_depth = 0.15", "row.canopy_depth = deep")
    bad = tmp_path / "bad.cfg"
    bad.write_text(text)
    with pytest.raises(ConfigError, match=r"bad\.cfg:\d+: 'row.canopy_depth' is not numeric"):
        Row(Config.load(str(bad)))
    bad.write_text(open(CONFIG).read().replace("row.length = 2.0", ""))
    with pytest.raises(ConfigError, match=r"bad\.cfg: missing key 'row.length'"):
        Row(Config.load(str(bad)))


@pytest.mark.parametrize("alpha", [0.25, 0.4, 1.0, 2.5, 4.0])
def test_uniform_counts_and_bounds(alpha):
    fruits = generate.generate("uniform", ROW, 50, alpha, seed=3)
    assert sum(f.side == "L" for f in fruits) == 50
    assert sum(f.side == "R" for f in fruits) == round(alpha * 50)
    check_bounds(fruits, ROW.length_m)


def test_uniform_fills_the_box():
    """Uniform really spans the box: 2000 fruits reach near every face of it."""
    fruits = generate.generate("uniform", ROW, 1000, 1.0, seed=1)
    xs = np.array([abs(f.x) for f in fruits])
    ys = np.array([f.y for f in fruits])
    yaws = np.array([f.yaw for f in fruits])
    assert xs.min() < ROW.x_near_m + 0.01 and xs.max() > ROW.x_far_m - 0.01
    assert ys.min() < 0.02 and ys.max() > ROW.length_m - 0.02
    assert yaws.min() < -ROW.yaw_max_rad + 0.02 and yaws.max() > ROW.yaw_max_rad - 0.02


@pytest.mark.parametrize("dist", ["clustered", "gradient"])
def test_other_distributions_bounds_and_counts(dist):
    fruits = generate.generate(dist, ROW, 60, 2.5, seed=5)
    assert sum(f.side == "L" for f in fruits) == 60
    assert sum(f.side == "R" for f in fruits) == 150
    check_bounds(fruits, ROW.length_m)


def _mean_nn_distance(fruits):
    p = np.array([[f.x, f.y, f.z] for f in fruits if f.side == "L"])
    d = np.linalg.norm(p[:, None, :] - p[None, :, :], axis=2)
    np.fill_diagonal(d, np.inf)
    return d.min(axis=1).mean()


def test_clustered_fruits_are_closer_together_than_uniform():
    u = generate.generate("uniform", ROW, 200, 1.0, seed=2)
    c = generate.generate("clustered", ROW, 200, 1.0, seed=2)
    assert _mean_nn_distance(c) < 0.6 * _mean_nn_distance(u)


def test_gradient_puts_more_fruit_towards_the_end():
    fruits = generate.generate("gradient", ROW, 500, 1.0, seed=4, gradient_g=0.8)
    late = sum(f.y > ROW.length_m / 2 for f in fruits) / len(fruits)
    assert 0.62 < late < 0.78  # expected 0.70 for g = 0.8
    flipped = generate.generate("gradient", ROW, 500, 1.0, seed=4, gradient_g=-0.8)
    assert sum(f.y > ROW.length_m / 2 for f in flipped) / len(flipped) < 0.38


def test_cli_same_seed_same_file_and_seeds_differ(tmp_path):
    a, b, c = (str(tmp_path / n) for n in ("a.csv", "b.csv", "c.csv"))
    for out, seed in ((a, 7), (b, 7), (c, 8)):
        r = harvest(
            "scenario", "--config", CONFIG, "--alpha", "0.4", "--seed", str(seed), "--out", out
        )
        assert r.returncode == 0, r.stderr
    assert open(a, "rb").read() == open(b, "rb").read()
    assert open(a, "rb").read() != open(c, "rb").read()
    fruits = fruit_map.read(a)
    assert [f.side for f in fruits].count("L") == 50 and [f.side for f in fruits].count("R") == 20
    check_bounds(fruits, ROW.length_m)
    assert open(a).readline().strip() == "id,side,x,y,z,yaw"


def test_cli_long_row_needs_and_writes_a_matching_config(tmp_path):
    out, cfg = str(tmp_path / "long.csv"), str(tmp_path / "long.cfg")
    r = harvest("scenario", "--config", CONFIG, "--distribution", "long", "--out", out)
    assert r.returncode == 2 and "--config-out" in r.stderr and not os.path.exists(out)
    r = harvest(
        "scenario",
        "--config",
        CONFIG,
        "--distribution",
        "long",
        "--length",
        "24",
        "--out",
        out,
        "--config-out",
        cfg,
    )
    assert r.returncode == 0, r.stderr
    fruits = fruit_map.read(out)
    assert sum(f.side == "L" for f in fruits) == 600  # the paper's 25 fruits/m over 24 m
    check_bounds(fruits, 24.0)
    assert max(f.y for f in fruits) > 23.0
    long_row = Row(Config.load(cfg))
    assert long_row.length_m == 24.0 and long_row.canopy_depth_m == ROW.canopy_depth_m


def test_fruit_map_reader_rejects_bad_fields(tmp_path):
    p = tmp_path / "m.csv"
    p.write_text("id,side,x,y,z,yaw\n1,L,-0.4,0.5,0.6,0\n2,Q,0.4,0.5,0.6,0\n")
    with pytest.raises(fruit_map.FruitMapError, match=r"m\.csv:3: field 'side'"):
        fruit_map.read(str(p))
    p.write_text("id,side,x,y,z,yaw\n1,L,-0.4,nan,0.6,0\n")
    with pytest.raises(fruit_map.FruitMapError, match=r"m\.csv:2: field 'y'"):
        fruit_map.read(str(p))


# The id set as docs/FRAMES.md spells it (core/include/hv/fruit_id.h in C).
ID_SET = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_.-"


def test_fruit_id_set_is_the_documented_one():
    for code in range(256):
        ch = chr(code)
        assert (fruit_map.check_id("a" + ch + "z") is None) == (ch in ID_SET), repr(ch)
    assert fruit_map.check_id("x" * 31) is None
    assert "more than 31" in fruit_map.check_id("x" * 32)
    assert fruit_map.check_id("") == "empty"


@pytest.mark.parametrize(
    "field,why",
    [
        ('"a\nb"', r"m\.csv:3: field 'id' 'a\\nb': character '\\n' at position 2"),
        ("fruit 7", r"m\.csv:3: field 'id' 'fruit 7': character ' ' at position 6"),
        ('"a,b"', r"m\.csv:3: field 'id' 'a,b': character ','"),
        ("x" * 32, r"m\.csv:3: field 'id' 'x+': 32 characters"),
        ("", r"m\.csv:3: field 'id' '': empty"),
        ("1", r"m\.csv:3: field 'id' is repeated"),
    ],
)
def test_fruit_map_reader_refuses_bad_ids(tmp_path, field, why):
    p = tmp_path / "m.csv"
    p.write_text(f"id,side,x,y,z,yaw\n1,L,-0.4,0.5,0.6,0\n{field},R,0.4,0.5,0.6,0\n")
    with pytest.raises(fruit_map.FruitMapError, match=why):
        fruit_map.read(str(p))


def test_fruit_map_writer_refuses_bad_ids_and_writes_nothing(tmp_path):
    good = fruit_map.Fruit("L000", "L", -0.4, 0.5, 0.6, 0.0)
    bad = fruit_map.Fruit("R\n001", "R", 0.4, 0.5, 0.6, 0.0)
    p = tmp_path / "m.csv"
    with pytest.raises(fruit_map.FruitMapError, match=r"fruit 1: field 'id'.*position 2"):
        fruit_map.write(str(p), [good, bad])
    assert not p.exists() and list(tmp_path.iterdir()) == []
    fruit_map.write(str(p), [good])
    assert fruit_map.read(str(p)) == [good]
