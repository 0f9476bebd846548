"""The simulated camera of online mode (DESIGN §5): it reveals a fruit map ahead of the
vehicle on LCM, camera_frame_t on HARVEST_CAMERA.

The camera sees the row from camera.lead to camera.lead + camera.window ahead of the
vehicle's position (config/harvest.cfg). Every `period_s` simulated seconds it sends the
fruit that came into view since its last frame (each fruit once, in y order) and how far
it has seen (while the vehicle stands and nothing is new, only every KEEPALIVE_S). With
`bad` > 0 it also sends, spread over the row, `bad` detections of each
kind the planner must refuse: outside the row, a fruit seen again with another pose, and a
new fruit behind the vehicle (late); each one is written to the record ("camera_bad").

On request (camera_replay_t on HARVEST_CAMERA_REPLAY, from the planner as it starts and
after a lost frame) it sends again every fruit revealed so far, in one frame with `replay`
set, the seq of its last frame and its view: what the planner missed while it was down is
recovered rather than lost. Each replay is written to the record ("camera_replay").
"""

import time

CHANNEL = "HARVEST_CAMERA"
REPLAY_CHANNEL = "HARVEST_CAMERA_REPLAY"
BAD_KINDS = ("outside_row", "duplicate", "late")
KEEPALIVE_S = 5.0  # simulated s between frames while the vehicle stands
LATE_BEHIND_M = 1.5  # a late detection lies this far behind the vehicle: out of reach of
# every stop not yet passed (the arms reach about 0.7 m ahead)


class Camera:
    def __init__(
        self, fruits, lead_m, window_m, row_length_m, url, log, period_s=0.5, bad=0, lc=None
    ):
        """`lc`: an LCM-like object (publish, subscribe, handle_timeout) instead of one on
        `url`, for tests."""
        import lcm

        from harvest.telemetry import lcm_types

        try:
            types = lcm_types.load()
        except lcm_types.LcmTypesMissing as e:
            raise ValueError(f"--fruits: the camera needs the LCM types: {e}") from None
        self._frame_t, self._det_t = types["camera_frame_t"], types["detection_t"]
        self._replay_t = types["camera_replay_t"]
        self._lcm = lc if lc is not None else lcm.LCM(url)
        self._lcm.subscribe(REPLAY_CHANNEL, self._on_request)
        self._requests = []  # requesters not answered yet
        self.replays, self.replayed = 0, 0
        self.fruits = sorted(fruits, key=lambda f: (f.y, f.id))
        self.lead, self.window, self.length = lead_m, window_m, row_length_m
        self.log, self.period = log, period_s
        self.next_t, self.seq, self.sent, self.seen_to = 0.0, 0, 0, None
        # the row fractions at which the bad detections go out, one of each kind per point
        self._bad_at = [(k + 1) / (bad + 1) for k in range(bad)]
        self.bad_sent = {k: 0 for k in BAD_KINDS}
        self._late_due = 0
        self._last_sent, self._last_t = None, 0.0

    def next_event(self):
        return self.next_t

    def _detection(self, fid, side, x, y, z, yaw):
        d = self._det_t()
        d.fruit_id, d.side = fid, 0 if side == "L" else 1
        d.x_m, d.y_m, d.z_m, d.yaw_rad = x, y, z, yaw
        return d

    def _bad(self, vehicle_m, seen_to):
        """The bad detections due once the camera has seen this far (a late one waits until
        the vehicle is 1.5 m into the row, so that a fruit behind it lies in the row)."""
        out = []
        while self._bad_at and seen_to >= self._bad_at[0] * self.length:
            self._bad_at.pop(0)
            self._late_due += 1
            k = self.bad_sent["outside_row"]
            out.append(
                (
                    "outside_row",
                    self._detection(f"bad_out_{k}", "L", -0.5, self.length + 0.3, 0.5, 0.0),
                )
            )
            if self.sent:
                f = self.fruits[self.sent - 1]
                out.append(("duplicate", self._detection(f.id, f.side, f.x, f.y + 0.2, f.z, f.yaw)))
        first = self.fruits[0] if self.fruits else None
        while self._late_due and first is not None and vehicle_m >= LATE_BEHIND_M:
            self._late_due -= 1
            k = self.bad_sent["late"]
            out.append(
                (
                    "late",
                    self._detection(
                        f"bad_late_{k}",
                        first.side,
                        first.x,
                        vehicle_m - LATE_BEHIND_M,
                        first.z,
                        first.yaw,
                    ),
                )
            )
        return out

    def _on_request(self, channel, data):
        self._requests.append(self._replay_t.decode(data).requester)

    def _replay(self, t, vehicle_m):
        """Every fruit sent so far, in one frame, for each request heard since the last
        step (several requests at once get one answer)."""
        requesters, self._requests = self._requests, []
        fruits = self.fruits[: self.sent]
        msg = self._frame_t()
        msg.utime = int(time.time() * 1e6)
        msg.seq, msg.replay, msg.vehicle_m = self.seq - 1, True, vehicle_m
        msg.seen_to_m = self.seen_to if self.seen_to is not None else 0.0
        msg.fruits = [self._detection(f.id, f.side, f.x, f.y, f.z, f.yaw) for f in fruits]
        msg.n = len(msg.fruits)
        self._lcm.publish(CHANNEL, msg.encode())
        self.replays += 1
        self.replayed += msg.n
        self.log(
            t,
            "camera_replay",
            requesters=requesters,
            seq=msg.seq,
            seen_to=msg.seen_to_m,
            fruits=msg.n,
        )

    def stats(self):
        """What it revealed and replayed, for the simulator's summary."""
        return {"revealed": self.sent, "replays": self.replays, "replayed": self.replayed}

    def step(self, t, vehicle_m):
        """Answer the replay requests that came, then send the frame due at simulated time
        t (the vehicle at vehicle_m)."""
        while self._lcm.handle_timeout(0) > 0:
            pass
        if self._requests:
            self._replay(t, vehicle_m)
        if t < self.next_t:
            return
        self.next_t = t + self.period
        seen_to = vehicle_m + self.lead + self.window
        if self.seen_to is not None and seen_to < self.seen_to:
            seen_to = self.seen_to  # it has seen that far already
        self.seen_to = seen_to
        dets = []
        while self.sent < len(self.fruits) and self.fruits[self.sent].y <= seen_to:
            f = self.fruits[self.sent]
            dets.append(self._detection(f.id, f.side, f.x, f.y, f.z, f.yaw))
            self.sent += 1
        for kind, d in self._bad(vehicle_m, seen_to):
            self.bad_sent[kind] += 1
            self.log(t, "camera_bad", kind=kind, fruit=d.fruit_id, y=d.y_m)
            dets.append(d)
        if (
            not dets
            and self._last_sent is not None
            and seen_to - self._last_sent < 0.005
            and t - self._last_t < KEEPALIVE_S
        ):
            return  # the vehicle stands: nothing new to say
        self._last_sent, self._last_t = seen_to, t
        msg = self._frame_t()
        msg.utime = int(time.time() * 1e6)
        msg.seq, msg.vehicle_m, msg.seen_to_m = self.seq, vehicle_m, seen_to
        msg.n, msg.fruits = len(dets), dets
        self._lcm.publish(CHANNEL, msg.encode())
        if dets:
            self.log(
                t,
                "camera",
                seq=self.seq,
                seen_to=seen_to,
                fruits=len(dets),
                ids=[d.fruit_id for d in dets],
            )
        self.seq += 1
