"""CAN side of the host tools: the DBC protocol (protocol), python-can buses (buses),
private network namespaces for UDP multicast (netns) and the QEMU vcan test bed (guest).

The DBC in executor/can/harvest.dbc is the single source of truth (DESIGN §6); this
package only loads it, it never restates a frame layout or a number of the protocol.
"""

from .protocol import (  # noqa: F401
    Protocol,
    ProtocolError,
    default_dbc_path,
    load,
)
