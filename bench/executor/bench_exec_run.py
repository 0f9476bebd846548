"""bench_exec_run: harvest-exec on a whole row against the simulator, over UDP multicast
in a private network namespace; prints

  - the executor's CPU share (getrusage user+sys / wall) and peak memory (VmHWM)
    during the row, against its idle loop (the same program waiting for nodes that never
    come, for a comparable time) measured in the same run;
  - the reaction delay on the bus, from a bus listener's receive timestamps: a "target
    reached" status -> the executor's next frame to that arm (the cut or release command),
    and an end-effector "done" -> the next setpoint; against the simulator's own reaction
    on the same bus (our command -> its status echoing it) as the baseline.

Usage: python bench/executor/bench_exec_run.py [--stops N] [--per-arm K] [--time-scale S]
"""

import argparse
import os
import statistics
import sys
import tempfile
import threading

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.environ.get("HV_SOURCE_DIR", os.path.dirname(os.path.dirname(HERE)))
sys.path.insert(0, os.path.join(SOURCE, "tests", "executor"))

import exec_hil as H  # noqa: E402

from harvest.canbus import netns, protocol  # noqa: E402


def pct(v, q):
    v = sorted(v)
    return v[min(len(v) - 1, int(round(q * (len(v) - 1))))]


def fmt(v):
    if not v:
        return "n/a (no samples)"
    return (
        f"median {statistics.median(v) * 1e3:7.3f} ms  p99 {pct(v, 0.99) * 1e3:7.3f} ms  "
        f"(n={len(v)})"
    )


class Listener(threading.Thread):
    def __init__(self):
        super().__init__(daemon=True)
        import can

        self.bus = can.Bus(interface="udp_multicast", channel=H.GROUP)
        self.frames = []
        self.stop = False

    def run(self):
        while not self.stop:
            m = self.bus.recv(0.1)
            if m is not None:
                self.frames.append((m.timestamp, m.arbitration_id, bytes(m.data)))

    def close(self):
        self.stop = True
        self.join(2)
        self.bus.shutdown()


def reactions(frames, proto):
    """Delays (s) per kind, from the listener's frames."""
    out = {
        "reached->ee command": [],
        "ee done->setpoint": [],
        "sim: setpoint->echo": [],
        "sim: ee command->echo": [],
    }
    for arm in ("LeftArm", "RightArm"):
        ids = {
            proto.message(arm + k).frame_id: k
            for k in ("Status", "Setpoint", "EeCommand", "EeStatus")
        }
        seen_reached, seen_done = set(), set()
        pending = None  # (t, kind) waiting for the executor's next frame to this arm
        sent_sp, sent_ee = {}, {}
        for t, fid, data in frames:
            k = ids.get(fid)
            if k is None:
                continue
            sig = proto.db.get_message_by_frame_id(fid).decode(data, decode_choices=False)
            if k == "Status":
                s = sig["SetpointSeq"]
                if s in sent_sp:
                    out["sim: setpoint->echo"].append(t - sent_sp.pop(s))
                if sig["TargetReached"] and s not in seen_reached:
                    seen_reached.add(s)
                    pending = (t, "reached->ee command")
            elif k == "EeStatus":
                e = sig["EeSeq"]
                if e in sent_ee and sig["State"] != 0:
                    out["sim: ee command->echo"].append(t - sent_ee.pop(e))
                if sig["State"] == 2 and e not in seen_done:
                    seen_done.add(e)
                    pending = (t, "ee done->setpoint")
            elif k == "Setpoint":
                sent_sp.setdefault(sig["SetpointSeq"], t)
                if pending and pending[1] == "ee done->setpoint" and t - pending[0] < 0.5:
                    out[pending[1]].append(t - pending[0])
                pending = None
            elif k == "EeCommand":
                sent_ee.setdefault(sig["EeSeq"], t)
                if pending and pending[1] == "reached->ee command":
                    out[pending[1]].append(t - pending[0])
                pending = None
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--stops", type=int, default=5)
    ap.add_argument("--per-arm", type=int, default=5)
    ap.add_argument("--time-scale", type=float, default=10.0)
    args = ap.parse_args(argv)
    missing = H.missing_pieces()
    if missing:
        print("bench_exec_run: SKIPPED: " + "; ".join(missing))
        return 0
    try:
        netns.enter_private_netns()
    except netns.NetnsUnavailable as e:
        print(f"bench_exec_run: SKIPPED: no private network namespace: {e}")
        return 0
    proto = protocol.Protocol()
    with tempfile.TemporaryDirectory(prefix="bench_exec_") as d:
        plan = os.path.join(d, "plan.json")
        H.make_plan(plan, args.stops, args.per_arm, seed=21)
        listener = Listener()
        listener.start()
        sim = H.Sim(d, args.time_scale)
        try:
            proc, run = H.run_exec(
                plan, os.path.join(d, "run.journal"), os.path.join(d, "run.json"), args.time_scale
            )
        finally:
            sim.stop()
            listener.close()
        if proc.returncode != 0:
            print(proc.stderr)
            return 1
        # idle baseline: the same loop with nobody on the bus, about as long as the row
        idle_wall = min(max(run["wall_s"], 3.0), 30.0)
        idle_proc, idle = H.run_exec(
            plan,
            os.path.join(d, "idle.journal"),
            os.path.join(d, "idle.json"),
            args.time_scale,
            ["--startup-timeout", f"{idle_wall:.1f}", "--quiet"],
        )
        assert idle["safe_reason"] == "nodes_absent", idle
    fruits = run["picked"]
    print(
        f"bench_exec_run: {args.stops} stops x {args.per_arm} fruits per arm ({fruits} picked), "
        f"time scale {args.time_scale:g}, udp multicast in a private namespace"
    )
    print(
        f"  row: executed {run['executed_makespan_s']:.2f} s vs expected "
        f"{run['expected_makespan_s']:.2f} s "
        f"({(run['executed_makespan_s'] / run['expected_makespan_s'] - 1) * 100:+.2f} %), "
        f"wall {run['wall_s']:.2f} s"
    )
    cpu_run = run["cpu_s"] / run["wall_s"] * 100
    cpu_idle = idle["cpu_s"] / idle["wall_s"] * 100
    print(
        f"  CPU share of one core: row {cpu_run:6.2f} %   idle loop (baseline) {cpu_idle:6.2f} %  "
        f"(target < 5 %)"
    )
    print(
        f"  peak memory (VmHWM): row {run['peak_rss_kb']} KiB   idle loop (baseline) "
        f"{idle['peak_rss_kb']} KiB"
    )
    print(
        f"  step in the running program: mean {run['step_ns_mean']:.0f} ns, max "
        f"{run['step_ns_max']} ns over {run['steps']} steps"
    )
    r = reactions(listener.frames, proto)
    print("  reaction delay on the bus (listener timestamps):")
    for k in ("reached->ee command", "ee done->setpoint"):
        print(f"    executor  {k:24s} {fmt(r[k])}")
    for k in ("sim: setpoint->echo", "sim: ee command->echo"):
        print(f"    baseline  {k:24s} {fmt(r[k])}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
