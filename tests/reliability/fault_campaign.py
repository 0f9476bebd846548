"""The fault campaign (issue 43, docs/RELIABILITY.md): one row run by harvest-exec against
the simulator (python -m harvest sim) over udp_multicast in a private network namespace,
once without faults and once per fault, each run resumed from its journal until the row is
done. Judged only from the simulator's record (--record JSONL):

  picked   planned fruits cut and then released into the container by the arm that cut them
  lost     planned fruits never picked
  twice    fruits cut more than once
  stray    cuts at no planned fruit

A cut is known by what the simulator saw when it was done: the arm's joint positions and
the vehicle's position, turned into the end effector's pose by the test's own forward
kinematics (tests/executor/fk_check.py) and matched to the plan's fruit of that arm at that
stop within the DBC's resolution. The fault-free row must pick every planned fruit once, or
the campaign stops.

Faults: kill -9 of harvest-exec at seeded moments (during a move, an approach, a cut, a
release, or at a random time) each followed by a plain restart; the simulator killed at a
seeded moment between picks and restarted where the vehicle stood; bus silence of each
node past the heartbeat timeout; a flood of frames from a node the DBC does not have; a
node's e-stop at a seeded moment; a joint fault on each arm. After a stop in the safe
state the restart without the operator's clear must stay safe (exit 4, latched e-stop) and
the one with --clear-estop finishes the row.

Usage: python tests/reliability/fault_campaign.py --plan PLAN.json [--kills N] [--seed S]
       [--time-scale K] [--flood N] [--work DIR] [--json FILE] [--doc FILE]
(HV_BUILD_DIR: the build with harvest-exec, make-test-plan and hv-can-tool.)
"""

import argparse
import collections
import json
import os
import random
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "executor"))
import exec_hil as H  # noqa: E402

CAN_TOOL = os.path.join(H.BUILD, "executor", "can", "hv-can-tool")
OPERATOR = "campaign"
# a node id the DBC does not have (1..4 are ours), command 3 (status)
UNKNOWN_NODE_ID = f"{(7 << 5) | 3:03X}"
# moments at which harvest-exec is killed: the record event that opens the window, the
# longest wait after it (wall s) and a filter on the event
KILL_WINDOWS = {
    "move": ("move", 0.05, lambda e: e.get("accepted")),
    "approach": ("setpoint", 0.1, lambda e: e.get("accepted")),
    "cut": ("ee", 0.04, lambda e: e.get("accepted") and e.get("action") == "CUT"),
    "release": ("ee", 0.02, lambda e: e.get("accepted") and e.get("action") == "RELEASE"),
    "time": (None, 3.0, None),
}
MARKER_BEGIN, MARKER_END = "<!-- faults:begin -->", "<!-- faults:end -->"


def read_record(path):
    out = []
    try:
        with open(path) as f:
            for line in f:
                if line.endswith("\n"):  # a line in flight is not read yet
                    out.append(json.loads(line))
    except FileNotFoundError:
        pass
    return out


def planned_fruits(plan):
    """(side, id) of every fruit the plan picks."""
    order = H.plan_order(plan)
    return {(side, i) for side in order for i in order[side]}


def fruit_keys(judge, plan, picks):
    """Each cut as the planned fruit it is, by forward kinematics of the recorded joints
    and vehicle position (tests/executor/fk_check.py): (side, id); a cut at no planned
    fruit is a stray, known by where it was."""
    return [
        (side, fid)
        if fid is not None
        else ("stray", e["node"], e["vehicle_position"], tuple(e["positions"]))
        for e, (side, fid, *_) in zip(picks, judge.identify(plan, picks))
    ]


class Row:
    """One row: its simulator lives, its harvest-exec runs, and what they left."""

    def __init__(self, work, name, plan_path, scale):
        self.dir = os.path.join(work, name)
        os.makedirs(self.dir, exist_ok=True)
        self.name, self.plan_path, self.scale = name, plan_path, scale
        with open(plan_path) as f:
            self.plan = json.load(f)
        p = self.plan["params"]
        self.judge = H.fk_check.Judge.for_plan(self.plan)
        self.vehicle_start = p["row_start_m"] - p["stop_margin_m"]
        self.journal = os.path.join(self.dir, "run.journal")
        self.sims, self.runs, self.notes = [], [], []

    # -- the simulator -------------------------------------------------------------------
    def start_sim(self, faults=(), vehicle_start=None):
        life = os.path.join(self.dir, f"sim{len(self.sims)}")
        os.makedirs(life, exist_ok=True)
        start = self.vehicle_start if vehicle_start is None else vehicle_start
        self.sims.append(
            H.Sim(life, self.scale, faults, ["--vehicle-start", f"{start:.4f}", "--seed", "1"])
        )
        return self.sims[-1]

    def sim(self):
        return self.sims[-1]

    def stop_sims(self):
        for s in self.sims:
            s.stop()

    def lives(self):
        return [read_record(s.record) for s in self.sims]

    # -- the executor --------------------------------------------------------------------
    def _summary(self):
        return os.path.join(self.dir, f"summary{len(self.runs)}.json")

    def start_exec(self, clear=False):
        extra = ["--clear-estop", OPERATOR] if clear else []
        summary = self._summary()
        proc = H.start_exec(self.plan_path, self.journal, summary, self.scale, extra)
        return proc, summary

    def finish(self, proc, summary, killed=False, timeout=600):
        out, err = proc.communicate(timeout=timeout)
        rc = proc.returncode
        s = {}
        if os.path.exists(summary) and not killed:
            with open(summary) as f:
                s = json.load(f)
        end = "killed" if killed else (s.get("safe_reason") or s.get("phase") or f"exit {rc}")
        if s.get("phase") == "row_done":
            end = "row_done"
        self.runs.append((rc, end))
        if rc not in (0, 3, 4) and not killed:
            self.notes.append(f"exit {rc}: {err.strip()[-300:]}")
        return rc, s

    def run(self, clear=False):
        return self.finish(*self.start_exec(clear))

    def resume_until_done(self, max_runs=8):
        """Restart after a stop: plainly; when that finds a latched e-stop (exit 4, having
        sent no command), with the operator's clear. Done when the row is."""
        for _ in range(max_runs):
            if self.runs and self.runs[-1][1] == "row_done":
                return True
            latched = self.runs and self.runs[-1][1] == "estop_latched"
            self.run(clear=bool(latched))
        return self.runs[-1][1] == "row_done"

    # -- judging from the simulator's record ----------------------------------------------
    def count(self, fruits):
        cuts = collections.Counter()
        picked = set()
        for events in self.lives():
            held = {}
            keys = iter(
                fruit_keys(self.judge, self.plan, [e for e in events if e["event"] == "pick"])
            )
            for e in events:
                if e["event"] == "pick":
                    k = next(keys)
                    cuts[k] += 1
                    held[e["node"]] = k
                elif e["event"] == "release" and e.get("fruit") and e["node"] in held:
                    picked.add(held.pop(e["node"]))
        return {
            "picked": len(picked & fruits),
            "lost": len(fruits - picked),
            "twice": sum(1 for k, n in cuts.items() if n > 1),
            "stray": sum(1 for k in cuts if k not in fruits),
        }

    def safe_latencies(self):
        """Wall s from each injected fault to the first e-stop frame after it (the executor
        in SAFE), per simulator life; and the longest executor silence the nodes saw before
        they declared it lost (comm_timeout)."""
        lat, silences = [], []
        for events in self.lives():
            pending = None
            for e in events:
                if e["event"] == "fault_injected" and e.get("fault") != "joint_fault":
                    pending = e["wall"] if pending is None else pending
                elif e["event"] == "estop_frame" and pending is not None:
                    lat.append(e["wall"] - pending)
                    pending = None
                elif e["event"] == "comm_timeout":
                    silences.append(e["silent_wall_s"])
        return lat, silences


def wait_record(row, pred, timeout, proc=None):
    """Wait until pred(events of the current simulator life) is true; False when the
    executor ended first or the time ran out."""
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        if pred(read_record(row.sim().record)):
            return True
        if proc is not None and proc.poll() is not None:
            return False
        time.sleep(0.01)
    return False


def count_events(events, name, filt):
    return sum(1 for e in events if e["event"] == name and (filt is None or filt(e)))


# ---- the scenarios ------------------------------------------------------------------------
def baseline(work, plan_path, scale):
    row = Row(work, "no fault", plan_path, scale)
    try:
        row.start_sim()
        row.run()
        fruits = planned_fruits(row.plan)
        c = row.count(fruits)
        if row.runs[-1][1] != "row_done" or (c["lost"], c["twice"], c["stray"]) != (0, 0, 0):
            raise RuntimeError(
                f"the fault-free row did not pick each of the {len(fruits)} planned "
                f"fruits once ({c}, end {row.runs[-1][1]}): see {row.dir}"
            )
        return row, fruits
    finally:
        row.stop_sims()


def kills(work, plan_path, scale, n, rng):
    row = Row(work, f"kill -9 of harvest-exec x{n}", plan_path, scale)
    kinds = collections.Counter()
    try:
        row.start_sim()
        done = 0
        while done < n:
            kind = rng.choice(sorted(KILL_WINDOWS))
            name, wait_max, filt = KILL_WINDOWS[kind]
            proc, summary = row.start_exec()
            if name is None:
                ok = proc.poll() is None
                time.sleep(rng.uniform(0.3, wait_max))
            else:
                before = count_events(read_record(row.sim().record), name, filt)
                ok = wait_record(row, lambda ev: count_events(ev, name, filt) > before, 120, proc)
                time.sleep(rng.uniform(0.0, wait_max))
            if not ok or proc.poll() is not None:  # the row ended before the moment came
                row.finish(proc, summary)
                break
            proc.send_signal(signal.SIGKILL)
            row.finish(proc, summary, killed=True)
            # stay away past the nodes' timeout, so they show their side of the safe state
            time.sleep(H.HEARTBEAT_TIMEOUT_S + 1.0)
            kinds[kind] += 1
            done += 1
        row.notes.append("kills: " + ", ".join(f"{k} {v}" for k, v in sorted(kinds.items())))
        row.resume_until_done()
        return row
    finally:
        row.stop_sims()


def sim_restart(work, plan_path, scale, rng):
    row = Row(work, "simulator killed and restarted", plan_path, scale)
    try:
        row.start_sim()
        proc, summary = row.start_exec()
        # a seeded number of picks into the row, then the moment no arm holds a fruit
        k = rng.randint(2, 6)
        wait_record(row, lambda ev: count_events(ev, "release", None) >= k, 120, proc)

        def between_picks(ev):
            held = {}
            for e in ev:
                if e["event"] == "pick":
                    held[e["node"]] = True
                elif e["event"] == "release":
                    held[e["node"]] = False
            return not any(held.values())

        wait_record(row, between_picks, 60, proc)
        sim = row.sim()
        sim.proc.send_signal(signal.SIGKILL)
        sim.proc.wait()
        events = read_record(sim.record)
        targets = [e["target"] for e in events if e["event"] == "move" and e.get("accepted")]
        arrived = [e["position"] for e in events if e["event"] == "arrived"]
        where = arrived[-1] if arrived else row.vehicle_start
        if targets and abs(targets[-1] - where) > 1e-6:
            row.notes.append("killed during a move: the vehicle restarts at its last arrival")
        row.finish(proc, summary)
        row.start_sim(vehicle_start=where)
        row.resume_until_done()
        return row
    finally:
        row.stop_sims()


def with_sim_fault(work, name, plan_path, scale, faults):
    row = Row(work, name, plan_path, scale)
    try:
        row.start_sim(faults)
        row.run()
        if row.runs[-1][1] not in ("row_done",):
            # a stop in the safe state: the first restart must stay safe without the clear
            row.run()
            if row.runs[-1][1] != "estop_latched":
                row.notes.append(f"restart without the clear ended {row.runs[-1][1]}")
        row.resume_until_done()
        return row
    finally:
        row.stop_sims()


def flood(work, plan_path, scale, count):
    row = Row(work, f"flood of {count} frames from an unknown node", plan_path, scale)
    try:
        row.start_sim()
        proc, summary = row.start_exec()
        wait_record(row, lambda ev: count_events(ev, "pick", None) >= 2, 120, proc)
        t0 = time.monotonic()
        tool = subprocess.run(
            [
                CAN_TOOL,
                "--bus",
                f"udp:{H.GROUP}",
                "flood",
                "--id",
                UNKNOWN_NODE_ID,
                "--count",
                str(count),
            ],
            capture_output=True,
            text=True,
            timeout=600,
        )
        row.notes.append(
            f"flood sent in {time.monotonic() - t0:.1f} s (hv-can-tool exit {tool.returncode})"
        )
        row.finish(proc, summary)
        if row.runs[-1][1] != "row_done":
            row.resume_until_done()
        return row
    finally:
        row.stop_sims()


def plan_time_s(plan_path):
    with open(plan_path) as f:
        return json.load(f)["totals"]["makespan_s"]


def campaign(plan_path, work, n_kills, seed, scale, flood_count):
    rng = random.Random(seed)
    rows = []
    base, fruits = baseline(work, plan_path, scale)
    rows.append(base)
    rows.append(kills(work, plan_path, scale, n_kills, rng))
    rows.append(sim_restart(work, plan_path, scale, rng))
    span = plan_time_s(plan_path)
    silent_s = 2 * H.HEARTBEAT_TIMEOUT_S * scale
    for node in ("vehicle", "left_arm", "right_arm"):
        at = rng.uniform(0.2, 0.7) * span
        rows.append(
            with_sim_fault(
                work,
                f"bus silence of {node}",
                plan_path,
                scale,
                [f"silent:node={node},after_s={at:.1f},for_s={silent_s:g}"],
            )
        )
    rows.append(flood(work, plan_path, scale, flood_count))
    node = rng.choice(["vehicle", "left_arm", "right_arm"])
    at = rng.uniform(0.2, 0.7) * span
    rows.append(
        with_sim_fault(
            work, f"e-stop of {node}", plan_path, scale, [f"estop:node={node},after_s={at:.1f}"]
        )
    )
    for arm in ("left_arm", "right_arm"):
        k = rng.randint(1, 4)
        rows.append(
            with_sim_fault(
                work,
                f"joint fault of {arm}",
                plan_path,
                scale,
                [f"joint_fault:node={arm},joint={rng.randint(1, 4)},pick={k}"],
            )
        )
    return rows, fruits


def table(rows, fruits):
    lines = [
        "| fault | harvest-exec runs, how each ended | picked | lost | twice | stray | "
        "fault to e-stop frame, max (ms) | nodes' longest wait for a lost executor (s) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    results = []
    for row in rows:
        c = row.count(fruits)
        lat, sil = row.safe_latencies()
        ends = " -> ".join(end for _, end in row.runs)
        cells = [
            row.name,
            f"{len(row.runs)}: {ends}",
            f"{c['picked']}/{len(fruits)}",
            str(c["lost"]),
            str(c["twice"]),
            str(c["stray"]),
            f"{1000 * max(lat):.1f}" if lat else "-",
            f"{max(sil):.3f}" if sil else "-",
        ]
        lines.append("| " + " | ".join(cells) + " |")
        results.append(
            {
                "fault": row.name,
                "runs": row.runs,
                "notes": row.notes,
                "safe_latency_s": lat,
                "comm_silence_s": sil,
                **c,
            }
        )
    return "\n".join(lines), results


def update_doc(doc, text):
    with open(doc) as f:
        s = f.read()
    a, b = s.index(MARKER_BEGIN) + len(MARKER_BEGIN), s.index(MARKER_END)
    with open(doc, "w") as f:
        f.write(s[:a] + "\n" + text + "\n" + s[b:])


def main(argv=None):
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--plan", required=True, help="the plan of the row (harvest-plan)")
    ap.add_argument("--kills", type=int, default=20, help="kill -9 moments (20)")
    ap.add_argument("--seed", type=int, default=43, help="seed of the moments (43)")
    ap.add_argument("--time-scale", type=float, default=20.0, help="simulator speed-up (20)")
    ap.add_argument("--flood", type=int, default=100000, help="frames of the flood (100000)")
    ap.add_argument("--work", default=None, help="folder for records and journals")
    ap.add_argument("--json", help="write every row's figures here")
    ap.add_argument("--doc", help="replace the table between the faults markers of this file")
    a = ap.parse_args(argv)
    missing = H.enter_udp_netns()
    if not os.access(CAN_TOOL, os.X_OK):
        missing.append(f"hv-can-tool not built at {CAN_TOOL}")
    if missing:
        print("SKIPPED: " + "; ".join(missing), file=sys.stderr)
        return 77
    work = a.work or os.path.join(H.BUILD, "faults")
    os.makedirs(work, exist_ok=True)
    rows, fruits = campaign(os.path.abspath(a.plan), work, a.kills, a.seed, a.time_scale, a.flood)
    text, results = table(rows, fruits)
    print(text)
    for r in results:
        for n in r["notes"]:
            print(f"  {r['fault']}: {n}")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(
                {
                    "plan": a.plan,
                    "seed": a.seed,
                    "kills": a.kills,
                    "time_scale": a.time_scale,
                    "fruits": len(fruits),
                    "rows": results,
                },
                f,
                indent=1,
            )
    if a.doc:
        with open(a.plan) as f:
            t = json.load(f)["totals"]
        about = (
            f"The paper-default row ({len(fruits)} fruits, planned makespan "
            f"{t['makespan_s']:.0f} s), time scale {a.time_scale:g}, seed {a.seed}, "
            f"{a.kills} kill moments, a flood of {a.flood} frames; heartbeat timeouts "
            f"{H.HEARTBEAT_TIMEOUT_S:g} s both ways."
        )
        update_doc(a.doc, about + "\n\n" + text)
    bad = [
        r
        for r in results
        if r["lost"] or r["twice"] or r["stray"] or r["runs"][-1][1] != "row_done"
    ]
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
