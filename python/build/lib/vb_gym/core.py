"""One environment over one vb_gym process: spaces, observation, action mapping, reward and the
episode's end, split into send/receive halves so a vector env can step many servers at once.

VbEnv (env.py) and VbVectorEnv (vector.py) are thin shells over this class: there is one way to
turn the server's arrays into observations and rewards.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from gymnasium import spaces

from .config import EnvConfig
from .protocol import ServerProcess, decode_arrays
from .reward import step_reward

# Features of the "state" observation (docs/gym.md): vehicle frame x forward, y left, SI units.
STATE_NAMES = (
    "local_goal_forward_m", "local_goal_left_m", "goal_forward_m", "goal_left_m",
    "goal_distance_m", "heading_error_rad", "forward_speed_mps", "roll_rad", "pitch_rad",
    "roll_rate_radps", "pitch_rate_radps", "yaw_rate_radps", "vz_mps", "gear",
    "engine_speed_radps", "throttle", "steering", "braking", "time_s",
)
# Outcomes that end the MDP (terminated) and those that cut it short (truncated).
TERMINATED = frozenset({"success", "rollover", "out_of_bounds", "sim_error"})
TRUNCATED = frozenset({"timeout", "stuck"})
CROP_BOUNDS = {
    "elevation": (-np.inf, np.inf),
    "semantics": (0.0, 9.0),
    "occupancy": (0.0, 1.0),
    "friction": (0.0, np.inf),
}


class EnvCore:
    def __init__(self, config: EnvConfig, wait: bool = True):
        """Starts the server and sends configure; with wait=False the caller finishes with
        finish_configure() (a vector env configures all its servers at once: loading 100 tasks
        takes seconds)."""
        config.validate()
        self.config = config
        self.server: ServerProcess | None = None
        self.server = ServerProcess(config.server_binary, config.timeout_s)
        self.server.send(config.configure_request())
        if wait:
            self.finish_configure()

    def finish_configure(self) -> None:
        config = self.config
        reply, _ = self.server.receive()
        self.tasks: list[dict[str, Any]] = reply["tasks"]
        self.state_fields: list[str] = reply["state_fields"]
        self._si = {name: i for i, name in enumerate(self.state_fields)}
        self.num_wheels = int(reply["num_wheels"])
        self.control_period_s = float(reply["control_period_s"])
        for t in self.tasks:
            bad = [p for p in (config.pairs or []) if p >= t["pairs"]]
            if bad:
                raise ValueError(f"pairs: {bad} out of range for task {t['file']} "
                                 f"({t['pairs']} pairs)")
        self.observation_space = self._make_observation_space()
        self.action_space = self._make_action_space()
        self._dict_space = self._make_dict_space()
        self._state: np.ndarray | None = None   # the server's state array (float64)
        self._arrays: dict[str, np.ndarray] = {}
        self.episode: dict[str, Any] = {}
        self.done = True

    # --- spaces ---
    def _make_dict_space(self) -> spaces.Dict:
        d: dict[str, spaces.Space] = {
            "state": spaces.Box(-np.inf, np.inf, (len(STATE_NAMES),), np.float32)}
        if self.config.include_wheels:
            d["wheels"] = spaces.Box(-np.inf, np.inf, (self.num_wheels, 6), np.float32)
        for c in self.config.crops:
            lo, hi = CROP_BOUNDS[c.layer]
            d[c.key] = spaces.Box(lo, hi, (c.size_cells, c.size_cells), np.float32)
        return spaces.Dict(d)

    def _make_observation_space(self) -> spaces.Space:
        d = self._make_dict_space()
        return spaces.flatten_space(d) if self.config.flatten else d

    def _make_action_space(self) -> spaces.Box:
        n = 2 if self.config.action == "speed" else 3
        return spaces.Box(-1.0, 1.0, (n,), np.float32)

    # --- observation ---
    def _s(self, name: str) -> float:
        return float(self._state[self._si[name]])

    def observation(self) -> Any:
        values = self._state.tolist()
        si = self._si

        def s(name: str) -> float:
            return values[si[name]]

        yaw = s("yaw_rad")
        c, sn = math.cos(yaw), math.sin(yaw)

        def ego(px: float, py: float) -> tuple[float, float]:
            dx, dy = px - s("x_m"), py - s("y_m")
            return c * dx + sn * dy, -sn * dx + c * dy

        lf, ll = ego(s("local_goal_x_m"), s("local_goal_y_m"))
        gf, gl = ego(s("goal_x_m"), s("goal_y_m"))
        state = np.array(
            [lf, ll, gf, gl, s("goal_distance_m"), s("heading_error_rad"),
             s("forward_speed_mps"), s("roll_rad"), s("pitch_rad"), s("roll_rate_radps"),
             s("pitch_rate_radps"), s("yaw_rate_radps"), s("vz_mps"), s("gear"),
             s("engine_speed_radps"), s("throttle"), s("steering"), s("braking"), s("time_s")],
            dtype=np.float32)
        obs: dict[str, np.ndarray] = {"state": state}
        if self.config.include_wheels:
            obs["wheels"] = self._arrays["wheels"].astype(np.float32)
        for crop in self.config.crops:
            a = self._arrays[crop.key].astype(np.float32)
            if crop.layer == "elevation":
                if self.config.relative_elevation:
                    a = a - np.float32(s("z_m"))
                if self.config.perception != "none":
                    a = np.nan_to_num(a, nan=np.float32(self.config.unknown_elevation_m))
            obs[crop.key] = a
        if self.config.flatten:
            return spaces.flatten(self._dict_space, obs)
        return obs

    # --- requests ---
    def send_reset(self, task: int, pair: int, trial_seed: int) -> None:
        self.server.send({"op": "reset", "task": int(task), "pair": int(pair),
                          "seed": int(trial_seed), "system": self.config.system})

    def receive_reset(self) -> tuple[Any, dict[str, Any]]:
        header, payload = self.server.receive()
        self._take(header, payload)
        self.episode = {"task": header["task"], "task_name": self.tasks[header["task"]]["name"],
                        "pair": header["pair"], "seed": header["seed"]}
        self.done = header["done"]
        return self.observation(), self._info(header)

    def command(self, action: Any) -> dict[str, Any]:
        a = np.asarray(action, dtype=np.float64)
        if a.shape != self.action_space.shape:
            raise ValueError(f"action: expected shape {self.action_space.shape}, got {a.shape}")
        a = a.tolist()
        if not all(math.isfinite(x) for x in a):
            raise ValueError(f"action: non-finite values {a}")
        a = [min(max(x, -1.0), 1.0) for x in a]
        if self.config.action == "speed":
            return {"op": "step", "steering": float(a[0]),
                    "speed_mps": float(a[1]) * float(self.config.max_speed_mps)}
        return {"op": "step", "throttle": 0.5 * (float(a[0]) + 1.0), "steering": float(a[1]),
                "braking": 0.5 * (float(a[2]) + 1.0)}

    def send_step(self, action: Any) -> None:
        if self.done:
            raise RuntimeError("step() after the episode ended: call reset()")
        self.server.send(self.command(action))

    def receive_step(self) -> tuple[Any, float, bool, bool, dict[str, Any]]:
        prev_xy = (self._s("x_m"), self._s("y_m"))
        header, payload = self.server.receive()
        self._take(header, payload)
        status = header["status"]
        reward, terms = step_reward(
            self.config.reward, self.control_period_s, prev_xy, (self._s("x_m"), self._s("y_m")),
            (self._s("local_goal_x_m"), self._s("local_goal_y_m")), self._s("roll_rad"),
            self._s("pitch_rad"), status, self._s("goal_distance_m"))
        self.done = header["done"]
        terminated = status in TERMINATED
        truncated = status in TRUNCATED
        info = self._info(header)
        info["reward_terms"] = terms
        return self.observation(), float(reward), terminated, truncated, info

    def _take(self, header: dict[str, Any], payload: bytes) -> None:
        self._arrays = decode_arrays(header, payload)
        self._state = self._arrays["state"]
        self._header = header

    def _info(self, header: dict[str, Any]) -> dict[str, Any]:
        info = dict(self.episode)
        info["time_s"] = header["time_s"]
        info["status"] = header["status"]
        if header["done"]:
            info["outcome"] = header["result"]
        return info

    def request(self, header: dict[str, Any]) -> dict[str, Any]:
        return self.server.request(header)[0]

    def close(self) -> None:
        if self.server is not None:
            self.server.close()
            self.server = None
