"""The LCM message classes of lcm_types/ (LCM package `harvest_lcm`), as lcm-gen generated
them into the build tree (<build>/lcm_types/python/harvest_lcm/*.py) with the same lcm-gen
as the C side. They are build outputs, not part of this installed package: `load()` puts
the build's generated folder on the import path (named by --lcm-python or HV_BUILD_DIR),
and says which folder it looked in when they are missing.
"""

import glob
import importlib
import os
import sys

from harvest import resources

TYPES = (
    "plan_pick_t",
    "plan_stop_t",
    "plan_t",
    "exec_state_t",
    "arm_joint_state_t",
    "fruit_event_t",
    "can_stats_t",
    "detection_t",
    "camera_frame_t",
    "plan_commit_t",
    "planner_status_t",
    "camera_replay_t",
)

CHANNELS = {
    "HARVEST_PLAN": "plan_t",
    "HARVEST_EXEC_STATE": "exec_state_t",
    "HARVEST_FRUIT": "fruit_event_t",
    "HARVEST_ARM_LEFT": "arm_joint_state_t",
    "HARVEST_ARM_RIGHT": "arm_joint_state_t",
    "HARVEST_CAN_STATS": "can_stats_t",
    "HARVEST_CAMERA": "camera_frame_t",
    "HARVEST_PLAN_COMMIT": "plan_commit_t",
    "HARVEST_PLANNER_STATUS": "planner_status_t",
    "HARVEST_CAMERA_REPLAY": "camera_replay_t",
}


class LcmTypesMissing(RuntimeError):
    """The generated Python is not in the build tree (build the project first)."""


def default_dir():
    return resources.lcm_python_dir()


_loaded = {}


def load(python_dir=None):
    """Dict type name -> class. Raises LcmTypesMissing naming the folder it looked in."""
    if _loaded:
        return dict(_loaded)
    root = os.path.abspath(python_dir or default_dir())
    folder = os.path.join(root, "harvest_lcm")
    missing = [t for t in TYPES if not os.path.isfile(os.path.join(folder, t + ".py"))]
    if missing:
        raise LcmTypesMissing(
            f"{folder}: generated LCM types missing ({', '.join(missing)}): build the project "
            "(cmake --build <build>) with HV_WITH_LCM=ON, or pass --lcm-python / HV_BUILD_DIR"
        )
    if root not in sys.path:
        sys.path.append(root)
    for name in TYPES:
        module = importlib.import_module("harvest_lcm." + name)
        _loaded[name] = getattr(module, name)
    return dict(_loaded)


def decode(channel, data, types=None):
    """Decode one message of a known channel; None for other channels."""
    types = types or load()
    name = CHANNELS.get(channel)
    return types[name].decode(data) if name else None


def generated_files(python_dir=None):
    return sorted(glob.glob(os.path.join(python_dir or default_dir(), "harvest_lcm", "*.py")))
