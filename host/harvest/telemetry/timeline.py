"""Read an executor telemetry log into a timeline: the plan as the executor expects it to
run, and what actually happened, per stop and per arm (plan time, s, from the row start).

Planned: the plan_t message's expected times (docs: executor/include/hv/exec_plan.h):
drive to a stop, then each arm's pick cycles back to back (cycle = 2 x IK move + cut +
release); the stop lasts as long as its slower arm, then the next drive.
Actual: fruit_event_t messages (approach of the first attempt -> outcome) and the
executor's state changes (arrival at a stop = phase harvest with that stop; the vehicle
drives in phases driving and final_drive, and stands still otherwise once the row started;
an end in safe or stopped is a halt, with the executor's reason).
"""

from . import eventlog, lcm_types


class Timeline:
    def __init__(self):
        self.plan = None
        self.planned = []  # (side, stop, fruit_id, start, end)
        self.planned_stops = []  # (stop, arrive, leave)
        self.planned_total = 0.0  # the course's end
        self.actual = {}  # (side, fruit_id) -> dict(start, end, outcome, reason, stop, attempts)
        self.actual_stops = {}  # stop -> arrival t_s
        self.states = []
        self.faults = []  # (t, side, fruit_id, reason)
        self.vehicle = []  # actual: (start, end, "drive" or "stopped"), merged, in time order
        self.halts = []  # (t, phase safe or stopped, safe_reason): the executor's stops
        self.final = None
        self.can_stats = None
        self.torn_at = None  # byte offset of an event the log's end cut short

    def fruits(self, outcome=None):
        return [
            a
            for a in self.actual.values()
            if a.get("outcome") and (outcome is None or a["outcome"] == outcome)
        ]


def planned_schedule(plan):
    """(bars, stops, total): the executor's expected schedule of a plan_t."""
    bars, stops = [], []
    t = 0.0
    by_stop = {}
    for k in plan.picks:
        by_stop.setdefault(k.stop, {0: [], 1: []})[k.side].append(k)
    for p, st in enumerate(plan.stops):
        t += st.drive_s
        arrive = t
        for side in (0, 1):
            s = arrive
            for k in by_stop.get(p, {}).get(side, []):
                bars.append((side, p, k.fruit_id, s, s + k.cycle_s))
                s += k.cycle_s
        t = arrive + st.expected_s
        stops.append((p, arrive, t))
    t += plan.final_drive_s
    return bars, stops, t


DRIVE_PHASES = ("driving", "final_drive")
BEFORE_ROW = ("wait_nodes", "enable", "homing")  # plan time has not started yet
HALT_PHASES = ("safe", "stopped")


def planned_drives(tl):
    """The vehicle's planned drives (start, end): to each stop and the final one."""
    out, t = [], 0.0
    for _, arrive, leave in tl.planned_stops:
        out.append((t, arrive))
        t = leave
    out.append((t, tl.planned_total))
    return [(a, b) for a, b in out if b > a]


def _vehicle_intervals(states):
    """(start, end, kind) between consecutive states from the row's start: each state's kind
    holds until the next state; consecutive ones of one kind are merged."""
    out = []
    rows = [s for s in states if s.phase not in BEFORE_ROW]
    for cur, nxt in zip(rows, rows[1:]):
        if nxt.t_s <= cur.t_s:
            continue
        kind = "drive" if cur.phase in DRIVE_PHASES else "stopped"
        if out and out[-1][2] == kind and out[-1][1] == cur.t_s:
            out[-1] = (out[-1][0], nxt.t_s, kind)
        else:
            out.append((cur.t_s, nxt.t_s, kind))
    return out


def read(path, python_dir=None):
    tl = Timeline()
    with eventlog.EventLog(path) as log:
        _read_events(tl, log, lcm_types.load(python_dir))
        tl.torn_at = log.torn_at
    tl.vehicle = _vehicle_intervals(tl.states)
    if tl.plan is not None:
        tl.planned, tl.planned_stops, tl.planned_total = planned_schedule(tl.plan)
    return tl


def _read_events(tl, log, types):
    for ev in log:
        msg = lcm_types.decode(ev.channel, ev.data, types)
        if msg is None:
            continue
        if ev.channel == "HARVEST_PLAN":
            tl.plan = msg
        elif ev.channel == "HARVEST_EXEC_STATE":
            if msg.phase in HALT_PHASES and (tl.final is None or tl.final.phase != msg.phase):
                tl.halts.append((msg.t_s, msg.phase, msg.safe_reason))
            tl.states.append(msg)
            tl.final = msg
            if msg.phase == "harvest" and msg.stop >= 0 and msg.stop not in tl.actual_stops:
                tl.actual_stops[msg.stop] = msg.t_s
        elif ev.channel == "HARVEST_FRUIT":
            key = (msg.side, msg.fruit_id)
            a = tl.actual.setdefault(
                key,
                {
                    "side": msg.side,
                    "fruit_id": msg.fruit_id,
                    "stop": msg.stop,
                    "start": None,
                    "end": None,
                    "outcome": None,
                    "reason": None,
                    "attempts": 0,
                },
            )
            if msg.event == "approach":
                a["attempts"] = max(a["attempts"], msg.attempt)
                if a["start"] is None:
                    a["start"] = msg.t_s
            elif msg.event == "outcome":
                a["end"] = msg.t_s
                a["outcome"] = msg.outcome
                a["reason"] = msg.reason
                if a["start"] is None:
                    a["start"] = msg.t_s
            elif msg.event == "fault":
                tl.faults.append((msg.t_s, msg.side, msg.fruit_id, msg.reason))
        elif ev.channel == "HARVEST_CAN_STATS":
            tl.can_stats = msg


def summary(tl):
    """A dict of what the log says about the run."""
    out = {
        "fruits_planned": tl.plan.n_picks if tl.plan else None,
        "picked": len(tl.fruits("picked")),
        "failed": len(tl.fruits("failed")),
        "skipped": len(tl.fruits("skipped")),
        "faults": len(tl.faults),
        "stops_reached": len(tl.actual_stops),
        "stops_planned": tl.plan.n_stops if tl.plan else None,
        "planned_makespan_s": tl.plan.planned_makespan_s if tl.plan else None,
        "expected_makespan_s": tl.plan.expected_makespan_s if tl.plan else None,
        "executed_makespan_s": tl.final.executed_s if tl.final else None,
        "final_phase": tl.final.phase if tl.final else None,
        "safe_reason": tl.final.safe_reason if tl.final else None,
    }
    if out["expected_makespan_s"] and out["executed_makespan_s"]:
        out["executed_vs_expected"] = out["executed_makespan_s"] / out["expected_makespan_s"] - 1
    return out
