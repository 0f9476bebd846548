"""The plan's top view draws each arm base where the plan's config puts it (docs/FRAMES.md:
left base ahead of the stop by half mount.base_spacing, right behind; both at
|x| = aisle_width / 2 - mount.offset), and the experiments read a plan's inputs relative to
the plan's folder, not the current directory."""

import os

import pytest
from exp_helpers import CONFIG

from harvest.experiments import plan_file, plan_view
from harvest.experiments.figures import plt
from harvest.scenario.config import Config, Row, derived_config_text
from harvest.scenario.fruit_map import Fruit

STOP_Y = 1.0


def _plan(config, fruit_map="m.csv"):
    pick = {"x": -0.42, "y": 1.05, "z": 0.6, "yaw": 0.0, "cost_s": 2.0, "start_s": 0.0}
    return {
        "method": "milp",
        "inputs": {
            "fruit_map": fruit_map,
            "cost_table_left": "l.tab",
            "cost_table_right": "r.tab",
            "config": config,
        },
        "totals": {"makespan_s": 30.0},
        "stops": [
            {
                "index": 100,
                "y_m": STOP_Y,
                "pass": 0,
                "C_left_s": 2.0,
                "C_right_s": 2.5,
                "C_s": 2.5,
                "idle_left_s": 0.5,
                "idle_right_s": 0.0,
                "left": [dict(pick, id="L1")],
                "right": [dict(pick, id="R1", x=0.44, y=0.9, cost_s=2.5)],
            }
        ],
    }


@pytest.mark.parametrize("spacing,offset", [(0.47, 0.26), (0.6, 0.1)])
def test_bases_drawn_where_the_config_puts_them(tmp_path, spacing, offset):
    cfg_path = tmp_path / "h.cfg"
    cfg_path.write_text(
        derived_config_text(CONFIG, {"mount.base_spacing": spacing, "mount.offset": offset})
    )
    cfg = Config.load(str(cfg_path))
    half_aisle = cfg.float("row.aisle_width") / 2.0
    want = {
        "left": (STOP_Y + spacing / 2.0, -(half_aisle - offset)),
        "right": (STOP_Y - spacing / 2.0, half_aisle - offset),
    }
    plan = _plan(str(cfg_path))
    fruits = [Fruit("L1", "L", -0.42, 1.05, 0.6, 0.0), Fruit("R1", "R", 0.44, 0.9, 0.6, 0.0)]
    fig = plan_view.plan_figure(plan, fruits, Row(cfg).arm_bases())
    try:
        top = fig.axes[0]
        bases = sorted(
            (float(ln.get_xdata()[0]), float(ln.get_ydata()[0]))
            for ln in top.get_lines()
            if ln.get_marker() == "^"
        )
        assert len(bases) == 2
        for got, exp in zip(bases, sorted(want.values())):
            assert got == pytest.approx(exp)
        # each fruit is joined to its own arm's base
        for arm, fr in (("left", fruits[0]), ("right", fruits[1])):
            joins = [
                ln
                for ln in top.get_lines()
                if len(ln.get_xdata()) == 2
                and tuple(ln.get_xdata()) == pytest.approx((want[arm][0], fr.y))
            ]
            assert joins and tuple(joins[0].get_ydata()) == pytest.approx((want[arm][1], fr.x))
    finally:
        plt.close(fig)


def test_plan_inputs_resolve_against_the_plan_folder(tmp_path, monkeypatch):
    folder = tmp_path / "plans"
    folder.mkdir()
    path = str(folder / "p.json")
    plan = _plan("../cfg/h.cfg")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    assert plan_file.input_path(path, plan, "fruit_map") == os.path.join(str(folder), "m.csv")
    assert os.path.normpath(plan_file.input_path(path, plan, "config")) == str(
        tmp_path / "cfg" / "h.cfg"
    )
    plan["inputs"]["config"] = CONFIG  # absolute: as written
    assert plan_file.input_path(path, plan, "config") == CONFIG
    del plan["inputs"]["fruit_map"]
    with pytest.raises(plan_file.PlanError, match=r"p\.json: field 'inputs\.fruit_map'"):
        plan_file.input_path(path, plan, "fruit_map")


def test_the_legends_cover_no_data():
    """Each axes' legend is drawn beside it, outside the area that holds the data."""
    cfg = Config.load(CONFIG)
    fruits = [Fruit("L1", "L", -0.42, 1.05, 0.6, 0.0), Fruit("X9", "R", 0.45, 1.6, 0.5, 0.0)]
    fig = plan_view.plan_figure(_plan(CONFIG), fruits, Row(cfg).arm_bases())
    try:
        fig.canvas.draw()
        axes = fig.axes[:2]
        assert all(ax.get_legend() is not None for ax in axes)
        for ax in axes:
            legend = ax.get_legend().get_window_extent()
            for other in axes:
                assert not legend.overlaps(other.get_window_extent()), ax.get_ylabel()
        key = [t.get_text() for t in axes[0].get_legend().get_texts()]
        assert "not picked" in key and "arm base" in key
    finally:
        plt.close(fig)
