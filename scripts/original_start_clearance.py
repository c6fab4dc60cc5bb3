#!/usr/bin/env python3
"""Where the original benchmark's start rule would put the HMMWV's wheels on vb's worlds.

The original runners start the vehicle with its reference point (the chassis frame, at wheel-centre
height) at the high-resolution map's height under the start + 1 m, level, facing the goal
(reference_verti_bench.md §5). The high-resolution map comes from a 129 m mesh of the world image
while the simulated terrain is 128 m wide (§2.4, quirk 1), so at the start (60 m from the centre)
the height is read ~0.4 m closer to the centre, i.e. ahead of the vehicle. vb instead drops the
vehicle 0.5 m above the highest ground under its reference point and wheels (docs/architecture.md),
so no wheel ever starts in the ground. This script computes, for every trial of the given task
files, how far the lowest point of each wheel (spindle height - r, wheels at the design position)
would start below the ground under its centre under the original's rule: geometry only, no
physics. Positive = below the ground.

Usage: scripts/original_start_clearance.py tasks/*.yaml [--csv FILE]
"""
import argparse
import csv
import math
import re
import sys
from pathlib import Path

import numpy as np

# HMMWV (data/vehicles/hmmwv.yaml; reference_vehicle_soil.md §1): spindles at x = +-1.651 m,
# half track 0.9097 m, rigid tire radius 0.467 m.
SPINDLE_X_M = (1.651, -1.651)
HALF_TRACK_M = 0.9097
WHEEL_RADIUS_M = 0.467
START_HEIGHT_M = 1.0  # the original's start.z (reference point above the high-res height)
HIGH_RES_PX = 1291  # the original's high-resolution map: 1291 x 1291 over [-64.5, 64.5] m
PRE_HEIGHT_HALF_M = 64.5  # its mesh spans 129 m, the world's 128 m (vertex spacing 129/128)


def _field(text, path, key):
    m = re.search(rf"^\s*{key}:\s*(.+)$", text, re.MULTILINE)
    if not m:
        sys.exit(f"{path}: no '{key}'")
    return m.group(1).strip()


def load_task(path):
    """Heights (row 0 = north), elevation label and (start, goal) pairs of a vb task file."""
    from PIL import Image  # pillow: part of the project's .venv (datasets extra)

    text = Path(path).read_text()
    size = [float(v) for v in re.search(r"size_m:\s*\[([^\]]+)\]", text).group(1).split(",")]
    if size != [128.0, 128.0] or float(_field(text, path, "scale")) != 1.0:
        sys.exit(f"{path}: only 128 m worlds at scale 1 (the original's) are supported")
    lo, hi = [float(v) for v in re.search(r"height_range_m:\s*\[([^\]]+)\]", text).group(1).split(",")]
    image = Path(path).parent / _field(text, path, "height_image")
    with Image.open(image) as im:
        if im.mode == "P":  # an 8-bit BMP with a gray palette
            im = im.convert("L")
        full_scale = {"L": 255.0, "I;16": 65535.0, "I": 65535.0}.get(im.mode)
        if full_scale is None:
            sys.exit(f"{image}: expected an 8- or 16-bit grayscale image, got mode {im.mode}")
        pixels = np.asarray(im, dtype=float)
    if pixels.shape != (129, 129):
        sys.exit(f"{image}: expected 129 x 129 pixels, got {pixels.shape}")
    heights = lo + pixels / full_scale * (hi - lo)  # docs/task_format.md: min + p / full scale
    level = re.search(r"elevation:\s*(\w+)", text)
    if not level:
        sys.exit(f"{path}: no 'elevation' label")
    level = level.group(1)
    starts = [tuple(float(v) for v in s.split(",")) for s in re.findall(r"- start:\s*\[([^\]]+)\]", text)]
    goals = [tuple(float(v) for v in g.split(",")) for g in re.findall(r"\bgoal:\s*\[([^\]]+)\]", text)]
    if not starts or len(starts) != len(goals):
        sys.exit(f"{path}: could not read the start/goal pairs")
    return heights, level, list(zip(starts, goals))


def height(h, x, y):
    """vb's terrain: vertex (row r, col c) at x = c - 64, y = 64 - r; cells split SW-NE."""
    c = x + 64.0
    r = 64.0 - y
    c0 = min(max(int(math.floor(c)), 0), 127)
    r0 = min(max(int(math.floor(r)), 0), 127)
    u, v = c - c0, r - r0  # u east, v south within the cell
    nw, ne, sw, se = h[r0, c0], h[r0, c0 + 1], h[r0 + 1, c0], h[r0 + 1, c0 + 1]
    if u + v <= 1.0:  # the north-west triangle (NW, NE, SW)
        return nw + u * (ne - nw) + v * (sw - nw)
    return se + (1.0 - u) * (sw - se) + (1.0 - v) * (ne - se)


def original_start_height(h, x, y):
    """The original's start z: its high-res map at the start's nearest pixel, + 1 m."""
    s = HIGH_RES_PX / 129.0
    col = int(np.round(np.clip((x + 64.5) * s, 0, HIGH_RES_PX - 1)))  # numpy: half to even
    row = int(np.round(np.clip((-y + 64.5) * s, 0, HIGH_RES_PX - 1)))
    xq = -PRE_HEIGHT_HALF_M + col * 0.1  # the query grid, linspace(-64.5, 64.5, 1291)
    yq = PRE_HEIGHT_HALF_M - row * 0.1
    # the 129 m mesh is the 128 m world scaled by 129/128 about its corner
    xp = (xq + PRE_HEIGHT_HALF_M) * 128.0 / 129.0 - 64.0
    yp = (yq + PRE_HEIGHT_HALF_M) * 128.0 / 129.0 - 64.0
    return height(h, xp, yp) + START_HEIGHT_M


def wheel_depths(h, start, goal):
    """Depth below the ground of each wheel's lowest point (FL, FR, RL, RR) at the original's start."""
    yaw = math.atan2(goal[1] - start[1], goal[0] - start[0])
    cy, sy = math.cos(yaw), math.sin(yaw)
    z = original_start_height(h, start[0], start[1])
    depths = []
    for dx in SPINDLE_X_M:
        for dy in (HALF_TRACK_M, -HALF_TRACK_M):
            wx = start[0] + cy * dx - sy * dy
            wy = start[1] + sy * dx + cy * dy
            depths.append(height(h, wx, wy) - (z - WHEEL_RADIUS_M))
    return depths


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("tasks", nargs="+")
    ap.add_argument("--csv", help="write one row per trial (task, pair, elevation, the four depths)")
    args = ap.parse_args()
    rows = []
    for path in args.tasks:
        h, level, pairs = load_task(path)
        for k, (start, goal) in enumerate(pairs):
            rows.append((Path(path).stem, k, level, wheel_depths(h, start, goal)))
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["task", "pair", "elevation", "fl_m", "fr_m", "rl_m", "rr_m"])
            for task, k, level, d in rows:
                w.writerow([task, k, level] + [f"{v:.4f}" for v in d])
    print("| elevation | trials | a wheel starts below the ground | by > 0.1 m | a wheel centre below "
          "the ground (> r) | deepest |\n|---|---:|---:|---:|---:|---:|")
    for level in ("low", "mid", "high", "all"):
        deepest = np.array([max(d) for (_, _, lv, d) in rows if level in ("all", lv)])
        if deepest.size == 0:
            continue
        print(f"| {level} | {deepest.size} | {100 * (deepest > 0).mean():.1f} % | "
              f"{100 * (deepest > 0.1).mean():.1f} % | {100 * (deepest > WHEEL_RADIUS_M).mean():.1f} % | "
              f"{deepest.max():.2f} m |")


if __name__ == "__main__":
    main()
