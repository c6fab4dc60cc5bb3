#!/usr/bin/env python3
"""Runs the original Verti-Bench's own code (PID, EH or MPPI) on Chrono for one world and pair,
or for a list of them, and records the trajectory and the outcome by both rule sets.

usage:
  run_original.py WORLD PAIR [--system pid|eh|mppi] [--out DIR] [--seed S] [--max-time S]
  run_original.py --tasks FILE [--out DIR] [--trial-timeout S]      batch, resumable

  FILE: one trial per line, "WORLD PAIR [SYSTEM]" (SYSTEM default pid; '#' starts a comment);
  several --tasks files run one after the other (scripts/reference/tasks/).
  --out DIR (default results/reference): per trial orig_w<W>_p<P>_<system>.json (record) and
  ..._traj.csv (every 10th physics step, 20 Hz, and the last state); both written atomically,
  the trajectory first, so a record implies its trajectory. The batch skips recorded trials, runs
  each of the others in a fresh process (nice it: `nice -n 10`), and on a crash or timeout writes
  ..._error.json, which the next run retries.
  --cache DIR: as build_chrono.sh (default $VB_REFERENCE_CACHE or ~/.cache/vb-reference); needs
  build_chrono.sh and prepare_original.sh done. This script re-executes itself in the cache's venv
  with PyChrono on its paths.

What runs is the original's `systems/<SYS>/<SYS>_sim.py` as its setup.py runs it (vehicle hmmwv,
speed 4, scale 1, no rendering), with the config's start/goal of the pair, unmodified; the
stand-ins are listed in original_env.py and prepare_original.sh. The harness observes it through
the vehicle manager's `advance` (called once per 5 ms step, after the loop's own checks) and sets
one attribute: the sim's `stuck_time` is made infinite and the harness applies the original's
stuck rule itself (trial_rules.OriginalRules, the same arithmetic), so the trial can go on until
vb's rules have decided too. Up to the original's own end the trajectory is the original's.
"""
import argparse
import csv
import io
import json
import math
import os
import subprocess
import sys
import time
from contextlib import redirect_stdout
from pathlib import Path

HERE = Path(__file__).resolve().parent
SYSTEMS = {"pid": ("verti_bench.systems.PID.PID_sim", "PIDSim"),
           "eh": ("verti_bench.systems.EH.EH_sim", "EHSim"),
           "mppi": ("verti_bench.systems.MPPI.MPPI_sim", "MPPISim")}
SAMPLE_EVERY = 10  # physics steps between trajectory rows
TIRE_RADIUS_M = 0.467  # HMMWV rigid tire (reference_vehicle_soil.md §1)
COLUMNS = ["t_s", "x_m", "y_m", "z_m", "roll_deg", "pitch_deg", "yaw_deg", "speed_mps", "throttle",
           "steering", "braking", "gear", "engine_radps",
           "contact_fl_N", "contact_fr_N", "contact_rl_N", "contact_rr_N"]


class StopTrial(Exception):
    """Both rule sets have decided: the harness ends the trial."""


def default_cache():
    return Path(os.environ.get("VB_REFERENCE_CACHE", Path.home() / ".cache/vb-reference"))


def trial_name(world, pair, system):
    return f"orig_w{world}_p{pair}_{system}"


def write_atomic(path, text):
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(text)
    os.replace(tmp, path)


# ----------------------------------------------------------------------------------- one trial
def ground_height(terrains, chrono, x, y):
    """The simulated ground under (x, y): the highest of the world's terrain objects there."""
    best = None
    for t in terrains:
        h = t.GetHeight(chrono.ChVector3d(x, y, 100.0))
        best = h if best is None else max(best, h)
    return best


def run_trial(args):
    sys.path.insert(0, str(HERE))
    import original_env

    original_env.enter(args.cache, args.seed)
    import numpy as np
    import pychrono as chrono
    import pychrono.vehicle as veh
    from make_heights import make_height_map
    from trial_rules import OriginalRules, VbRules, with_rollover

    t_heights = time.time()
    make_height_map(args.cache, args.world)
    heights_s = time.time() - t_heights
    from verti_bench.envs.utils.utils import SetChronoDataDirectories

    SetChronoDataDirectories()
    module, cls = SYSTEMS[args.system]
    sim_class = getattr(__import__(module, fromlist=[cls]), cls)
    config = {"vehicle": "hmmwv", "speed": 4.0, "system": args.system, "world_id": args.world,
              "max_time": args.max_time, "scale_factor": 1.0, "render": False, "use_gui": False}
    log = io.StringIO()
    t0 = time.time()
    with redirect_stdout(log):
        sim = sim_class(config)
        tm = sim.terrain_manager
        if not 0 <= args.pair < len(tm.positions):
            raise SystemExit(f"run_original: world {args.world} has {len(tm.positions)} pairs, "
                             f"not pair {args.pair}")
        pos = tm.positions[args.pair]
        sim.initialize(start_pos=list(pos["start"]), goal_pos=list(pos["goal"]))
    sim.stuck_time = math.inf  # the harness applies the original's stuck rule (OriginalRules)
    vm = sim.vehicle_manager
    vehicle = vm.vehicle.GetVehicle()
    wheels = [axle.m_wheels[side] for axle in vehicle.GetAxles() for side in (0, 1)]
    scm = [t for t in sim.terrains if isinstance(t, veh.SCMTerrain)]
    goal = vm.goal
    orig_rules = OriginalRules((goal.x, goal.y, goal.z), args.max_time)
    vb_rules = VbRules((pos["goal"][0], pos["goal"][1]), args.max_time)
    start_depth = [round(ground_height(sim.terrains, chrono, w.GetSpindle().GetPos().x,
                                       w.GetSpindle().GetPos().y)
                         - (w.GetSpindle().GetPos().z - TIRE_RADIUS_M), 4) for w in wheels]
    rows, extremes = [], {"roll": 0.0, "pitch": 0.0}
    state = {"k": 0, "last": None, "scm_forces": bool(scm)}

    def sample(t, p, r):
        forces = []
        for w in wheels:
            f = w.GetSpindle().GetContactForce()  # rigid ground and obstacles (Bullet contacts)
            fx, fy, fz = f.x, f.y, f.z
            for s in scm if state["scm_forces"] else ():
                try:  # the soil's force on the wheel is a load, not a contact
                    g = w.GetTire().ReportTireForce(s).force
                except (TypeError, AttributeError):  # not reachable through this SWIG build
                    state["scm_forces"] = False
                    break
                fx, fy, fz = fx + g.x, fy + g.y, fz + g.z
            forces.append(round(math.sqrt(fx * fx + fy * fy + fz * fz), 1))
        inputs = sim.driver_inputs
        try:
            gear = vehicle.GetTransmission().GetCurrentGear()
            engine = vehicle.GetEngine().GetMotorSpeed()
        except AttributeError:
            gear, engine = -1, float("nan")
        return [round(t, 3), p.x, p.y, p.z, math.degrees(r.x), math.degrees(r.y), math.degrees(r.z),
                vehicle.GetSpeed(), inputs.m_throttle, inputs.m_steering, inputs.m_braking, gear,
                engine] + forces

    original_advance = vm.advance

    def observed_advance(step):
        t = sim.system.GetChTime()
        p = vehicle.GetPos()
        r = vehicle.GetRot().GetCardanAnglesXYZ()
        roll_deg, pitch_deg = math.degrees(r.x), math.degrees(r.y)
        extremes["roll"] = max(extremes["roll"], abs(roll_deg))
        extremes["pitch"] = max(extremes["pitch"], abs(pitch_deg))
        orig_rules.push(t, (p.x, p.y, p.z))
        vb_rules.push(t, (p.x, p.y, p.z), roll_deg)
        if state["k"] % SAMPLE_EVERY == 0:
            rows.append(sample(t, p, r))
        state["k"] += 1
        state["last"] = (t, p, r)
        if orig_rules.status is not None and vb_rules.status is not None:
            raise StopTrial()
        original_advance(step)

    vm.advance = observed_advance
    ended_by = "harness"
    with redirect_stdout(log):
        try:
            sim.run()
            ended_by = "original"
        except StopTrial:
            pass
    wall_s = time.time() - t0
    t = sim.system.GetChTime()
    p = vehicle.GetPos()
    r = vehicle.GetRot().GetCardanAnglesXYZ()
    if ended_by == "original":  # its goal or its time limit ended the loop before advance
        orig_rules.push(t, (p.x, p.y, p.z))
    final_roll = math.degrees(r.x)
    vb_rules.finish(t, final_roll)
    if not rows or rows[-1][0] != round(t, 3):
        rows.append(sample(t, p, r))
    start, goal_xy = pos["start"], pos["goal"]
    direction = np.array(goal_xy[:2]) - np.array(start[:2])
    progress = float(np.dot(np.array([p.x, p.y]) - np.array(start[:2]), direction)
                     / np.linalg.norm(direction))
    record = {
        "world": args.world, "pair": args.pair, "system": args.system, "seed": args.seed,
        "level": tm.difficulty, "terrain_type": tm.terrain_type, "density": tm.obstacle_density,
        "start": list(start), "goal": list(goal_xy),
        "start_position": [vm.init_loc.x, vm.init_loc.y, vm.init_loc.z],
        "goal_marker": [goal.x, goal.y, goal.z],
        "start_wheel_depth_m": start_depth,  # fl, fr, rl, rr: ground above the wheel's lowest point
        "original_status": orig_rules.status or "undecided",
        "original_time_s": orig_rules.time_s,
        "original_status_with_rollover": with_rollover(orig_rules.status, final_roll),
        "vb_rules_status": vb_rules.status, "vb_rules_time_s": vb_rules.time_s,
        "end_time_s": t, "ended_by": ended_by,
        "final_position": [p.x, p.y, p.z], "final_roll_deg": final_roll,
        "final_pitch_deg": math.degrees(r.y),
        "max_abs_roll_deg": extremes["roll"], "max_abs_pitch_deg": extremes["pitch"],
        "tipped": extremes["roll"] > 45.0,
        "final_goal_distance_planar_m": math.dist((p.x, p.y), goal_xy[:2]),
        "progress_m": progress,
        "wall_s": wall_s, "height_map_s": heights_s,
        "trajectory_columns": COLUMNS, "trajectory_every_steps": SAMPLE_EVERY,
        "contact_forces_include_soil": state["scm_forces"] if scm else None,
        "original_log_tail": log.getvalue()[-600:],
    }
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    name = trial_name(args.world, args.pair, args.system)
    text = io.StringIO()
    writer = csv.writer(text, lineterminator="\n")
    writer.writerow(COLUMNS)
    writer.writerows(rows)
    write_atomic(out / f"{name}_traj.csv", text.getvalue())
    write_atomic(out / f"{name}.json", json.dumps(record, indent=1) + "\n")
    print(f"{name}: original {record['original_status_with_rollover']} "
          f"({record['original_status']} at {orig_rules.time_s}), vb rules {vb_rules.status} "
          f"at {vb_rules.time_s}, progress {progress:.1f} m, wall {wall_s:.0f} s")


# ---------------------------------------------------------------------------------------- batch
def read_tasks(path):
    tasks = []
    for n, line in enumerate(Path(path).read_text().splitlines(), 1):
        fields = line.split("#", 1)[0].split()
        if not fields:
            continue
        if len(fields) not in (2, 3) or not fields[0].isdigit() or not fields[1].isdigit():
            raise SystemExit(f"{path}:{n}: expected 'WORLD PAIR [SYSTEM]', got '{line.strip()}'")
        system = fields[2] if len(fields) == 3 else "pid"
        if system not in SYSTEMS:
            raise SystemExit(f"{path}:{n}: unknown system '{system}' (valid: {', '.join(SYSTEMS)})")
        task = (int(fields[0]), int(fields[1]), system)
        if task not in tasks:  # a trial listed twice runs once
            tasks.append(task)
    return tasks


def run_batch(args):
    tasks = []
    for path in args.tasks:
        tasks += [t for t in read_tasks(path) if t not in tasks]
    out = Path(args.out)
    (out / "logs").mkdir(parents=True, exist_ok=True)
    todo = [t for t in tasks if not (out / f"{trial_name(*t)}.json").exists()]
    print(f"run_original: {len(tasks)} trials, {len(tasks) - len(todo)} already recorded, "
          f"{len(todo)} to run into {out}", flush=True)
    for i, (world, pair, system) in enumerate(todo, 1):
        name = trial_name(world, pair, system)
        cmd = [sys.executable, str(Path(__file__).resolve()), str(world), str(pair), "--system",
               system, "--out", str(out), "--seed", str(args.seed), "--max-time",
               str(args.max_time), "--cache", str(args.cache)]
        t0 = time.time()
        with open(out / "logs" / f"{name}.log", "w") as logf:
            try:
                rc = subprocess.run(cmd, stdout=logf, stderr=subprocess.STDOUT,
                                    timeout=args.trial_timeout).returncode
                why = f"exit code {rc}"
            except subprocess.TimeoutExpired:
                rc, why = -1, f"wall-clock limit of {args.trial_timeout} s"
        error = out / f"{name}_error.json"
        if rc == 0 and (out / f"{name}.json").exists():
            error.unlink(missing_ok=True)
            status = json.loads((out / f"{name}.json").read_text())
            line = f"{status['original_status_with_rollover']} / vb rules {status['vb_rules_status']}"
        else:
            write_atomic(error, json.dumps({"world": world, "pair": pair, "system": system,
                                            "error": why, "log": f"logs/{name}.log"}) + "\n")
            line = f"crashed ({why})"
        print(f"[{i}/{len(todo)}] {name}: {line} ({time.time() - t0:.0f} s wall)", flush=True)


# ----------------------------------------------------------------------------------------- main
def enter_harness_env(cache, script=None):
    """Re-executes `script` (default this one) in the cache's venv with PyChrono on its paths,
    unless already there."""
    if os.environ.get("VB_REFERENCE_INSIDE") == str(cache):
        return
    build = cache / "chrono-build"
    for stamp, how in ((cache / ".built", "scripts/reference/build_chrono.sh"),
                       (cache / ".prepared", "scripts/reference/prepare_original.sh")):
        if not stamp.exists():
            raise SystemExit(f"run_original: {stamp} missing: run {how} --cache {cache} first")
    env = dict(os.environ, VB_REFERENCE_INSIDE=str(cache))
    env["PYTHONPATH"] = os.pathsep.join([str(build / "bin"), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    env["LD_LIBRARY_PATH"] = os.pathsep.join([str(build / "lib"), env.get("LD_LIBRARY_PATH", "")]).rstrip(os.pathsep)
    python = str(cache / "venv/bin/python")
    script = Path(script or __file__).resolve()
    os.execve(python, [python, str(script)] + sys.argv[1:], env)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("world", nargs="?", type=int)
    ap.add_argument("pair", nargs="?", type=int)
    ap.add_argument("--system", default="pid", choices=sorted(SYSTEMS))
    ap.add_argument("--tasks", nargs="+", help="batch: files of 'WORLD PAIR [SYSTEM]' lines")
    ap.add_argument("--out", default="results/reference")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--max-time", type=float, default=60.0)
    ap.add_argument("--trial-timeout", type=float, default=None, help="batch: wall-clock s per trial")
    ap.add_argument("--cache", type=Path, default=default_cache())
    args = ap.parse_args()
    if (args.tasks is None) == (args.world is None or args.pair is None):
        ap.error("give WORLD PAIR, or --tasks FILE")
    args.cache = args.cache.resolve()
    args.out = str(Path(args.out).resolve())
    enter_harness_env(args.cache)
    if args.tasks:
        run_batch(args)
    else:
        run_trial(args)


if __name__ == "__main__":
    main()
