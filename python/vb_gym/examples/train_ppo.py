"""Train PPO (Stable-Baselines3) through the vector env for a short budget, plot the learning
curve, then evaluate the policy with vb_gym.evaluate (vb_batch's format, vb_report-ready).

    pip install -e "python[sb3]"      # Stable-Baselines3 + torch: not installed by setup.sh
    python -m vb_gym.examples.train_ppo --timesteps 50000 --workers 2 --out results/ppo

Writes OUT/model.zip, OUT/monitor.csv (episode return, length, wall time), OUT/learning_curve.png,
and OUT/eval/ (trials of the trained policy on the evaluation tasks, index.csv). Never run in CI.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

import numpy as np

from vb_gym import Crop, EnvConfig
from vb_gym import evaluate

# A small observation for a small network: the state vector and a coarse elevation crop.
CROPS = (Crop("elevation", 16, 0.5),)


def load_policy(env):
    """Policy factory for vb_gym.evaluate: the model saved by main() ($VB_PPO_MODEL)."""
    from stable_baselines3 import PPO

    model = PPO.load(os.environ["VB_PPO_MODEL"], device="cpu")

    def policy(obs):
        action, _ = model.predict(obs, deterministic=True)
        return action

    return policy


def plot_learning_curve(monitor_csv: Path, png: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    data = np.genfromtxt(monitor_csv, delimiter=",", names=True, skip_header=1)
    returns, lengths = np.atleast_1d(data["r"]), np.atleast_1d(data["l"])
    steps = np.cumsum(lengths)
    window = max(1, len(returns) // 20)
    smooth = np.convolve(returns, np.ones(window) / window, mode="valid")
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(steps, returns, ".", alpha=0.3, label="episode return")
    ax.plot(steps[window - 1:], smooth, "-", label=f"mean of {window}")
    ax.set_xlabel("env steps (0.1 s each)")
    ax.set_ylabel("episode return")
    ax.set_title("PPO on vb/OffRoad-v0")
    ax.legend()
    fig.tight_layout()
    fig.savefig(png, dpi=120)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--train-tasks", nargs="+", default=["tasks/env000.yaml", "tasks/env001.yaml"])
    ap.add_argument("--eval-tasks", nargs="+", default=["tasks/env002.yaml"])
    ap.add_argument("--timesteps", type=int, default=50_000)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", default="results/ppo")
    args = ap.parse_args()

    from stable_baselines3 import PPO
    from stable_baselines3.common.vec_env import VecMonitor

    from vb_gym.sb3 import VbSB3VecEnv

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    config = EnvConfig(tasks=args.train_tasks, crops=CROPS)
    venv = VecMonitor(VbSB3VecEnv(args.workers, config), filename=str(out / "monitor.csv"))
    venv.seed(args.seed)
    model = PPO("MultiInputPolicy", venv, n_steps=256, batch_size=256, learning_rate=3e-4,
                gamma=0.99, seed=args.seed, device="cpu", verbose=1)
    model.learn(total_timesteps=args.timesteps)
    model.save(out / "model.zip")
    venv.close()
    plot_learning_curve(out / "monitor.csv", out / "learning_curve.png")

    os.environ["VB_PPO_MODEL"] = str(out / "model.zip")
    evaluate.main([*args.eval_tasks, "--system", "ppo", "--policy",
                   "vb_gym.examples.train_ppo:load_policy", "--out", str(out / "eval"),
                   "--workers", str(args.workers), "--crops", "elevation:16:0.5"])


if __name__ == "__main__":
    main()
