"""Journals for the journal fuzz target's seed corpus, written by harvest-exec itself:
the plan of fuzz/data/plan.json run against the simulator over udp_multicast in a
private network namespace, once to the end and once stopped (SIGTERM) after three
outcomes. Usage: python fuzz/seed_journals.py OUT_DIR (HV_BUILD_DIR: the build to use)."""

import os
import signal
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests", "executor"))
import exec_hil as H  # noqa: E402

SCALE = 20.0


def main():
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(sys.argv) == 2 else 2
    out = sys.argv[1]
    missing = H.enter_udp_netns()
    if missing:
        print("seed_journals: cannot run: " + "; ".join(missing), file=sys.stderr)
        return 1
    plan = os.path.join(HERE, "data", "plan.json")
    with tempfile.TemporaryDirectory() as tmp:
        sim = H.Sim(tmp, SCALE)
        try:
            full = os.path.join(tmp, "full.journal")
            proc, _ = H.run_exec(plan, full, os.path.join(tmp, "s1.json"), SCALE)
            if proc.returncode != 0:
                print(proc.stderr, file=sys.stderr)
                return 1
        finally:
            sim.stop()
        sim = H.Sim(tmp, SCALE)
        try:
            part = os.path.join(tmp, "stopped.journal")
            p = H.start_exec(plan, part, os.path.join(tmp, "s2.json"), SCALE)
            H.wait_for(
                lambda: os.path.exists(part) and open(part, "rb").read().count(b"\nF ") >= 3, 60
            )
            p.send_signal(signal.SIGTERM)
            p.communicate(timeout=30)
        finally:
            sim.stop()
        os.makedirs(out, exist_ok=True)
        for name in ("full", "stopped"):
            with open(os.path.join(tmp, name + ".journal"), "rb") as f:
                data = f.read()
            # flag byte 0: as written; 1: re-signed by the target (same text)
            for flag in (0, 1):
                with open(os.path.join(out, f"{name}-{flag}"), "wb") as f:
                    f.write(bytes([flag]) + data)
    return 0


if __name__ == "__main__":
    sys.exit(main())
