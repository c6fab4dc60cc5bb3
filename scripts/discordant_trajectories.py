#!/usr/bin/env python3
"""Trajectory signatures of the trials one system solves and another does not (docs/results).

For systems A and B in one vb_batch directory (trial records DIR/trials/*.json and their
*_traj.csv), takes every task that A solved and B did not and prints, per task and summed up:
B's outcome and end time, where the two paths part (first time they are > 2 m apart, matched by
time), how far apart they end, B's mean |steering| over its last 10 s (saturated steering is a
planner pushing against the terrain), each system's maximum |roll| on the way, and the task's
elevation class. Standard library only; Markdown on stdout.
  usage: scripts/discordant_trajectories.py DIR A B [--list]
"""
import csv
import glob
import json
import math
import os
import statistics
import sys


def load_traj(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [(float(r["t_s"]), float(r["x_m"]), float(r["y_m"]), float(r["roll_deg"]),
             float(r["steering"])) for r in rows]


def records(root, system):
    out = {}
    for path in glob.glob(os.path.join(root, "trials", f"*_{system}.json")):
        with open(path) as f:
            d = json.load(f)
        if d.get("system") != system:
            continue
        key = (d["task"], d["pair"], d["seed"], d["vehicle"])
        out[key] = (d, path[:-len(".json")] + "_traj.csv")
    return out


def signature(a_traj, b_traj):
    part_t = None
    j = 0
    for t, x, y, _, _ in a_traj:
        while j + 1 < len(b_traj) and b_traj[j + 1][0] <= t:
            j += 1
        if j >= len(b_traj) or abs(b_traj[j][0] - t) > 0.06:
            break
        if math.hypot(x - b_traj[j][1], y - b_traj[j][2]) > 2.0:
            part_t = t
            break
    b_end = b_traj[-1]
    a_at = min(a_traj, key=lambda r: abs(r[0] - b_end[0]))
    end_apart = math.hypot(a_at[1] - b_end[1], a_at[2] - b_end[2])
    last = [abs(r[4]) for r in b_traj if r[0] >= b_end[0] - 10.0]
    return {
        "part_t": part_t,
        "end_apart": end_apart,
        "b_last10_steer": statistics.fmean(last) if last else float("nan"),
        "a_max_roll": max(abs(r[3]) for r in a_traj),
        "b_max_roll": max(abs(r[3]) for r in b_traj),
        "b_end_t": b_end[0],
    }


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    root, a, b = sys.argv[1:4]
    listing = "--list" in sys.argv[4:]
    ra, rb = records(root, a), records(root, b)
    elevation = {}
    index = os.path.join(root, "index.csv")
    if os.path.exists(index):
        with open(index) as f:
            for row in csv.DictReader(f):
                elevation[row["task"]] = row["elevation"]
    rows = []
    for key in sorted(ra.keys() & rb.keys()):
        da, ta = ra[key]
        db, tb = rb[key]
        if da["status"] != "success" or db["status"] == "success":
            continue
        if not (os.path.exists(ta) and os.path.exists(tb)):
            continue
        s = signature(load_traj(ta), load_traj(tb))
        s["task"] = f"{key[0]}_p{key[1]}"
        s["b_status"] = db["status"]
        s["elevation"] = elevation.get(key[0], "?")
        rows.append(s)
    if not rows:
        print(f"no task that {a} solved and {b} did not")
        return
    n = len(rows)
    by_status = {}
    for r in rows:
        by_status[r["b_status"]] = by_status.get(r["b_status"], 0) + 1
    parted = [r["part_t"] for r in rows if r["part_t"] is not None]
    early = sum(1 for t in parted if t <= 10.0)
    sat = sum(1 for r in rows if r["b_last10_steer"] >= 0.8)
    higher = sum(1 for r in rows if r["a_max_roll"] > r["b_max_roll"])
    elev = {}
    for r in rows:
        elev[r["elevation"]] = elev.get(r["elevation"], 0) + 1
    stuck_t = [r["b_end_t"] for r in rows if r["b_status"] == "stuck"]
    print(f"## {n} tasks {a} solved and {b} did not\n")
    print(f"- {b} ended: " + ", ".join(f"{v} {k}" for k, v in sorted(by_status.items())))
    print("- elevation: " + ", ".join(f"{v} {k}" for k, v in sorted(elev.items())))
    if stuck_t:
        print(f"- {b}'s stuck trials end at median {statistics.median(stuck_t):.1f} s")
    print(f"- paths part (> 2 m) in {len(parted)} of {n}, within the first 10 s in {early}; "
          f"median end distance {statistics.median(r['end_apart'] for r in rows):.1f} m")
    print(f"- {b}'s mean |steering| over its last 10 s >= 0.8 in {sat} of {n}")
    print(f"- {a}'s max |roll| higher than {b}'s in {higher} of {n} (medians "
          f"{statistics.median(r['a_max_roll'] for r in rows):.1f} vs "
          f"{statistics.median(r['b_max_roll'] for r in rows):.1f} deg)")
    if listing:
        print(f"\n| task | elevation | {b} | {b} end s | part s | end apart m | {b} last-10-s "
              f"\\|steer\\| | max \\|roll\\| {a} / {b} deg |")
        print("|---|---|---|---:|---:|---:|---:|---|")
        for r in rows:
            part = f"{r['part_t']:.1f}" if r["part_t"] is not None else "—"
            print(f"| {r['task']} | {r['elevation']} | {r['b_status']} | {r['b_end_t']:.1f} | "
                  f"{part} | {r['end_apart']:.1f} | {r['b_last10_steer']:.2f} | "
                  f"{r['a_max_roll']:.0f} / {r['b_max_roll']:.0f} |")


if __name__ == "__main__":
    main()
