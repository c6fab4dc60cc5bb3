"""A few hundred steps of each learned baseline's training and the export to safetensors (needs
the sb3 extra: skipped without torch). Never a real training budget."""

from __future__ import annotations

import json

import numpy as np
import pytest

torch = pytest.importorskip("torch")
pytest.importorskip("stable_baselines3")
pytest.importorskip("safetensors")
pytest.importorskip("matplotlib")


@pytest.mark.parametrize("system", ["rl", "mcl", "acl"])
def test_tiny_training_exports_a_policy(tmp_path, vb_gym_bin, system):
    from vb_gym.learned import NUM_FEATURES
    from vb_gym.train.export import load_sequential
    from vb_gym.train.ppo import main

    main([system, "--timesteps", "256", "--workers", "1", "--worlds-per-combo", "1",
          "--out", str(tmp_path)])
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["timesteps"] >= 256 and summary["world_seeds"] == [1000, 1026]
    net, meta = load_sequential(tmp_path / "policy.safetensors")
    assert meta["format"] == "vb-policy-1" and meta["policy.activations"] == "tanh,tanh,none"
    from stable_baselines3 import PPO
    model = PPO.load(tmp_path / "model.zip", device="cpu")
    x = np.random.default_rng(0).normal(size=(4, NUM_FEATURES)).astype(np.float32)
    a, _ = model.predict(x, deterministic=True)
    with torch.no_grad():
        b = np.clip(net(torch.from_numpy(x)).numpy(), -1, 1)
    np.testing.assert_allclose(a, b, atol=1e-6)
    assert (tmp_path / "learning_curve.png").stat().st_size > 1000
