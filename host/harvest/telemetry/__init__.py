"""Telemetry of the executor (DESIGN §8): an LCM logger and a Gantt viewer of a log."""
