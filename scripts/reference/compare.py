#!/usr/bin/env python3
"""Side-by-side comparison of the original's runs (run_original.py) with vb's (run_vb.sh), trial
by trial: outcome agreement matrices, distance reached, where the trajectories part, roll/pitch
traces and top-down pictures.

usage: compare.py --original DIR [DIR ...] --vb DIR [DIR ...] --out DIR [--data DIR]
                  [--pictures all|disagree|none] [--tasks FILE]

--original: run_original.py output directories (orig_w<W>_p<P>_<sys>.json + _traj.csv); also
  reads the earlier probe's format (w<W>_p<P>.json with 'rec' and a 10 Hz 'traj').
--vb: vb_batch directories (trials/orig<W>_p<P>_s0_<vehicle>_<system>.json + _traj.csv); each is
  labelled by its directory name; vb's <system>_original is matched with the original's <system>.
--tasks: only these "WORLD PAIR [SYSTEM]" lines (default: every original trial found).
--data: the original sampled_maps directory, for the world images under the pictures.
Writes OUT/report.md (tables), OUT/trials.csv (one row per original trial and vb run) and
OUT/png/w<W>_p<P>_<sys>.png. Needs numpy and matplotlib (the harness venv has them:
CACHE/venv/bin/python scripts/reference/compare.py ...).
"""
import argparse
import csv
import json
import math
import re
import sys
from collections import Counter, defaultdict
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from trial_rules import VbRules, with_rollover  # noqa: E402

OUTCOMES = ["success", "rollover", "stuck", "timeout", "out_of_bounds", "sim_error"]
PART_DISTANCE_M = 1.0


class Run:
    """One trajectory and its outcomes, from either side."""

    def __init__(self, label, world, pair, system, status_vb_rules, status_orig_rules, t, xy,
                 z, roll, pitch, extra):
        self.label, self.world, self.pair, self.system = label, world, pair, system
        self.status_vb_rules = status_vb_rules      # vb's rules
        self.status_orig_rules = status_orig_rules  # the original's (+ rollover at the end)
        self.t, self.xy, self.z, self.roll, self.pitch = t, xy, z, roll, pitch
        self.extra = extra


def _columns(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    head, body = rows[0], np.array(rows[1:], dtype=float) if len(rows) > 1 else np.zeros((0, len(rows[0])))
    return {name: body[:, i] for i, name in enumerate(head)}


def load_original(dirs):
    runs = {}
    for d in map(Path, dirs):
        for path in sorted(d.glob("orig_w*_p*_*.json")):
            if path.name.endswith("_error.json"):
                continue
            r = json.loads(path.read_text())
            c = _columns(path.with_name(path.stem + "_traj.csv"))
            runs[(r["world"], r["pair"], r["system"])] = Run(
                "original", r["world"], r["pair"], r["system"], r["vb_rules_status"],
                r["original_status_with_rollover"], c["t_s"], np.c_[c["x_m"], c["y_m"]], c["z_m"],
                c["roll_deg"], c["pitch_deg"], r)
        for path in sorted(d.glob("w*_p*.json")):  # the earlier probe's format
            m = re.fullmatch(r"w(\d+)_p(\d+)\.json", path.name)
            if not m or (int(m[1]), int(m[2]), "pid") in runs:
                continue
            data = json.loads(path.read_text())
            rec, tr = data["rec"], np.array(data["traj"], dtype=float)
            roll = np.degrees(tr[:, 4])
            vb = VbRules(tuple(rec["goal"][:2]), step_s=0.1)
            for row, rd in zip(tr, roll):
                vb.push(row[0], (row[1], row[2], row[3]), rd)
            status = vb.status or ("stuck" if abs(rec["final_roll_deg"]) <= 30 else "rollover")
            rec.update(vb_rules_note="from the 10 Hz trajectory; undecided ends take the original's label",
                       original_status=rec["status_original_rules"])
            runs[(rec["world"], rec["pair"], "pid")] = Run(
                "original", rec["world"], rec["pair"], "pid", status,
                with_rollover(rec["status_original_rules"], rec["final_roll_deg"]), tr[:, 0],
                tr[:, 1:3], tr[:, 3], roll, np.degrees(tr[:, 5]), rec)
    return runs


def load_vb(d):
    d = Path(d)
    runs = {}
    for path in sorted((d / "trials").glob("orig*_p*_s*_*.json")):
        r = json.loads(path.read_text())
        m = re.fullmatch(r"orig(\d+)", r["task"])
        if not m:
            continue
        traj = path.with_name(path.stem + "_traj.csv")
        if not traj.exists():
            continue
        c = _columns(traj)
        status = r["status"]
        system = r["system"].removesuffix("_original")  # vb's pid_original beside the original's pid
        runs[(int(m[1]), r["pair"], system)] = Run(
            d.name, int(m[1]), r["pair"], r["system"], status, status, c["t_s"],
            np.c_[c["x_m"], c["y_m"]], c["z_m"], c["roll_deg"], c["pitch_deg"], r)
    return runs


def progress_m(run, start, goal):
    direction = np.asarray(goal[:2]) - np.asarray(start[:2])
    return float(np.dot(run.xy[-1] - np.asarray(start[:2]), direction) / np.linalg.norm(direction))


def parting_time(a, b):
    """First time the two trajectories are more than 1 m apart (planar), or None."""
    end = min(a.t[-1], b.t[-1])
    grid = np.arange(0.0, end + 1e-9, 0.05)
    if len(grid) == 0:
        return None
    pa = np.c_[np.interp(grid, a.t, a.xy[:, 0]), np.interp(grid, a.t, a.xy[:, 1])]
    pb = np.c_[np.interp(grid, b.t, b.xy[:, 0]), np.interp(grid, b.t, b.xy[:, 1])]
    apart = np.nonzero(np.linalg.norm(pa - pb, axis=1) > PART_DISTANCE_M)[0]
    return float(grid[apart[0]]) if len(apart) else None


def leaving_time(a, b):
    """First time b is more than 1 m from any point of a's path (a lag along the path does not
    count), or None."""
    def dense(run):
        grid = np.arange(0.0, run.t[-1] + 1e-9, 0.05)
        return grid, np.c_[np.interp(grid, run.t, run.xy[:, 0]), np.interp(grid, run.t, run.xy[:, 1])]
    _, pa = dense(a)
    tb, pb = dense(b)
    if len(pa) == 0 or len(pb) == 0:
        return None
    d = np.min(np.linalg.norm(pb[:, None, :] - pa[None, :, :], axis=2), axis=1)
    off = np.nonzero(d > PART_DISTANCE_M)[0]
    return float(tb[off[0]]) if len(off) else None


def matrix_md(pairs, title):
    """pairs: (original outcome, vb outcome) per trial."""
    rows = [o for o in OUTCOMES if any(p[0] == o for p in pairs)]
    cols = [o for o in OUTCOMES if any(p[1] == o for p in pairs)]
    count = Counter(pairs)
    agree = sum(v for (a, b), v in count.items() if a == b)
    lines = [f"{title}: agree {agree} / {len(pairs)} ({100.0 * agree / max(1, len(pairs)):.0f} %)", "",
             "| original \\ vb | " + " | ".join(cols) + " | all |",
             "|---|" + "---:|" * (len(cols) + 1)]
    for r in rows:
        lines.append(f"| {r} | " + " | ".join(str(count[(r, c)]) for c in cols)
                     + f" | {sum(count[(r, c)] for c in cols)} |")
    lines.append("| all | " + " | ".join(str(sum(count[(r, c)] for r in rows)) for c in cols)
                 + f" | {len(pairs)} |")
    return "\n".join(lines) + "\n"


def mix_md(runs_by_label):
    lines = ["| runs | trials | " + " | ".join(OUTCOMES[:4]) + " |", "|---|---:|" + "---:|" * 4]
    for label, statuses in runs_by_label:
        n = len(statuses)
        c = Counter(statuses)
        lines.append(f"| {label} | {n} | " + " | ".join(
            f"{c[o]} ({100.0 * c[o] / max(1, n):.0f} %)" for o in OUTCOMES[:4]) + " |")
    return "\n".join(lines) + "\n"


def picture(path, key, orig, vbs, data_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(12, 5.2))
    ax = fig.add_axes([0.04, 0.08, 0.42, 0.84])
    world = key[0]
    if data_dir is not None:
        from PIL import Image
        img = Path(data_dir) / "Worlds" / f"{world}.bmp"
        if img.exists():
            ax.imshow(np.asarray(Image.open(img).convert("L")), cmap="gray",
                      extent=[-64.5, 64.5, -64.5, 64.5], origin="upper", alpha=0.8)
    colors = ["tab:red", "tab:blue", "tab:green", "tab:purple", "tab:orange", "tab:brown"]
    runs = [orig] + vbs
    for run, col in zip(runs, colors):
        ax.plot(run.xy[:, 0], run.xy[:, 1], color=col, lw=1.6,
                label=f"{run.label}: {run.status_vb_rules}")
        ax.plot(run.xy[-1, 0], run.xy[-1, 1], "x", color=col, ms=8)
    rec = orig.extra
    ax.plot(*rec["start"][:2], "o", color="k")
    ax.add_patch(plt.Circle(rec["goal"][:2], 10.0, fill=False, color="k", ls="--"))
    ax.set_xlim(-65, 65)
    ax.set_ylim(-65, 65)
    ax.set_aspect("equal")
    ax.legend(loc="lower left", fontsize=7)
    kind = f" ({rec['level']} {rec['terrain_type']})" if rec.get("level") else ""
    ax.set_title(f"world {key[0]} pair {key[1]}{kind}, {key[2]}: top-down (start o, 10 m goal "
                 "circle, end x)", fontsize=8)
    for i, (field, name) in enumerate((("roll", "roll"), ("pitch", "pitch"))):
        a2 = fig.add_axes([0.53, 0.56 - 0.48 * i, 0.45, 0.38])
        for run, col in zip(runs, colors):
            a2.plot(run.t, getattr(run, field), color=col, lw=1.0, label=run.label)
        a2.set_ylabel(f"{name} (deg)")
        a2.axhline(30, color="gray", lw=0.5, ls=":")
        a2.axhline(-30, color="gray", lw=0.5, ls=":")
        if i == 1:
            a2.set_xlabel("t (s)")
        else:
            a2.legend(fontsize=7)
    fig.savefig(path, dpi=80)
    plt.close(fig)


def stratum_sizes(data_dir):
    """Tasks per (level, terrain type) of the original worlds in data_dir (10 pairs a world)."""
    import yaml

    sizes = Counter()
    for path in Path(data_dir, "Configs/Final").glob("config*_*.yaml"):
        with open(path) as f:
            cfg = yaml.safe_load(f)
        sizes[(cfg["terrain"]["difficulty"], cfg["terrain_type"])] += len(cfg["positions"])
    return sizes


def weighted_mix_md(keys, orig, per_label, labels, strata):
    """The outcome mix of a stratified sample weighted back to the worlds' strata (PID only)."""
    def mix(statuses_by_key):
        per = defaultdict(Counter)
        for k, st in statuses_by_key.items():
            per[(orig[k].extra["level"], orig[k].extra["terrain_type"])][st] += 1
        total = sum(strata[s] for s in per)
        out = Counter()
        for s, c in per.items():
            n = sum(c.values())
            for o, v in c.items():
                out[o] += strata[s] / total * v / n
        return out
    pid = [k for k in keys if k[2] == "pid"]
    rows = [("original", mix({k: orig[k].status_vb_rules for k in pid}))]
    for label in labels:
        got = {(o.world, o.pair, o.system): v.status_vb_rules
               for o, v in per_label[label] if o.system == "pid"}
        if got:
            rows.append((label, mix(got)))
    lines = ["## Outcome mix weighted to the strata of the worlds (pid, vb's rules)\n",
             "| runs | " + " | ".join(OUTCOMES[:4]) + " |", "|---|" + "---:|" * 4]
    for label, m in rows:
        lines.append(f"| {label} | " + " | ".join(f"{100 * m[o]:.1f} %" for o in OUTCOMES[:4]) + " |")
    return "\n".join(lines) + "\n"


BASE_FIELDS = ["world", "pair", "system", "level", "terrain", "original_vb_rules", "original_orig_rules",
               "original_progress_m", "original_max_roll_deg", "original_start_depth_m"]


def fields(labels):
    return BASE_FIELDS + [f"{label}{suffix}" for label in labels
                          for suffix in ("", "_progress_m", "_parts_at_s", "_leaves_path_at_s", "_max_roll_deg")]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--original", nargs="+", required=True)
    ap.add_argument("--vb", nargs="+", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--data")
    ap.add_argument("--tasks")
    ap.add_argument("--pictures", choices=["all", "disagree", "none"], default="all")
    args = ap.parse_args()
    orig = load_original(args.original)
    vbs = [load_vb(d) for d in args.vb]
    labels = [Path(d).name for d in args.vb]
    keys = sorted(orig)
    if args.tasks:
        wanted = set()
        for line in Path(args.tasks).read_text().splitlines():
            f = line.split("#", 1)[0].split()
            if f:
                wanted.add((int(f[0]), int(f[1]), f[2] if len(f) > 2 else "pid"))
        keys = [k for k in keys if k in wanted]
    out = Path(args.out)
    (out / "png").mkdir(parents=True, exist_ok=True)
    table, per_label = [], defaultdict(list)
    for key in keys:
        o = orig[key]
        row = {"world": key[0], "pair": key[1], "system": key[2],
               "level": o.extra.get("level", ""), "terrain": o.extra.get("terrain_type", ""),
               "original_vb_rules": o.status_vb_rules, "original_orig_rules": o.status_orig_rules,
               "original_progress_m": round(progress_m(o, o.extra["start"], o.extra["goal"]), 1),
               "original_max_roll_deg": round(float(np.max(np.abs(o.roll))), 1),
               "original_start_depth_m": max(o.extra.get("start_wheel_depth_m", [float("nan")]))}
        matched = []
        for label, vb in zip(labels, vbs):
            v = vb.get(key)
            if v is None:
                continue
            matched.append(v)
            per_label[label].append((o, v))
            row[f"{label}"] = v.status_vb_rules
            row[f"{label}_progress_m"] = round(progress_m(v, o.extra["start"], o.extra["goal"]), 1)
            row[f"{label}_parts_at_s"] = parting_time(o, v)
            row[f"{label}_leaves_path_at_s"] = leaving_time(o, v)
            row[f"{label}_max_roll_deg"] = round(float(np.max(np.abs(v.roll))), 1)
            for k in ("_parts_at_s", "_leaves_path_at_s"):
                if row[f"{label}{k}"] is not None:
                    row[f"{label}{k}"] = round(row[f"{label}{k}"], 2)
        table.append(row)
        disagree = any(v.status_vb_rules != o.status_vb_rules for v in matched[:1])
        if matched and (args.pictures == "all" or (args.pictures == "disagree" and disagree)):
            picture(out / "png" / f"w{key[0]}_p{key[1]}_{key[2]}.png", key, o, matched, args.data)
    with open(out / "trials.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields(labels))
        w.writeheader()
        w.writerows(table)
    md = [f"# Cross-check: the original's runs beside vb's ({len(keys)} original trials)\n"]
    for label in labels:
        pairs = per_label[label]
        if not pairs:
            continue
        is_orig_rules = "rules-verti_bench" in label
        md.append(matrix_md([(o.status_orig_rules if is_orig_rules else o.status_vb_rules,
                              v.status_vb_rules) for o, v in pairs],
                            f"## {label} ({'the original' if is_orig_rules else 'vb'}'s rules on both sides)"))
        fails = [(o, v) for o, v in pairs if v.status_vb_rules != "success"]
        agree = sum(o.status_vb_rules == v.status_vb_rules for o, v in fails)
        md.append(f"Where {label} fails: agree {agree} / {len(fails)}.\n")
    strata = stratum_sizes(args.data) if args.data else {}
    if strata and all(orig[k].extra.get("level") for k in keys):
        md.append(weighted_mix_md(keys, orig, per_label, labels, strata))
    for system in sorted({k[2] for k in keys}):
        md.append(f"## Outcome mix, {system} (vb's rules; the original's trials and vb's on the same tasks)\n")
        md.append(mix_md([("original", [orig[k].status_vb_rules for k in keys if k[2] == system])]
                         + [(label, [v.status_vb_rules for o, v in per_label[label] if o.system == system])
                            for label in labels if any(o.system == system for o, _ in per_label[label])]))
    md.append("\n## Per trial\n")
    cols = fields(labels)
    md.append("| " + " | ".join(cols) + " |\n|" + "---|" * len(cols))
    for r in table:
        md.append("| " + " | ".join("" if r.get(c) is None else str(r.get(c)) for c in cols) + " |")
    (out / "report.md").write_text("\n".join(md) + "\n")
    print(f"compare: {len(keys)} original trials -> {out}/report.md, trials.csv, png/")


if __name__ == "__main__":
    main()
