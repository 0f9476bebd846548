"""No silent waits online (issue 55): an online 5 m row (the simulator's camera,
harvest-plan-online and harvest-exec --online over CAN on UDP multicast and LCM, in a
private network namespace).

- A planner that refuses its input (here the journal of another row) says so on LCM
  (planner_status_t): the waiting executor prints the refusal, carries it in its telemetry
  (exec_state_t.planner) while it waits, and its controlled stop after
  online.wait_plan_timeout names it; nothing was cut.
- A planner killed mid-row and restarted on its journal while the camera revealed more
  fruit: it asks the camera to replay, recovers every fruit it missed and loses none; by
  the simulator's record every fruit the camera revealed is planned and cut once.
"""

import json
import os
import signal
import sys
import threading

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exec_hil as H  # noqa: E402

_skip = H.enter_online_netns()
pytestmark = pytest.mark.skipif(bool(_skip), reason="SKIPPED: " + "; ".join(_skip))

SCALE = 20.0
LENGTH_M = 5.0
WAIT_PLAN_TIMEOUT_S = 10.0


@pytest.fixture
def row(tmp_path):
    r = H.OnlineRow(tmp_path, LENGTH_M, seed=3, scale=SCALE)
    yield r
    r.close()


class ExecStates:
    """The executor's exec_state_t as they come (phase, planner), on a thread of its own."""

    def __init__(self):
        import lcm

        from harvest.telemetry import lcm_types

        self._type = lcm_types.load()["exec_state_t"]
        self._lcm = lcm.LCM(H.ONLINE_URL)
        self._lcm.subscribe("HARVEST_EXEC_STATE", self._on)
        self.seen = []
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _on(self, channel, data):
        m = self._type.decode(data)
        self.seen.append((m.phase, m.planner))

    def _run(self):
        while not self._stop.is_set():
            self._lcm.handle_timeout(100)

    def close(self):
        self._stop.set()
        self._thread.join(timeout=5)


def test_a_planner_refusal_is_shown_and_named_at_the_stop(row):
    from harvest.scenario.config import derived_config_text

    # a journal of another row: the planner's own, for a row 1 m longer
    other = row.dir / "other.cfg"
    other.write_text(derived_config_text(row.cfg, {"row.length": str(LENGTH_M + 1.0)}))
    journal = row.dir / "other.journal"
    p = row.planner(0, journal="other.journal", cfg=other, url="memq://")
    assert H.wait_for(lambda: journal.exists() and journal.stat().st_size > 0, 60)
    p.send_signal(signal.SIGTERM)
    p.communicate(timeout=60)
    assert p.returncode == 5  # interrupted before the row was planned
    # the executor's wait cut short (it must not be below the horizon limit)
    cfg = row.dir / "exec.cfg"
    limits = {"online.horizon_limit_min": "1.0", "online.horizon_limit_max": "4.0"}
    cfg.write_text(
        derived_config_text(
            row.cfg, {**limits, "online.wait_plan_timeout": str(WAIT_PLAN_TIMEOUT_S)}
        )
    )
    states = ExecStates()
    try:
        ex = row.executor(1, cfg=cfg)
        assert H.wait_for(lambda: any(ph == "wait_plan" for ph, _ in states.seen), 120)
        pl = row.planner(1, journal="other.journal")
        _, pl_err = pl.communicate(timeout=60)
        out, err = ex.communicate(timeout=120)
    finally:
        states.close()
    # the planner: bad input, one line naming the journal
    assert pl.returncode == 2, pl_err
    refusal = pl_err.strip()
    assert len(refusal.splitlines()) == 1 and str(journal) in refusal, pl_err
    assert refusal.startswith("harvest-plan-online: "), refusal
    # the executor: said as it came, in its telemetry while it waited, and at its stop
    note = f"the planner refused: {refusal}"
    assert f"harvest-exec: {note}\n" in err, err[-3000:]
    assert ("wait_plan", note) in states.seen, sorted(set(states.seen))[-5:]
    assert ex.returncode == 6, out + err[-2000:]
    assert out.startswith("harvest-exec: stopped plan_timeout:"), out
    assert f"(online.wait_plan_timeout): {note}\n" in out, out
    with open(row.dir / "exec1.json") as f:
        ex_sum = json.load(f)
    assert ex_sum["stop_reason"] == "plan_timeout" and ex_sum["planner"] == note, ex_sum
    assert ex_sum["planner_state"] == "refused" and ex_sum["planner_reason"] == refusal, ex_sum
    with open(row.dir / "exec.journal") as f:
        assert [ln.split()[1] for ln in f if ln.startswith("H ")] == ["plan_timeout"]
    # the simulator's word: no plan, so nothing was cut and the vehicle never moved
    assert row.sim.events("pick") == [] and row.sim.events("move") == []


def revealed(sim):
    """Fruit ids the simulated camera revealed so far, by its record."""
    return {i for e in sim.events("camera") for i in e["ids"]}


def test_the_camera_replays_what_a_restarted_planner_missed(row):
    pl1, ex = row.planner(1), row.executor(1)
    assert H.wait_for(lambda: row.cuts() >= row.n_map // 4, 300), "no harvest under way"
    pl1.send_signal(signal.SIGKILL)
    pl1.communicate(timeout=30)
    before = revealed(row.sim)
    assert H.wait_for(lambda: revealed(row.sim) > before, 120), "the camera revealed nothing"
    missed = revealed(row.sim) - before  # published before the planner is back
    pl2 = row.planner(2)
    ex_out, ex_err = ex.communicate(timeout=400)
    pl_out, pl_err = pl2.communicate(timeout=60)
    assert ex.returncode == 0, ex_err[-3000:]
    assert pl2.returncode == 0, pl_err[-3000:]
    assert "resumed from" in pl_err and "the camera replayed" in pl_err, pl_err[-3000:]
    with open(row.dir / "planner2.json") as f:
        pl = json.load(f)
    with open(row.dir / "exec1.json") as f:
        ex_sum = json.load(f)
    with open(row.dir / "plan.json") as f:
        plan = json.load(f)
    # the planner: what it missed recovered from the replay, nothing lost, every map fruit
    # accepted once over both of its runs
    rp = pl["camera_replay"]
    assert rp["replays"] >= 1 and rp["lost"] == 0 and rp["recovered"] >= len(missed) > 0, pl
    det = pl["detections"]
    assert pl["done"] and det["accepted"] + det["unreachable"] == row.n_map, pl
    assert det["duplicate"] == det["late"] == 0, pl
    # the executor's summary says the same, as the planner published it
    assert (ex_sum["camera_recovered"], ex_sum["camera_lost"]) == (rp["recovered"], 0), ex_sum
    assert ex_sum["phase"] == "row_done" and ex_sum["picked"] == det["accepted"], ex_sum
    check = H.check_plan(row.dir / "plan.json", row.cfg, row.fruits)
    assert check.returncode == 0, check.stdout + check.stderr
    # the simulator's word: it replayed, every fruit it revealed is in the plan (the
    # unreachable listed), and every planned fruit was cut once at its stop
    assert row.sim.events("camera_replay"), "the camera never replayed"
    order = H.plan_order(plan)
    planned = set(order["L"]) | set(order["R"])
    listed = planned | {u["id"] for u in plan["unreachable"]}
    assert revealed(row.sim) <= listed and missed & planned, sorted(revealed(row.sim) - listed)
    H.assert_every_fruit_cut_once(plan, row.sim)
