"""What the vehicle drive and the arms share: the enable/disable/home/e-stop/clear-fault
state machine over a set of axes on trapezoidal profiles.

Nodes are pure state machines: every call takes the simulated time, nothing reads a clock
or a bus, so the runner decides when things happen and tests can drive a node by hand.
The numbers of states, commands and health values are the DBC's; the runner checks them
against the loaded DBC at start-up (`check_against`).
"""
from .profile import Profile

# State (VAL_ of <Node>Status.State)
DISABLED, IDLE, HOMING, MOVING, FAULT, ESTOP = range(6)
STATE_NAMES = ("DISABLED", "IDLE", "HOMING", "MOVING", "FAULT", "ESTOP")
# Command (VAL_ of <Node>Command.Command)
CMD_NONE, CMD_ENABLE, CMD_DISABLE, CMD_HOME, CMD_ESTOP, CMD_CLEAR_FAULT, CMD_CLEAR_ESTOP = range(7)
COMMAND_NAMES = ("NONE", "ENABLE", "DISABLE", "HOME", "ESTOP", "CLEAR_FAULT", "CLEAR_ESTOP")
# Health (VAL_ of <Node>Heartbeat.Health)
HEALTH_OK, HEALTH_WARNING, HEALTH_FAULT, HEALTH_ESTOP = range(4)
HEALTH_NAMES = ("OK", "WARNING", "FAULT", "ESTOP")


def check_against(proto, prefix):
    """Raise ValueError when the DBC's enum values differ from the ones this module uses."""
    for msg, sig, names in ((f"{prefix}Status", "State", STATE_NAMES),
                            (f"{prefix}Command", "Command", COMMAND_NAMES),
                            (f"{prefix}Heartbeat", "Health", HEALTH_NAMES)):
        want = dict(enumerate(names))
        got = proto.choices(msg, sig)
        if got != want:
            raise ValueError(f"{proto.path}: {msg}.{sig} values {got} differ from the "
                             f"simulator's {want}")


class Node:
    """Base state machine; subclasses say what homing and their fault bits are."""

    ESTOP_BIT = 0     # fault bit latched by an e-stop (subclass)
    COMM_BIT = 0      # fault bit of a lost executor heartbeat (subclass)

    def __init__(self, name, positions, limits, log):
        self.name = name
        self.limits = limits                      # [(vmax, amax)] per axis
        self.axes = [Profile.hold(0.0, p) for p in positions]
        self.state = DISABLED
        self.fault_bits = 0
        self.homed = False
        self.command_seq = 0
        self.motion = None                        # the running commanded motion, or None
        self.changed = True                       # status must go out at once
        self._log = log                           # log(t, event, **fields)

    # -- helpers ----------------------------------------------------------------------
    def log(self, t, event, **fields):
        self._log(t, event, **fields)

    def set_state(self, t, state, why):
        if state != self.state:
            self.log(t, "state", **{"from": STATE_NAMES[self.state], "to": STATE_NAMES[state],
                                    "why": why})
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
        self.motion = {"kind": kind, "seq": seq, "t_start": t, "targets": list(targets),
                       "durations": durations, "t_end": t + max(durations)}
        return self.motion

    def health(self):
        if self.state == ESTOP:
            return HEALTH_ESTOP
        if self.state == FAULT:
            return HEALTH_FAULT
        return HEALTH_WARNING if self.fault_bits else HEALTH_OK

    def fault(self, t, bits, why):
        """Stop and enter FAULT (an e-stop stays the stronger state)."""
        self.stop_axes(t)
        self.set_bits(bits)
        if self.state != ESTOP:
            self.set_state(t, FAULT, why)
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
        name = COMMAND_NAMES[command] if 0 <= command < len(COMMAND_NAMES) else str(command)
        before = self.state
        accepted, why = True, ""
        if command == CMD_NONE:
            pass
        elif command == CMD_ENABLE:
            if self.state in (FAULT, ESTOP):
                accepted, why = False, (f"latched {STATE_NAMES[self.state]}: "
                                        f"{'CLEAR_ESTOP' if self.state == ESTOP else 'CLEAR_FAULT'} first")
            elif self.state == DISABLED:
                self.set_state(t, IDLE, "ENABLE")
        elif command == CMD_DISABLE:
            if self.motion is not None or any(v for v in self.velocities(t)):
                self.stop_axes(t)
                self.on_stopped(t, "DISABLE")
            if self.state not in (FAULT, ESTOP):
                self.set_state(t, DISABLED, "DISABLE")
        elif command == CMD_HOME:
            if self.state in (DISABLED, FAULT, ESTOP):
                accepted, why = False, f"state {STATE_NAMES[self.state]}"
            elif self.state != HOMING:
                self.start_motion(t, self.home_targets(), "home")
                self.on_new_motion(t)
                self.on_homing(t)
                self.set_state(t, HOMING, "HOME")
                self.log(t, "homing", targets=self.motion["targets"],
                         duration=self.motion["t_end"] - t)
        elif command == CMD_ESTOP:
            self.estop(t, "ESTOP command")
        elif command == CMD_CLEAR_FAULT:
            # an e-stop is the operator's: only CLEAR_ESTOP releases it (DBC)
            if self.state == ESTOP:
                accepted, why = False, "latched ESTOP: CLEAR_ESTOP first"
            else:
                self.clear_bits(0xFFFF)
                if self.state == FAULT:
                    self.set_state(t, DISABLED, "CLEAR_FAULT")
        elif command == CMD_CLEAR_ESTOP:
            self.clear_bits(1 << self.ESTOP_BIT)
            if self.state == ESTOP:
                # a fault from before the e-stop is still there: FAULT until CLEAR_FAULT
                self.set_state(t, FAULT if self.fault_bits else DISABLED, "CLEAR_ESTOP")
        else:
            accepted, why = False, f"unknown command {command}"
        if accepted and seq != self.command_seq:
            self.command_seq = seq
            self.changed = True
        self.log(t, "command", command=name, seq=seq, accepted=accepted, reason=why,
                 state_before=STATE_NAMES[before], state_after=STATE_NAMES[self.state])

    def estop(self, t, why):
        if self.state != ESTOP:
            self.stop_axes(t)
            self.set_bits(1 << self.ESTOP_BIT)
            self.set_state(t, ESTOP, why)
            self.on_stopped(t, why)

    def comm_timeout(self, t):
        self.fault(t, 1 << self.COMM_BIT, "executor heartbeat lost")

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
            if self.state in (HOMING, MOVING):
                if m["kind"] == "home":
                    self.homed = True
                    self.changed = True
                    self.log(m["t_end"], "homed", positions=self.positions(m["t_end"]),
                             elapsed=m["t_end"] - m["t_start"])
                self.set_state(m["t_end"], IDLE, f"{m['kind']} done")
            self.on_motion_done(m["t_end"], m)

    def next_event(self):
        """Simulated time of the next thing update() must notice, or None."""
        m = self.motion
        if m is not None and not m.get("stalled"):
            return m["t_end"]
        return None
