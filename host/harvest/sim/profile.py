"""Time-optimal trapezoidal motion of one axis (a joint or the vehicle drive).

A profile is a list of constant-acceleration segments starting at (t0, p0, v0) and ending
at rest on the target, so the position at any simulated time is exact (no integration
drift) and the end time is known in advance: the simulator stamps "target reached" at the
profile's end, not at whatever tick noticed it.
"""

import math


def trapezoid_time(dist, vmax, amax):
    """Rest-to-rest time (s) over |dist| (DESIGN §1): 2 sqrt(d/a) if d <= v^2/a, else d/v + v/a."""
    d = abs(dist)
    if d <= vmax * vmax / amax:
        return 2.0 * math.sqrt(d / amax)
    return d / vmax + vmax / amax


class Profile:
    """Motion from (p0, v0) at time t0 to rest at `target` within |v| <= vmax, |a| <= amax.

    If the axis is already moving away from the target, or too fast to stop before it, it
    first brakes to rest and then runs a rest-to-rest trapezoid from there; that is the
    time-optimal plan for a single axis with symmetric limits.
    """

    def __init__(self, t0, p0, v0, target, vmax, amax):
        if vmax <= 0 or amax <= 0:
            raise ValueError(f"vmax {vmax} and amax {amax} must be > 0")
        self.t0 = float(t0)
        self.p0 = float(p0)
        self.v0 = float(v0)
        self.target = float(target)
        self.segments = []  # (duration s, acceleration) in order
        self._plan(self.p0, self.v0, self.target, float(vmax), float(amax))
        self.duration = sum(d for d, _ in self.segments)

    @classmethod
    def hold(cls, t0, p0):
        """An axis standing still at p0."""
        return cls(t0, p0, 0.0, p0, 1.0, 1.0)

    @classmethod
    def brake(cls, t0, p0, v0, amax):
        """Stop as fast as the axis can: the target is where full deceleration ends."""
        stop = p0 + v0 * abs(v0) / (2.0 * amax)
        return cls(t0, p0, v0, stop, max(abs(v0), 1e-9), amax)

    def _plan(self, p, v, target, vmax, amax):
        d = target - p
        if d == 0.0 and v == 0.0:
            return
        s = 1.0 if d > 0 or (d == 0.0 and v < 0) else -1.0
        u = s * v  # speed towards the target
        dist = abs(d)
        if u < 0 or u * u / (2.0 * amax) > dist + 1e-12:
            # moving away, or cannot stop in time: brake to rest first, then start over
            t_brake = abs(v) / amax
            self.segments.append((t_brake, -math.copysign(amax, v)))
            p_rest = p + v * abs(v) / (2.0 * amax)
            self._rest_to_rest(p_rest, target, vmax, amax)
            return
        if u > vmax:
            # faster than allowed (a lowered limit): come down to vmax first
            t_down = (u - vmax) / amax
            self.segments.append((t_down, -s * amax))
            dist -= (u * u - vmax * vmax) / (2.0 * amax)
            u = vmax
        peak = min(vmax, math.sqrt(max(0.0, (2.0 * amax * dist + u * u) / 2.0)))
        t_acc = (peak - u) / amax
        d_acc = (peak * peak - u * u) / (2.0 * amax)
        d_dec = peak * peak / (2.0 * amax)
        t_cruise = max(0.0, (dist - d_acc - d_dec) / peak) if peak > 0 else 0.0
        if t_acc > 0:
            self.segments.append((t_acc, s * amax))
        if t_cruise > 0:
            self.segments.append((t_cruise, 0.0))
        if peak > 0:
            self.segments.append((peak / amax, -s * amax))

    def _rest_to_rest(self, p, target, vmax, amax):
        self._plan(p, 0.0, target, vmax, amax)

    @property
    def t_end(self):
        return self.t0 + self.duration

    def done(self, t):
        return t >= self.t_end

    def state(self, t):
        """(position, velocity) at simulated time t; exactly (target, 0) from t_end on."""
        if t >= self.t_end:
            return self.target, 0.0
        tau = max(0.0, t - self.t0)
        p, v = self.p0, self.v0
        for dur, acc in self.segments:
            step = min(dur, tau)
            p += v * step + 0.5 * acc * step * step
            v += acc * step
            tau -= step
            if tau <= 0:
                break
        return p, v
