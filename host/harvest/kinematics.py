"""Forward kinematics of the two SCARA arms as mounted on the vehicle (docs/FRAMES.md), from
the config (arm.origin.*, mount.*, row.aisle_width of config/harvest.cfg, read with
harvest.scenario.config): where each joint and the end effector are for joint positions
q = (joint 1 m, joints 2..4 rad), in the vehicle frame (x lateral, y along the row from the
vehicle's reference point, z up; m).

Joint 1 lifts everything beyond it; joints 2..4 turn about vertical axes through their
zero-pose origins, so each link keeps its zero-pose vector turned by the sum of the joint
angles before it (the planar chain of a SCARA)."""

import math

SIDES = ("left", "right")
POINTS = ("base", "j1", "carriage", "j2", "j3", "j4", "ee")  # what Arm.points() returns


class Arm:
    """One side's arm: its base on the vehicle and its links at zero joints."""

    def __init__(self, cfg, side):
        if side not in SIDES:
            raise ValueError(f"side {side!r}: expected one of {SIDES}")
        self.side = side
        self.origins = {k: cfg.floats(f"arm.origin.{k}", 3) for k in ("j1", "j2", "j3", "j4", "ee")}
        lateral = 0.5 * cfg.float("row.aisle_width") - cfg.float("mount.offset")
        half = 0.5 * cfg.float("mount.base_spacing")
        theta = math.radians(cfg.float(f"mount.theta_{side}_deg"))
        # the right base turned clockwise by theta from the right row's normal (+x); the left
        # arm is the right one turned half a turn about z
        if side == "left":
            self.base = (-lateral, half, cfg.float("mount.base_height"))
            self.heading = math.pi - theta
        else:
            self.base = (lateral, -half, cfg.float("mount.base_height"))
            self.heading = -theta

    def _to_vehicle(self, p):
        c, s = math.cos(self.heading), math.sin(self.heading)
        return (
            self.base[0] + c * p[0] - s * p[1],
            self.base[1] + s * p[0] + c * p[1],
            self.base[2] + p[2],
        )

    def points(self, q):
        """[(x, y, z)] of POINTS at joints q, vehicle frame: the base, joint 1's foot and its
        carriage (lifted by q[0]), the axes of joints 2..4, the end effector."""
        if len(q) != 4:
            raise ValueError(f"{self.side} arm: {len(q)} joint positions, expected 4")
        o = self.origins
        lift = q[0]
        chain = [(o["j2"][0], o["j2"][1], o["j2"][2] + lift)]
        angle = 0.0
        for prev, nxt, turn in (("j2", "j3", q[1]), ("j3", "j4", q[2]), ("j4", "ee", q[3])):
            angle += turn
            dx, dy = o[nxt][0] - o[prev][0], o[nxt][1] - o[prev][1]
            c, s = math.cos(angle), math.sin(angle)
            x, y, _ = chain[-1]
            chain.append((x + c * dx - s * dy, y + s * dx + c * dy, o[nxt][2] + lift))
        foot = tuple(o["j1"])
        carriage = (foot[0], foot[1], foot[2] + lift)
        return [self._to_vehicle(p) for p in [(0.0, 0.0, 0.0), foot, carriage, *chain]]


def arms(cfg):
    """{side: Arm} of both arms of a config."""
    return {side: Arm(cfg, side) for side in SIDES}
