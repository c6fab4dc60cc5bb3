"""The hybrid baselines' training code on a tiny synthetic dataset (seconds; skipped without torch
and safetensors, which CI does not install): features, the four models' training and export, the
folded normalisation, and the evaluation's output."""

import json

import numpy as np
import pytest

from vb_gym import hybrid_features as hf


def synthetic(episodes=6, steps=60, seed=0):
    rng = np.random.default_rng(seed)
    cols = {k: [] for k in ("episode", "world_seed", "terrain", "pos", "rpy", "speed", "steer",
                            "heights", "semantic", "slip")}
    for e in range(episodes):
        t = np.arange(steps) * 0.1
        yaw = 0.1 * np.sin(t) + e
        pos = np.column_stack([np.cumsum(0.2 * np.cos(yaw)), np.cumsum(0.2 * np.sin(yaw)),
                               0.1 * np.sin(0.3 * t)])
        slope = rng.normal(0, 0.1, 2)
        g = hf.grid_offsets()
        h = (g[:, 0] * slope[0] + g[:, 1] * slope[1])[None, :] - 1.0 + 0.01 * rng.normal(size=(steps, 15))
        cols["episode"].append(np.full(steps, e))
        cols["world_seed"].append(np.full(steps, 1000 + e))
        cols["terrain"].append(np.full(steps, e % 3))
        cols["pos"].append(pos)
        cols["rpy"].append(np.column_stack([np.full(steps, slope[1]), np.full(steps, -slope[0]), yaw]))
        cols["speed"].append(np.full(steps, 2.0))
        cols["steer"].append(np.sin(t))
        cols["heights"].append(h)
        cols["semantic"].append(np.full(steps, e % 10))
        cols["slip"].append(np.full(steps, 0.05 * (e % 10)))
    return {k: np.concatenate(v) for k, v in cols.items()}


def test_crop_grid_values_on_a_plane():
    n, res = 64, 0.1
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    fwd, left = ((n - 1) / 2 - i) * res, ((n - 1) / 2 - j) * res
    crop = (0.3 * fwd - 0.2 * left + 1.0)[None]
    got = hf.crop_grid_values(crop, res)[0]
    want = np.array([0.3 * f - 0.2 * l + 1.0 for f, l in hf.grid_offsets()])
    np.testing.assert_allclose(got, want, atol=1e-12)


def test_train_export_evaluate_tiny(tmp_path):
    torch = pytest.importorskip("torch")
    pytest.importorskip("safetensors")
    pytest.importorskip("matplotlib")
    from vb_gym import hybrid_models as hm
    from vb_gym.examples import train_hybrid as th

    # folding the normalisation into the Linear layers changes nothing
    torch.manual_seed(0)
    net = hm.Normalised(hm.mlp([5, 8, 3]), np.arange(5.0), np.arange(1.0, 6.0), np.ones(3),
                        np.full(3, 2.0))
    x = torch.randn(4, 5)
    torch.testing.assert_close(net(x), net.fold()(x), atol=1e-5, rtol=1e-5)

    cache = tmp_path / "samples.npz"
    np.savez(cache, **synthetic())
    out, img = tmp_path / "models", tmp_path / "img"
    for m in th.MODELS:
        th.main(["--data", str(tmp_path), "--cache", str(cache), "--model", m, "--epochs", "1",
                 "--holdout-seed", "1004", "--out", str(out)])
        assert (out / f"{m}.safetensors").is_file()
    th.main(["--data", str(tmp_path), "--cache", str(cache), "--evaluate", "--holdout-seed",
             "1004", "--out", str(out), "--img", str(img)])
    summary = json.loads((out / "hybrid_eval.json").read_text())
    assert summary["starts"] > 0
    assert set(summary["errors"]) == {"bicycle", "wmvct", "mppi6", "tal"}
    assert (img / "hybrid_model_errors.png").is_file()
