"""Configuration of a vb environment: tasks, vehicle, control period, observation, action.

All checking happens here, before any process starts, with errors that name the offending key and
value (``ConfigError``, a ``ValueError``). The server checks again (and names task files by line).
"""

from __future__ import annotations

import dataclasses
import os
import re
import subprocess
from pathlib import Path
from typing import Any, Sequence

from .protocol import find_server_binary
from .reward import RewardWeights

REPO_ROOT = Path(__file__).resolve().parents[2]
LAYERS = ("elevation", "semantics", "occupancy", "friction")
ACTIONS = ("speed", "direct")
RULE_SETS = ("vb", "verti_bench")   # runner::RuleSet (include/vb/engine/runner/outcome_rules.h)
PHYSICS_STEP_S = 0.005


class ConfigError(ValueError):
    """A bad configuration value; the message names the key."""


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
        if self.action not in ACTIONS:
            raise ConfigError(f"action: {self.action!r} unknown; valid: {', '.join(ACTIONS)}")
        ratio = self.control_period_s / PHYSICS_STEP_S if self.control_period_s > 0 else 0.0
        if not (self.control_period_s > 0) or abs(ratio - round(ratio)) > 1e-9 * ratio:
            raise ConfigError(
                f"control_period_s: {self.control_period_s!r} is not a positive whole number of "
                f"physics steps of {PHYSICS_STEP_S} s"
            )
        if not (0 < self.time_limit_s <= 3600):  # runner::kMaxTimeLimit_s
            raise ConfigError(f"time_limit_s: {self.time_limit_s!r} not in (0, 3600]")
        if self.rules not in RULE_SETS:
            raise ConfigError(f"rules: {self.rules!r} unknown; valid: {', '.join(RULE_SETS)}")
        if not (self.max_speed_mps > 0):
            raise ConfigError(f"max_speed_mps: {self.max_speed_mps!r} must be > 0")
        if isinstance(self.crops, Crop):
            raise ConfigError("crops: expected a list of Crop, got a single Crop")
        crops = []
        for c in self.crops:
            if isinstance(c, dict):
                c = Crop(**c)
            if not isinstance(c, Crop):
                raise ConfigError(f"crops: expected Crop or dict entries, got {c!r}")
            if c.layer not in LAYERS:
                raise ConfigError(f"crops: layer {c.layer!r} unknown; valid: {', '.join(LAYERS)}")
            if not (isinstance(c.size_cells, int) and 1 <= c.size_cells <= 1024):
                raise ConfigError(f"crops: size_cells {c.size_cells!r} not an integer in [1, 1024]")
            if not (c.resolution_m > 0):
                raise ConfigError(f"crops: resolution_m {c.resolution_m!r} must be > 0")
            crops.append(c)
        keys = [c.key for c in crops]
        if len(set(keys)) != len(keys) or {"state", "wheels"} & set(keys):
            raise ConfigError(f"crops: names must be unique and not state/wheels, got {keys}")
        self.crops = tuple(crops)
        if self.pairs is not None:
            if not all(isinstance(p, int) and p >= 0 for p in self.pairs) or not self.pairs:
                raise ConfigError(f"pairs: expected a non-empty list of indices >= 0, got "
                                  f"{self.pairs!r}")
        if not re.fullmatch(r"[A-Za-z0-9_-][A-Za-z0-9_.-]{0,63}", str(self.system)):
            raise ConfigError(f"system: {self.system!r} is not a name of 1-64 letters, digits, "
                              "'_', '-', '.'")
        if not isinstance(self.reward, RewardWeights):
            raise ConfigError("reward: expected a vb_gym.RewardWeights")
        self.reward.validate()

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
