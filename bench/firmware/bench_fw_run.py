#!/usr/bin/env python3
"""bench_fw_run: the firmware (harvest-fw.elf in QEMU, SLCAN on its UART, python-can's
slcan + can.bridge onto the udp bus) against harvest-exec on Linux, on the same plan, time
scale and simulator rate, alternated round by round in one private network namespace.
Prints per target the medians over the rounds of

  - executed makespan (the simulator's record: first accepted move to arrival at the course
    end) against expected (the executor's own preparation of the plan), in %;
  - the reaction delay on the bus (a listener's receive timestamps): "target reached" ->
    the executor's cut/release command, end-effector "done" -> the next setpoint; and the
    simulator's own reaction (command -> its status echoing it) as the baseline.

The Linux run is the baseline: the difference is what the serial line, the bridge and the
emulated board add. Usage: python bench/firmware/bench_fw_run.py [--stops N] [--per-arm K]
[--time-scale S] [--rounds R]
"""

import argparse
import json
import os
import statistics
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.environ.get("HV_SOURCE_DIR", os.path.dirname(os.path.dirname(HERE)))
sys.path.insert(0, os.path.join(SOURCE, "tests", "executor"))
sys.path.insert(0, os.path.join(SOURCE, "tests", "firmware"))
sys.path.insert(0, os.path.join(SOURCE, "bench", "executor"))

import bench_exec_run as B  # noqa: E402
import exec_hil as H  # noqa: E402

from harvest.canbus import netns, protocol  # noqa: E402
from harvest.firmware import cli as fw_cli  # noqa: E402
from harvest.firmware import rig  # noqa: E402


def missing():
    import shutil

    out = H.missing_pieces()
    for tool in ("qemu-system-arm", "arm-none-eabi-gcc"):
        if shutil.which(tool) is None:
            out.append(f"{tool} not installed (scripts/setup.sh installs it)")
    return out


FINAL = ("row_done", "safe")


def build_image():
    import fw_build

    done = fw_build.build()
    if done.returncode != 0:
        raise SystemExit("bench_fw_run: the firmware's cross build failed:\n" + done.stdout)


def run_linux(d, plan_path, plan, scale, rate):
    listener = B.Listener()
    listener.start()
    sim = H.Sim(d, scale, extra=("--rate", str(rate)))
    try:
        proc, summary = H.run_exec(
            plan_path, os.path.join(d, "run.journal"), os.path.join(d, "run.json"), scale
        )
    finally:
        sim.stop()
        listener.close()
    # judged by the simulator's record, as the firmware run is (fw_cli.summarize)
    if proc.returncode != 0 or len(sim.events("pick")) != summary["fruits_planned"]:
        raise SystemExit("bench_fw_run: the Linux run did not finish its row:\n" + proc.stderr)
    executed = fw_cli.executed_makespan(sim.record, plan)
    return executed, summary["expected_makespan_s"], listener.frames


def run_firmware(d, plan_path, plan, scale, rate):
    import fw_hil

    image = fw_hil.plan_image(d, plan_path, scale)
    listener = B.Listener()
    listener.start()
    r = fw_hil.Rig(d, scale, sim_extra=("--rate", str(rate)))
    try:
        fw_hil.upload(image, 60)
        fw_hil.wait_until(lambda: rig.last_status(r.qemu.uart_log).get("phase") in FINAL, 1800)
    finally:
        r.stop()
        listener.close()
    s = fw_cli.summarize(r.sim.record, plan, image, r.qemu.uart_log)
    if s["phase"] != "row_done" or s["picked"] != s["fruits_planned"]:
        raise SystemExit(f"bench_fw_run: the firmware did not finish its row: {json.dumps(s)}")
    return s["executed_makespan_s"], s["expected_makespan_s"], listener.frames


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--stops", type=int, default=4, help="stops of the plan (4)")
    ap.add_argument("--per-arm", type=int, default=3, help="fruits per arm and stop (3)")
    ap.add_argument("--time-scale", type=float, default=2.0, help="as the firmware demo (2)")
    ap.add_argument("--rounds", type=int, default=3, help="alternated rounds (3)")
    args = ap.parse_args(argv)
    reasons = missing()
    if reasons:
        print("bench_fw_run: SKIPPED: " + "; ".join(reasons))
        return 0
    build_image()  # where fw_hil's rig takes it from
    try:
        netns.enter_private_netns()
    except netns.NetnsUnavailable as e:
        print(f"bench_fw_run: SKIPPED: no private network namespace: {e}")
        return 0
    # the simulator's frames per wall second stay those of time scale 1, as in the demo:
    # the serial line carries every frame of the bus
    rate = 50.0 / args.time_scale
    proto = protocol.Protocol()
    excess = {"linux": [], "firmware": []}
    delays = {t: {} for t in excess}
    with tempfile.TemporaryDirectory(prefix="bench_fw_") as d:
        plan_path = os.path.join(d, "plan.json")
        plan = H.make_plan(plan_path, args.stops, args.per_arm, seed=21)
        for r in range(args.rounds):
            for target in ("linux", "firmware"):
                work = os.path.join(d, f"{target}{r}")
                os.makedirs(work)
                if target == "linux":
                    got = run_linux(work, plan_path, plan, args.time_scale, rate)
                else:
                    got = run_firmware(work, plan_path, plan, args.time_scale, rate)
                executed, expected, frames = got
                excess[target].append((executed / expected - 1.0) * 100.0)
                for k, v in B.reactions(frames, proto).items():
                    delays[target].setdefault(k, []).extend(v)
                print(
                    f"  round {r + 1} {target:8s} executed {executed:8.2f} s vs expected "
                    f"{expected:8.2f} s ({excess[target][-1]:+.2f} %)",
                    flush=True,
                )
    fruits = args.stops * args.per_arm * 2
    print(
        f"bench_fw_run: {args.stops} stops x {args.per_arm} fruits per arm ({fruits} fruits), "
        f"time scale {args.time_scale:g}, simulator at {rate:g} simulated Hz, "
        f"{args.rounds} rounds"
    )
    for target in ("linux", "firmware"):
        label = "baseline" if target == "linux" else "        "
        print(
            f"  {label} {target:8s} executed vs expected: median "
            f"{statistics.median(excess[target]):+.2f} %"
        )
    print("  reaction delay on the bus (listener timestamps, all rounds):")
    for target in ("linux", "firmware"):
        for k in ("reached->ee command", "ee done->setpoint"):
            print(f"    {target:8s} {k:24s} {B.fmt(delays[target].get(k, []))}")
    for k in ("sim: setpoint->echo", "sim: ee command->echo"):
        both = delays["linux"].get(k, []) + delays["firmware"].get(k, [])
        print(f"    baseline {k:24s} {B.fmt(both)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
