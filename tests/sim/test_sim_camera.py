"""The simulated camera of online mode (harvest.sim.camera) without a network: what it would
publish is captured and decoded with the generated LCM types."""

import pytest

from harvest.scenario.fruit_map import Fruit
from harvest.sim.model import Model

MODEL = Model.load()

try:
    from harvest.telemetry import lcm_types

    TYPES = lcm_types.load()
    from harvest.sim.camera import Camera
except Exception as e:  # the generated types live in the build tree
    pytest.skip(f"SKIPPED: the LCM types are not built: {e}", allow_module_level=True)


class Capture:
    def __init__(self):
        self.frames = []

    def publish(self, channel, data):
        assert channel == "HARVEST_CAMERA"
        self.frames.append(TYPES["camera_frame_t"].decode(data))


def camera(fruits, bad=0):
    log = []
    cam = Camera(
        fruits,
        MODEL.camera_lead,
        MODEL.camera_window,
        5.0,
        "memq://",
        lambda t, event, **f: log.append((event, f)),
        period_s=0.5,
        bad=bad,
    )
    cam._lcm = Capture()
    return cam, log


def row(n=20, length=5.0):
    return [
        Fruit(f"F{i}", "LR"[i % 2], (-1) ** (i + 1) * 0.45, length * (n - i) / (n + 1), 0.5, 0.0)
        for i in range(n)
    ]


def drive(cam, until_m, speed=0.1, dt=0.25):
    t, y = 0.0, 0.0
    while y <= until_m:
        cam.step(t, y)
        t, y = t + dt, y + speed * dt
    return t


def test_each_fruit_once_in_y_order_within_the_view():
    fruits = row()
    cam, _ = camera(fruits)
    drive(cam, 5.0)
    frames = cam._lcm.frames
    assert [f.seq for f in frames] == list(range(len(frames)))
    seen = [d for f in frames for d in f.fruits]
    assert sorted(d.fruit_id for d in seen) == sorted(f.id for f in fruits)
    ys = [d.y_m for d in seen]
    assert ys == sorted(ys)
    for f in frames:  # a fruit is sent only once the view reaches it
        assert f.seen_to_m == pytest.approx(f.vehicle_m + MODEL.camera_lead + MODEL.camera_window)
        assert all(d.y_m <= f.seen_to_m for d in f.fruits)
    assert all(f.seen_to_m >= g.seen_to_m for f, g in zip(frames[1:], frames))


def test_quiet_while_the_vehicle_stands():
    cam, _ = camera(row())
    for k in range(40):  # 20 s standing still: the first frame and keep-alives only
        cam.step(0.5 * k, 0.0)
    assert 1 <= len(cam._lcm.frames) <= 1 + 20 // 5


def test_bad_detections_of_each_kind():
    fruits = row()
    cam, log = camera(fruits, bad=1)
    drive(cam, 5.0)
    bad = [f for e, f in log if e == "camera_bad"]
    assert sorted(b["kind"] for b in bad) == ["duplicate", "late", "outside_row"]
    dets = {d.fruit_id: d for f in cam._lcm.frames for d in f.fruits}
    out = next(b for b in bad if b["kind"] == "outside_row")
    assert not 0.0 <= dets[out["fruit"]].y_m <= 5.0
    dup = next(b for b in bad if b["kind"] == "duplicate")
    assert dup["fruit"] in {f.id for f in fruits}
    late = next(b for b in bad if b["kind"] == "late")
    sent = next(f for f in cam._lcm.frames for d in f.fruits if d.fruit_id == late["fruit"])
    assert late["y"] <= sent.vehicle_m - 1.5 + 1e-9
