"""A few hundred steps of each learned baseline's training and the export to safetensors (needs
the sb3 extra: skipped without torch). Never a real training budget."""

from __future__ import annotations

import json

import numpy as np
import pytest



@pytest.fixture(autouse=True)
def sb3_extra():
    """Skips each test without the sb3 extra (a module-level skip would collect no test, which
    pytest reports with exit code 5 and CTest as a failure)."""
    for module in ("torch", "stable_baselines3", "safetensors", "matplotlib"):
        pytest.importorskip(module)


@pytest.mark.parametrize("system", ["rl", "mcl", "acl"])
def test_tiny_training_exports_a_policy(tmp_path, vb_gym_bin, system):
    import torch

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


def test_training_is_reproducible_from_its_seed(tmp_path, vb_gym_bin):
    from vb_gym.train.ppo import main

    for run in ("a", "b"):
        main(["acl", "--timesteps", "2048", "--workers", "2", "--worlds-per-combo", "1",
              "--seed", "3", "--out", str(tmp_path / run)])
    from safetensors.numpy import load_file

    a = load_file(str(tmp_path / "a" / "policy.safetensors"))
    b = load_file(str(tmp_path / "b" / "policy.safetensors"))
    assert sorted(a) == sorted(b)
    for name in a:   # bit-identical weights (the header's key order may differ)
        assert a[name].tobytes() == b[name].tobytes(), name
    ea = (tmp_path / "a" / "episodes.csv").read_text().splitlines()
    eb = (tmp_path / "b" / "episodes.csv").read_text().splitlines()

    def strip(line: str) -> list[str]:   # without the wall time
        fields = line.split(",")
        return fields[:2] + fields[3:]

    assert len(ea) > 1 and [strip(x) for x in ea] == [strip(x) for x in eb]
