"""scripts/original_start_clearance.py: on a uniform slope the wheels' depths under the original's
start rule are the closed form (the height read 0.37 m ahead of the start, + 1 m), on flat ground
every wheel is r - 1 m above it, and a task without pairs is a clear error."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
from PIL import Image

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "scripts" / "original_start_clearance.py"


def _task(tmp_path: Path, slope: float, pairs: bool = True) -> Path:
    x = np.arange(129) - 64.0                      # vertex column c at x = c - 64
    heights = np.tile(slope * (x + 64.0), (129, 1))  # rises towards +x, the same on every row
    hi = float(heights.max()) if slope > 0 else 1.0
    pixels = np.round(heights / hi * 65535.0).astype(np.uint16)
    Image.fromarray(pixels).save(tmp_path / "w.png")
    text = (
        "format: vb-task\nversion: 2\nname: w\nworld:\n  size_m: [128.0, 128.0]\n  scale: 1.0\n"
        f"  height_image: w.png\n  height_range_m: [0.0, {hi}]\n"
        "labels: {elevation: high, terrain: rigid, density: sparse, classes: [rock]}\n"
    )
    if pairs:
        text += "pairs:\n  - start: [60.0, 0.0]\n    goal: [-60.0, 0.0]\n"
    path = tmp_path / "w.yaml"
    path.write_text(text)
    return path


def _depths(task: Path, tmp_path: Path) -> list[float]:
    out = tmp_path / "d.csv"
    subprocess.run([sys.executable, str(SCRIPT), str(task), "--csv", str(out)], check=True,
                   capture_output=True, text=True)
    row = out.read_text().splitlines()[1].split(",")
    return [float(v) for v in row[3:]]


def test_a_uniform_slope_gives_the_closed_form_depths(tmp_path):
    s = 0.4  # the ground rises behind the vehicle (it starts at x = 60 facing -x: downhill)
    # the original reads the height at x = (60.1 + 64.5) * 128/129 - 64 = 59.634 m (high-res
    # pixel 1246 of the 129 m mesh) and puts the reference point 1 m above it
    read_x = (-64.5 + 1246 * 0.1 + 64.5) * 128.0 / 129.0 - 64.0
    rear = s * (61.651 - read_x) - 0.533   # wheel bottom = reference - r = reference - 0.467
    front = s * (58.349 - read_x) - 0.533
    fl, fr, rl, rr = _depths(_task(tmp_path, s), tmp_path)
    assert abs(rl - rear) < 2e-3 and abs(rr - rear) < 2e-3
    assert abs(fl - front) < 2e-3 and abs(fr - front) < 2e-3
    assert rl > 0.25  # the rear wheels start 0.27 m in the ground


def test_flat_ground_leaves_every_wheel_above_it(tmp_path):
    assert all(abs(d + 0.533) < 1e-9 for d in _depths(_task(tmp_path, 0.0), tmp_path))


def test_a_task_without_pairs_is_a_clear_error(tmp_path):
    r = subprocess.run([sys.executable, str(SCRIPT), str(_task(tmp_path, 0.1, pairs=False))],
                       capture_output=True, text=True)
    assert r.returncode != 0
    assert "w.yaml" in r.stderr and "pairs" in r.stderr
