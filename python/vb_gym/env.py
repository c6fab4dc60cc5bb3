"""VbEnv: a gymnasium environment over one vb_gym process (registered as ``vb/OffRoad-v0``).

Seeding (docs/gym.md): ``reset(seed=s)`` re-seeds ``np_random`` and draws the task, the pair and
the trial seed from it, so the same seed gives the same start, goal and bit-identical episode;
``reset()`` without a seed draws the next start/goal from the same stream. ``options`` may fix
``task`` (index into the task list) and ``pair``. Nothing is kept across episodes but the RNG.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np

from .config import EnvConfig
from .core import EnvCore


def draw_episode(core: EnvCore, rng: np.random.Generator,
                 options: dict[str, Any] | None) -> tuple[int, int, int]:
    """(task, pair, trial seed) from options, else from rng (always three draws, so the stream
    does not depend on the options)."""
    options = dict(options or {})
    unknown = set(options) - {"task", "pair", "trial_seed"}
    if unknown:
        raise ValueError(f"reset options: unknown {sorted(unknown)}; valid: task, pair, trial_seed")
    u_task, u_pair = rng.random(), rng.random()
    drawn_seed = int(rng.integers(0, 2**63))
    n_tasks = len(core.tasks)
    task = options.get("task", int(u_task * n_tasks))
    if not (isinstance(task, (int, np.integer)) and 0 <= task < n_tasks):
        raise ValueError(f"reset options: task {task!r} not in [0, {n_tasks})")
    pairs = list(core.config.pairs) if core.config.pairs is not None else list(
        range(core.tasks[task]["pairs"]))
    pair = options.get("pair", pairs[int(u_pair * len(pairs))])
    if not (isinstance(pair, (int, np.integer)) and 0 <= pair < core.tasks[task]["pairs"]):
        raise ValueError(f"reset options: pair {pair!r} not in [0, {core.tasks[task]['pairs']})")
    trial_seed = options.get("trial_seed", drawn_seed)
    return int(task), int(pair), int(trial_seed)


class VbEnv(gym.Env):
    """Off-road navigation on vb's tasks: drive the vehicle to the goal (docs/gym.md)."""

    metadata = {"render_modes": []}

    def __init__(self, config: EnvConfig | None = None, render_mode: str | None = None,
                 **kwargs: Any):
        self._core: EnvCore | None = None
        if render_mode is not None:
            raise ValueError(f"render_mode {render_mode!r} not supported (vb has no renderer "
                             "here; results go to trial files, see docs/gym.md)")
        if config is None:
            config = EnvConfig.from_kwargs(**kwargs)
        elif kwargs:
            raise ValueError("give either config or keyword options, not both")
        self.config = config
        self._core = EnvCore(config)
        self.observation_space = self._core.observation_space
        self.action_space = self._core.action_space
        self.render_mode = None

    def _open_core(self) -> EnvCore:
        """The running environment; after close() a clear RuntimeError, not an AttributeError."""
        if self._core is None:
            raise RuntimeError("VbEnv is closed: make a new environment")
        return self._core

    @property
    def tasks(self) -> list[dict[str, Any]]:
        return self._open_core().tasks

    @property
    def server_pid(self) -> int | None:
        return self._core.server.pid if self._core and self._core.server else None

    def reset(self, *, seed: int | None = None,
              options: dict[str, Any] | None = None) -> tuple[Any, dict[str, Any]]:
        core = self._open_core()
        super().reset(seed=seed)
        task, pair, trial_seed = draw_episode(core, self.np_random, options)
        core.send_reset(task, pair, trial_seed)
        return core.receive_reset()

    def step(self, action: Any) -> tuple[Any, float, bool, bool, dict[str, Any]]:
        core = self._open_core()
        core.send_step(action)
        return core.receive_step()

    def write_result(self, directory: str) -> dict[str, Any]:
        """Writes the ended trial's JSON and trajectory CSV (vb_run's format) into directory;
        needs keep_trajectory=True."""
        return self._open_core().request({"op": "write_result", "dir": str(directory)})

    def close(self) -> None:
        if self._core is not None:
            self._core.close()
            self._core = None
