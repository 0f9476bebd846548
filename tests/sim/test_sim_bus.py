"""The simulator seen from the bus: a python-can client plays the executor.

Runs on the bus HV_SIM_BUS names (conftest.py): `virtual` here, udp_multicast in a private
network namespace (test_sim_netns.py) and vcan0 in the QEMU guest (test_sim_guest.py).
Motion times are checked in simulated time (the record's stamps), against the trapezoid
formula computed here independently of the simulator; nothing asserts wall-clock speed.
"""

import json
import math
import os

import pytest

from harvest.sim.model import Model

SCALE = float(os.environ.get("HV_SIM_SCALE", "20"))  # as in conftest.py

MODEL = Model.load()
LIMITS = [(j.min, j.max, j.vmax, j.amax) for j in MODEL.joints]
HOME = list(MODEL.home)
ARMS = ("LeftArm", "RightArm")
NODE_OF = {"Vehicle": "vehicle", "LeftArm": "left_arm", "RightArm": "right_arm"}
ESTOP_BIT = {"Vehicle": 4, "LeftArm": 10, "RightArm": 10}
REJECT_BIT = 11
POS_TOL = 1.5e-4  # DBC position resolution 1e-4, plus rounding
TIME_TOL = 1e-3  # s simulated; the record keeps microseconds
START = [0.05, 0.6, 0.3, -1.0]  # an arm pose away from home, inside every joint range


def trap(d, v, a):
    """DESIGN §1: t = 2 sqrt(d/a) if d <= v^2/a else d/v + v/a."""
    d = abs(d)
    return 2 * math.sqrt(d / a) if d <= v * v / a else d / v + v / a


def move_time(q0, q1):
    return max(trap(b - a, lim[2], lim[3]) for a, b, lim in zip(q0, q1, LIMITS))


def val(proto, msg, sig, label):
    return proto.value_of(msg, sig, label)


class Exec:
    """Executor-side helpers over the client: commands with sequence numbers and waits."""

    def __init__(self, client, proto):
        self.c, self.p = client, proto
        self.seq = {}

    def next_seq(self, key, mod=256):
        self.seq[key] = (self.seq.get(key, 0) + 1) % mod
        return self.seq[key]

    def command(self, prefix, label):
        seq = self.next_seq(prefix + "cmd")
        mark = self.c.mark()
        self.c.send(
            f"{prefix}Command",
            Command=val(self.p, f"{prefix}Command", "Command", label),
            CommandSeq=seq,
        )
        return seq, mark

    def state(self, prefix, label):
        return val(self.p, f"{prefix}Status", "State", label)

    def accepted(self, prefix, label, state=None):
        """Send a command, wait for its echo (and the state), return the status."""
        seq, mark = self.command(prefix, label)
        want = None if state is None else self.state(prefix, state)
        return self.c.wait_for(
            f"{prefix}Status",
            lambda s: s["CommandSeq"] == seq and (want is None or s["State"] == want),
            since=mark,
        )[1]

    def sync(self, prefix):
        """Everything sent to `prefix` before has been handled once a NONE is echoed."""
        return self.accepted(prefix, "NONE")

    def refused(self, prefix, label):
        """Send a command that must not be accepted: its seq is never echoed."""
        before = self.seq.get(prefix + "cmd", 0)
        seq, mark = self.command(prefix, label)
        # a later NONE is handled after it: if its echo comes, the refused one was handled
        status = self.sync(prefix)
        assert status["CommandSeq"] != seq
        return before, status

    def setpoint(self, prefix, q, strict=True):
        seq = self.next_seq(prefix + "sp", 32)
        mark = self.c.mark()
        self.c.send(
            f"{prefix}Setpoint",
            strict=strict,
            SetpointSeq=seq,
            **{f"Joint{j + 1}Position": q[j] for j in range(4)},
        )
        return seq, mark

    def reached(self, prefix, seq, since):
        return self.c.wait_for(
            f"{prefix}Status",
            lambda s: s["SetpointSeq"] == seq and s["TargetReached"] == 1,
            since=since,
        )

    def ee(self, prefix, label):
        seq = self.next_seq(prefix + "ee")
        mark = self.c.mark()
        self.c.send(
            f"{prefix}EeCommand",
            Action=val(self.p, f"{prefix}EeCommand", "Action", label),
            EeSeq=seq,
        )
        return seq, mark

    def ee_state(self, prefix, label):
        return val(self.p, f"{prefix}EeStatus", "State", label)


@pytest.fixture
def ex(proto):
    return lambda client: Exec(client, proto)


def one(events, **match):
    hits = [e for e in events if all(e.get(k) == v for k, v in match.items())]
    assert len(hits) == 1, f"expected one record line {match}, got {hits}"
    return hits[0]


# -- heartbeats and commands ---------------------------------------------------------------


def test_every_node_sends_heartbeats_with_the_time_scale(sim, proto):
    h, c = sim()
    for prefix in ("Vehicle", "LeftArm", "RightArm"):
        _, first = c.wait_for(f"{prefix}Heartbeat")
        i, second = c.wait_for(f"{prefix}Heartbeat", lambda s: s["Counter"] != first["Counter"])
        assert second["Counter"] == (first["Counter"] + 1) % 256
        assert second["TimeScale"] == pytest.approx(SCALE)
        assert second["ProtocolVersion"] == 1
        assert second["Health"] == val(proto, f"{prefix}Heartbeat", "Health", "OK")


@pytest.mark.parametrize("prefix", ["Vehicle", "LeftArm", "RightArm"])
def test_command_state_machine(sim, ex, prefix):
    h, c = sim()
    e = ex(c)
    st = e.sync(prefix)
    assert st["State"] == e.state(prefix, "DISABLED")
    e.refused(prefix, "HOME")  # not enabled
    e.accepted(prefix, "ENABLE", "IDLE")
    e.accepted(prefix, "DISABLE", "DISABLED")
    e.accepted(prefix, "ENABLE", "IDLE")
    st = e.accepted(prefix, "ESTOP", "ESTOP")
    assert st["FaultBits"] & (1 << ESTOP_BIT[prefix])
    e.refused(prefix, "ENABLE")  # latched until CLEAR_ESTOP
    e.refused(prefix, "CLEAR_FAULT")  # which a fault clear never is
    st = e.accepted(prefix, "CLEAR_ESTOP", "DISABLED")
    assert st["FaultBits"] == 0
    e.accepted(prefix, "ENABLE", "IDLE")
    events = h.stop()
    cmds = [x for x in events if x["event"] == "command" and x["node"] == NODE_OF[prefix]]
    labels = [(x["command"], x["accepted"]) for x in cmds if x["command"] != "NONE"]
    assert labels == [
        ("HOME", False),
        ("ENABLE", True),
        ("DISABLE", True),
        ("ENABLE", True),
        ("ESTOP", True),
        ("ENABLE", False),
        ("CLEAR_FAULT", False),
        ("CLEAR_ESTOP", True),
        ("ENABLE", True),
    ]


# -- arm motion ---------------------------------------------------------------------------------


@pytest.mark.parametrize("prefix", ARMS)
def test_home_moves_every_joint_on_its_trapezoid(sim, ex, prefix):
    h, c = sim("--arm-start", *map(str, START))
    e = ex(c)
    e.accepted(prefix, "ENABLE", "IDLE")
    st = e.accepted(prefix, "HOME")
    assert st["State"] == e.state(prefix, "HOMING") and st["Homed"] == 0
    c.wait_for(
        f"{prefix}Status", lambda s: s["Homed"] == 1 and s["State"] == e.state(prefix, "IDLE")
    )
    _, js = c.wait_for(
        f"{prefix}JointState",
        lambda s: all(abs(s[f"Joint{j + 1}Position"] - HOME[j]) < POS_TOL for j in range(4)),
    )
    homed = one(h.events("homed", NODE_OF[prefix]))
    assert homed["elapsed"] == pytest.approx(move_time(START, HOME), abs=TIME_TOL)


@pytest.mark.parametrize("prefix", ARMS)
def test_setpoint_reaches_target_on_the_trapezoid(sim, ex, prefix):
    h, c = sim()
    e = ex(c)
    e.accepted(prefix, "ENABLE", "IDLE")
    target = [0.40, -0.8, 2.2, 1.0]
    seq, mark = e.setpoint(prefix, target)
    end, st = e.reached(prefix, seq, mark)
    assert st["State"] == e.state(prefix, "IDLE") and st["FaultBits"] == 0
    # the motion as the bus saw it: speeds within the limits, each joint monotone
    vel = c.all(f"{prefix}JointVelocity", mark, end)
    pos = c.all(f"{prefix}JointState", mark, end + 20)
    for j, (lo, hi, vmax, amax) in enumerate(LIMITS):
        speeds = [abs(v[f"Joint{j + 1}Velocity"]) for v in vel]
        assert max(speeds) <= vmax + 1e-4
        qs = [p[f"Joint{j + 1}Position"] for p in pos]
        sign = 1 if target[j] > HOME[j] else -1
        assert all(sign * (b - a) >= -POS_TOL for a, b in zip(qs, qs[1:]))
    # joints 3 and 4 travel 0.8 and 1.0 rad > v^2/a = 0.2 rad: they cruise at vmax for 3-4 s
    for j in (3, 4):
        assert max(abs(v[f"Joint{j}Velocity"]) for v in vel) == pytest.approx(
            LIMITS[j - 1][2], abs=2e-3
        )
    _, last = c.wait_for(f"{prefix}JointState", since=end)
    for j in range(4):
        assert last[f"Joint{j + 1}Position"] == pytest.approx(target[j], abs=POS_TOL)
    node = NODE_OF[prefix]
    sp = one(h.events("setpoint", node), seq=seq)
    for j in range(4):
        assert sp["durations"][j] == pytest.approx(
            trap(target[j] - HOME[j], *LIMITS[j][2:]), abs=TIME_TOL
        )
    done = one(h.events("target_reached", node), seq=seq)
    assert done["elapsed"] == pytest.approx(move_time(HOME, target), abs=TIME_TOL)
    assert done["t"] - sp["t"] == pytest.approx(move_time(HOME, target), abs=TIME_TOL)


def test_new_setpoint_replaces_the_running_one(sim, ex):
    h, c = sim()
    e = ex(c)
    e.accepted("LeftArm", "ENABLE", "IDLE")
    seq1, mark = e.setpoint("LeftArm", [0.45, 1.0, 0.5, 2.0])
    c.wait_for(
        "LeftArmStatus",
        lambda s: s["SetpointSeq"] == seq1 and s["State"] == e.state("LeftArm", "MOVING"),
        since=mark,
    )
    c.wait_for("LeftArmJointState", lambda s: s["Joint2Position"] > 0.05, since=mark)
    seq2, mark2 = e.setpoint("LeftArm", HOME)
    end, _ = e.reached("LeftArm", seq2, mark2)
    assert not any(
        s["TargetReached"] and s["SetpointSeq"] == seq1 for s in c.all("LeftArmStatus", mark)
    )
    _, last = c.wait_for("LeftArmJointState", since=end)
    assert last["Joint2Position"] == pytest.approx(HOME[1], abs=POS_TOL)
    vel = c.all("LeftArmJointVelocity", mark, end)
    assert max(abs(v["Joint2Velocity"]) for v in vel) <= LIMITS[1][2] + 1e-4


@pytest.mark.parametrize("joint,value", [(1, 0.6), (2, 1.6), (3, 2.9), (4, -3.2)])
def test_out_of_range_setpoint_is_rejected_with_bit_11(sim, ex, joint, value):
    h, c = sim()
    e = ex(c)
    e.accepted("RightArm", "ENABLE", "IDLE")
    q = list(HOME)
    q[joint - 1] = value
    seq, mark = e.setpoint("RightArm", q, strict=False)
    _, st = c.wait_for("RightArmStatus", lambda s: s["FaultBits"] & (1 << REJECT_BIT), since=mark)
    assert st["SetpointSeq"] != seq and st["State"] == e.state("RightArm", "IDLE")
    line = one(h.events("setpoint", "right_arm"), seq=seq)
    assert line["accepted"] is False and f"joint {joint}" in line["reason"]
    # a valid setpoint is accepted and clears the bit
    ok = list(HOME)
    ok[0] = 0.3
    seq2, mark2 = e.setpoint("RightArm", ok)
    _, st = e.reached("RightArm", seq2, mark2)
    assert not st["FaultBits"] & (1 << REJECT_BIT)


def test_setpoint_refused_while_disabled(sim, ex):
    h, c = sim()
    e = ex(c)
    seq, mark = e.setpoint("LeftArm", [0.3, 0.1, 1.0, 0.0])
    st = e.sync("LeftArm")
    assert st["SetpointSeq"] != seq and st["State"] == e.state("LeftArm", "DISABLED")
    line = one(h.events("setpoint", "left_arm"), seq=seq)
    assert line["accepted"] is False and "DISABLED" in line["reason"]


# -- end effector ------------------------------------------------------------------------------


@pytest.mark.parametrize("prefix", ARMS)
def test_cut_and_release_take_their_configured_time(sim, ex, prefix):
    h, c = sim("--cut-time", "2.0", "--release-time", "0.8")
    e = ex(c)
    e.accepted(prefix, "ENABLE", "IDLE")
    seq, mark = e.ee(prefix, "CUT")
    c.wait_for(
        f"{prefix}EeStatus",
        lambda s: s["EeSeq"] == seq and s["State"] == e.ee_state(prefix, "BUSY"),
        since=mark,
    )
    _, st = c.wait_for(
        f"{prefix}EeStatus",
        lambda s: s["EeSeq"] == seq and s["State"] == e.ee_state(prefix, "DONE"),
        since=mark,
    )
    assert st["FruitHeld"] == 1
    seq2, mark = e.ee(prefix, "RELEASE")
    _, st = c.wait_for(
        f"{prefix}EeStatus",
        lambda s: s["EeSeq"] == seq2 and s["State"] == e.ee_state(prefix, "DONE"),
        since=mark,
    )
    assert st["FruitHeld"] == 0
    node = NODE_OF[prefix]
    cut = one(h.events("ee", node), seq=seq)
    pick = one(h.events("pick", node))
    assert pick["pick"] == 1 and pick["t"] - cut["t"] == pytest.approx(2.0, abs=TIME_TOL)
    for j in range(4):
        assert pick["positions"][j] == pytest.approx(HOME[j], abs=1e-9)
    rel = one(h.events("ee", node), seq=seq2)
    released = one(h.events("release", node))
    assert released["fruit"] is True
    assert released["t"] - rel["t"] == pytest.approx(0.8, abs=TIME_TOL)


def test_cut_fails_while_the_arm_moves(sim, ex):
    h, c = sim()
    e = ex(c)
    e.accepted("LeftArm", "ENABLE", "IDLE")
    sp, mark = e.setpoint("LeftArm", [0.45, 1.0, 0.5, 2.0])
    c.wait_for("LeftArmStatus", lambda s: s["State"] == e.state("LeftArm", "MOVING"), since=mark)
    seq, mark = e.ee("LeftArm", "CUT")
    c.wait_for(
        "LeftArmEeStatus",
        lambda s: s["EeSeq"] == seq and s["State"] == e.ee_state("LeftArm", "FAILED"),
        since=mark,
    )
    assert not h.events("pick")


# -- vehicle -------------------------------------------------------------------------------------


def test_vehicle_moves_at_its_speed_and_arrives(sim, ex):
    h, c = sim()
    e = ex(c)
    e.accepted("Vehicle", "ENABLE", "IDLE")
    for target, max_speed in ((0.5, 0.0), (0.3, 0.05)):
        seq = e.next_seq("move")
        mark = c.mark()
        c.send("VehicleMove", TargetPosition=target, MaxSpeed=max_speed, MoveSeq=seq)
        end, st = c.wait_for(
            "VehicleStatus", lambda s: s["MoveSeq"] == seq and s["Arrived"] == 1, since=mark
        )
        assert st["Position"] == pytest.approx(target, abs=POS_TOL)
        assert st["State"] == e.state("Vehicle", "IDLE")
        speed = max_speed or MODEL.vehicle_speed
        seen = c.all("VehicleStatus", mark, end)
        assert max(abs(s["Velocity"]) for s in seen) <= speed + 1e-3
        arrived = one(h.events("arrived", "vehicle"), seq=seq)
        start = one(h.events("move", "vehicle"), seq=seq)["start"]
        assert arrived["elapsed"] == pytest.approx(
            trap(target - start, speed, MODEL.vehicle_accel), abs=TIME_TOL
        )
    # homing drives back to the row start
    e.accepted("Vehicle", "HOME")
    _, st = c.wait_for("VehicleStatus", lambda s: s["Homed"] == 1)
    assert st["Position"] == pytest.approx(0.0, abs=POS_TOL)


def test_vehicle_move_outside_travel_is_refused(sim, ex):
    h, c = sim("--travel", "0", "2")
    e = ex(c)
    e.accepted("Vehicle", "ENABLE", "IDLE")
    mark = c.mark()
    c.send("VehicleMove", TargetPosition=2.5, MaxSpeed=0, MoveSeq=9)
    _, st = c.wait_for("VehicleStatus", lambda s: s["FaultBits"] & 0b10, since=mark)
    assert st["MoveSeq"] != 9 and st["Position"] == pytest.approx(0.0, abs=POS_TOL)


# -- e-stop -------------------------------------------------------------------------------------


def test_estop_frame_stops_every_node_until_clear_estop(sim, ex):
    h, c = sim()
    e = ex(c)
    for prefix in ("Vehicle", "LeftArm", "RightArm"):
        e.accepted(prefix, "ENABLE", "IDLE")
    c.send("VehicleMove", TargetPosition=1.0, MaxSpeed=0, MoveSeq=1)
    sp, mark = e.setpoint("LeftArm", [0.45, 1.0, 0.5, 2.0])
    c.wait_for("VehicleStatus", lambda s: s["Velocity"] > 0.05)
    c.wait_for("LeftArmJointVelocity", lambda s: abs(s["Joint2Velocity"]) > 0.05, since=mark)
    c.send("Estop", EstopActive=0, Counter=1)  # carries no meaning
    mark = c.mark()
    c.send("Estop", EstopActive=1, Counter=2)
    for prefix in ("Vehicle", "LeftArm", "RightArm"):
        _, st = c.wait_for(
            f"{prefix}Status", lambda s: s["State"] == e.state(prefix, "ESTOP"), since=mark
        )
        assert st["FaultBits"] & (1 << ESTOP_BIT[prefix])
        _, hb = c.wait_for(f"{prefix}Heartbeat", since=c.mark())
        assert hb["Health"] == val(e.p, f"{prefix}Heartbeat", "Health", "ESTOP")
    # the drives brake to a standstill short of their targets
    _, v = c.wait_for("VehicleStatus", lambda s: s["Velocity"] == 0, since=mark)
    assert 0.0 < v["Position"] < 1.0 - POS_TOL
    _, jv = c.wait_for(
        "LeftArmJointVelocity",
        lambda s: all(s[f"Joint{j}Velocity"] == 0 for j in range(1, 5)),
        since=mark,
    )
    assert not any(s["TargetReached"] and s["SetpointSeq"] == sp for s in c.all("LeftArmStatus"))
    for prefix in ("Vehicle", "LeftArm", "RightArm"):
        e.refused(prefix, "ENABLE")
        e.refused(prefix, "CLEAR_FAULT")
        st = e.accepted(prefix, "CLEAR_ESTOP", "DISABLED")
        assert st["FaultBits"] == 0
    assert len(h.events("estop_frame")) == 6  # two frames, each delivered to three nodes


def test_fault_estop_latches_one_node_until_clear_estop(sim, ex):
    h, c = sim("--fault", "estop:node=left_arm,after_s=1")
    e = ex(c)
    mark = c.mark()
    _, st = c.wait_for(
        "LeftArmStatus", lambda s: s["State"] == e.state("LeftArm", "ESTOP"), since=mark
    )
    assert st["FaultBits"] == 1 << ESTOP_BIT["LeftArm"]
    _, hb = c.wait_for("LeftArmHeartbeat", since=c.mark())
    assert hb["Health"] == val(e.p, "LeftArmHeartbeat", "Health", "ESTOP")
    for prefix in ("Vehicle", "RightArm"):  # the others' own e-stops did not trip
        assert e.sync(prefix)["State"] == e.state(prefix, "DISABLED")
    e.refused("LeftArm", "CLEAR_FAULT")
    e.accepted("LeftArm", "CLEAR_ESTOP", "DISABLED")
    e.accepted("LeftArm", "ENABLE", "IDLE")
    injected = one(h.events("fault_injected", "left_arm"))
    assert injected["fault"] == "estop" and injected["t"] == pytest.approx(1.0, abs=TIME_TOL)


# -- fault injection: each one visible on the bus -------------------------------------------------


def test_fault_drop_tx_leaves_gaps_in_one_node_only(sim):
    h, c = sim("--fault", "drop:fraction=0.5,node=left_arm", "--seed", "3")
    mark = c.mark()
    c.wait_for("RightArmHeartbeat", lambda s: True, since=mark)
    n = 0
    while n < 60:
        i, _ = c.wait_for("RightArmHeartbeat", since=mark)
        mark, n = i + 1, n + 1
    left = [s["Counter"] for s in c.all("LeftArmHeartbeat")]
    right = [s["Counter"] for s in c.all("RightArmHeartbeat")]
    gaps = lambda xs: sum((b - a) % 256 != 1 for a, b in zip(xs, xs[1:]))  # noqa: E731
    assert gaps(right) == 0 and gaps(left) > 0
    assert 0 < len(left) < 0.8 * len(right)
    stats = h.stop()[-1]["stats"]
    assert stats["tx_dropped"] > 0


def test_fault_drop_rx_loses_commands_to_one_node(sim, ex):
    h, c = sim("--fault", "drop:fraction=1,direction=rx,node=right_arm")
    e = ex(c)
    e.accepted("LeftArm", "ENABLE", "IDLE")
    seq, mark = e.command("RightArm", "ENABLE")
    e.sync("LeftArm")
    # twenty status periods later the right arm has still not seen it
    i = mark
    for _ in range(20):
        i, st = c.wait_for("RightArmStatus", since=i + 1)
        assert st["CommandSeq"] != seq and st["State"] == e.state("RightArm", "DISABLED")
    assert any(x["name"] == "RightArmCommand" for x in h.events("rx_dropped", "right_arm"))


@pytest.mark.parametrize("direction", ["tx", "rx"])
def test_fault_delay_makes_one_node_answer_late(sim, ex, direction):
    h, c = sim("--fault", f"delay:delay_s=4,node=left_arm,direction={direction}")
    e = ex(c)
    mark = c.mark()
    lseq, _ = e.command("LeftArm", "ENABLE")
    rseq, _ = e.command("RightArm", "ENABLE")
    li, _ = c.wait_for("LeftArmStatus", lambda s: s["CommandSeq"] == lseq, since=mark)
    ri, _ = c.wait_for("RightArmStatus", lambda s: s["CommandSeq"] == rseq, since=mark)
    # sent together, the left answer came 4 s later (its reply or the command held back)
    assert ri < li
    lcmd = one(h.events("command", "left_arm"), seq=lseq)
    rcmd = one(h.events("command", "right_arm"), seq=rseq)
    assert lcmd["accepted"] and rcmd["accepted"]
    if direction == "rx":
        # the left command was handled no earlier than 4 s after it arrived (the right one
        # arrived just after it and was handled at once)
        assert lcmd["t"] - rcmd["t"] >= 4.0 - 0.1
    # delayed frames keep their order: the heartbeat counters still arrive in sequence
    left = [s["Counter"] for s in c.all("LeftArmHeartbeat")]
    assert left and all((b - a) % 256 == 1 for a, b in zip(left, left[1:]))
    assert h.stop()[-1]["stats"][f"{direction}_delayed"] > 0


def test_fault_stall_never_reaches_the_target(sim, ex):
    h, c = sim("--fault", "stall:node=left_arm,joint=2,fraction=0.5")
    e = ex(c)
    e.accepted("LeftArm", "ENABLE", "IDLE")
    target = [0.3, 1.0, 1.4, 0.0]  # joint 2 travels 1 rad: 6 s planned
    seq, mark = e.setpoint("LeftArm", target)
    planned = move_time(HOME, target)
    # wait twice the planned time, counted in 0.1 s heartbeats of the other arm
    i = mark
    for _ in range(int(2 * planned / 0.1)):
        i, _ = c.wait_for("RightArmHeartbeat", since=i + 1)
    assert not any(s["TargetReached"] for s in c.all("LeftArmStatus", mark))
    _, st = c.wait_for("LeftArmStatus", since=i)
    assert st["State"] == e.state("LeftArm", "MOVING") and st["SetpointSeq"] == seq
    _, js = c.wait_for("LeftArmJointState", since=i)
    _, jv = c.wait_for("LeftArmJointVelocity", since=i)
    assert js["Joint2Position"] == pytest.approx(0.5, abs=POS_TOL)
    assert js["Joint1Position"] == pytest.approx(0.3, abs=POS_TOL)
    assert all(jv[f"Joint{j}Velocity"] == 0 for j in range(1, 5))


def test_fault_joint_fault_at_the_kth_pick(sim, ex):
    h, c = sim(
        "--fault",
        "joint_fault:node=right_arm,joint=3,pick=2",
        "--cut-time",
        "0.5",
        "--release-time",
        "0.5",
    )
    e = ex(c)
    e.accepted("RightArm", "ENABLE", "IDLE")
    for label in ("CUT", "RELEASE"):
        seq, mark = e.ee("RightArm", label)
        c.wait_for(
            "RightArmEeStatus",
            lambda s: s["EeSeq"] == seq and s["State"] == e.ee_state("RightArm", "DONE"),
            since=mark,
        )
    seq, mark = e.ee("RightArm", "CUT")
    fi, st = c.wait_for(
        "RightArmStatus", lambda s: s["State"] == e.state("RightArm", "FAULT"), since=mark
    )
    assert st["FaultBits"] == 1 << (4 + 2)  # following error of joint 3
    c.wait_for(
        "RightArmEeStatus",
        lambda s: s["EeSeq"] == seq and s["State"] == e.ee_state("RightArm", "FAILED"),
        since=mark,
    )
    _, hb = c.wait_for("RightArmHeartbeat", since=fi)
    assert hb["Health"] == val(e.p, "RightArmHeartbeat", "Health", "FAULT")
    assert [p["pick"] for p in h.events("pick", "right_arm")] == [1]
    e.refused("RightArm", "ENABLE")
    e.accepted("RightArm", "CLEAR_FAULT", "DISABLED")


def test_fault_joint_fault_during_a_setpoint(sim, ex):
    h, c = sim("--fault", "joint_fault:node=left_arm,joint=1,setpoint=1,at=0.5,kind=limit")
    e = ex(c)
    e.accepted("LeftArm", "ENABLE", "IDLE")
    target = [0.45, 0.0, 1.4, 0.0]
    seq, mark = e.setpoint("LeftArm", target)
    fi, st = c.wait_for(
        "LeftArmStatus", lambda s: s["State"] == e.state("LeftArm", "FAULT"), since=mark
    )
    assert st["FaultBits"] == 1 << 0 and st["TargetReached"] == 0
    i, _ = c.wait_for("LeftArmJointVelocity", lambda s: s["Joint1Velocity"] == 0, since=fi)
    _, js = c.wait_for("LeftArmJointState", since=i)
    assert HOME[0] + 0.01 < js["Joint1Position"] < target[0] - 0.01
    injected = one(h.events("fault_injected", "left_arm"))
    sp = one(h.events("setpoint", "left_arm"), seq=seq)
    assert injected["t"] - sp["t"] == pytest.approx(0.5 * sp["duration"], abs=TIME_TOL)


def test_fault_silent_node_stops_sending(sim):
    h, c = sim(
        "--fault",
        "silent:after_s=1,node=vehicle",
        "--fault",
        "silent:after_s=1,node=left_arm,frames=heartbeat",
    )
    # 3 s simulated later (30 right-arm heartbeats) nothing more came from the vehicle
    i = 0
    for _ in range(40):
        i, _ = c.wait_for("RightArmHeartbeat", since=i + 1)
    names = [n for _, n, _ in c.frames]
    last_vehicle = max(k for k, n in enumerate(names) if n.startswith("Vehicle"))
    last_left_hb = max(k for k, n in enumerate(names) if n == "LeftArmHeartbeat")
    after = names[last_vehicle + 1 :]
    assert after.count("RightArmHeartbeat") >= 20
    # the left arm lost only its heartbeat: its status keeps coming
    assert names[last_left_hb + 1 :].count("LeftArmStatus") >= 20
    assert {(x["node"], x["frames"]) for x in h.events("fault_injected")} == {
        ("vehicle", "all"),
        ("left_arm", "heartbeat"),
    }


def test_fault_silent_for_a_while_then_back(sim):
    h, c = sim("--fault", "silent:after_s=1,node=vehicle,for_s=2")
    h.wait_events("fault_ended", 1)
    mark = c.mark()
    _, hb = c.wait_for("VehicleHeartbeat", since=mark)
    names = [n for _, n, _ in c.frames]
    # no vehicle frame for 2 s simulated: about 20 right-arm heartbeats in a row
    run = longest = 0
    for n in names:
        run = 0 if n.startswith("Vehicle") else run + (n == "RightArmHeartbeat")
        longest = max(longest, run)
    assert 15 <= longest <= 25
    ended = one(h.events("fault_ended", "vehicle"))
    assert ended["t"] == pytest.approx(3.0, abs=TIME_TOL)
    assert one(h.events("fault_injected", "vehicle"))["for_s"] == 2


def test_fault_silent_just_after_a_pick(sim, ex):
    h, c = sim("--fault", "silent:node=left_arm,pick=1,for_s=2", "--cut-time", "0.5")
    e = ex(c)
    e.accepted("LeftArm", "ENABLE", "IDLE")
    seq, mark = e.ee("LeftArm", "CUT")
    c.wait_for(
        "LeftArmEeStatus",
        lambda s: s["EeSeq"] == seq and s["State"] == e.ee_state("LeftArm", "DONE"),
        since=mark,
    )
    # the cut's DONE was held back by the silence: its end is in the record before it
    pick = one(h.events("pick", "left_arm"))
    assert one(h.events("fault_injected", "left_arm"))["t"] == pytest.approx(
        pick["t"], abs=TIME_TOL
    )
    ended = one(h.events("fault_ended", "left_arm"))
    assert ended["t"] == pytest.approx(pick["t"] + 2, abs=TIME_TOL)


def test_fault_reject_the_nth_setpoint(sim, ex):
    h, c = sim("--fault", "reject:node=left_arm,setpoint=2")
    e = ex(c)
    e.accepted("LeftArm", "ENABLE", "IDLE")
    q = [0.3, 0.2, 1.2, 0.1]
    s1, m1 = e.setpoint("LeftArm", q)
    e.reached("LeftArm", s1, m1)
    s2, m2 = e.setpoint("LeftArm", HOME)
    _, st = c.wait_for("LeftArmStatus", lambda s: s["FaultBits"] & (1 << REJECT_BIT), since=m2)
    assert st["SetpointSeq"] == s1
    s3, m3 = e.setpoint("LeftArm", HOME)
    _, st = e.reached("LeftArm", s3, m3)
    assert st["FaultBits"] == 0


def test_lost_executor_heartbeat_faults_every_node(sim, ex):
    h, c = sim("--exec-timeout", "0.3")
    e = ex(c)
    c.heartbeat(0.05)
    h.wait_events("executor_seen", 3)
    for prefix in ("Vehicle", "LeftArm", "RightArm"):
        e.accepted(prefix, "ENABLE", "IDLE")
    mark = c.mark()
    c.stop_heartbeat()
    for prefix, bit in (("Vehicle", 3), ("LeftArm", 9), ("RightArm", 9)):
        _, st = c.wait_for(
            f"{prefix}Status", lambda s: s["State"] == e.state(prefix, "FAULT"), since=mark
        )
        assert st["FaultBits"] & (1 << bit)
    assert {x["node"] for x in h.events("comm_timeout")} == {"vehicle", "left_arm", "right_arm"}


def test_scenario_file_and_record_of_a_pick_cycle(sim, ex, tmp_path):
    scen = tmp_path / "faults.json"
    scen.write_text(
        json.dumps({"seed": 5, "faults": [{"type": "reject", "node": "right_arm", "setpoint": 1}]})
    )
    h, c = sim("--scenario", str(scen), "--cut-time", "0.4", "--release-time", "0.2")
    e = ex(c)
    for prefix in ("Vehicle", "LeftArm", "RightArm"):
        e.accepted(prefix, "ENABLE", "IDLE")
    c.send("VehicleMove", TargetPosition=0.2, MaxSpeed=0, MoveSeq=1)
    c.wait_for("VehicleStatus", lambda s: s["MoveSeq"] == 1 and s["Arrived"] == 1)
    approach = [0.3, 0.4, 1.0, -0.2]
    sr, mr = e.setpoint("RightArm", approach)
    c.wait_for("RightArmStatus", lambda s: s["FaultBits"] & (1 << REJECT_BIT), since=mr)
    seq, mark = e.setpoint("LeftArm", approach)
    e.reached("LeftArm", seq, mark)
    cut, mark = e.ee("LeftArm", "CUT")
    c.wait_for("LeftArmEeStatus", lambda s: s["EeSeq"] == cut and s["FruitHeld"] == 1, since=mark)
    seq, mark = e.setpoint("LeftArm", HOME)
    e.reached("LeftArm", seq, mark)
    rel, mark = e.ee("LeftArm", "RELEASE")
    c.wait_for("LeftArmEeStatus", lambda s: s["EeSeq"] == rel and s["FruitHeld"] == 0, since=mark)
    events = h.stop()
    assert events[0]["event"] == "start" and events[0]["seed"] == 5
    assert events[0]["faults"] == [{"type": "reject", "node": "right_arm", "setpoint": 1}]
    assert events[-1]["event"] == "stop"
    pick = one(events, event="pick")
    assert pick["node"] == "left_arm" and pick["vehicle_position"] == pytest.approx(0.2, abs=1e-9)
    assert pick["positions"] == pytest.approx(approach, abs=1e-9)
    kinds = [x["event"] for x in events if x["node"] == "left_arm"]
    for a, b in (
        ("setpoint", "target_reached"),
        ("target_reached", "ee"),
        ("ee", "pick"),
        ("pick", "release"),
    ):
        assert kinds.index(a) < kinds.index(b)
    assert one(events, event="setpoint", node="right_arm")["accepted"] is False


# -- input the simulator cannot take ---------------------------------------------------------


def test_bad_frames_counted_and_dropped_then_a_session_completes(sim, ex, proto):
    """Frames with an id the DBC does not have, a wrong length, a value the DBC does not
    list, or no data (remote): each is counted and dropped with its reason in the record;
    the simulator keeps running and a session after them completes."""
    import can

    h, c = sim()
    e = ex(c)
    cmd = proto.message("LeftArmCommand")
    enable = val(proto, "LeftArmCommand", "Command", "ENABLE")
    unlisted = max(proto.choices("LeftArmCommand", "Command")) + 1
    good = cmd.encode({"Command": enable, "CommandSeq": 200})
    bad = {
        "unknown_id": [
            can.Message(arbitration_id=0x7F0, data=b"\x01", is_extended_id=False),
            can.Message(arbitration_id=cmd.frame_id, data=good, is_extended_id=True),
        ],
        "wrong_length": [
            can.Message(arbitration_id=cmd.frame_id, data=good[:1], is_extended_id=False),
            can.Message(arbitration_id=cmd.frame_id, data=good + b"\x00", is_extended_id=False),
        ],
        "bad_value": [
            can.Message(
                arbitration_id=cmd.frame_id,
                is_extended_id=False,
                data=cmd.encode({"Command": unlisted, "CommandSeq": 201}, strict=False),
            )
        ],
        "not_data_frame": [
            can.Message(
                arbitration_id=cmd.frame_id, is_remote_frame=True, dlc=2, is_extended_id=False
            )
        ],
    }
    for msgs in bad.values():
        for m in msgs:
            c.bus.send(m)
    # handled in order: once a later command is echoed, every bad frame was seen
    st = e.accepted("LeftArm", "ENABLE", "IDLE")
    assert st["CommandSeq"] not in (200, 201)
    seq, mark = e.setpoint("LeftArm", START)
    e.reached("LeftArm", seq, mark)
    events = h.stop()
    stop = events[-1]
    assert stop["event"] == "stop" and stop["reason"] == "stop requested"
    rejected = [x for x in events if x["event"] == "rx_rejected"]
    for reason, msgs in bad.items():
        assert stop["stats"][f"rx_{reason}"] == len(msgs), (reason, stop["stats"])
        assert len([x for x in rejected if x["reason"] == reason]) == len(msgs), rejected
    assert one(rejected, reason="bad_value")["signal"] == "Command"
    assert not [x for x in events if x["event"] == "command" and x["seq"] in (200, 201)]
    assert one(events, event="target_reached", node="left_arm", seq=seq)
