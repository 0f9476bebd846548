"""The LCM message classes of lcm_types/ (package `harvest`), as lcm-gen generated them
into the build tree (<build>/lcm_types/python/harvest/*.py) with the same lcm-gen as the C
side.

lcm-gen names the Python package after the LCM package, `harvest`, which is also this
package's name; the generated modules refer to each other as `harvest.<type>` and expect
that attribute to be the class (their own __init__.py rebinds it so). `load()` therefore
adds the generated folder to this package's search path and binds each class the same
way, so both the generated code and we find `harvest.plan_t` etc.
"""
import glob
import importlib
import os

import harvest

TYPES = ("plan_pick_t", "plan_stop_t", "plan_t", "exec_state_t", "arm_joint_state_t",
         "fruit_event_t", "can_stats_t", "detection_t", "camera_frame_t", "plan_commit_t")

CHANNELS = {
    "HARVEST_PLAN": "plan_t",
    "HARVEST_EXEC_STATE": "exec_state_t",
    "HARVEST_FRUIT": "fruit_event_t",
    "HARVEST_ARM_LEFT": "arm_joint_state_t",
    "HARVEST_ARM_RIGHT": "arm_joint_state_t",
    "HARVEST_CAN_STATS": "can_stats_t",
    "HARVEST_CAMERA": "camera_frame_t",
    "HARVEST_PLAN_COMMIT": "plan_commit_t",
}


class LcmTypesMissing(RuntimeError):
    """The generated Python is not in the build tree (build the project first)."""


def default_dir():
    src = os.environ.get("HV_SOURCE_DIR") or os.path.dirname(
        os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
    build = os.environ.get("HV_BUILD_DIR") or os.path.join(src, "build")
    return os.path.join(build, "lcm_types", "python")


_loaded = {}


def load(python_dir=None):
    """Dict type name -> class. Raises LcmTypesMissing naming the folder it looked in."""
    if _loaded:
        return dict(_loaded)
    folder = os.path.join(python_dir or default_dir(), "harvest")
    missing = [t for t in TYPES if not os.path.isfile(os.path.join(folder, t + ".py"))]
    if missing:
        raise LcmTypesMissing(
            f"{folder}: generated LCM types missing ({', '.join(missing)}): build the project "
            "(cmake --build <build>) with HV_WITH_LCM=ON, or pass --lcm-python / HV_BUILD_DIR")
    if folder not in harvest.__path__:
        harvest.__path__.append(folder)
    # dependencies first: plan_t refers to plan_stop_t and plan_pick_t at encode time
    for name in TYPES:
        module = importlib.import_module("harvest." + name)
        cls = getattr(module, name)
        setattr(harvest, name, cls)
        _loaded[name] = cls
    return dict(_loaded)


def decode(channel, data, types=None):
    """Decode one message of a known channel; None for other channels."""
    types = types or load()
    name = CHANNELS.get(channel)
    return types[name].decode(data) if name else None


def generated_files(python_dir=None):
    return sorted(glob.glob(os.path.join(python_dir or default_dir(), "harvest", "*.py")))
