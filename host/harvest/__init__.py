"""Host-side tools of the harvest stack: simulator, scenarios, experiments, telemetry."""

__version__ = "0.1.0"
