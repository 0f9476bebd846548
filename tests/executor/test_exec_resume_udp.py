"""Stopping and resuming (issue 45): harvest-exec stopped in each way it can be, then
restarted on its journal, against the simulator over UDP multicast in a private network
namespace. Judged from the simulator's record: every planned fruit cut exactly once and
the vehicle at the row end.

Each stop leaves the nodes holding an e-stop, so each restart first goes without the
operator's clear (it must stay safe, exit 4, and send the nodes no command at all) and
then with --clear-estop (it must resume and finish the row).
"""

import os
import signal
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exec_hil as H  # noqa: E402

_skip = H.enter_udp_netns()
pytestmark = pytest.mark.skipif(bool(_skip), reason="SKIPPED: " + "; ".join(_skip))

SCALE = 20.0
OPERATOR = "op.test-1"
# what the simulator's record calls the executor's nodes (hv_exec_node_name)
NODE_NAMES = ("vehicle", "left_arm", "right_arm")


@pytest.fixture
def row(tmp_path):
    """(plan file, plan, start_sim(faults)); the simulator is stopped at teardown."""
    sims = []

    def start_sim(faults=()):
        sims.append(H.Sim(str(tmp_path), SCALE, faults))
        return sims[-1]

    path = tmp_path / "plan.json"
    plan = H.make_plan(path, stops=3, per_arm=2, seed=21)
    yield path, plan, start_sim
    for s in sims:
        s.stop()


def run_to_safe(tmp_path, path):
    """The first run, to its stop in the safe state: (safe reason, node)."""
    proc, summary = H.run_exec(path, tmp_path / "j.journal", tmp_path / "s1.json", SCALE)
    assert proc.returncode == 3, proc.stdout + proc.stderr
    return summary["safe_reason"], summary["safe_node_name"]


def restart_until_done(tmp_path, path, plan, sim):
    """After a stop: a restart without the clear stays safe; one with it finishes the row."""
    journal = tmp_path / "j.journal"
    _, before = H.read_journal(journal)
    assert 0 < len(H.outcomes(before)) < len(H.plan_order(plan)["L"]) * 2
    commands = H.sim_commands(sim)
    proc, summary = H.run_exec(path, journal, tmp_path / "s2.json", SCALE)
    assert proc.returncode == 4, proc.stdout + proc.stderr
    assert summary["phase"] == "safe" and summary["safe_reason"] == "estop_latched"
    assert summary["safe_node_name"] in NODE_NAMES
    assert "--clear-estop" in proc.stdout and summary["picked_this_run"] == 0
    # a frame sent after the restart ended, back in the record: whatever the restart sent
    # is in the record by then
    assert H.bus_barrier(sim), "the simulator never recorded the test's own frame"
    assert H.sim_commands(sim) == commands, "a restart without the clear sent a command"
    assert [r for r in H.read_journal(journal)[1] if r[0] == "E"] == []

    proc, summary = H.run_exec(
        path, journal, tmp_path / "s3.json", SCALE, ["--clear-estop", OPERATOR]
    )
    assert proc.returncode == 0, proc.stderr
    assert summary["phase"] == "row_done" and summary["estop_cleared"] is True
    assert f"cleared by {OPERATOR} (journalled)" in proc.stderr
    _, recs = H.read_journal(journal)
    clears = [r for r in recs if r[0] == "E"]
    assert len(clears) == 1 and clears[0][1] == OPERATOR, clears
    assert set(clears[0][2][len("nodes=") :].split(",")) <= set(NODE_NAMES)
    outs = H.outcomes(recs)  # one outcome per fruit across the runs
    assert len(outs) == len(H.plan_order(plan)["L"]) * 2
    assert all(o[0] == "picked" for o in outs.values()), outs
    # the simulator's word, not the executor's
    H.assert_every_fruit_cut_once(plan, sim)
    assert H.row_end_reached(plan, sim)
    # the nodes got CLEAR_ESTOP only in the run with the operator's clear
    assert [c for c in H.sim_commands(sim)[len(commands) :] if c[1] == "CLEAR_ESTOP"]


def test_resume_after_sigterm(tmp_path, row):
    """SIGTERM (systemctl stop) is a controlled stop: a plain restart, no operator, finishes."""
    path, plan, start_sim = row
    sim = start_sim()
    journal = tmp_path / "j.journal"
    p = H.start_exec(path, journal, tmp_path / "s1.json", SCALE)
    assert H.wait_for(lambda: journal.exists() and journal.read_bytes().count(b"\nF ") >= 3, 60)
    p.send_signal(signal.SIGTERM)
    out, err = p.communicate(timeout=60)
    assert p.returncode == 6, out + err
    assert out.startswith("harvest-exec: stopped operator:"), out
    _, before = H.read_journal(journal)
    assert 0 < len(H.outcomes(before)) < len(H.plan_order(plan)["L"]) * 2
    assert [r[:2] for r in before if r[0] == "H"] == [["H", "operator"]]
    proc, summary = H.run_exec(path, journal, tmp_path / "s2.json", SCALE)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert summary["phase"] == "row_done" and summary["estop_cleared"] is False
    outs = H.outcomes(H.read_journal(journal)[1])  # one outcome per fruit across the runs
    assert len(outs) == len(H.plan_order(plan)["L"]) * 2
    assert all(o[0] == "picked" for o in outs.values()), outs
    # the simulator's word: no e-stop in either run, every fruit cut once, the row's end
    assert not sim.events("estop_frame")
    H.assert_every_fruit_cut_once(plan, sim)
    assert H.row_end_reached(plan, sim)


def test_resume_after_a_node_estop_and_the_operators_clear(tmp_path, row):
    path, plan, start_sim = row
    # the right arm's own e-stop trips just after its 3rd pick, the fruit in the gripper
    sim = start_sim(["estop:node=right_arm,pick=3"])
    assert run_to_safe(tmp_path, path) == ("estop", "right_arm")
    restart_until_done(tmp_path, path, plan, sim)


def test_resume_after_an_arm_fault(tmp_path, row):
    path, plan, start_sim = row
    # the left arm faults at its 2nd cut and again while homing to recover from it
    sim = start_sim(
        ["joint_fault:node=left_arm,joint=2,pick=2", "joint_fault:node=left_arm,joint=1,home=2"]
    )
    assert run_to_safe(tmp_path, path) == ("fault", "left_arm")
    restart_until_done(tmp_path, path, plan, sim)


def test_resume_after_bus_silence(tmp_path, row):
    path, plan, start_sim = row
    # the left arm falls silent just after its 3rd pick, for 4 s of wall time: past the
    # heartbeat timeout, then it is back
    silent_s = 2 * H.HEARTBEAT_TIMEOUT_S * SCALE
    sim = start_sim([f"silent:node=left_arm,pick=3,for_s={silent_s:g}"])
    reason, node = run_to_safe(tmp_path, path)
    # lost, or late with what the executor waited for from it: both are the silence
    assert reason in ("lost_heartbeat", "timeout") and node == "left_arm", (reason, node)
    assert H.wait_for(lambda: sim.events("fault_ended"), 60), "the arm never came back"
    restart_until_done(tmp_path, path, plan, sim)
