#!/usr/bin/env python3
"""Compares two vb_batch indexes of the same matrix run under different outcome rules (or any
two runs): outcome percentages per elevation, terrain and density, the trials whose outcome
changed, and (with --trials, the trial files of run B) what B's trajectories show about them.

  scripts/compare_rules.py docs/results/pid_hmmwv/index.csv \\
      docs/results/pid_hmmwv_verti_bench/index.csv --trials RUN_B/trials --tasks tasks

Markdown on stdout; standard library only. docs/validation.md "The original's rules".
"""
import argparse
import collections
import csv
import math
import os
import re

STATUSES = ["success", "rollover", "stuck", "timeout", "out_of_bounds"]


def load(path):
    return {(r["task"], int(r["pair"]), r["seed"], r["vehicle"], r["system"]): r
            for r in csv.DictReader(open(path, newline=""))}


def pct(rows, status):
    return 100.0 * sum(r["status"] == status for r in rows) / max(1, len(rows))


def outcome_table(a, b, keys):
    print("| group | n | " + " | ".join(f"{s} % (A → B)" for s in STATUSES) + " |")
    print("|---|---:|" + "---:|" * len(STATUSES))
    groups = [("all", keys)]
    for factor in ("elevation", "terrain", "density"):
        for level in dict.fromkeys(a[k][factor] for k in keys):
            groups.append((f"{factor} {level}", [k for k in keys if a[k][factor] == level]))
    for name, ks in groups:
        ra, rb = [a[k] for k in ks], [b[k] for k in ks]
        cells = [f"{pct(ra, s):.1f} → {pct(rb, s):.1f}" for s in STATUSES]
        print(f"| {name} | {len(ks)} | " + " | ".join(cells) + " |")


def goal_of(tasks_dir, task, pair):
    text = open(os.path.join(tasks_dir, task + ".yaml")).read()
    g = re.findall(r"goal: \[([-\d.e]+), ([-\d.e]+)\]", text)[pair]
    return float(g[0]), float(g[1])


def trajectory(trials_dir, key):
    task, pair, seed, vehicle, system = key
    path = os.path.join(trials_dir, f"{task}_p{pair}_s{seed}_{vehicle}_{system}_traj.csv")
    return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(path))]


def last_window(traj, seconds=10.0):
    end = traj[-1]["t_s"]
    w = [r for r in traj if r["t_s"] > end - seconds + 1e-9]
    moved = math.hypot(w[-1]["x_m"] - w[0]["x_m"], w[-1]["y_m"] - w[0]["y_m"])
    speeds = sorted(r["speed_mps"] for r in w)
    return moved, speeds[len(speeds) // 2], speeds[-1]


def longest_slow_spell(traj, below_mps=2.0):
    best = start = None
    for r in traj:
        if r["speed_mps"] < below_mps:
            start = r["t_s"] if start is None else start
            best = max(best or 0.0, r["t_s"] - start)
        else:
            start = None
    return best or 0.0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("index_a")
    p.add_argument("index_b")
    p.add_argument("--trials", help="trial files of run B (trajectories)")
    p.add_argument("--tasks", default="tasks", help="task set (goal positions)")
    args = p.parse_args()
    a, b = load(args.index_a), load(args.index_b)
    keys = [k for k in a if k in b]
    print(f"A = {args.index_a}, B = {args.index_b}: {len(keys)} trials in both\n")
    outcome_table(a, b, keys)
    changed = [k for k in keys if a[k]["status"] != b[k]["status"]]
    moves = collections.Counter((a[k]["status"], b[k]["status"]) for k in changed)
    print(f"\n{len(changed)} trials change outcome: " +
          ", ".join(f"{n} {x} → {y}" for (x, y), n in moves.most_common()))
    if not args.trials:
        return
    print("\n| trial | A | B | B: planar distance at A's end, closest after, at its end (m) |")
    print("|---|---|---|---|")
    for k in changed:
        traj = trajectory(args.trials, k)
        gx, gy = goal_of(args.tasks, k[0], k[1])
        dist = [(r["t_s"], math.hypot(r["x_m"] - gx, r["y_m"] - gy)) for r in traj]
        t_a = float(a[k]["sim_time_s"])
        at_a = min(dist, key=lambda td: abs(td[0] - t_a))[1]
        closest = min(d for t, d in dist if t >= t_a)
        print(f"| {k[0]} p{k[1]} | {a[k]['status']} {t_a:.1f} s | {b[k]['status']} "
              f"{float(b[k]['sim_time_s']):.1f} s | {at_a:.2f}, {closest:.2f}, {dist[-1][1]:.2f} |")
    both = [k for k in keys if a[k]["status"] == b[k]["status"] == "stuck"]
    lag = sorted(float(b[k]["sim_time_s"]) - float(a[k]["sim_time_s"]) for k in both)
    print(f"\nstuck under both ({len(both)}): B decides later by median {lag[len(lag) // 2]:+.2f} s "
          f"(range {lag[0]:+.1f} to {lag[-1]:+.1f} s)")
    early = [k for k in both if float(b[k]["sim_time_s"]) < float(a[k]["sim_time_s"]) - 1.0]
    for k in early:
        moved, median_v, max_v = last_window(trajectory(args.trials, k))
        print(f"- {k[0]} p{k[1]}: B stuck {float(a[k]['sim_time_s']) - float(b[k]['sim_time_s']):.1f}"
              f" s earlier; last 10 s of B: moved {moved:.2f} m, median {median_v:.2f} m/s, "
              f"max {max_v:.2f} m/s")
    spells = sorted(longest_slow_spell(trajectory(args.trials, k)) for k in keys
                    if b[k]["status"] == "success")
    print(f"\nB's successes ({len(spells)}): longest continuous spell below 2 m/s (sampled "
          f"trajectory): median {spells[len(spells) // 2]:.1f} s, max {spells[-1]:.1f} s")


if __name__ == "__main__":
    main()
