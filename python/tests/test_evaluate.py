"""The evaluation entry point: a Python policy evaluated over tasks with vb's rules lands in
vb_batch's directory format beside vb_batch's PID results, and vb_report's Table I lists both;
a re-run resumes (only missing trials run)."""

from __future__ import annotations

import csv
import subprocess
import sys
from pathlib import Path

from conftest import RIGID_TASK

ARGS = ["--pairs", "0,1", "--time-limit", "8"]


def evaluate(out: Path, *extra: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "vb_gym.evaluate", RIGID_TASK, "--system", "follower",
         "--policy", "vb_gym.policies:heading_follower", "--out", str(out), "--workers", "2",
         *ARGS, *extra], capture_output=True, text=True, timeout=600)


def test_external_policy_appears_in_table1_beside_pid(tmp_path, vb_gym_bin):
    tools = Path(vb_gym_bin).parent
    out = tmp_path / "results"
    batch = subprocess.run([str(tools / "vb_batch"), RIGID_TASK, "--jobs", "2", "--quiet",
                            "--out", str(out), *ARGS], capture_output=True, text=True)
    assert batch.returncode == 0, batch.stderr
    first = evaluate(out)
    assert first.returncode == 0, first.stderr
    assert "follower: 2 trials to run, 0 already recorded" in first.stdout
    assert "index of 4 trials" in first.stdout
    records = sorted(p.name for p in (out / "trials").glob("*follower*"))
    assert records == ["env000_p0_s0_hmmwv_follower.json", "env000_p0_s0_hmmwv_follower_traj.csv",
                       "env000_p1_s0_hmmwv_follower.json", "env000_p1_s0_hmmwv_follower_traj.csv"]
    report = subprocess.run([str(tools / "vb_report"), str(out)], capture_output=True, text=True)
    assert report.returncode == 0, report.stderr
    with open(out / "report" / "table1.csv") as f:
        table = list(csv.DictReader(f))
    systems = {row.get("system") for row in table}
    assert {"pid/hmmwv", "follower/hmmwv"} <= systems, table
    # The index alone, rebuilt from the records: their tasks are found by the task set path
    # they record (tasks/env000.yaml, beside the results' parents) or given as TASK arguments.
    only = subprocess.run([sys.executable, "-m", "vb_gym.evaluate", "--index-only", "--out",
                           str(out), RIGID_TASK], capture_output=True, text=True, timeout=600)
    assert only.returncode == 0, only.stderr
    assert "index of 4 trials" in only.stdout
    # Killed or not, a re-run only runs what has no record.
    (out / "trials" / "env000_p1_s0_hmmwv_follower.json").unlink()
    again = evaluate(out)
    assert again.returncode == 0, again.stderr
    assert "follower: 1 trials to run, 1 already recorded" in again.stdout
    assert (out / "trials" / "env000_p1_s0_hmmwv_follower.json").exists()


def test_bad_policy_is_a_clear_error(tmp_path):
    run = subprocess.run([sys.executable, "-m", "vb_gym.evaluate", RIGID_TASK, "--system", "x",
                          "--policy", "no_such_module:f", "--out", str(tmp_path)],
                         capture_output=True, text=True)
    assert run.returncode != 0
    assert "--policy: cannot load 'no_such_module:f'" in run.stderr
