"""The learned baselines' observation (vb_gym.learned) and level samplers (vb_gym.train.curricula):
numpy only. The training itself needs the sb3 extra: test_learned_train.py."""

from __future__ import annotations

import math

import numpy as np
import pytest

from vb_gym.core import STATE_NAMES
from vb_gym.learned import CLIP, NUM_FEATURES, features, learned_env_config
from vb_gym.train.curricula import (STAGES, SWITCH_WINDOW, ManualCurriculum,
                                    PrioritizedLevelReplay, UniformSampler)
from vb_gym.train.worlds import World

from conftest import RIGID_TASK


def fake_obs(**state) -> dict[str, np.ndarray]:
    s = np.zeros(len(STATE_NAMES), np.float32)
    for k, v in state.items():
        s[STATE_NAMES.index(k)] = v
    crop = np.zeros((16, 16), np.float32)
    return {"state": s, "elevation": crop}


def test_state_features_are_scaled_as_documented():
    obs = fake_obs(heading_error_rad=math.pi / 2, local_goal_forward_m=8.0, local_goal_left_m=-3.0,
                   goal_distance_m=250.0, forward_speed_mps=2.0, roll_rad=0.1, pitch_rad=-0.2,
                   roll_rate_radps=0.3, pitch_rate_radps=-0.4, yaw_rate_radps=0.5, vz_mps=1.0,
                   steering=-0.7)
    f = features(obs)
    assert f.shape == (NUM_FEATURES,) and f.dtype == np.float32
    expected = [0.5, 0.8, -0.3, 2.5, 0.5, 0.2, -0.4, 0.3, -0.4, 0.5, 0.5, -0.7]
    np.testing.assert_allclose(f[:12], expected, rtol=1e-6, atol=1e-7)
    assert np.all(f[12:] == 0.0)


def test_elevation_is_a_2x2_block_mean_over_2_m_clipped():
    obs = fake_obs()
    crop = obs["elevation"]
    crop[0:2, 0:2] = [[1.0, 2.0], [3.0, 4.0]]   # mean 2.5 -> 1.25
    crop[0:2, 14:16] = 20.0                        # -> 10, clipped
    crop[15, 0] = -4.0                             # block (7, 0): mean -1 -> -0.5
    f = features(obs)[12:].reshape(8, 8)
    assert f[0, 0] == pytest.approx(1.25)
    assert f[0, 7] == CLIP
    assert f[7, 0] == pytest.approx(-0.5)
    assert np.count_nonzero(f) == 3


def test_batched_features_equal_single():
    rng = np.random.default_rng(1)
    batch = {"state": rng.normal(size=(3, len(STATE_NAMES))).astype(np.float32),
             "elevation": rng.normal(size=(3, 16, 16)).astype(np.float32)}
    f = features(batch)
    for i in range(3):
        np.testing.assert_array_equal(
            f[i], features({"state": batch["state"][i], "elevation": batch["elevation"][i]}))


def test_env_config_gives_the_feature_inputs(vb_gym_bin):
    from vb_gym import VbEnv
    env = VbEnv(learned_env_config(RIGID_TASK))
    try:
        obs, _ = env.reset(seed=0)
        assert set(obs) == {"state", "elevation"} and obs["elevation"].shape == (16, 16)
        assert env.config.control_period_s == 0.1
        f = features(obs)
        assert np.all(np.isfinite(f)) and np.all(np.abs(f) <= CLIP)
        assert f[3] > 0.5          # goal distance / 100 m: pairs are 120 m apart
    finally:
        env.close()


def worlds() -> list[World]:
    out = []
    seed = 1000
    for e in ("low", "mid", "high"):
        for t in ("rigid", "deformable", "mixed"):
            for d in ("sparse", "medium", "dense"):
                out.append(World(seed, e, t, d, f"w{seed}.yaml"))
                seed += 1
    return out


def test_uniform_sampler_covers_all_levels_and_is_seeded():
    a = UniformSampler(worlds(), 10, np.random.default_rng(3))
    b = UniformSampler(worlds(), 10, np.random.default_rng(3))
    la = [a.sample() for _ in range(2000)]
    assert la == [b.sample() for _ in range(2000)]
    assert len({w for w, _ in la}) == 27 and len({p for _, p in la}) == 10


def test_manual_curriculum_switches_on_success_then_on_budget():
    ws = worlds()
    mcl = ManualCurriculum(ws, 10, np.random.default_rng(0), total_timesteps=1000)
    for _ in range(50):
        w, _ = mcl.sample()
        assert ws[w].elevation == "low" and ws[w].terrain == "rigid" and \
            ws[w].density in ("sparse", "medium")
    for k in range(SWITCH_WINDOW):   # 60 % success in the window: switch
        mcl.on_episode_end((0, 0), "success" if k % 5 < 3 else "stuck", 100 + k)
    assert mcl.stage() == 1 and mcl.switches[0]["at_timestep"] == 100 + SWITCH_WINDOW - 1
    assert {ws[mcl.sample()[0]].elevation for _ in range(200)} == set(STAGES[1][0])
    mcl.on_step(mcl.stage_start + 249)
    assert mcl.stage() == 1
    mcl.on_step(mcl.stage_start + 250)       # 25 % of 1000 steps in stage 1: budget used up
    assert mcl.stage() == 2 and "budget" in mcl.switches[1]["reason"]
    assert len({mcl.sample()[0] for _ in range(2000)}) == 27


def test_plr_replays_high_score_levels():
    plr = PrioritizedLevelReplay(worlds(), 10, np.random.default_rng(0))
    first = [plr.sample() for _ in range(20)]
    assert len(set(first)) >= 10              # mostly unseen levels at first
    for level in first:
        plr.update_score(level, 5.0 if level == first[0] else 0.01)
    p = plr.replay_distribution()
    assert p.sum() == pytest.approx(1.0)
    assert p[plr.index[first[0]]] > 0.7       # rank 1 with temperature 0.1, 30 % staleness
    draws = [plr.sample() for _ in range(400)]
    assert draws.count(first[0]) > 100


@pytest.mark.parametrize("system", ["rl", "mcl", "acl"])
def test_numpy_policy_equals_the_torch_fixture(system):
    pytest.importorskip("safetensors")
    from safetensors.numpy import load_file

    from vb_gym.config import REPO_ROOT
    from vb_gym.learned import load_policy

    forward = load_policy(REPO_ROOT / "data" / "policies" / f"{system}.safetensors")
    fx = load_file(str(REPO_ROOT / "test" / "data" / "learned" / f"forward_{system}.safetensors"))
    np.testing.assert_allclose(forward(fx["inputs"]), np.clip(fx["outputs"], -1, 1), atol=1e-5)
