"""The telemetry viewer and its CLI without an executor: a log written here with the
generated LCM types (the same lcm-gen output the C side uses) is read back into the
planned and actual timelines, summarised and plotted; bad input gets a clear error."""

import json
import os
import struct
import subprocess
import sys

import pytest

from harvest.telemetry import lcm_types

try:
    T = lcm_types.load()
except lcm_types.LcmTypesMissing as e:
    pytest.skip(f"SKIPPED: {e}", allow_module_level=True)

import lcm  # noqa: E402

from harvest.telemetry import gantt, timeline  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exec_hil as H  # noqa: E402

SOURCE = os.environ.get("HV_SOURCE_DIR", os.getcwd())


def env():
    return dict(os.environ)


def _pick(fid, side, stop, cycle):
    p = T["plan_pick_t"]()
    p.fruit_id, p.side, p.stop, p.cycle_s, p.reachable = fid, side, stop, cycle, True
    return p


def _write_log(path, end=("row_done", "none")):
    """A row of two stops; `end` is the executor's last (phase, safe_reason)."""
    plan = T["plan_t"]()
    plan.plan_path = "p.json"
    plan.expected_makespan_s = 5.0 + 10.0 + 4.0 + 3.0 + 2.0
    plan.final_drive_s = 2.0
    plan.n_stops = 2
    for drive, exp in ((5.0, 10.0), (4.0, 3.0)):
        s = T["plan_stop_t"]()
        s.drive_s, s.expected_s = drive, exp
        plan.stops.append(s)
    plan.picks = [
        _pick("a", 0, 0, 6.0),
        _pick("b", 0, 0, 4.0),
        _pick("c", 1, 0, 7.0),
        _pick("d", 1, 1, 3.0),
    ]
    plan.n_picks = len(plan.picks)
    log = lcm.EventLog(str(path), "w", overwrite=True)
    t = 1_000_000
    log.write_event(t, "HARVEST_PLAN", plan.encode())

    def state(phase, stop, t_s, executed, reason="none"):
        m = T["exec_state_t"]()
        m.phase, m.safe_reason, m.stop, m.t_s, m.executed_s = phase, reason, stop, t_s, executed
        m.arm_phase = ["idle", "idle"]
        m.expected_makespan_s = plan.expected_makespan_s
        return m.encode()

    def fruit(fid, side, stop, event, t_s, outcome="", reason="", attempt=1):
        m = T["fruit_event_t"]()
        m.fruit_id, m.side, m.stop, m.event, m.t_s = fid, side, stop, event, t_s
        m.outcome, m.reason, m.attempt = outcome, reason, attempt
        return m.encode()

    for ch, data in (
        ("HARVEST_EXEC_STATE", state("homing", -1, 0.0, 0.0)),
        ("HARVEST_EXEC_STATE", state("driving", 0, 0.0, 0.0)),
        ("HARVEST_EXEC_STATE", state("harvest", 0, 5.1, 5.1)),
        ("HARVEST_FRUIT", fruit("a", 0, 0, "approach", 5.1)),
        ("HARVEST_FRUIT", fruit("c", 1, 0, "approach", 5.1)),
        ("HARVEST_FRUIT", fruit("a", 0, 0, "outcome", 11.2, "picked", "ok")),
        ("HARVEST_FRUIT", fruit("b", 0, 0, "approach", 11.2)),
        ("HARVEST_FRUIT", fruit("c", 1, 0, "fault", 8.0, reason="joint_fault")),
        ("HARVEST_FRUIT", fruit("c", 1, 0, "approach", 9.0, attempt=2)),
        ("HARVEST_FRUIT", fruit("b", 0, 0, "outcome", 15.3, "picked", "ok")),
        ("HARVEST_FRUIT", fruit("c", 1, 0, "outcome", 16.0, "failed", "joint_fault", 3)),
        ("HARVEST_EXEC_STATE", state("driving", 1, 16.0, 16.0)),
        ("HARVEST_EXEC_STATE", state("harvest", 1, 20.5, 20.5)),
        ("HARVEST_FRUIT", fruit("d", 1, 1, "outcome", 20.5, "skipped", "ik_unreachable", 0)),
        ("HARVEST_EXEC_STATE", state("final_drive", 1, 21.0, 21.0)),
        ("HARVEST_EXEC_STATE", state(end[0], 2, 25.0, 25.0, end[1])),
    ):
        t += 1000
        log.write_event(t, ch, data)
    log.close()


def test_timeline_and_summary(tmp_path):
    _write_log(tmp_path / "t.lcmlog")
    tl = timeline.read(str(tmp_path / "t.lcmlog"))
    # planned: drive 5, left a [5,11] b [11,15], right c [5,12]; stop 1 from 15, drive 4
    assert tl.planned_stops == [(0, 5.0, 15.0), (1, 19.0, 22.0)]
    assert (0, 0, "a", 5.0, 11.0) in tl.planned and (0, 0, "b", 11.0, 15.0) in tl.planned
    assert (1, 1, "d", 19.0, 22.0) in tl.planned
    assert tl.planned_total == pytest.approx(24.0)
    a = tl.actual[(1, "c")]
    assert (a["start"], a["end"], a["outcome"], a["attempts"]) == (5.1, 16.0, "failed", 2)
    assert tl.actual_stops == {0: 5.1, 1: 20.5}
    s = timeline.summary(tl)
    assert (s["picked"], s["failed"], s["skipped"], s["faults"]) == (2, 1, 1, 1)
    assert s["final_phase"] == "row_done" and s["stops_reached"] == 2
    assert s["executed_vs_expected"] == pytest.approx(25.0 / 24.0 - 1.0)
    # the vehicle: from the first move (homing left out), drives and stands merged
    assert tl.vehicle == [
        (0.0, 5.1, "drive"),
        (5.1, 16.0, "stopped"),
        (16.0, 20.5, "drive"),
        (20.5, 21.0, "stopped"),
        (21.0, 25.0, "drive"),
    ]
    assert timeline.planned_drives(tl) == [(0.0, 5.0), (15.0, 19.0), (22.0, 24.0)]
    assert tl.halts == []
    out = gantt.plot(tl, str(tmp_path / "g.svg"))
    assert "<svg" in open(out).read(400)


def _bars(ax, lane):
    """(start, end, colour) of the bars on the lane named `lane`."""
    labels = [t.get_text() for t in ax.get_yticklabels()]
    y = ax.get_yticks()[labels.index(lane)]
    return sorted(
        (round(r.get_x(), 6), round(r.get_x() + r.get_width(), 6), r.get_facecolor())
        for r in ax.patches
        if hasattr(r, "get_y") and abs(r.get_y() + r.get_height() / 2 - y) < 1e-9
    )


def test_gantt_vehicle_lanes_and_fault_marks(tmp_path):
    from matplotlib.colors import to_rgba

    _write_log(tmp_path / "t.lcmlog", end=("safe", "estop"))
    tl = timeline.read(str(tmp_path / "t.lcmlog"))
    assert tl.halts == [(25.0, "safe", "estop")]
    fig = gantt.figure(tl)
    try:
        ax = fig.axes[0]
        actual = _bars(ax, "vehicle actual")
        assert [(a, b) for a, b, _ in actual] == [(a, b) for a, b, _ in tl.vehicle]
        for (_, _, colour), (_, _, kind) in zip(actual, tl.vehicle):
            assert colour == to_rgba(gantt.VEHICLE[kind])
        planned = [(a, b) for a, b, _ in _bars(ax, "vehicle planned")]
        assert planned == timeline.planned_drives(tl)
        # the arm fault named at its time on the right arm's actual lane, the halt across
        texts = {t.get_text().strip(): t.get_position() for t in ax.texts}
        assert texts["joint_fault"][0] == 8.0
        right = ax.get_yticks()[[t.get_text() for t in ax.get_yticklabels()].index("right actual")]
        assert right < texts["joint_fault"][1] < right + 1
        assert texts["safe: estop"][0] == 25.0
        assert any(
            tuple(ln.get_xdata()) == (25.0, 25.0) and ln.get_color() == gantt.HALT["safe"]
            for ln in ax.get_lines()
        )
    finally:
        gantt.plt.close(fig)


def test_cli(tmp_path):
    _write_log(tmp_path / "t.lcmlog")
    r = subprocess.run(
        [sys.executable, "-m", "harvest", "telemetry", "summary", str(tmp_path / "t.lcmlog")],
        capture_output=True,
        text=True,
        env=env(),
    )
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["picked"] == 2
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "harvest",
            "telemetry",
            "gantt",
            str(tmp_path / "t.lcmlog"),
            "--out",
            str(tmp_path / "g.pdf"),
        ],
        capture_output=True,
        text=True,
        env=env(),
    )
    assert r.returncode == 2 and "g.pdf" in r.stderr
    r = subprocess.run(
        [sys.executable, "-m", "harvest", "telemetry", "summary", str(tmp_path / "missing.lcmlog")],
        capture_output=True,
        text=True,
        env=env(),
    )
    missing = f"harvest-stack telemetry summary: {tmp_path / 'missing.lcmlog'}: No such file"
    assert r.returncode == 2 and r.stderr.startswith(missing), r.stderr
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "harvest",
            "telemetry",
            "--lcm-python",
            str(tmp_path),
            "summary",
            str(tmp_path / "t.lcmlog"),
        ],
        capture_output=True,
        text=True,
        env=env(),
    )
    assert r.returncode == 1 and "generated LCM types missing" in r.stderr
    r = subprocess.run(
        [sys.executable, "-m", "harvest", "telemetry", "--help"],
        capture_output=True,
        text=True,
        env=env(),
    )
    assert r.returncode == 0 and "gantt" in r.stdout


def test_mcap_export(tmp_path):
    _write_log(tmp_path / "t.lcmlog")
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "harvest",
            "telemetry",
            "mcap",
            str(tmp_path / "t.lcmlog"),
            "--out",
            str(tmp_path / "t.mcap"),
        ],
        capture_output=True,
        text=True,
        env=env(),
    )
    assert r.returncode == 0, r.stderr
    assert "HARVEST_EXEC_STATE 7, HARVEST_FRUIT 9, HARVEST_PLAN 1" in r.stdout
    assert H.mcap_matches_log(tmp_path / "t.mcap", tmp_path / "t.lcmlog") == 17


def test_lcm_schema_from_definitions(tmp_path):
    from harvest.telemetry import lcm_schema

    structs = lcm_schema.load()
    assert set(structs) == set(lcm_types.TYPES)
    plan = lcm_schema.json_schema(structs, "plan_t")
    stop = plan["properties"]["stops"]["items"]
    assert stop["title"] == "plan_stop_t"
    assert stop["properties"]["arm_s"]["maxItems"] == 2
    assert plan["properties"]["utime"]["type"] == "integer"
    assert "microseconds" in plan["properties"]["utime"]["description"]
    bad = tmp_path / "bad.lcm"
    bad.write_text("package harvest;\nstruct x_t\n{\n    double a b;\n}\n")
    with pytest.raises(ValueError, match="bad.lcm:4"):
        lcm_schema.parse(str(bad))


def _events(data):
    """Byte offsets of the events of an LCM log's bytes (its own format, big-endian)."""
    offsets, off = [], 0
    while off < len(data):
        offsets.append(off)
        clen, dlen = struct.unpack_from(">ii", data, off + 20)
        off += 28 + clen + dlen
    return offsets


def test_a_torn_end_is_reported_and_damage_refused(tmp_path):
    _write_log(tmp_path / "t.lcmlog")
    data = (tmp_path / "t.lcmlog").read_bytes()
    last = _events(data)[-1]
    torn = tmp_path / "torn.lcmlog"
    torn.write_bytes(data[:-5])  # a logger stopped in the middle of its last write
    r = subprocess.run(
        [sys.executable, "-m", "harvest", "telemetry", "summary", str(torn)],
        capture_output=True,
        text=True,
        env=env(),
    )
    assert r.returncode == 0, r.stderr
    assert r.stderr.strip() == (
        f"harvest-stack telemetry summary: {torn}: byte {last}: the last event is cut short "
        "(left out)"
    )
    assert timeline.read(str(torn)).torn_at == last
    second = _events(data)[1]
    damaged = tmp_path / "damaged.lcmlog"
    damaged.write_bytes(data[:second] + b"\0\0\0\0" + data[second + 4 :])
    r = subprocess.run(
        [sys.executable, "-m", "harvest", "telemetry", "mcap", str(damaged), "--out", "d.mcap"],
        capture_output=True,
        text=True,
        env=env(),
        cwd=tmp_path,
    )
    assert r.returncode == 2 and not (tmp_path / "d.mcap").exists(), r.stderr
    assert r.stderr.startswith(f"harvest-stack telemetry mcap: {damaged}: byte {second}: ")


def test_log_stops_cleanly_on_sigterm(tmp_path):
    """SIGTERM (what systemd and scripts send) ends `telemetry log` with the log closed and
    exit 0, also when it lands in the middle of LCM's wait."""
    import signal
    import time

    ready, out = tmp_path / "ready", tmp_path / "t.lcmlog"
    p = subprocess.Popen(
        [sys.executable, "-m", "harvest", "telemetry", "log", "--url", "memq://",
         "--out", str(out), "--ready-file", str(ready)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env(),
    )  # fmt: skip
    deadline = time.monotonic() + 60
    while not ready.exists() and p.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    p.send_signal(signal.SIGTERM)
    stdout, stderr = p.communicate(timeout=60)
    assert p.returncode == 0, stderr
    assert stdout.startswith(f"telemetry log: {out}: 0 messages"), stdout
