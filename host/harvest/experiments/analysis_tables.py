"""Make the analysis tables of cost_analysis.py with costgen: right arm, joint 3 limited and
free, on the widened grid. Made once per output directory (temp file, then renamed)."""

import os
import subprocess

from ..scenario.config import derived_config_text
from .cost_analysis import analysis_overrides
from .runner import RunError


def ensure(costgen, config_path, row, out_dir, log):
    d = os.path.join(out_dir, "analysis_tables")
    os.makedirs(d, exist_ok=True)
    cfg = os.path.join(d, "analysis.cfg")
    text = derived_config_text(config_path, analysis_overrides(row))
    if os.path.isfile(cfg):
        with open(cfg, encoding="utf-8") as f:
            if f.read() != text:  # the config changed since: the old tables are stale
                for name in ("limited", "elbow_free"):
                    p = os.path.join(d, f"right_{name}.bin")
                    if os.path.exists(p):
                        os.remove(p)
    with open(cfg + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(cfg + ".tmp", cfg)
    paths = {}
    for name, extra in (("limited", []), ("elbow_free", ["--elbow-free"])):
        path = os.path.join(d, f"right_{name}.bin")
        paths[name] = path
        if os.path.isfile(path):
            continue
        tmp = path + ".part"
        cmd = [costgen, "--config", cfg, "--side", "right", "--out", tmp, "--quiet"] + extra
        print(f"experiments: analysis table: {' '.join(cmd)}", file=log, flush=True)
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if r.returncode != 0 or not os.path.isfile(tmp):
            tail = (r.stdout.strip().splitlines() or ["(no output)"])[-1]
            raise RunError(f"costgen failed with exit {r.returncode}: {tail}")
        os.replace(tmp, path)
    return paths["limited"], paths["elbow_free"]
