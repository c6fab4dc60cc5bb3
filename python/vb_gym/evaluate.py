"""Evaluate any policy over a task set with vb's episode rules; results in vb_batch's format.

    python -m vb_gym.evaluate TASK_OR_DIR... --system NAME --policy MODULE:FACTORY --out DIR
        [--pairs all|0,3,5-9] [--seeds 0] [--workers 1] [--vehicle hmmwv] [--time-limit 60]
        [--control-period 0.1] [--action speed|direct] [--crops elevation:64:0.1,...]
        [--perception none|mild|moderate|severe|FILE]
    python -m vb_gym.evaluate --index-only --out DIR

``FACTORY(env)`` is called once per worker with its VbEnv and returns the policy: a callable
``policy(obs) -> action``, optionally with ``policy.reset(info)`` called at each episode start.
Trials (task x pair x seed) are run in WORKERS processes (one vb_gym each); each ended trial is
written to DIR/trials/<task>_p<K>_s<seed>_<vehicle>_<system>.json and _traj.csv exactly as vb_run
and vb_batch write them, atomically. A run that is killed resumes: trials with a record are
skipped. Workers die with the evaluation: each asks the kernel for SIGKILL when its parent
dies (Linux PR_SET_PDEATHSIG), and SIGTERM or Ctrl-C end the evaluation at once (exit 128 +
signal), so no worker and no vb_gym outlives a killed run. At the end DIR/index.csv is rebuilt from every record in DIR/trials, so a directory that
also holds vb_batch's baselines shows them side by side in ``vb_report DIR`` (Table I, Fig. 6).
docs/gym.md "Submitting a system".
"""

from __future__ import annotations

import argparse
import concurrent.futures
import ctypes
import importlib
import json
import multiprocessing
import os
import signal
import sys
import time
from pathlib import Path
from typing import Any, Callable

from .config import Crop, EnvConfig, resolve_tasks
from .env import VbEnv


def parse_indices(text: str, flag: str) -> list[int] | None:
    """'all' -> None; '0,3,5-9' -> [0, 3, 5, 6, 7, 8, 9]."""
    if text == "all":
        return None
    out: list[int] = []
    for part in text.split(","):
        try:
            if "-" in part:
                lo, hi = (int(x) for x in part.split("-", 1))
                if lo > hi or lo < 0:
                    raise ValueError
                out += range(lo, hi + 1)
            else:
                value = int(part)
                if value < 0:
                    raise ValueError
                out.append(value)
        except ValueError:
            raise SystemExit(f"vb_gym.evaluate: error: {flag}: bad list {text!r} "
                             "(e.g. all, 0,3,5-9)") from None
    return out


def parse_crops(text: str) -> tuple[Crop, ...]:
    if not text:
        return ()
    crops = []
    for item in text.split(","):
        fields = item.split(":")
        try:
            crops.append(Crop(fields[0], int(fields[1]), float(fields[2])))
        except (IndexError, ValueError):
            raise SystemExit(f"vb_gym.evaluate: error: --crops: bad entry {item!r} "
                             "(LAYER:SIZE_CELLS:RESOLUTION_M)") from None
    return tuple(crops)


def load_factory(spec: str) -> Callable[[VbEnv], Any]:
    module_name, _, attr = spec.partition(":")
    if not module_name or not attr:
        raise SystemExit(f"vb_gym.evaluate: error: --policy: {spec!r} is not MODULE:FACTORY")
    try:
        factory = getattr(importlib.import_module(module_name), attr)
    except (ImportError, AttributeError) as error:
        raise SystemExit(f"vb_gym.evaluate: error: --policy: cannot load {spec!r}: {error}") \
            from None
    if not callable(factory):
        raise SystemExit(f"vb_gym.evaluate: error: --policy: {spec!r} is not callable")
    return factory


def recorded(path: Path) -> bool:
    """A finished record (vb_batch's rule: parses, and not 'crashed')."""
    try:
        return json.loads(path.read_text()).get("status") not in (None, "crashed")
    except (OSError, ValueError):
        return False


_PR_SET_PDEATHSIG = 1   # <linux/prctl.h>


def die_with_parent(parent_pid: int) -> None:
    """Worker initializer: SIGKILL when the evaluation's process dies (even by SIGKILL, which no
    handler sees), and exit at once if it is already gone. The worker's vb_gym then sees its
    stdin close and exits too."""
    if sys.platform.startswith("linux"):
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    if os.getppid() != parent_pid:
        os._exit(1)


def _exit_on_signal(signum: int, _frame: Any) -> None:
    # Not SystemExit: the pool's shutdown would wait for every worker's remaining trials. The
    # workers follow by their parent-death signal; finished trials are on disk (resume).
    print(f"vb_gym.evaluate: interrupted by signal {signum}; run the same command again to "
          "resume", file=sys.stderr, flush=True)
    os._exit(128 + signum)


def run_trials(config: EnvConfig, policy_spec: str, trials: list[tuple[int, int, int]],
               trial_dir: str) -> list[tuple[int, int, int, str, float]]:
    """One worker: its own vb_gym, the policy, trials in order; (task, pair, seed, status,
    sim_time_s) per trial."""
    env = VbEnv(config)
    try:
        policy = load_factory(policy_spec)(env)
        out = []
        for task, pair, seed in trials:
            obs, info = env.reset(options={"task": task, "pair": pair, "trial_seed": seed})
            if hasattr(policy, "reset"):
                policy.reset(info)
            while True:
                obs, _, terminated, truncated, info = env.step(policy(obs))
                if terminated or truncated:
                    break
            env.write_result(trial_dir)
            out.append((task, pair, seed, info["outcome"]["status"],
                        info["outcome"]["sim_time_s"]))
        return out
    finally:
        env.close()


def recorded_tasks(files: list[str], trial_dir: Path) -> list[str]:
    """The task files the records name. A record names its task by its task set path (e.g.
    "tasks/env042.yaml"; older records: an absolute path), looked for beside the results and in
    their parent directories, never in the current directory (vb's rule, io/task_ref.h)."""
    found = set()
    for f in files:
        name = json.loads(Path(f).read_text())["provenance"]["task_file"]
        rec = Path(name)
        if rec.is_absolute() and rec.is_file():
            found.add(str(rec))
            continue
        if rec.is_absolute():
            rec = Path(rec.parent.name) / rec.name
        for d in [trial_dir.resolve(), *trial_dir.resolve().parents]:
            if (d / rec).is_file():
                found.add(str(d / rec))
                break
        else:
            raise SystemExit(f"vb_gym.evaluate: error: the task {name!r} of {f} is not beside "
                             "the results; give the task set as TASK arguments")
    return sorted(found)


def write_index(config: EnvConfig, out_dir: Path) -> int:
    with VbEnv(config) as env:
        return env._core.request({"op": "write_index", "dir": str(out_dir)})["trials"]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m vb_gym.evaluate",
                                 description=__doc__.split("\n")[0])
    ap.add_argument("tasks", nargs="*", help="task files or directories of them")
    ap.add_argument("--system", help="name of the system in the results (letters, digits, _-.)")
    ap.add_argument("--policy", help="MODULE:FACTORY; FACTORY(env) returns the policy")
    ap.add_argument("--out", required=True, help="output directory (vb_batch's layout)")
    ap.add_argument("--pairs", default="all")
    ap.add_argument("--seeds", default="0")
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--vehicle", default="hmmwv")
    ap.add_argument("--soil", default="verti_bench")
    ap.add_argument("--perception", default="none",
                    help="none (ground truth), a preset of data/perception, or a .yaml file")
    ap.add_argument("--time-limit", type=float, default=60.0,
                    help="simulated seconds (60: the benchmark rule; other values for tests)")
    ap.add_argument("--control-period", type=float, default=0.1)
    ap.add_argument("--action", default="speed", choices=["speed", "direct"])
    ap.add_argument("--max-speed", type=float, default=4.0)
    ap.add_argument("--crops", default="elevation:64:0.1", help="LAYER:SIZE:RES,... or ''")
    ap.add_argument("--flatten", action="store_true", help="flat Box observations")
    ap.add_argument("--index-only", action="store_true",
                    help="only rebuild DIR/index.csv from DIR/trials")
    args = ap.parse_args(argv)
    out_dir = Path(args.out).resolve()
    trial_dir = out_dir / "trials"
    if args.index_only:
        files = sorted(str(p) for p in trial_dir.glob("*.json"))
        if not files:
            raise SystemExit(f"vb_gym.evaluate: error: no records in {trial_dir}")
        tasks = resolve_tasks(args.tasks) if args.tasks else recorded_tasks(files, trial_dir)
        n = write_index(EnvConfig(tasks=tasks, crops=()), out_dir)
        print(f"index of {n} trials: {out_dir / 'index.csv'}")
        return 0
    if not args.tasks or not args.system or not args.policy:
        ap.error("TASK..., --system and --policy are required (or --index-only)")
    if args.workers < 1:
        ap.error("--workers must be >= 1")
    load_factory(args.policy)   # fail before starting anything
    config = EnvConfig.from_kwargs(
        tasks=resolve_tasks(args.tasks), vehicle=args.vehicle, soil=args.soil,
        perception=args.perception,
        time_limit_s=args.time_limit, control_period_s=args.control_period,
        action=args.action, max_speed_mps=args.max_speed, crops=parse_crops(args.crops),
        flatten=args.flatten, keep_trajectory=True, system=args.system)
    pairs = parse_indices(args.pairs, "--pairs")
    seeds = parse_indices(args.seeds, "--seeds") or [0]
    with VbEnv(config) as env:   # checks the configuration; names the tasks
        tasks = env.tasks
    # File stems as vb_batch names them (a perception suffix only when not ground truth).
    suffix = "" if args.perception == "none" else f"_perc-{Path(args.perception).stem}"
    todo, done = [], 0
    for ti, task in enumerate(tasks):
        for pair in (pairs if pairs is not None else range(task["pairs"])):
            if pair >= task["pairs"]:
                raise SystemExit(f"vb_gym.evaluate: error: --pairs: {pair} out of range for "
                                 f"{task['file']} ({task['pairs']} pairs)")
            for seed in seeds:
                stem = f"{task['name']}_p{pair}_s{seed}_{args.vehicle}_{args.system}{suffix}"
                if recorded(trial_dir / f"{stem}.json"):
                    done += 1
                else:
                    todo.append((ti, pair, seed))
    print(f"{args.system}: {len(todo)} trials to run, {done} already recorded in {out_dir}",
          flush=True)
    trial_dir.mkdir(parents=True, exist_ok=True)
    t0 = time.monotonic()
    chunks = [todo[w::args.workers] for w in range(args.workers) if todo[w::args.workers]]
    counts: dict[str, int] = {}
    if chunks:
        ctx = multiprocessing.get_context("spawn")
        for sig in (signal.SIGTERM, signal.SIGINT):
            signal.signal(sig, _exit_on_signal)
        with concurrent.futures.ProcessPoolExecutor(len(chunks), mp_context=ctx,
                                                    initializer=die_with_parent,
                                                    initargs=(os.getpid(),)) as pool:
            futures = [pool.submit(run_trials, config, args.policy, c, str(trial_dir))
                       for c in chunks]
            for f in concurrent.futures.as_completed(futures):
                for task, pair, seed, status, sim_s in f.result():
                    counts[status] = counts.get(status, 0) + 1
                    print(f"{tasks[task]['name']} pair {pair} seed {seed}: {status} "
                          f"({sim_s:.2f} s)", flush=True)
    n = write_index(config, out_dir)
    summary = ", ".join(f"{k} {v}" for k, v in sorted(counts.items())) or "nothing new"
    print(f"{summary}; {time.monotonic() - t0:.1f} s wall; index of {n} trials: "
          f"{out_dir / 'index.csv'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
