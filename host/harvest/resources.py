"""Where the package finds the project's data: the DBC, the default config, the LCM definitions
and the Python lcm-gen made from them. The one place that locates them.

In a source tree (an editable install, or HV_SOURCE_DIR naming one) these are the tree's own
files, and the generated LCM Python is the build's ($HV_BUILD_DIR, else build/). In an
installed wheel they are the copies host/setup.py put beside the code (harvest/data/), so every
command runs from any folder with no source tree and no build."""

import os
from importlib import resources

# name -> (path in a source tree, path under harvest/data/ in a wheel)
_FILES = {
    "dbc": ("executor/can/harvest.dbc", "harvest.dbc"),
    "config": ("config/harvest.cfg", "harvest.cfg"),
    "lcm_defs": ("lcm_types", "lcm"),
}
PACKAGED_DIR = "data"  # under the harvest package
LCM_PYTHON = "lcm_python"  # under PACKAGED_DIR: lcm-gen's output (the harvest_lcm package)


class DataMissing(RuntimeError):
    """Neither a source tree nor the wheel's data holds the file asked for."""


def source_root():
    """The source tree this package runs from ($HV_SOURCE_DIR wins), or None when installed."""
    named = os.environ.get("HV_SOURCE_DIR")
    if named:
        return os.path.abspath(named)
    # host/harvest/resources.py -> the tree's root is three levels up
    here = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    return here if os.path.isfile(os.path.join(here, _FILES["dbc"][0])) else None


def packaged(name):
    """Path of harvest/data/<name> in the installed package (it may not exist)."""
    return str(resources.files("harvest").joinpath(PACKAGED_DIR, name))


def path(kind):
    """The file or folder of `kind` (dbc, config, lcm_defs); DataMissing names where it looked."""
    in_tree, in_wheel = _FILES[kind]
    root = source_root()
    found = os.path.join(root, in_tree) if root else packaged(in_wheel)
    if not os.path.exists(found):
        where = "the source tree" if root else "the installed package's data"
        raise DataMissing(f"{found}: missing ({kind}, looked in {where})")
    return found


def lcm_python_dir():
    """Folder holding the generated harvest_lcm package: $HV_BUILD_DIR/lcm_types/python, else
    build/lcm_types/python of the source tree, else the installed package's copy."""
    build = os.environ.get("HV_BUILD_DIR")
    root = source_root()
    if build or root:
        return os.path.join(build or os.path.join(root, "build"), "lcm_types", "python")
    return packaged(LCM_PYTHON)
