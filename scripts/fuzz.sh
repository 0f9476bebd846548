#!/usr/bin/env bash
# Build the libFuzzer targets (build-fuzz/: clang, ASan + UBSan, -DHV_FUZZ=ON) and run each
# for SECONDS (default 60), one after the other; print per target the executions, the
# coverage (edges, features) and the crashes found. Each target starts from its corpus in
# fuzz/corpus/<target> (seeds and the reproducers of fixed crashes); what it adds is kept in
# build-fuzz/corpus/<target>, crashes in build-fuzz/crashes/<target>/ (copy one into
# fuzz/corpus/<target>/ with its fix, so it stays a regression test).
# Usage: scripts/fuzz.sh [--runs N] [SECONDS] [TARGET...]   (targets: fuzz/CMakeLists.txt)
#   --runs N   stop a target after N executions when that comes before SECONDS
set -euo pipefail
if [[ "${1:-}" == "--help" || "${1:-}" == "-h" ]]; then
  sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'
  exit 0
fi
root=$(cd "$(dirname "$0")/.." && pwd)
runs=-1
if [[ "${1:-}" == "--runs" ]]; then
  runs=${2:?--runs needs a number}
  [[ "$runs" =~ ^[0-9]+$ ]] || { echo "fuzz.sh: --runs must be a whole number, got '$runs'" >&2; exit 2; }
  shift 2
fi
secs=${1:-60}
shift || true
[[ "$secs" =~ ^[0-9]+$ ]] || { echo "fuzz.sh: SECONDS must be a whole number, got '$secs'" >&2; exit 2; }
build="$root/build-fuzz"

command -v clang > /dev/null || { echo "fuzz.sh: clang missing: run scripts/setup.sh" >&2; exit 1; }
if [[ ! -f "$build/build.ninja" ]]; then
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug \
    -DHV_FUZZ=ON -DHV_WITH_TOOLS=OFF -DHV_WITH_LCM=OFF -DHV_BUILD_TESTS=OFF > /dev/null
fi
cmake --build "$build" -j2 > "$build/fuzz-build.log" 2>&1 || { tail -30 "$build/fuzz-build.log"; exit 1; }

targets=("$@")
if ((${#targets[@]} == 0)); then
  for d in "$root"/fuzz/corpus/*/; do
    t=$(basename "$d")
    [[ -x "$build/fuzz/fuzz_$t" ]] && targets+=("$t")
  done
fi

printf '%-12s %12s %10s %8s %8s %8s\n' target executions exec/s edges features crashes
status=0
for t in "${targets[@]}"; do
  exe="$build/fuzz/fuzz_$t"
  [[ -x "$exe" ]] || { echo "fuzz.sh: no target '$t' ($exe)" >&2; exit 2; }
  work="$build/corpus/$t" crashes="$build/crashes/$t"
  mkdir -p "$work" "$crashes"
  log="$build/fuzz-$t.log"
  # new inputs go to the first folder (the working corpus); fuzz/corpus is read only
  start=$(date +%s.%N)
  "$exe" -max_total_time="$secs" -runs="$runs" -print_final_stats=1 -artifact_prefix="$crashes/" \
    -timeout=10 -rss_limit_mb=2048 "$work" "$root/fuzz/corpus/$t" > "$log" 2>&1 || true
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+' "$log" | tail -1)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<< "$last")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<< "$last")
  rate=$(awk -v n="${execs:-0}" -v t0="$start" -v t1="$(date +%s.%N)" 'BEGIN { printf "%d", n / (t1 - t0) }')
  n_crash=$(find "$crashes" -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  printf '%-12s %12s %10s %8s %8s %8s\n' "$t" "${execs:-?}" "$rate" "${cov:-?}" "${ft:-?}" "$n_crash"
  if ((n_crash > 0)); then
    status=1
    grep -m1 -E 'ERROR: |property broken' "$log" | sed 's/^/             /' || true
  fi
done
exit $status
