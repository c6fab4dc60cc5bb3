"""The observation and action of vb's learned baselines RL, MCL and ACL (docs/learning.md).

One definition, used for training (vb_gym.train) and mirrored operation for operation by the C++
controller that runs the trained policies in vb_run / vb_batch (src/controllers/
learned_features.cc; a test checks both give the same vector on the same observation).

Observation: 76 float32 features computed from the gym's Dict observation with
``learned_env_config`` (state + one elevation crop, no wheels):

* 12 state features, each scaled to about [-1, 1] and clipped to [-CLIP, CLIP]:
  heading error to the local goal / pi, local goal forward and left / 10 m, goal distance / 100 m,
  forward speed / 4 m/s, roll / 0.5 rad, pitch / 0.5 rad, roll, pitch and yaw rates (rad/s),
  vertical speed / 2 m/s, the steering applied in the last physics step.
* 64 elevation features: the egocentric elevation crop of 16 x 16 cells of 1 m (16 m square
  centred on the vehicle, row 0 ahead, column 0 left) relative to the chassis height, reduced by
  the mean of each 2 x 2 block to 8 x 8 (row-major), divided by 2 m and clipped to [-CLIP, CLIP].
  A fixed reduction in place of the original's SWAE encoder, whose weights are absent
  (reference_verti_bench.md §7.8).

Action: Box(2) in [-1, 1]: steering (+ left) and target speed x 4 m/s for the speed controller
(kp 1, every 5 ms), as the original; one decision every DECISION_PERIOD_S = 0.1 s.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .config import Crop, EnvConfig
from .core import STATE_NAMES

DECISION_PERIOD_S = 0.1
MAX_SPEED_MPS = 4.0
CROP = Crop("elevation", 16, 1.0)
POOL = 2                       # block size of the mean reduction
ELEVATION_SCALE_M = 2.0
CLIP = 3.0
STATE_FEATURES = (
    "heading_error", "local_goal_forward", "local_goal_left", "goal_distance", "forward_speed",
    "roll", "pitch", "roll_rate", "pitch_rate", "yaw_rate", "vz", "steering",
)
# (state field, multiplier) of each state feature, in order.
_STATE_SCALES = (
    ("heading_error_rad", 1.0 / math.pi),
    ("local_goal_forward_m", 0.1),
    ("local_goal_left_m", 0.1),
    ("goal_distance_m", 0.01),
    ("forward_speed_mps", 1.0 / MAX_SPEED_MPS),
    ("roll_rad", 2.0),
    ("pitch_rad", 2.0),
    ("roll_rate_radps", 1.0),
    ("pitch_rate_radps", 1.0),
    ("yaw_rate_radps", 1.0),
    ("vz_mps", 0.5),
    ("steering", 1.0),
)
_STATE_INDEX = np.array([STATE_NAMES.index(name) for name, _ in _STATE_SCALES])
_STATE_MULT = np.array([m for _, m in _STATE_SCALES], dtype=np.float32)
NUM_ELEVATION = (CROP.size_cells // POOL) ** 2
NUM_FEATURES = len(STATE_FEATURES) + NUM_ELEVATION


def learned_env_config(tasks: Any, **kwargs: Any) -> EnvConfig:
    """The gym configuration the learned systems are trained and evaluated with."""
    return EnvConfig(tasks=tasks, crops=(CROP,), include_wheels=False, action="speed",
                     control_period_s=DECISION_PERIOD_S, max_speed_mps=MAX_SPEED_MPS,
                     relative_elevation=True, **kwargs)


def features(obs: dict[str, np.ndarray]) -> np.ndarray:
    """The feature vector(s) of one Dict observation (state (19,)) or a batch (state (n, 19)):
    float32, shape (76,) or (n, 76)."""
    state = np.asarray(obs["state"], dtype=np.float32)
    crop = np.asarray(obs[CROP.key], dtype=np.float32)
    single = state.ndim == 1
    if single:
        state, crop = state[None], crop[None]
    n = state.shape[0]
    s = state[:, _STATE_INDEX] * _STATE_MULT
    m = CROP.size_cells // POOL
    blocks = crop.reshape(n, m, POOL, m, POOL)
    # Sum in a fixed order (the C++ side adds the same four floats in the same order).
    total = (blocks[:, :, 0, :, 0] + blocks[:, :, 0, :, 1]) + \
            (blocks[:, :, 1, :, 0] + blocks[:, :, 1, :, 1])
    e = total.reshape(n, m * m) * np.float32(1.0 / (POOL * POOL * ELEVATION_SCALE_M))
    out = np.clip(np.concatenate([s, e], axis=1), np.float32(-CLIP), np.float32(CLIP))
    out = out.astype(np.float32)
    return out[0] if single else out


def load_policy(path: str):
    """The exported policy (data/policies/<system>.safetensors) as a numpy function
    features (n, 76) -> clipped actions (n, 2), float32. Needs the safetensors package."""
    from safetensors.numpy import load_file
    from safetensors import safe_open

    with safe_open(str(path), "np") as f:
        meta = f.metadata()
    if meta.get("format") != "vb-policy-1":
        raise ValueError(f"{path}: metadata format {meta.get('format')!r} is not 'vb-policy-1'")
    tensors = load_file(str(path))
    indices = sorted(int(k.split(".")[1]) for k in tensors if k.endswith(".weight"))
    acts = meta["policy.activations"].split(",")
    if len(acts) != len(indices):
        raise ValueError(f"{path}: {len(indices)} Linear layers but {len(acts)} activations")
    layers = [(tensors[f"policy.{i}.weight"], tensors[f"policy.{i}.bias"], a)
              for i, a in zip(indices, acts)]

    def forward(x: np.ndarray) -> np.ndarray:
        h = np.asarray(x, np.float32)
        for w, b, a in layers:
            h = h @ w.T + b
            if a == "tanh":
                h = np.tanh(h)
            elif a == "relu":
                h = np.maximum(h, 0)
            elif a != "none":
                raise ValueError(f"{path}: activation {a!r} not supported here")
        return np.clip(h, -1.0, 1.0).astype(np.float32)

    return forward


def _policy_factory(system: str):
    def make(env: Any):
        """vb_gym.evaluate factory: the committed policy data/policies/<system>.safetensors on
        an env configured as learned_env_config (--control-period 0.1 --crops elevation:16:1)."""
        from .config import REPO_ROOT

        cfg = env.config
        if cfg.action != "speed" or cfg.flatten or abs(cfg.control_period_s - DECISION_PERIOD_S) \
                > 1e-12 or tuple(cfg.crops) != (CROP,):
            raise ValueError(f"{system}: needs action speed, Dict observations, control period "
                             f"{DECISION_PERIOD_S} s and crops elevation:16:1")
        forward = load_policy(REPO_ROOT / "data" / "policies" / f"{system}.safetensors")

        def policy(obs: dict[str, np.ndarray]) -> np.ndarray:
            return forward(features(obs)[None])[0]

        return policy

    return make


rl_policy = _policy_factory("rl")
mcl_policy = _policy_factory("mcl")
acl_policy = _policy_factory("acl")
