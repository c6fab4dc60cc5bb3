"""Small reference policies (for examples, tests and as a template for your own system).

A policy factory takes the env and returns ``policy(obs) -> action`` (optionally with
``reset(info)``); ``python -m vb_gym.evaluate --policy vb_gym.policies:heading_follower`` runs it.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .core import STATE_NAMES

_HEADING = STATE_NAMES.index("heading_error_rad")


def heading_follower(env: Any, speed_fraction: float = 0.75):
    """Steer towards the local goal on the global path (steering = heading error, as vb's PID
    without its rate limit) at a fixed fraction of the maximum target speed ("speed" actions,
    Dict observations)."""
    if env.config.action != "speed" or env.config.flatten:
        raise ValueError("heading_follower needs action='speed' and Dict observations")

    def policy(obs: dict[str, np.ndarray]) -> np.ndarray:
        steering = float(np.clip(obs["state"][_HEADING], -1.0, 1.0))
        return np.array([steering, speed_fraction], dtype=np.float32)

    return policy
