"""NEW-16 of the probe at 8ff4def (../shared/reports/reliability_probe_8ff4def.md): every bad
option is a ConfigError naming its key (no OverflowError, no JSON error naming nothing), a closed
VbEnv says so instead of raising AttributeError, and a killed ``vb_gym.evaluate`` leaves no
worker and no vb_gym behind."""

from __future__ import annotations

import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from conftest import RIGID_TASK
from vb_gym import ConfigError, Crop, EnvConfig, VbEnv


@pytest.mark.parametrize("key, value", [
    ("control_period_s", 1e308),          # P02: OverflowError from round(inf)
    ("control_period_s", math.nan),
    ("speed_kp", math.nan),               # P04: "Out of range float values" at configure
    ("max_speed_mps", math.inf),          # P05: passed, then the first step failed
    ("time_limit_s", math.inf),
    ("lookahead_m", -1.0),
    ("replan_period_s", math.nan),
    ("unknown_elevation_m", math.inf),
    ("timeout_s", 0.0),
    ("episode_cache", 0),
    ("episode_cache", 2.5),
    ("flatten", "yes"),
    ("vehicle", 3),
])
def test_every_bad_value_is_a_config_error_naming_its_key(key, value):
    with pytest.raises(ConfigError, match=key):
        EnvConfig(tasks=RIGID_TASK, **{key: value}).validate()


def test_bad_crops_name_the_crops_key():
    for crops in ([Crop("elevation", 64, math.nan)], [{"layer": "elevation", "colour": 1}],
                  [Crop("elevation", 2**40)], [Crop("elevation", 1024, 0.1, f"c{i}") for i in range(70)]):
        with pytest.raises(ConfigError, match="crops"):
            EnvConfig(tasks=RIGID_TASK, crops=crops).validate()


def test_a_closed_env_says_so(vb_gym_bin):
    env = VbEnv(tasks=RIGID_TASK, server_binary=vb_gym_bin)
    env.close()
    env.close()   # twice is fine
    with pytest.raises(RuntimeError, match="VbEnv is closed"):
        env.reset()   # P14: AttributeError 'NoneType' object has no attribute 'tasks'
    with pytest.raises(RuntimeError, match="VbEnv is closed"):
        env.step([0.0, 0.0])


def _descendants(pid: int) -> set[int]:
    """Every process below pid (children's children too), from /proc."""
    parents: dict[int, list[int]] = {}
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            stat = Path(f"/proc/{d}/stat").read_text()
        except OSError:
            continue
        ppid = int(stat[stat.rindex(")") + 2:].split()[1])
        parents.setdefault(ppid, []).append(int(d))
    out, todo = set(), [pid]
    while todo:
        for child in parents.get(todo.pop(), []):
            out.add(child)
            todo.append(child)
    return out


def _alive(pid: int) -> bool:
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat[stat.rindex(")") + 2] != "Z"


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="PR_SET_PDEATHSIG is Linux's")
def test_a_killed_evaluation_leaves_no_workers(tmp_path, vb_gym_bin):
    env = dict(os.environ, VB_GYM_BIN=vb_gym_bin)
    proc = subprocess.Popen(
        [sys.executable, "-m", "vb_gym.evaluate", RIGID_TASK, "--system", "follower",
         "--policy", "vb_gym.policies:heading_follower", "--out", str(tmp_path / "r"),
         "--workers", "2", "--pairs", "0-9", "--time-limit", "60"],
        env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    # Wait until both workers run their vb_gym (4 processes below the evaluation).
    deadline = time.monotonic() + 120
    below: set[int] = set()
    while time.monotonic() < deadline and len(below) < 4:
        time.sleep(0.2)
        below = _descendants(proc.pid)
    assert len(below) >= 4, f"workers did not start: {below}"
    proc.send_signal(signal.SIGKILL)   # no handler can see this one
    proc.wait()
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline and any(_alive(p) for p in below):
        time.sleep(0.2)
    assert not [p for p in below if _alive(p)], "workers or vb_gym outlived the evaluation"
