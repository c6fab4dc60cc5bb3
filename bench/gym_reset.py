"""Median and minimum wall time of VbEnv.reset() on a cached task (docs/benchmarks.md, "Gym
throughput"). usage: .venv/bin/python bench/gym_reset.py [VB_GYM_BINARY] [RESETS]"""
import sys
import time

from vb_gym import VbEnv


def main() -> None:
    binary = sys.argv[1] if len(sys.argv) > 1 else None
    resets = int(sys.argv[2]) if len(sys.argv) > 2 else 40
    env = VbEnv(tasks="tasks/env000.yaml", server_binary=binary)
    env.reset(seed=0)
    times = []
    for _ in range(resets):
        t = time.perf_counter()
        env.reset()
        times.append(time.perf_counter() - t)
    env.close()
    times.sort()
    print(f"{resets} resets: median {1e3 * times[len(times) // 2]:.1f} ms, "
          f"min {1e3 * times[0]:.1f} ms")


if __name__ == "__main__":
    main()
