"""`harvest-stack live` as a Foxglove viewer meets it: the server runs on a free loopback port
in a private network namespace, telemetry is published on LCM there with the types
harvest-exec publishes (lcm-gen's Python), and a WebSocket client speaking Foxglove's
protocol checks the channels advertised, subscribes, and
decodes what it receives: the plan sent before it connected, the executor's state, the
faults, the 3D scene. The arms' links come from the product's forward kinematics
(harvest.kinematics), held here against the independent one of fk_check.py."""

import json
import math
import os
import random
import signal
import subprocess
import sys
import time

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fk_check  # noqa: E402

from harvest import kinematics  # noqa: E402
from harvest.scenario.config import Config  # noqa: E402
from harvest.telemetry import lcm_types  # noqa: E402

SOURCE = os.environ.get(
    "HV_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
CONFIG = os.path.join(SOURCE, "config", "harvest.cfg")
LAYOUT = os.path.join(SOURCE, "host", "harvest", "live", "layout.json")
URL = "udpm://239.255.76.71:7671?ttl=0"
SCENE = ["/harvest/scene/plan", "/harvest/scene/robot", "/tf", "/harvest/faults", "/harvest/log"]
SUBPROTOCOL = "foxglove.sdk.v1"
WAIT_S = 60.0  # for the server and each message: a bound, not a measurement


def test_forward_kinematics_agrees_with_the_independent_one():
    cfg = Config.load(CONFIG)
    rnd = random.Random(53)
    worst = 0.0
    for side, arm in kinematics.arms(cfg).items():
        ref = fk_check.Arm(cfg, "L" if side == "left" else "R")
        for _ in range(500):
            q = [rnd.uniform(0, 0.5), rnd.uniform(-1.57, 1.57), rnd.uniform(0, 2.8)]
            q.append(rnd.uniform(-3.14, 3.14))
            vehicle_y = rnd.uniform(-1.0, 3.0)
            x, y, z, _ = ref.pose(q, vehicle_y)
            ee = arm.points(q)[-1]
            worst = max(worst, math.dist((x, y, z), (ee[0], ee[1] + vehicle_y, ee[2])))
        # the base is where docs/FRAMES.md puts it, joint 1 lifts the links beyond it
        pts = arm.points([0.2, 0.0, 0.0, 0.0])
        assert pts[0] == pytest.approx(ref.base + (ref.base_z,))
        assert pts[2][2] - pts[1][2] == pytest.approx(0.2)
    assert worst < 1e-9, worst


@pytest.fixture(scope="module")
def lcm_world():
    """Reasons aside, this process in a private network namespace with the LCM types."""
    try:
        import foxglove  # noqa: F401
        import websockets.sync.client  # noqa: F401
    except ImportError as e:
        pytest.skip(f"SKIPPED: {e} (scripts/setup.sh installs host/requirements.txt)")
    try:
        types = lcm_types.load()
    except lcm_types.LcmTypesMissing as e:
        pytest.skip(f"SKIPPED: {e}")
    from harvest.canbus import netns

    try:
        netns.enter_private_netns()
    except netns.NetnsUnavailable as e:
        pytest.skip(f"SKIPPED: no private network namespace: {e}")
    assert netns.in_private_netns()
    import lcm

    return types, lcm.LCM(URL)


def _plan(T):
    plan = T["plan_t"]()
    plan.plan_path, plan.expected_makespan_s, plan.n_stops = "row.json", 30.0, 2
    for y in (0.4, 1.1):
        s = T["plan_stop_t"]()
        s.y_m, s.expected_s, s.drive_s = y, 10.0, 4.0
        plan.stops.append(s)
    for fid, side, stop, x, y in (("L1", 0, 0, -0.42, 0.6), ("R1", 1, 1, 0.44, 0.9)):
        p = T["plan_pick_t"]()
        p.fruit_id, p.side, p.stop, p.reachable = fid, side, stop, True
        p.x_m, p.y_m, p.z_m = x, y, 0.6
        plan.picks.append(p)
    plan.n_picks = len(plan.picks)
    return plan


def _state(T, phase, reason, vehicle_y):
    m = T["exec_state_t"]()
    m.phase, m.safe_reason, m.stop, m.t_s, m.vehicle_position_m = phase, reason, 0, 7.5, vehicle_y
    m.arm_phase = ["approach", "idle"]
    m.expected_makespan_s = 30.0
    return m


def _arm(T, side, q, fault_bits=0):
    m = T["arm_joint_state_t"]()
    m.side, m.q, m.qd, m.fault_bits = side, list(q), [0.0] * 4, fault_bits
    return m


class Client:
    """A Foxglove WebSocket client: JSON ops in text frames, message data in binary ones
    (opcode 1, subscription id u32, receive time u64, little-endian, then the payload). The
    SDK's server asks for the subprotocol by the SDK's name (foxglove.sdk.v1; the protocol
    is the one the older ws-protocol servers call foxglove.websocket.v1)."""

    def __init__(self, ws):
        assert ws.subprotocol == SUBPROTOCOL
        self.ws = ws
        self.ops = []

    def next(self, deadline):
        left = deadline - time.monotonic()
        if left <= 0:
            return None
        try:
            frame = self.ws.recv(timeout=left)
        except TimeoutError:
            return None
        if isinstance(frame, str):
            op = json.loads(frame)
            self.ops.append(op)
            return op
        assert frame[0] == 1, f"binary opcode {frame[0]}"
        return {
            "op": "messageData",
            "subscriptionId": int.from_bytes(frame[1:5], "little"),
            "payload": frame[13:],
        }

    def until(self, **wants):
        """{name: the first message for which wants[name](message) is true}, each within
        WAIT_S; the messages in between are read past."""
        got = {}
        deadline = time.monotonic() + WAIT_S
        while len(got) < len(wants) and (m := self.next(deadline)) is not None:
            got.update({k: m for k, want in wants.items() if k not in got and want(m)})
        missing = sorted(set(wants) - set(got))
        assert not missing, (
            f"{missing}: none within {WAIT_S} s (ops: {[o['op'] for o in self.ops]})"
        )
        return got


def _layout_topics():
    """Every topic the layout's panels read."""
    with open(LAYOUT, encoding="utf-8") as f:
        configs = json.load(f)["configById"]
    out = set()
    for panel, c in configs.items():
        out |= set(c.get("topics", {}))
        for key in ("topicPath", "topicToRender"):
            if key in c:
                out.add(c[key])
        out |= {p["value"].split(".")[0] for p in c.get("paths", [])}
    return out


def test_a_foxglove_client_sees_the_robot(lcm_world, tmp_path):
    types, lc = lcm_world
    ready = tmp_path / "ready"
    server = subprocess.Popen(
        [sys.executable, "-m", "harvest", "live", "--lcm-url", URL, "--port", "0",
         "--ready-file", str(ready)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        deadline = time.monotonic() + WAIT_S
        while not ready.exists() and server.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
        assert ready.exists(), server.communicate(timeout=10)
        port = int(ready.read_text())
        # the plan goes out once, at the executor's start: before any viewer
        lc.publish("HARVEST_PLAN", _plan(types).encode())
        from websockets.sync.client import connect

        with connect(f"ws://127.0.0.1:{port}", subprotocols=[SUBPROTOCOL]) as ws:
            client = Client(ws)
            info = client.until(info=lambda m: m.get("op") == "serverInfo")["info"]
            assert info["name"] == "harvest-stack live"
            channels = {}
            want = set(lcm_types.CHANNELS) | set(SCENE)
            while set(channels) != want:
                ad = client.until(advertise=lambda m: m.get("op") == "advertise")["advertise"]
                channels.update({c["topic"]: c for c in ad["channels"]})
            state = channels["HARVEST_EXEC_STATE"]
            assert (state["encoding"], state["schemaEncoding"]) == ("json", "jsonschema")
            assert state["schemaName"] == "harvest.exec_state_t"
            assert "vehicle_position_m" in json.loads(state["schema"])["properties"]
            for topic, schema in (
                ("/harvest/scene/robot", "foxglove.SceneUpdate"),
                ("/tf", "foxglove.FrameTransforms"),
                ("/harvest/log", "foxglove.Log"),
            ):
                assert (channels[topic]["encoding"], channels[topic]["schemaName"]) == (
                    "protobuf",
                    schema,
                ), topic
            assert _layout_topics() <= set(channels), _layout_topics() - set(channels)

            subs = ["HARVEST_PLAN", "HARVEST_EXEC_STATE", "/harvest/faults", "/harvest/scene/robot"]
            subs.append("/harvest/scene/plan")
            client.ws.send(
                json.dumps(
                    {
                        "op": "subscribe",
                        "subscriptions": [
                            {"id": k, "channelId": channels[t]["id"]} for k, t in enumerate(subs)
                        ],
                    }
                )
            )
            got = client.until(
                plan=lambda m: m.get("subscriptionId") == 0,
                scene=lambda m: m.get("subscriptionId") == 4,
            )
            plan = json.loads(got["plan"]["payload"])
            assert plan["plan_path"] == "row.json" and plan["n_picks"] == 2
            assert [p["fruit_id"] for p in plan["picks"]] == ["L1", "R1"]
            # the plan's scene in the row's frame (protobuf: its strings as they are)
            assert all(s in got["scene"]["payload"] for s in (b"row", b"stops", b"fruits"))

            fault = types["fruit_event_t"]()
            fault.fruit_id, fault.side, fault.event, fault.reason = "R1", 1, "fault", "joint_fault"
            lc.publish("HARVEST_FRUIT", fault.encode())
            lc.publish("HARVEST_ARM_LEFT", _arm(types, 0, [0.3, 0.2, 1.1, -0.4]).encode())
            lc.publish("HARVEST_EXEC_STATE", _state(types, "safe", "estop", 1.25).encode())

            got = client.until(
                state=lambda m: m.get("subscriptionId") == 1 and b'"safe"' in m["payload"],
                faults=lambda m: m.get("subscriptionId") == 2 and b"estop" in m["payload"],
                scene=lambda m: m.get("subscriptionId") == 3 and b"SAFE: estop" in m["payload"],
            )
            st = json.loads(got["state"]["payload"])
            assert (st["phase"], st["safe_reason"], st["vehicle_position_m"]) == (
                "safe",
                "estop",
                1.25,
            )
            assert st["arm_phase"] == ["approach", "idle"]
            faults = json.loads(got["faults"]["payload"])["faults"]
            assert [(f["source"], f["name"]) for f in faults] == [
                ("right arm", "joint_fault"),
                ("executor", "estop"),
            ]
            # protobuf: the scene's strings are in its bytes as they are
            assert b"arm/left" in got["scene"]["payload"]
            assert b"left: approach" in got["scene"]["payload"]
    finally:
        server.send_signal(signal.SIGTERM)
        out, err = server.communicate(timeout=WAIT_S)
    assert server.returncode == 0, err
    assert "HARVEST_EXEC_STATE 1" in out and "HARVEST_PLAN 1" in out, out


def test_the_layout_is_written_where_asked(tmp_path):
    out = tmp_path / "harvest.json"
    r = subprocess.run(
        [sys.executable, "-m", "harvest", "live", "--write-layout", str(out)],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, r.stderr
    with open(LAYOUT, encoding="utf-8") as f:
        assert json.loads(out.read_text()) == json.load(f)
    r = subprocess.run(
        [sys.executable, "-m", "harvest", "live", "--write-layout", str(tmp_path / "no" / "l")],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 1
    assert r.stderr.startswith(f"harvest-stack live: {tmp_path / 'no' / 'l'}: No such file")


def test_a_nodes_fault_bits_are_named_by_the_dbc():
    from harvest.canbus import enums
    from harvest.live.state import LiveState

    try:
        T = lcm_types.load()
    except lcm_types.LcmTypesMissing as e:
        pytest.skip(f"SKIPPED: {e}")
    first, second = list(enums.ArmFault)[:2]
    s = LiveState(lambda bits: enums.flag_names(enums.ArmFault, bits))
    assert s.apply("HARVEST_ARM_RIGHT", _arm(T, 1, [0.25, 0, 1.4, 0])).parts == {"robot"}
    change = s.apply("HARVEST_ARM_RIGHT", _arm(T, 1, [0.25, 0, 1.4, 0], first | second))
    assert change.parts == {"robot", "faults"}
    assert [(f["source"], f["name"]) for f in s.faults] == [
        ("right arm", f"{first.name}+{second.name}")
    ]
    # the same bits again are the same fault, not a new one
    s.apply("HARVEST_ARM_RIGHT", _arm(T, 1, [0.25, 0, 1.4, 0], first | second))
    assert len(s.faults) == 1
    unnamed = 1 << 15
    assert not unnamed & sum(enums.ArmFault), "bit 15 is named now: pick another"
    assert enums.flag_names(enums.ArmFault, first | unnamed) == [first.name, "0x8000"]
