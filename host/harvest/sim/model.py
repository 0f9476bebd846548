"""The numbers the simulated hardware needs from config/harvest.cfg: joint limits, the home
pose and the vehicle drive. Read through harvest.scenario.config so no number is restated."""

from harvest.scenario.config import Config, ConfigError, default_config_path  # noqa: F401

JOINTS = 4


class JointLimit:
    """One joint: range [min, max] (m or rad), vmax (m/s or rad/s), amax (m/s^2 or rad/s^2)."""

    def __init__(self, lo, hi, vmax, amax):
        self.min, self.max, self.vmax, self.amax = lo, hi, vmax, amax

    def contains(self, q):
        return self.min <= q <= self.max


class Model:
    """Arm and vehicle parameters of one config file."""

    def __init__(self, cfg):
        self.path = cfg.path
        self.joints = []
        for j in range(1, JOINTS + 1):
            lo = cfg.float(f"joint{j}.min")
            hi = cfg.float(f"joint{j}.max")
            if hi <= lo:
                raise ConfigError(
                    f"{cfg.path}: 'joint{j}.max' ({hi}) must exceed 'joint{j}.min' ({lo})"
                )
            self.joints.append(
                JointLimit(lo, hi, cfg.positive(f"joint{j}.vmax"), cfg.positive(f"joint{j}.amax"))
            )
        self.home = cfg.floats("arm.home", JOINTS)
        for j, (q, lim) in enumerate(zip(self.home, self.joints), 1):
            if not lim.contains(q):
                raise ConfigError(
                    f"{cfg.path}: 'arm.home' joint {j} = {q} outside [{lim.min}, {lim.max}]"
                )
        self.vehicle_speed = cfg.positive("vehicle.speed")  # m/s
        self.vehicle_accel = cfg.positive("vehicle.accel")  # m/s^2
        self.row_length = cfg.positive("row.length")  # m
        self.cut_s = cfg.positive("pick.cut_time")  # s, the end effector's CUT
        self.release_s = cfg.positive("pick.release_time")  # s, and its RELEASE
        # online mode's camera: the row in view from lead to lead + window ahead (m)
        self.camera_lead = cfg.float("camera.lead")
        if self.camera_lead < 0:
            raise ConfigError(f"{cfg.path}: 'camera.lead' ({self.camera_lead}) must be >= 0")
        self.camera_window = cfg.positive("camera.window")

    @classmethod
    def load(cls, path=None):
        return cls(Config.load(path or default_config_path()))
