"""harvest-fw.elf (firmware/) on the simulator's bus: QEMU's mps2-an386 with UART0 on a
TCP port, python-can's slcan interface and can.bridge carrying it onto the udp_multicast
bus (rig), and `python -m harvest firmware run` for a whole row (cli)."""
