"""Simulator of the CAN nodes the executor drives: the vehicle drive and the two SCARA joint
controllers (DESIGN §9), on any python-can bus, with a time scale and fault injection.

`python -m harvest sim --help` runs it; `runner.Simulator` is the program, `arm.ArmNode`
and `vehicle.VehicleNode` the node state machines, `faults` the injection plan.
"""
