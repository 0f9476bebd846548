#!/usr/bin/env bash
# The fault campaign on the paper-default row (docs/RELIABILITY.md): the scenario of
# scripts/demo.sh (uniform, m^L = 50, alpha = 1), its MILP plan, then harvest-exec against
# the simulator over udp_multicast in a private network namespace, once without faults and
# once per fault, each run resumed from its journal (tests/reliability/fault_campaign.py).
# Judged from the simulator's record; prints the table and writes it into
# docs/RELIABILITY.md. Records, journals and summaries stay in build/faults/.
# Usage: scripts/faults.sh [--kills N] [--seed S] [--time-scale K] [--no-doc]
set -euo pipefail
if [[ "${1:-}" == "--help" || "${1:-}" == "-h" ]]; then
  sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'
  exit 0
fi
root=$(cd "$(dirname "$0")/.." && pwd)
kills=20 seed=43 scale=20 doc=(--doc "$root/docs/RELIABILITY.md")
while (($#)); do
  case "$1" in
    --kills) kills=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --time-scale) scale=$2; shift 2 ;;
    --no-doc) doc=(); shift ;;
    *) echo "faults.sh: unknown option '$1' (--help)" >&2; exit 2 ;;
  esac
done
build="$root/build"
py="$root/.venv/bin/python"
export PYTHONPATH="$root/host" HV_BUILD_DIR="$build" HV_SOURCE_DIR="$root"

"$root/scripts/setup.sh" > /dev/null
[[ -f "$build/build.ninja" ]] || cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$build" -j2 > /dev/null

out="$build/faults"
rm -rf "$out"
mkdir -p "$out"
"$py" -m harvest scenario --distribution uniform --left 50 --alpha 1 --seed 1 --out "$out/fruits.csv"
"$build/planner/harvest-plan" --config "$root/config/harvest.cfg" --fruits "$out/fruits.csv" \
  --method milp --time-limit 20 --out "$out/plan.json" > "$out/plan.log" 2>&1
"$py" "$root/tests/reliability/fault_campaign.py" --plan "$out/plan.json" --kills "$kills" \
  --seed "$seed" --time-scale "$scale" --work "$out" --json "$out/faults.json" "${doc[@]}"
