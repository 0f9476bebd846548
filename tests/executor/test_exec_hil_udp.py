"""Hardware-in-the-loop: harvest-exec and the simulator on one CAN bus carried over UDP
multicast (python-can's udp_multicast wire format) inside a private network namespace.

A whole 2 m row, each injected fault, an operator stop and SIGKILL-and-resume.
"""

import collections
import json
import os
import signal
import subprocess
import sys
import time

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exec_hil as H  # noqa: E402
import fk_check  # noqa: E402

_skip = H.enter_udp_netns()
pytestmark = pytest.mark.skipif(bool(_skip), reason="SKIPPED: " + "; ".join(_skip))

ROW_SCALE = 5.0  # simulated s per wall s for the makespan check (bus delays scale with it)
FAULT_SCALE = 20.0  # faster for the fault runs (no timing asserted there)


@pytest.fixture
def sim_factory(tmp_path):
    sims = []

    def make(time_scale, faults=()):
        s = H.Sim(str(tmp_path), time_scale, faults)
        sims.append(s)
        return s

    yield make
    for s in sims:
        s.stop()


def test_whole_row_in_plan_order_within_5_percent(tmp_path, sim_factory):
    plan = H.make_plan(tmp_path / "plan.json", stops=5, per_arm=3, seed=3)
    order = H.plan_order(plan)
    n = len(order["L"]) + len(order["R"])
    sim = sim_factory(ROW_SCALE)
    proc, summary = H.run_exec(
        tmp_path / "plan.json", tmp_path / "j.journal", tmp_path / "summary.json", ROW_SCALE
    )
    assert proc.returncode == 0, proc.stderr
    assert summary["phase"] == "row_done"
    assert summary["picked"] == n and summary["failed"] == 0 and summary["skipped"] == 0
    # plan order, per arm, as journalled
    _, recs = H.read_journal(tmp_path / "j.journal")
    assert H.outcome_order(recs) == order
    assert all(o == ("picked", "ok", 1) for o in H.outcomes(recs).values())
    assert [r[0] for r in recs].count("S") == len(plan["stops"])
    assert recs[-1][0] == "D"
    # the simulator cut every planned fruit once, each where the plan has it, in order
    H.assert_every_fruit_cut_once(plan, sim)
    picks = H.sim_picks(sim)
    stop_y = [round(s["y_m"], 3) for s in plan["stops"]]
    seen_y = [p[2] for p in picks]
    assert sorted(set(seen_y)) == stop_y and seen_y == sorted(seen_y)
    # the executed makespan by the simulator's clock (from the first move it accepted to
    # its arrival at the course's end) within 5 % of the executor's expected one
    prm = plan["params"]
    end = prm["row_start_m"] + prm["row_length_m"] + prm["stop_margin_m"]
    moves = [e["t"] for e in sim.events("move") if e.get("accepted")]
    ends = [e["t"] for e in sim.events("arrived") if abs(e["position"] - end) < 1e-3]
    assert moves and ends, "the simulator recorded no move or no arrival at the course end"
    executed = ends[-1] - moves[0]
    rel = executed / summary["expected_makespan_s"] - 1.0
    assert abs(rel) < 0.05, (executed, summary)


def test_telemetry_logged_and_plotted(tmp_path, sim_factory):
    if not os.path.isfile(os.path.join(H.BUILD, "lcm_types", "python", "harvest_lcm", "plan_t.py")):
        pytest.skip("SKIPPED: built without LCM (HV_WITH_LCM=OFF): no telemetry to log")
    plan = H.make_plan(tmp_path / "plan.json", stops=2, per_arm=2, seed=4)
    n = sum(len(s["left"]) + len(s["right"]) for s in plan["stops"])
    sim = sim_factory(FAULT_SCALE)
    url = "udpm://239.255.76.67:7667?ttl=0"
    logger = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "harvest",
            "telemetry",
            "log",
            "--url",
            url,
            "--out",
            str(tmp_path / "run.lcmlog"),
            "--until-done",
            "--grace",
            "0.5",
            "--ready-file",
            str(tmp_path / "ready"),
        ],
        env=H.env(),
        cwd=H.SOURCE,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    can_logger = H.start_can_logger(tmp_path / "bus.blf")
    assert H.wait_for(lambda: (tmp_path / "ready").exists(), 30)
    proc, summary = H.run_exec(
        tmp_path / "plan.json",
        tmp_path / "j.journal",
        tmp_path / "summary.json",
        FAULT_SCALE,
        ["--lcm-url", url],
    )
    assert proc.returncode == 0, proc.stderr
    out, err = logger.communicate(timeout=30)
    assert logger.returncode == 0, err
    H.stop_can_logger(can_logger)
    H.assert_every_fruit_cut_once(plan, sim)
    # the bus log, read back with the DBC: one cut command per fruit the simulator cut
    cut = collections.Counter(node for node, _, _ in H.sim_picks(sim))
    assert H.cut_commands(tmp_path / "bus.blf") == {
        "left_arm": cut["left_arm"],
        "right_arm": cut["right_arm"],
    }
    # and python-can's player puts every frame of it back on the bus (now quiet)
    import can

    sim.stop()
    assert H.replayed_frames(tmp_path / "bus.blf") == sum(
        1 for _ in can.LogReader(str(tmp_path / "bus.blf"))
    )
    # the telemetry log as MCAP: every message, in order, typed by its channel's schema
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "harvest",
            "telemetry",
            "mcap",
            str(tmp_path / "run.lcmlog"),
            "--out",
            str(tmp_path / "run.mcap"),
        ],
        env=H.env(),
        cwd=H.SOURCE,
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, r.stderr
    assert H.mcap_matches_log(tmp_path / "run.mcap", tmp_path / "run.lcmlog") > 0
    assert "HARVEST_ARM_LEFT" in out and "HARVEST_CAN_STATS" in out, out
    r = subprocess.run(
        [sys.executable, "-m", "harvest", "telemetry", "summary", str(tmp_path / "run.lcmlog")],
        env=H.env(),
        cwd=H.SOURCE,
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, r.stderr
    tsum = json.loads(r.stdout)
    assert tsum["picked"] == n and tsum["fruits_planned"] == n
    assert tsum["stops_reached"] == len(plan["stops"])
    assert tsum["final_phase"] == "row_done"
    assert abs(tsum["executed_makespan_s"] - summary["executed_makespan_s"]) < 0.5
    assert abs(tsum["expected_makespan_s"] - summary["expected_makespan_s"]) < 1e-6
    g = subprocess.run(
        [
            sys.executable,
            "-m",
            "harvest",
            "telemetry",
            "gantt",
            str(tmp_path / "run.lcmlog"),
            "--out",
            str(tmp_path / "g.png"),
            "--out",
            str(tmp_path / "g.svg"),
        ],
        env=H.env(),
        cwd=H.SOURCE,
        capture_output=True,
        text=True,
    )
    assert g.returncode == 0, g.stderr
    assert (tmp_path / "g.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert b"<svg" in (tmp_path / "g.svg").read_bytes()[:400]


# (fault flags, expected end, what the journal must show)
RECOVERABLE = {
    "joint_fault_at_cut": ["joint_fault:node=left_arm,joint=2,pick=2"],
    "stall_then_timeout": ["stall:node=right_arm,joint=1,setpoint=3"],
    "rejected_setpoint": ["reject:node=left_arm,setpoint=3"],
    "dropped_frames": ["drop:fraction=0.03,direction=both"],
}


@pytest.mark.parametrize("name", sorted(RECOVERABLE))
def test_recoverable_fault_row_completes(tmp_path, sim_factory, name):
    plan = H.make_plan(tmp_path / "plan.json", stops=2, per_arm=3, seed=5)
    n = sum(len(s["left"]) + len(s["right"]) for s in plan["stops"])
    sim = sim_factory(FAULT_SCALE, RECOVERABLE[name])
    proc, summary = H.run_exec(
        tmp_path / "plan.json", tmp_path / "j.journal", tmp_path / "summary.json", FAULT_SCALE
    )
    assert proc.returncode == 0, proc.stderr
    assert summary["phase"] == "row_done"
    _, recs = H.read_journal(tmp_path / "j.journal")
    outs = H.outcomes(recs)
    assert len(outs) == n
    # every cut a planned fruit of its arm, none twice, and the fruits cut are the ones the
    # journal calls picked
    picked = {k for k, o in outs.items() if o[0] == "picked"}
    fk_check.assert_cuts_on_plan(plan, sim.events("pick"), picked=picked)
    assert summary["picked"] == n and len(picked) == n, outs
    if name == "dropped_frames":
        # the fault happened: the simulator's final stats, written once it stopped
        sim.stop()
        stats = sim.events("stop")[-1]["stats"]
        assert stats["tx_dropped"] > 0 and stats["rx_dropped"] > 0, stats
    else:
        assert summary["faults"] >= 1
        retried = [o for o in outs.values() if o[2] > 1]
        assert retried and all(o[0] == "picked" for o in retried), outs


# A node that falls silent altogether is caught by whichever comes first: its heartbeat
# timeout or the timeout of what the executor was waiting for from it; both end in SAFE.
SAFE = {
    "vehicle_heartbeat_lost": (
        ["silent:after_s=40,node=vehicle,frames=heartbeat"],
        {"lost_heartbeat"},
    ),
    "arm_heartbeat_lost": (
        ["silent:after_s=40,node=right_arm,frames=heartbeat"],
        {"lost_heartbeat"},
    ),
    "arm_silent": (["silent:after_s=40,node=left_arm"], {"lost_heartbeat", "timeout"}),
}


@pytest.mark.parametrize("name", sorted(SAFE))
def test_fatal_fault_ends_safe_with_journal_intact(tmp_path, sim_factory, name):
    faults, reasons = SAFE[name]
    plan = H.make_plan(tmp_path / "plan.json", stops=3, per_arm=3, seed=7)
    sim = sim_factory(FAULT_SCALE, faults)
    proc, summary = H.run_exec(
        tmp_path / "plan.json", tmp_path / "j.journal", tmp_path / "summary.json", FAULT_SCALE
    )
    assert proc.returncode == 3, proc.stderr
    assert summary["phase"] == "safe" and summary["safe_reason"] in reasons, summary
    _, recs = H.read_journal(tmp_path / "j.journal")  # verifies every record's CRC
    outs = H.outcomes(recs)
    assert summary["picked"] == len([o for o in outs.values() if o[0] == "picked"])
    assert summary["remaining"] > 0
    # what was cut before the stop: planned fruits, once each (a fruit in the gripper at
    # the stop is cut but not journalled as picked)
    cuts = fk_check.assert_cuts_on_plan(plan, sim.events("pick"))
    assert {k for k, o in outs.items() if o[0] == "picked"} <= set(cuts)
    # the nodes were told: e-stop frames reached the simulator
    assert H.wait_for(lambda: sim.events("estop_frame"), 30), "no e-stop frame on the bus"


def _run_until_an_outcome(tmp_path, sim_factory):
    H.make_plan(tmp_path / "plan.json", stops=3, per_arm=3, seed=9)
    sim = sim_factory(FAULT_SCALE)
    p = H.start_exec(
        tmp_path / "plan.json", tmp_path / "j.journal", tmp_path / "s.json", FAULT_SCALE
    )
    assert H.wait_for(
        lambda: (
            os.path.exists(tmp_path / "j.journal")
            and b"\nF " in (tmp_path / "j.journal").read_bytes()
        ),
        60,
    )
    return sim, p


def _send_stop_requests(n):
    """An operator's panel on the bus: ExecutorStopRequest, n times (its repeats are one)."""
    import can

    from harvest.canbus import load

    msg = load().message("ExecutorStopRequest")
    with can.Bus(interface="udp_multicast", channel=H.GROUP) as bus:
        for _ in range(n):
            data = msg.encode({"StopRequested": 1})
            bus.send(can.Message(arbitration_id=msg.frame_id, is_extended_id=False, data=data))
            time.sleep(0.05)


@pytest.mark.parametrize("how", ["sigterm", "bus"])
def test_operator_stop_is_a_controlled_stop(tmp_path, sim_factory, how):
    sim, p = _run_until_an_outcome(tmp_path, sim_factory)
    if how == "sigterm":
        p.send_signal(signal.SIGTERM)
    else:
        _send_stop_requests(3)
    out, err = p.communicate(timeout=60)
    assert p.returncode == 6, out + err
    assert out.startswith("harvest-exec: stopped operator:"), out
    _, recs = H.read_journal(tmp_path / "j.journal")
    # every cut issued has its outcome: the picks under way finished
    assert {(r[1], r[2]) for r in recs if r[0] == "C"} <= set(H.outcomes(recs)), recs

    def last_commands():
        last = {}
        for node, command, accepted in H.sim_commands(sim):
            last[node] = (command, accepted)
        return last

    # the simulator's record: each node's last command DISABLE, accepted (the executor's
    # last frames), and no e-stop frame before them
    want = {n: ("DISABLE", True) for n in ("vehicle", "left_arm", "right_arm")}
    assert H.wait_for(lambda: last_commands() == want, 10), last_commands()
    assert not sim.events("estop_frame")


def test_a_second_stop_request_is_an_estop(tmp_path, sim_factory):
    sim, p = _run_until_an_outcome(tmp_path, sim_factory)
    # two different signals: two of one kind sent at once may reach the process as one
    p.send_signal(signal.SIGTERM)
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=30)
    assert p.returncode == 3, err
    assert "operator_stop" in out
    H.read_journal(tmp_path / "j.journal")
    assert H.wait_for(lambda: sim.events("estop_frame"), 30), "no e-stop frame on the bus"


@pytest.mark.parametrize("kill_after_outcomes", [3, 8])
def test_sigkill_and_resume_loses_nothing_picks_nothing_twice(
    tmp_path, sim_factory, kill_after_outcomes
):
    plan = H.make_plan(tmp_path / "plan.json", stops=3, per_arm=3, seed=11)
    order = H.plan_order(plan)
    n = len(order["L"]) + len(order["R"])
    sim = sim_factory(FAULT_SCALE)
    journal = tmp_path / "j.journal"

    def outcomes_so_far():
        return journal.exists() and journal.read_bytes().count(b"\nF ") >= kill_after_outcomes

    p = H.start_exec(tmp_path / "plan.json", journal, tmp_path / "s1.json", FAULT_SCALE)
    assert H.wait_for(outcomes_so_far, 60), "the run did not get far enough"
    time.sleep(0.07)  # somewhere inside the next pick cycle
    p.send_signal(signal.SIGKILL)
    p.communicate(timeout=10)
    assert p.returncode == -signal.SIGKILL
    _, before = H.read_journal(journal)
    done_before = H.outcomes(before)
    assert 0 < len(done_before) < n
    # the nodes notice the lost heartbeat and stop; a new executor resumes
    time.sleep(1.0)
    proc, summary = H.run_exec(tmp_path / "plan.json", journal, tmp_path / "s2.json", FAULT_SCALE)
    assert proc.returncode == 0, proc.stderr
    assert "resuming" in proc.stderr
    _, recs = H.read_journal(journal)
    outs = H.outcomes(recs)  # asserts one outcome per fruit across both runs
    assert len(outs) == n
    assert all(o[0] == "picked" for o in outs.values()), outs
    for key, o in done_before.items():
        assert outs[key] == o  # nothing recorded before the kill changed
    assert H.outcome_order(recs) == order
    H.assert_every_fruit_cut_once(plan, sim)
