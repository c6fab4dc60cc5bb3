"""Export a trained policy for vb's C++ controller and make the test fixtures that tie the C++
inference to Python (docs/learning.md). Needs the sb3 extra (torch, safetensors).

    python -m vb_gym.train.export policy RUN/model.zip data/policies/rl.safetensors --system rl \
        --summary RUN/summary.json
    python -m vb_gym.train.export fixtures data/policies/rl.safetensors --out test/data/learned

``fixtures`` writes two small safetensors files that the C++ tests read (no torch there):

* forward_<system>.safetensors: 16 fixed feature vectors (normal, seed 0, x 1.5) and the torch
  forward pass of the exported Sequential on them (the action mean, not clipped);
* pipeline_<system>.safetensors: the features the Python side computes from vb_gym's
  observations and the policy's clipped actions for the first DECISIONS decisions of one trial
  (task, pair and seed in the metadata), driven through vb_gym with those actions.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Sequence

import numpy as np

from ..learned import NUM_FEATURES, features, learned_env_config

DECISIONS = 40
PIPELINE_TASK = "tasks/env000.yaml"   # any world: the fixture checks the pipeline, not skill
PIPELINE_PAIR = 3
PIPELINE_SEED = 7


def load_sequential(path: str | Path):
    """The exported policy as a torch Sequential (its forward pass is the reference)."""
    import torch
    from safetensors import safe_open

    with safe_open(str(path), "pt") as f:
        meta = f.metadata()
        tensors = {k: f.get_tensor(k) for k in f.keys()}
    acts = meta["policy.activations"].split(",")
    modules = {"tanh": torch.nn.Tanh, "relu": torch.nn.ReLU}
    layers: list[torch.nn.Module] = []
    indices = sorted(int(k.split(".")[1]) for k in tensors if k.endswith(".weight"))
    for n, i in enumerate(indices):
        w, b = tensors[f"policy.{i}.weight"], tensors[f"policy.{i}.bias"]
        lin = torch.nn.Linear(w.shape[1], w.shape[0])
        with torch.no_grad():
            lin.weight.copy_(w)
            lin.bias.copy_(b)
        layers.append(lin)
        if acts[n] != "none":
            layers.append(modules[acts[n]]())
    return torch.nn.Sequential(*layers).eval(), meta


def export_from_zip(model_zip: str, out: str, system: str, summary: str | None) -> None:
    from stable_baselines3 import PPO

    from .ppo import export_policy

    model = PPO.load(model_zip, device="cpu")
    meta = {"format": "vb-policy-1", "system": system,
            "features": "vb_gym.learned: 12 state + 64 elevation (16x16 cells of 1 m, 2x2 mean)",
            "action": "steering, target speed / 4 m/s; decision every 0.1 s"}
    if summary:
        s = json.loads(Path(summary).read_text())
        meta.update({"timesteps": str(s["timesteps"]), "seed": str(s["seed"]),
                     "training_worlds": f"vb_gen seeds {s['world_seeds'][0]}..."
                                        f"{s['world_seeds'][1]}"})
    Path(out).parent.mkdir(parents=True, exist_ok=True)
    export_policy(model, Path(out), meta)


def make_fixtures(policy: str, out_dir: str) -> None:
    import torch
    from safetensors.numpy import save_file

    from ..env import VbEnv

    torch.set_num_threads(1)
    net, meta = load_sequential(policy)
    system = meta["system"]
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    x = (np.random.default_rng(0).standard_normal((16, NUM_FEATURES)) * 1.5).astype(np.float32)
    with torch.no_grad():
        y = net(torch.from_numpy(x)).numpy().astype(np.float32)
    save_file({"inputs": x, "outputs": y}, str(out / f"forward_{system}.safetensors"),
              metadata={"policy": f"data/policies/{system}.safetensors"})

    env = VbEnv(learned_env_config(PIPELINE_TASK, system=system))
    obs, _ = env.reset(options={"task": 0, "pair": PIPELINE_PAIR, "trial_seed": PIPELINE_SEED})
    feats, actions = [], []
    for _ in range(DECISIONS):
        f = features(obs)
        with torch.no_grad():
            a = np.clip(net(torch.from_numpy(f[None])).numpy()[0], -1.0, 1.0).astype(np.float32)
        feats.append(f)
        actions.append(a)
        obs, _, terminated, truncated, _ = env.step(a)
        if terminated or truncated:
            break
    env.close()
    save_file({"features": np.stack(feats), "actions": np.stack(actions)},
              str(out / f"pipeline_{system}.safetensors"),
              metadata={"policy": f"data/policies/{system}.safetensors", "task": PIPELINE_TASK,
                        "pair": str(PIPELINE_PAIR), "seed": str(PIPELINE_SEED),
                        "decision_period_s": "0.1"})


def main(argv: Sequence[str] | None = None) -> None:
    ap = argparse.ArgumentParser(prog="python -m vb_gym.train.export")
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("policy")
    p.add_argument("model_zip")
    p.add_argument("out")
    p.add_argument("--system", required=True)
    p.add_argument("--summary")
    f = sub.add_parser("fixtures")
    f.add_argument("policy")
    f.add_argument("--out", default="test/data/learned")
    args = ap.parse_args(argv)
    if args.cmd == "policy":
        export_from_zip(args.model_zip, args.out, args.system, args.summary)
    else:
        make_fixtures(args.policy, args.out)


if __name__ == "__main__":
    main()
