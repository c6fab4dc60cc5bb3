"""VbVectorEnv: N vb_gym processes stepped in lock step, as a gymnasium ``VectorEnv``.

Each sub-environment is its own vb_gym process (the physics of the N environments runs in
parallel on N cores); this process only sends the N requests, then reads the N replies. No Python
worker processes are involved. Seeding as gymnasium's vector envs: an int seed gives env i the
seed ``seed + i``, and each env draws its episodes from its own stream exactly as ``VbEnv`` does,
so env i of a vector env reproduces ``VbEnv.reset(seed=seed + i)`` bit for bit.

Autoreset: ``next_step`` (gymnasium's default: the step after an episode's end resets that env
and returns its first observation with reward 0) or ``same_step`` (the end step already returns
the next episode's first observation; the last one is in ``info["final_obs"]``, as
Stable-Baselines3 expects: see vb_gym.sb3).
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np
from gymnasium.utils import seeding
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space, concatenate, create_empty_array

from .config import EnvConfig
from .core import EnvCore
from .env import draw_episode
from .protocol import ServerCrashed, VbGymError


class VbVectorEnv(VectorEnv):
    def __init__(self, num_envs: int = 2, config: EnvConfig | None = None,
                 autoreset_mode: str | AutoresetMode = AutoresetMode.NEXT_STEP, **kwargs: Any):
        self._cores: list[EnvCore] = []
        self.closed = False
        if not (isinstance(num_envs, int) and num_envs >= 1):
            raise ValueError(f"num_envs: {num_envs!r} is not an integer >= 1")
        if config is None:
            config = EnvConfig.from_kwargs(**kwargs)
        elif kwargs:
            raise ValueError("give either config or keyword options, not both")
        names = {"next_step": AutoresetMode.NEXT_STEP, "same_step": AutoresetMode.SAME_STEP}
        mode = names.get(autoreset_mode) if isinstance(autoreset_mode, str) else autoreset_mode
        if isinstance(autoreset_mode, str) and mode is None:
            mode = AutoresetMode(autoreset_mode)   # gymnasium's own spelling, "NextStep"
        if mode not in (AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP):
            raise ValueError(f"autoreset_mode {mode} not supported; use next_step or same_step")
        self.config = config
        self.autoreset_mode = mode
        self.metadata = {"autoreset_mode": mode, "render_modes": []}
        self.render_mode = None
        self.num_envs = num_envs
        try:
            for _ in range(num_envs):
                self._cores.append(EnvCore(config, wait=False))
            for i, core in enumerate(self._cores):
                try:
                    core.finish_configure()
                except (ServerCrashed, VbGymError) as e:
                    raise self._fail(i, e) from None
        except BaseException:
            self.close()
            raise
        self.single_observation_space = self._cores[0].observation_space
        self.single_action_space = self._cores[0].action_space
        self.observation_space = batch_space(self.single_observation_space, num_envs)
        self.action_space = batch_space(self.single_action_space, num_envs)
        self._rngs: list[np.random.Generator | None] = [None] * num_envs
        self._obs = create_empty_array(self.single_observation_space, num_envs)
        self._pending_reset = np.zeros(num_envs, dtype=bool)   # next_step: reset on next step

    @property
    def tasks(self) -> list[dict[str, Any]]:
        return self._cores[0].tasks

    @property
    def server_pids(self) -> list[int | None]:
        return [c.server.pid if c.server else None for c in self._cores]

    def _rng(self, i: int) -> np.random.Generator:
        if self._rngs[i] is None:
            self._rngs[i], _ = seeding.np_random()
        return self._rngs[i]

    def _fail(self, i: int, error: Exception) -> Exception:
        """The error of worker i, named (the other workers are closed: lock step is broken)."""
        self.close()
        if isinstance(error, ServerCrashed):
            return ServerCrashed(f"vector env worker {i}: {error}", error.exit_code,
                                 error.stderr_tail)
        if isinstance(error, VbGymError):
            return VbGymError(error.op, error.kind, f"vector env worker {i}: {error}")
        return error

    def reset(self, *, seed: int | Sequence[int | None] | None = None,
              options: dict[str, Any] | None = None) -> tuple[Any, dict[str, Any]]:
        if self.closed:
            raise RuntimeError("the vector env is closed")
        if seed is None:
            seeds: list[int | None] = [None] * self.num_envs
        elif isinstance(seed, (int, np.integer)):
            seeds = [int(seed) + i for i in range(self.num_envs)]
        else:
            seeds = list(seed)
            if len(seeds) != self.num_envs:
                raise ValueError(f"seed: {len(seeds)} seeds for {self.num_envs} envs")
        for i, s in enumerate(seeds):
            if s is not None:
                self._rngs[i], _ = seeding.np_random(s)
        infos: dict[str, Any] = {}
        results = self._reset_envs(range(self.num_envs), options)
        for i, (obs, info) in results.items():
            infos = self._add_info(infos, info, i)
        self._obs = self._batch([results[i][0] for i in range(self.num_envs)])
        self._pending_reset[:] = False
        return self._obs, infos

    def _episode_options(self, i: int, options: dict[str, Any] | None
                         ) -> dict[str, Any] | None:
        """The reset options of env i's next episode: the caller's (subclasses may choose)."""
        return options

    def _reset_envs(self, indices: Sequence[int], options: dict[str, Any] | None
                    ) -> dict[int, tuple[Any, dict[str, Any]]]:
        for i in indices:
            opts = self._episode_options(i, options)
            try:
                self._cores[i].send_reset(*draw_episode(self._cores[i], self._rng(i), opts))
            except (ServerCrashed, VbGymError) as e:
                raise self._fail(i, e) from None
        out = {}
        for i in indices:
            try:
                out[i] = self._cores[i].receive_reset()
            except (ServerCrashed, VbGymError) as e:
                raise self._fail(i, e) from None
        return out

    def step(self, actions: Any) -> tuple[Any, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
        if self.closed:
            raise RuntimeError("the vector env is closed")
        actions = np.asarray(actions)
        if actions.shape != self.action_space.shape:
            raise ValueError(f"actions: expected shape {self.action_space.shape}, got "
                             f"{actions.shape}")
        n = self.num_envs
        rewards = np.zeros(n, dtype=np.float64)
        terminations = np.zeros(n, dtype=np.bool_)
        truncations = np.zeros(n, dtype=np.bool_)
        observations: list[Any] = [None] * n
        env_infos: list[dict[str, Any]] = [{} for _ in range(n)]
        # Send all requests, then read all replies: the servers step in parallel.
        resetting = [i for i in range(n) if self._pending_reset[i]]
        stepping = [i for i in range(n) if not self._pending_reset[i]]
        for i in resetting:
            try:
                self._cores[i].send_reset(*draw_episode(self._cores[i], self._rng(i), None))
            except (ServerCrashed, VbGymError) as e:
                raise self._fail(i, e) from None
        for i in stepping:
            try:
                self._cores[i].send_step(actions[i])
            except (ServerCrashed, VbGymError) as e:
                raise self._fail(i, e) from None
        for i in range(n):
            try:
                if self._pending_reset[i]:
                    observations[i], env_infos[i] = self._cores[i].receive_reset()
                    self._pending_reset[i] = False
                else:
                    (observations[i], rewards[i], terminations[i], truncations[i],
                     env_infos[i]) = self._cores[i].receive_step()
            except (ServerCrashed, VbGymError) as e:
                raise self._fail(i, e) from None
        ended = [i for i in stepping if terminations[i] or truncations[i]]
        if self.autoreset_mode == AutoresetMode.NEXT_STEP:
            self._pending_reset[ended] = True
        elif ended:
            # As gymnasium's same-step mode: the info is the new episode's, the ended one's last
            # observation and info are in final_obs / final_info.
            for i, (obs, info) in self._reset_envs(ended, None).items():
                info["final_obs"] = observations[i]
                info["final_info"] = env_infos[i]
                observations[i], env_infos[i] = obs, info
        infos: dict[str, Any] = {}
        for i in range(n):
            infos = self._add_info(infos, env_infos[i], i)
        self._obs = self._batch(observations)
        return self._obs, rewards, terminations, truncations, infos

    def _batch(self, observations: list[Any]) -> Any:
        """A fresh batch (never a buffer the next step overwrites: callers keep observations)."""
        out = create_empty_array(self.single_observation_space, self.num_envs)
        return concatenate(self.single_observation_space, observations, out)

    @staticmethod
    def _info_of(infos: dict[str, Any], i: int) -> dict[str, Any]:
        """Env i's entries of a batched info dict (for final_info)."""
        out = {}
        for key, value in infos.items():
            if key.startswith("_"):
                continue
            mask = infos.get("_" + key)
            if isinstance(value, dict):
                out[key] = VbVectorEnv._info_of(value, i)
            elif mask is None or mask[i]:
                out[key] = value[i]
        return out

    def close_extras(self, **kwargs: Any) -> None:
        for core in self._cores:
            core.close()

    def close(self, **kwargs: Any) -> None:
        if self.closed:
            return
        self.close_extras(**kwargs)
        self.closed = True

    def __enter__(self) -> "VbVectorEnv":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __del__(self) -> None:
        try:
            self.close()
        except Exception:  # noqa: BLE001 - interpreter shutdown
            pass
