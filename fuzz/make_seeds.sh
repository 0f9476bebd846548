#!/usr/bin/env bash
# Write the seed corpora of the fuzz targets (fuzz/corpus/<target>/seed-*) from files the
# product itself writes: the config, a cost table by costgen (coarse grid, so it is small),
# a fruit map by `python -m harvest scenario`, plans by harvest-plan and make-test-plan,
# journals by harvest-exec against the simulator (the whole run's also becomes
# tests/reliability/data/run.journal, for the power-loss test), datagrams packed by python-can.
# Usage: fuzz/make_seeds.sh [BUILD_DIR]   (a Release build with tools; default build/)
# Reproducers of fixed crashes (fuzz/corpus/<target>/crash-*) are kept as they are.
set -euo pipefail
if [[ "${1:-}" == "--help" || "${1:-}" == "-h" ]]; then
  sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'
  exit 0
fi
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
py="$root/.venv/bin/python"
corpus="$root/fuzz/corpus"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

for t in config cost_table fruit_map plan_json exec_plan journal exec_step udp_wire exec_online \
  plan_upload slcan; do
  mkdir -p "$corpus/$t"
  rm -f "$corpus/$t"/seed-*
done

cp "$root/config/harvest.cfg" "$corpus/config/seed-harvest.cfg"

# a cost table of a coarse grid (10 cm, 45 deg): a real file of a few KB
sed -e 's/^grid.step = .*/grid.step = 0.1/' -e 's/^grid.yaw_step_deg = .*/grid.yaw_step_deg = 45/' \
  "$root/config/harvest.cfg" > "$tmp/coarse.cfg"
"$build/tools/costgen" --config "$tmp/coarse.cfg" --side left --out "$corpus/cost_table/seed-left.bin" --quiet
"$build/tools/costgen" --config "$tmp/coarse.cfg" --side right --out "$corpus/cost_table/seed-right.bin" --quiet

# a fruit map (first byte: 0 range-checked, 1 not) and the plans of it
"$py" -m harvest scenario --left 6 --alpha 1 --seed 3 --out "$tmp/map.csv"
{ printf '\0'; cat "$tmp/map.csv"; } > "$corpus/fruit_map/seed-map-checked"
{ printf '\1'; cat "$tmp/map.csv"; } > "$corpus/fruit_map/seed-map-unchecked"
for m in milp fov serial; do
  "$build/planner/harvest-plan" --config "$root/config/harvest.cfg" --fruits "$tmp/map.csv" \
    --method "$m" --out "$tmp/plan-$m.json" > /dev/null 2>&1
  cp "$tmp/plan-$m.json" "$corpus/plan_json/seed-plan-$m.json"
  cp "$tmp/plan-$m.json" "$corpus/exec_plan/seed-plan-$m.json"
done
cp "$root/fuzz/data/plan.json" "$corpus/plan_json/seed-test-plan.json"
cp "$root/fuzz/data/plan.json" "$corpus/exec_plan/seed-test-plan.json"

# journals of fuzz/data/plan.json (the plan the journal target replays against)
HV_BUILD_DIR="$build" HV_SOURCE_DIR="$root" "$py" "$root/fuzz/seed_journals.py" "$tmp/j"
# the power-loss test (tests/reliability) cuts and damages the whole run's journal
tail -c +2 "$tmp/j/full-0" > "$root/tests/reliability/data/run.journal"
for f in "$tmp"/j/*; do cp "$f" "$corpus/journal/seed-$(basename "$f")"; done

# the step function: a whole run of well-behaved nodes (op 5), with the operator's clear,
# an operator stop part way, and a resume with every pick's cut journalled
"$py" - "$corpus/exec_step" <<'PY'
import sys, os
out = sys.argv[1]
def put(name, data):
    with open(os.path.join(out, "seed-" + name), "wb") as f:
        f.write(bytes(data))
put("good-run", [0] + [5] * 30)
put("good-run-clear", [1] + [5] * 30)
put("stopped", [0] + [5] * 8 + [6] + [5] * 5)
put("journal-failed", [0] + [5] * 6 + [7] + [5] * 5)
put("resume-cut", [2] + [1] * 12 + [5] * 30)
put("resume-release", [3] + [2] * 12 + [5] * 30)
# every node seen, the vehicle reporting a latched e-stop, time passing
put("estop-latched", [0, 2, 0, 3, 0, 2, 1, 0, 0, 2, 2, 0, 0, 3, 0, 5, 4, 0, 0x10, 0,
                      3, 1, 1, 4, 0, 0, 0, 3, 2, 1, 4, 0, 0, 0, 4, 0, 0, 0, 2, 0,
                      4, 1, 0, 0, 2, 0] + [0, 10] * 5)
# the same with the operator's clear: CLEAR_ESTOP, then the run
put("estop-cleared", [1, 2, 0, 3, 0, 2, 1, 0, 0, 2, 2, 0, 0, 3, 0, 5, 4, 0, 0x10, 0,
                      3, 1, 1, 4, 0, 0, 0, 3, 2, 1, 4, 0, 0, 0, 4, 0, 0, 0, 2, 0,
                      4, 1, 0, 0, 2, 0] + [5] * 40)
# the other plan shapes (flag bits 2-3): one stop, one stop per pick, the right arm idle
put("one-stop", [4] + [5] * 20)
put("many-stops", [8] + [5] * 120)
put("one-arm", [12] + [5] * 40)
put("many-stops-stopped", [8] + [5] * 20 + [0x16] + [5] * 10)
# the left arm faults (joint bit 0) part way, then behaves
put("arm-fault", [0] + [5] * 5 + [3, 1, 4, 4, 0, 1, 0] + [5] * 30)
# a cut fails, then the end effector reports faulted
put("ee-fail", [0] + [5] * 4 + [4, 0, 3, 1, 2, 0] + [5] * 3 + [4, 1, 4, 1, 2, 0] + [5] * 30)
PY

# inputs made by hand for the decoders of the online plan, the plan upload and SLCAN (the
# opcodes of fuzz_exec_online.c, fuzz_plan_upload.c; a serial stream for fuzz_slcan.c)
"$py" - "$corpus" <<'PY'
import sys, os
corpus = sys.argv[1]
def put(t, name, data):
    with open(os.path.join(corpus, t, "seed-" + name), "wb") as f:
        f.write(bytes(data))
# online: the planner's stops one message at a time (op 8: n, event byte), repeated, final
good = [5] * 6
put("exec_online", "grows", [0] + good + [8, 1, 40] + [5] * 25 + [8, 2, 70] + [5] * 25
    + [8, 3, 101] + [5] * 40)
put("exec_online", "repeats", [0] + good + [8, 2, 0, 8, 2, 0, 8, 1, 0] + [5] * 30 + [8, 3, 1]
    + [5] * 30)
# a stop of the input's making behind, then beyond, a fruit twice, then the source contradicted
put("exec_online", "contradicts", [0] + good + [8, 1, 0] + [9, 10, 20, 1, 0, 0, 0]
    + [9, 250, 150, 2, 1, 129, 1, 2, 0] + [5] * 20 + [8, 3, 1] + [5] * 40)
# commit lines beyond the course end and NaN, a final of 2 (refused), the bus's stop requests
put("exec_online", "events", [0] + good + [10, 0, 200, 10, 0, 253, 10, 2, 60, 10, 1, 60]
    + [5] * 10 + [0x16, 0x16, 0x26] + [5] * 10)
put("exec_online", "waits-then-stops", [0] + good + [8, 1, 30] + [5] * 30 + [6] + [5] * 10)
# the upload: whole and running, a bad CRC, a flipped bit, a lost frame, a second Begin,
# a wrong total, raw frames
put("plan_upload", "accepted-running", [1, 3, 4, 5, 2, 0, 0, 1, 3])
put("plan_upload", "bad-crc", [1, 1, 4])
put("plan_upload", "bit-flip", [1, 3, 3, 0, 3, 0, 3, 0x85, 4])
put("plan_upload", "order", [1, 3, 3, 0, 2, 5, 0, 4])
put("plan_upload", "truncated", [1, 3, 3, 0, 3, 0, 1, 3, 4, 7, 5])
put("plan_upload", "length", [1, 0, 0x10, 0, 4, 0, 0, 3, 1, 2])
put("plan_upload", "raw", [0, 0, 8] + [0] * 8 + [0, 1, 8] + [0] * 8 + [0, 3, 0x23, 1, 2, 1, 2, 0,
                                                                       4, 5])
# SLCAN: every command, frames of each kind, damage, an overrun (0xFF), frames to send
put("slcan", "stream", b"O\rS6\rs031C\rV\rN\rF\rZ1\rZ0\r\r"
    b"t1230\rt7FF8DEADBEEF00112233\rt02a2beef\rT1ABCDEF02AABB\rr7FF3\rR000000010\r"
    b"t12\rt1239\rt12G1\rT2000000000\rQ\rS9\r" + b"t" + b"1" * 40 + b"\rC\r\a\n")
put("slcan", "overrun", b"O\rt0212AB\xffCC\rt0221FF\r\xff\r")
put("slcan", "frames", [0x23, 0x01, 0, 0, 3, 0, 1, 2, 3, 0, 0, 0, 0, 0,
                        0xEF, 0xCD, 0xAB, 0x01, 8, 1] + list(range(8))
    + [0x7F, 0x07, 0, 0, 2, 2] + [0] * 8)
PY

# datagrams as python-can's udp_multicast packs them: the DBC's frames and the kinds of
# frame a bus may carry (error, remote, extended, CAN FD)
"$py" - "$corpus/udp_wire" <<'PY'
import sys, os
import can
from can.interfaces.udp_multicast.utils import pack_message
out = sys.argv[1]
msgs = {
    "heartbeat": can.Message(arbitration_id=0x41, data=[0, 0, 0xE8, 3, 1], is_extended_id=False),
    "status": can.Message(arbitration_id=0x63, data=[1, 1, 1, 7, 3], is_extended_id=False),
    "estop": can.Message(arbitration_id=0x00, data=[1, 0], is_extended_id=False),
    "error": can.Message(arbitration_id=0x4, is_error_frame=True, data=[0] * 8, is_extended_id=False),
    "remote": can.Message(arbitration_id=0x123, is_remote_frame=True, dlc=2, is_extended_id=False),
    "extended": can.Message(arbitration_id=0x1ABCDEF, data=[1, 2, 3], is_extended_id=True),
    "fd": can.Message(arbitration_id=0x10, data=list(range(12)), is_fd=True, is_extended_id=False),
}
for i, (name, m) in enumerate(msgs.items()):
    m.timestamp = 1765000000.0 + i
    with open(os.path.join(out, "seed-" + name), "wb") as f:
        f.write(pack_message(m))
PY
for t in "$corpus"/*; do echo "make_seeds: $(basename "$t"): $(ls "$t" | wc -l) files"; done
