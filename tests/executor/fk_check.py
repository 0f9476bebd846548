"""Which fruit each cut in the simulator's record was, by forward kinematics of our own.

A 'pick' event of the record carries the arm's joint positions and the vehicle's position
when the cut was done. This module turns them into the end effector's pose in the row
(x lateral, y along the row, z up, heading relative to the side's inward normal:
docs/FRAMES.md) and names the planned fruit there. The kinematics are written here, apart
from core/src/scara.c and the simulator, so a wrong sign or offset in either side of the
executor cannot hide behind the same mistake in the check: each revolute joint turns the
zero-pose points beyond it about its own zero-pose axis (product of rotations), rather
than summing link headings as core does. Geometry from config/harvest.cfg read with the
project's reader; the tolerance from the DBC's resolution (the executor rounds every joint
setpoint and the vehicle's target to one step of its signal).
"""

import math
import os

import cantools

from harvest.scenario.config import Config

SOURCE = os.environ.get(
    "HV_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
CONFIG = os.path.join(SOURCE, "config", "harvest.cfg")
DBC = os.path.join(SOURCE, "executor", "can", "harvest.dbc")
SIDE_OF_NODE = {"left_arm": "L", "right_arm": "R"}
# The rounding of the plan file's fruit poses (6 decimals) and of the firmware's single
# precision (a float's 2^-24 relative on poses under 1 m) both stay below this, m or rad.
NUMERIC_SLACK = 2e-6


def _rotate(p, centre, a):
    """p turned by a (rad, counter-clockwise) about a vertical axis through centre (x, y)."""
    c, s = math.cos(a), math.sin(a)
    dx, dy = p[0] - centre[0], p[1] - centre[1]
    return (centre[0] + c * dx - s * dy, centre[1] + s * dx + c * dy)


def _wrap(a):
    return math.atan2(math.sin(a), math.cos(a))


class Arm:
    """One side's SCARA as mounted on the vehicle (vehicle frame at the stop)."""

    def __init__(self, cfg, side):
        o = {k: cfg.floats(f"arm.origin.{k}", 3) for k in ("j1", "j2", "j3", "j4", "ee")}
        self.axes = [o["j2"][:2], o["j3"][:2], o["j4"][:2]]  # revolute joints 2..4
        self.ee0 = o["ee"]
        self.side = side
        lateral = 0.5 * cfg.float("row.aisle_width") - cfg.float("mount.offset")
        half = 0.5 * cfg.float("mount.base_spacing")
        theta = math.radians(cfg.float(f"mount.theta_{'left' if side == 'L' else 'right'}_deg"))
        # the right base turned clockwise by theta from +x; the left one half a turn from it
        self.normal = math.pi if side == "L" else 0.0
        self.base = (-lateral if side == "L" else lateral, half if side == "L" else -half)
        self.base_z = cfg.float("mount.base_height")
        self.base_heading = self.normal - theta
        # the longest lever of each revolute joint: its axis to the end effector, no farther
        # than the links beyond it laid end to end
        pts = self.axes + [self.ee0[:2]]
        self.levers = [
            sum(math.dist(pts[k], pts[k + 1]) for k in range(j, len(pts) - 1)) for j in range(3)
        ]

    def pose(self, q, vehicle_y):
        """(x, y along the row, z, heading relative to the side's normal) of the end
        effector at joints q (m, rad, rad, rad) with the vehicle at vehicle_y."""
        ee, wrist = self.ee0[:2], self.axes[2]
        for axis, a in reversed(list(zip(self.axes, q[1:]))):
            ee = _rotate(ee, axis, a)
            wrist = _rotate(wrist, axis, a)  # joint 4's axis moves with joints 2 and 3
        heading_base = math.atan2(ee[1] - wrist[1], ee[0] - wrist[0])
        if math.dist(ee, wrist) < 1e-9:
            raise ValueError("the configured wrist link has no length: no heading")
        world = _rotate(ee, (0.0, 0.0), self.base_heading)
        return (
            self.base[0] + world[0],
            vehicle_y + self.base[1] + world[1],
            self.base_z + self.ee0[2] + q[0],
            _wrap(self.base_heading + heading_base - self.normal),
        )


def dbc_steps():
    """The resolution of what the executor sends: (vehicle target, joint 1..4 setpoints) of
    each arm, from the DBC's scale factors."""
    db = cantools.database.load_file(DBC)
    out = {}
    for side, arm in (("L", "LeftArm"), ("R", "RightArm")):
        m = db.get_message_by_name(f"{arm}Setpoint")
        out[side] = [m.get_signal_by_name(f"Joint{j}Position").scale for j in range(1, 5)]
    vehicle = db.get_message_by_name("VehicleMove").get_signal_by_name("TargetPosition").scale
    return vehicle, out


class Judge:
    """The arms of a config and the tolerance of a cut on the planned fruit."""

    def __init__(self, config=CONFIG):
        cfg = Config.load(config)
        self.arms = {s: Arm(cfg, s) for s in ("L", "R")}
        vehicle_step, joint_steps = dbc_steps()
        self.stop_tol = 0.5 * vehicle_step + NUMERIC_SLACK
        # half a step of each rounded value, times how far it moves the end effector
        self.pos_tol, self.yaw_tol = {}, {}
        for s, arm in self.arms.items():
            h = [0.5 * x for x in joint_steps[s]]
            self.pos_tol[s] = (
                0.5 * vehicle_step
                + h[0]
                + sum(hj * r for hj, r in zip(h[1:], arm.levers))
                + NUMERIC_SLACK
            )
            self.yaw_tol[s] = sum(h[1:]) + NUMERIC_SLACK

    @classmethod
    def for_plan(cls, plan):
        """The judge of a plan's own config (inputs.config: a scenario's config may differ
        from the repository's), relative paths from the source tree."""
        path = plan.get("inputs", {}).get("config") or CONFIG
        return cls(path if os.path.isabs(path) else os.path.join(SOURCE, path))

    def identify(self, plan, picks):
        """Each pick event as (side, fruit id or None, the nearest planned fruit's id, its
        position error m, heading error rad, stop error m): a cut is the planned fruit when
        its pose is that fruit's within tolerance and the vehicle stood at the fruit's stop."""
        fruits = {"L": [], "R": []}
        for st in plan["stops"]:
            for side, key in (("L", "left"), ("R", "right")):
                fruits[side] += [
                    (k["id"], (k["x"], k["y"], k["z"]), k["yaw"], st["y_m"]) for k in st[key]
                ]
        return self._identify(fruits, picks)

    def identify_in_map(self, fruit_map, picks):
        """identify() against a fruit map's fruits (harvest.scenario.fruit_map.Fruit), from
        whichever stop (stop error 0): for a row whose plan is not at hand."""
        fruits = {"L": [], "R": []}
        for f in fruit_map:
            fruits[f.side].append((f.id, (f.x, f.y, f.z), f.yaw, None))
        return self._identify(fruits, picks)

    def _identify(self, fruits, picks):
        out = []
        for e in picks:
            side = SIDE_OF_NODE[e["node"]]
            x, y, z, yaw = self.arms[side].pose(e["positions"], e["vehicle_position"])
            best = None
            for fid, pos, fyaw, stop_y in fruits[side]:
                d = math.dist((x, y, z), pos)
                if best is None or d < best[1]:
                    dstop = 0.0 if stop_y is None else abs(e["vehicle_position"] - stop_y)
                    best = (fid, d, abs(_wrap(yaw - fyaw)), dstop)
            if best is None:
                out.append((side, None, None, math.inf, math.inf, math.inf))
                continue
            fid, d, dyaw, dstop = best
            ok = d <= self.pos_tol[side] and dyaw <= self.yaw_tol[side] and dstop <= self.stop_tol
            out.append((side, fid if ok else None, fid, d, dyaw, dstop))
        return out

    def cut_fruits(self, plan, picks, found=None):
        """(side, id) of each cut in record order; AssertionError naming every stray (a cut
        that is no planned fruit of its arm at its stop) with the nearest fruit. `found`:
        identify()'s or identify_in_map()'s answer, when already at hand."""
        found = self.identify(plan, picks) if found is None else found
        strays = [
            f"{side} cut {i}: nearest fruit {near} at {d * 1000:.3f} mm (<= "
            f"{self.pos_tol[side] * 1000:.3f}), heading off {dyaw:.2e} rad (<= "
            f"{self.yaw_tol[side]:.2e}), stop off {dstop:.2e} m (<= {self.stop_tol:.2e})"
            for i, (side, fid, near, d, dyaw, dstop) in enumerate(found)
            if fid is None
        ]
        assert not strays, "cuts at no planned fruit:\n  " + "\n  ".join(strays)
        return [(side, fid) for side, fid, *_ in found]


def plan_order(plan):
    """Fruit ids of each side in the order the plan picks them."""
    out = {"L": [], "R": []}
    for st in plan["stops"]:
        out["L"] += [k["id"] for k in st["left"]]
        out["R"] += [k["id"] for k in st["right"]]
    return out


def assert_cuts_on_plan(plan, picks, picked=None, judge=None):
    """Every cut in `picks` (the record's 'pick' events, in order) is a planned fruit of its
    arm at its stop, none is cut twice, each arm cuts in the plan's order; `picked`, when
    given (a set of (side, id)), is exactly the set of fruits cut. Returns the cuts."""
    cuts = (judge or Judge.for_plan(plan)).cut_fruits(plan, picks)
    twice = sorted({c for c in cuts if cuts.count(c) > 1})
    assert not twice, f"cut more than once: {twice}"
    order = plan_order(plan)
    for side in ("L", "R"):
        mine = [fid for s, fid in cuts if s == side]
        rank = [order[side].index(fid) for fid in mine]
        assert rank == sorted(rank), f"{side} arm out of the plan's order: {mine}"
    if picked is not None:
        assert set(cuts) == set(picked), (
            f"cut but not picked: {sorted(set(cuts) - set(picked))}; "
            f"picked but not cut: {sorted(set(picked) - set(cuts))}"
        )
    return cuts
