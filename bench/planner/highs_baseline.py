"""Solve an exported planner model (CPLEX LP, `harvest-plan --export-lp`) with HiGHS.

The independent baseline of bench_milp: the same model file the planner exports, HiGHS's
own defaults except the stopping rule (the planner's: a relative gap, and an absolute gap
just under 1 ms, which with whole-ms pick costs is a proof too), the thread count and the
time limit. Prints one line: status (optimal, or HiGHS's word for why it stopped),
objective (s), dual bound (s), wall time (s), branch-and-bound nodes. Exit 0 when HiGHS
ran, 2 on a usage error, 3 when highspy is missing or the file cannot be read.
"""

import argparse
import sys
import time


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("lp", help="the model, CPLEX LP format")
    ap.add_argument("--time-limit", type=float, required=True, help="s")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--rel-gap", type=float, default=1e-6)
    ap.add_argument("--abs-gap", type=float, default=0.000999, help="s")
    a = ap.parse_args(argv)
    try:
        import highspy
    except ImportError as e:
        print(f"highs_baseline: highspy is not installed ({e})", file=sys.stderr)
        return 3
    h = highspy.Highs()
    h.setOptionValue("output_flag", False)
    if h.readModel(a.lp) != highspy.HighsStatus.kOk:
        print(f"highs_baseline: {a.lp}: HiGHS cannot read it", file=sys.stderr)
        return 3
    h.setOptionValue("time_limit", a.time_limit)
    h.setOptionValue("threads", a.threads)
    h.setOptionValue("mip_rel_gap", a.rel_gap)
    h.setOptionValue("mip_abs_gap", a.abs_gap)
    t0 = time.monotonic()
    h.run()
    t = time.monotonic() - t0
    info = h.getInfo()
    status = h.getModelStatus()
    st = highspy.HighsModelStatus
    words = {st.kOptimal: "optimal", st.kTimeLimit: "time_limit", st.kInfeasible: "infeasible"}
    word = words.get(status, h.modelStatusToString(status).lower().replace(" ", "_"))
    obj, bound = info.objective_function_value, info.mip_dual_bound
    print(f"{word} {obj:.6f} {bound:.6f} {t:.3f} {info.mip_node_count}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
