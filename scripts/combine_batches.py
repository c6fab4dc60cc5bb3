#!/usr/bin/env python3
"""Combine finished vb_batch directories into one, for vb_report and the comparison scripts.

Every results README of docs/results that puts systems side by side ran them as separate batches
(e.g. `--systems eh,mppi` and `--systems pid`); this writes OUT/index.csv (the batches' index rows
under their one common header) and links every file of each DIR/trials into OUT/trials
(symbolic links, absolute paths), refusing batches whose headers differ, a trial that two batches
both hold, or an OUT that already has an index. Standard library only.
  usage: scripts/combine_batches.py OUT DIR [DIR ...]
  then:  build/tools/vb_report OUT --out REPORT_DIR [--tasks tasks]; scripts/compare_systems.py OUT
"""
import csv
import os
import sys

KEY = ("task", "pair", "seed", "vehicle", "system")


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out, dirs = sys.argv[1], sys.argv[2:]
    if os.path.exists(os.path.join(out, "index.csv")):
        sys.exit(f"{out}: already holds an index.csv; choose an empty directory")
    header, rows, seen = None, [], {}
    for d in dirs:
        index = os.path.join(d, "index.csv")
        if not os.path.isfile(index):
            sys.exit(f"{index}: missing (not a finished vb_batch directory)")
        with open(index, newline="") as f:
            reader = csv.reader(f)
            h = next(reader, None)
            if h is None:
                sys.exit(f"{index}: empty")
            if header is None:
                header = h
            elif h != header:
                sys.exit(f"{index}: header differs from {os.path.join(dirs[0], 'index.csv')}'s")
            missing = [k for k in KEY if k not in h]
            if missing:
                sys.exit(f"{index}: no column {missing[0]!r}")
            for line, row in enumerate(reader, start=2):
                key = tuple(row[h.index(k)] for k in KEY)
                if key in seen:
                    sys.exit(f"{index}:{line}: trial {'/'.join(key)} is also in {seen[key]}")
                seen[key] = index
                rows.append(row)
    os.makedirs(os.path.join(out, "trials"), exist_ok=True)
    linked = 0
    for d in dirs:
        trials = os.path.join(d, "trials")
        for name in sorted(os.listdir(trials)) if os.path.isdir(trials) else []:
            target = os.path.join(out, "trials", name)
            if os.path.lexists(target):
                sys.exit(f"{target}: two batches hold a file of this name")
            os.symlink(os.path.abspath(os.path.join(trials, name)), target)
            linked += 1
    tmp = os.path.join(out, "index.csv.tmp")
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)
    os.replace(tmp, os.path.join(out, "index.csv"))  # atomic: an index is whole or absent
    print(f"{out}: {len(rows)} trials from {len(dirs)} batches, {linked} trial files linked")


if __name__ == "__main__":
    main()
