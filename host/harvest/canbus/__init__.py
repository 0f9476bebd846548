"""CAN side of the host tools: the DBC protocol (protocol), python-can buses (buses),
private network namespaces for UDP multicast (netns) and the QEMU vcan test bed (guest).

The DBC in executor/can/harvest.dbc is the single source of truth (DESIGN §6); this
package only loads it, it never restates a frame layout.
"""

from .protocol import (  # noqa: F401
    BROADCAST_NODE,
    COMMANDS,
    DBC_PATH,
    NODES,
    PROTOCOL_VERSION,
    Protocol,
    ProtocolError,
    frame_id,
    load,
    split_id,
)
