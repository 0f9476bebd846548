"""The live view's 3D scene and log lines as Foxglove messages, drawn from a LiveState.

Frames: "row" is the row's frame of docs/FRAMES.md (x lateral, positive towards the right
row; y along the row from its start; z up; m), "vehicle" the same axes moved along y to the
vehicle's position (the FrameTransforms of transforms()). The plan (canopies, stops, fruits
coloured by outcome) is drawn in the row frame; the vehicle and both arms, their links from
the reported joints by forward kinematics (harvest.kinematics), in the vehicle frame.
"""

from foxglove.messages import (
    Color,
    CubePrimitive,
    CylinderPrimitive,
    FrameTransform,
    FrameTransforms,
    LinePrimitive,
    LinePrimitiveLineType,
    Log,
    LogLevel,
    Point3,
    Pose,
    Quaternion,
    SceneEntity,
    SceneUpdate,
    SpherePrimitive,
    TextPrimitive,
    Vector3,
)

from .. import kinematics
from ..scenario.config import Row
from . import state as st

ROW_FRAME, VEHICLE_FRAME = "row", "vehicle"
FRUIT_COLORS = {
    "seen": "#fec44f",  # in the camera's view, not planned yet (online)
    "planned": "#9ecae1",
    "picked": "#31a354",
    "failed": "#de2d26",
    "skipped": "#969696",
}
ARM_COLORS = {"left": "#0072b2", "right": "#d55e00"}
FAULT_COLOR = "#de2d26"
FRUIT_DIAMETER = 0.035  # m, about a strawberry's
LOG_LEVELS = {
    st.LOG_INFO: LogLevel.Info,
    st.LOG_WARNING: LogLevel.Warning,
    st.LOG_ERROR: LogLevel.Error,
}


class Geometry:
    """What the config fixes: both arms on the vehicle and the row's canopies."""

    def __init__(self, cfg):
        self.arms = kinematics.arms(cfg)
        self.row = Row(cfg)


def _color(hex_rgb, alpha=1.0):
    r, g, b = (int(hex_rgb[i : i + 2], 16) / 255.0 for i in (1, 3, 5))
    return Color(r=r, g=g, b=b, a=alpha)


def _pose(x=0.0, y=0.0, z=0.0):
    return Pose(position=Vector3(x=x, y=y, z=z), orientation=Quaternion(w=1.0))


def _size(x, y, z):
    return Vector3(x=x, y=y, z=z)


def _text(text, at, size=12.0, color="#202020"):
    return TextPrimitive(
        pose=_pose(*at),
        billboard=True,
        font_size=size,
        scale_invariant=True,
        color=_color(color),
        text=text,
    )


def extent(state, geo):
    """(start, end) along the row to draw: the course when the online planner gave it, else
    the config's row stretched over every known fruit and stop."""
    if state.course is not None:
        return state.course
    ys = [f.pos[1] for f in state.fruits.values() if f.pos] + list(state.stops)
    return min([0.0, *ys]), max([geo.row.length_m, *ys])


def plan_update(state, geo, ts):
    """SceneUpdate of the row frame: the canopies, the stops (the current one orange, those
    passed darker) and each fruit coloured by how far it got."""
    row = geo.row
    y0, y1 = extent(state, geo)
    x_mid = row.x_near_m + row.canopy_depth_m / 2
    z_mid = row.canopy_z_min_m + row.canopy_height_m / 2
    canopies = [
        CubePrimitive(
            pose=_pose(sign * x_mid, (y0 + y1) / 2, z_mid),
            size=_size(row.canopy_depth_m, y1 - y0, row.canopy_height_m),
            color=_color("#74c476", 0.15),
        )
        for sign in (-1.0, 1.0)
    ]
    centre = LinePrimitive(
        type=LinePrimitiveLineType.LineStrip,
        pose=_pose(),
        thickness=0.01,
        points=[Point3(x=0.0, y=y0, z=0.0), Point3(x=0.0, y=y1, z=0.0)],
        color=_color("#bdbdbd"),
    )
    at = state.exec_state.stop if state.exec_state else -1
    stops = []
    for k, y in enumerate(state.stops):
        colour = "#e6550d" if k == at else "#636363" if k < at else "#bdbdbd"
        d = 0.1 if k == at else 0.06
        stops.append(
            CylinderPrimitive(
                pose=_pose(0.0, y, 0.005),
                size=_size(d, d, 0.01),
                bottom_scale=1.0,
                top_scale=1.0,
                color=_color(colour),
            )
        )
    fruits = [
        SpherePrimitive(
            pose=_pose(*f.pos),
            size=_size(FRUIT_DIAMETER, FRUIT_DIAMETER, FRUIT_DIAMETER),
            color=_color(FRUIT_COLORS.get(f.status, "#fd8d3c")),
        )
        for f in state.fruits.values()
        if f.pos is not None
    ]
    ents = [
        SceneEntity(timestamp=ts, frame_id=ROW_FRAME, id="row", cubes=canopies, lines=[centre]),
        SceneEntity(timestamp=ts, frame_id=ROW_FRAME, id="stops", cylinders=stops),
        SceneEntity(timestamp=ts, frame_id=ROW_FRAME, id="fruits", spheres=fruits),
    ]
    return SceneUpdate(entities=ents)


def _arm_entity(state, geo, side, k, ts):
    arm = geo.arms[side]
    js = state.arms[k]
    label_at = (arm.base[0], arm.base[1], arm.base[2] + 0.75)
    phase = state.exec_state.arm_phase[k] if state.exec_state else "?"
    label = f"{side}: {phase}"
    if state.working_on[k]:
        label += f" {state.working_on[k]}"
    if js is None:
        return SceneEntity(
            timestamp=ts,
            frame_id=VEHICLE_FRAME,
            id=f"arm/{side}",
            frame_locked=True,
            texts=[_text(label + " (no joint state yet)", label_at)],
        )
    faulted = js.fault_bits != 0
    colour = FAULT_COLOR if faulted else ARM_COLORS[side]
    pts = arm.points(list(js.q))
    if faulted:
        label += f" [{state.state_names(js.state)}]"
    link = LinePrimitive(
        type=LinePrimitiveLineType.LineStrip,
        pose=_pose(),
        thickness=0.02,
        points=[Point3(x=p[0], y=p[1], z=p[2]) for p in pts],
        color=_color(colour),
    )
    joints = [
        SpherePrimitive(pose=_pose(*p), size=_size(d, d, d), color=_color("#404040"))
        for p, d in zip(pts, [0.05] + [0.03] * (len(pts) - 2))
    ]
    ee = SpherePrimitive(pose=_pose(*pts[-1]), size=_size(0.04, 0.04, 0.04), color=_color(colour))
    return SceneEntity(
        timestamp=ts,
        frame_id=VEHICLE_FRAME,
        id=f"arm/{side}",
        frame_locked=True,
        lines=[link],
        spheres=[*joints, ee],
        texts=[_text(label, label_at, color=colour)],
    )


def status_line(state):
    """The executor's state in two lines of text."""
    m = state.exec_state
    if m is None:
        return "no executor state yet"
    phase = f"SAFE: {m.safe_reason}" if m.phase == "safe" else m.phase
    at = f", stop {m.stop + 1}/{len(state.stops)}" if m.stop >= 0 else ""  # -1: at none
    return (
        f"{phase}{at}, t {m.t_s:.1f} s of {m.expected_makespan_s:.1f} s expected\n"
        f"picked {m.picked}, failed {m.failed}, skipped {m.skipped}, remaining {m.remaining}, "
        f"faults {len(state.faults)}"
    )


def robot_update(state, geo, ts):
    """SceneUpdate of the vehicle frame: the vehicle (a box through the arm bases), both
    arms and the executor's state above them."""
    bases = [a.base for a in geo.arms.values()]
    half_x = max(abs(b[0]) for b in bases) + 0.05
    half_y = max(abs(b[1]) for b in bases) + 0.1
    height = min(b[2] for b in bases)
    m = state.exec_state
    body = CubePrimitive(
        pose=_pose(0.0, 0.0, height / 2),
        size=_size(2 * half_x, 2 * half_y, height),
        color=_color("#525252", 0.5),
    )
    status_colour = FAULT_COLOR if m is not None and m.phase == "safe" else "#202020"
    ents = [
        SceneEntity(
            timestamp=ts,
            frame_id=VEHICLE_FRAME,
            id="vehicle",
            frame_locked=True,
            cubes=[body],
            texts=[_text(status_line(state), (0.0, 0.0, height + 0.95), 14.0, status_colour)],
        )
    ]
    ents += [_arm_entity(state, geo, side, k, ts) for k, side in enumerate(kinematics.SIDES)]
    return SceneUpdate(entities=ents)


def transforms(state, ts):
    """The vehicle frame in the row frame: moved along y to the vehicle's position."""
    return FrameTransforms(
        transforms=[
            FrameTransform(
                timestamp=ts,
                parent_frame_id=ROW_FRAME,
                child_frame_id=VEHICLE_FRAME,
                translation=Vector3(x=0.0, y=state.vehicle_y, z=0.0),
                rotation=Quaternion(w=1.0),
            )
        ]
    )


def log_message(level, source, text, ts):
    return Log(timestamp=ts, level=LOG_LEVELS[level], message=text, name=source)
