"""Train one of vb's learned baselines (RL, MCL, ACL) with Stable-Baselines3 PPO on generated
training worlds, export the policy to safetensors for vb's C++ controller, and plot the learning
curve (docs/learning.md).

    pip install -e "python[sb3]"          # Stable-Baselines3, torch, safetensors, matplotlib
    python -m vb_gym.train rl  --timesteps 150000 --seed 0 --out runs/rl
    python -m vb_gym.train mcl --timesteps 150000 --seed 0 --out runs/mcl
    python -m vb_gym.train acl --timesteps 150000 --seed 0 --out runs/acl

Writes OUT/policy.safetensors (the file data/policies/<system>.safetensors is a copy of),
OUT/model.zip (SB3), OUT/episodes.csv (one row per training episode), OUT/progress.csv (SB3's
per-update log), OUT/curriculum.json, OUT/summary.json and OUT/learning_curve.png. Never run in CI.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import time
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from ..learned import CLIP, NUM_FEATURES, features, learned_env_config
from ..vector import VbVectorEnv
from ..reward import RewardWeights
from .curricula import ManualCurriculum, PrioritizedLevelReplay, UniformSampler
from .worlds import training_worlds

SYSTEMS = ("rl", "mcl", "acl")
NUM_PAIRS = 10

# PPO hyperparameters (docs/learning.md compares them with the original checkpoints').
HYPER = {
    "n_steps": 512,          # per worker; original 400 x 15 envs at 200 Hz
    "batch_size": 256,       # original 200
    "n_epochs": 10,          # original 10
    "learning_rate": 3e-4,   # original 5e-4
    "gamma": 0.99,           # original 0.99 (per 5 ms step; here per 0.1 s decision)
    "gae_lambda": 0.95,      # original 0.95
    "ent_coef": 0.0,         # original 0
    "vf_coef": 0.5,          # original 0.5
    "max_grad_norm": 0.5,    # original 0.5
    "clip_range": 0.2,       # original 0.2 (SB3 default)
}
NET_ARCH = {"pi": [64, 64], "vf": [64, 64]}   # original: 18->64->128->64->32 extractor + these
LOG_STD_INIT = -0.5
# The reward: vb_gym.reward's terms (the original's), with the stall penalty 40x smaller
# (-0.25 instead of -10 per 5 ms below 2 m/s of progress, -5 per 0.1 s decision). At the
# original's weight a decision without progress costs -200, ten times what full-speed progress
# earns (+20), so ending an episode early (stuck -300, rollover -600) pays better than driving:
# the first runs here lost ~-120 000 per 60 s timeout. docs/learning.md "Reward".
STALL_PER_REFERENCE_STEP = -0.25


class LevelVectorEnv(VbVectorEnv):
    """VbVectorEnv whose episodes (task, pair) come from a level sampler."""

    def __init__(self, num_envs: int, config: Any, sampler: Any):
        self.sampler = sampler
        super().__init__(num_envs, config, autoreset_mode="same_step")

    def _episode_options(self, i: int, options: dict[str, Any] | None
                         ) -> dict[str, Any] | None:
        if options is not None:
            return options
        task, pair = self.sampler.sample()
        return {"task": task, "pair": pair}


def make_vec_env(num_envs: int, config: Any, sampler: Any, episode_log: Path):
    from gymnasium import spaces
    from stable_baselines3.common.vec_env.base_vec_env import VecEnv

    from ..sb3 import VbSB3VecEnv

    class LearnedVecEnv(VbSB3VecEnv):
        """SB3 VecEnv over LevelVectorEnv with the learned systems' 76 features; logs episodes
        and tells the sampler how they ended."""

        def __init__(self) -> None:
            self.venv = LevelVectorEnv(num_envs, config, sampler)
            self._actions = None
            self.num_timesteps = 0
            self.levels = [(-1, -1)] * num_envs          # level of each env's current episode
            self.levels_before_step = list(self.levels)
            self.returns = np.zeros(num_envs)
            self.lengths = np.zeros(num_envs, dtype=int)
            self.episodes = 0
            self.start = time.time()
            self.log = open(episode_log, "w", newline="")
            self.writer = csv.writer(self.log)
            self.writer.writerow(["episode", "timesteps", "wall_s", "world_seed", "elevation",
                                  "terrain", "density", "pair", "stage", "status", "return",
                                  "length"])
            VecEnv.__init__(self, num_envs,
                            spaces.Box(-CLIP, CLIP, (NUM_FEATURES,), np.float32),
                            self.venv.single_action_space)

        def _level(self, info: dict[str, Any]) -> tuple[int, int]:
            return int(info["task"]), int(info["pair"])

        def reset(self) -> Any:
            obs = super().reset()
            self.levels = [self._level(info) for info in self.reset_infos]
            self.returns[:] = 0
            self.lengths[:] = 0
            return features(obs)

        def step_async(self, actions: np.ndarray) -> None:
            self.levels_before_step = list(self.levels)
            super().step_async(actions)

        def step_wait(self):
            obs, rewards, dones, infos = super().step_wait()
            self.num_timesteps += self.num_envs
            self.returns += rewards
            self.lengths += 1
            for i, info in enumerate(infos):
                if dones[i]:
                    info["terminal_observation"] = features(info["terminal_observation"])
                    status = info["outcome"]["status"]
                    level = self.levels[i]
                    world = sampler.worlds[level[0]]
                    self.episodes += 1
                    self.writer.writerow([self.episodes, self.num_timesteps,
                                          f"{time.time() - self.start:.1f}", world.seed,
                                          world.elevation, world.terrain, world.density,
                                          level[1], sampler.stage(), status,
                                          f"{self.returns[i]:.2f}", self.lengths[i]])
                    sampler.on_episode_end(level, status, self.num_timesteps)
                    self.returns[i] = 0
                    self.lengths[i] = 0
                    # The info already belongs to the next episode (same-step autoreset).
                    self.levels[i] = self._level(info)
            sampler.on_step(self.num_timesteps)
            self.log.flush()
            return features(obs), rewards, dones, infos

        def close(self) -> None:
            self.log.close()
            super().close()

    return LearnedVecEnv()


def make_callback(learned_env: Any, sampler: Any, max_wall_s: float | None):
    from stable_baselines3.common.callbacks import BaseCallback

    class Callback(BaseCallback):
        """Records the level of every rollout entry (for PLR's scores) and stops at the wall
        clock budget."""

        def __init__(self) -> None:
            super().__init__()
            self.step_levels: list[list[tuple[int, int]]] = []
            self.start = time.time()
            self.stopped_by_wall = False

        def _on_rollout_start(self) -> None:
            self.step_levels = []

        def _on_step(self) -> bool:
            self.step_levels.append(learned_env.levels_before_step)
            if max_wall_s is not None and time.time() - self.start > max_wall_s:
                self.stopped_by_wall = True
                return False
            return True

        def _on_rollout_end(self) -> None:
            if not sampler.wants_scores():
                return
            adv = self.model.rollout_buffer.advantages   # (n_steps, n_envs)
            starts = self.model.rollout_buffer.episode_starts
            n_steps, n_envs = adv.shape
            for e in range(n_envs):
                seg_start = 0
                for t in range(1, n_steps + 1):
                    if t == n_steps or starts[t, e] or \
                            self.step_levels[t][e] != self.step_levels[seg_start][e]:
                        level = self.step_levels[seg_start][e]
                        score = float(np.mean(np.maximum(adv[seg_start:t, e], 0.0)))
                        sampler.update_score(level, score)
                        seg_start = t

    return Callback()


def export_policy(model: Any, path: Path, metadata: dict[str, str]) -> None:
    """The deterministic policy (action mean) as a PyTorch-style Sequential 'policy': Linear,
    Tanh, Linear, Tanh, Linear; float32 [out, in] weights (include/vb/nn/mlp.h reads it)."""
    import torch
    from safetensors.torch import save_file

    layers = list(model.policy.mlp_extractor.policy_net) + [model.policy.action_net]
    tensors = {}
    activations: list[str] = []   # one per Linear layer: the module after it, or none
    for i, layer in enumerate(layers):
        if isinstance(layer, torch.nn.Linear):
            tensors[f"policy.{i}.weight"] = layer.weight.detach().float().contiguous().clone()
            tensors[f"policy.{i}.bias"] = layer.bias.detach().float().contiguous().clone()
            activations.append("none")
        elif isinstance(layer, (torch.nn.Tanh, torch.nn.ReLU)) and activations and \
                activations[-1] == "none":
            activations[-1] = "tanh" if isinstance(layer, torch.nn.Tanh) else "relu"
        else:
            raise TypeError(f"cannot export layer {i}: {layer!r}")
    meta = dict(metadata)
    meta["policy.activations"] = ",".join(activations)
    save_file(tensors, str(path), metadata=meta)


def plot_curve(episode_csv: Path, png: Path, title: str, switches: list[dict]) -> dict:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = list(csv.DictReader(open(episode_csv)))
    steps = np.array([int(r["timesteps"]) for r in rows])
    ret = np.array([float(r["return"]) for r in rows])
    succ = np.array([r["status"] == "success" for r in rows], dtype=float)
    window = 50
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    if len(rows) >= window:
        k = np.ones(window) / window
        a1.plot(steps[window - 1:], np.convolve(ret, k, mode="valid"), "-")
        a2.plot(steps[window - 1:], 100 * np.convolve(succ, k, mode="valid"), "-")
    a1.plot(steps, ret, ".", alpha=0.2, markersize=2)
    for s in switches:
        for a in (a1, a2):
            a.axvline(s["at_timestep"], color="k", ls="--", lw=0.8)
    a1.set_ylabel("episode return")
    a2.set_ylabel(f"success % (last {window})")
    a2.set_xlabel("env steps (0.1 s decisions, all workers)")
    a1.set_title(title)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)
    last = slice(max(0, len(rows) - 100), len(rows))
    return {"episodes": len(rows),
            "last100_success": float(succ[last].mean()) if len(rows) else 0.0,
            "last100_return": float(ret[last].mean()) if len(rows) else 0.0}


def main(argv: Sequence[str] | None = None) -> None:
    ap = argparse.ArgumentParser(prog="python -m vb_gym.train",
                                 description="Train vb's RL, MCL or ACL baseline (PPO).")
    ap.add_argument("system", choices=SYSTEMS)
    ap.add_argument("--timesteps", type=int, default=150_000)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", default=None, help="default: runs/<system>")
    ap.add_argument("--worlds-per-combo", type=int, default=3)
    ap.add_argument("--max-wall-minutes", type=float, default=None,
                    help="stop early at this wall time (then the run is not reproducible)")
    ap.add_argument("--torch-threads", type=int, default=1)
    args = ap.parse_args(argv)

    import torch
    from stable_baselines3 import PPO
    from stable_baselines3.common.logger import configure
    from stable_baselines3.common.vec_env import VecNormalize

    torch.set_num_threads(args.torch_threads)
    out = Path(args.out or f"runs/{args.system}")
    out.mkdir(parents=True, exist_ok=True)
    worlds = training_worlds(out / "worlds", args.worlds_per_combo)
    rng = np.random.default_rng(args.seed)
    if args.system == "rl":
        sampler = UniformSampler(worlds, NUM_PAIRS, rng)
    elif args.system == "mcl":
        sampler = ManualCurriculum(worlds, NUM_PAIRS, rng, args.timesteps)
    else:
        sampler = PrioritizedLevelReplay(worlds, NUM_PAIRS, rng)
    config = learned_env_config([w.file for w in worlds], episode_cache=4, system=args.system,
                                reward=RewardWeights(stall=STALL_PER_REFERENCE_STEP))
    learned_env = make_vec_env(args.workers, config, sampler, out / "episodes.csv")
    learned_env.seed(args.seed)
    venv = VecNormalize(learned_env, norm_obs=False, norm_reward=True, gamma=HYPER["gamma"])
    model = PPO("MlpPolicy", venv, seed=args.seed, device="cpu", verbose=0,
                policy_kwargs={"net_arch": NET_ARCH, "activation_fn": torch.nn.Tanh,
                               "log_std_init": LOG_STD_INIT}, **HYPER)
    model.set_logger(configure(str(out), ["csv"]))
    callback = make_callback(learned_env, sampler, None if args.max_wall_minutes is None
                             else 60.0 * args.max_wall_minutes)
    t0, c0 = time.time(), time.process_time()
    model.learn(total_timesteps=args.timesteps, callback=callback)
    wall, cpu_self = time.time() - t0, time.process_time() - c0
    steps = learned_env.num_timesteps
    pids = [p for p in learned_env.venv.server_pids if p]
    server_cpu = 0.0
    for pid in pids:   # CPU time of the vb_gym servers (Linux /proc, clock ticks)
        try:
            fields = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
            server_cpu += (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
        except OSError:
            pass
    venv.close()
    model.save(out / "model.zip")
    switches = getattr(sampler, "switches", [])
    meta = {"format": "vb-policy-1", "system": args.system,
            "features": "vb_gym.learned: 12 state + 64 elevation (16x16 cells of 1 m, 2x2 mean)",
            "action": "steering, target speed / 4 m/s; decision every 0.1 s",
            "timesteps": str(steps), "seed": str(args.seed)}
    export_policy(model, out / "policy.safetensors", meta)
    curve = plot_curve(out / "episodes.csv", out / "learning_curve.png",
                       f"{args.system.upper()} (PPO, {sampler.name} levels)", switches)
    summary = {"system": args.system, "seed": args.seed, "timesteps": steps,
               "requested_timesteps": args.timesteps, "wall_s": round(wall, 1),
               "cpu_s_trainer": round(cpu_self, 1), "cpu_s_servers": round(server_cpu, 1),
               "stopped_by_wall_budget": callback.stopped_by_wall, "workers": args.workers,
               "worlds": len(worlds), "world_seeds": [worlds[0].seed, worlds[-1].seed],
               "hyperparameters": HYPER, "stall_reward": STALL_PER_REFERENCE_STEP, "net_arch": NET_ARCH, "log_std_init": LOG_STD_INIT,
               "sampler": sampler.name, "curriculum_switches": switches, **curve}
    if isinstance(sampler, PrioritizedLevelReplay):
        summary["plr"] = {"levels": len(sampler.levels), "seen": int(sampler.seen.sum()),
                          "replays": sampler.replays, "episodes": sampler.episodes}
    (out / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    print(json.dumps(summary, indent=2))
