"""Stable-Baselines3 VecEnv over VbVectorEnv (optional: ``pip install -e "python[sb3]"``).

SB3 has its own vector API (``step_async``/``step_wait``, same-step autoreset with
``info["terminal_observation"]`` and ``info["TimeLimit.truncated"]``, ``seed()`` applied at the next
``reset()``). This adapter runs VbVectorEnv in ``same_step`` mode and translates; each env is still
its own vb_gym process, stepped in parallel.
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

try:
    from stable_baselines3.common.vec_env.base_vec_env import VecEnv
except ImportError as error:  # pragma: no cover - depends on the optional extra
    raise ImportError(
        'vb_gym.sb3 needs Stable-Baselines3: pip install -e "python[sb3]" (see docs/gym.md)'
    ) from error

from .config import EnvConfig
from .vector import VbVectorEnv


class VbSB3VecEnv(VecEnv):
    def __init__(self, num_envs: int, config: EnvConfig | None = None, **kwargs: Any):
        self.venv = VbVectorEnv(num_envs, config, autoreset_mode="same_step", **kwargs)
        self._actions: np.ndarray | None = None
        super().__init__(num_envs, self.venv.single_observation_space,
                         self.venv.single_action_space)

    def reset(self) -> Any:
        seeds = list(getattr(self, "_seeds", [None] * self.num_envs))
        obs, infos = self.venv.reset(seed=seeds if any(s is not None for s in seeds) else None)
        self.reset_infos = [VbVectorEnv._info_of(infos, i) for i in range(self.num_envs)]
        if hasattr(self, "_reset_seeds"):
            self._reset_seeds()
        if hasattr(self, "_reset_options"):
            self._reset_options()
        return obs

    def step_async(self, actions: np.ndarray) -> None:
        self._actions = np.asarray(actions)

    def step_wait(self) -> tuple[Any, np.ndarray, np.ndarray, list[dict[str, Any]]]:
        obs, rewards, terminated, truncated, infos = self.venv.step(self._actions)
        dones = terminated | truncated
        out = []
        for i in range(self.num_envs):
            info = VbVectorEnv._info_of(infos, i)
            if dones[i]:
                final_obs = info.pop("final_obs")
                info = dict(info.pop("final_info", info))
                info["terminal_observation"] = final_obs
                info["TimeLimit.truncated"] = bool(truncated[i] and not terminated[i])
            out.append(info)
        return obs, rewards.astype(np.float32), dones, out

    def close(self) -> None:
        self.venv.close()

    def get_attr(self, attr_name: str, indices: Any = None) -> list[Any]:
        return [getattr(self.venv, attr_name)] * len(self._indices(indices))

    def set_attr(self, attr_name: str, value: Any, indices: Any = None) -> None:
        raise AttributeError(f"VbSB3VecEnv: setting {attr_name!r} on the workers is not supported")

    def env_method(self, method_name: str, *args: Any, indices: Any = None,
                   **kwargs: Any) -> list[Any]:
        raise AttributeError(f"VbSB3VecEnv: {method_name!r} cannot be called on the workers")

    def env_is_wrapped(self, wrapper_class: type, indices: Any = None) -> list[bool]:
        return [False] * len(self._indices(indices))

    def _indices(self, indices: Any) -> Sequence[int]:
        if indices is None:
            return range(self.num_envs)
        if isinstance(indices, int):
            return [indices]
        return list(indices)
