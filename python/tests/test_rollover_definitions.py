"""scripts/rollover_definitions.py over a synthetic batch: each rule counts the failures it
should, per elevation level, and bad input is a clear error."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "scripts" / "rollover_definitions.py"


def _trial(task: str, pair: int, status: str, roll_max: float, pitch_max: float,
           tipped: bool) -> dict:
    return {"task": task, "pair": pair, "seed": 0, "vehicle": "hmmwv", "system": "pid",
            "status": status, "tipped": tipped,
            "abs_roll_deg": {"mean": 1.0, "var": 0.0, "max": roll_max},
            "abs_pitch_deg": {"mean": 1.0, "var": 0.0, "max": pitch_max}}


def _batch(tmp_path: Path) -> Path:
    run = tmp_path / "run"
    (run / "trials").mkdir(parents=True)
    trials = [
        ("env000", 0, "low", _trial("env000", 0, "success", 35.0, 5.0, False)),   # success: never
        ("env000", 1, "low", _trial("env000", 1, "stuck", 10.0, 35.0, False)),    # pitch only
        ("env008", 0, "high", _trial("env008", 0, "rollover", 90.0, 20.0, True)),  # all rules
        ("env008", 1, "high", _trial("env008", 1, "stuck", 40.0, 10.0, False)),   # rolled, fell back
        ("env008", 2, "high", _trial("env008", 2, "stuck", 50.0, 10.0, True)),    # tipped, fell back
    ]
    rows = ["task,pair,seed,vehicle,system,elevation"]
    for task, pair, level, record in trials:
        rows.append(f"{task},{pair},0,hmmwv,pid,{level}")
        (run / "trials" / f"{task}_p{pair}_s0_hmmwv_pid.json").write_text(json.dumps(record))
    (run / "index.csv").write_text("\n".join(rows) + "\n")
    return run


def test_counts_each_rule_per_level(tmp_path: Path) -> None:
    out = subprocess.run([sys.executable, str(SCRIPT), str(_batch(tmp_path))],
                         capture_output=True, text=True, check=True).stdout
    lines = {line[:34].strip(): line[34:] for line in out.splitlines()[2:]}

    def counts(rule: str) -> list[int]:  # columns low, high, all: "count (pct%)"
        return [int(n) for n in re.findall(r"(\d+) \(\s*[\d.]+%\)", lines[rule])]
    assert counts("success") == [1, 0, 1]
    assert counts("end |roll| > 30 (vb, the spec)") == [0, 1, 1]
    assert counts("ever |roll| > 30") == [0, 3, 3]
    assert counts("ever |roll| > 45 (tipped)") == [0, 2, 2]
    assert counts("ever |roll| or |pitch| > 30") == [1, 3, 4]


def test_a_directory_without_an_index_is_an_error(tmp_path: Path) -> None:
    r = subprocess.run([sys.executable, str(SCRIPT), str(tmp_path)], capture_output=True,
                       text=True)
    assert r.returncode != 0
    assert "index.csv" in r.stderr
