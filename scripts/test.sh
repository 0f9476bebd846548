#!/usr/bin/env bash
# The test command (README, .ci/run): install what is missing, build everything in Debug
# with ASan + UBSan into build-test/, then run every suite (cmocka and pytest) with ctest.
# Usage: scripts/test.sh [--help] [extra ctest arguments, e.g. -L core or -R planner]
set -euo pipefail
if [[ "${1:-}" == "--help" || "${1:-}" == "-h" ]]; then
  sed -n '2,4p' "$0" | sed 's/^# \{0,1\}//'
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
ctest --output-on-failure --timeout 900 "$@"
