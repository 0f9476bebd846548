"""Run the real planner CLI over the paper's instance grid, one results row per plan.

Layout of an output directory:
  run.json              what the run was started with (checked again on resume)
  planner.cfg           the config the planner is given: --config with row.stops_beyond_ends
                        and plan.pick_cycle as the run asks (0 and 0 unless
                        --stops-beyond-ends / --pick-cycle: the paper's N = 201 stops over
                        the row and its one-way G with tau)
  tables/               the two cost tables, made once with costgen
  instances/*.csv       the fruit maps (pure functions of distribution, alpha and seed)
  plans/*.json          one plan per (instance, method), as the planner wrote it
  results.csv           one row per (instance, method), appended as each one finishes
"""

import concurrent.futures as cf
import ctypes
import datetime
import hashlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field

from tqdm import tqdm

from ..scenario import fruit_map, generate
from ..scenario.config import Config, Row, derived_config_text
from . import plan_file
from .binaries import build_info
from .results import ResultsFile, row_key
from .results import read as read_results

METHODS = ("fov", "serial", "milp")
# harvest-plan --method fov's progress line: fruits in view out of reach of their stop
FOV_MOVED_RE = re.compile(r"(\d+) fruits moved")
PAPER_ALPHAS = (0.25, 0.4, 1.0, 2.5, 4.0)
PAPER_SEEDS = tuple(range(10))
QUICK_ALPHAS = (0.25, 1.0)
QUICK_SEEDS = (0, 1)
TABLE_FILES = {"L": "costtab_left.bin", "R": "costtab_right.bin"}
# harvest-plan's exit code when a signal stopped it (its --help): the plan it wrote is not a
# final result, so the row is not recorded (a Ctrl-C in the terminal reaches it too).
PLANNER_EXIT_INTERRUPTED = 5
# A planner still running this long after its own time limit is hung: kill it, record an error.
HANG_FACTOR, HANG_MARGIN_S = 3.0, 120.0
DEFAULT_HANG_S = 600.0


class RunError(RuntimeError):
    """The run failed: a program it ran (exit 1)."""


class RunInputError(RunError):
    """The run cannot start: its options, or the --out folder they do not fit (exit 2)."""


@dataclass(frozen=True)
class Instance:
    distribution: str
    alpha: float
    seed: int
    n_left: int

    @property
    def name(self):
        return f"{self.distribution}_a{self.alpha:g}_s{self.seed}"


@dataclass
class Settings:
    config: str
    out_dir: str
    planner: str
    costgen: str
    alphas: tuple = PAPER_ALPHAS
    seeds: tuple = PAPER_SEEDS
    methods: tuple = METHODS
    distribution: str = "uniform"
    n_left: int = generate.PAPER_LEFT_FRUITS
    time_limit_s: float = None  # None: the planner's own default
    fov_width_m: float = None  # None: the config's fov.width
    fov_offset_m: float = None  # None: the config's fov.offset
    jobs: int = 1
    stops_beyond_ends: bool = False  # False: the paper's candidate stops, over the row only
    pick_cycle: bool = False  # False: the paper's costs (G one way, tau)
    progress: bool = True
    log: object = field(default=sys.stderr)


def instances(s):
    return [Instance(s.distribution, a, seed, s.n_left) for a in s.alphas for seed in s.seeds]


def _sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        h.update(f.read())
    return h.hexdigest()


def _manifest(s):
    """What makes finished rows comparable with new ones: same config and planner options."""
    return {
        "config_sha256": _sha256(s.config),
        "time_limit_s": s.time_limit_s,
        "fov_width_m": s.fov_width_m,
        "fov_offset_m": s.fov_offset_m,
        "n_left": s.n_left,
        "distribution": s.distribution,
        "stops_beyond_ends": s.stops_beyond_ends,
        "pick_cycle": s.pick_cycle,
    }


def check_manifest(s):
    path = os.path.join(s.out_dir, "run.json")
    want = _manifest(s)
    if os.path.exists(path):
        with open(path, encoding="utf-8") as f:
            have = json.load(f)
        diff = [k for k in want if have.get(k) != want[k]]
        if diff:
            raise RunInputError(
                f"{path}: this directory was started with different "
                f"{', '.join(diff)} ({', '.join(f'{k}={have.get(k)!r}' for k in diff)}): "
                "its rows would not be comparable; use another --out"
            )
        return
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        # Recorded for the report, not compared: where the planner came from and its build.
        json.dump(
            dict(
                want,
                config=os.path.abspath(s.config),
                planner=s.planner,
                planner_build=build_info(s.planner),
            ),
            f,
            indent=1,
        )
    os.replace(tmp, path)


def ensure_tables(s, elbow_free=False, subdir="tables"):
    """Both arms' tables in out_dir/subdir, made by costgen once (in a temp dir, then moved)."""
    tdir = os.path.join(s.out_dir, subdir)
    paths = {side: os.path.join(tdir, name) for side, name in TABLE_FILES.items()}
    if all(os.path.isfile(p) for p in paths.values()):
        return paths
    tmp = f"{tdir}.tmp{os.getpid()}"
    shutil.rmtree(tmp, ignore_errors=True)
    os.makedirs(tmp)
    cmd = [s.costgen, "--config", s.config, "--side", "both", "--out-dir", tmp]
    if elbow_free:
        cmd.append("--elbow-free")
    print(f"experiments: making cost tables: {' '.join(cmd)}", file=s.log, flush=True)
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        shutil.rmtree(tmp, ignore_errors=True)
        tail = r.stdout.strip().splitlines()[-1:] or ["(no output)"]
        raise RunError(f"costgen failed with exit {r.returncode}: {tail[0]}")
    os.makedirs(tdir, exist_ok=True)
    for side, name in TABLE_FILES.items():
        if not os.path.isfile(os.path.join(tmp, name)):
            raise RunError(f"costgen wrote no {name} in {tmp}")
        os.replace(os.path.join(tmp, name), paths[side])
    shutil.rmtree(tmp, ignore_errors=True)
    return paths


def planner_config(s):
    """OUT/planner.cfg: the run's config with the stops and the cost model the run asks for."""
    path = os.path.join(s.out_dir, "planner.cfg")
    text = derived_config_text(
        s.config,
        {"row.stops_beyond_ends": int(s.stops_beyond_ends), "plan.pick_cycle": int(s.pick_cycle)},
    )
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)
    return path


def ensure_instance(s, row, inst):
    path = os.path.join(s.out_dir, "instances", inst.name + ".csv")
    if not os.path.isfile(path):
        fruits = generate.generate(inst.distribution, row, inst.n_left, inst.alpha, inst.seed)
        fruit_map.write(path, fruits)
    return path


_STOP_SIGNALS = {signal.SIGINT, signal.SIGTERM}


_PR_SET_CHILD_SUBREAPER = 36  # linux/prctl.h
ORPHAN_GRACE_S = 5.0


def _become_subreaper():
    """Make orphaned descendants (a killed planner's own children) ours to reap.

    A planner killed at the wrong moment leaves a child of its own behind: the sanitizers'
    leak check runs in a cloned tracer at exit. Orphans go to PID 1, which on some machines
    never reaps them; as subreaper the runner gets them and reaps them before it exits.
    Returns False where prctl is not available (not Linux)."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        return libc.prctl(_PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


def _own_children():
    """PIDs of this process's children, from /proc (every thread's list)."""
    pids = set()
    try:
        for tid in os.listdir("/proc/self/task"):
            with open(f"/proc/self/task/{tid}/children", encoding="ascii") as f:
                pids.update(int(x) for x in f.read().split())
    except OSError:
        pass
    return pids


def reap_orphans(grace_s=ORPHAN_GRACE_S):
    """Reap every child left once the planners are waited for: what is still running after
    grace_s is killed, and after twice grace_s the rest is left (a process stuck in the
    kernel). Returns how many are left."""
    start, killed = time.monotonic(), False
    while True:
        try:
            if os.waitpid(-1, os.WNOHANG)[0]:
                continue
        except ChildProcessError:
            return 0
        waited = time.monotonic() - start
        if waited >= 2 * grace_s:
            return len(_own_children())
        if waited >= grace_s and not killed:
            for pid in _own_children():
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
            killed = True
        time.sleep(0.01)


class _Children:
    """The planner processes running now, so an interruption can stop them with the runner."""

    def __init__(self):
        self._lock = threading.Lock()
        self._procs = set()
        self.stopping = False
        self.subreaper = _become_subreaper()

    def start(self, cmd):
        # Ctrl-C / SIGTERM are held back until the new process is registered: raised between
        # the fork and the registration, they would leave a planner nobody stops.
        held = signal.pthread_sigmask(signal.SIG_BLOCK, _STOP_SIGNALS)
        try:
            with self._lock:
                if self.stopping:
                    raise KeyboardInterrupt
                p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
                self._procs.add(p)
                return p
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, held)

    def done(self, p):
        with self._lock:
            self._procs.discard(p)

    def stop_all(self):
        with self._lock:
            self.stopping = True
            procs = list(self._procs)
        for p in procs:
            p.kill()
        for p in procs:
            p.wait()  # reaped before we exit: no planner, not even a zombie, outlives us
        if self.subreaper:
            left = reap_orphans()
            if left:
                print(
                    f"experiments: {left} process(es) left by the planners would not die",
                    file=sys.stderr,
                    flush=True,
                )


def _hang_timeout(s):
    return (
        DEFAULT_HANG_S if s.time_limit_s is None else s.time_limit_s * HANG_FACTOR + HANG_MARGIN_S
    )


def run_one(s, children, planner_cfg, tables, inst, map_path, method):
    """Plan one (instance, method) with the planner CLI; returns the results row."""
    plans = os.path.join(s.out_dir, "plans")
    plan_rel = os.path.join("plans", f"{inst.name}_{method}.json")
    plan_path = os.path.join(s.out_dir, plan_rel)
    # Per-runner temp name: a planner orphaned by a killed runner cannot clobber the plan a
    # resumed runner is writing for the same row.
    tmp = os.path.join(plans, f".{inst.name}_{method}.{os.getpid()}.part")
    cmd = [
        s.planner,
        "--config",
        planner_cfg,
        "--left",
        tables["L"],
        "--right",
        tables["R"],
        "--fruits",
        map_path,
        "--method",
        method,
        "--out",
        tmp,
    ]
    # FOV's progress line is its only report of the fruits moved to another stop
    if method != "fov":
        cmd.append("--quiet")
    if s.time_limit_s is not None:
        cmd += ["--time-limit", f"{s.time_limit_s:g}"]
    if s.fov_width_m is not None:
        cmd += ["--fov-width", f"{s.fov_width_m:g}"]
    if s.fov_offset_m is not None:
        cmd += ["--fov-offset", f"{s.fov_offset_m:g}"]
    n_right = generate.right_count(inst.n_left, inst.alpha)
    row = {
        "distribution": inst.distribution,
        "alpha": inst.alpha,
        "seed": inst.seed,
        "method": method,
        "n_left": inst.n_left,
        "n_right": n_right,
        "stops": None,
        "makespan_s": None,
        "throughput_fruit_per_s": None,
        "runtime_s": None,
        "status": "error",
        "gap": None,
        "pick_time_s": None,
        "stop_time_s": None,
        "travel_time_s": None,
        "idle_s": None,
        "fruits_planned": None,
        "fruits_unreachable": None,
        "fov_moved": None,
        "time_limit_s": s.time_limit_s,
        "wall_s": None,
        "plan": "",
        "finished_utc": None,
        "error": "",
    }
    t0 = time.monotonic()
    p = children.start(cmd)
    try:
        try:
            _, err = p.communicate(timeout=_hang_timeout(s))
        except subprocess.TimeoutExpired:
            p.kill()
            _, err = p.communicate()
            err = f"planner still running after {_hang_timeout(s):g} s: killed"
    except BaseException:  # interrupted while waiting: the planner must not outlive us
        p.kill()
        p.wait()
        raise
    finally:
        children.done(p)
    if children.stopping or p.returncode == PLANNER_EXIT_INTERRUPTED:
        raise KeyboardInterrupt
    row["wall_s"] = round(time.monotonic() - t0, 3)
    row["finished_utc"] = datetime.datetime.now(datetime.timezone.utc).strftime(
        "%Y-%m-%dT%H:%M:%SZ"
    )
    if p.returncode != 0 or not os.path.isfile(tmp):
        lines = [ln for ln in (err or "").strip().splitlines() if ln.strip()]
        row["error"] = (f"exit {p.returncode}: " + (lines[-1] if lines else "no message"))[:300]
        return row
    try:
        summary = plan_file.summary(tmp, plan_file.load(tmp))
    except plan_file.PlanError as e:
        row["error"] = str(e)[:300]
        return row
    os.replace(tmp, plan_path)
    row.update(summary)
    row["plan"] = plan_rel
    if method == "fov":
        m = FOV_MOVED_RE.search(err or "")
        if m is None:
            row["error"] = "harvest-plan fov: no 'fruits moved' count on stderr"
            row["status"] = "error"
            return row
        row["fov_moved"] = int(m.group(1))
    return row


def _interrupt(signum, frame):
    raise KeyboardInterrupt


def run(s, retry_errors=False):
    """Run every (instance, method) not yet in results.csv. Returns (rows done now, total)."""
    for d in ("instances", "plans"):
        os.makedirs(os.path.join(s.out_dir, d), exist_ok=True)
    check_manifest(s)
    results = ResultsFile(os.path.join(s.out_dir, "results.csv"), log=s.log)
    if retry_errors:
        dropped = results.drop_errors()
        if dropped:
            print(
                f"experiments: {dropped} failed row(s) removed, to be run again",
                file=s.log,
                flush=True,
            )
    row_cfg = Row(Config.load(s.config))
    tables = ensure_tables(s)
    cfg = planner_config(s)
    todo, keys = [], set()
    for inst in instances(s):
        map_path = ensure_instance(s, row_cfg, inst)
        for method in s.methods:
            key = (inst.distribution, float(inst.alpha), inst.seed, method)
            keys.add(key)
            if key not in results.done:
                todo.append((inst, map_path, method))
    total = len(keys)
    done_before = total - len(todo)
    if done_before:
        print(
            f"experiments: resuming: {done_before} of {total} rows already in "
            f"{results.path}, {len(todo)} to run",
            file=s.log,
            flush=True,
        )
    children = _Children()
    bar = tqdm(
        total=total,
        initial=done_before,
        desc="plans",
        unit="plan",
        file=s.log,
        disable=not s.progress,
        dynamic_ncols=True,
    )
    errors = 0

    def record(row):
        nonlocal errors
        results.append(row)
        errors += row["status"] == "error"
        bar.set_postfix_str(f"{row['method']} a={row['alpha']:g} s={row['seed']} {row['status']}")
        bar.update(1)

    previous = signal.getsignal(signal.SIGTERM)
    if threading.current_thread() is threading.main_thread():
        # SIGTERM behaves like Ctrl-C: stop the planners, keep every finished row.
        signal.signal(signal.SIGTERM, _interrupt)
    ran = 0
    try:
        if s.jobs <= 1:
            for inst, map_path, method in todo:
                record(run_one(s, children, cfg, tables, inst, map_path, method))
                ran += 1
        else:
            with cf.ThreadPoolExecutor(max_workers=s.jobs) as pool:
                futures = [
                    pool.submit(run_one, s, children, cfg, tables, inst, mp, m)
                    for inst, mp, m in todo
                ]
                try:
                    for fut in cf.as_completed(futures):
                        record(fut.result())
                        ran += 1
                except BaseException:
                    children.stop_all()
                    for fut in futures:
                        fut.cancel()
                    raise
    except KeyboardInterrupt:
        children.stop_all()
        bar.close()
        # Count from the file itself: the interrupt may have come between a row's write and
        # the bookkeeping after it.
        saved = sum(1 for r in read_results(results.path) if row_key(r) in keys)
        print(
            f"experiments: interrupted: {saved} of {total} rows are saved in "
            f"{results.path}; run the same command again to resume",
            file=s.log,
            flush=True,
        )
        raise
    finally:
        if threading.current_thread() is threading.main_thread():
            signal.signal(signal.SIGTERM, previous)
    bar.close()
    if errors:
        print(
            f"experiments: {errors} plan(s) failed: see the 'error' column of {results.path}",
            file=s.log,
            flush=True,
        )
    return ran, total
