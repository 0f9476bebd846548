"""The generated Markdown report: our numbers beside each claim of the paper.

Every number here is computed from results.csv (and the analysis tables); the text around
it is chosen by those numbers, so the report cannot claim agreement the data does not show.
"""

import json
import math
import os
import statistics

PAPER_GAIN_LO, PAPER_GAIN_HI = 0.10, 0.20  # throughput gain of MILP over FOV (paper)
PAPER_DUAL_RATIO = 2.0  # dual arm / single arm at alpha = 1 (paper)
PAPER_RUNTIME_S = 7.0  # MILP runtime, Gurobi, AMD 7950 (paper)
PROVEN = ("optimal",)
# after a verdict that differs: where the report measures each cause (variants.causes_section)
CAUSES_POINTER = (
    " The section 'What each cause accounts for' measures each cause on the same instances."
)


def _ok(r):
    return r["status"] != "error" and r["makespan_s"] is not None


def by_instance(rows):
    """{(distribution, alpha, seed): {method: row}} of rows that produced a plan."""
    out = {}
    for r in rows:
        if _ok(r):
            out.setdefault((r["distribution"], r["alpha"], r["seed"]), {})[r["method"]] = r
    return out


def _med(v):
    return statistics.median(v) if v else math.nan


def fmt(v, nd=2):
    return "n/a" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.{nd}f}"


def pct(v):
    return "n/a" if v is None or math.isnan(v) else f"{100.0 * v:+.1f} %"


def _share(v):
    return "n/a" if v is None or math.isnan(v) else f"{100.0 * v:.1f} %"


def summary_table(rows, methods):
    alphas = sorted({r["alpha"] for r in rows})
    lines = [
        "| alpha | method | plans | stops (median) | makespan s (median) | "
        "throughput fruit/s (median) | runtime s (median / max) | status | unreachable |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for a in alphas:
        for m in methods:
            rs = [r for r in rows if r["alpha"] == a and r["method"] == m]
            ok = [r for r in rs if _ok(r)]
            if not rs:
                continue
            statuses = {}
            for r in rs:
                statuses[r["status"]] = statuses.get(r["status"], 0) + 1
            st = ", ".join(f"{k} {v}" for k, v in sorted(statuses.items()))
            rt = [r["runtime_s"] for r in ok]
            lines.append(
                f"| {a:g} | {m} | {len(ok)}/{len(rs)} | "
                f"{fmt(_med([r['stops'] for r in ok]), 1)} | "
                f"{fmt(_med([r['makespan_s'] for r in ok]), 1)} | "
                f"{fmt(_med([r['throughput_fruit_per_s'] for r in ok]), 3)} | "
                f"{fmt(_med(rt), 2)} / {fmt(max(rt) if rt else math.nan, 2)} | {st} | "
                f"{sum(r['fruits_unreachable'] or 0 for r in ok)} |"
            )
    return "\n".join(lines)


def claim_stops(inst):
    """Paper: MILP needs the fewest stops (and their number grows with alpha)."""
    n, fewest, worse = 0, 0, {"fov": [], "serial": []}
    for key, ms in sorted(inst.items()):
        if not all(m in ms for m in ("milp", "fov", "serial")):
            continue
        n += 1
        s = ms["milp"]["stops"]
        fewest += s <= min(ms["fov"]["stops"], ms["serial"]["stops"])
        for other in worse:
            if s > ms[other]["stops"]:
                worse[other].append(f"alpha {key[1]:g} seed {key[2]}")
    med = {m: {} for m in ("fov", "serial", "milp")}
    for key, ms in inst.items():
        for m in med:
            if m in ms:
                med[m].setdefault(key[1], []).append(ms[m]["stops"])
    trend = "; ".join(
        f"{m}: " + ", ".join(f"{fmt(_med(v), 1)} at alpha {a:g}" for a, v in sorted(med[m].items()))
        for m in med
    )
    text = [
        "**Paper:** MILP consistently needs the fewest stops; stops rise with alpha.",
        f"**Ours:** MILP has no more stops than both baselines on {fewest} of {n} instances; "
        f"more than FOV on {len(worse['fov'])}, more than Serial on {len(worse['serial'])}. "
        f"Median stops per method: {trend}.",
    ]
    if n and fewest == n:
        text.append("**Verdict:** holds.")
    elif n:
        why = (
            "the objective is time, not stops: one more stop costs tau = 5 s and pays off "
            "when it saves more than that in picking (G grows fast with the fruit's distance "
            "from the arm's sweet spot, see the cost figure) or in one arm waiting for the "
            "other"
        )
        per_fruit = {
            m: _med(
                [
                    ms[m]["pick_time_s"] / ms[m]["fruits_planned"]
                    for ms in inst.values()
                    if m in ms and ms[m]["fruits_planned"]
                ]
            )
            for m in ("fov", "milp")
        }
        why += (
            f"; median pick time per fruit (stop time C_p shared out): FOV "
            f"{fmt(per_fruit['fov'])} s, MILP {fmt(per_fruit['milp'])} s"
        )
        if worse["fov"]:
            why += (
                "; FOV stops once per camera window (plus a few stops for fruits no window "
                "stop reaches), whatever the pick times, so it trades long picks for few stops"
            )
        text.append(
            f"**Verdict:** differs on {n - fewest} of {n} instances. Why: {why}. "
            "The paper's FOV window is not given; a wider window means even fewer FOV "
            "stops, a narrower one more."
        )
    return "\n\n".join(text), {
        "fewest": fewest,
        "n": n,
        "more_than_fov": len(worse["fov"]),
        "more_than_serial": len(worse["serial"]),
    }


def claim_throughput(inst, rows):
    gains, per_alpha = [], {}
    for key, ms in inst.items():
        if "milp" in ms and "fov" in ms:
            g = ms["milp"]["throughput_fruit_per_s"] / ms["fov"]["throughput_fruit_per_s"] - 1.0
            gains.append(g)
            per_alpha.setdefault(key[1], []).append(g)
    med = _med(gains)
    parts = [f"alpha {a:g}: {pct(_med(v))}" for a, v in sorted(per_alpha.items())]
    fov = [r for r in rows if _ok(r) and r["method"] == "fov" and r["fov_moved"] is not None]
    moved = sum(r["fov_moved"] for r in fov)
    planned = sum(r["fruits_planned"] for r in fov)
    text = [
        "**Paper:** MILP raises throughput by 10-20 % over FOV.",
        f"**Ours:** median gain {pct(med)} over {len(gains)} instances "
        f"(range {pct(min(gains) if gains else math.nan)} to "
        f"{pct(max(gains) if gains else math.nan)}); per alpha {'; '.join(parts)}. "
        f"FOV moved {moved} of its {planned} fruits "
        f"({_share(moved / planned if planned else math.nan)}) to another stop "
        "than the one they were in view at (out of that stop's reach).",
    ]
    if not gains:
        text.append("**Verdict:** no data.")
    elif PAPER_GAIN_LO <= med <= PAPER_GAIN_HI:
        text.append("**Verdict:** holds: the median gain is inside the paper's band.")
    else:
        where = "above" if med > PAPER_GAIN_HI else "below"
        off = med - (PAPER_GAIN_HI if med > PAPER_GAIN_HI else PAPER_GAIN_LO)
        text.append(
            f"**Verdict:** differs: the median is {where} the paper's band by "
            f"{100.0 * abs(off):.1f} points. Why: the gain over FOV depends on where each "
            "arm's camera window lies and how wide it is (the paper gives neither; "
            "`experiments fov-width` sweeps both) and on the pick costs, which depend "
            "on our home pose and mount choices (config/harvest.cfg); "
            + (
                "MILP plans stopped by the time limit are feasible, not optimal: proven optima "
                "would "
                + (
                    "raise the gain further."
                    if med > PAPER_GAIN_HI
                    else "raise the gain, mostly where the balanced case is hard for GLPK."
                )
                if any(r["method"] == "milp" and r["status"] not in PROVEN for r in rows if _ok(r))
                else "every MILP plan here is proven optimal, so the difference is not the "
                "solver's."
            )
            + CAUSES_POINTER
        )
    return "\n\n".join(text), {
        "median_gain": med,
        "fov_moved": moved,
        "fov_planned": planned,
        "per_alpha": {a: _med(v) for a, v in per_alpha.items()},
    }


def _breakdown(rs):
    """Median makespan split (s): picks (sum of C_p, idle included), stops x tau, travel."""
    parts = [("picks", "pick_time_s"), ("stops", "stop_time_s"), ("travel", "travel_time_s")]
    return (
        ", ".join(
            f"{name} {fmt(_med([r[c] for r in rs if r[c] is not None]), 0)}" for name, c in parts
        )
        + f" (makespan {fmt(_med([r['makespan_s'] for r in rs]), 0)})"
    )


def claim_dual_arm(inst):
    pairs = [
        (ms["milp"], ms["serial"])
        for key, ms in inst.items()
        if key[1] == 1.0 and "milp" in ms and "serial" in ms
    ]
    ratios = [m["throughput_fruit_per_s"] / s["throughput_fruit_per_s"] for m, s in pairs]
    med = _med(ratios)
    text = [
        "**Paper:** at alpha = 1 the dual-arm robot nearly doubles the single-arm throughput.",
        f"**Ours:** MILP / Serial throughput at alpha = 1: median {fmt(med, 2)}x over "
        f"{len(ratios)} instances (range {fmt(min(ratios) if ratios else math.nan, 2)}x to "
        f"{fmt(max(ratios) if ratios else math.nan, 2)}x).",
    ]
    if not ratios:
        text.append("**Verdict:** no data at alpha = 1.")
        return "\n\n".join(text), {"median_ratio": med}
    text.append(
        f"Median makespan split in s: MILP {_breakdown([m for m, _ in pairs])}; "
        f"Serial {_breakdown([s for _, s in pairs])}."
    )
    if abs(med - PAPER_DUAL_RATIO) <= 0.2:
        text.append(f"**Verdict:** holds (within 0.2 of 2x; off by {med - PAPER_DUAL_RATIO:+.2f}).")
    else:
        text.append(
            f"**Verdict:** differs by {med - PAPER_DUAL_RATIO:+.2f} from 2x. Why (from the split "
            "above): exactly 2x would need the dual plan's picks to be half of Serial's with no "
            "waiting; but at every stop the faster arm waits for the slower one (its idle time "
            "is inside the picks), and each Serial pass places its stops for one side alone, "
            "so its picks are cheaper per fruit; the travel and stop terms do not halve either."
            + CAUSES_POINTER
        )
    return "\n\n".join(text), {"median_ratio": med}


def claim_runtime(rows):
    milp = [r for r in rows if r["method"] == "milp" and _ok(r)]
    rt = [r["runtime_s"] for r in milp]
    not_proven = [r for r in milp if r["status"] not in PROVEN]
    gaps = [r["gap"] for r in not_proven if r["gap"] is not None]
    by_alpha = {}
    for r in milp:
        by_alpha.setdefault(r["alpha"], []).append(r["runtime_s"])
    parts = [
        f"alpha {a:g}: median {fmt(_med(v))} s, max {fmt(max(v))} s"
        for a, v in sorted(by_alpha.items())
    ]
    mx = max(rt) if rt else math.nan
    per_method = ", ".join(
        f"{m} {_med([r['runtime_s'] for r in rows if r['method'] == m and _ok(r)]):.3g} s"
        for m in ("fov", "serial", "milp")
    )
    text = [
        f"**Paper:** the MILP solves within about {PAPER_RUNTIME_S:g} s (Gurobi, AMD 7950); "
        "FOV is the fastest method.",
        f"**Ours, median runtime per method:** {per_method}.",
        f"**Ours (GLPK):** max {fmt(mx)} s, median {fmt(_med(rt))} s over {len(rt)} plans; "
        f"{'; '.join(parts)}. {len(milp) - len(not_proven)} of {len(milp)} proven optimal"
        + (
            f"; {len(not_proven)} stopped early (median gap "
            f"{fmt(100.0 * _med(gaps), 2)} %, max {fmt(100.0 * max(gaps), 2)} %)"
            if not_proven and gaps
            else ""
        )
        + ".",
    ]
    if not rt:
        text.append("**Verdict:** no data.")
    elif mx <= PAPER_RUNTIME_S and not not_proven:
        text.append("**Verdict:** holds: every plan proven optimal within the paper's time.")
    else:
        text.append(
            "**Verdict:** differs: "
            f"{'the slowest plan takes ' + fmt(mx) + ' s, ' if mx > PAPER_RUNTIME_S else ''}"
            f"{len(not_proven)} plan(s) not proven optimal. Why: our exact search (branch-and-"
            "price on GLPK's simplex with subset-row cuts, planner/SOLVER.md) gets a tight root "
            "bound but closes its last fraction of a percent slowly at alpha >= 1: near-identical "
            "neighbouring stops give the LP many equivalent fractional optima, and a node costs "
            "10-300 ms (GLPK's simplex on the master with its cut rows, and the pricing that "
            "carries the cuts), so the largest instances (alpha 4) search 60-160 nodes in 10 s; "
            "our machine has 2 cores: the second improves plans and, once the plan is within 0.2 % "
            "of the bound, searches the tree too."
        )
    return "\n\n".join(text), {"max_s": mx, "not_proven": len(not_proven)}


def cost_model_text(pick_cycle):
    """The cost model a table or figure was planned in, named with its config key."""
    if pick_cycle:
        return (
            "the robot's time, a pick its whole cycle 2 t(home -> fruit) + cut + release "
            "and a stop the drive's v/a (plan.pick_cycle = 1)"
        )
    return (
        "the paper's, G = t(home -> fruit) one way and tau = vehicle.stop_penalty "
        "(plan.pick_cycle = 0)"
    )


def costs_line(pick_cycle):
    return f"*Costs: {cost_model_text(pick_cycle)}.*"


def costs_per_row_line():
    """For a table with a costs column."""
    return (
        f"*Costs: per row; plan.pick_cycle = 0 is {cost_model_text(False)}; "
        f"plan.pick_cycle = 1 is {cost_model_text(True)}.*"
    )


def _offsets_line(table, width_m):
    best = min(table, key=lambda t: t["median_gain"])
    worst = max(table, key=lambda t: t["median_gain"])
    return (
        f"| {width_m:g} | {best['offset_m']:g} | {fmt(best['fov_stops'], 1)} | "
        f"{_share(best['moved_share'])} | {pct(best['median_gain'])} | "
        f"{pct(best['min_gain'])} to {pct(best['max_gain'])} | {best['in_band']} | "
        f"{pct(worst['median_gain'])} at {worst['offset_m']:g} |"
    )


def fov_window_section(tables, main_pick_cycle, main_window):
    """The gain over FOV by FOV window placement and width in each cost model swept
    ({pick_cycle: sensitivity.gain_table(...)}): per width the best placement, and where the
    main run's window (main_window = (width, offset), m) stands."""
    models = [
        pc
        for pc in sorted(tables, key=lambda m: m != main_pick_cycle)
        if any(t["n"] for t in tables[pc])
    ]
    if not models:
        return None
    lines = [
        "| costs | FOV width (m) | best offset (m) | FOV stops (median) | FOV fruits moved | "
        "gain over FOV (median) | gain range | instances inside +10-20 % | "
        "worst placement's median gain |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    verdicts = []
    for pc in models:
        rows = [t for t in tables[pc] if t["n"]]
        for w in sorted({t["width_m"] for t in rows}):
            at_w = [t for t in rows if t["width_m"] == w]
            lines.append(f"| plan.pick_cycle = {int(pc)} " + _offsets_line(at_w, w))
        low = min(rows, key=lambda t: t["median_gain"])
        band = [t for t in rows if PAPER_GAIN_LO <= t["median_gain"] <= PAPER_GAIN_HI]
        text = (
            f"With plan.pick_cycle = {int(pc)}, FOV does best at width {low['width_m']:g} m, "
            f"offset {low['offset_m']:g} m (median gain {pct(low['median_gain'])}); the "
            f"median gain is inside the paper's band at {len(band)} of {len(rows)} windows"
        )
        main = [
            t
            for t in rows
            if main_window is not None
            and abs(t["width_m"] - main_window[0]) < 1e-9
            and abs(t["offset_m"] - main_window[1]) < 1e-9
        ]
        if main:
            best = min(
                (t for t in rows if t["width_m"] == main[0]["width_m"]),
                key=lambda t: t["median_gain"],
            )
            text += (
                f"; the main run's window ({main_window[0]:g} m wide, {main_window[1]:g} m "
                f"from the base) gives {pct(main[0]['median_gain'])}, the best placement at "
                f"that width {pct(best['median_gain'])} (offset {best['offset_m']:g} m)"
            )
        verdicts.append(text + ".")
    return "\n".join(
        [
            "#### The gain over FOV by FOV window placement and width",
            "",
            "The paper gives neither where FOV's camera looks nor how wide its view is, only "
            "that the view is smaller than the arm's reach. Each arm has its own window, its "
            "centre fov.offset from the arm's base along the row, outward, fov.width long "
            "(docs/FRAMES.md). In each cost model the MILP plans are that model's run (the MILP "
            "does not depend on the window); FOV is planned again at each (width, offset) on "
            "the same instances (`python -m harvest experiments fov-width`; the heat map below "
            "shows every median). Per width, the placement where FOV does best; 'moved' is the "
            "share of FOV's fruits in view out of reach of their stop, picked at another stop. "
            f"The main run's FOV uses {main_window[0]:g} m wide windows {main_window[1]:g} m "
            "from the base (config/harvest.cfg fov.width, fov.offset).",
            "",
            costs_per_row_line(),
            "",
            "\n".join(lines),
            "",
            " ".join(verdicts),
        ]
    )


def cost_models_section(models, main_pick_cycle):
    """MILP / Serial and MILP over FOV per alpha in each cost model planned
    ({pick_cycle: cost_models.ratios(rows)})."""
    lines = [
        "| costs | alpha | instances | MILP / Serial throughput (median) | range | "
        "MILP makespan s (median) | Serial makespan s (median) | gain over FOV (median) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    at_one = []
    for pc in sorted(models, key=lambda m: m != main_pick_cycle):
        name = f"plan.pick_cycle = {int(pc)}"
        for t in models[pc]:
            lines.append(
                f"| {name} | {t['alpha']:g} | {t['n']} | {fmt(t['dual_median'], 2)}x | "
                f"{fmt(t['dual_min'], 2)}x to {fmt(t['dual_max'], 2)}x | "
                f"{fmt(t['milp_makespan_s'], 1)} | {fmt(t['serial_makespan_s'], 1)} | "
                f"{pct(t['fov_gain_median'])} |"
            )
            if t["alpha"] == 1.0 and t["n"]:
                at_one.append(f"{fmt(t['dual_median'], 2)}x with {cost_model_text(pc)}")
    text = [
        "#### Dual arm / single arm in both cost models",
        "",
        "The same instances planned in each cost model (`python -m harvest experiments "
        "cost-models`).",
        "",
        costs_per_row_line(),
        "",
        "\n".join(lines),
    ]
    if len(models) < 2:
        text += ["", "Only the main run's cost model is planned yet."]
    if at_one:
        text += ["", f"At alpha = 1 (paper: nearly 2x): {'; '.join(at_one)}."]
    return "\n".join(text)


def sanity(inst):
    """MILP is warm-started from a heuristic: its makespan should never exceed FOV's/Serial's."""
    bad = []
    for key, ms in sorted(inst.items()):
        if "milp" not in ms:
            continue
        for other in ("fov", "serial"):
            if (
                other in ms
                and ms["milp"]["makespan_s"] > ms[other]["makespan_s"] * (1 + 1e-9) + 1e-6
            ):
                bad.append(
                    f"alpha {key[1]:g} seed {key[2]}: MILP {ms['milp']['makespan_s']:.2f} s "
                    f"> {other} {ms[other]['makespan_s']:.2f} s"
                )
    return bad


def analysis_section(path):
    """The analysis figures' numbers (analysis.json written by the analysis step), or None."""
    if not os.path.exists(path):
        return None
    with open(path, encoding="utf-8") as f:
        a = json.load(f)
    cov = a["coverage_m2"]
    lines = [
        f"Slice z = {a['z_m']:.2f} m, right arm, canopy band of one stop "
        "(|x| over the canopy depth, fruit y - stop y over the table's span):",
        "",
        "| pick mode | area of the canopy band covered (m^2) |",
        "|---|---|",
    ]
    lines += [f"| {k} | {v:.4f} |" for k, v in cov.items()]
    r = a["roughness_s"]
    lines += [
        "",
        f"Roughness of G at yaw 0 (mean |difference| between neighbouring reachable "
        f"cells): joint 3 limited {r['limited']:.4f} s, unlimited {r['free']:.4f} s. "
        "The paper reads the unlimited cost as less smooth (two IK branches meet) and "
        "keeps the elbow on one side; "
        + (
            "our numbers agree."
            if r["free"] >= r["limited"]
            else "our numbers show the opposite on this slice: with our home pose the other "
            "elbow branch is rarely the faster one, so the lifted limit mostly adds "
            "reachable cells rather than jumps."
        ),
    ]
    return "\n".join(lines)


# What each reason of a plan's unreachable list means (docs/PLAN_FORMAT.md).
WHY_TEXT = {
    "row_end": "reachable only from vehicle positions beyond the row's ends, which "
    "the candidate stops exclude (row.stops_beyond_ends = 0)",
    "height": "outside joint 1's stroke",
    "depth": "out of the arm's reach from every vehicle position",
    "yaw": "in reach, but not at its pick heading within the joint limits",
}


def unreachable_text(total, reasons):
    """The check line's explanation of the unreachable fruits, from the plans' reasons."""
    if not total:
        return "."
    parts = [
        f"{n} {why} ({WHY_TEXT.get(why, 'unknown reason')})"
        for why, n in sorted(reasons.items(), key=lambda kv: -kv[1])
    ]
    return ": " + "; ".join(parts) + ". The paper counts all m^L + m^R fruits."


def write(
    path,
    rows,
    settings_text,
    figures,
    analysis=None,
    methods=("fov", "serial", "milp"),
    unreachable_reasons=None,
    pick_cycle=False,
    fov_width=None,
    cost_models=None,
    variants=None,
    causes=None,
):
    """Write the report; `figures` maps a caption to a path (relative links are made).
    pick_cycle: the main run's cost model; fov_width, cost_models, variants, causes: the
    sections of the derived runs (fov_window_section, cost_models_section, variants.section,
    variants.causes_section), left out when None."""
    inst = by_instance(rows)
    base = os.path.dirname(os.path.abspath(path))
    c1, _ = claim_stops(inst)
    c2, _ = claim_throughput(inst, rows)
    c3, _ = claim_dual_arm(inst)
    c4, _ = claim_runtime(rows)
    bad = sanity(inst)
    errors = [r for r in rows if r["status"] == "error"]
    out = [
        "# Reproducing the paper's comparison (FOV, Serial, MILP)",
        "",
        "Generated by `python -m harvest experiments` from `results.csv` (the main run) "
        + (
            "and the derived runs' results.csv (`fov_width/`, `pick_cycle_<0|1>/`, "
            "`mount_side_by_side/`, `flat_costs/`)"
            if fov_width or cost_models or variants
            else ""
        )
        + "; every number below is computed from them.",
        "",
        "## Set-up",
        "",
        settings_text,
        "",
        "## Results by alpha and method",
        "",
        costs_line(pick_cycle),
        "",
        summary_table(rows, methods),
        "",
        "## The paper's claims beside ours",
        "",
        "Each claim is read on the main run, planned with the costs above; the tables after "
        "claims 2 and 3 add the derived runs (other FOV windows, the other cost model).",
        "",
        "### 1. Fewest stops",
        "",
        c1,
        "",
        "### 2. Throughput over FOV",
        "",
        c2,
        "",
    ]
    if fov_width:
        out += [fov_width, ""]
    out += ["### 3. Dual arm vs single arm at alpha = 1", "", c3, ""]
    if cost_models:
        out += [cost_models, ""]
    out += ["### 4. Runtime", "", c4, ""]
    for part in (variants, causes):
        if part:
            out += [part, ""]
    out += ["## Checks", ""]
    out.append(
        "- MILP makespan never above FOV's or Serial's on the same instance: "
        + (
            "yes, on every instance."
            if not bad
            else f"**no**, on {len(bad)}: " + "; ".join(bad[:5])
        )
    )
    out.append(
        f"- Planner failures: {len(errors)}"
        + (
            ""
            if not errors
            else " ("
            + "; ".join(
                f"{r['method']} alpha {r['alpha']:g} seed {r['seed']}: {r['error']}"
                for r in errors[:5]
            )
            + ")"
        )
    )
    unreachable = sum(
        r["fruits_unreachable"] or 0 for r in rows if _ok(r) and r["method"] == "milp"
    )
    out.append(
        f"- Fruits no stop can reach (left out of every plan and of its throughput): "
        f"{unreachable} over all MILP plans"
        + unreachable_text(unreachable, unreachable_reasons or {})
    )
    if analysis:
        out += ["", "## Analysis figures from our cost tables", "", analysis]
    if figures:
        out += ["", "## Figures", ""]
        for caption, p in figures.items():
            out += [f"![{caption}]({os.path.relpath(p, base)})", "", f"*{caption}*", ""]
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write("\n".join(out) + "\n")
    os.replace(tmp, path)
    return path
