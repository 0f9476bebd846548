"""The vehicle drive (DBC node Vehicle): moves along the row to the commanded position at
the config's speed and acceleration, reports its position and "arrived"."""

from ..canbus.enums import State, VehicleFault
from .node import Node

POSITION_LIMIT = int(VehicleFault.POSITION_LIMIT)  # FaultBits of VehicleStatus

# "Within 1 mm of the target" (DBC): the profile ends exactly on it.
ARRIVED_TOL_M = 1e-3


class VehicleNode(Node):
    ESTOP_FAULT = int(VehicleFault.ESTOP)
    COMM_FAULT = int(VehicleFault.COMM_TIMEOUT)

    def __init__(self, model, log, start_m=0.0, travel=None, home_m=0.0):
        super().__init__("vehicle", [start_m], [(model.vehicle_speed, model.vehicle_accel)], log)
        self.model = model
        self.travel = travel  # (min, max) position limits in m, or None
        self.home_m = home_m
        self.arrived = False
        self.move_seq = 0
        self.move_request = None  # (target, max speed) of the move accepted with move_seq

    def home_targets(self):
        return [self.home_m]

    def on_new_motion(self, t):
        if self.arrived:
            self.arrived = False
            self.changed = True

    def on_motion_done(self, t, motion):
        if motion["kind"] == "move":
            self.arrived = True
            self.changed = True
            self.log(
                t,
                "arrived",
                seq=motion["seq"],
                position=self.positions(t)[0],
                elapsed=t - motion["t_start"],
                planned=motion["durations"][0],
            )

    def on_move(self, t, target_m, max_speed, seq):
        """Handle VehicleMove: drive to target_m at max_speed (0: the configured speed)."""
        if (
            seq == self.move_seq
            and (target_m, max_speed) == self.move_request
            and self.state in (State.IDLE, State.MOVING)
        ):
            # sent again before its echo came back: the drive under way (or done) stays
            self.changed = True
            self.log(
                t,
                "move",
                seq=seq,
                target=target_m,
                max_speed=max_speed,
                accepted=True,
                reason="",
                repeat=True,
            )
            return
        reason, bits = "", 0
        if self.state not in (State.IDLE, State.MOVING):
            reason = f"state {State(self.state).name}"
        elif self.travel and not self.travel[0] <= target_m <= self.travel[1]:
            reason = f"target {target_m:.4f} m outside travel [{self.travel[0]}, {self.travel[1]}]"
            bits = POSITION_LIMIT
        if reason:
            self.set_bits(bits)
            self.log(
                t,
                "move",
                seq=seq,
                target=target_m,
                max_speed=max_speed,
                accepted=False,
                reason=reason,
            )
            return
        self.clear_bits(POSITION_LIMIT)
        self.move_request = (target_m, max_speed)
        # the configured speed is the drive's limit; a move may only ask for less
        speed = (
            self.model.vehicle_speed if max_speed <= 0 else min(max_speed, self.model.vehicle_speed)
        )
        self.limits = [(speed, self.model.vehicle_accel)]
        motion = self.start_motion(t, [target_m], "move", seq)
        self.limits = [(self.model.vehicle_speed, self.model.vehicle_accel)]
        self.on_new_motion(t)
        if seq != self.move_seq:
            self.move_seq = seq
            self.changed = True
        self.set_state(t, State.MOVING, "move")
        self.log(
            t,
            "move",
            seq=seq,
            target=target_m,
            max_speed=speed,
            accepted=True,
            reason="",
            start=self.axes[0].p0,
            duration=motion["t_end"] - t,
        )

    def status_signals(self, t):
        p, v = self.axes[0].state(t)
        return {
            "Position": p,
            "Velocity": v,
            "State": self.state,
            "Arrived": int(self.arrived),
            "Homed": int(self.homed),
            "FaultBits": self.fault_bits,
            "MoveSeq": self.move_seq,
            "CommandSeq": self.command_seq,
        }
