"""One SCARA joint controller with its end effector (DBC nodes LeftArm / RightArm).

Setpoints move all four joints at once, each on its own trapezoid at the config's limits;
a setpoint outside a joint's range is refused with fault bit SETPOINT_REJECTED and not
echoed. The end effector cuts or releases in the config's times (or others given), only
while the arm stands.
Injected faults (stall, joint fault, reject) are applied here, counted per arm.
"""

from ..canbus.enums import ArmFault, EeAction, EeState, State, label, member
from .node import Node
from .profile import Profile

REJECTED = int(ArmFault.SETPOINT_REJECTED)  # FaultBits of <Arm>Status (the DBC's ArmFault)

# "Within tolerance of the setpoint": the DBC's resolution of a joint position.
REACHED_TOL = 1e-4


class ArmNode(Node):
    ESTOP_FAULT = int(ArmFault.ESTOP)
    COMM_FAULT = int(ArmFault.COMM_TIMEOUT)

    def __init__(
        self,
        name,
        model,
        log,
        faults=(),
        start=None,
        cut_s=None,
        release_s=None,
        vehicle_position=lambda t: 0.0,
    ):
        start = list(model.home if start is None else start)
        super().__init__(name, start, [(j.vmax, j.amax) for j in model.joints], log)
        self.model = model
        # the end effector's times: the config's unless given
        self.cut_s = model.cut_s if cut_s is None else cut_s
        self.release_s = model.release_s if release_s is None else release_s
        self.vehicle_position = vehicle_position
        self.faults = [f for f in faults if f.get("node") == name]
        self.target_reached = False
        self.setpoint_seq = 0
        self.setpoint_target = None  # joint targets of the setpoint accepted with setpoint_seq
        self.setpoints_received = 0
        self.setpoints_accepted = 0
        self.cuts_received = 0
        self.homings = 0
        self.picks = 0
        self.pick_times = []  # simulated time of each pick
        self.ee_state, self.ee_action, self.ee_seq = EeState.IDLE, EeAction.NONE, 0
        self.ee_done_t = None
        self.fruit_held = False
        self.ee_changed = True
        self.pending_fault = None  # (t, joint index, bits, why) of a scheduled joint fault

    # -- Node hooks ----------------------------------------------------------------------
    def home_targets(self):
        return list(self.model.home)

    def on_new_motion(self, t):
        if self.target_reached:
            self.target_reached = False
            self.changed = True
        self.pending_fault = None
        self._fail_ee(t, "arm started moving")

    def on_homing(self, t):
        self.homings += 1
        jf = self._fault_at("joint_fault", "home", self.homings)
        if jf is not None:
            self.pending_fault = (t + jf["at"] * (self.motion["t_end"] - t), jf)

    def on_stopped(self, t, why):
        self.pending_fault = None
        self._fail_ee(t, why)

    def on_motion_done(self, t, motion):
        if motion["kind"] == "setpoint":
            self.target_reached = True
            self.changed = True
            self.log(
                t,
                "target_reached",
                seq=motion["seq"],
                positions=self.positions(t),
                elapsed=t - motion["t_start"],
                planned=max(motion["durations"]),
            )

    # -- inputs ----------------------------------------------------------------------------
    def on_setpoint(self, t, q, seq):
        """Handle <Arm>Setpoint with joint positions q (m, rad) and its 5-bit sequence."""
        if (
            seq == self.setpoint_seq
            and list(q) == self.setpoint_target
            and self.state in (State.IDLE, State.MOVING)
        ):
            # sent again before its echo came back: the motion under way (or done) stays
            self.changed = True
            self.log(t, "setpoint", seq=seq, positions=list(q), accepted=True, repeat=True)
            return
        self.setpoints_received += 1
        reason, bits = "", 0
        injected = self._fault_at("reject", "setpoint", self.setpoints_received)
        if self.state not in (State.IDLE, State.MOVING):
            reason = f"state {State(self.state).name}"
        elif injected is not None:
            reason, bits = (
                f"injected reject of setpoint #{self.setpoints_received}",
                REJECTED,
            )
        else:
            for j, (qj, lim) in enumerate(zip(q, self.model.joints)):
                if not lim.contains(qj):
                    reason = f"joint {j + 1} = {qj:.4f} outside [{lim.min}, {lim.max}]"
                    bits = REJECTED
                    break
        if reason:
            self.set_bits(bits)
            self.log(
                t,
                "setpoint",
                seq=seq,
                positions=list(q),
                accepted=False,
                reason=reason,
                number=self.setpoints_received,
            )
            return
        self.setpoints_accepted += 1
        self.setpoint_target = list(q)
        self.clear_bits(REJECTED)
        if seq != self.setpoint_seq:
            self.setpoint_seq = seq
            self.changed = True
        motion = self.start_motion(t, q, "setpoint", seq)
        self.on_new_motion(t)
        fields = {}
        stall = self._fault_at("stall", "setpoint", self.setpoints_accepted)
        if stall is not None:
            self._stall(t, stall, motion)
            fields["stall"] = {"joint": stall["joint"], "fraction": stall["fraction"]}
        jf = self._fault_at("joint_fault", "setpoint", self.setpoints_accepted)
        if jf is not None:
            at = t + jf["at"] * (motion["t_end"] - t)
            self.pending_fault = (at, jf)
            fields["joint_fault_at"] = at
        self.set_state(t, State.MOVING, "setpoint")
        self.log(
            t,
            "setpoint",
            seq=seq,
            positions=list(q),
            accepted=True,
            reason="",
            number=self.setpoints_received,
            durations=motion["durations"],
            duration=motion["t_end"] - t,
            **fields,
        )

    def _stall(self, t, stall, motion):
        """The joint stops part of the way: its profile ends short and the motion never ends."""
        j = stall["joint"] - 1
        p, v = self.axes[j].state(t)
        stop = p + stall["fraction"] * (motion["targets"][j] - p)
        vmax, amax = self.limits[j]
        self.axes[j] = Profile(t, p, v, stop, vmax, amax)
        motion["stalled"] = True

    def on_ee(self, t, action, seq):
        """Handle <Arm>EeCommand: CUT at the fruit, RELEASE at home."""
        known = member(EeAction, action)
        name = label(EeAction, action)
        if (
            seq == self.ee_seq
            and known is not None
            and known == self.ee_action
            and known != EeAction.NONE
            and self.ee_state in (EeState.BUSY, EeState.DONE)
        ):
            # The executor sends a request again while it has not yet seen its status
            # (a late frame on a loaded bus): it is the action already under way or done,
            # not a new one; the status frame tells the sender where it stands.
            self.ee_changed = True
            self.log(t, "ee", action=name, seq=seq, accepted=True, reason="", repeat=True)
            return
        self.ee_seq, self.ee_action = seq, EeAction.NONE if known is None else known
        self.ee_changed = True
        if action == EeAction.CUT:
            self.cuts_received += 1
            jf = self._fault_at("joint_fault", "pick", self.cuts_received)
            if jf is not None and self.state not in (State.FAULT, State.ESTOP):
                self.log(
                    t,
                    "ee",
                    action=name,
                    seq=seq,
                    accepted=False,
                    reason=f"injected joint fault at pick #{self.cuts_received}",
                )
                self._joint_fault(t, jf)
                self._set_ee(t, EeState.FAILED)
                return
        reason = ""
        if known is None:
            reason = f"unknown action {action}"
        elif action == EeAction.NONE:
            self.ee_done_t = None
            self._set_ee(t, EeState.IDLE)
        elif self.state != State.IDLE:
            reason = f"arm {State(self.state).name}, not standing"
        elif self.ee_state == EeState.BUSY:
            reason = "end effector busy"
        elif action == EeAction.CUT and self.fruit_held:
            reason = "already holding a fruit"
        if reason:
            self._set_ee(
                t, EeState.FAULT if self.state in (State.FAULT, State.ESTOP) else EeState.FAILED
            )
            self.log(t, "ee", action=name, seq=seq, accepted=False, reason=reason)
            return
        if action != EeAction.NONE:
            self.ee_done_t = t + (self.cut_s if action == EeAction.CUT else self.release_s)
            self._set_ee(t, EeState.BUSY)
        self.log(t, "ee", action=name, seq=seq, accepted=True, reason="", done_at=self.ee_done_t)

    # -- faults and the end effector ----------------------------------------------------------
    def _fault_at(self, kind, trigger, count):
        """This arm's injected fault of `kind` whose `trigger` field is `count`, or None."""
        return next((f for f in self.faults if f["type"] == kind and f.get(trigger) == count), None)

    def _joint_fault(self, t, jf):
        what = "FOLLOWING_ERROR" if jf["kind"] == "following" else "LIMIT"
        bits = int(ArmFault[f"JOINT{jf['joint']}_{what}"])
        self.log(
            t,
            "fault_injected",
            fault="joint_fault",
            joint=jf["joint"],
            kind=jf["kind"],
            bits=bits,
        )
        self.fault(t, bits, f"injected {jf['kind']} fault on joint {jf['joint']}")

    def _set_ee(self, t, state):
        if state != self.ee_state:
            self.ee_state = state
            self.ee_changed = True

    def _fail_ee(self, t, why):
        if self.ee_state == EeState.BUSY:
            self.ee_done_t = None
            self._set_ee(t, EeState.FAILED)
            self.log(
                t,
                "ee_done",
                action=EeAction(self.ee_action).name,
                seq=self.ee_seq,
                result="FAILED",
                reason=why,
            )

    # -- time ------------------------------------------------------------------------------
    def update(self, t):
        if self.pending_fault is not None and t >= self.pending_fault[0]:
            at, jf = self.pending_fault
            self.pending_fault = None
            self._joint_fault(at, jf)
        super().update(t)
        if self.ee_done_t is not None and t >= self.ee_done_t:
            done, self.ee_done_t = self.ee_done_t, None
            q = self.positions(done)
            if self.ee_action == EeAction.CUT:
                self.fruit_held = True
                self.picks += 1
                self.pick_times.append(done)
                self.log(
                    done,
                    "pick",
                    pick=self.picks,
                    seq=self.ee_seq,
                    positions=q,
                    vehicle_position=self.vehicle_position(done),
                )
            else:
                self.log(done, "release", seq=self.ee_seq, fruit=self.fruit_held, positions=q)
                self.fruit_held = False
            self._set_ee(done, EeState.DONE)
            self.log(
                done,
                "ee_done",
                action=EeAction(self.ee_action).name,
                seq=self.ee_seq,
                result="DONE",
            )
            if self.ee_action == EeAction.CUT and self._fault_at("estop", "pick", self.picks):
                # once the cut is done: the arm stops with the fruit held
                self.log(done, "fault_injected", fault="estop", pick=self.picks)
                self.estop(done, f"injected e-stop after pick #{self.picks}")

    def next_event(self):
        times = [
            x
            for x in (
                super().next_event(),
                self.ee_done_t,
                self.pending_fault[0] if self.pending_fault else None,
            )
            if x is not None
        ]
        return min(times) if times else None

    # -- frames ----------------------------------------------------------------------------
    def status_signals(self):
        return {
            "State": self.state,
            "TargetReached": int(self.target_reached),
            "Homed": int(self.homed),
            "SetpointSeq": self.setpoint_seq,
            "CommandSeq": self.command_seq,
            "FaultBits": self.fault_bits,
        }

    def joint_state_signals(self, t, counter):
        q = self.positions(t)
        return {
            "Joint1Position": q[0],
            "Joint2Position": q[1],
            "Joint3Position": q[2],
            "Joint4Position": q[3],
            "Counter": counter,
        }

    def joint_velocity_signals(self, t):
        v = self.velocities(t)
        return {f"Joint{j + 1}Velocity": v[j] for j in range(4)}

    def ee_status_signals(self):
        return {
            "State": self.ee_state,
            "Action": self.ee_action,
            "EeSeq": self.ee_seq,
            "FruitHeld": int(self.fruit_held),
        }
