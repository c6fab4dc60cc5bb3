"""scripts/world_spread_effect.py: the logistic fit recovers a known model, worlds that already
have the original's mean and spread are left unchanged by the stretch, and a batch naming a world
the statistics file lacks is a clear error."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "scripts" / "world_spread_effect.py"


def _module():
    spec = importlib.util.spec_from_file_location("world_spread_effect", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_fit_recovers_the_coefficients_of_a_known_logistic_model():
    m = _module()
    rng = np.random.default_rng(7)
    x = rng.uniform(5.0, 45.0, 20_000)
    y = (rng.uniform(size=x.size) < 1.0 / (1.0 + np.exp(-(7.0 - 0.25 * x)))).astype(float)
    b = m.fit_logistic(x, y)
    assert abs(b[0] - 7.0) < 0.35
    assert abs(b[1] + 0.25) < 0.012


def test_worlds_with_the_originals_mean_and_range_are_unchanged_by_the_stretch():
    m = _module()
    worlds = {}
    for level, (mean, lo, hi) in m.ORIGINAL_P95.items():
        # three worlds per level: the original's min, mean and max (their mean is the original's
        # only if the range is symmetric, so centre them on the mean explicitly)
        half = (hi - lo) / 2.0
        for k, v in enumerate((mean - half, mean, mean + half)):
            worlds[f"{level}{k}"] = (level, v)
    pred = m.predictions(np.array([6.8, -0.22]), worlds)
    for level in m.LEVELS:
        on_vb, stretched, _normal, n, moved = pred[level]
        assert n == 3
        assert abs(stretched - on_vb) < 1e-12
        assert abs(moved - on_vb) < 1e-12


def _write_inputs(tmp_path: Path, extra_task: str | None = None):
    worlds = tmp_path / "worlds.csv"
    rows = ["name,elevation,height_std_m,mean_slope_deg,p95_slope_deg,roughness_m,"
            "max_slope_deg,height_range_m"]
    index = ["task,pair,system,status"]
    p95 = {"low": [10.0, 12.0], "mid": [20.0, 23.0], "high": [31.0, 35.0]}
    for level, values in p95.items():
        for k, v in enumerate(values):
            name = f"{level}{k}"
            rows.append(f"{name},{level},0.1,5.0,{v},0.1,30.0,2.0")
            for pair in range(10):
                ok = pair < round(10 / (1.0 + np.exp(-(6.8 - 0.22 * v))))
                index.append(f"{name},{pair},pid,{'success' if ok else 'stuck'}")
    if extra_task:
        index.append(f"{extra_task},0,pid,success")
    worlds.write_text("\n".join(rows) + "\n")
    idx = tmp_path / "index.csv"
    idx.write_text("\n".join(index) + "\n")
    return worlds, idx


def test_the_script_prints_the_table_and_the_shift_estimates(tmp_path):
    worlds, idx = _write_inputs(tmp_path)
    out = subprocess.run([sys.executable, str(SCRIPT), str(worlds), str(idx), "--bootstrap", "20"],
                         capture_output=True, text=True, check=True).stdout
    assert "pid: 60 trials" in out
    assert "| all |" in out
    for label in ("(b) - (a)", "(c) - (a)", "(m) - (a)"):
        assert label in out


def test_a_task_missing_from_the_worlds_file_is_a_clear_error(tmp_path):
    worlds, idx = _write_inputs(tmp_path, extra_task="env999")
    r = subprocess.run([sys.executable, str(SCRIPT), str(worlds), str(idx)],
                       capture_output=True, text=True)
    assert r.returncode != 0
    assert "env999" in r.stderr and "index.csv" in r.stderr
