#!/usr/bin/env bash
# Run the benchmarks and print their figures; each compares against a baseline measured in
# the same run. Release build in build/. Usage: scripts/bench.sh [--help] [--quick] [core|planner|can|executor|online|firmware ...]
# (default: all six; planner ~25 min, online ~15 min, firmware ~6). Timings depend on the machine's load: run it on a quiet machine.
# --quick: the planner's smoke run (bench_milp --quick: one instance per model, HiGHS beside it); the others run in full.
set -euo pipefail
if [[ "${1:-}" == "--help" || "${1:-}" == "-h" ]]; then
  sed -n '2,5p' "$0" | sed 's/^# \{0,1\}//'
  exit 0
fi
quick=()
if [[ "${1:-}" == "--quick" ]]; then
  quick=(--quick)
  shift
fi
root=$(cd "$(dirname "$0")/.." && pwd)
build="$root/build"
which=("$@")
((${#which[@]})) || which=(core planner can executor online firmware)

"$root/scripts/setup.sh" >/dev/null
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j"$(nproc)" >/dev/null
export HV_BUILD_DIR="$build" HV_SOURCE_DIR="$root"
for b in "${which[@]}"; do
  echo "=== bench: $b ==="
  case "$b" in
    core) "$build/bench/core/bench_costtab" --config "$root/config/harvest.cfg" ;;
    planner) "$build/bench/planner/bench_milp" "${quick[@]}" ;;
    can) "$root/.venv/bin/python" "$root/bench/can/bench_can.py" ;;
    executor) cmake --build "$build" --target bench_executor ;;
    online) "$build/bench/planner/bench_online" ;;
    firmware) "$root/.venv/bin/python" "$root/bench/firmware/bench_fw_run.py" ;;
    *) echo "bench: unknown benchmark '$b' (core, planner, can, executor, online, firmware)" >&2; exit 2 ;;
  esac
done
