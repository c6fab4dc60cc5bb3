"""Configuration of a vb environment: tasks, vehicle, control period, observation, action.

All checking happens here, before any process starts, with errors that name the offending key and
value (``ConfigError``, a ``ValueError``). The server checks again (and names task files by line).
"""

from __future__ import annotations

import dataclasses
import math
import os
import re
import subprocess
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from .protocol import find_server_binary
from .reward import RewardWeights

REPO_ROOT = Path(__file__).resolve().parents[2]
LAYERS = ("elevation", "semantics", "occupancy", "friction")
ACTIONS = ("speed", "direct")
RULE_SETS = ("vb", "verti_bench")   # runner::RuleSet (include/vb/engine/runner/outcome_rules.h)
PHYSICS_STEP_S = 0.005


# vb_gym's limit on an observation's crops: the protocol's 256 MiB payload less 1 MiB for the
# state arrays (tools/vb_gym/server.cc, kMaxCropPayloadBytes).
MAX_CROP_PAYLOAD_BYTES = (256 << 20) - (1 << 20)


class ConfigError(ValueError):
    """A bad configuration value; the message names the key."""


def _is_int(v: Any) -> bool:
    return isinstance(v, (int, np.integer)) and not isinstance(v, bool)


def _number(key: str, value: Any, lo: float, hi: float, open_low: bool = False) -> float:
    """value as a float in [lo, hi] ((lo, hi] with open_low); ConfigError naming key otherwise.
    NaN and the infinities fail every comparison, so they are refused too."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ConfigError(f"{key}: expected a number, got {value!r}")
    x = float(value)
    ok = math.isfinite(x) and (lo < x if open_low else lo <= x) and x <= hi
    if not ok:
        low = "(" if open_low else "["
        raise ConfigError(f"{key}: {value!r} not in {low}{lo:g}, {hi:g}]")
    return x


def _integer(key: str, value: Any, lo: int, hi: int) -> int:
    if not _is_int(value) or not lo <= value <= hi:
        raise ConfigError(f"{key}: {value!r} not an integer in [{lo}, {hi}]")
    return int(value)


@dataclasses.dataclass(frozen=True)
class Crop:
    """One egocentric crop (docs/gym.md): size_cells x size_cells cells of resolution_m (times
    the environment scale); row 0 farthest ahead, column 0 the vehicle's far left."""

    layer: str = "elevation"
    size_cells: int = 64
    resolution_m: float = 0.1
    name: str | None = None

    @property
    def key(self) -> str:
        return self.name or self.layer


@dataclasses.dataclass(frozen=True)
class GeneratedTasks:
    """Training worlds outside the benchmark set, made by vb_gen from seeds (docs/generator.md)."""

    seeds: tuple[int, ...]
    elevation: str = "mid"
    terrain: str = "rigid"
    density: str = "sparse"
    out_dir: str | None = None   # default: ~/.cache/vb_gym/generated


@dataclasses.dataclass
class EnvConfig:
    """Everything that defines an environment (docs/gym.md lists units and defaults)."""

    tasks: Any = "tasks/env042.yaml"   # file, directory, list of them, or GeneratedTasks
    vehicle: str = "hmmwv"
    soil: str = "verti_bench"
    perception: str = "none"            # what the policy sees: none (ground truth), a preset of
                                        # data/perception (mild, moderate, severe) or a .yaml
    control_period_s: float = 0.1       # 0.005 reproduces the original's 200 Hz policy
    time_limit_s: float = 60.0
    rules: str = "vb"                   # success and stuck rules: "vb" (the benchmark's) or
                                        # "verti_bench" (the original runners', docs/task_format.md)
    pairs: Sequence[int] | None = None  # pair indices to draw from (default: all of each task)
    action: str = "speed"               # "speed": steering + target speed; "direct": throttle,
                                        # steering, brake
    max_speed_mps: float = 4.0          # target speed of action +1 in "speed" mode (the
                                        # original's CLI speed)
    speed_kp: float = 1.0
    crops: Sequence[Crop] = (Crop("elevation", 64, 0.1),)
    include_wheels: bool = True
    relative_elevation: bool = True     # elevation crops minus the chassis height
    unknown_elevation_m: float = 0.0    # value of elevation cells the perception did not see
                                        # (NaN in vb's crops; spaces hold finite numbers)
    flatten: bool = False               # one flat Box instead of a Dict
    reward: RewardWeights = dataclasses.field(default_factory=RewardWeights)
    lookahead_m: float = 10.0
    replan_period_s: float = 0.1
    keep_trajectory: bool = False       # needed only to write results (evaluation)
    system: str = "gym"                 # the system's name in result files
    episode_cache: int = 4
    server_binary: str | None = None
    timeout_s: float = 600.0

    @staticmethod
    def from_kwargs(**kwargs: Any) -> "EnvConfig":
        names = {f.name for f in dataclasses.fields(EnvConfig)}
        unknown = sorted(set(kwargs) - names)
        if unknown:
            raise ConfigError(
                f"unknown option(s) {', '.join(unknown)}; valid: {', '.join(sorted(names))}"
            )
        config = EnvConfig(**kwargs)
        config.validate()
        return config

    def validate(self) -> None:
        """Checks every option; ConfigError (a ValueError) naming the key for any bad value or
        type, including NaN, infinities and numbers too large to use (1e308 s is no period)."""
        if self.action not in ACTIONS:
            raise ConfigError(f"action: {self.action!r} unknown; valid: {', '.join(ACTIONS)}")
        for key in ("vehicle", "soil", "perception", "system"):
            if not isinstance(getattr(self, key), (str, os.PathLike)):
                raise ConfigError(f"{key}: expected a name, got {getattr(self, key)!r}")
        # The server's ranges (tools/vb_gym/server.cc, Configure), checked here first.
        period = _number("control_period_s", self.control_period_s, 0.0, 60.0, open_low=True)
        ratio = period / PHYSICS_STEP_S
        if abs(ratio - round(ratio)) > 1e-9 * ratio:
            raise ConfigError(
                f"control_period_s: {self.control_period_s!r} is not a positive whole number of "
                f"physics steps of {PHYSICS_STEP_S} s"
            )
        _number("time_limit_s", self.time_limit_s, 0.0, 3600.0, open_low=True)  # kMaxTimeLimit_s
        if self.rules not in RULE_SETS:
            raise ConfigError(f"rules: {self.rules!r} unknown; valid: {', '.join(RULE_SETS)}")
        _number("max_speed_mps", self.max_speed_mps, 0.0, 1e3, open_low=True)
        _number("speed_kp", self.speed_kp, 0.0, 1e3)
        _number("unknown_elevation_m", self.unknown_elevation_m, -1e9, 1e9)
        _number("lookahead_m", self.lookahead_m, 0.0, 1e4)
        _number("replan_period_s", self.replan_period_s, 0.0, 1e4)
        _number("timeout_s", self.timeout_s, 0.0, 1e9, open_low=True)
        _integer("episode_cache", self.episode_cache, 1, 1000)
        for key in ("include_wheels", "relative_elevation", "flatten", "keep_trajectory"):
            if not isinstance(getattr(self, key), bool):
                raise ConfigError(f"{key}: expected True or False, got {getattr(self, key)!r}")
        if isinstance(self.crops, (Crop, dict, str)) or not isinstance(self.crops, Sequence):
            raise ConfigError(f"crops: expected a list of Crop, got {self.crops!r}")
        crops = []
        for c in self.crops:
            if isinstance(c, dict):
                try:
                    c = Crop(**c)
                except TypeError as e:
                    raise ConfigError(f"crops: {e}") from None
            if not isinstance(c, Crop):
                raise ConfigError(f"crops: expected Crop or dict entries, got {c!r}")
            if c.layer not in LAYERS:
                raise ConfigError(f"crops: layer {c.layer!r} unknown; valid: {', '.join(LAYERS)}")
            _integer("crops: size_cells", c.size_cells, 1, 1024)
            _number("crops: resolution_m", c.resolution_m, 1e-3, 100.0)
            crops.append(c)
        keys = [c.key for c in crops]
        if len(set(keys)) != len(keys) or {"state", "wheels"} & set(keys):
            raise ConfigError(f"crops: names must be unique and not state/wheels, got {keys}")
        crop_bytes = sum(4 * c.size_cells**2 for c in crops)
        if crop_bytes > MAX_CROP_PAYLOAD_BYTES:
            raise ConfigError(f"crops: {crop_bytes} bytes per observation, above the protocol's "
                              f"limit of {MAX_CROP_PAYLOAD_BYTES}")
        self.crops = tuple(crops)
        if self.pairs is not None:
            if isinstance(self.pairs, (str, bytes)) or not isinstance(self.pairs, Sequence) or \
                    not self.pairs or not all(_is_int(p) and p >= 0 for p in self.pairs):
                raise ConfigError(f"pairs: expected a non-empty list of indices >= 0, got "
                                  f"{self.pairs!r}")
        if not re.fullmatch(r"[A-Za-z0-9_][A-Za-z0-9_.-]{0,63}", str(self.system)):
            raise ConfigError(f"system: {self.system!r} is not a name of 1-64 letters, digits, "
                              "'_', '-', '.' (not starting with '.' or '-')")
        if not isinstance(self.reward, RewardWeights):
            raise ConfigError("reward: expected a vb_gym.RewardWeights")
        try:
            self.reward.validate()
        except ValueError as e:
            raise ConfigError(str(e)) from None

    def task_files(self) -> list[str]:
        """The task files, resolved (relative paths against the cwd, then the repository)."""
        return resolve_tasks(self.tasks)

    def configure_request(self) -> dict[str, Any]:
        return {
            "op": "configure",
            "tasks": self.task_files(),
            "vehicle": self.vehicle,
            "soil": self.soil,
            "perception": str(self.perception),
            "control_period_s": float(self.control_period_s),
            "time_limit_s": float(self.time_limit_s),
            "rules": str(self.rules),
            "lookahead_m": float(self.lookahead_m),
            "replan_period_s": float(self.replan_period_s),
            "crops": [
                {"layer": c.layer, "size_cells": c.size_cells,
                 "resolution_m": float(c.resolution_m), "name": c.key}
                for c in self.crops
            ],
            "action": self.action,
            "speed_kp": float(self.speed_kp),
            "trajectory_every_n_steps": 1 if self.keep_trajectory else 0,
            "episode_cache": int(self.episode_cache),
        }


def _installed_share() -> Path | None:
    """share/vb of the vb install whose vb_gym this package runs (bin/../share/vb), if any."""
    try:
        share = Path(find_server_binary()).resolve().parent.parent / "share" / "vb"
    except FileNotFoundError:
        return None
    return share if share.is_dir() else None


def _resolve_path(item: str) -> Path:
    """A task path as given: against the cwd, then a source checkout holding this package, then
    the share/vb of the vb_gym in use (so "tasks/env042.yaml" works with an installed vb)."""
    p = Path(item).expanduser()
    if p.exists():
        return p.resolve()
    bases = [REPO_ROOT] if (REPO_ROOT / "tasks").is_dir() else []
    share = _installed_share()
    if share is not None:
        bases.append(share)
    for base in bases:
        if not p.is_absolute() and (base / p).exists():
            return (base / p).resolve()
    where = ", ".join(str(b) for b in bases) or "no vb checkout or install found"
    raise ConfigError(f"tasks: {item!r} does not exist (nor relative to {where})")


def resolve_tasks(tasks: Any) -> list[str]:
    if isinstance(tasks, GeneratedTasks):
        return generate_tasks(tasks)
    if isinstance(tasks, (str, os.PathLike)):
        tasks = [tasks]
    files: list[str] = []
    for item in tasks:
        if isinstance(item, GeneratedTasks):
            files += generate_tasks(item)
            continue
        p = _resolve_path(str(item))
        if p.is_dir():
            found = sorted(str(f) for f in p.glob("*.yaml"))
            if not found:
                raise ConfigError(f"tasks: directory {str(p)!r} holds no *.yaml task files")
            files += found
        else:
            files.append(str(p))
    if not files:
        raise ConfigError("tasks: no task files given")
    return files


def generate_tasks(spec: GeneratedTasks) -> list[str]:
    """Runs vb_gen once per seed (skipped when the file exists: vb_gen is deterministic)."""
    out = Path(spec.out_dir or Path.home() / ".cache" / "vb_gym" / "generated").expanduser()
    vb_gen = str(Path(find_server_binary()).with_name("vb_gen"))
    files = []
    for seed in spec.seeds:
        if not isinstance(seed, int) or seed < 0:
            raise ConfigError(f"tasks: generator seed {seed!r} is not an integer >= 0")
        name = f"gen_{spec.elevation}_{spec.terrain}_{spec.density}_s{seed}"
        task = out / "tasks" / f"{name}.yaml"
        if not task.exists():
            cmd = [vb_gen, "--seed", str(seed), "--name", name, "--elevation", spec.elevation,
                   "--terrain", spec.terrain, "--density", spec.density,
                   "--out", str(out / "tasks"), "--image-dir", str(out / "worlds")]
            run = subprocess.run(cmd, capture_output=True, text=True)
            if run.returncode != 0:
                raise ConfigError(f"tasks: vb_gen failed for seed {seed}: {run.stderr.strip()}")
        files.append(str(task))
    return files
