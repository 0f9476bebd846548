"""The paper's comparison (FOV, Serial, MILP) on the real planner: runner, plots, report."""
