"""The harvest CAN protocol as loaded by cantools from executor/can/harvest.dbc.

The DBC is the one source of every number of the protocol (DESIGN §6); this module reads
them from it and restates none:
  - ids are `(node id << KindBits) | kind`; a node's id is its NodeId attribute (the
    BroadcastNodeId for Estop), a message's name is the node's name and its kind
    ("LeftArm" + "Setpoint"), and a kind has one number on every node that has it;
  - ProtocolVersion (network attribute): what every heartbeat carries;
  - GenMsgCycleTime / TimeoutTime (message attributes): a kind's period and how long its
    receiver waits before it treats the sender as lost;
  - BitTable (signal attribute): the VAL_TABLE_ naming a bit field's bits.
`Protocol` checks at load time that the frame ids agree with the attributes, so a DBC edit
that breaks the layout fails loudly instead of being silently misrouted.

Typical use (simulator side):

    proto = load()
    msg = proto.message("LeftArmSetpoint")          # cantools Message
    data = proto.encode("LeftArmSetpoint", {...})  # bytes, strict range check
    name, fields = proto.decode(frame_id, data)     # -> ("LeftArmSetpoint", {...})
    proto.name_for("left_arm", "setpoint")          # -> "LeftArmSetpoint"
    proto.version, proto.cycle_s("heartbeat")        # -> 1, 0.1
"""

import os
import re
from typing import NamedTuple

import cantools
from cantools.database.can.c_source import camel_to_snake_case

from harvest import resources


def default_dbc_path():
    """The DBC to load when none is named: $HV_CAN_DBC, else the project's (harvest.resources:
    the source tree's executor/can/harvest.dbc or the installed package's copy)."""
    return os.environ.get("HV_CAN_DBC") or resources.path("dbc")


class Node(NamedTuple):
    id: int  # the node's NodeId attribute
    prefix: str  # its DBC name, which begins the names of its messages ("LeftArm")


class Kind(NamedTuple):
    number: int  # the low KindBits of the frame ids
    suffix: str  # what follows the node's name in a message name ("Setpoint")


def snake(name):
    """A DBC name in snake case, as cantools' C generator spells it: "LeftArm" -> "left_arm"."""
    return camel_to_snake_case(name)


class ProtocolError(ValueError):
    """The DBC disagrees with the id layout, or a frame does not belong to it."""


_LABEL = re.compile(r"[A-Z][A-Z0-9_]*")


class Protocol:
    """The loaded DBC with lookups by message name, frame id and (node, kind), and the
    protocol's numbers: version, kind_bits, broadcast_node, nodes, kinds, cycle_s,
    timeout_s, bit_tables."""

    def __init__(self, path=None):
        self.path = path or default_dbc_path()
        self.db = cantools.database.load_file(self.path, strict=True)
        self._by_name = {m.name: m for m in self.db.messages}
        self._by_id = {m.frame_id: m for m in self.db.messages}
        self.version = self._network_int("ProtocolVersion")
        self.kind_bits = self._network_int("KindBits")
        self.broadcast_node = self._network_int("BroadcastNodeId")
        self.nodes = self._read_nodes()  # {"left_arm": Node(id, "LeftArm"), ...}
        self.kinds = {}  # {"setpoint": Kind(number, "Setpoint"), ...}
        self._kind_of = {}  # message name -> kind name
        self._check_layout()
        self.cycle_ms = self._per_kind("GenMsgCycleTime")  # {"heartbeat": 100, ...}
        self.timeout_ms = self._per_kind("TimeoutTime")  # {"heartbeat": 500}
        self.bit_signals = {}  # {"ArmFault": ["LeftArmStatus.FaultBits", ...]}
        self.bit_tables = self._read_bit_tables()  # {"ArmFault": {"ESTOP": 10, ...}}

    # -- reading the attributes ----------------------------------------------------------
    def _network_int(self, name):
        attrs = self.db.dbc.attributes if self.db.dbc else {}
        if name not in attrs:
            raise ProtocolError(f'{self.path}: no network attribute {name} (BA_ "{name}" N;)')
        return int(attrs[name].value)

    def _read_nodes(self):
        nodes = {}
        for n in self.db.nodes:
            attrs = n.dbc.attributes if n.dbc else {}
            if "NodeId" not in attrs:
                raise ProtocolError(f"{self.path}: node {n.name} has no NodeId attribute")
            node_id = int(attrs["NodeId"].value)
            if node_id == self.broadcast_node or node_id >= 1 << (11 - self.kind_bits):
                raise ProtocolError(f"{self.path}: node {n.name}: NodeId {node_id} not usable")
            if any(o.id == node_id for o in nodes.values()):
                raise ProtocolError(f"{self.path}: node {n.name}: NodeId {node_id} given twice")
            nodes[snake(n.name)] = Node(node_id, n.name)
        return nodes

    def _check_layout(self):
        by_id = {node.id: node for node in self.nodes.values()}
        for m in self.db.messages:
            where = f"{self.path}: message {m.name}"
            if m.is_extended_frame:
                raise ProtocolError(f"{where}: extended id, protocol uses 11-bit ids")
            node_id, number = self.split_id(m.frame_id)
            if node_id == self.broadcast_node:
                suffix = m.name
            elif node_id in by_id and m.name.startswith(by_id[node_id].prefix):
                suffix = m.name[len(by_id[node_id].prefix) :]
            else:
                owner = by_id[node_id].prefix if node_id in by_id else "no node"
                raise ProtocolError(
                    f"{where}: frame id 0x{m.frame_id:03x} is node {node_id} ({owner}), "
                    "whose name does not begin the message's"
                )
            kind = snake(suffix)
            if kind in self.kinds and self.kinds[kind].number != number:
                raise ProtocolError(
                    f"{where}: kind {suffix} is number {number} here, "
                    f"{self.kinds[kind].number} on another node"
                )
            self.kinds.setdefault(kind, Kind(number, suffix))
            self._kind_of[m.name] = kind

    def _per_kind(self, attr):
        """{kind: ms} of a message attribute, which every message of a kind must share."""
        out, where = {}, {}
        for m in self.db.messages:
            attrs = m.dbc.attributes if m.dbc else {}
            if attr not in attrs or not attrs[attr].value:
                continue
            kind, ms = self._kind_of[m.name], int(attrs[attr].value)
            if kind in out and out[kind] != ms:
                raise ProtocolError(
                    f"{self.path}: {attr} of {m.name} is {ms} ms, of {where[kind]} {out[kind]} ms"
                    " (a kind has one period)"
                )
            out.setdefault(kind, ms)
            where.setdefault(kind, m.name)
        for m in self.db.messages:
            kind = self._kind_of[m.name]
            attrs = m.dbc.attributes if m.dbc else {}
            if kind in out and not (attr in attrs and attrs[attr].value):
                raise ProtocolError(f"{self.path}: {m.name} has no {attr}, {where[kind]} has")
        return out

    def _read_bit_tables(self):
        tables = self.db.dbc.value_tables if self.db.dbc else {}
        used = {}
        for m in self.db.messages:
            for s in m.signals:
                attrs = s.dbc.attributes if s.dbc else {}
                if "BitTable" not in attrs or not attrs["BitTable"].value:
                    continue
                name = str(attrs["BitTable"].value)
                where = f"{self.path}: {m.name}.{s.name}"
                if name not in tables:
                    raise ProtocolError(f"{where}: BitTable {name} is no VAL_TABLE_")
                bits = {str(label): int(bit) for bit, label in tables[name].items()}
                for label, bit in bits.items():
                    if not _LABEL.fullmatch(label) or not 0 <= bit < s.length:
                        raise ProtocolError(
                            f"{where}: {name} bit {label!r} = {bit}: not an upper-case "
                            f"identifier naming one of the signal's {s.length} bits"
                        )
                used[name] = bits
                self.bit_signals.setdefault(name, []).append(f"{m.name}.{s.name}")
        unused = sorted(set(tables) - set(used))
        if unused:
            raise ProtocolError(f"{self.path}: VAL_TABLE_ {unused[0]} is no signal's BitTable")
        return used

    # -- the protocol's numbers ----------------------------------------------------------
    def frame_id(self, node_id, kind):
        """Standard 11-bit id of kind number `kind` on node `node_id`."""
        if not 0 <= kind < 1 << self.kind_bits or not 0 <= node_id < 1 << (11 - self.kind_bits):
            raise ValueError(f"node_id {node_id} / kind {kind} outside the id layout")
        return (node_id << self.kind_bits) | kind

    def split_id(self, can_id):
        """(node_id, kind number) of an 11-bit id."""
        return can_id >> self.kind_bits, can_id & ((1 << self.kind_bits) - 1)

    def kind_of(self, name):
        """The kind of message `name`, e.g. "setpoint" for "LeftArmSetpoint"."""
        self.message(name)
        return self._kind_of[name]

    def cycle_s(self, kind):
        """Period of a periodic kind ("heartbeat", "status", ...), s (GenMsgCycleTime)."""
        return self._period(self.cycle_ms, "GenMsgCycleTime", kind)

    def timeout_s(self, kind):
        """How long a receiver waits for the next message of `kind` before it treats the
        sender as lost, s (TimeoutTime)."""
        return self._period(self.timeout_ms, "TimeoutTime", kind)

    def _period(self, table, attr, kind):
        if kind not in table:
            raise ProtocolError(f"{self.path}: no message of kind '{kind}' has {attr}")
        return table[kind] / 1000.0

    # -- messages --------------------------------------------------------------------------
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
        if kind not in self.kinds:
            raise ProtocolError(f"unknown message kind '{kind}' (known: {', '.join(self.kinds)})")
        if self.kinds[kind].suffix in self._by_name:  # a broadcast message: no node
            return self.kinds[kind].suffix
        if node not in self.nodes:
            raise ProtocolError(f"unknown node '{node}' (known: {', '.join(self.nodes)})")
        name = self.nodes[node].prefix + self.kinds[kind].suffix
        self.message(name)
        return name

    def node_of(self, can_id):
        """Node name an id belongs to ("broadcast" for the broadcast node), None if unknown."""
        node_id, _ = self.split_id(can_id)
        if node_id == self.broadcast_node:
            return "broadcast"
        return next((n for n, node in self.nodes.items() if node.id == node_id), None)

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


def load(path=None):
    """The protocol from `path` (default: default_dbc_path()), loaded once per path."""
    path = path or default_dbc_path()
    if path not in _CACHE:
        _CACHE[path] = Protocol(path)
    return _CACHE[path]
