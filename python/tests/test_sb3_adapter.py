"""vb_gym.sb3's translation to Stable-Baselines3's VecEnv conventions (terminal_observation,
TimeLimit.truncated, seeds at the next reset). SB3 is an optional extra: without it the adapter is
tested against a minimal stand-in of SB3's VecEnv base class (only the attributes the adapter
uses); with it, against the real class, plus a few PPO steps."""

from __future__ import annotations

import importlib
import sys
import types

import numpy as np
import pytest

from vb_gym import Crop

from conftest import RIGID_TASK

OPTS = dict(tasks=RIGID_TASK, crops=(Crop("elevation", 8, 0.5),), time_limit_s=0.2)


def _sb3_installed() -> bool:
    try:
        importlib.import_module("stable_baselines3")
        return True
    except ImportError:
        return False


@pytest.fixture
def sb3_module(monkeypatch):
    if not _sb3_installed():
        class VecEnv:   # the part of SB3's base class the adapter relies on
            def __init__(self, num_envs, observation_space, action_space):
                self.num_envs = num_envs
                self.observation_space = observation_space
                self.action_space = action_space
                self._seeds = [None] * num_envs

            def seed(self, seed=None):
                self._seeds = [None if seed is None else seed + i for i in range(self.num_envs)]

            def _reset_seeds(self):
                self._seeds = [None] * self.num_envs

            def step(self, actions):
                self.step_async(actions)
                return self.step_wait()

        base = types.ModuleType("stable_baselines3.common.vec_env.base_vec_env")
        base.VecEnv = VecEnv
        for name in ("stable_baselines3", "stable_baselines3.common",
                     "stable_baselines3.common.vec_env"):
            monkeypatch.setitem(sys.modules, name, types.ModuleType(name))
        monkeypatch.setitem(sys.modules, base.__name__, base)
    monkeypatch.delitem(sys.modules, "vb_gym.sb3", raising=False)
    return importlib.import_module("vb_gym.sb3")


def test_adapter_follows_sb3_conventions(sb3_module):
    venv = sb3_module.VbSB3VecEnv(2, **OPTS)
    try:
        venv.seed(5)
        first = venv.reset()
        assert first["state"].shape == (2, 19)
        zero = np.zeros((2, 2), np.float32)
        obs, rewards, dones, infos = venv.step(zero)
        assert rewards.dtype == np.float32 and not dones.any() and len(infos) == 2
        obs, rewards, dones, infos = venv.step(zero)
        assert dones.all()
        for i in range(2):
            assert infos[i]["TimeLimit.truncated"] is True
            assert infos[i]["outcome"]["status"] == "timeout"
            assert infos[i]["terminal_observation"]["state"][-1] == pytest.approx(0.2)
            assert obs["state"][i][-1] == 0.0     # already the next episode
        # seed(5) applied at that reset only: a second seed(5) + reset repeats the first obs.
        venv.seed(5)
        again = venv.reset()
        assert np.array_equal(again["state"], first["state"])
        assert venv.env_is_wrapped(object) == [False, False]
    finally:
        venv.close()


@pytest.mark.skipif(not _sb3_installed(), reason="Stable-Baselines3 extra not installed")
def test_ppo_runs_a_few_steps_through_the_adapter():
    from stable_baselines3 import PPO
    from vb_gym.sb3 import VbSB3VecEnv

    venv = VbSB3VecEnv(2, **OPTS)
    try:
        model = PPO("MultiInputPolicy", venv, n_steps=8, batch_size=8, n_epochs=1, seed=0,
                    device="cpu")
        model.learn(total_timesteps=16)
    finally:
        venv.close()
