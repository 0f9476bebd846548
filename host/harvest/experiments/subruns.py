"""Runs derived from the main run: the same instances, cost tables and planner, one option
changed (the FOV window width, the cost model).

Each derived run is a complete runner output directory of its own under the main run's
(resumable, with its own run.json and results.csv). The main run's cost tables and fruit
maps are linked into it, so every run plans exactly the same inputs and costgen runs once.
"""

import dataclasses
import os
import shutil

from . import results as results_mod
from .runner import RunInputError, check_manifest


def require_main(s):
    """The main run's typed rows; it must exist and have been made with these settings."""
    if not os.path.exists(os.path.join(s.out_dir, "run.json")):
        raise RunInputError(
            f"{s.out_dir}: no main run yet: run 'experiments run --out {s.out_dir}' "
            "with the same options first"
        )
    check_manifest(s)  # raises when the options differ from the main run's
    rows = results_mod.read(os.path.join(s.out_dir, "results.csv"))
    if not rows:
        raise RunInputError(f"{s.out_dir}/results.csv: no results yet: run 'experiments run' first")
    return rows


def _link_or_copy(src, dst):
    try:
        os.link(src, dst)
    except OSError:  # another file system, or no hard links: copy, then rename into place
        tmp = f"{dst}.tmp{os.getpid()}"
        shutil.copyfile(src, tmp)
        os.replace(tmp, dst)


def derive(s, subdir, links=("tables", "instances"), **changes):
    """Settings of a run in s.out_dir/subdir with `changes`, the main run's inputs named in
    `links` linked into it (a run whose config changes the cost tables makes its own)."""
    sub = dataclasses.replace(s, out_dir=os.path.join(s.out_dir, subdir), **changes)
    for d in links:
        src_dir = os.path.join(s.out_dir, d)
        if not os.path.isdir(src_dir):
            continue
        dst_dir = os.path.join(sub.out_dir, d)
        os.makedirs(dst_dir, exist_ok=True)
        for name in os.listdir(src_dir):
            src = os.path.join(src_dir, name)
            dst = os.path.join(dst_dir, name)
            if os.path.isfile(src) and not name.startswith(".") and not os.path.exists(dst):
                _link_or_copy(src, dst)
    return sub
