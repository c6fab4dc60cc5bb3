"""The vb_gym protocol against the real binary: replies, error frames that name the problem, a
server that stays usable after a bad request, broken framing, and a client that goes away."""

from __future__ import annotations

import os
import signal
import struct
import subprocess
import sys
import time

import numpy as np
import pytest

from vb_gym.protocol import ServerProcess, VbGymError, decode_arrays, encode_frame

from conftest import RIGID_TASK


def configure(server: ServerProcess, **extra):
    request = {"op": "configure", "tasks": [RIGID_TASK], "control_period_s": 0.1,
               "crops": [{"layer": "elevation", "size_cells": 8, "resolution_m": 0.5}]}
    request.update(extra)
    return server.request(request)[0]


def test_hello_reports_protocol_version(vb_gym_bin):
    with ServerProcess(vb_gym_bin) as s:
        assert s.hello["type"] == "hello"
        assert s.hello["protocol"] == 1
        with pytest.raises(VbGymError, match="protocol version 2 not supported"):
            s.request({"op": "hello", "protocol": 2})


def test_bad_requests_get_error_frames_and_the_server_stays_usable(vb_gym_bin):
    with ServerProcess(vb_gym_bin) as s:
        with pytest.raises(VbGymError, match="unknown op 'jump'; valid: hello, configure"):
            s.request({"op": "jump"})
        with pytest.raises(VbGymError, match="send configure first"):
            s.request({"op": "reset", "task": 0, "pair": 0})
        with pytest.raises(VbGymError, match="unknown key 'speed'"):
            s.request({"op": "configure", "tasks": [RIGID_TASK], "speed": 3})
        with pytest.raises(VbGymError, match="control_period_s.*whole number of physics steps"):
            s.request({"op": "configure", "tasks": [RIGID_TASK], "control_period_s": 0.0071})
        with pytest.raises(VbGymError, match="unknown vehicle 'tank'"):
            s.request({"op": "configure", "tasks": [RIGID_TASK], "vehicle": "tank"})
        with pytest.raises(VbGymError) as missing:
            s.request({"op": "configure", "tasks": ["/nonexistent/task.yaml"]})
        assert missing.value.kind == "input" and "/nonexistent/task.yaml" in str(missing.value)
        with pytest.raises(VbGymError, match="unknown layer 'lidar'"):
            s.request({"op": "configure", "tasks": [RIGID_TASK], "crops": [{"layer": "lidar"}]})
        reply = configure(s)
        assert reply["type"] == "configured" and reply["tasks"][0]["pairs"] == 10
        with pytest.raises(VbGymError, match="send reset first"):
            s.request({"op": "step", "steering": 0.0, "speed_mps": 1.0})
        with pytest.raises(VbGymError, match=r"key 'pair': 10 out of range \[0, 9\]"):
            s.request({"op": "reset", "task": 0, "pair": 10})
        s.request({"op": "reset", "task": 0, "pair": 1, "seed": 7})
        with pytest.raises(VbGymError, match="missing key 'throttle'"):
            s.request({"op": "step", "steering": 0.0, "braking": 0.0})
        with pytest.raises(VbGymError, match="key 'steering': expected a number"):
            s.request({"op": "step", "throttle": 1, "steering": "left", "braking": 0})
        with pytest.raises(VbGymError, match="still running"):
            s.request({"op": "write_result", "dir": "/tmp"})
        # Raw bytes that are not JSON.
        s._proc.stdin.write(struct.pack("<II", 5, 0) + b"{nope")
        with pytest.raises(VbGymError, match="not valid JSON"):
            s.receive()
        # Still serving the same episode.
        reply, arrays = s.request({"op": "step", "throttle": 0.5, "steering": 0.0, "braking": 0.0})
        assert reply["type"] == "obs" and reply["pair"] == 1 and reply["seed"] == 7
        assert reply["physics_steps"] == 20 and reply["time_s"] == pytest.approx(0.1)


def test_observation_arrays_have_the_announced_layout(vb_gym_bin):
    with ServerProcess(vb_gym_bin) as s:
        conf = configure(s)
        reply, arrays = s.request({"op": "reset", "task": 0, "pair": 0})
        assert list(arrays) == ["state", "wheels", "elevation"]
        assert arrays["state"].dtype == np.float64
        assert arrays["state"].shape == (len(conf["state_fields"]),)
        assert arrays["wheels"].shape == (conf["num_wheels"], 6)
        assert arrays["elevation"].dtype == np.float32 and arrays["elevation"].shape == (8, 8)
        state = dict(zip(conf["state_fields"], arrays["state"]))
        assert state["time_s"] == 0.0
        # The episode starts at the task's start, facing the goal, the goal's distance as stated.
        assert state["goal_distance_m"] == pytest.approx(
            np.hypot(state["goal_x_m"] - state["x_m"], state["goal_y_m"] - state["y_m"]))
        # It faces the goal (the local goal on the A* path may bend around obstacles).
        to_goal = np.arctan2(state["goal_y_m"] - state["y_m"], state["goal_x_m"] - state["x_m"])
        assert abs(np.angle(np.exp(1j * (to_goal - state["yaw_rad"])))) < 0.05
        assert abs(state["heading_error_rad"]) < np.pi / 2


def test_broken_framing_gets_an_error_frame_and_exit_code_2(vb_gym_bin):
    proc = subprocess.Popen([vb_gym_bin], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE)
    out, err = proc.communicate(struct.pack("<II", 0, 0), timeout=30)
    assert proc.returncode == 2
    header_len, payload_len = struct.unpack("<II", out[:8])
    assert b'"kind":"framing"' in out[8:8 + header_len]
    assert b"header length 0" in err


def test_client_closing_its_pipe_ends_the_server(vb_gym_bin):
    proc = subprocess.Popen([vb_gym_bin], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                            stderr=subprocess.DEVNULL)
    proc.stdin.write(encode_frame({"op": "hello"}))
    proc.stdin.flush()
    proc.stdin.close()
    assert proc.wait(timeout=30) == 0


def _process_gone(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/status") as f:
            return any(line.startswith("State:") and "Z" in line.split()[1] for line in f)
    except FileNotFoundError:
        return True


def test_killed_client_ends_the_server(vb_gym_bin):
    """A Python client killed with SIGKILL (no cleanup at all) leaves no vb_gym behind."""
    code = ("import sys, time; from vb_gym.protocol import ServerProcess; "
            f"s = ServerProcess({vb_gym_bin!r}); print(s.pid, flush=True); time.sleep(60)")
    client = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    server_pid = int(client.stdout.readline())
    assert not _process_gone(server_pid)
    client.send_signal(signal.SIGKILL)
    client.wait(timeout=30)
    deadline = time.monotonic() + 30
    while not _process_gone(server_pid) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert _process_gone(server_pid)


def test_decode_arrays_rejects_a_short_payload():
    header = {"arrays": [{"name": "a", "dtype": "<f4", "shape": [4]}]}
    assert decode_arrays(header, np.arange(4, dtype="<f4").tobytes())["a"].tolist() == [0, 1, 2, 3]
    with pytest.raises(ValueError, match="too short for array 'a'"):
        decode_arrays(header, b"\0" * 12)
