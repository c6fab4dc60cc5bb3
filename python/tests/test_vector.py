"""VbVectorEnv: N vb_gym processes in lock step; env i reproduces VbEnv(seed + i) bit for bit,
both autoreset modes, a crashed worker named in the error."""

from __future__ import annotations

import os
import signal

import gymnasium as gym
import numpy as np
import pytest

from vb_gym import Crop, EnvConfig, ServerCrashed, VbEnv, VbVectorEnv

from conftest import RIGID_TASK, RIGID_TASK_2

OPTS = dict(tasks=[RIGID_TASK, RIGID_TASK_2], crops=(Crop("elevation", 8, 0.5),))


def test_env_i_reproduces_the_single_env_with_seed_plus_i():
    rng = np.random.default_rng(0)
    actions = rng.uniform(-1, 1, size=(12, 2, 2)).astype(np.float32)
    with VbVectorEnv(2, **OPTS) as venv:
        assert venv.observation_space["state"].shape == (2, 19)
        assert venv.action_space.shape == (2, 2)
        obs, info = venv.reset(seed=10)
        vec_obs = [obs]
        vec_rewards = []
        for a in actions:
            obs, reward, terminated, truncated, info = venv.step(a)
            vec_obs.append(obs)
            vec_rewards.append(reward)
            assert not terminated.any() and not truncated.any()
        pids = venv.server_pids
        assert len(set(pids)) == 2   # one process per env
    for i in range(2):
        with VbEnv(**OPTS) as env:
            obs, info = env.reset(seed=10 + i)
            singles = [obs] + [env.step(actions[k, i])[0] for k in range(len(actions))]
            rewards = []
            env.reset(seed=10 + i)
            for k in range(len(actions)):
                rewards.append(env.step(actions[k, i])[1])
        for k, single in enumerate(singles):
            for key in single:
                assert np.array_equal(vec_obs[k][key][i], single[key]), (i, k, key)
        assert [r[i] for r in vec_rewards] == rewards


def test_next_step_autoreset_starts_a_new_episode_on_the_following_step():
    with VbVectorEnv(2, time_limit_s=0.3, **OPTS) as venv:
        venv.reset(seed=1)
        zero = np.zeros((2, 2), np.float32)
        for _ in range(2):
            _, _, terminated, truncated, _ = venv.step(zero)
            assert not (terminated | truncated).any()
        obs, reward, terminated, truncated, info = venv.step(zero)
        assert truncated.all() and not terminated.any()
        assert list(info["outcome"]["status"]) == ["timeout", "timeout"]
        obs, reward, terminated, truncated, info = venv.step(zero)   # the reset step
        assert reward.tolist() == [0.0, 0.0] and not (terminated | truncated).any()
        assert info["time_s"].tolist() == [0.0, 0.0]
        assert np.all(obs["state"][:, -1] == 0)   # time_s feature


def test_same_step_autoreset_puts_the_last_observation_in_info():
    with VbVectorEnv(2, autoreset_mode="same_step", time_limit_s=0.2, **OPTS) as venv:
        venv.reset(seed=2)
        zero = np.zeros((2, 2), np.float32)
        venv.step(zero)
        obs, reward, terminated, truncated, info = venv.step(zero)
        assert truncated.all()
        assert info["_final_obs"].all()
        assert info["final_obs"][0]["state"][-1] == pytest.approx(0.2)   # time of the end
        assert info["final_info"]["outcome"]["status"][1] == "timeout"
        assert np.all(obs["state"][:, -1] == 0)                            # new episodes
        assert (reward < 0).all()                                          # the end step's reward


def test_gymnasium_make_vec_uses_the_vector_env():
    venv = gym.make_vec("vb/OffRoad-v0", num_envs=2, vectorization_mode="vector_entry_point",
                        **OPTS)
    try:
        assert isinstance(venv.unwrapped, VbVectorEnv)
        obs, _ = venv.reset(seed=0)
        assert venv.observation_space.contains(obs)
    finally:
        venv.close()


def test_a_crashed_worker_is_named_and_the_others_are_closed():
    venv = VbVectorEnv(2, **OPTS)
    venv.reset(seed=0)
    victim, other = venv.server_pids
    os.kill(other, signal.SIGKILL)
    with pytest.raises(ServerCrashed, match=r"vector env worker 1: .*exit code -9"):
        venv.step(np.zeros((2, 2), np.float32))
    assert venv.closed
    venv.close()


def test_a_subclass_chooses_each_episode_through_episode_options():
    """The training env (train/ppo.py LevelVectorEnv) draws (task, pair) from its sampler for
    every env reset without options, and resets exactly like VbVectorEnv given those options."""
    from vb_gym.train.ppo import LevelVectorEnv

    class Fixed:
        calls = 0

        def sample(self):
            Fixed.calls += 1
            return 1, 0

    config = EnvConfig.from_kwargs(**OPTS)
    with LevelVectorEnv(2, config, Fixed()) as level:
        obs, _ = level.reset(seed=3)
        assert Fixed.calls == 2
        level.reset(seed=3, options={"task": 0, "pair": 0})
        assert Fixed.calls == 2
    with VbVectorEnv(2, config, autoreset_mode="same_step") as plain:
        ref, _ = plain.reset(seed=3, options={"task": 1, "pair": 0})
    for key in ref:
        assert np.array_equal(obs[key], ref[key]), key
