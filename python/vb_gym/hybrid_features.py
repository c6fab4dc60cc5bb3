"""Training data of the hybrid baselines (WMVCT, MPPI-6, TAL, TNT; docs/learning.md "Hybrid
kinodynamic models"), numpy + h5py only.

Every learned model of the four reads the same terrain description of a planar pose (x, y, yaw):
the terrain height at 15 points of an egocentric 5 x 3 grid (forward 2, 1, 0, -1, -2 m; left 1, 0,
-1 m; forward-major, as the dataset's crops: row 0 farthest ahead, column 0 far left), minus the
height at the centre point. The C++ planners sample the same points on the ground-truth surface
(src/controllers/hybrid_terrain.cc); here they come from the dataset's 64 x 64 elevation crops at
0.1 m, where every grid point falls between four cells (bilinear = their mean).

A model step is two dataset samples (0.2 s): at the explorer's 2 m/s that is 0.4 m, the length of
an MPPI rollout step (0.35-0.47 m), so the learned models and the planner use steps of the same
length.
"""

from __future__ import annotations

import numpy as np

from vb_gym.datasets import dataset_file, _h5py

GRID_FORWARD_M = (2.0, 1.0, 0.0, -1.0, -2.0)
GRID_LEFT_M = (1.0, 0.0, -1.0)
GRID_POINTS = len(GRID_FORWARD_M) * len(GRID_LEFT_M)   # 15
CENTRE_INDEX = 7                                        # forward 0, left 0
NUM_CLASSES = 10                                        # surface classes 0..9
STRIDE = 2                                              # dataset samples per model step
STEP_S = 0.2
TERRAINS = ("rigid", "deformable", "mixed")


def grid_offsets() -> np.ndarray:
    """(15, 2) (forward, left) offsets in metres, forward-major."""
    return np.array([(f, l) for f in GRID_FORWARD_M for l in GRID_LEFT_M], dtype=np.float64)


def crop_grid_values(crops: np.ndarray, resolution_m: float = 0.1) -> np.ndarray:
    """(N, 15) values of (N, n, n) egocentric crops at the grid points (bilinear).

    Crop cell (i, j) is at forward ((n-1)/2 - i) res, left ((n-1)/2 - j) res (gt_maps.h)."""
    n = crops.shape[-1]
    out = np.empty((crops.shape[0], GRID_POINTS), dtype=np.float64)
    for g, (f, l) in enumerate(grid_offsets()):
        i = (n - 1) / 2.0 - f / resolution_m
        j = (n - 1) / 2.0 - l / resolution_m
        i0, j0 = int(np.floor(i)), int(np.floor(j))
        a, b = i - i0, j - j0
        out[:, g] = ((1 - a) * (1 - b) * crops[:, i0, j0] + (1 - a) * b * crops[:, i0, j0 + 1] +
                     a * (1 - b) * crops[:, i0 + 1, j0] + a * b * crops[:, i0 + 1, j0 + 1])
    return out


def extract(path, max_episodes: int | None = None, progress: bool = False) -> dict:
    """Per-sample arrays of a dataset (explore mode), episodes concatenated:

    episode (N,) int, world_seed (N,), terrain (N,) index in TERRAINS, status code,
    pos (N, 3), rpy (N, 3), speed (N,) forward speed, steer (N,) steering action applied from the
    sample on (0 at the last), heights (N, 15) grid heights minus the chassis reference height,
    semantic (N,) surface class under the centre point, slip (N,) mean |longitudinal slip| of
    the wheels."""
    h5py = _h5py()
    cols: dict[str, list] = {k: [] for k in ("episode", "world_seed", "terrain", "pos", "rpy",
                                             "speed", "steer", "heights", "semantic",
                                             "slip")}
    with h5py.File(dataset_file(path), "r") as f:
        n = int(f.attrs["total_episodes"])
        if max_episodes is not None:
            n = min(n, max_episodes)
        for e in range(n):
            g = f[f"episode_{e}"]
            a = g.attrs
            res = float(str(a["crops"]).split(",")[0].split("x")[1])
            pos = g["infos/position_m"][()]
            m = pos.shape[0]
            elev = g["observations/elevation"][()]
            sem = g["observations/semantics"][()]
            c = sem.shape[-1] // 2
            cols["episode"].append(np.full(m, e, np.int32))
            cols["world_seed"].append(np.full(m, int(a["world_seed"]), np.int32))
            cols["terrain"].append(np.full(m, TERRAINS.index(str(a["terrain"])), np.int8))
            cols["pos"].append(pos)
            cols["rpy"].append(g["infos/rpy_rad"][()])
            cols["speed"].append(g["infos/forward_speed_mps"][()])
            steer = np.zeros(m)
            steer[:-1] = g["actions"][()][:, 0]
            cols["steer"].append(steer)
            cols["heights"].append(crop_grid_values(elev, res))
            cols["semantic"].append(sem[:, c, c].astype(np.int8))
            cols["slip"].append(np.abs(g["infos/wheel_slip"][()]).mean(axis=1))
            if progress and e % 50 == 0:
                print(f"episode {e}/{n}", flush=True)
    return {k: np.concatenate(v) for k, v in cols.items()}


def wrap(a):
    return (a + np.pi) % (2 * np.pi) - np.pi


def step_pairs(d: dict, stride: int = STRIDE) -> dict:
    """Model steps (sample k -> k + stride within one episode), as the planners see them:

    shape_k (15) = heights at k minus the centre height, shape_n (15) the same at k + stride,
    roll/pitch at k and k + stride, z_rel_n = chassis z minus centre terrain height at k + stride,
    z_rel_k the same at k, ds_cmd = speed_k * stride * 0.1 s, steer = mean steering over the step,
    body-frame displacement (dx, dy) and dyaw, semantic class and terrain type of the episode."""
    ep = d["episode"]
    k = np.arange(len(ep) - stride)
    k = k[ep[k] == ep[k + stride]]
    n = k + stride
    h = d["heights"]
    centre = h[:, CENTRE_INDEX:CENTRE_INDEX + 1]
    shape = h - centre
    yaw = d["rpy"][:, 2]
    dxy = d["pos"][n, :2] - d["pos"][k, :2]
    c, s = np.cos(yaw[k]), np.sin(yaw[k])
    steer = np.mean([d["steer"][k + i] for i in range(stride)], axis=0)
    return {
        "k": k, "n": n, "episode": ep[k], "world_seed": d["world_seed"][k],
        "terrain": d["terrain"][k],
        "shape_k": shape[k], "shape_n": shape[n],
        "roll_k": d["rpy"][k, 0], "pitch_k": d["rpy"][k, 1],
        "roll_n": d["rpy"][n, 0], "pitch_n": d["rpy"][n, 1],
        # heights are relative to the chassis: terrain centre height = z + centre, so
        # z - terrain centre = -centre
        "z_rel_k": -centre[k, 0], "z_rel_n": -centre[n, 0],
        "ds_cmd": d["speed"][k] * stride * 0.1, "steer": steer,
        "dx_body": c * dxy[:, 0] + s * dxy[:, 1], "dy_body": -s * dxy[:, 0] + c * dxy[:, 1],
        "dyaw": wrap(yaw[n] - yaw[k]),
        # terrain centre height change in the world (for z over a rollout)
        "dcentre_world": (d["pos"][n, 2] + centre[n, 0]) - (d["pos"][k, 2] + centre[k, 0]),
        "semantic_k": d["semantic"][k],
    }


def progress_ratio(d: dict, horizon_s: float = 1.0, speed_mps: float = 2.0) -> np.ndarray:
    """(N,) planar distance covered in the next horizon_s divided by speed_mps * horizon_s,
    clipped to [0, 1]; samples whose episode ends sooner get the ratio of what remains (an episode
    ends stuck, rolled over or out of the world)."""
    ep = d["episode"]
    steps = int(round(horizon_s / 0.1))
    out = np.empty(len(ep))
    pos = d["pos"][:, :2]
    for e in np.unique(ep):
        idx = np.nonzero(ep == e)[0]
        p = pos[idx]
        j = np.minimum(np.arange(len(idx)) + steps, len(idx) - 1)
        out[idx] = np.linalg.norm(p[j] - p, axis=1) / (speed_mps * horizon_s)
    return np.clip(out, 0.0, 1.0)


def traversability(d: dict, horizon_s: float = 1.0, speed_mps: float = 2.0) -> np.ndarray:
    """(N,) TNT's label: progress_ratio x (1 - mean |wheel slip| over the same horizon), in [0, 1]:
    the fraction of the commanded speed achieved, discounted by how much the wheels slipped to
    achieve it. Progress alone hardly separates the surfaces at the explorer's 2 m/s (mean 0.73
    on concrete, 0.68 on mud: most slow samples are the vehicle against a rock or tree, which the
    terrain grid does not see); slip does (median 0.11 on concrete, 0.45 on mud)."""
    ep = d["episode"]
    steps = int(round(horizon_s / 0.1))
    slip = np.empty(len(ep))
    for e in np.unique(ep):
        idx = np.nonzero(ep == e)[0]
        c = np.concatenate([[0.0], np.cumsum(np.clip(d["slip"][idx], 0.0, 1.0))])
        i = np.arange(len(idx))
        j = np.minimum(i + steps, len(idx) - 1)
        slip[idx] = (c[j + 1] - c[i]) / (j + 1 - i)
    return np.clip(progress_ratio(d, horizon_s, speed_mps) * (1.0 - slip), 0.0, 1.0)
