#!/usr/bin/env python3
"""How much of a system's success depends on the spread of world difficulty within a level.

vb's generated worlds match the original worlds' per-level means of the elevation statistics
(reference_verti_bench.md §9) but vary less from world to world (vb_bench_generator_stats). This
script estimates what that costs in success: it fits a logistic model of a trial's success on its
world's p95 slope over all trials of one system (index.csv), then averages the model's success
over (a) vb's worlds of each level, (b) the same worlds stretched about the level mean to the
original's [min..max] and moved to the original's mean, (m) the same worlds only moved to the
original's mean (the part of (b) that is the mean's), (c) a normal distribution with the
original's mean and (max - min) / 4.2 as its standard deviation (the expected range of 33 normal
samples is ~4.2 sigma). A crude estimate: one statistic, a pooled model, ten chaotic trials per
world; read its differences, not its levels.

Usage:
  build/bench/vb_bench_generator_stats --csv worlds.csv [IMPORTED.yaml ...]
  scripts/world_spread_effect.py worlds.csv docs/results/pid_hmmwv/index.csv [--system pid] \
      [--predict OTHER/index.csv]
--predict compares the model's expected successes with a batch on other worlds (e.g. the original
sample worlds imported with vb_import, whose statistics the worlds file must hold).
"""
import argparse
import csv
import sys

import numpy as np

# reference_verti_bench.md §9: p95 slope [deg] of the original worlds, mean [min..max] per level
ORIGINAL_P95 = {"low": (11.9, 9.5, 15.4), "mid": (22.0, 17.8, 30.1), "high": (34.2, 28.7, 42.4)}
LEVELS = ("low", "mid", "high")


def read_worlds(path):
    worlds = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            worlds[row["name"]] = (row["elevation"], float(row["p95_slope_deg"]))
    return worlds


def read_trials(path, system, worlds):
    x, y, task = [], [], []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            if row["system"] != system:
                continue
            if row["task"] not in worlds:
                sys.exit(f"{path}: task {row['task']!r} is not in the worlds file")
            x.append(worlds[row["task"]][1])
            y.append(1.0 if row["status"] == "success" else 0.0)
            task.append(row["task"])
    if not x:
        sys.exit(f"{path}: no trials of system {system!r}")
    return np.array(x), np.array(y), np.array(task)


def fit_logistic(x, y):
    """Maximum likelihood fit of P(success) = 1 / (1 + exp(-(b0 + b1 x))) by Newton's method."""
    a = np.column_stack([np.ones_like(x), x])
    b = np.zeros(2)
    for _ in range(100):
        p = 1.0 / (1.0 + np.exp(-a @ b))
        step = np.linalg.solve(a.T @ (a * (p * (1.0 - p))[:, None]), a.T @ (y - p))
        b += step
        if np.max(np.abs(step)) < 1e-12:
            break
    return b


def predictions(b, worlds):
    """Mean model success per level over the world distributions (a), (b), (c), (m)."""
    f = lambda t: 1.0 / (1.0 + np.exp(-(b[0] + b[1] * t)))
    rng = np.random.default_rng(0)
    out = {}
    for level in LEVELS:
        p95 = np.array([v for (lv, v) in worlds.values() if lv == level])
        mean, lo, hi = ORIGINAL_P95[level]
        stretched = mean + (p95 - p95.mean()) * (hi - lo) / (p95.max() - p95.min())
        normal = rng.normal(mean, (hi - lo) / 4.2, 200_000)
        moved = p95 - p95.mean() + mean
        out[level] = (f(p95).mean(), f(stretched).mean(), f(normal).mean(), len(p95), f(moved).mean())
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("worlds_csv", help="vb_bench_generator_stats --csv output")
    ap.add_argument("index_csv", help="a batch's index.csv (all 1000 tasks of one system)")
    ap.add_argument("--system", default="pid")
    ap.add_argument("--bootstrap", type=int, default=1000, help="resamples of the worlds (seeded)")
    ap.add_argument("--predict", metavar="INDEX", help="another batch's index.csv to compare with the model")
    args = ap.parse_args()

    all_worlds = read_worlds(args.worlds_csv)
    worlds = all_worlds
    x, y, task = read_trials(args.index_csv, args.system, worlds)
    worlds = {name: v for name, v in worlds.items() if name in set(task)}  # the batch's worlds only
    b = fit_logistic(x, y)
    pred = predictions(b, worlds)
    n_all = sum(v[3] for v in pred.values())

    def overall(p, k):
        return sum(p[lv][k] * p[lv][3] for lv in LEVELS) / n_all

    print(f"{args.system}: {len(y)} trials, success {100 * y.mean():.1f} %; "
          f"logit P = {b[0]:.3f} + {b[1]:.4f} x p95 slope [deg]")
    print("| level | success on vb's worlds | model, vb's worlds (a) | model, stretched to the "
          "original's spread (b) | model, normal at the original's mean and spread (c) | model, vb's worlds "
          "moved to the original's mean (m) |")
    print("|---|---:|---:|---:|---:|---:|")
    for level in LEVELS:
        actual = y[np.array([worlds[t][0] == level for t in task])].mean()
        a, s, c, _, m = pred[level]
        print(f"| {level} | {100 * actual:.1f} % | {100 * a:.1f} % | {100 * s:.1f} % | {100 * c:.1f} % "
              f"| {100 * m:.1f} % |")
    print(f"| all | {100 * y.mean():.1f} % | {100 * overall(pred, 0):.1f} % | "
          f"{100 * overall(pred, 1):.1f} % | {100 * overall(pred, 2):.1f} % | "
          f"{100 * overall(pred, 4):.1f} % |")

    # Bootstrap over worlds (each world keeps its ten trials): the spread of (b) - (a) and (c) - (a).
    rng = np.random.default_rng(1)
    names = np.array(sorted(set(task)))
    rows_of = {n: np.flatnonzero(task == n) for n in names}
    d_b, d_c, d_m = [], [], []
    for _ in range(args.bootstrap):
        pick = rng.choice(names, size=len(names), replace=True)
        idx = np.concatenate([rows_of[n] for n in pick])
        bb = fit_logistic(x[idx], y[idx])
        p = predictions(bb, worlds)
        d_b.append(overall(p, 1) - overall(p, 0))
        d_c.append(overall(p, 2) - overall(p, 0))
        d_m.append(overall(p, 4) - overall(p, 0))
    for label, d in (("(b) - (a)", d_b), ("(c) - (a)", d_c), ("(m) - (a)", d_m)):
        lo, mid, hi = np.percentile(100 * np.array(d), [5, 50, 95])
        print(f"{label}: {mid:+.1f} points over all levels (bootstrap over worlds, 5-95 %: "
              f"{lo:+.1f} .. {hi:+.1f})")

    if args.predict:
        px, py, ptask = read_trials(args.predict, args.system, all_worlds)
        f = lambda t: 1.0 / (1.0 + np.exp(-(b[0] + b[1] * t)))
        print(f"\n| world ({args.predict}) | elevation | p95 slope [deg] | trials | successes | "
              "expected by the model |\n|---|---|---:|---:|---:|---:|")
        for name in sorted(set(ptask), key=lambda n: (len(n), n)):
            m = ptask == name
            print(f"| {name} | {all_worlds[name][0]} | {all_worlds[name][1]:.1f} | {m.sum()} | "
                  f"{int(py[m].sum())} | {f(px[m]).sum():.1f} |")
        print(f"| all | | | {len(py)} | {int(py.sum())} | {f(px).sum():.1f} |")


if __name__ == "__main__":
    main()
