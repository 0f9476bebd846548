"""`python -m harvest sim` as a program: help, input errors, clean stop on signals."""

import json
import os
import signal
import subprocess
import sys
import time

import pytest

from harvest.sim import record as sim_record

SRC = os.environ.get(
    "HV_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
ENV = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")


def run(*args, timeout=60):
    return subprocess.run(
        [sys.executable, "-m", "harvest", "sim", *args],
        env=ENV,
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def test_help_lists_every_fault():
    r = run("--help")
    assert r.returncode == 0
    for word in (
        "drop:",
        "delay:",
        "stall:",
        "joint_fault:",
        "silent:",
        "reject:",
        "estop:",
        "--time-scale",
        "--record",
        "--rate",
    ):
        assert word in r.stdout


@pytest.mark.parametrize(
    "args,message",
    [
        (["--fault", "drop:fraction=1.5"], "field 'fraction'"),
        (["--time-scale", "0"], "--time-scale"),
        (["--time-scale", "1.234"], "steps of 0.01"),
        (["--arm-start", "0.7", "0", "1", "0"], "--arm-start: joint 1"),
        (["--config", "/nonexistent/h.cfg"], "/nonexistent/h.cfg"),
        (["--scenario", "/nonexistent/s.json"], "/nonexistent/s.json"),
        (["--dbc", "/nonexistent/x.dbc"], "/nonexistent/x.dbc: cannot load the DBC"),
    ],
)
def test_bad_input_is_one_clear_line(args, message):
    r = run("--interface", "virtual", *args)
    assert r.returncode == 2
    assert message in r.stderr.strip().splitlines()[-1]  # the error is one line, last


def test_unknown_interface_fails_cleanly():
    r = run("--interface", "no-such-interface", "--channel", "x")
    assert r.returncode == 1 and "harvest-stack sim: no-such-interface:x: cannot open" in r.stderr


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_signal_stops_cleanly_and_flushes_the_record(tmp_path, sig):
    rec = tmp_path / "rec.jsonl"
    p = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "harvest",
            "sim",
            "--interface",
            "virtual",
            "--channel",
            "cli",
            "--time-scale",
            "10",
            "--record",
            str(rec),
            "--fault",
            "silent:after_s=0.5,node=vehicle",
        ],
        env=ENV,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        deadline = time.monotonic() + 30
        # wait until the injected silence (0.05 s wall at 10x) has been recorded
        while not (rec.exists() and "fault_injected" in rec.read_text()):
            assert p.poll() is None, p.stderr.read()
            assert time.monotonic() < deadline, "simulator never started"
            time.sleep(0.05)
        p.send_signal(sig)
        _, err = p.communicate(timeout=30)
    finally:
        if p.poll() is None:
            p.kill()
    assert p.returncode == 0, err
    events = sim_record.read(str(rec))
    assert events[0]["event"] == "start" and events[-1]["event"] == "stop"
    assert events[-1]["stats"]["tx"] > 0 and events[-1]["stats"]["tx_silenced"] > 0
    assert "stopped at" in err
    json.dumps(events)  # every line was valid JSON


def test_duration_flag_stops_by_itself(tmp_path):
    rec = tmp_path / "rec.jsonl"
    r = run("--interface", "virtual", "--channel", "dur", "--duration", "0.3", "--record", str(rec))
    assert r.returncode == 0
    assert sim_record.read(str(rec))[-1]["event"] == "stop"
