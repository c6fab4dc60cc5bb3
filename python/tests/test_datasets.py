"""vb_collect datasets read by vb_gym.datasets (numpy + h5py) and by Minari from PyPI
(docs/datasets.md): shapes, transitions, the spaces equal the gym interface's, rewards equal
vb_gym's reward function, and minari.load_dataset loads the files as they are."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from vb_gym import datasets
from vb_gym.core import CROP_BOUNDS, STATE_NAMES, TERMINATED, TRUNCATED
from vb_gym.reward import RewardWeights, step_reward

EPISODES = 3


@pytest.fixture(scope="module")
def collection(tmp_path_factory: pytest.TempPathFactory) -> Path:
    vb_collect = Path(os.environ.get("VB_GYM_BIN", "")).with_name("vb_collect")
    assert vb_collect.exists(), "vb_collect must be built next to vb_gym"
    root = tmp_path_factory.mktemp("datasets")
    out = root / "vb" / "explore-v0"       # $MINARI_DATASETS_PATH/<dataset id>
    subprocess.run([str(vb_collect), "explore", "--out", str(out), "--episodes", str(EPISODES),
                    "--episodes-per-world", "3", "--max-episode-s", "4", "--crop-size", "8",
                    "--crop-res", "0.5", "--quiet"], check=True, capture_output=True)
    return out


def test_reader_yields_consistent_transitions(collection: Path) -> None:
    attrs = datasets.dataset_attributes(collection)
    assert attrs["total_episodes"] == EPISODES
    eps = list(datasets.episodes(collection))
    assert len(eps) == EPISODES
    for ep in eps:
        n = len(ep["actions"])
        assert n == 40                                  # 4 s at 0.1 s
        assert ep["actions"].shape == (n, 2)
        assert ep["observations"]["state"].shape == (n + 1, len(STATE_NAMES))
        assert ep["observations"]["wheels"].shape == (n + 1, 4, 6)
        assert ep["observations"]["elevation"].shape == (n + 1, 8, 8)
        assert ep["terminations"].dtype == np.bool_
        assert ep["attrs"]["mode"] == "explore"
        assert ep["attrs"]["seed"] >= 1000 * 100
        assert ep["attrs"]["git_commit"] == attrs["git_commit"]
    ts = list(datasets.transitions(collection))
    assert len(ts) == EPISODES * 40
    np.testing.assert_array_equal(ts[0].next_state, ts[1].state)
    assert ts[0].map["semantics"].shape == (8, 8)
    assert set(np.unique(ts[0].map["semantics"])) <= set(range(10))


def test_rewards_and_state_match_the_gym_interface(collection: Path) -> None:
    w = RewardWeights()
    for ep in datasets.episodes(collection):
        inf = ep["infos"]
        status = ep["attrs"]["status"]
        n = len(ep["actions"])
        for k in range(n):
            s = status if k == n - 1 else "running"
            dt = inf["time_s"][k + 1] - inf["time_s"][k]
            r, _ = step_reward(w, dt, tuple(inf["position_m"][k, :2]),
                               tuple(inf["position_m"][k + 1, :2]),
                               tuple(inf["local_goal_m"][k + 1]), inf["rpy_rad"][k + 1, 0],
                               inf["rpy_rad"][k + 1, 1], s, inf["goal_distance_m"][k + 1])
            assert math.isclose(ep["rewards"][k], r, rel_tol=1e-9, abs_tol=1e-9)
        assert bool(ep["terminations"][-1]) == (status in TERMINATED)
        assert bool(ep["truncations"][-1]) == (status in TRUNCATED)
        st = ep["observations"]["state"]
        i = {name: j for j, name in enumerate(STATE_NAMES)}
        np.testing.assert_allclose(st[:, i["forward_speed_mps"]], inf["forward_speed_mps"],
                                   rtol=1e-6, atol=1e-6)
        np.testing.assert_allclose(st[:, i["time_s"]], inf["time_s"], atol=1e-6)
        np.testing.assert_allclose(st[:, i["steering"]], inf["command"][:, 1], atol=1e-6)


def test_spaces_are_the_gym_interfaces(collection: Path) -> None:
    meta = json.loads((collection / "data" / "metadata.json").read_text())
    obs = json.loads(meta["observation_space"])
    assert obs["type"] == "Dict"
    assert list(obs["subspaces"]) == ["state", "wheels", "elevation", "semantics"]
    assert obs["subspaces"]["state"]["shape"] == [len(STATE_NAMES)]
    lo, hi = CROP_BOUNDS["semantics"]
    assert obs["subspaces"]["semantics"]["low"][0][0] == lo
    assert obs["subspaces"]["semantics"]["high"][0][0] == hi
    assert obs["subspaces"]["elevation"]["low"][0][0] == -math.inf
    act = json.loads(meta["action_space"])
    assert act["shape"] == [2] and act["low"] == [-1.0, -1.0]


def test_minari_loads_the_dataset(collection: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    minari = pytest.importorskip("minari")
    from gymnasium import spaces
    monkeypatch.setenv("MINARI_DATASETS_PATH", str(collection.parent.parent))
    ds = minari.load_dataset("vb/explore-v0")
    assert ds.total_episodes == EPISODES
    assert ds.total_steps == EPISODES * 40
    assert isinstance(ds.observation_space, spaces.Dict)
    assert ds.action_space == spaces.Box(-1.0, 1.0, (2,), np.float32)
    eps = list(ds.iterate_episodes())
    assert len(eps) == EPISODES
    ours = list(datasets.episodes(collection))
    for mine, theirs in zip(ours, eps):
        np.testing.assert_array_equal(theirs.actions, mine["actions"])
        np.testing.assert_array_equal(theirs.observations["elevation"],
                                      mine["observations"]["elevation"])
        assert ds.observation_space.contains({k: v[0] for k, v in theirs.observations.items()})
    meta = list(ds.storage.get_episode_metadata([0]))[0]
    assert meta["seed"] == ours[0]["attrs"]["seed"]


# Teleoperated demonstrations (docs/datasets.md): the committed vb_view recordings in
# test/data/teleop, collected with the settings of the committed oracle demonstration sample
# (docs/results/datasets/demos_sample: 16² crops at 0.25 m, a sample every 0.5 s), have exactly
# its schema.
SOURCE = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def teleop_collection(tmp_path_factory: pytest.TempPathFactory) -> Path:
    vb_collect = Path(os.environ.get("VB_GYM_BIN", "")).with_name("vb_collect")
    out = tmp_path_factory.mktemp("teleop") / "vb" / "teleop-v0"
    subprocess.run([str(vb_collect), "teleop", str(SOURCE / "test" / "data" / "teleop"),
                    "--out", str(out), "--crop-size", "16", "--crop-res", "0.25",
                    "--sample-period", "0.5", "--quiet"], check=True, capture_output=True)
    return out


def _schema(group) -> dict:
    out = {}
    group.visititems(lambda name, obj: out.__setitem__(name, (obj.dtype.str, obj.shape[1:]))
                     if hasattr(obj, "dtype") else None)
    return out


def test_teleop_dataset_has_the_demonstrations_schema(teleop_collection: Path) -> None:
    h5py = pytest.importorskip("h5py")
    demos = SOURCE / "docs" / "results" / "datasets" / "demos_sample" / "main_data.hdf5"
    with h5py.File(demos, "r") as d, \
            h5py.File(teleop_collection / "data" / "main_data.hdf5", "r") as t:
        assert t.attrs["total_episodes"] == 1            # the success; the stopped drive filtered
        for key in ("observation_space", "action_space", "vb_action_space"):
            assert t.attrs[key] == d.attrs[key], key
        assert set(t.attrs) == set(d.attrs)
        ep, ref = t["episode_0"], d["episode_0"]
        assert _schema(ep) == _schema(ref)
        # Every attribute of a demonstration except the generated world's labels, and the source.
        world_only = {"world_seed", "elevation", "terrain", "density"}
        assert set(ref.attrs) - world_only <= set(ep.attrs)
        assert ep.attrs["source"] == "teleop" and ep.attrs["mode"] == "teleop"
        assert ep.attrs["operator"] == "scripted"
        assert ep.attrs["status"] == "success" and bool(ep["terminations"][-1])
        assert ep.attrs["crops"] == ref.attrs["crops"]
        assert ep["infos"]["goal_distance_m"][-1] <= 10.0


def test_minari_loads_the_teleop_dataset(teleop_collection: Path,
                                         monkeypatch: pytest.MonkeyPatch) -> None:
    minari = pytest.importorskip("minari")
    monkeypatch.setenv("MINARI_DATASETS_PATH", str(teleop_collection.parent.parent))
    ds = minari.load_dataset("vb/teleop-v0")
    assert ds.total_episodes == 1
    (ep,) = list(ds.iterate_episodes())
    assert ep.actions.shape[1] == 3
    assert ds.action_space.contains(ep.actions[0])
    assert ds.observation_space.contains({k: v[0] for k, v in ep.observations.items()})
    meta = list(ds.storage.get_episode_metadata([0]))[0]
    assert meta["source"] == "teleop"


def test_a_fresh_scripted_drive_through_vb_view_replays(tmp_path: Path) -> None:
    """The whole chain on this build: vb_view teleop driven over its WebSocket by the scripted
    driver (the page's key ramps), then vb_collect teleop, which re-simulates the drive and
    checks it bit for bit (exit 2 otherwise)."""
    bin_dir = Path(os.environ.get("VB_GYM_BIN", "")).parent
    rec = tmp_path / "rec"
    run = subprocess.run([sys.executable, str(SOURCE / "scripts" / "teleop_scripted_drive.py"),
                          "--vb-view", str(bin_dir / "vb_view"),
                          "--task", str(SOURCE / "test" / "data" / "teleop" / "teleop_demo.yaml"),
                          "--out", str(rec), "--operator", "pytest", "W@0-10,D@0.5-0.8"],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip().endswith(": success"), run.stdout
    out = tmp_path / "ds"
    # The task lies elsewhere than beside the recording: --tasks names its directory.
    col = subprocess.run([str(bin_dir / "vb_collect"), "teleop", str(rec), "--out", str(out),
                          "--tasks", str(SOURCE / "test" / "data" / "teleop"),
                          "--crop-size", "8", "--crop-res", "0.5", "--quiet"],
                         capture_output=True, text=True)
    assert col.returncode == 0, col.stdout + col.stderr
    (ep,) = list(datasets.episodes(out))
    assert ep["attrs"]["operator"] == "pytest" and ep["attrs"]["status"] == "success"
    assert ep["infos"]["position_m"][-1, 0] - ep["infos"]["position_m"][0, 0] > 10.0
