#!/usr/bin/env python3
"""Instructions per physics step, by stage, from callgrind: a step-cost measure that does not
depend on what else the machine is doing (wall-clock timings on a shared machine do).

Runs build/bench/vb_bench_episode under `valgrind --tool=callgrind` on PAIRS pairs (from pair
SKIP) of TASK (a trimmed copy of the task, its relative paths made absolute) and prints, per step,
the inclusive instruction counts of the stages of Episode::Impl::PhysicsStep. Compare two builds
by running it with --build of each (the instruction count of the same binary and input is
repeatable; different builds may take different trajectories, hence "per step").

usage: scripts/profile_step.py TASK [--pairs 2] [--skip 0] [--build build] [--keep FILE]
       [--vehicle hmmwv] [--soil FILE]
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

STAGES = [
    ("physics step (all)", r"vb::runner::Episode::Impl::PhysicsStep\(\)"),
    ("  vehicle synchronise", r"vb::vehicles::Vehicle::Synchronize\(double\)"),
    ("    wheel-ground contact", r"vb::vehicles::FindWheelContact\("),
    ("    body contacts", r"vb::vehicles::Vehicle::AddBodyContacts\(\)"),
    ("    soil", r"vb::soil::ScmSoil::WheelContact\("),
    ("    soil (track)", r"vb::soil::ScmSoil::TrackContact\("),
    ("  soil end of step", r"vb::soil::ScmSoil::EndStep\("),
    ("    erosion", r"vb::soil::ScmSoil::Impl::Erode\("),
    ("  dynamics step (vb)", r"vb::engine::PhysicsWorld::Impl::StepBody\("),
    ("  Bullet step", r"btDiscreteDynamicsWorld::stepSimulation\("),
    ("    articulated-body dynamics", r"btMultiBodyDynamicsWorld::solveExternalForces\("),
    ("    solver setup (rows)", r"btMultiBodyConstraintSolver::solveGroupCacheFriendlySetup\("),
    ("    solver sweeps",
     r"btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyIterations\("),
    ("    integration", r"(btMultiBodyDynamicsWorld|VbMultiBodyWorld)::integrateTransforms\("),
    ("  state read-out", r"vb::vehicles::Vehicle::UpdateState\(\)"),
]


def trimmed_task(task, pairs, out_path, skip=0):
    text = open(task).read()
    base = os.path.dirname(os.path.abspath(task))
    # relative file references (height image, ...) become absolute
    text = re.sub(r"(:\s*)(\.\./[^\s,\]]+|[\w./-]+\.png)",
                  lambda m: m.group(1) + os.path.normpath(os.path.join(base, m.group(2)))
                  if not os.path.isabs(m.group(2)) else m.group(0), text)
    head, sep, body = text.partition("\npairs:\n")
    if not sep:
        sys.exit(f"{task}: no 'pairs:' block")
    items = re.split(r"\n(?=  - start:)", body)
    if skip >= len(items):
        sys.exit(f"{task}: --skip {skip} but only {len(items)} pairs")
    open(out_path, "w").write(head + sep + "\n".join(items[skip:skip + pairs]).rstrip("\n") + "\n")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("task")
    ap.add_argument("--pairs", type=int, default=2)
    ap.add_argument("--skip", type=int, default=0, help="start at this pair (0-based)")
    ap.add_argument("--build", default="build")
    ap.add_argument("--keep", help="keep the callgrind output in this file")
    ap.add_argument("--vehicle", default="hmmwv", help="data/vehicles/NAME.yaml")
    ap.add_argument("--soil", help="soil file of deformable worlds (default: the bench's, "
                    "data/soils/verti_bench.yaml)")
    a = ap.parse_args()
    bench = os.path.join(a.build, "bench", "vb_bench_episode")
    if not os.access(bench, os.X_OK):
        sys.exit(f"{bench} not found: build first")
    with tempfile.TemporaryDirectory() as tmp:
        task = os.path.join(tmp, os.path.basename(a.task))
        trimmed_task(a.task, a.pairs, task, a.skip)
        out = a.keep or os.path.join(tmp, "callgrind.out")
        run = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out,
                              bench, task, "1", a.vehicle]
                             + (["0.005", os.path.abspath(a.soil)] if a.soil else []),
                             capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(run.stdout + run.stderr)
        m = re.search(r"(\d+) steps", run.stdout)
        if not m:
            sys.exit("no step count in the bench output:\n" + run.stdout)
        steps = int(m.group(1))
        ann = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", out],
                             capture_output=True, text=True).stdout
    counts = {}
    for line in ann.splitlines():
        m = re.match(r"\s*([\d,]+) \([ \d.]+%\)\s+\S*?:(.*)", line)
        if not m:
            continue
        n, fn = int(m.group(1).replace(",", "")), m.group(2)
        for label, pattern in STAGES:
            if re.search(pattern, fn):
                counts[label] = counts.get(label, 0) + n
    outcome = re.search(r"run 1: (.*?), \d", run.stdout)
    print(f"{a.task} (pairs {a.skip}-{a.skip + a.pairs - 1}, {steps} steps, "
          f"{outcome.group(1) if outcome else '?'}), {bench}")
    total = counts.get(STAGES[0][0], 0)
    for label, _ in STAGES:
        if label in counts:
            n = counts[label] / steps
            share = 100 * counts[label] / total
            print(f"  {label:<32} {n / 1000:8.1f} k instructions/step  {share:5.1f} %")


if __name__ == "__main__":
    main()
