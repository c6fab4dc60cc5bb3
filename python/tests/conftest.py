"""Shared fixtures: the built vb_gym (VB_GYM_BIN, set by ctest) and small task sets."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
RIGID_TASK = str(REPO / "tasks" / "env000.yaml")     # low, rigid, sparse: PID succeeds on all pairs
RIGID_TASK_2 = str(REPO / "tasks" / "env001.yaml")


def pytest_configure(config: pytest.Config) -> None:
    if not os.environ.get("VB_GYM_BIN"):
        built = REPO / "build" / "tools" / "vb_gym"
        if built.exists():
            os.environ["VB_GYM_BIN"] = str(built)


@pytest.fixture
def vb_gym_bin() -> str:
    path = os.environ.get("VB_GYM_BIN", "")
    assert path and os.access(path, os.X_OK), "VB_GYM_BIN must point to the built vb_gym"
    return path


@pytest.fixture
def vb_run_bin(vb_gym_bin: str) -> str:
    return str(Path(vb_gym_bin).with_name("vb_run"))
