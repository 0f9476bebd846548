"""Open python-can buses the way the rest of the stack expects them.

Bus specs are the ones hv-can-tool takes: "socketcan:vcan0" or
"udp[:GROUP[:PORT]]" (python-can udp_multicast, TTL 0 so nothing leaves the host).
Note: python-can's udp_multicast bus receives the frames it sent itself (python-can
4.6.1 cannot turn that off); `recv_foreign` skips them, the C transport never sees its own.
"""

import can

UDP_GROUP = "239.74.163.2"
UDP_PORT = 43113


def parse_spec(spec):
    """("socketcan", {"channel": "vcan0"}) / ("udp_multicast", {...}) from a bus spec."""
    kind, _, rest = spec.partition(":")
    if kind == "socketcan":
        if not rest:
            raise ValueError(
                f"bus spec '{spec}': socketcan needs an interface, e.g. socketcan:vcan0"
            )
        return "socketcan", {"channel": rest}
    if kind == "udp":
        parts = rest.split(":") if rest else []
        group = parts[0] if parts and parts[0] else UDP_GROUP
        try:
            port = int(parts[1]) if len(parts) > 1 else UDP_PORT
        except ValueError:
            raise ValueError(f"bus spec '{spec}': port '{parts[1]}' is not a number") from None
        return "udp_multicast", {"channel": group, "port": port, "hop_limit": 0, "fd": False}
    raise ValueError(f"bus spec '{spec}': expected socketcan:IFNAME or udp[:GROUP[:PORT]]")


def open_bus(spec, can_filters=None, **kwargs):
    """A python-can Bus for `spec`; caller shuts it down (use it as a context manager)."""
    interface, args = parse_spec(spec)
    args.update(kwargs)
    return can.Bus(interface=interface, can_filters=can_filters, **args)


def is_undecodable_datagram(exc):
    """True when `exc` is python-can udp_multicast's refusal of one received datagram.

    Its bus reads the datagram, then unpacks it (msgpack, then can.Message(check=True)) and
    raises CanOperationError("could not unpack received message") from whatever that
    raised; the datagram is consumed by then, so the next recv() reads the next one. A
    failing socket raises CanOperationError from an OSError, or with no cause: not this.
    """
    return (
        isinstance(exc, can.CanOperationError)
        and exc.__cause__ is not None
        and not isinstance(exc.__cause__, OSError)
    )


def recv_foreign(bus, sent_ids, timeout):
    """Next message whose id is not in `sent_ids` (our own looped-back udp frames), or
    None after `timeout` seconds without one."""
    import time

    deadline = time.monotonic() + timeout
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            return None
        msg = bus.recv(left)
        if msg is None:
            return None
        if msg.arbitration_id not in sent_ids:
            return msg
