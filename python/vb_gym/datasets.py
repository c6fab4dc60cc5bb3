"""Reading vb datasets (docs/datasets.md) with numpy and h5py only, for users who do not want
Minari: episodes as dicts of arrays, and (state, action, map, next_state) transitions for model
learning.

    from vb_gym.datasets import episodes, transitions
    for t in transitions("results/explore"):        # DIR, DIR/data or the .hdf5 file
        t.state, t.action, t.map["elevation"], t.next_state

The same files load in Minari: ``minari.load_dataset(id)`` with ``MINARI_DATASETS_PATH`` set so
that ``$MINARI_DATASETS_PATH/<id>`` is the collection directory, or
``minari.MinariDataset("DIR/data")``.
"""

from __future__ import annotations

import os
from typing import Any, Iterator, NamedTuple

import numpy as np

# The robot state of the transitions (world x east, y north, z up; body x forward, y left, z up;
# SI units, radians): position, roll/pitch/yaw, world velocity, body angular velocity, speed
# along the chassis axis.
ROBOT_STATE_NAMES = (
    "x_m", "y_m", "z_m", "roll_rad", "pitch_rad", "yaw_rad", "vx_mps", "vy_mps", "vz_mps",
    "roll_rate_radps", "pitch_rate_radps", "yaw_rate_radps", "forward_speed_mps",
)


class Transition(NamedTuple):
    state: np.ndarray                 # (13,) float64, ROBOT_STATE_NAMES
    action: np.ndarray                # the dataset's action space (speed: 2, direct: 3)
    map: dict[str, np.ndarray]        # egocentric crops at `state` (observations/<name>)
    next_state: np.ndarray            # (13,) one sample period later


def _h5py():
    try:
        import h5py
    except ImportError as e:   # pragma: no cover - the datasets extra installs it
        raise ImportError('reading datasets needs h5py: pip install -e "python[datasets]"') from e
    return h5py


def dataset_file(path: str | os.PathLike) -> str:
    """The main_data.hdf5 of a collection directory, its data/ folder, or the file itself."""
    p = os.fspath(path)
    for candidate in (p, os.path.join(p, "main_data.hdf5"),
                      os.path.join(p, "data", "main_data.hdf5")):
        if os.path.isfile(candidate):
            return candidate
    raise FileNotFoundError(f"{p}: no dataset (expected DIR/data/main_data.hdf5)")


def _read_group(group: Any) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in group.items():
        out[key] = _read_group(value) if hasattr(value, "keys") else value[()]
    return out


def _attrs(group: Any) -> dict[str, Any]:
    return {k: (v.decode() if isinstance(v, bytes) else v) for k, v in group.attrs.items()}


def dataset_attributes(path: str | os.PathLike) -> dict[str, Any]:
    """The root attributes: dataset_id, spaces (Minari JSON), vb_version, git_commit, ..."""
    with _h5py().File(dataset_file(path), "r") as f:
        return _attrs(f)


def episodes(path: str | os.PathLike) -> Iterator[dict[str, Any]]:
    """Every episode in order: {"id", "attrs", "observations", "actions", "rewards",
    "terminations", "truncations", "infos"} (observations and infos have one row more than
    actions: the samples before and after every transition)."""
    with _h5py().File(dataset_file(path), "r") as f:
        n = int(f.attrs["total_episodes"])
        for i in range(n):
            g = f[f"episode_{i}"]
            ep = _read_group(g)
            ep["id"] = i
            ep["attrs"] = _attrs(g)
            yield ep


def robot_states(infos: dict[str, np.ndarray]) -> np.ndarray:
    """(samples, 13) robot states (ROBOT_STATE_NAMES) from an episode's infos."""
    return np.concatenate(
        [infos["position_m"], infos["rpy_rad"], infos["velocity_mps"],
         infos["angular_velocity_radps"], infos["forward_speed_mps"][:, None]], axis=1)


def transitions(path: str | os.PathLike) -> Iterator[Transition]:
    """(state, action, map, next_state) for every transition of every episode, in order."""
    for ep in episodes(path):
        states = robot_states(ep["infos"])
        crops = {k: v for k, v in ep["observations"].items() if k not in ("state", "wheels")}
        for k in range(len(ep["actions"])):
            yield Transition(states[k], ep["actions"][k], {n: c[k] for n, c in crops.items()},
                             states[k + 1])
