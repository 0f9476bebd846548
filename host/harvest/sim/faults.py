"""Fault-injection plan: what goes wrong, where and when, from flags or a scenario file.

A fault is a dict with a "type" and its fields; the same validator reads both sources so a
flag and a file entry mean exactly the same thing. Times are simulated seconds.

  drop         fraction (0..1], direction tx|rx|both (tx), node (all)
               drop that fraction of frames (seeded, so a run is repeatable)
  delay        delay_s > 0, direction tx|rx|both (tx), node (all)
               hold frames back by delay_s of simulated time, order kept
  stall        node (an arm), joint 1..4, setpoint n >= 1 (1), fraction [0, 1) (0.5)
               on the n-th accepted setpoint the joint stops at that fraction of its way
               and the arm never reports the target reached
  joint_fault  node (an arm), joint 1..4, and one of pick k >= 1 (on the k-th CUT command),
               setpoint n >= 1 or home n >= 1 (after `at` (0.5) of the n-th accepted
               setpoint's or the n-th homing's motion time);
               kind following|limit (following): the arm goes to FAULT with that joint's bit
  silent       node (all), frames all|heartbeat (all), for_s > 0 (for ever), and one of
               after_s >= 0 or pick k >= 1 (an arm: just after its k-th pick)
               the node stops sending (everything, or only its heartbeat) from then on,
               and sends again after for_s
  estop        node (all), and one of after_s >= 0 or pick k >= 1 (an arm: just after its
               k-th pick, the fruit held): the node's own e-stop trips and latches, as an
               e-stop button wired to it would; only CLEAR_ESTOP releases it
  reject       node (an arm), setpoint n >= 1: the n-th setpoint received is refused as
               out of range (fault bit SETPOINT_REJECTED), whatever its values

Flag form: `--fault TYPE:key=value,key=value`, e.g. `--fault drop:fraction=0.1,node=left_arm`.
File form (JSON): {"seed": 7, "faults": [{"type": "drop", "fraction": 0.1}, ...]}.
"""

import json

NODES = ("vehicle", "left_arm", "right_arm")
ARMS = ("left_arm", "right_arm")
DIRECTIONS = ("tx", "rx", "both")


class FaultError(ValueError):
    """A fault that cannot be understood; the message names the source and the field."""


def _num(
    spec, key, where, default=None, lo=None, hi=None, lo_open=False, hi_open=False, integer=False
):
    if key not in spec:
        if default is None:
            raise FaultError(f"{where}: missing field '{key}'")
        return default
    raw = spec[key]
    try:
        if isinstance(raw, bool):
            raise ValueError
        value = int(raw) if integer else float(raw)
        if integer and isinstance(raw, float) and raw != int(raw):
            raise ValueError
        if integer and isinstance(raw, str) and str(int(raw)) != raw.strip():
            raise ValueError
    except (TypeError, ValueError):
        kind = "an integer" if integer else "a number"
        raise FaultError(f"{where}: field '{key}' must be {kind}, got {raw!r}") from None
    if value != value or value in (float("inf"), float("-inf")):
        raise FaultError(f"{where}: field '{key}' must be finite, got {raw!r}")
    if lo is not None and (value < lo or (lo_open and value == lo)):
        raise FaultError(
            f"{where}: field '{key}' = {value} must be {'>' if lo_open else '>='} {lo}"
        )
    if hi is not None and (value > hi or (hi_open and value == hi)):
        raise FaultError(
            f"{where}: field '{key}' = {value} must be {'<' if hi_open else '<='} {hi}"
        )
    return value


def _choice(spec, key, where, choices, default=None):
    if key not in spec:
        if default is None:
            raise FaultError(f"{where}: missing field '{key}' (one of {', '.join(choices)})")
        return default
    value = spec[key]
    if value not in choices:
        raise FaultError(f"{where}: field '{key}' = {value!r} must be one of {', '.join(choices)}")
    return value


_FIELDS = {
    "drop": {"fraction", "direction", "node"},
    "delay": {"delay_s", "direction", "node"},
    "stall": {"node", "joint", "setpoint", "fraction"},
    "joint_fault": {"node", "joint", "pick", "setpoint", "home", "kind", "at"},
    "silent": {"after_s", "pick", "node", "frames", "for_s"},
    "reject": {"node", "setpoint"},
    "estop": {"node", "after_s", "pick"},
}


def _one_of(spec, keys, where, kind):
    """The one trigger field of `keys` that `spec` has; FaultError unless exactly one."""
    given = [k for k in keys if k in spec]
    if len(given) != 1:
        names = ", ".join(f"'{k}'" for k in keys)
        raise FaultError(f"{where}: a {kind} needs exactly one of fields {names}")
    return given[0]


def validate(spec, where):
    """A normalised copy of one fault dict, or FaultError naming `where` and the field."""
    if not isinstance(spec, dict):
        raise FaultError(f"{where}: a fault must be an object with a 'type', got {spec!r}")
    kind = spec.get("type")
    if kind not in _FIELDS:
        raise FaultError(f"{where}: field 'type' = {kind!r} must be one of {', '.join(_FIELDS)}")
    unknown = sorted(set(spec) - _FIELDS[kind] - {"type"})
    if unknown:
        raise FaultError(
            f"{where}: unknown field '{unknown[0]}' for a {kind} fault "
            f"(known: {', '.join(sorted(_FIELDS[kind]))})"
        )
    out = {"type": kind}
    if kind == "drop":
        out["fraction"] = _num(spec, "fraction", where, lo=0.0, hi=1.0, lo_open=True)
        out["direction"] = _choice(spec, "direction", where, DIRECTIONS, "tx")
        out["node"] = _choice(spec, "node", where, NODES + ("all",), "all")
    elif kind == "delay":
        out["delay_s"] = _num(spec, "delay_s", where, lo=0.0, lo_open=True)
        out["direction"] = _choice(spec, "direction", where, DIRECTIONS, "tx")
        out["node"] = _choice(spec, "node", where, NODES + ("all",), "all")
    elif kind == "stall":
        out["node"] = _choice(spec, "node", where, ARMS)
        out["joint"] = _num(spec, "joint", where, lo=1, hi=4, integer=True)
        out["setpoint"] = _num(spec, "setpoint", where, 1, lo=1, integer=True)
        out["fraction"] = _num(spec, "fraction", where, 0.5, lo=0.0, hi=1.0, hi_open=True)
    elif kind == "joint_fault":
        out["node"] = _choice(spec, "node", where, ARMS)
        out["joint"] = _num(spec, "joint", where, lo=1, hi=4, integer=True)
        trigger = _one_of(spec, ("pick", "setpoint", "home"), where, kind)
        out[trigger] = _num(spec, trigger, where, lo=1, integer=True)
        if trigger == "pick":
            if "at" in spec:
                raise FaultError(f"{where}: field 'at' only applies with 'setpoint' or 'home'")
        else:
            out["at"] = _num(spec, "at", where, 0.5, lo=0.0, hi=1.0, lo_open=True, hi_open=True)
        out["kind"] = _choice(spec, "kind", where, ("following", "limit"), "following")
    elif kind == "silent":
        _trigger(spec, out, where, kind)
        out["frames"] = _choice(spec, "frames", where, ("all", "heartbeat"), "all")
        if "for_s" in spec:
            out["for_s"] = _num(spec, "for_s", where, lo=0.0, lo_open=True)
    elif kind == "reject":
        out["node"] = _choice(spec, "node", where, ARMS)
        out["setpoint"] = _num(spec, "setpoint", where, lo=1, integer=True)
    elif kind == "estop":
        _trigger(spec, out, where, kind)
    return out


def _trigger(spec, out, where, kind):
    """`node` and when: a time (any node, default all) or an arm's k-th pick."""
    if _one_of(spec, ("after_s", "pick"), where, kind) == "pick":
        out["node"] = _choice(spec, "node", where, ARMS)
        out["pick"] = _num(spec, "pick", where, lo=1, integer=True)
    else:
        out["node"] = _choice(spec, "node", where, NODES + ("all",), "all")
        out["after_s"] = _num(spec, "after_s", where, lo=0.0)


def parse_flag(text):
    """One `--fault TYPE:key=value,...` flag as a validated fault dict."""
    where = f"--fault {text!r}"
    kind, _, rest = text.partition(":")
    spec = {"type": kind.strip()}
    for item in filter(None, (p.strip() for p in rest.split(","))):
        key, eq, value = item.partition("=")
        if not eq or not key.strip():
            raise FaultError(f"{where}: expected key=value, got {item!r}")
        if key.strip() in spec:
            raise FaultError(f"{where}: field '{key.strip()}' given twice")
        spec[key.strip()] = value.strip()
    return validate(spec, where)


def load_scenario(path):
    """(seed or None, [fault dicts]) of a JSON scenario file."""
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
    except OSError as e:
        raise FaultError(f"{path}: cannot read scenario: {e.strerror}") from None
    except json.JSONDecodeError as e:
        raise FaultError(f"{path}:{e.lineno}: not valid JSON: {e.msg}") from None
    if not isinstance(doc, dict):
        raise FaultError(f"{path}: the scenario must be a JSON object with 'faults'")
    unknown = sorted(set(doc) - {"seed", "faults"})
    if unknown:
        raise FaultError(f"{path}: unknown field '{unknown[0]}' (known: seed, faults)")
    seed = None
    if "seed" in doc:
        seed = _num(doc, "seed", path, lo=0, integer=True)
    faults = doc.get("faults", [])
    if not isinstance(faults, list):
        raise FaultError(f"{path}: field 'faults' must be a list")
    return seed, [validate(spec, f"{path}: faults[{i}]") for i, spec in enumerate(faults)]


def applies(fault, node):
    """Whether a fault with a `node` field concerns `node`."""
    return fault.get("node", "all") in ("all", node)
