"""Helpers of the executor's hardware-in-the-loop tests: the simulator (python -m harvest
sim) and harvest-exec on one CAN bus, their records, and checks of the harvest journal.

The udp bus is python-can's udp_multicast on loopback; callers run inside a private
network namespace (harvest.canbus.netns) so nothing leaves the machine.
"""

import json
import os
import signal
import subprocess
import sys
import time
import zlib

import fk_check

SOURCE = os.environ.get(
    "HV_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
BUILD = os.environ.get("HV_BUILD_DIR", os.path.join(SOURCE, "build"))
EXEC = os.path.join(BUILD, "executor", "harvest-exec")
MAKE_PLAN = os.path.join(BUILD, "tests", "executor", "make-test-plan")
CONFIG = os.path.join(SOURCE, "config", "harvest.cfg")
GROUP = "239.74.163.2"
# The test machines are shared (load averages of 10 on 2 cores happen): a simulator or an
# executor descheduled for more than the DBC's 500 ms would look like a lost node. The
# tests are not about that margin, so both sides get 2 s (the fault tests still lose
# heartbeats on purpose, and are detected within it).
HEARTBEAT_TIMEOUT_S = 2.0


def missing_pieces():
    """Reasons the tests cannot run (empty when everything is there)."""
    out = []
    for path, what in ((EXEC, "harvest-exec"), (MAKE_PLAN, "make-test-plan")):
        if not os.access(path, os.X_OK):
            out.append(f"{what} not built at {path}")
    try:
        import harvest.sim.cli  # noqa: F401
    except ImportError as e:
        out.append(f"the simulator (harvest.sim) cannot be imported: {e}")
    return out


def enter_udp_netns():
    """Reasons the udp tests cannot run (empty when they can); when they can, this process
    has moved into a private network namespace, so the multicast stays on its loopback."""
    from harvest.canbus import netns

    reasons = missing_pieces()
    if not reasons:
        try:
            netns.enter_private_netns()
        except netns.NetnsUnavailable as e:
            reasons = [f"no private network namespace: {e}"]
    return reasons


# Online mode: the planner's process and the checker, and the LCM URL the tests use.
PLAN_ONLINE = os.path.join(BUILD, "planner", "online", "harvest-plan-online")
HARVEST_PLAN = os.path.join(BUILD, "planner", "harvest-plan")
ONLINE_URL = "udpm://239.255.76.67:7667?ttl=0"


def online_row_scenario(workdir, length_m, seed):
    """A long row (8 fruits per m and side) and its config, made by `harvest scenario`:
    (map path, config path, fruits in the map)."""
    fruits, cfg = workdir / "fruits.csv", workdir / "harvest.cfg"
    subprocess.run(
        [
            sys.executable,
            "-m",
            "harvest",
            "scenario",
            "--distribution",
            "long",
            "--length",
            str(length_m),
            "--left",
            "40",
            "--seed",
            str(seed),
            "--out",
            str(fruits),
            "--config-out",
            str(cfg),
        ],
        check=True,
        env=env(),
        cwd=SOURCE,
        capture_output=True,
    )
    with open(fruits) as f:
        return fruits, cfg, len(f.read().splitlines()) - 1


class OnlineRow:
    """The simulator with its camera on an online row (online_row_scenario), and
    harvest-plan-online and harvest-exec --online to start, kill and judge; files in tmp_path."""

    def __init__(self, tmp_path, length_m, seed, scale):
        self.dir, self.scale = tmp_path, scale
        self.fruits, self.cfg, self.n_map = online_row_scenario(tmp_path, length_m, seed)
        self.sim = Sim(
            str(tmp_path),
            scale,
            extra=[
                "--config",
                str(self.cfg),
                "--fruits",
                str(self.fruits),
                "--lcm-url",
                ONLINE_URL,
            ],
        )
        self.procs = []

    def planner(self, n, journal="planner.journal", cfg=None, url=ONLINE_URL):
        p = subprocess.Popen(
            [
                PLAN_ONLINE,
                "--config",
                str(cfg or self.cfg),
                "--lcm-url",
                url,
                "--time-limit",
                "2",
                "--threads",
                "1",
                "--journal",
                str(self.dir / journal),
                "--summary",
                str(self.dir / f"planner{n}.json"),
                "--out",
                str(self.dir / "plan.json"),
            ],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        self.procs.append(p)
        return p

    def executor(self, n, stderr=subprocess.PIPE, cfg=None):
        p = subprocess.Popen(
            [
                EXEC,
                "--online",
                "--lcm-url",
                ONLINE_URL,
                "--config",
                str(cfg or self.cfg),
                "--journal",
                str(self.dir / "exec.journal"),
                "--summary",
                str(self.dir / f"exec{n}.json"),
                "--transport",
                "udp",
                "--channel",
                GROUP,
                "--time-scale",
                str(self.scale),
                "--heartbeat-timeout",
                str(HEARTBEAT_TIMEOUT_S),
            ],
            stdout=subprocess.PIPE,
            stderr=stderr,
            text=True,
        )
        self.procs.append(p)
        return p

    def cuts(self):
        """Cuts the simulated arms completed so far (none before the record exists)."""
        return len(self.sim.events("pick")) if os.path.exists(self.sim.record) else 0

    def close(self):
        for p in self.procs:
            if p.poll() is None:
                p.kill()
                p.wait()
        self.sim.stop()


def check_plan(plan, cfg, fruits):
    """`harvest-plan check PLAN --config CFG --fruits MAP`, the independent checker: the
    finished process (returncode 0: every reachable fruit of the map planned exactly once)."""
    return subprocess.run(
        [HARVEST_PLAN, "check", str(plan), "--config", str(cfg), "--fruits", str(fruits)],
        capture_output=True,
        text=True,
    )


def enter_online_netns():
    """enter_udp_netns() for the online tests, which need the planner's programs too."""
    missing = [
        f"harvest-plan-online not built at {PLAN_ONLINE} (needs GLPK and LCM)"
        for p in (PLAN_ONLINE, HARVEST_PLAN)
        if not os.access(p, os.X_OK)
    ][:1]
    return missing or enter_udp_netns()


def make_plan(path, stops, per_arm, seed=1):
    subprocess.run([MAKE_PLAN, CONFIG, str(path), str(stops), str(per_arm), str(seed)], check=True)
    with open(path) as f:
        return json.load(f)


# Fruit ids of each side ("L", "R") in the order the plan picks them.
plan_order = fk_check.plan_order


def env():
    """The environment of the programs a test starts (the venv has harvest installed)."""
    return dict(os.environ)


class Sim:
    """The simulator as a subprocess with a JSONL record."""

    def __init__(self, workdir, time_scale, faults=(), extra=()):
        self.record = os.path.join(workdir, "sim.jsonl")
        self.log = open(os.path.join(workdir, "sim.log"), "w")
        argv = [
            sys.executable,
            "-m",
            "harvest",
            "sim",
            "--interface",
            "udp_multicast",
            "--channel",
            GROUP,
            "--time-scale",
            str(time_scale),
            "--record",
            self.record,
        ]
        argv += ["--exec-timeout", str(HEARTBEAT_TIMEOUT_S)]
        for f in faults:
            argv += ["--fault", f]
        argv += list(extra)
        self.proc = subprocess.Popen(
            argv, stdout=self.log, stderr=subprocess.STDOUT, env=env(), cwd=SOURCE
        )

    def stop(self):
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
            try:
                self.proc.wait(timeout=15)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.log.close()

    def events(self, name=None):
        out = []
        with open(self.record) as f:
            for line in f:
                line = line.strip()
                if line:
                    e = json.loads(line)
                    if name is None or e["event"] == name:
                        out.append(e)
        return out


def exec_argv(plan, journal, summary, time_scale, extra=()):
    return [
        EXEC,
        "--plan",
        str(plan),
        "--config",
        CONFIG,
        "--journal",
        str(journal),
        "--summary",
        str(summary),
        "--transport",
        "udp",
        "--channel",
        GROUP,
        "--time-scale",
        str(time_scale),
        "--heartbeat-timeout",
        str(HEARTBEAT_TIMEOUT_S),
    ] + list(extra)


def run_exec(plan, journal, summary, time_scale, extra=(), timeout=240):
    proc = subprocess.run(
        exec_argv(plan, journal, summary, time_scale, extra),
        capture_output=True,
        text=True,
        timeout=timeout,
    )
    with open(summary) as f:
        return proc, json.load(f)


def start_exec(plan, journal, summary, time_scale, extra=()):
    return subprocess.Popen(
        exec_argv(plan, journal, summary, time_scale, extra),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def read_journal(path):
    """Parse and verify a journal: (header, records). Every complete line must carry a
    valid CRC-32; raises AssertionError naming the line otherwise."""
    recs = []
    with open(path, "rb") as f:
        data = f.read()
    lines = data.split(b"\n")
    assert lines[-1] == b"", f"{path}: last record is torn"
    for n, raw in enumerate(lines[:-1], 1):
        text, sep, crc = raw.rpartition(b" *")
        assert sep, f"{path}: line {n}: no checksum"
        assert zlib.crc32(text) == int(crc, 16), f"{path}: line {n}: checksum mismatch"
        recs.append(text.decode().split())
    assert recs and recs[0][0] == "HVJ", f"{path}: no header"
    return recs[0], recs[1:]


def outcomes(records):
    """{(side, id): (outcome, reason, attempt)}; asserts a single outcome per fruit."""
    out = {}
    for r in records:
        if r[0] == "F":
            key = (r[1], r[2])
            assert key not in out, f"fruit {key} has two outcomes"
            out[key] = (r[3], r[4], int(r[5].split("=")[1]))
    return out


def outcome_order(records):
    order = {"L": [], "R": []}
    for r in records:
        if r[0] == "F":
            order[r[1]].append(r[2])
    return order


def sim_picks(sim):
    """Cuts the simulated arms completed: (node, rounded joint positions, vehicle position)."""
    return [
        (e["node"], tuple(round(q, 3) for q in e["positions"]), round(e["vehicle_position"], 3))
        for e in sim.events("pick")
    ]


def assert_every_fruit_cut_once(plan, sim):
    """From the simulator's own record: each cut is a planned fruit of its arm at its stop
    (the end effector's pose by fk_check's forward kinematics, within the DBC's
    resolution), in the plan's order, and every planned fruit is cut exactly once."""
    order = plan_order(plan)
    fk_check.assert_cuts_on_plan(
        plan, sim.events("pick"), picked={(s, i) for s in order for i in order[s]}
    )


def row_end_reached(plan, sim):
    """The simulated vehicle arrived at the row end (the executor's last move)."""
    end = plan["params"]["row_start_m"] + plan["params"]["row_length_m"]
    return any(abs(e["position"] - end) < 1e-3 for e in sim.events("arrived"))


def sim_commands(sim):
    """Every command the simulated nodes received: (node, command, accepted)."""
    return [(e["node"], e["command"], e["accepted"]) for e in sim.events("command")]


# A CAN id of a node the DBC does not have (1..4 are ours), command 3 (status)
UNKNOWN_ID = (7 << 5) | 3


def bus_barrier(sim, timeout=30.0):
    """Put a frame of an id the DBC does not have, with data of its own, on the bus and
    wait until the simulator's record refuses it: every frame sent before it is then in
    the record too (one bus, one socket, frames taken in the order they came). True when
    it came back within the timeout."""
    import can

    mark = os.urandom(8)
    with can.Bus(interface="udp_multicast", channel=GROUP) as bus:
        bus.send(can.Message(arbitration_id=UNKNOWN_ID, data=mark, is_extended_id=False))
    return wait_for(
        lambda: any(
            e["reason"] == "unknown_id" and e.get("data") == mark.hex()
            for e in sim.events("rx_rejected")
        ),
        timeout,
    )


def wait_for(pred, timeout, period=0.05):
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        if pred():
            return True
        time.sleep(period)
    return False


def start_can_logger(path):
    """python-can's own logger on the test's bus, writing `path` (.blf or .asc by extension)."""
    return subprocess.Popen(
        [sys.executable, "-m", "can.logger", "-i", "udp_multicast", "-c", GROUP, "-f", str(path)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )


def stop_can_logger(proc):
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode in (0, -signal.SIGINT), err


def cut_commands(log_path):
    """Per arm ("left_arm"/"right_arm"), the distinct end-effector CUT commands (by their
    sequence number) in a CAN log, decoded with the repository's DBC."""
    import can
    import cantools

    db = cantools.database.load_file(os.path.join(SOURCE, "executor", "can", "harvest.dbc"))
    seqs = {"left_arm": set(), "right_arm": set()}
    for msg in can.LogReader(str(log_path)):
        m = db.get_message_by_frame_id(msg.arbitration_id)
        if m.name.endswith("ArmEeCommand"):
            d = m.decode(msg.data, decode_choices=True)
            if str(d["Action"]) == "CUT":
                seqs["left_arm" if m.name.startswith("Left") else "right_arm"].add(d["EeSeq"])
    return {k: len(v) for k, v in seqs.items()}


def mcap_matches_log(mcap_path, log_path):
    """Every message of the LCM log is in the MCAP file, in order, with the same content,
    on its channel, and each channel's schema describes its messages' fields. Returns the
    number of messages."""
    import lcm
    from mcap.reader import make_reader

    from harvest.telemetry import lcm_schema, lcm_types

    types = lcm_types.load()

    expected = [
        (
            ev.channel,
            ev.timestamp * 1000,
            lcm_schema.to_json(lcm_types.decode(ev.channel, ev.data, types)),
        )
        for ev in lcm.EventLog(str(log_path), "r")
    ]
    got = []
    with open(mcap_path, "rb") as f:
        for schema, channel, message in make_reader(f).iter_messages(log_time_order=False):
            data = json.loads(message.data)
            assert schema.encoding == "jsonschema" and channel.message_encoding == "json"
            props = json.loads(schema.data)["properties"]
            assert set(props) == set(data), channel.topic
            got.append((channel.topic, message.log_time, data))
    assert got == expected
    return len(got)


def replayed_frames(log_path, timeout_s=60.0):
    """Replay a CAN log onto the test's bus with python-can's player and count, on a bus
    of our own, the frames that arrive (the player's order and timing kept)."""
    import can

    with can.Bus(interface="udp_multicast", channel=GROUP) as bus:
        player = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "can.player",
                "-i",
                "udp_multicast",
                "-c",
                GROUP,
                "-s",
                "0.05",
                str(log_path),
            ],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
        )
        n, deadline = 0, time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            if bus.recv(timeout=0.5) is not None:
                n += 1
            elif player.poll() is not None:
                break
        _, err = player.communicate(timeout=30)
        assert player.returncode == 0, err
    return n
