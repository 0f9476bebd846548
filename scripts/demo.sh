#!/usr/bin/env bash
# The end-to-end demo: set-up, Release build, cost tables, the installation-pose search,
# a paper-default scenario, the MILP plan, then the simulator and the executor on one CAN
# bus with telemetry logged and plotted, the bus recorded (BLF) and the telemetry exported to
# MCAP. Ends with fruits picked, planned vs executed makespan, faults and the files' paths.
# Usage: scripts/demo.sh [--help] [--out DIR] [--time-scale K] [--seed S] [--time-limit S]
#        scripts/demo.sh --row M [--alpha A] [--out DIR] [--time-scale K] [--seed S] [--time-limit S]
#
# --row M: online mode (DESIGN §5) on an M m row at the paper's density (25 fruits per m on
# the left, alpha times that on the right: --row 50 is 2500 fruits at alpha 1): the
# simulator's camera reveals the row ahead of the vehicle, harvest-plan-online plans it
# horizon by horizon (--time-limit per horizon, default 2 s) while harvest-exec --online
# works what is committed; both print progress (stops done of known, fruits picked, the
# robot time committed ahead, the waits for the planner). Default time scale 20 (a 50 m
# row then takes about 15 min). No telemetry plots in this mode.
# scripts/demo.sh --target firmware [--out DIR] [--time-scale K] [--seed S] [--time-limit S]
#
# --target firmware: the executor as firmware (harvest-fw.elf, firmware/README.md) in
# QEMU's mps2-an386 on the same bus over SLCAN, the plan uploaded over the bus; adds the
# image's size and its worst step (QEMU icount). Default time scale 2 (a row takes about
# 7 min): each reply crosses the serial line and python-can's bridge (~10 ms), which the
# time scale multiplies in simulated time.
#
# The bus is CAN carried over UDP multicast (python-can's udp_multicast wire format) on
# loopback inside a private network namespace (unshare -rn): this machine's kernel has no
# CAN, and the QEMU test-bed guest that has vcan0 runs code ~20x slower, too slow for a
# whole row of 100 fruits (tests/executor/test_exec_hil_vcan.py runs a short row there).
# A piece that is not built yet makes the demo stop with "MISSING PIECE: ...".
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out="$root/build/demo"
time_scale=
seed=0
time_limit=
row=
alpha=1
target=linux

if [[ "${1:-}" == "--inner" ]]; then
  inner=1; shift
elif [[ "${1:-}" == "--inner-online" ]]; then
  inner=2; shift
else
  inner=0
fi
while (($#)); do
  case "$1" in
    -h|--help) sed -n '2,28p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    --row) row=$2; shift 2 ;;
    --alpha) alpha=$2; shift 2 ;;
    --target) target=$2; shift 2
              [[ "$target" == linux || "$target" == firmware ]] || { echo "demo: --target: linux or firmware, got '$target'" >&2; exit 2; } ;;
    --out) out=$2; shift 2 ;;
    --time-scale) time_scale=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --time-limit) time_limit=$2; shift 2 ;;
    *) echo "demo: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

if [[ -n "$row" ]]; then
  time_scale=${time_scale:-20}; time_limit=${time_limit:-2}
elif [[ "$target" == firmware ]]; then
  time_scale=${time_scale:-2}; time_limit=${time_limit:-60}
else
  time_scale=${time_scale:-20}; time_limit=${time_limit:-60}
fi
py="$root/.venv/bin/python"
build="$root/build"
export HV_BUILD_DIR="$build" HV_SOURCE_DIR="$root"
lcm_url="udpm://239.255.76.67:7667?ttl=0"
group=239.74.163.2

missing() { echo "demo: MISSING PIECE: $*" >&2; exit 1; }
step() { echo; echo "=== demo: $* ==="; }

# Inside the private network namespace: multicast on its loopback, and whatever we start
# (pids) is stopped when we exit.
netns_up() {
  ip link set lo up
  ip route add 224.0.0.0/4 dev lo
  pids=()
  cleanup() { for p in "${pids[@]}"; do kill -INT "$p" 2>/dev/null || true; done; wait || true; }
  trap cleanup EXIT
}

# ---- online mode, inside the private network namespace: simulator + camera, online
# planner, executor -------------------------------------------------------------------------
if ((inner == 2)); then
  netns_up
  rm -f "$out/run.journal" "$out/planner.json" "$out/plan.json"
  # The planner runs beside the robot's processes on this machine (2 cores): it gets one
  # thread at a lower priority, and both ends of the bus 2 s before they call a node lost
  # (the DBC's 500 ms, as in the HIL tests) and the executor 1 s of wall time more on each
  # motion timeout (--latency, 0.3 s), so a busy moment is not taken for a fault.
  "$py" -m harvest sim --interface udp_multicast --channel "$group" --time-scale "$time_scale" \
        --config "$out/harvest.cfg" --fruits "$out/fruits.csv" --lcm-url "$lcm_url" \
        --exec-timeout 2 --record "$out/sim.jsonl" >"$out/sim.log" 2>&1 &
  pids+=($!)
  nice -n 10 "$build/planner/online/harvest-plan-online" --config "$out/harvest.cfg" \
      --lcm-url "$lcm_url" --threads 1 --time-limit "$time_limit" --progress 10 \
      --summary "$out/planner.json" --out "$out/plan.json" \
      2> >(tee "$out/planner.log" | grep --line-buffered -E "horizon [0-9]*0 \(|: refused: |: end: " >&2) &
  planner=$!
  set +e
  "$build/executor/harvest-exec" --online --lcm-url "$lcm_url" --config "$out/harvest.cfg" \
      --transport udp --channel "$group" --time-scale "$time_scale" --heartbeat-timeout 2 \
      --latency 1 \
      --journal "$out/run.journal" --summary "$out/executor.json" \
      2> >(tee "$out/executor.log" | grep --line-buffered -E "stop [0-9]*0 of|waiting|row_done|SAFE" >&2)
  rc=$?
  wait "$planner"
  set -e
  exit $rc
fi

# ---- inside the private network namespace: simulator, logger, executor ------------------
if ((inner == 1)); then
  netns_up
  if [[ "$target" == firmware ]]; then
    exec "$py" -m harvest firmware run --image "$root/build-fw/firmware/harvest-fw.elf" \
        --plan "$out/plan.json" --plan-image "$out/plan.img" --time-scale "$time_scale" --out "$out/firmware"
  fi
  # the vehicle waits at the start of its course (docs/PLAN_FORMAT.md: row start - stop margin)
  vstart=$("$py" -c "import json, sys; p = json.load(open(sys.argv[1]))['params']; print(p['row_start_m'] - p['stop_margin_m'])" "$out/plan.json")
  "$py" -m harvest sim --interface udp_multicast --channel "$group" --time-scale "$time_scale" --vehicle-start "$vstart" \
        --record "$out/sim.jsonl" >"$out/sim.log" 2>&1 &
  pids+=($!)
  rm -f "$out/telemetry.lcmlog" "$out/logger.ready" "$out/run.journal"
  "$py" -m harvest telemetry log --url "$lcm_url" --out "$out/telemetry.lcmlog" --until-done \
        --grace 1 --ready-file "$out/logger.ready" >"$out/logger.log" 2>&1 &
  logger=$!
  # the bus as python-can's BLF log: replay with `python -m can.player`, decode with the DBC.
  # Started as a job (set -m): a plain background command ignores SIGINT, and only SIGINT
  # makes the logger close the file properly.
  set -m
  "$py" -m can.logger -i udp_multicast -c "$group" -f "$out/bus.blf" >"$out/can_logger.log" 2>&1 &
  pids+=($!)
  set +m
  for _ in $(seq 100); do [[ -f "$out/logger.ready" ]] && break; sleep 0.1; done
  [[ -f "$out/logger.ready" ]] || { echo "demo: the telemetry logger did not start (see $out/logger.log)" >&2; exit 1; }
  set +e
  "$build/executor/harvest-exec" --plan "$out/plan.json" --config "$root/config/harvest.cfg" \
      --cost-table-left "$out/tables/costtab_left.bin" --cost-table-right "$out/tables/costtab_right.bin" \
      --transport udp --channel "$group" --time-scale "$time_scale" \
      --journal "$out/run.journal" --summary "$out/executor.json" --lcm-url "$lcm_url"
  rc=$?
  wait "$logger"
  set -e
  exit $rc
fi

# ---- on the host -----------------------------------------------------------------------
mkdir -p "$out"
step "set-up (scripts/setup.sh)"
"$root/scripts/setup.sh"

step "Release build in build/"
# every part on, whatever an earlier configure of build/ left in its cache
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DHV_WITH_TOOLS=ON \
      -DHV_WITH_GLPK=ON -DHV_WITH_EXECUTOR=ON -DHV_WITH_LCM=ON -DHV_SANITIZE=OFF >/dev/null
cmake --build "$build" -j2

[[ -x "$build/tools/costgen" ]] || missing "costgen (tools/) was not built: $build/tools/costgen"
[[ -x "$build/tools/mountopt" ]] || missing "mountopt (tools/) was not built: $build/tools/mountopt"
[[ -x "$build/planner/harvest-plan" ]] || missing "harvest-plan (planner/) was not built: $build/planner/harvest-plan"
[[ -x "$build/executor/harvest-exec" ]] || missing "harvest-exec (executor/) was not built: $build/executor/harvest-exec"
"$py" -c "import harvest.sim.cli" 2>/dev/null || missing "the simulator (host/harvest/sim) cannot be imported"
"$py" -c "import harvest.scenario.cli" 2>/dev/null || missing "the scenario generator (host/harvest/scenario) cannot be imported"
[[ -f "$build/lcm_types/python/harvest_lcm/plan_t.py" ]] || missing "the generated LCM Python types ($build/lcm_types/python)"

if [[ -n "$row" ]]; then
  [[ -x "$build/planner/online/harvest-plan-online" ]] || missing "harvest-plan-online (planner/online, needs GLPK and LCM)"
  step "online mode: a ${row} m row at the paper's density (alpha $alpha, seed $seed)"
  "$py" -m harvest scenario --distribution long --length "$row" --alpha "$alpha" --seed "$seed" \
      --out "$out/fruits.csv" --config-out "$out/harvest.cfg"
  step "simulator + camera, online planner, executor on CAN over UDP multicast and LCM in a private network namespace (time scale $time_scale, ${time_limit} s per horizon)"
  command -v unshare >/dev/null || missing "unshare (util-linux) for the private network namespace"
  set +e
  unshare -rn bash "$0" --inner-online --row "$row" --out "$out" --time-scale "$time_scale" --time-limit "$time_limit"
  exec_rc=$?
  set -e
  step "result"
  "$py" - "$out" "$exec_rc" <<'PY'
import json, os, sys
out, rc = sys.argv[1], int(sys.argv[2])
s = json.load(open(os.path.join(out, "executor.json")))
p = json.load(open(os.path.join(out, "planner.json")))
d = p["detections"]
print(f"row: {d['accepted'] + d['unreachable']} fruits seen by the camera ({d['unreachable']} unreachable); "
      f"refused: {d['outside_row']} outside_row, {d['duplicate']} duplicate, {d['late']} late, {d['bad_id']} bad_id")
print(f"planner: {p['horizons']} horizons ({p['horizons_optimal']} proven optimal), wall time per horizon "
      f"median {p['horizon_s_median']:.2f} s, max {p['horizon_s_max']:.2f} s; {p['stops']} stops committed")
print(f"executor ended in: {s['phase']}" + (f" ({s['safe_reason']})" if s['phase'] == 'safe' else ""))
print(f"fruits picked: {s['picked']} of {p['fruits_committed']} committed "
      f"(failed {s['failed']}, skipped {s['skipped']}, remaining {s['remaining']})")
print(f"waited for the planner: {s['plan_wait_first_s']:.1f} s before the first stop, "
      f"{s['plan_wait_row_s']:.1f} s in the row ({s['plan_waits']} times), simulated time")
print(f"makespan: expected by the executor {s['expected_makespan_s']:.1f} s; executed "
      f"{s['executed_makespan_s']:.1f} s ({(s['executed_makespan_s'] / s['expected_makespan_s'] - 1) * 100:+.2f} %)"
      + ("" if rc == 0 else f"; executor exit {rc}"))
for f in ("plan.json", "planner.log", "executor.log", "run.journal", "sim.jsonl"):
    print(f"  {os.path.join(out, f)}")
PY
  exit "$exec_rc"
fi

step "cost tables (costgen)"
mkdir -p "$out/tables"
"$build/tools/costgen" --config "$root/config/harvest.cfg" --side both --out-dir "$out/tables"

step "installation pose (mountopt)"
"$build/tools/mountopt" --config "$root/config/harvest.cfg" --json "$out/mountopt.json"

step "paper-default scenario: uniform, m^L = 50, alpha = 1, seed $seed"
"$py" -m harvest scenario --distribution uniform --left 50 --alpha 1 --seed "$seed" --out "$out/fruits.csv"

step "MILP plan (harvest-plan --method milp, time limit ${time_limit} s)"
"$build/planner/harvest-plan" --config "$root/config/harvest.cfg" \
    --left "$out/tables/costtab_left.bin" --right "$out/tables/costtab_right.bin" \
    --fruits "$out/fruits.csv" --method milp --time-limit "$time_limit" --out "$out/plan.json"

command -v unshare >/dev/null || missing "unshare (util-linux) for the private network namespace"
if [[ "$target" == firmware ]]; then
  step "firmware: cross build in build-fw/, plan image (harvest-fw-plan)"
  command -v arm-none-eabi-gcc >/dev/null || missing "arm-none-eabi-gcc (scripts/setup.sh installs gcc-arm-none-eabi)"
  command -v qemu-system-arm >/dev/null || missing "qemu-system-arm (scripts/setup.sh installs it)"
  cmake -S "$root" -B "$root/build-fw" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$root/cmake/arm-none-eabi.cmake" \
        -DHV_FIRMWARE=ON -DHV_PYTHON="$py" >/dev/null
  cmake --build "$root/build-fw" -j2
  "$build/firmware/harvest-fw-plan" --plan "$out/plan.json" --config "$root/config/harvest.cfg" \
      --out "$out/plan.img" --time-scale "$time_scale"
  step "simulator + harvest-fw.elf in QEMU over SLCAN, bridged to CAN over UDP multicast in a private network namespace (time scale $time_scale)"
  set +e
  unshare -rn bash "$0" --inner --target firmware --out "$out" --time-scale "$time_scale"
  exec_rc=$?
  set -e
  step "result"
  "$py" - "$out" "$exec_rc" "$(arm-none-eabi-size "$root/build-fw/firmware/harvest-fw.elf" | tail -1)" <<'PY'
import json, os, sys
out, rc, size = sys.argv[1], int(sys.argv[2]), sys.argv[3].split()
s = json.load(open(os.path.join(out, "firmware", "firmware.json")))
p = json.load(open(os.path.join(out, "plan.json")))
print("ran on: harvest-fw.elf in QEMU mps2-an386 (Cortex-M4F), SLCAN over its UART, python-can "
      "slcan + can.bridge to CAN over UDP multicast in a private network namespace")
print(f"plan: {p['method']}, solver {p['solver']['status']}, gap {p['solver']['gap']:.4g}, "
      f"{p['totals']['stops']} stops, {p['totals']['fruits_planned']} fruits "
      f"({p['totals']['fruits_unreachable']} unreachable)")
print(f"firmware ended in: {s['phase']}")
print(f"fruits picked: {s['picked']} of {s['fruits_planned']} planned (the simulator's record)")
ex = s["executed_makespan_s"]
print(f"makespan: planned {s['planned_makespan_s']:.1f} s; expected by the executor "
      f"{s['expected_makespan_s']:.1f} s; executed " + ("n/a" if ex is None else
      f"{ex:.1f} s ({(ex / s['expected_makespan_s'] - 1) * 100:+.2f} % vs expected, "
      f"{(ex / s['planned_makespan_s'] - 1) * 100:+.2f} % vs planned)"))
print(f"faults: {s['faults']} injected" + ("" if rc == 0 else f", firmware run exit {rc}"))
print(f"image (arm-none-eabi-size): text {size[0]} B, data {size[1]} B, bss {size[2]} B")
print(f"worst step: {s['worst_step_cycles']} SysTick cycles under QEMU -icount shift=5 "
      f"(= {s['worst_step_instructions']} instructions; QEMU counts instructions, not M4 cycles), "
      f"{s['steps']} steps")
for f in ("firmware/firmware.json", "firmware/sim.jsonl", "firmware/uart0.log", "plan.img"):
    print(f"  {os.path.join(out, f)}")
PY
  exit "$exec_rc"
fi

step "simulator + executor on CAN over UDP multicast in a private network namespace (time scale $time_scale)"
set +e
unshare -rn bash "$0" --inner --out "$out" --time-scale "$time_scale"
exec_rc=$?
set -e

step "telemetry plots and the run in MCAP"
"$py" -m harvest telemetry gantt "$out/telemetry.lcmlog" --out "$out/gantt.png" --out "$out/gantt.svg"
"$py" -m harvest telemetry mcap "$out/telemetry.lcmlog" --out "$out/telemetry.mcap"

step "result"
"$py" - "$out" "$exec_rc" <<'PY'
import json, os, sys
out, rc = sys.argv[1], int(sys.argv[2])
s = json.load(open(os.path.join(out, "executor.json")))
p = json.load(open(os.path.join(out, "plan.json")))
print(f"ran on: CAN over UDP multicast (python-can udp_multicast format) in a private network namespace")
print(f"plan: {p['method']}, solver {p['solver']['status']}, gap {p['solver']['gap']:.4g}, "
      f"{p['totals']['stops']} stops, {p['totals']['fruits_planned']} fruits "
      f"({p['totals']['fruits_unreachable']} unreachable)")
print(f"executor ended in: {s['phase']}" + (f" ({s['safe_reason']})" if s['phase'] == 'safe' else ""))
print(f"fruits picked: {s['picked']} of {s['fruits_planned']} planned "
      f"(failed {s['failed']}, skipped {s['skipped']}, remaining {s['remaining']})")
cost = {"cycle": "the robot's pick cycles", "one_way": "the paper's one-way G"}[p["params"]["pick_time"]]
print(f"makespan: planned {s['planned_makespan_s']:.1f} s ({cost}); expected by the executor "
      f"{s['expected_makespan_s']:.1f} s; executed {s['executed_makespan_s']:.1f} s "
      f"({(s['executed_makespan_s'] / s['expected_makespan_s'] - 1) * 100:+.2f} % vs expected, "
      f"{(s['executed_makespan_s'] / s['planned_makespan_s'] - 1) * 100:+.2f} % vs planned)")
print(f"faults: {s['faults']} recoverable arm faults" + ("" if rc == 0 else f", executor exit {rc}"))
# its work follows the simulated clock: at time scale K the run is K times faster than real time
print(f"executor CPU {s['cpu_s'] / s['wall_s'] * 100:.2f} % of a core at time scale {s['time_scale']:g}, "
      f"peak memory {s['peak_rss_kb']} KiB")
for f in ("gantt.png", "gantt.svg", "telemetry.lcmlog", "telemetry.mcap", "bus.blf", "run.journal",
          "sim.jsonl", "mountopt.json"):
    print(f"  {os.path.join(out, f)}")
PY
exit "$exec_rc"
