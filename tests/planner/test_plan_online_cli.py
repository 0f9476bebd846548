"""harvest-plan-online's command line: --help, and each bad argument refused with exit 2 and
one line naming it, before any network is opened. (Its run is in
tests/executor/test_exec_online_udp.py, against the simulator.)"""

import os
import subprocess

import pytest

SRC = os.environ.get(
    "HV_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
BUILD = os.environ.get("HV_BUILD_DIR", os.path.join(SRC, "build"))
PROG = os.path.join(BUILD, "planner", "online", "harvest-plan-online")
CONFIG = os.path.join(SRC, "config", "harvest.cfg")

pytestmark = pytest.mark.skipif(
    not os.access(PROG, os.X_OK),
    reason="SKIPPED: harvest-plan-online not built (needs GLPK and LCM)",
)


def run(*args):
    return subprocess.run([PROG, *args], capture_output=True, text=True, timeout=60)


def test_help_names_the_bad_input_reasons():
    p = run("--help")
    assert p.returncode == 0
    for word in (
        "HARVEST_CAMERA",
        "HARVEST_PLAN_COMMIT",
        "outside_row",
        "duplicate",
        "late",
        "--threads",
        "--out",
    ):
        assert word in p.stdout


@pytest.mark.parametrize(
    "args,named",
    [
        ([], "--config"),
        (["--config", CONFIG], "--lcm-url"),
        (["--config", CONFIG, "--lcm-url", "memq://", "--threads", "3"], "--threads"),
        (
            ["--config", CONFIG, "--lcm-url", "memq://", "--window", "1", "--commit", "2"],
            "--commit",
        ),
        (["--config", CONFIG, "--lcm-url", "memq://", "--time-limit", "-1"], "--time-limit"),
        (["--config", CONFIG, "--lcm-url", "memq://", "--bogus", "1"], "--bogus"),
    ],
)
def test_bad_arguments_refused(args, named):
    p = run(*args)
    assert p.returncode == 2, p.stderr
    assert named in p.stderr and len(p.stderr.strip().splitlines()) == 1, p.stderr


def test_bad_config_refused(tmp_path):
    cfg = tmp_path / "bad.cfg"
    with open(CONFIG) as f:
        cfg.write_text("".join(line for line in f if not line.startswith("camera.window")))
    p = run("--config", str(cfg), "--lcm-url", "memq://")
    assert p.returncode == 2 and "camera.window" in p.stderr, p.stderr
