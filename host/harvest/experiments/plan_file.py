"""The planner's plan JSON (docs/PLAN_FORMAT.md): load it and take the figures we report."""

import json
import math
import os

PLAN_VERSION = 2  # plan/include/hv/plan.h HV_PLAN_FORMAT_VERSION


class PlanError(ValueError):
    """A plan that cannot be used: the message names the file and the field."""


def load(path):
    try:
        with open(path, encoding="utf-8") as f:
            plan = json.load(f)
    except OSError as e:
        raise PlanError(f"{path}: cannot read plan: {e.strerror}") from None
    except json.JSONDecodeError as e:
        raise PlanError(f"{path}: not JSON: {e}") from None
    if plan.get("format") != "harvest-plan":
        raise PlanError(
            f"{path}: field 'format' must be 'harvest-plan', got {plan.get('format')!r}"
        )
    if plan.get("version") != PLAN_VERSION:
        raise PlanError(
            f"{path}: field 'version' must be {PLAN_VERSION}, got {plan.get('version')!r}"
        )
    for key in ("solver", "totals", "stops"):
        if key not in plan:
            raise PlanError(f"{path}: missing field '{key}'")
    return plan


def input_path(path, plan, key):
    """The file to open for the plan's input `key` ("fruit_map", "config", ...): as written
    when absolute, else relative to the folder of the plan file at `path`, never to the
    current directory (docs/PLAN_FORMAT.md)."""
    inputs = plan.get("inputs")
    value = inputs.get(key) if isinstance(inputs, dict) else None
    if not isinstance(value, str) or not value:
        raise PlanError(f"{path}: field 'inputs.{key}' is not a path: {value!r}")
    return value if os.path.isabs(value) else os.path.join(os.path.dirname(path), value)


def _num(path, obj, section, key):
    v = obj.get(key)
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise PlanError(f"{path}: field '{section}.{key}' is not a finite number: {v!r}")
    return float(v)


def summary(path, plan):
    """The figures of one results row, from the plan's totals and solver sections."""
    t, s = plan["totals"], plan["solver"]
    gap = s.get("gap")
    out = {
        "stops": int(_num(path, t, "totals", "stops")),
        "makespan_s": _num(path, t, "totals", "makespan_s"),
        "throughput_fruit_per_s": _num(path, t, "totals", "throughput_fruit_per_s"),
        "pick_time_s": _num(path, t, "totals", "pick_time_s"),
        "stop_time_s": _num(path, t, "totals", "stop_time_s"),
        "travel_time_s": _num(path, t, "totals", "travel_time_s"),
        "fruits_planned": int(_num(path, t, "totals", "fruits_planned")),
        "fruits_unreachable": int(_num(path, t, "totals", "fruits_unreachable")),
        "runtime_s": _num(path, s, "solver", "runtime_s"),
        "status": str(s.get("status", "")),
        "gap": "" if gap is None else _num(path, s, "solver", "gap"),
        "idle_s": sum(
            float(st.get("idle_left_s", 0.0)) + float(st.get("idle_right_s", 0.0))
            for st in plan["stops"]
        ),
    }
    if s.get("time_limit_s") is not None:  # the limit the planner applied (its default too)
        out["time_limit_s"] = _num(path, s, "solver", "time_limit_s")
    return out
