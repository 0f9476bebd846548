"""What the install tests share: the build they test (HV_BUILD_DIR, HV_SOURCE_DIR from
ctest), the programs every install holds, its CMake cache and a command that must succeed."""

import os
import subprocess

SOURCE_DIR = os.environ.get("HV_SOURCE_DIR", "")
BUILD_DIR = os.environ.get("HV_BUILD_DIR", "")
PROGRAMS = [
    "harvest-plan",
    "harvest-plan-online",
    "harvest-exec",
    "hv-can-tool",
    "harvest-fw-plan",
    "costgen",
    "mountopt",
]


def cache(key):
    """The value of KEY in the build's CMakeCache.txt, "" when absent."""
    with open(os.path.join(BUILD_DIR, "CMakeCache.txt")) as f:
        for line in f:
            if line.startswith(key + ":"):
                return line.split("=", 1)[1].strip()
    return ""


def run(cmd, **kw):
    """stdout of CMD, which must exit 0 (else its output in the failure)."""
    res = subprocess.run(cmd, capture_output=True, text=True, **kw)
    assert res.returncode == 0, f"{cmd}\n{res.stdout}\n{res.stderr}"
    return res.stdout
