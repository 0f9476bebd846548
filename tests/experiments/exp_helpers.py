"""Paths and programs the experiment tests share (the build named by $HV_BUILD_DIR)."""

import os
import subprocess
import sys

import pytest

SOURCE_DIR = os.environ.get(
    "HV_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
BUILD_DIR = os.environ.get("HV_BUILD_DIR", os.path.join(SOURCE_DIR, "build"))
CONFIG = os.path.join(SOURCE_DIR, "config", "harvest.cfg")
PLANNER = os.path.join(BUILD_DIR, "planner", "harvest-plan")
COSTGEN = os.path.join(BUILD_DIR, "tools", "costgen")


def require(path, what):
    if not (os.path.isfile(path) and os.access(path, os.X_OK)):
        pytest.skip(f"SKIPPED: {what} is not built (no executable at {path})")


def harvest(*args, **kw):
    """Run `python -m harvest ...` as a user would, with host/ on the path."""
    env = dict(os.environ, HV_BUILD_DIR=BUILD_DIR)
    return subprocess.run(
        [sys.executable, "-m", "harvest", *args],
        env=env,
        text=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        **kw,
    )


def assert_checked(plan_path):
    """The planner's independent checker accepts the plan under the config its inputs name."""
    c = subprocess.run(
        [PLANNER, "check", str(plan_path), "--quiet"],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    assert c.returncode == 0, (plan_path, c.stdout)
