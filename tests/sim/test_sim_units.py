"""The simulator's parts without a bus: profiles, fault specs, the node state machines."""

import json
import math

import pytest

from harvest.canbus.enums import ArmFault, Command, EeAction, EeState, Health, State
from harvest.sim import faults
from harvest.sim.arm import ArmNode
from harvest.sim.clock import ScaledClock
from harvest.sim.model import ConfigError, Model
from harvest.sim.profile import Profile, trapezoid_time
from harvest.sim.vehicle import VehicleNode

MODEL = Model.load()


def formula(d, v, a):
    d = abs(d)
    return 2 * math.sqrt(d / a) if d <= v * v / a else d / v + v / a


def sample(p, n=2000):
    ts = [p.t0 + p.duration * k / n for k in range(n + 1)]
    return ts, [p.state(t) for t in ts]


# -- profiles -------------------------------------------------------------------------------


@pytest.mark.parametrize("d", [0.0, 0.001, 0.05, 0.1, 0.2, 1.4, -0.7, -3.0])
def test_rest_to_rest_time_is_the_trapezoid_formula(d):
    p = Profile(2.0, 0.5, 0.0, 0.5 + d, 0.2, 0.2)
    assert p.duration == pytest.approx(formula(d, 0.2, 0.2), abs=1e-12)
    assert trapezoid_time(d, 0.2, 0.2) == pytest.approx(formula(d, 0.2, 0.2), abs=1e-12)
    assert p.state(p.t_end) == (0.5 + d, 0.0)
    assert p.state(1.0) == (0.5, 0.0)  # before the start


@pytest.mark.parametrize(
    "p0,v0,target",
    [
        (0.0, 0.1, 1.0),  # moving towards, will cruise
        (0.0, 0.2, 0.05),  # too fast to stop in time: brake, come back
        (0.0, -0.15, 0.5),  # moving away: brake first
        (0.3, 0.15, 0.3),  # already on the target but moving
        (0.0, 0.25, 2.0),  # faster than a lowered vmax
    ],
)
def test_profile_from_motion_is_continuous_and_within_limits(p0, v0, target):
    vmax, amax = 0.2, 0.2
    p = Profile(0.0, p0, v0, target, vmax, amax)
    ts, states = sample(p)
    dt = ts[1] - ts[0]
    assert states[0] == pytest.approx((p0, v0))
    assert states[-1] == (target, 0.0)
    for (x1, v1), (x2, v2) in zip(states, states[1:]):
        assert abs(v2 - v1) <= amax * dt + 1e-9  # bounded acceleration
        assert abs(x2 - x1) <= max(abs(v1), abs(v2)) * dt + 1e-9
    assert all(abs(v) <= max(vmax, abs(v0)) + 1e-9 for _, v in states)


def test_brake_stops_at_full_deceleration():
    p = Profile.brake(1.0, 0.2, -0.1, 0.1)
    assert p.duration == pytest.approx(1.0)
    assert p.state(p.t_end) == (pytest.approx(0.2 - 0.05), 0.0)


def test_scaled_clock_runs_faster():
    now = [100.0]
    c = ScaledClock(20, lambda: now[0])
    now[0] = 100.5
    assert c.sim() == pytest.approx(10.0) and c.to_wall(10.0) == pytest.approx(0.5)
    with pytest.raises(ValueError):
        ScaledClock(0)


# -- model ------------------------------------------------------------------------------------


def test_model_reads_the_config(tmp_path):
    assert [j.vmax for j in MODEL.joints] == [0.1, 0.2, 0.2, 0.2]
    assert len(MODEL.home) == 4 and MODEL.vehicle_speed == 0.1
    bad = tmp_path / "bad.cfg"
    text = open(MODEL.path).read().replace("joint3.max = 2.8", "joint3.max = -1")
    bad.write_text(text)
    with pytest.raises(ConfigError, match=r"bad.cfg.*joint3.max"):
        Model.load(str(bad))


# -- fault specs --------------------------------------------------------------------------------


def test_fault_flags_parse_with_defaults():
    assert faults.parse_flag("drop:fraction=0.25") == {
        "type": "drop",
        "fraction": 0.25,
        "direction": "tx",
        "node": "all",
    }
    assert faults.parse_flag("stall:node=left_arm,joint=2") == {
        "type": "stall",
        "node": "left_arm",
        "joint": 2,
        "setpoint": 1,
        "fraction": 0.5,
    }
    assert faults.parse_flag("joint_fault:node=right_arm,joint=4,pick=3")["kind"] == "following"
    assert faults.parse_flag("silent:after_s=2.5,node=vehicle,frames=heartbeat")["after_s"] == 2.5
    assert "for_s" not in faults.parse_flag("silent:after_s=1")
    assert faults.parse_flag("silent:after_s=1,for_s=3")["for_s"] == 3.0
    assert faults.parse_flag("silent:node=left_arm,pick=2") == {
        "type": "silent",
        "node": "left_arm",
        "pick": 2,
        "frames": "all",
    }
    assert faults.parse_flag("joint_fault:node=left_arm,joint=2,home=2") == {
        "type": "joint_fault",
        "node": "left_arm",
        "joint": 2,
        "home": 2,
        "at": 0.5,
        "kind": "following",
    }
    assert faults.parse_flag("estop:after_s=4") == {"type": "estop", "node": "all", "after_s": 4.0}
    assert faults.parse_flag("estop:node=right_arm,pick=3") == {
        "type": "estop",
        "node": "right_arm",
        "pick": 3,
    }


@pytest.mark.parametrize(
    "flag,field",
    [
        ("drop:fraction=0", "fraction"),
        ("drop:fraction=x", "fraction"),
        ("drop:fraction=0.1,node=arm", "node"),
        ("delay:delay_s=-1", "delay_s"),
        ("stall:node=vehicle,joint=1", "node"),
        ("stall:node=left_arm,joint=5", "joint"),
        ("stall:node=left_arm,joint=1.5", "joint"),
        ("joint_fault:node=left_arm,joint=1", "pick"),
        ("joint_fault:node=left_arm,joint=1,pick=1,setpoint=2", "pick"),
        ("silent:node=vehicle", "after_s"),
        ("reject:node=left_arm,setpoint=0", "setpoint"),
        ("reject:node=left_arm,setpoint=1,colour=red", "colour"),
        ("explode:x=1", "type"),
        ("drop:fraction", "fraction"),
        ("joint_fault:node=left_arm,joint=1,pick=1,home=2", "home"),
        ("joint_fault:node=left_arm,joint=1,pick=1,at=0.3", "at"),
        ("silent:after_s=1,for_s=0", "for_s"),
        ("estop:node=vehicle", "after_s"),
        ("silent:node=vehicle,pick=1", "node"),
        ("silent:after_s=1,pick=1", "pick"),
        ("estop:after_s=1,pick=2", "pick"),
        ("estop:node=vehicle,pick=2", "node"),
        ("estop:node=left_arm,pick=0", "pick"),
    ],
)
def test_bad_fault_flags_name_the_field(flag, field):
    with pytest.raises(faults.FaultError, match=field):
        faults.parse_flag(flag)


def test_scenario_file(tmp_path):
    path = tmp_path / "s.json"
    path.write_text(
        json.dumps({"seed": 4, "faults": [{"type": "reject", "node": "left_arm", "setpoint": 2}]})
    )
    assert faults.load_scenario(str(path)) == (
        4,
        [{"type": "reject", "node": "left_arm", "setpoint": 2}],
    )
    path.write_text(
        json.dumps(
            {"faults": [{"type": "drop", "fraction": 1}, {"type": "delay", "delay_s": "soon"}]}
        )
    )
    with pytest.raises(faults.FaultError, match=r"s.json: faults\[1\]: field 'delay_s'"):
        faults.load_scenario(str(path))
    path.write_text("{not json")
    with pytest.raises(faults.FaultError, match=r"s.json:1: not valid JSON"):
        faults.load_scenario(str(path))


# -- node state machines, driven by hand ----------------------------------------------------------


class Log(list):
    def __call__(self, t, event, **fields):
        self.append(dict(t=t, event=event, **fields))

    def of(self, event):
        return [e for e in self if e["event"] == event]


def test_arm_state_machine_and_setpoint():
    log = Log()
    a = ArmNode("left_arm", MODEL, log)
    a.on_setpoint(0.0, [0.3, 0.0, 1.4, 0.0], 1)
    assert a.setpoint_seq == 0 and log.of("setpoint")[-1]["accepted"] is False
    a.on_command(0.0, Command.ENABLE, 1)
    assert a.state == State.IDLE and a.command_seq == 1
    q = [0.35, 0.5, 1.0, -0.5]
    a.on_setpoint(1.0, q, 2)
    assert a.state == State.MOVING and a.setpoint_seq == 2 and not a.target_reached
    t_end = 1.0 + max(
        formula(b - x, j.vmax, j.amax) for x, b, j in zip(MODEL.home, q, MODEL.joints)
    )
    assert a.next_event() == pytest.approx(t_end)
    a.update(t_end - 1e-6)
    assert not a.target_reached
    a.update(t_end + 5.0)
    assert a.target_reached and a.state == State.IDLE
    assert log.of("target_reached")[-1]["t"] == pytest.approx(t_end)
    assert a.positions(t_end + 5) == q
    # out of range: bit 11, not echoed, state kept
    a.on_setpoint(20.0, [0.3, 0.0, 3.0, 0.0], 3)
    assert a.fault_bits == ArmFault.SETPOINT_REJECTED and a.setpoint_seq == 2
    assert a.state == State.IDLE and a.health() == Health.WARNING


def test_arm_estop_brakes_and_latches():
    log = Log()
    a = ArmNode("right_arm", MODEL, log)
    a.on_command(0.0, Command.ENABLE, 1)
    a.on_setpoint(0.0, [0.45, 1.5, 0.2, 3.0], 1)
    a.update(3.0)
    _, v = a.axes[1].state(3.0)
    assert v > 0
    a.estop(3.0, "test")
    assert a.state == State.ESTOP and a.fault_bits == ArmFault.ESTOP
    stop = a.axes[1].t_end
    assert stop == pytest.approx(3.0 + v / MODEL.joints[1].amax)
    a.update(stop + 1)
    assert a.velocities(stop + 1) == [0.0] * 4 and not a.target_reached
    a.on_command(stop + 1, Command.ENABLE, 2)
    assert a.state == State.ESTOP and a.command_seq == 1
    a.on_command(stop + 1, Command.CLEAR_FAULT, 3)  # never releases an e-stop
    assert a.state == State.ESTOP and a.command_seq == 1
    a.on_command(stop + 1, Command.CLEAR_ESTOP, 4)
    assert a.state == State.DISABLED and a.fault_bits == 0 and a.command_seq == 4


def test_clear_estop_leaves_an_older_fault_latched():
    log = Log()
    v = VehicleNode(MODEL, log)
    v.on_command(0.0, Command.ENABLE, 1)
    v.comm_timeout(1.0)
    v.estop(2.0, "test")
    assert v.state == State.ESTOP and v.health() == Health.ESTOP
    v.on_command(3.0, Command.CLEAR_ESTOP, 2)
    assert v.state == State.FAULT and v.fault_bits == 1 << 3  # the comm timeout
    assert v.health() == Health.FAULT
    v.on_command(3.0, Command.CLEAR_FAULT, 3)
    assert v.state == State.DISABLED and v.fault_bits == 0 and v.command_seq == 3


def test_injected_estop_after_the_kth_pick_keeps_the_fruit():
    log = Log()
    a = ArmNode(
        "left_arm",
        MODEL,
        log,
        faults=[faults.parse_flag("estop:node=left_arm,pick=2")],
        cut_s=1.0,
        release_s=0.5,
    )
    a.on_command(0.0, Command.ENABLE, 1)
    t = 0.0
    for k in range(2):
        a.on_ee(t, EeAction.CUT, 2 * k)
        a.update(t + 1.0)
        assert a.state == (State.IDLE if k == 0 else State.ESTOP)
        if k == 0:
            a.on_ee(t + 1.0, EeAction.RELEASE, 2 * k + 1)
            a.update(t + 1.5)
        t += 2.0
    assert a.picks == 2 and a.fruit_held and a.ee_state == EeState.DONE
    assert [e["pick"] for e in log.of("fault_injected")] == [2]
    a.on_command(t, Command.CLEAR_ESTOP, 2)
    assert a.state == State.DISABLED and a.fruit_held


def test_injected_joint_fault_during_the_nth_homing():
    log = Log()
    a = ArmNode(
        "right_arm",
        MODEL,
        log,
        start=[0.05, 0.6, 0.3, -1.0],
        faults=[faults.parse_flag("joint_fault:node=right_arm,joint=1,home=2,at=0.5")],
    )
    a.on_command(0.0, Command.ENABLE, 1)
    a.on_command(0.0, Command.HOME, 2)
    first = a.next_event()
    a.update(first)
    assert a.homed and a.state == State.IDLE  # the first homing is untouched
    a.on_setpoint(first, [0.05, 0.6, 0.3, -1.0], 1)
    a.update(100.0)
    a.on_command(100.0, Command.HOME, 3)
    due = a.next_event()
    assert due == pytest.approx(100.0 + 0.5 * (a.motion["t_end"] - 100.0))
    a.update(due)
    assert a.state == State.FAULT and a.fault_bits == ArmFault.JOINT1_FOLLOWING_ERROR
    assert a.motion is None and [e["joint"] for e in log.of("fault_injected")] == [1]


def test_end_effector_cut_counts_picks():
    log = Log()
    a = ArmNode("left_arm", MODEL, log, cut_s=1.5, release_s=0.5, vehicle_position=lambda t: 0.7)
    a.on_command(0.0, Command.ENABLE, 1)
    a.on_ee(1.0, EeAction.CUT, 5)
    assert a.ee_state == EeState.BUSY and a.next_event() == pytest.approx(2.5)
    a.update(3.0)
    assert a.ee_state == EeState.DONE and a.fruit_held and a.picks == 1
    pick = log.of("pick")[0]
    assert pick["t"] == pytest.approx(2.5) and pick["vehicle_position"] == 0.7
    a.on_ee(3.0, EeAction.CUT, 6)  # still holding one
    assert a.ee_state == EeState.FAILED and a.picks == 1


def test_a_repeated_end_effector_request_is_the_action_under_way():
    log = Log()
    a = ArmNode("left_arm", MODEL, log, cut_s=1.5, release_s=0.5, vehicle_position=lambda t: 0.7)
    a.on_command(0.0, Command.ENABLE, 1)
    a.on_ee(1.0, EeAction.CUT, 5)
    a.on_ee(1.2, EeAction.CUT, 5)  # sent again: its status had not reached the executor
    assert a.ee_state == EeState.BUSY and a.next_event() == pytest.approx(2.5)
    a.update(3.0)
    a.on_ee(3.1, EeAction.CUT, 5)  # again after the cut: still the one cut
    assert a.ee_state == EeState.DONE and a.picks == 1
    a.on_ee(3.2, EeAction.RELEASE, 6)
    a.on_ee(3.3, EeAction.RELEASE, 6)
    a.update(4.0)
    a.on_ee(4.1, EeAction.RELEASE, 6)
    assert [e["fruit"] for e in log.of("release")] == [True]
    assert [e.get("repeat", False) for e in log.of("ee")] == [False, True, True, False, True, True]


def test_a_repeated_command_setpoint_or_move_is_the_request_under_way():
    """A node takes a request with the seq it last accepted (the executor never reuses an
    echoed one) as that request sent again: nothing restarts, nothing is refused."""
    log = Log()
    a = ArmNode("left_arm", MODEL, log, cut_s=1.5, release_s=0.5, vehicle_position=lambda t: 0.7)
    a.on_command(0.0, Command.ENABLE, 1)
    a.on_command(0.1, Command.HOME, 2)
    a.update(50.0)
    assert a.homed and a.state == State.IDLE
    a.on_command(50.0, Command.HOME, 2)  # resent: no second homing
    assert a.state == State.IDLE and a.motion is None
    q = [0.05, 0.6, 0.3, -1.0]
    a.on_setpoint(50.0, q, 3)
    t_end = a.motion["t_end"]
    a.on_setpoint(50.2, list(q), 3)  # resent mid-motion: the same motion, same end
    assert a.state == State.MOVING and a.motion["t_end"] == t_end
    a.update(t_end + 1.0)
    assert a.target_reached
    a.on_setpoint(t_end + 1.0, list(q), 3)  # resent after arriving: still arrived, standing
    assert a.target_reached and a.state == State.IDLE
    a.on_ee(t_end + 1.0, EeAction.CUT, 7)  # so a cut right after it is accepted
    assert a.ee_state == EeState.BUSY
    assert [e.get("repeat", False) for e in log.of("command")] == [False, False, True]
    assert [e.get("repeat", False) for e in log.of("setpoint")] == [False, True, True]
    a.on_setpoint(t_end + 5.0, [0.06, 0.6, 0.3, -1.0], 3)  # same seq, other target: new
    assert not log.of("setpoint")[-1].get("repeat")

    v = VehicleNode(MODEL, log, travel=(0.0, 2.0))
    v.on_command(0.0, Command.ENABLE, 1)
    v.on_move(0.0, 1.0, 0.0, 4)
    v_end = v.motion["t_end"]
    v.on_move(0.3, 1.0, 0.0, 4)
    assert v.motion["t_end"] == v_end and log.of("move")[-1]["repeat"]
    v.update(v_end + 1.0)
    v.on_move(v_end + 1.0, 1.0, 0.0, 4)
    assert v.arrived and v.state == State.IDLE


def test_vehicle_move_and_limits():
    log = Log()
    v = VehicleNode(MODEL, log, travel=(0.0, 2.0))
    v.on_command(0.0, Command.ENABLE, 1)
    v.on_move(0.0, 2.0, 0.0, 1)
    assert v.next_event() == pytest.approx(formula(2.0, MODEL.vehicle_speed, MODEL.vehicle_accel))
    v.update(100.0)
    assert v.arrived and v.positions(100.0) == [2.0]
    v.on_move(100.0, 2.5, 0.0, 2)
    assert (
        v.move_seq == 1 and v.fault_bits == 0b10 and v.arrived
    )  # the refused move changes nothing
