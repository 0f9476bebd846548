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
    """LCM as the camera uses it: what it publishes is kept, requests are handed to it."""

    def __init__(self):
        self.frames = []
        self.handlers = {}
        self.inbox = []

    def publish(self, channel, data):
        assert channel == "HARVEST_CAMERA"
        self.frames.append(TYPES["camera_frame_t"].decode(data))

    def subscribe(self, channel, handler):
        self.handlers[channel] = handler

    def handle_timeout(self, ms):
        if not self.inbox:
            return 0
        channel, data = self.inbox.pop(0)
        self.handlers[channel](channel, data)
        return 1

    def ask_replay(self, requester="test"):
        m = TYPES["camera_replay_t"]()
        m.utime, m.requester = 1, requester
        self.inbox.append(("HARVEST_CAMERA_REPLAY", m.encode()))


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
        lc=Capture(),
    )
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


def test_replay_on_request_sends_every_fruit_revealed_again():
    fruits = row()
    cam, log = camera(fruits, bad=1)
    t = drive(cam, 2.0)
    before = list(cam._lcm.frames)
    # the map's fruit in the order first sent (the bad ones are not of the map)
    ids = {f.id for f in fruits}
    revealed = list(
        dict.fromkeys(d.fruit_id for f in before for d in f.fruits if d.fruit_id in ids)
    )
    assert 0 < len(revealed) < len(fruits)
    cam._lcm.ask_replay("planner")
    cam._lcm.ask_replay("planner")  # two requests before the camera looks: one answer
    cam.step(t, 2.0)
    replays = [f for f in cam._lcm.frames[len(before) :] if f.replay]
    assert len(replays) == 1
    r = replays[0]
    # the real fruit only (no bad detection again), in y order; the seq of the last frame,
    # which the replay does not take from the frames that follow
    assert [d.fruit_id for d in r.fruits] == revealed
    assert r.seq == before[-1].seq and r.seen_to_m == before[-1].seen_to_m
    assert all(not f.replay for f in before)
    drive(cam, 5.0)
    regular = [f.seq for f in cam._lcm.frames if not f.replay]
    assert regular == list(range(len(regular)))
    assert cam.stats() == {"revealed": len(fruits), "replays": 1, "replayed": len(revealed)}
    rec = [f for e, f in log if e == "camera_replay"]
    assert len(rec) == 1 and rec[0]["requesters"] == ["planner", "planner"], rec
    assert (rec[0]["seq"], rec[0]["fruits"]) == (r.seq, len(revealed)), rec


def test_replay_before_the_first_frame_is_empty():
    cam, log = camera(row())
    cam._lcm.ask_replay()
    cam.step(0.0, 0.0)
    first, second = cam._lcm.frames[:2]
    assert first.replay and first.n == 0 and first.seq == -1
    assert not second.replay and second.seq == 0 and second.n > 0
    assert [e for e, _ in log].count("camera_replay") == 1
