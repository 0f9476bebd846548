#!/usr/bin/env bash
# The test command (README, .ci/run): install what is missing, build everything in Debug
# with ASan + UBSan into build-test/, then run every suite (cmocka and pytest) with ctest.
# Usage: scripts/test.sh [--help] [extra ctest arguments, e.g. -L core or -R planner]
# Fails when a suite is skipped that .ci/may_skip does not list (HV_ALLOW_SKIPS=1: warn only).
set -euo pipefail
if [[ "${1:-}" == "--help" || "${1:-}" == "-h" ]]; then
  sed -n '2,5p' "$0" | sed 's/^# \{0,1\}//'
  exit 0
fi
root=$(cd "$(dirname "$0")/.." && pwd)
build="$root/build-test"

"$root/scripts/setup.sh"
echo "test: configuring $build (Debug, ASan+UBSan)"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DHV_SANITIZE=ON >/dev/null
echo "test: building"
cmake --build "$build" -j"$(nproc)"
echo "test: running ctest"
cd "$build"
# A leak in a test program is a failure; the Python interpreter itself is not sanitized.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
# A skipped suite is a check that did not run: each one is named, and the command fails
# unless .ci/may_skip lists it (a test this machine may lack the means for, with why) or
# HV_ALLOW_SKIPS=1 (a developer's machine without vcan, QEMU, ...).
log=$(mktemp)
trap 'rm -f "$log"' EXIT
set +e
ctest --output-on-failure --timeout 900 "$@" | tee "$log"
rc=${PIPESTATUS[0]}
set -e
skipped=$(sed -n 's/^[[:space:]]*[0-9]* - \([^ ]*\) (Skipped)$/\1/p' "$log")
allowed=$(sed -e 's/#.*//' -e '/^[[:space:]]*$/d' "$root/.ci/may_skip" | awk '{print $1}')
required=()
for t in $skipped; do
  if ! grep -qx "$t" <<<"$allowed"; then
    required+=("$t")
  fi
done
if ((${#required[@]})); then
  echo "test: skipped, though not listed in .ci/may_skip: ${required[*]}" >&2
  if [[ "${HV_ALLOW_SKIPS:-0}" != 1 ]]; then
    echo "test: FAILED: a required check did not run (HV_ALLOW_SKIPS=1 accepts that)" >&2
    exit $((rc ? rc : 1))
  fi
fi
exit "$rc"
