"""Read config/harvest.cfg (`key = value [value...]`, `#` comments) without copying numbers.

The C parser (core/include/hv/config.h) is the authority on the whole file; this reader
only needs the row, canopy, vehicle and grid keys, and fails with the file and key named
when one is missing or malformed, so a renamed key cannot be silently replaced by a default.
"""

import math
import re

from harvest import resources


class ConfigError(ValueError):
    """A config file that cannot be read: the message names the file and the key/line."""


_LINE = re.compile(r"^\s*([A-Za-z0-9_.]+)\s*=\s*(.*?)\s*$")


class Config:
    """The key/value pairs of one config file, with typed getters that name file and key."""

    def __init__(self, path, values, lines):
        self.path = path
        self._values = values  # key -> raw text value
        self._lines = lines  # key -> 1-based line number (for messages)

    @classmethod
    def load(cls, path):
        try:
            with open(path, encoding="utf-8") as f:
                text = f.read()
        except OSError as e:
            raise ConfigError(f"{path}: cannot read config: {e.strerror}") from None
        return cls.parse(text, path)

    @classmethod
    def parse(cls, text, path="<config>"):
        values, lines = {}, {}
        for n, raw in enumerate(text.splitlines(), 1):
            line = raw.split("#", 1)[0]
            if not line.strip():
                continue
            m = _LINE.match(line)
            if not m or not m.group(2):
                raise ConfigError(f"{path}:{n}: expected 'key = value', got {raw.strip()!r}")
            key = m.group(1)
            if key in values:
                raise ConfigError(f"{path}:{n}: duplicate key '{key}' (first on line {lines[key]})")
            values[key], lines[key] = m.group(2), n
        return cls(path, values, lines)

    def text(self, key):
        if key not in self._values:
            raise ConfigError(f"{self.path}: missing key '{key}'")
        return self._values[key]

    def floats(self, key, count):
        parts = self.text(key).split()
        if len(parts) != count:
            raise ConfigError(
                f"{self.path}:{self._lines[key]}: '{key}' needs {count} number(s), got {len(parts)}"
            )
        try:
            out = [float(p) for p in parts]
        except ValueError:
            raise ConfigError(
                f"{self.path}:{self._lines[key]}: '{key}' is not numeric: {self.text(key)!r}"
            ) from None
        if not all(math.isfinite(v) for v in out):
            raise ConfigError(f"{self.path}:{self._lines[key]}: '{key}' is not finite")
        return out

    def float(self, key):
        return self.floats(key, 1)[0]

    def at_least_zero(self, key):
        v = self.float(key)
        if v < 0:
            raise ConfigError(f"{self.path}:{self._lines[key]}: '{key}' must be >= 0, got {v}")
        return v

    def positive(self, key):
        v = self.float(key)
        if v <= 0:
            raise ConfigError(f"{self.path}:{self._lines[key]}: '{key}' must be > 0, got {v}")
        return v


class Row:
    """The fruit-planted area and the timing numbers the experiments need (SI units)."""

    def __init__(self, cfg):
        self.length_m = cfg.positive("row.length")
        self.aisle_width_m = cfg.positive("row.aisle_width")
        self.canopy_depth_m = cfg.positive("row.canopy_depth")
        self.canopy_z_min_m = cfg.float("row.canopy_z_min")
        self.canopy_height_m = cfg.positive("row.canopy_height")
        self.yaw_max_rad = math.radians(cfg.positive("row.pick_yaw_max_deg"))
        self.vehicle_speed_mps = cfg.positive("vehicle.speed")
        self.stop_penalty_s = cfg.float("vehicle.stop_penalty")
        self.grid_step_m = cfg.positive("grid.step")
        self.grid_yaw_step_rad = math.radians(cfg.positive("grid.yaw_step_deg"))
        self.base_spacing_m = cfg.at_least_zero("mount.base_spacing")  # 0: side by side
        self.mount_offset_m = cfg.float("mount.offset")

    @property
    def x_near_m(self):
        """|x| of the canopy's near face: half the aisle between the two canopies."""
        return self.aisle_width_m / 2.0

    @property
    def x_far_m(self):
        return self.aisle_width_m / 2.0 + self.canopy_depth_m

    @property
    def z_max_m(self):
        return self.canopy_z_min_m + self.canopy_height_m

    def arm_bases(self):
        """Where each arm's base stands relative to the stop (docs/FRAMES.md, arm mount):
        {"left": (dy, x), "right": (dy, x)} in m, dy along the row (left ahead by half the
        base spacing, right behind), x lateral: mount.offset (the paper's D) is measured
        from the canopy's near face towards the aisle centre."""
        x = self.x_near_m - self.mount_offset_m
        half = self.base_spacing_m / 2.0
        return {"left": (half, -x), "right": (-half, x)}


def load_row(path):
    return Row(Config.load(path))


def derived_config_text(path, overrides):
    """The text of `path` with the values of some keys replaced (e.g. a long row's length).

    Every key in `overrides` must already exist, so a typo cannot add a key the C parser
    would reject or silently leave the original value in place.
    """
    cfg = Config.load(path)
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    for key, value in overrides.items():
        cfg.text(key)  # raises when missing
        n = cfg._lines[key] - 1
        lines[n] = f"{key} = {value}"
    return "\n".join(lines) + "\n"


def default_config_path():
    """The project's config (harvest.resources: the source tree's config/harvest.cfg or the
    installed package's copy)."""
    return resources.path("config")
