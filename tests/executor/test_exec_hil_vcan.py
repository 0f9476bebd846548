"""Hardware-in-the-loop on SocketCAN: harvest-exec (socketcan transport) and the simulator
(python-can socketcan) on vcan0. Runs on the host's vcan0 when it has one, else inside the
QEMU test-bed guest (testbed/run-in-guest, DESIGN §6), else SKIPPED with the reason.

The guest runs code ~20x slower than the host, so the row here is short and slow (time
scale 2); the 5 % makespan check is the udp test's (test_exec_hil_udp.py).
"""

import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exec_hil as H  # noqa: E402
import fk_check  # noqa: E402

from harvest.canbus import guest  # noqa: E402

SCALE = 2.0
# In the guest Python runs ~20x slower: the simulator's 100 ms heartbeats can come late by
# more than the DBC's 500 ms, so both sides get a longer heartbeat timeout there.
SLOW_HEARTBEAT_S = 3.0


def _run_row(tmp_path, iface):
    plan = H.make_plan(tmp_path / "plan.json", stops=1, per_arm=2, seed=13)
    order = H.plan_order(plan)
    import subprocess

    log = open(tmp_path / "sim_vcan.log", "w")
    record = tmp_path / "sim_vcan.jsonl"
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "harvest",
            "sim",
            "--interface",
            "socketcan",
            "--channel",
            iface,
            "--time-scale",
            str(SCALE),
            "--record",
            str(record),
            "--exec-timeout",
            str(SLOW_HEARTBEAT_S),
        ],
        stdout=log,
        stderr=subprocess.STDOUT,
        env=H.env(),
        cwd=H.SOURCE,
    )
    try:
        r = subprocess.run(
            [
                H.EXEC,
                "--plan",
                str(tmp_path / "plan.json"),
                "--config",
                H.CONFIG,
                "--journal",
                str(tmp_path / "j.journal"),
                "--summary",
                str(tmp_path / "s.json"),
                "--transport",
                "socketcan",
                "--channel",
                iface,
                "--time-scale",
                str(SCALE),
                "--startup-timeout",
                "60",
                "--heartbeat-timeout",
                str(SLOW_HEARTBEAT_S),
                "--latency",
                "2",
            ],
            capture_output=True,
            text=True,
            timeout=500,
        )
    finally:
        proc.terminate()
        proc.wait(timeout=60)
        log.close()
    assert r.returncode == 0, r.stderr
    _, recs = H.read_journal(tmp_path / "j.journal")
    assert H.outcome_order(recs) == order
    assert all(o[0] == "picked" for o in H.outcomes(recs).values())
    import json

    picks = [json.loads(line) for line in open(record) if '"event":"pick"' in line.replace(" ", "")]
    # each cut a planned fruit (forward kinematics of the recorded joints), each once
    fk_check.assert_cuts_on_plan(
        plan, picks, picked={(side, i) for side in order for i in order[side]}
    )


def test_whole_row_on_vcan(tmp_path):
    missing = H.missing_pieces()
    if missing:
        pytest.skip("SKIPPED: " + "; ".join(missing))
    iface = guest.local_vcan()
    if iface:
        _run_row(tmp_path, iface)
        return
    if guest.in_guest():
        pytest.skip("SKIPPED: inside the guest but vcan0 is not usable")
    if not os.path.exists(guest.RUNNER):
        pytest.skip(f"SKIPPED: no vcan here and no test-bed guest runner ({guest.RUNNER})")
    proc = guest.run_in_guest(
        [
            sys.executable,
            "-m",
            "pytest",
            "-q",
            "-rs",
            "-p",
            "no:cacheprovider",
            os.path.abspath(__file__),
            "--basetemp",
            str(tmp_path / "guest"),
        ],
        timeout=540,
        rw=[tmp_path],
        cwd=H.SOURCE,
    )
    reason = guest.skip_reason(proc)
    if reason:
        pytest.skip(reason)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    assert " passed" in proc.stdout, proc.stdout[-2000:]
