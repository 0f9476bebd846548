"""Simulated time: wall time since start multiplied by the time scale, so a 20x simulator
runs the physics and every period 20 times faster than real time."""

import time


class ScaledClock:
    def __init__(self, scale, now=time.monotonic):
        if not scale > 0:
            raise ValueError(f"time scale must be > 0, got {scale}")
        self.scale = float(scale)
        self._now = now
        self.t0_wall = now()

    def wall(self):
        """Wall seconds since start."""
        return self._now() - self.t0_wall

    def sim(self, wall=None):
        """Simulated seconds since start (at wall seconds `wall`, default now)."""
        return (self.wall() if wall is None else wall) * self.scale

    def to_wall(self, sim_seconds):
        """Wall duration of a simulated duration."""
        return sim_seconds / self.scale
