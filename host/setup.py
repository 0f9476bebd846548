"""The package's version is the repository's (VERSION, which CMake reads too). The wheel
carries the project's data beside the code (harvest/data/, found by harvest.resources): the
DBC, the default config, the LCM definitions and the Python lcm-gen makes from them, so an
installed harvest-stack needs no source tree and no build. The files are copied from the
repository this folder sits in at build time (pip builds in place), never kept twice in the
tree. An editable install reads the tree's own files instead."""

import glob
import os
import shutil
import subprocess

from setuptools import setup
from setuptools.command.build_py import build_py

HOST = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HOST)
SOURCES = {  # path in the repository -> name under harvest/data/ (harvest/resources.py)
    "executor/can/harvest.dbc": "harvest.dbc",
    "config/harvest.cfg": "harvest.cfg",
}


class BuildPyWithData(build_py):
    def run(self):
        super().run()
        if getattr(self, "editable_mode", False):
            return
        out = os.path.join(self.build_lib, "harvest", "data")
        os.makedirs(out, exist_ok=True)
        for src, name in SOURCES.items():
            shutil.copyfile(self._source(src), os.path.join(out, name))
        defs = sorted(glob.glob(os.path.join(ROOT, "lcm_types", "*.lcm")))
        if not defs:
            raise SystemExit(f"{ROOT}/lcm_types: no .lcm definitions (build from the repository)")
        os.makedirs(os.path.join(out, "lcm"), exist_ok=True)
        for d in defs:
            shutil.copyfile(d, os.path.join(out, "lcm", os.path.basename(d)))
        lcm_gen = shutil.which("lcm-gen")
        if lcm_gen is None:
            raise SystemExit("lcm-gen not found: the build needs the lcm package (pyproject.toml)")
        subprocess.run(
            [lcm_gen, "--python", "--ppath", os.path.join(out, "lcm_python"), *defs], check=True
        )

    @staticmethod
    def _source(rel):
        path = os.path.join(ROOT, rel)
        if not os.path.isfile(path):
            raise SystemExit(f"{path}: missing (build the wheel from the repository's host/)")
        return path


def project_version():
    """The repository's one version (VERSION at its top), as CMake reads it."""
    path = os.path.join(ROOT, "VERSION")
    try:
        with open(path, encoding="ascii") as f:
            return f.readline().strip()
    except OSError as e:
        raise SystemExit(f"{path}: cannot read the project's version: {e.strerror}") from e


setup(version=project_version(), cmdclass={"build_py": BuildPyWithData})
