"""The harvest CAN protocol as loaded by cantools from executor/can/harvest.dbc.

IDs are `(node_id << 5) | command` (11-bit, ODrive CANSimple style). The node and
command numbers below name what the DBC already encodes; `Protocol` checks at load time
that every message of the DBC agrees with them, so a DBC edit that breaks the layout
fails loudly instead of being silently misrouted.

Typical use (simulator side):

    proto = load()
    msg = proto.message("LeftArmSetpoint")          # cantools Message
    data = proto.encode("LeftArmSetpoint", {...})  # bytes, strict range check
    name, fields = proto.decode(frame_id, data)     # -> ("LeftArmSetpoint", {...})
    proto.name_for("left_arm", "setpoint")          # -> "LeftArmSetpoint"
"""

import os

import cantools

# host/harvest/canbus/protocol.py -> repository root is four levels up.
_ROOT = os.path.dirname(
    os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
DBC_PATH = os.environ.get("HV_CAN_DBC", os.path.join(_ROOT, "executor", "can", "harvest.dbc"))

PROTOCOL_VERSION = 1  # the ProtocolVersion every heartbeat carries

BROADCAST_NODE = 0
# node name -> (node id, DBC message-name prefix)
NODES = {
    "executor": (1, "Executor"),
    "vehicle": (2, "Vehicle"),
    "left_arm": (3, "LeftArm"),
    "right_arm": (4, "RightArm"),
}
# command name -> (command number, DBC message-name suffix)
COMMANDS = {
    "estop": (0, "Estop"),  # broadcast node only: the whole message name is "Estop"
    "heartbeat": (1, "Heartbeat"),
    "command": (2, "Command"),
    "status": (3, "Status"),
    "setpoint": (4, "Setpoint"),  # arms
    "move": (4, "Move"),  # vehicle
    "joint_state": (5, "JointState"),
    "joint_velocity": (6, "JointVelocity"),
    "ee_command": (7, "EeCommand"),
    "ee_status": (8, "EeStatus"),
    "plan_begin": (9, "PlanBegin"),  # executor: the plan upload (firmware/)
    "plan_data": (10, "PlanData"),
    "plan_status": (11, "PlanStatus"),
}


def frame_id(node_id, command):
    """Standard 11-bit id of `command` (0..31) on node `node_id` (0..63)."""
    if not 0 <= node_id < 64 or not 0 <= command < 32:
        raise ValueError(f"node_id {node_id} / command {command} outside 6/5 bits")
    return (node_id << 5) | command


def split_id(can_id):
    """(node_id, command) of an 11-bit id."""
    return can_id >> 5, can_id & 0x1F


class ProtocolError(ValueError):
    """The DBC disagrees with the id layout, or a frame does not belong to it."""


class Protocol:
    """The loaded DBC with lookups by message name, frame id and (node, kind)."""

    def __init__(self, path=DBC_PATH):
        self.path = path
        self.db = cantools.database.load_file(path, strict=True)
        self._by_name = {m.name: m for m in self.db.messages}
        self._by_id = {m.frame_id: m for m in self.db.messages}
        self._check_layout()

    def _check_layout(self):
        prefixes = {prefix: node_id for node_id, prefix in NODES.values()}
        suffix_cmds = {}
        for number, suffix in COMMANDS.values():
            suffix_cmds[suffix] = number
        for m in self.db.messages:
            where = f"{self.path}: message {m.name}"
            if m.is_extended_frame:
                raise ProtocolError(f"{where}: extended id, protocol uses 11-bit ids")
            node_id, command = split_id(m.frame_id)
            if m.name == "Estop":
                expected = frame_id(BROADCAST_NODE, 0)
            else:
                prefix = next((p for p in prefixes if m.name.startswith(p)), None)
                suffix = m.name[len(prefix) :] if prefix else None
                if prefix is None or suffix not in suffix_cmds:
                    raise ProtocolError(f"{where}: name is not <Node><Kind> of protocol.py")
                expected = frame_id(prefixes[prefix], suffix_cmds[suffix])
            if m.frame_id != expected:
                raise ProtocolError(
                    f"{where}: frame id 0x{m.frame_id:03x}, layout says "
                    f"0x{expected:03x} (node {node_id}, command {command})"
                )

    @property
    def messages(self):
        """Every cantools Message of the DBC, in file order."""
        return list(self.db.messages)

    def message(self, name):
        """cantools Message by DBC name, e.g. "RightArmStatus"."""
        try:
            return self._by_name[name]
        except KeyError:
            raise ProtocolError(f"{self.path}: no message named '{name}'") from None

    def by_id(self, can_id):
        """cantools Message by frame id, or None for an id outside the protocol."""
        return self._by_id.get(can_id)

    def name_for(self, node, kind):
        """DBC name of `kind` ("setpoint", "status", ...) on `node` ("left_arm", ...)."""
        if kind == "estop":
            return "Estop"
        if node not in NODES:
            raise ProtocolError(f"unknown node '{node}' (known: {', '.join(NODES)})")
        if kind not in COMMANDS:
            raise ProtocolError(f"unknown message kind '{kind}' (known: {', '.join(COMMANDS)})")
        name = NODES[node][1] + COMMANDS[kind][1]
        self.message(name)
        return name

    def node_of(self, can_id):
        """Node name an id belongs to ("broadcast" for node 0), None if unknown."""
        node_id, _ = split_id(can_id)
        if node_id == BROADCAST_NODE:
            return "broadcast"
        return next((n for n, (i, _) in NODES.items() if i == node_id), None)

    def encode(self, name, signals, scaling=True):
        """Frame payload for `name`; raises on a missing or out-of-range signal."""
        return self.message(name).encode(signals, scaling=scaling, strict=True)

    def decode(self, can_id, data, decode_choices=False, scaling=True):
        """(message name, signals) of a received frame; ProtocolError if unknown."""
        m = self.by_id(can_id)
        if m is None:
            raise ProtocolError(f"frame id 0x{can_id:03x} is not in {self.path}")
        return m.name, m.decode(bytes(data), decode_choices=decode_choices, scaling=scaling)

    def unlisted_choice(self, name, signals):
        """(signal, value) of the first enumerated signal of message `name` whose value in
        `signals` (decoded with decode_choices=False) the DBC does not list, else None."""
        for sig in self.message(name).signals:
            if sig.choices and signals.get(sig.name) not in sig.choices:
                return sig.name, signals.get(sig.name)
        return None

    def choices(self, name, signal):
        """{value: label} of an enum signal, e.g. choices("LeftArmStatus", "State")."""
        sig = self.message(name).get_signal_by_name(signal)
        return {int(k): str(v) for k, v in (sig.choices or {}).items()}

    def value_of(self, name, signal, label):
        """Numeric value of an enum label, e.g. value_of("VehicleCommand", "Command", "HOME")."""
        for value, text in self.choices(name, signal).items():
            if text == label:
                return value
        raise ProtocolError(f"{self.path}: {name}.{signal} has no value '{label}'")


_CACHE = {}


def load(path=DBC_PATH):
    """The protocol from `path` (default: the repository's DBC), loaded once per path."""
    if path not in _CACHE:
        _CACHE[path] = Protocol(path)
    return _CACHE[path]
