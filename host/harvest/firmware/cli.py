"""python -m harvest firmware run: a whole row with harvest-fw.elf in QEMU on the
simulator's bus, the plan uploaded over the bus, and a summary from the simulator's own
record (scripts/demo.sh --target firmware). Run it inside a private network namespace
(unshare -rn): QEMU's serial port and the multicast bus stay on its loopback. The
firmware's journal is a host file (semihosting, standing for the board's flash): fresh in
the output folder for each run, or --journal FILE, kept across runs, so a run started
again on the same file resumes the row the last one left."""

import json
import os
import struct
import subprocess
import sys
import time

from ..cmdline import EXIT_FAILURE, EXIT_USAGE, Parser, error, os_error
from . import rig

PROG = "harvest-stack firmware"
EXIT_NOT_DONE = 3  # the row did not end in row_done (firmware.json: the phase)


def _image_makespans(image):
    """(planned, expected) makespan of a plan image (firmware/plan_image.h: header f64 17
    and 20 after the 12 leading bytes)."""
    (planned,) = struct.unpack_from("<d", image, 12 + 8 * 17)
    (expected,) = struct.unpack_from("<d", image, 12 + 8 * 20)
    return planned, expected


def _events(record_path):
    with open(record_path) as f:
        return [json.loads(ln) for ln in f if ln.strip()]


def executed_makespan(record_path, plan):
    """The row's makespan in the simulator's record (s, simulated): its first accepted move
    to the vehicle's arrival at the course end; None when it never got there."""
    events = _events(record_path)
    p = plan["params"]
    course_end = p["row_start_m"] + p["row_length_m"] + p["stop_margin_m"]
    moves = [e["t"] for e in events if e["event"] == "move" and e["accepted"]]
    ends = [
        e["t"] for e in events if e["event"] == "arrived" and abs(e["position"] - course_end) < 1e-3
    ]
    return (ends[-1] - moves[0]) if moves and ends else None


def summarize(record_path, plan, image, uart_log, icount=True):
    """The run judged by the simulator's record; the firmware's own figures beside."""
    events = _events(record_path)
    planned_s, expected_s = _image_makespans(image)
    st = rig.last_status(uart_log)
    cycles = int(st.get("worst_step_cycles", 0))
    # what the firmware's journal held when the plan started (more than its header: resumed)
    jl = [ln for ln in rig.uart_lines(uart_log) if ln.startswith("harvest-fw: journal")]
    journal = rig.status_fields(jl[-1]) if jl else {}
    return {
        "phase": st.get("phase", "unknown"),
        "safe_reason": st.get("safe_reason"),
        "safe_node": st.get("safe_node"),
        "fruits_planned": sum(len(s["left"]) + len(s["right"]) for s in plan["stops"]),
        "picked": sum(1 for e in events if e["event"] == "pick"),
        "faults": sum(1 for e in events if e["event"] == "fault_injected"),
        "planned_makespan_s": planned_s,
        "expected_makespan_s": expected_s,
        "executed_makespan_s": executed_makespan(record_path, plan),
        "steps": int(st.get("steps", 0)),
        "worst_step_cycles": cycles,
        "worst_step_instructions": round(cycles / rig.CYCLES_PER_INSN) if icount else None,
        "bad_lines": int(st.get("bad_lines", 0)),
        "overruns": int(st.get("overruns", 0)),
        "journal_records_at_start": int(journal.get("records", 0)),
        "journal_outcomes_at_start": int(journal.get("outcomes", 0)),
    }


def run(a):
    from harvest.canbus import plan_upload
    from harvest.canbus.buses import open_bus

    try:
        with open(a.plan_image, "rb") as f:
            image = f.read()
        with open(a.plan) as f:
            plan = json.load(f)
        p = plan["params"]
        open(a.image, "rb").close()
    except OSError as e:
        error(f"{PROG} run", os_error(e))
        return EXIT_USAGE
    except (ValueError, KeyError, TypeError) as e:
        error(f"{PROG} run", a.plan, f"not a plan file: {e}")
        return EXIT_USAGE
    os.makedirs(a.out, exist_ok=True)
    record = os.path.join(a.out, "sim.jsonl")
    journal = a.journal or os.path.join(a.out, "fw.journal")
    stale = [os.path.join(a.out, "uart0.log")] + ([] if a.journal else [journal])
    for path in stale:  # this run's only (the UART log is appended to)
        if os.path.exists(path):
            os.remove(path)
    qemu = rig.Qemu(a.image, a.out, icount=a.icount, journal=journal)
    qemu.wait_listening()
    bridge = rig.Bridge(a.out, qemu.port)
    # the simulator's frame rate in wall time stays that of time scale 1: the serial line
    # carries every frame of the bus
    sim_log = open(os.path.join(a.out, "sim.log"), "w")
    sim = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "harvest",
            "sim",
            "--interface",
            "udp_multicast",
            "--channel",
            rig.UDP_GROUP,
            "--time-scale",
            str(a.time_scale),
            "--rate",
            str(a.rate or 50.0 / a.time_scale),
            "--vehicle-start",
            str(p["row_start_m"] - p["stop_margin_m"]),
            "--record",
            record,
        ],
        stdout=sim_log,
        stderr=subprocess.STDOUT,
    )
    try:
        with open_bus("udp") as bus:
            state = plan_upload.upload(bus, image, timeout=60)
        print(
            f"harvest firmware: plan image {len(image)} bytes uploaded, firmware {state[0]}",
            flush=True,
        )
        end = time.monotonic() + a.timeout
        while time.monotonic() < end:
            if rig.last_status(qemu.uart_log).get("phase") in ("row_done", "safe", "stopped"):
                break
            time.sleep(1.0)
        time.sleep(1.5)  # the final status line
    finally:
        if sim.poll() is None:
            sim.send_signal(2)
            sim.wait(timeout=15)
        sim_log.close()
        bridge.stop()
        qemu.stop()
    s = summarize(record, plan, image, qemu.uart_log, a.icount)
    with open(os.path.join(a.out, "firmware.json"), "w") as f:
        json.dump(s, f, indent=2)
    print(json.dumps(s, indent=2))
    return 0 if s["phase"] == "row_done" else EXIT_NOT_DONE


def main(argv=None):
    ap = Parser(prog=PROG, description=__doc__)
    sub = ap.add_subparsers(dest="cmd", required=True, metavar="COMMAND")
    r = sub.add_parser(
        "run",
        help="a row with the firmware in QEMU (inside a private netns)",
        exit_codes=(f"{EXIT_NOT_DONE} the row not done, firmware.json says how it ended",),
    )
    r.add_argument("--image", required=True, help="harvest-fw.elf")
    r.add_argument("--plan", required=True, help="the plan file (for the fruit count)")
    r.add_argument("--plan-image", required=True, help="harvest-fw-plan's image of that plan")
    r.add_argument(
        "--time-scale",
        type=float,
        default=2.0,
        help="simulated s per wall s; must match the image's (2)",
    )
    r.add_argument("--timeout", type=float, default=1800.0, help="wall s for the row (1800)")
    r.add_argument(
        "--no-icount",
        dest="icount",
        action="store_false",
        help="QEMU's clock follows the host's; the worst step is then in host "
        "time, not instructions (default: -icount shift=5)",
    )
    r.add_argument(
        "--rate",
        type=float,
        default=None,
        help="the simulator's frame rate, simulated Hz (default 50 / time scale)",
    )
    r.add_argument(
        "--journal",
        default=None,
        help="the firmware's journal file, kept across runs: a run on the file an "
        "interrupted run left resumes its row (default: a fresh OUT/fw.journal)",
    )
    r.add_argument("--out", required=True, help="folder for the record, logs, firmware.json")
    a = ap.parse_args(argv)
    try:
        return run(a)
    except OSError as e:  # QEMU not listening in time, a file of --out not written
        error(f"{PROG} run", os_error(e))
    except (RuntimeError, EOFError) as e:  # QEMU ended, the upload refused, the UART closed
        error(f"{PROG} run", str(e))
    return EXIT_FAILURE
