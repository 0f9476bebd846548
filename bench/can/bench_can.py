#!/usr/bin/env python3
"""CAN transport benchmark: frames per second and median / 99th-percentile round-trip
latency C -> python-can -> C, on udp (private network namespace) and on vcan (this
machine's vcan0, else inside the QEMU test-bed guest), each against a baseline measured
in the same run: python-can -> python-can -> python-can over the same transport.

Usage: bench/can/bench_can.py [--transport udp|vcan|all] [--count N] [--window W]
  --count N    round trips per measurement (default 2000 on the host, 300 in the guest)
  --window W   frames in flight for the throughput figure (default 32)
Needs the build (HV_BUILD_DIR, default <repo>/build-can or <repo>/build) for hv-can-tool.
Numbers inside the guest are software-emulated (~20x slower): compare them only with the
baseline printed next to them, never with the host's.
"""

import argparse
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

from harvest.canbus.buses import open_bus  # noqa: E402
from harvest.canbus.guest import guest_or_skip, in_guest, local_vcan, run_in_guest, skip_reason  # noqa: E402,F401

PING_ID, REPLY_ID = 0x7F0, 0x7F1

# A python-can echo: every frame on PING_ID comes back on REPLY_ID (own frames filtered).
ECHO = f"""
import sys, can
from harvest.canbus.buses import open_bus
bus = open_bus(sys.argv[1], can_filters=[{{"can_id": {PING_ID}, "can_mask": 0x7FF}}])
print("ready", flush=True)
while True:
    m = bus.recv(float(sys.argv[2]))
    if m is None:
        break
    bus.send(can.Message(arbitration_id={REPLY_ID}, data=m.data, is_extended_id=False))
bus.shutdown()
"""


def build_dir():
    for cand in (
        os.environ.get("HV_BUILD_DIR"),
        os.path.join(ROOT, "build-can"),
        os.path.join(ROOT, "build"),
    ):
        if cand and os.path.exists(os.path.join(cand, "executor", "can", "hv-can-tool")):
            return cand
    sys.exit("bench_can: hv-can-tool not built; set HV_BUILD_DIR to your build directory")


TOOL = None


def start_echo(spec, idle_s):
    p = subprocess.Popen(
        [sys.executable, "-c", ECHO, spec, str(idle_s)], stdout=subprocess.PIPE, text=True
    )
    if p.stdout.readline().strip() != "ready":
        sys.exit("bench_can: python echo did not start")
    return p


def c_ping(spec, count, window):
    out = subprocess.run(
        [
            TOOL,
            "--bus",
            spec,
            "ping",
            "--count",
            str(count),
            "--window",
            str(window),
            "--id",
            f"{PING_ID:X}",
            "--reply-id",
            f"{REPLY_ID:X}",
            "--timeout-ms",
            "5000",
        ],
        capture_output=True,
        text=True,
        timeout=600,
    )
    fields = dict(f.split("=") for f in out.stdout.split()[1:] if "=" in f)
    if out.returncode != 0 or "fps" not in fields:
        sys.exit(f"bench_can: C ping failed: {out.stdout} {out.stderr}")
    return (
        float(fields["fps"]),
        float(fields["rtt_median_us"]),
        float(fields["rtt_p99_us"]),
        int(fields["lost"]),
    )


def py_ping(spec, count, window):
    import can

    rtts, lost = [], 0
    with open_bus(spec, can_filters=[{"can_id": REPLY_ID, "can_mask": 0x7FF}]) as bus:
        sent = {}
        nxt = 0
        t0 = time.perf_counter()
        while len(rtts) + lost < count:
            while nxt < count and len(sent) < window:
                sent[nxt] = time.perf_counter()
                bus.send(
                    can.Message(
                        arbitration_id=PING_ID,
                        is_extended_id=False,
                        data=nxt.to_bytes(4, "little") + b"\xee\xff\xc0\x00",
                    )
                )
                nxt += 1
            m = bus.recv(5.0)
            if m is None:
                lost += len(sent)
                sent.clear()
                continue
            seq = int.from_bytes(bytes(m.data[:4]), "little")
            if seq in sent:
                rtts.append(time.perf_counter() - sent.pop(seq))
        elapsed = time.perf_counter() - t0
    rtts.sort()
    p99 = rtts[min(len(rtts) - 1, int(round((len(rtts) - 1) * 0.99)))]
    return len(rtts) / elapsed, statistics.median(rtts) * 1e6, p99 * 1e6, lost


def bench(spec, label, count, window):
    print(f"\n== {label} ({spec}), {count} round trips each, python-can echo ==")
    print(f"{'path':<50} {'fps':>9} {'median us':>10} {'p99 us':>10} {'lost':>5}")
    rows = []
    idle = 30 if in_guest() else 5
    for who, fn in (
        ("C -> python-can -> C", c_ping),
        ("baseline python-can -> python-can -> python-can", py_ping),
    ):
        for w in (1, window):
            echo = start_echo(spec, idle)
            try:
                fps, med, p99, lost = fn(spec, count, w)
            finally:
                echo.kill()
                echo.wait()
            name = f"{who}, window {w}"
            rows.append((name, fps, med, p99, lost))
            print(f"{name:<50} {fps:>9.0f} {med:>10.1f} {p99:>10.1f} {lost:>5}", flush=True)
    c1, b1 = rows[0], rows[2]
    print(
        f"C side vs baseline at window 1: median latency x{c1[2] / b1[2]:.2f}, "
        f"throughput x{rows[1][1] / rows[3][1]:.2f} at window {window}"
    )


def main(argv=None):
    global TOOL
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--transport", choices=["udp", "vcan", "all"], default="all")
    ap.add_argument("--count", type=int, default=300 if in_guest() else 2000)
    ap.add_argument("--window", type=int, default=32)
    args = ap.parse_args(argv)
    os.environ.setdefault("HV_BUILD_DIR", build_dir())
    TOOL = os.path.join(os.environ["HV_BUILD_DIR"], "executor", "can", "hv-can-tool")
    if args.count < 10 or not 1 <= args.window <= 1024:
        ap.error("--count must be >= 10 and --window in 1..1024")

    if args.transport in ("vcan", "all"):
        iface = local_vcan()
        if iface:
            bench(
                f"socketcan:{iface}",
                "vcan" + (" (inside the QEMU guest)" if in_guest() else ""),
                args.count,
                args.window,
            )
        else:
            print(
                "\n== vcan: no vcan here, running in the QEMU test-bed guest (boot ~10-30 s) ==",
                flush=True,
            )
            proc = run_in_guest(
                [
                    sys.executable,
                    os.path.abspath(__file__),
                    "--transport",
                    "vcan",
                    "--count",
                    str(max(10, args.count // 7)),
                    "--window",
                    str(args.window),
                ],
                timeout=900,
            )
            reason = skip_reason(proc)
            if reason:
                print(f"vcan: {reason}")
            else:
                print(proc.stdout, end="")
                if proc.returncode != 0:
                    print(proc.stderr, file=sys.stderr)
                    return proc.returncode
    if args.transport in ("udp", "all"):
        if in_guest():
            return 0
        # the udp part runs in a child inside its own network namespace
        code = (
            "import sys; sys.argv = [sys.argv[0]] + sys.argv[1:]\n"
            f"sys.path.insert(0, {HERE!r})\n"
            "import bench_can\n"
            "from harvest.canbus.netns import enter_private_netns\n"
            "enter_private_netns()\n"
            "sys.exit(bench_can.main_udp(int(sys.argv[1]), int(sys.argv[2])))\n"
        )
        r = subprocess.run([sys.executable, "-c", code, str(args.count), str(args.window)])
        if r.returncode != 0:
            return r.returncode
    return 0


def main_udp(count, window):
    global TOOL
    TOOL = os.path.join(os.environ["HV_BUILD_DIR"], "executor", "can", "hv-can-tool")
    bench("udp:239.74.163.2:43113", "udp multicast, private network namespace", count, window)
    return 0


if __name__ == "__main__":
    sys.exit(main())
