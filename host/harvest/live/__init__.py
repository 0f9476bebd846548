"""The live view: the running robot in Foxglove, from the executor's LCM telemetry."""
