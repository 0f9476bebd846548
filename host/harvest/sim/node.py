"""What the vehicle drive and the arms share: the enable/disable/home/e-stop/clear-fault
state machine over a set of axes on trapezoidal profiles.

Nodes are pure state machines: every call takes the simulated time, nothing reads a clock
or a bus, so the runner decides when things happen and tests can drive a node by hand.
States, commands and health values are the DBC's, read from it at import
(harvest.canbus.enums); the runner checks that the DBC it loads has the same tables.
"""

from ..canbus.enums import Command, Health, State, label
from .profile import Profile


class Node:
    """Base state machine; subclasses say what homing and their fault bits are."""

    ESTOP_FAULT = 0  # fault bit (mask) latched by an e-stop (subclass)
    COMM_FAULT = 0  # fault bit (mask) of a lost executor heartbeat (subclass)

    def __init__(self, name, positions, limits, log):
        self.name = name
        self.limits = limits  # [(vmax, amax)] per axis
        self.axes = [Profile.hold(0.0, p) for p in positions]
        self.state = State.DISABLED
        self.fault_bits = 0
        self.homed = False
        self.command_seq = 0
        self.command_last = None  # the last command accepted, with command_seq
        self.motion = None  # the running commanded motion, or None
        self.changed = True  # status must go out at once
        self._log = log  # log(t, event, **fields)

    # -- helpers ----------------------------------------------------------------------
    def log(self, t, event, **fields):
        self._log(t, event, **fields)

    def set_state(self, t, state, why):
        if state != self.state:
            self.log(
                t, "state", **{"from": State(self.state).name, "to": State(state).name, "why": why}
            )
            self.state = state
            self.changed = True

    def set_bits(self, bits):
        if self.fault_bits | bits != self.fault_bits:
            self.fault_bits |= bits
            self.changed = True

    def clear_bits(self, bits):
        if self.fault_bits & bits:
            self.fault_bits &= ~bits
            self.changed = True

    def positions(self, t):
        return [a.state(t)[0] for a in self.axes]

    def velocities(self, t):
        return [a.state(t)[1] for a in self.axes]

    def stop_axes(self, t):
        """Brake every axis at its full deceleration and drop the commanded motion."""
        for i, (axis, (_, amax)) in enumerate(zip(self.axes, self.limits)):
            p, v = axis.state(t)
            self.axes[i] = Profile.brake(t, p, v, amax) if v else Profile.hold(t, p)
        self.motion = None

    def start_motion(self, t, targets, kind, seq=None):
        """All axes start at once, each on its own profile; returns the motion."""
        durations = []
        for i, (axis, target, (vmax, amax)) in enumerate(zip(self.axes, targets, self.limits)):
            p, v = axis.state(t)
            self.axes[i] = Profile(t, p, v, target, vmax, amax)
            durations.append(self.axes[i].duration)
        self.motion = {
            "kind": kind,
            "seq": seq,
            "t_start": t,
            "targets": list(targets),
            "durations": durations,
            "t_end": t + max(durations),
        }
        return self.motion

    def health(self):
        if self.state == State.ESTOP:
            return Health.ESTOP
        if self.state == State.FAULT:
            return Health.FAULT
        return Health.WARNING if self.fault_bits else Health.OK

    def fault(self, t, bits, why):
        """Stop and enter FAULT (an e-stop stays the stronger state)."""
        self.stop_axes(t)
        self.set_bits(bits)
        if self.state != State.ESTOP:
            self.set_state(t, State.FAULT, why)
        self.on_stopped(t, why)

    # -- hooks for subclasses -----------------------------------------------------------
    def home_targets(self):
        raise NotImplementedError

    def on_stopped(self, t, why):
        """Motion was cut short (fault, e-stop, disable): fail what depended on it."""

    def on_motion_done(self, t, motion):
        """A commanded motion reached its end at simulated time t."""

    # -- inputs ------------------------------------------------------------------------
    def on_command(self, t, command, seq):
        """Handle <Node>Command; the seq is echoed only when the command is accepted."""
        name = label(Command, command)
        before = self.state
        if seq == self.command_seq and command == self.command_last:
            # The executor sends a request again while its echo is on the way (it never
            # reuses a seq a node echoes, DBC): the command already accepted, not a new one.
            self.changed = True
            self.log(t, "command", command=name, seq=seq, accepted=True, reason="", repeat=True)
            return
        accepted, why = True, ""
        if command == Command.NONE:
            pass
        elif command == Command.ENABLE:
            if self.state in (State.FAULT, State.ESTOP):
                accepted, why = (
                    False,
                    (
                        f"latched {State(self.state).name}: "
                        f"{'CLEAR_ESTOP' if self.state == State.ESTOP else 'CLEAR_FAULT'} first"
                    ),
                )
            elif self.state == State.DISABLED:
                self.set_state(t, State.IDLE, "ENABLE")
        elif command == Command.DISABLE:
            if self.motion is not None or any(v for v in self.velocities(t)):
                self.stop_axes(t)
                self.on_stopped(t, "DISABLE")
            if self.state not in (State.FAULT, State.ESTOP):
                self.set_state(t, State.DISABLED, "DISABLE")
        elif command == Command.HOME:
            if self.state in (State.DISABLED, State.FAULT, State.ESTOP):
                accepted, why = False, f"state {State(self.state).name}"
            elif self.state != State.HOMING:
                self.start_motion(t, self.home_targets(), "home")
                self.on_new_motion(t)
                self.on_homing(t)
                self.set_state(t, State.HOMING, "HOME")
                self.log(
                    t, "homing", targets=self.motion["targets"], duration=self.motion["t_end"] - t
                )
        elif command == Command.ESTOP:
            self.estop(t, "ESTOP command")
        elif command == Command.CLEAR_FAULT:
            # an e-stop is the operator's: only CLEAR_ESTOP releases it (DBC)
            if self.state == State.ESTOP:
                accepted, why = False, "latched ESTOP: CLEAR_ESTOP first"
            else:
                self.clear_bits(0xFFFF)
                if self.state == State.FAULT:
                    self.set_state(t, State.DISABLED, "CLEAR_FAULT")
        elif command == Command.CLEAR_ESTOP:
            self.clear_bits(self.ESTOP_FAULT)
            if self.state == State.ESTOP:
                # a fault from before the e-stop is still there: FAULT until CLEAR_FAULT
                self.set_state(t, State.FAULT if self.fault_bits else State.DISABLED, "CLEAR_ESTOP")
        else:
            accepted, why = False, f"unknown command {command}"
        if accepted:
            self.command_last = command
            if seq != self.command_seq:
                self.command_seq = seq
                self.changed = True
        self.log(
            t,
            "command",
            command=name,
            seq=seq,
            accepted=accepted,
            reason=why,
            state_before=State(before).name,
            state_after=State(self.state).name,
        )

    def estop(self, t, why):
        if self.state != State.ESTOP:
            self.stop_axes(t)
            self.set_bits(self.ESTOP_FAULT)
            self.set_state(t, State.ESTOP, why)
            self.on_stopped(t, why)

    def comm_timeout(self, t):
        self.fault(t, self.COMM_FAULT, "executor heartbeat lost")

    def on_new_motion(self, t):
        """A new motion replaced the running one (hook)."""

    def on_homing(self, t):
        """A homing motion started (hook, after on_new_motion)."""

    # -- time --------------------------------------------------------------------------
    def update(self, t):
        """Advance to simulated time t: finish the motion if its profiles have ended."""
        m = self.motion
        if m is not None and t >= m["t_end"] and not m.get("stalled"):
            self.motion = None
            if self.state in (State.HOMING, State.MOVING):
                if m["kind"] == "home":
                    self.homed = True
                    self.changed = True
                    self.log(
                        m["t_end"],
                        "homed",
                        positions=self.positions(m["t_end"]),
                        elapsed=m["t_end"] - m["t_start"],
                    )
                self.set_state(m["t_end"], State.IDLE, f"{m['kind']} done")
            self.on_motion_done(m["t_end"], m)

    def next_event(self):
        """Simulated time of the next thing update() must notice, or None."""
        m = self.motion
        if m is not None and not m.get("stalled"):
            return m["t_end"]
        return None
