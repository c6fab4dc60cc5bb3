"""scripts/combine_batches.py: two batches become one index (one header) with every trial file
linked; a trial in both, differing headers and an existing index are clear errors. Also the
sign test of scripts/compare_systems.py against hand-computed values."""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "scripts" / "combine_batches.py"
HEADER = "matrix_index,task,pair,seed,vehicle,system,status"


def _batch(root: Path, name: str, system: str, pairs, header: str = HEADER) -> Path:
    d = root / name
    (d / "trials").mkdir(parents=True)
    rows = [header]
    for i, p in enumerate(pairs):
        rows.append(f"{i},env000,{p},0,hmmwv,{system},success")
        (d / "trials" / f"env000_p{p}_s0_hmmwv_{system}.json").write_text("{}")
    (d / "index.csv").write_text("\n".join(rows) + "\n")
    return d


def _run(*args):
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True, text=True)


def test_two_batches_become_one(tmp_path):
    a = _batch(tmp_path, "a", "eh", [0, 1])
    b = _batch(tmp_path, "b", "pid", [0, 1, 2])
    r = _run(tmp_path / "out", a, b)
    assert r.returncode == 0, r.stderr
    lines = (tmp_path / "out" / "index.csv").read_text().splitlines()
    assert lines[0] == HEADER and len(lines) == 6
    links = sorted(os.listdir(tmp_path / "out" / "trials"))
    assert len(links) == 5 and all(os.path.islink(tmp_path / "out" / "trials" / n) for n in links)
    again = _run(tmp_path / "out", a)
    assert again.returncode != 0 and "already holds an index.csv" in again.stderr


def test_a_trial_in_two_batches_and_differing_headers_are_errors(tmp_path):
    a = _batch(tmp_path, "a", "pid", [0])
    b = _batch(tmp_path, "b", "pid", [0])
    r = _run(tmp_path / "out", a, b)
    assert r.returncode != 0 and "env000/0/0/hmmwv/pid" in r.stderr
    c = _batch(tmp_path, "c", "eh", [0], header=HEADER + ",extra")
    r = _run(tmp_path / "out2", a, c)
    assert r.returncode != 0 and "header differs" in r.stderr
    assert not (tmp_path / "out2" / "index.csv").exists()


def test_sign_test_of_compare_systems():
    spec = importlib.util.spec_from_file_location("compare_systems", REPO / "scripts" / "compare_systems.py")
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)
    assert m.sign_test_p(0, 0) == 1.0
    assert m.sign_test_p(5, 5) == 1.0
    assert abs(m.sign_test_p(0, 5) - 2 / 32) < 1e-15        # 2 * (1/2)^5
    assert abs(m.sign_test_p(9, 1) - 2 * 11 / 1024) < 1e-15  # 2 * (1 + 10) / 2^10
