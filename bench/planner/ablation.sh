#!/bin/sh
# Ablation of the MILP's improvements (planner/SOLVER.md): the default solver, then the
# default with one choice switched, on the same instances in the same run.
# usage: bench/planner/ablation.sh BUILD_DIR [ALPHAS] [SEEDS] [LIMIT_S] [MODEL]
set -eu
if [ "${1:-}" = "--help" ] || [ $# -lt 1 ]; then
    echo "usage: $0 BUILD_DIR [ALPHAS=1,4] [SEEDS=3] [LIMIT_S=10] [MODEL=product|paper]"
    echo "Runs bench_milp once per variant and prints each variant's summary rows."
    exit 0
fi
bench="$1/bench/planner/bench_milp"
alphas="${2:-1,4}"
seeds="${3:-3}"
limit="${4:-10}"
model="${5:-product}"
[ -x "$bench" ] || { echo "ablation.sh: $bench not built" >&2; exit 1; }
# the default (branch-and-price), its incumbent, interval branching (or its pseudocosts),
# tailing off (or only its branching of stalled masters the incumbent does not prune), the
# binding-arm weighting of fruit splits, the workers' balancing or their warm starts
# switched off, then
# GLPK's branch-and-cut on the paper's model (algorithm=0) and that with one of its
# choices switched
c="--set algorithm=0"
for variant in \
    "" \
    "--set heuristic_incumbent=0" \
    "--set interval_branching=0" \
    "--set iv_pseudocost=0" \
    "--set tail_off_ms=0" \
    "--set tail_off_open=0" \
    "--set binding_splits=0" \
    "--set balance_workers=0" \
    "--set warm_transfer=0" \
    "$c" \
    "$c --set link_disaggregated=0" \
    "$c --set link_disaggregated=2" \
    "$c --set heuristic_incumbent=0" \
    "$c --set polish_work=0" \
    "$c --set pattern_cuts=-1" \
    "$c --set glpk_cuts=15" \
    "$c --set glpk_cuts_phase2=0" \
    "$c --set pcost_branching=1" \
    "$c --set backtracking=2"; do
    echo "== variant: ${variant:-default}"
    # shellcheck disable=SC2086
    "$bench" --alphas "$alphas" --seeds "$seeds" --models "$model" --highs-seeds 0 \
        --time-limit "$limit" --no-baselines $variant 2>/dev/null |
        sed -n '/^# Summary/,$p' | tail -n +3
done
