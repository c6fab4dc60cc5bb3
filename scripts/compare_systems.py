#!/usr/bin/env python3
"""Paired comparison of mobility systems in one vb_batch directory (docs/baselines.md "Results").

Reads DIR/trials/*.json (standard library only) and prints, per system: success by elevation /
terrain / density, failure types, obstacle contacts, tipped trials, path length and steering
activity; then, for each pair of systems, the trials (same task, pair, seed, vehicle) that one
solved and the other did not, with the other's failure. Markdown on stdout.
  usage: scripts/compare_systems.py DIR [SYSTEM...]
"""
import glob
import json
import math
import os
import re
import sys
from collections import defaultdict


def sign_test_p(a, b):
    """Two-sided exact sign test on a discordant pairs one way and b the other (p = 1 if none)."""
    n, k = a + b, min(a, b)
    if n == 0:
        return 1.0
    return min(1.0, 2.0 * sum(math.comb(n, i) for i in range(k + 1)) / 2.0 ** n)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    root = sys.argv[1]
    wanted = sys.argv[2:]
    trials = {}
    labels = {}
    index = os.path.join(root, "index.csv")
    if os.path.exists(index):
        with open(index) as f:
            header = f.readline().strip().split(",")
            for line in f:
                row = dict(zip(header, line.strip().split(",")))
                labels[row["task"]] = (row["elevation"], row["terrain"], row["density"])
    for path in sorted(glob.glob(os.path.join(root, "trials", "*.json"))):
        with open(path) as f:
            d = json.load(f)
        if d.get("task") and d["task"] not in labels:
            # a batch still running has no index yet: the labels line of the task file
            task_file = os.path.join(os.path.dirname(__file__), "..", "tasks", d["task"] + ".yaml")
            if os.path.exists(task_file):
                with open(task_file) as f:
                    m = re.search(r"labels: \{elevation: (\w+), terrain: (\w+), density: (\w+)",
                                  f.read())
                if m:
                    labels[d["task"]] = m.groups()
        if "system" not in d or (wanted and d["system"] not in wanted):
            continue
        trials[(d["task"], d["pair"], d["seed"], d["vehicle"], d["system"])] = d
    systems = wanted or sorted({k[4] for k in trials})
    keys = sorted({k[:4] for k in trials if all(k[:4] + (s,) in trials for s in systems)})
    print(f"{len(keys)} trials with a record for every system ({', '.join(systems)})\n")

    print("| system | success % | rollover % | stuck % | timeout % | out_of_bounds % | "
          "tipped % | obstacle contacts / trial | path m (success) | mean abs steering |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for s in systems:
        ds = [trials[k + (s,)] for k in keys]
        n = len(ds)
        pct = lambda st: 100.0 * sum(d["status"] == st for d in ds) / n
        ok = [d for d in ds if d["status"] == "success"]
        print(f"| {s} | {pct('success'):.1f} | {pct('rollover'):.1f} | {pct('stuck'):.1f} | "
              f"{pct('timeout'):.1f} | {pct('out_of_bounds'):.1f} | "
              f"{100.0 * sum(bool(d['tipped']) for d in ds) / n:.1f} | "
              f"{sum(d['obstacle_contacts'] for d in ds) / n:.2f} | "
              f"{(sum(d['path_length_m'] for d in ok) / len(ok)) if ok else float('nan'):.1f} | "
              f"{sum(d['abs_steering']['mean'] for d in ds) / n:.3f} |")
    print()
    for fi, factor in enumerate(["elevation", "terrain", "density"]):
        levels = sorted({labels.get(k[0], ("?",) * 3)[fi] for k in keys})
        print(f"| {factor} | n | " + " | ".join(f"{s} success %" for s in systems) + " |")
        print("|---|---|" + "---|" * len(systems))
        for lv in levels:
            ks = [k for k in keys if labels.get(k[0], ("?",) * 3)[fi] == lv]
            cells = [100.0 * sum(trials[k + (s,)]["status"] == "success" for k in ks) / len(ks)
                     for s in systems]
            print(f"| {lv} | {len(ks)} | " + " | ".join(f"{c:.1f}" for c in cells) + " |")
        print()
    # How the failures look at their end (trajectory CSVs): the last sample's |roll|, |pitch|, and
    # whether the steering was saturated and the vehicle touched an obstacle.
    print("| system | failure | n | median end abs roll deg | median end abs pitch deg | "
          "steering saturated at the end % | touched an obstacle % |")
    print("|---|---|---|---|---|---|---|")
    for s in systems:
        for status in ("stuck", "rollover"):
            ks = [k for k in keys if trials[k + (s,)]["status"] == status]
            if not ks:
                continue
            rolls, pitches, sat = [], [], 0
            for k in ks:
                stem = f"{k[0]}_p{k[1]}_s{k[2]}_{k[3]}_{s}"
                with open(os.path.join(root, "trials", stem + "_traj.csv")) as f:
                    header = f.readline().strip().split(",")
                    last = None
                    for line in f:
                        last = line
                row = dict(zip(header, last.strip().split(",")))
                rolls.append(abs(float(row["roll_deg"])))
                pitches.append(abs(float(row["pitch_deg"])))
                sat += abs(float(row["steering"])) >= 0.95
            rolls.sort()
            pitches.sort()
            touched = sum(trials[k + (s,)]["obstacle_contacts"] > 0 for k in ks)
            print(f"| {s} | {status} | {len(ks)} | {rolls[len(rolls) // 2]:.1f} | "
                  f"{pitches[len(pitches) // 2]:.1f} | {100.0 * sat / len(ks):.0f} | "
                  f"{100.0 * touched / len(ks):.0f} |")
    print()
    for i, a in enumerate(systems):
        for b in systems[i + 1:]:
            only_a = [k for k in keys if trials[k + (a,)]["status"] == "success"
                      and trials[k + (b,)]["status"] != "success"]
            only_b = [k for k in keys if trials[k + (b,)]["status"] == "success"
                      and trials[k + (a,)]["status"] != "success"]
            print(f"{a} vs {b}: {len(only_a)} solved only by {a}, {len(only_b)} only by {b} "
                  f"(two-sided sign test p = {sign_test_p(len(only_a), len(only_b)):.2g})")
            for name, lst, other in ((a, only_a, b), (b, only_b, a)):
                why = defaultdict(int)
                for k in lst:
                    why[trials[k + (other,)]["status"]] += 1
                print(f"  only {name}: {other} ended " +
                      ", ".join(f"{v} {st}" for st, v in sorted(why.items())))
                print("    e.g. " + ", ".join(f"{k[0]}_p{k[1]}" for k in lst[:8]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
