"""Online resume (issue 41): an online 5 m row (the simulator's camera, harvest-plan-online
and harvest-exec --online over CAN on UDP multicast and LCM, in a private network
namespace) is interrupted by SIGKILL and restarted on the same journals:

- harvest-exec alone is killed mid-row: the restart rebuilds the committed stops from its
  journal and the running planner's next message agrees with them;
- harvest-exec and then harvest-plan-online are killed (the planner once the vehicle stood,
  so it missed no camera frame): the planner's restart replays its own journal and commits
  nothing differently, the executor's rebuilds its stops;
- both killed, the planner restarted without its journal: the executor refuses its plan
  (HV_ERR_EXEC_PLAN_CONFLICT) and never grows its journalled one.

Judged by the simulator's record: every fruit of the committed plan (which the checker
finds holds every reachable fruit of the map exactly once) was cut exactly once at its
stop, none twice, and the vehicle reached the course's end.
"""

import json
import os
import signal
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exec_hil as H  # noqa: E402

_skip = H.enter_online_netns()
pytestmark = pytest.mark.skipif(bool(_skip), reason="SKIPPED: " + "; ".join(_skip))

SCALE = 20.0
LENGTH_M = 5.0


@pytest.fixture
def row(tmp_path):
    r = H.OnlineRow(tmp_path, LENGTH_M, seed=7, scale=SCALE)
    yield r
    r.close()


def kill(proc):
    proc.send_signal(signal.SIGKILL)
    proc.communicate(timeout=30)
    assert proc.returncode == -signal.SIGKILL


def vehicle_stood(row, before):
    """The simulated vehicle lost the executor's heartbeat (and stopped) more times than
    `before`."""
    return sum(e["node"] == "vehicle" for e in row.sim.events("comm_timeout")) > before


def judge(row, ex_proc, pl_proc, n_cut_before, planner_resumed):
    ex_out, ex_err = ex_proc.communicate(timeout=400)
    pl_out, pl_err = pl_proc.communicate(timeout=60)
    assert ex_proc.returncode == 0, ex_err[-3000:]
    assert pl_proc.returncode == 0, pl_err[-3000:]
    assert "resuming from" in ex_err and "committed stops rebuilt" in ex_err, ex_err[-2000:]
    assert ("resumed from" in pl_err) == planner_resumed, pl_err[-2000:]
    with open(row.dir / "exec2.json") as f:
        ex = json.load(f)
    with open(row.dir / "plan.json") as f:
        plan = json.load(f)
    planners = sorted(row.dir.glob("planner*.json"))
    with open(planners[-1]) as f:
        pl = json.load(f)
    det = pl["detections"]
    # the planner: every map fruit accepted once, over both of its runs when it restarted
    assert pl["done"] and det["accepted"] + det["unreachable"] == row.n_map, pl
    assert det["duplicate"] == det["late"] == 0 and pl["frames_lost"] == 0, pl
    check = H.check_plan(row.dir / "plan.json", row.cfg, row.fruits)
    assert check.returncode == 0, check.stdout + check.stderr
    # the restarted executor: the whole plan, nothing refused; some of it done before the kill
    assert ex["phase"] == "row_done" and ex["plan_final"] and ex["plan_refused"] == 0, ex
    assert ex["plan_stops"] == len(plan["stops"]) and ex["picked"] == det["accepted"], ex
    assert ex["picked_this_run"] < ex["picked"] and ex["failed"] == ex["skipped"] == 0, ex
    # the simulator's word: every committed fruit cut once at its stop, none twice, the
    # vehicle at the course's end
    assert 0 < n_cut_before < row.cuts()
    H.assert_every_fruit_cut_once(plan, row.sim)
    p = plan["params"]
    end = p["row_start_m"] + p["row_length_m"] + p["stop_margin_m"]
    assert any(abs(e["position"] - end) < 1e-3 for e in row.sim.events("arrived")), end


def test_executor_killed_mid_row(row):
    planner, ex1 = row.planner(1), row.executor(1)
    assert H.wait_for(lambda: row.cuts() >= row.n_map // 3, 300), "no harvest under way"
    kill(ex1)
    n_cut = row.cuts()
    ex2 = row.executor(2)
    judge(row, ex2, planner, n_cut, planner_resumed=False)


def kill_both(row):
    """Start both, kill harvest-exec after a third of the fruit, then the planner once the
    vehicle stood (so no camera frame was lost to it); the cuts so far."""
    pl1, ex1 = row.planner(1), row.executor(1)
    assert H.wait_for(lambda: row.cuts() >= row.n_map // 3, 300), "no harvest under way"
    stood = sum(e["node"] == "vehicle" for e in row.sim.events("comm_timeout"))
    kill(ex1)
    assert H.wait_for(lambda: vehicle_stood(row, stood), 30), "the vehicle never stopped"
    H.wait_for(lambda: False, 0.5)  # the last camera frame taken
    kill(pl1)
    return row.cuts()


def test_executor_and_planner_killed(row):
    n_cut = kill_both(row)
    pl2 = row.planner(2)
    ex2 = row.executor(2)
    judge(row, ex2, pl2, n_cut, planner_resumed=True)


def stop_records(path):
    with open(path) as f:
        return sum(line.startswith("P ") for line in f)


def test_a_planner_that_forgot_is_refused(row):
    """A planner restarted without its journal commits from scratch. With the camera's replay
    and the same config it may commit the journalled stops again; restarted also on another
    candidate grid (stops 2 cm apart), none of its stops can be the journal's. The restarted
    executor refuses its plan by name, never grows its journalled one, and, the wait for a
    stop it can take over, makes a controlled stop journalled as plan_timeout."""
    from harvest.scenario.config import derived_config_text

    kill_both(row)
    before = stop_records(row.dir / "exec.journal")
    # the executor's wait for the planner cut short (it must not be below the horizon limit)
    cfg2 = row.dir / "exec2.cfg"
    limits = {"online.horizon_limit_min": "1.0", "online.horizon_limit_max": "4.0"}
    cfg2.write_text(derived_config_text(row.cfg, {**limits, "online.wait_plan_timeout": "4.0"}))
    cfg_pl2 = row.dir / "planner2.cfg"
    cfg_pl2.write_text(derived_config_text(row.cfg, {**limits, "grid.step": "0.02"}))
    pl2 = row.planner(2, journal="fresh.journal", cfg=cfg_pl2)
    err_path = row.dir / "exec2.err"
    with open(err_path, "w") as err:
        ex2 = row.executor(2, stderr=err, cfg=cfg2)
        out, _ = ex2.communicate(timeout=120)
    pl2.communicate(timeout=30)
    assert pl2.returncode == 6  # it ends with the executor's controlled stop
    # refused by name: its course (another candidate grid) is not the journalled plan's
    assert "refused, the last for another course than the first message's" in (
        err_path.read_text()
    ), err_path.read_text()[-2000:]
    assert ex2.returncode == 6, out
    assert out.startswith("harvest-exec: stopped plan_timeout:"), out
    # the stop names why no plan came: the planner's plan, refused here
    assert "(online.wait_plan_timeout): the planner's committed plan refused here: " in out, out
    with open(row.dir / "exec.journal") as f:
        assert [ln.split()[1] for ln in f if ln.startswith("H ")] == ["plan_timeout"]
    assert stop_records(row.dir / "exec.journal") == before
    with open(row.dir / "exec2.json") as f:
        assert json.load(f)["plan_refused"] > 0
    # every cut a fruit of the map (forward kinematics of the recorded joints), none twice
    from harvest.scenario import fruit_map

    judge = H.fk_check.Judge(str(row.cfg))
    picks = row.sim.events("pick")
    cuts = judge.cut_fruits(None, picks, judge.identify_in_map(fruit_map.read(row.fruits), picks))
    assert len(set(cuts)) == len(cuts), f"a fruit was cut twice: {cuts}"
