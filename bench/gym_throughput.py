"""Gym throughput: env steps per second and simulated seconds per wall second through vb_gym and
the Python package, random actions, for 1 worker (VbEnv) and N workers (VbVectorEnv), on a rigid
and a deformable world; peak memory (VmHWM) of each vb_gym process. Compare with the in-process
reference build/bench/vb_bench_gym_inprocess (same work without protocol and Python).

    .venv/bin/python bench/gym_throughput.py [--steps 3000] [--runs 3] [--workers 1 2 4]
        [--tasks tasks/env000.yaml tasks/env061.yaml]

Per run: STEPS env steps per worker (0.1 s control period, "speed" actions uniform in [-1, 1],
64 x 64 elevation crop at 0.1 m, wheels, no trajectory), every episode from pair 0 (as the
in-process reference), episodes auto-reset; the medians over runs are printed as a Markdown table.
"sim s per CPU s" divides by the CPU time of all processes (Python and every vb_gym): on a loaded
machine it is the figure to compare with the in-process reference's CPU figure.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from vb_gym import Crop, EnvConfig, VbEnv, VbVectorEnv  # noqa: E402


def peak_rss_mib(pid: int) -> float:
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def cpu_s(pid: int) -> float:
    """User + system CPU seconds of a process so far (/proc/PID/stat)."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def own_cpu_s() -> float:
    t = os.times()
    return t.user + t.system


def run_single(config: EnvConfig, steps: int, seed: int) -> tuple[float, float, float]:
    env = VbEnv(config)
    try:
        env.action_space.seed(seed)
        env.reset(seed=seed)
        sim_s = 0.0
        t0 = time.perf_counter()
        cpu0 = own_cpu_s() + cpu_s(env.server_pid)
        for _ in range(steps):
            _, _, terminated, truncated, info = env.step(env.action_space.sample())
            if terminated or truncated:
                sim_s += info["time_s"]
                env.reset()
        sim_s += env._core._s("time_s")
        wall = time.perf_counter() - t0
        cpu = own_cpu_s() + cpu_s(env.server_pid) - cpu0
        return steps / wall, sim_s / wall, peak_rss_mib(env.server_pid), sim_s / cpu
    finally:
        env.close()


def run_vector(config: EnvConfig, workers: int, steps: int, seed: int
               ) -> tuple[float, float, float]:
    env = VbVectorEnv(workers, config)
    try:
        env.action_space.seed(seed)
        env.reset(seed=seed)
        sim_s = 0.0
        t0 = time.perf_counter()
        cpu0 = own_cpu_s() + sum(cpu_s(p) for p in env.server_pids)
        for _ in range(steps):
            _, _, terminated, truncated, info = env.step(env.action_space.sample())
            ended = terminated | truncated
            if ended.any():
                sim_s += float(np.sum(np.asarray(info["time_s"])[ended]))
        sim_s += sum(c._s("time_s") for c in env._cores if not c.done)
        wall = time.perf_counter() - t0
        cpu = own_cpu_s() + sum(cpu_s(p) for p in env.server_pids) - cpu0
        mem = max(peak_rss_mib(pid) for pid in env.server_pids)
        return workers * steps / wall, sim_s / wall, mem, sim_s / cpu
    finally:
        env.close()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--steps", type=int, default=3000)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2, 4])
    ap.add_argument("--tasks", nargs="+", default=["tasks/env000.yaml", "tasks/env061.yaml"])
    args = ap.parse_args()
    print("command:", " ".join(sys.argv))
    print("| world | workers | env steps/s | sim s per wall s | per worker | sim s per CPU s "
          "(all processes) | peak RSS per vb_gym (MiB) |")
    print("|---|---|---|---|---|---|---|")
    for task in args.tasks:
        # Pair 0 only, as vb_bench_gym_inprocess: both drive the same ground.
        config = EnvConfig(tasks=task, pairs=[0], crops=(Crop("elevation", 64, 0.1),))
        for workers in args.workers:
            results = []
            for r in range(args.runs):
                if workers == 1:
                    results.append(run_single(config, args.steps, 100 + r))
                else:
                    results.append(run_vector(config, workers, args.steps, 100 + r))
            sps = statistics.median(x[0] for x in results)
            rtf = statistics.median(x[1] for x in results)
            mem = max(x[2] for x in results)
            cpu_rtf = statistics.median(x[3] for x in results)
            print(f"| {Path(task).stem} | {workers} | {sps:.0f} | {rtf:.1f} | "
                  f"{rtf / workers:.1f} | {cpu_rtf:.1f} | {mem:.0f} |", flush=True)


if __name__ == "__main__":
    main()
