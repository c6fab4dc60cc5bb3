#!/usr/bin/env python3
"""Rollover counted three ways over a batch's trial records (docs/validation.md, issue 11).

The original's runners never end a trial for a rollover (reference_verti_bench.md §6.1): a
vehicle on its side ends as "stuck" or at the time limit, and only the per-step |roll| and
|pitch| are logged. vb's rule (the spec's, kept) calls a failed trial a rollover when |roll| >
30 deg at its end. This prints, for one batch directory, how many failures a rule over the whole
trajectory would call rollovers instead: |roll| above 30 deg at some moment, above 45 deg
(`tipped`), and |roll| or |pitch| above 30 deg, per elevation level and overall.

usage: scripts/rollover_definitions.py BATCH_DIR   (a vb_batch --out directory with trials/)
"""
import collections
import csv
import glob
import json
import os
import sys


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    run = sys.argv[1]
    index = os.path.join(run, "index.csv")
    if not os.path.isfile(index):
        sys.exit(f"{index}: no such file (not a vb_batch output directory)")
    level = {}
    with open(index, newline="") as f:
        for row in csv.DictReader(f):
            level[(row["task"], row["pair"], row["seed"], row["vehicle"], row["system"])] = (
                row["elevation"])
    rules = {
        "end |roll| > 30 (vb, the spec)": lambda r: r["status"] == "rollover",
        "ever |roll| > 30": lambda r: r["abs_roll_deg"]["max"] > 30.0,
        "ever |roll| > 45 (tipped)": lambda r: bool(r["tipped"]),
        "ever |roll| or |pitch| > 30": lambda r: max(r["abs_roll_deg"]["max"],
                                                      r["abs_pitch_deg"]["max"]) > 30.0,
    }
    counts = collections.defaultdict(collections.Counter)
    trials = collections.Counter()
    files = sorted(glob.glob(os.path.join(run, "trials", "*.json")))
    if not files:
        sys.exit(f"{run}/trials: no trial records")
    for path in files:
        with open(path) as f:
            r = json.load(f)
        key = (r["task"], str(r["pair"]), str(r["seed"]), r["vehicle"], r["system"])
        lv = level.get(key, "?")
        for g in (lv, "all"):
            trials[g] += 1
            if r["status"] == "success":
                counts[g]["success"] += 1
                continue
            for name, rule in rules.items():
                if rule(r):
                    counts[g][name] += 1
    groups = [g for g in ("low", "mid", "high", "?") if trials[g]] + ["all"]
    print(f"{run}: {trials['all']} trials; failed trials called rollover by each rule (% of all "
          "trials)")
    print(f"{'rule':34s}" + "".join(f"{g:>16s}" for g in groups))
    print(f"{'success':34s}" + "".join(
        f"{counts[g]['success']:>8d} ({100.0 * counts[g]['success'] / trials[g]:4.1f}%)"
        for g in groups))
    for name in rules:
        print(f"{name:34s}" + "".join(
            f"{counts[g][name]:>8d} ({100.0 * counts[g][name] / trials[g]:4.1f}%)"
            for g in groups))


if __name__ == "__main__":
    main()
