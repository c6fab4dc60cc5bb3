"""A trial driven through vb_gym with the PID's commands, computed here in Python from the
protocol's float64 observations, gives the same outcome and the same trajectory bytes as vb_run
on the same task, pair and seed: the protocol adds nothing and loses nothing."""

from __future__ import annotations

import subprocess
from pathlib import Path

from vb_gym.protocol import ServerProcess

from conftest import RIGID_TASK

TIME_LIMIT_S = 6.0


def pid_command(state: dict, steering: float, control_period_s: float) -> tuple[float, dict]:
    """vb's PID baseline (src/controllers/pid_controller.cc), the same IEEE double operations."""
    max_change = 10.0 * control_period_s
    steering = min(max(1.0 * state["heading_error_rad"], steering - max_change),
                   steering + max_change)
    steering = min(max(steering, -1.0), 1.0)
    out = min(max(1.0 * (4.0 - state["forward_speed_mps"]), -1.0), 1.0)
    throttle, braking = (out, 0.0) if out > 0.0 else (0.0, -out)
    return steering, {"op": "step", "throttle": throttle, "steering": steering,
                      "braking": braking}


def stable_json(path: Path) -> list[str]:
    skip = ('"wall_time_s"', '"real_time_factor"', '"host"')
    return [line for line in path.read_text().splitlines() if not any(k in line for k in skip)]


def test_pid_through_the_protocol_matches_vb_run(tmp_path, vb_gym_bin, vb_run_bin):
    pair, seed = 3, 11
    with ServerProcess(vb_gym_bin) as s:
        conf, _ = s.request({"op": "configure", "tasks": [RIGID_TASK], "control_period_s": 0.005,
                             "time_limit_s": TIME_LIMIT_S, "action": "direct"})
        fields = conf["state_fields"]
        reply, arrays = s.request({"op": "reset", "task": 0, "pair": pair, "seed": seed,
                                   "system": "pid"})
        steering = 0.0
        steps = 0
        while not reply["done"]:
            state = dict(zip(fields, arrays["state"].tolist()))
            steering, command = pid_command(state, steering, 0.005)
            reply, arrays = s.request(command)
            steps += 1
        assert steps == round(TIME_LIMIT_S / 0.005)
        written, _ = s.request({"op": "write_result", "dir": str(tmp_path / "gym")})
    run = subprocess.run([vb_run_bin, RIGID_TASK, "--vehicle", "hmmwv", "--pair", str(pair),
                          "--seed", str(seed), "--time-limit", str(TIME_LIMIT_S), "--quiet",
                          "--out", str(tmp_path / "run")], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    gym_traj = Path(written["trajectory"])
    run_traj = tmp_path / "run" / gym_traj.name
    assert gym_traj.name == f"env000_p{pair}_s{seed}_hmmwv_pid_traj.csv"
    gym_bytes, run_bytes = gym_traj.read_bytes(), run_traj.read_bytes()
    assert gym_bytes.count(b"\n") == steps + 2     # header, t = 0, one row per physics step
    assert gym_bytes == run_bytes
    assert stable_json(Path(written["json"])) == stable_json(run_traj.with_name(
        gym_traj.name.replace("_traj.csv", ".json")))
    assert reply["result"]["status"] == "timeout"
    assert reply["result"]["path_length_m"] > 10.0   # it drove
