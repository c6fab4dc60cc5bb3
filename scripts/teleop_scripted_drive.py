#!/usr/bin/env python3
"""A scripted driver for vb_view teleop (docs/viewer.md "Teleoperation", docs/datasets.md
"Teleoperated demonstrations"): starts `vb_view teleop`, connects to its WebSocket as the page
does, and drives with keys held on a timeline, turned into commands exactly as the page turns
held keys into commands (web/viewer/js/teleop.js: every 50 ms the throttle moves towards 1 at
2/s while W is held, the brake at 4/s while S is held, the steering at 1.5/s while A or D is held,
and back at the same rates; `command T S B` with three decimals, sent when it changed). The
server steps the drive at real time and records it as a person's drive would be recorded.

Python standard library only. Used to make test/data/teleop/ (scripts/make_teleop_recording.sh):

    scripts/teleop_scripted_drive.py --vb-view build/tools/vb_view --task TASK \
        --out DIR --operator NAME DRIVE [DRIVE ...]

DRIVE is a timeline `KEY@FROM-TO,KEY@FROM-TO,...,stop@T` in seconds of wall time since the
drive's start (keys: W A S D); without `stop@T` the drive runs until the episode ends it (goal,
rollover, stuck, out of bounds, time limit).
"""

from __future__ import annotations

import argparse
import base64
import json
import os
import socket
import struct
import subprocess
import sys
import time

THROTTLE_RATE = 2.0
BRAKE_RATE = 4.0
STEER_RATE = 1.5
SEND_PERIOD_S = 0.05


def approach(value: float, target: float, rate: float, dt: float) -> float:
    step = rate * dt
    if abs(target - value) <= step:
        return target
    return value + (step if target > value else -step)


class WebSocket:
    """A minimal RFC 6455 client: masked text frames out, unfragmented frames in."""

    def __init__(self, port: int) -> None:
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=10)
        key = base64.b64encode(os.urandom(16)).decode()
        self.sock.sendall((f"GET /ws HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\n"
                           f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\n"
                           "Sec-WebSocket-Version: 13\r\n\r\n").encode())
        head = b""
        while b"\r\n\r\n" not in head:
            chunk = self.sock.recv(1)
            if not chunk:
                raise RuntimeError("vb_view closed the connection during the handshake")
            head += chunk
        if b" 101 " not in head.split(b"\r\n", 1)[0]:
            raise RuntimeError(f"WebSocket handshake refused: {head!r}")
        self.buffer = b""

    def send(self, text: str) -> None:
        payload = text.encode()
        mask = os.urandom(4)
        header = bytes([0x81])
        n = len(payload)
        header += bytes([0x80 | n]) if n < 126 else bytes([0x80 | 126]) + struct.pack(">H", n)
        masked = bytes(b ^ mask[i % 4] for i, b in enumerate(payload))
        self.sock.sendall(header + mask + masked)

    def poll(self) -> list[str]:
        """The complete text frames received so far (non-blocking)."""
        self.sock.setblocking(False)
        try:
            while True:
                chunk = self.sock.recv(65536)
                if not chunk:
                    break
                self.buffer += chunk
        except BlockingIOError:
            pass
        finally:
            self.sock.setblocking(True)
        frames = []
        while len(self.buffer) >= 2:
            n = self.buffer[1] & 0x7F
            at = 2
            if n == 126:
                if len(self.buffer) < 4:
                    break
                n = struct.unpack(">H", self.buffer[2:4])[0]
                at = 4
            elif n == 127:
                if len(self.buffer) < 10:
                    break
                n = struct.unpack(">Q", self.buffer[2:10])[0]
                at = 10
            if len(self.buffer) < at + n:
                break
            opcode = self.buffer[0] & 0x0F
            if opcode == 0x1:
                frames.append(self.buffer[at:at + n].decode())
            self.buffer = self.buffer[at + n:]
        return frames


def parse_drive(text: str) -> tuple[list[tuple[str, float, float]], float | None]:
    keys, stop = [], None
    for part in text.split(","):
        name, _, span = part.partition("@")
        if name == "stop":
            stop = float(span)
            continue
        if name.upper() not in "WASD" or len(name) != 1:
            raise SystemExit(f"teleop_scripted_drive: unknown key '{name}' in '{text}'")
        a, _, b = span.partition("-")
        keys.append((name.upper(), float(a), float(b)))
    return keys, stop


def drive(ws: WebSocket, keys: list[tuple[str, float, float]], stop: float | None) -> dict:
    ws.send("start")
    t0 = time.monotonic()
    command = {"throttle": 0.0, "steering": 0.0, "braking": 0.0}
    sent = "command 0.000 0.000 0.000"   # the session starts with a zero command
    last = t0
    stopped = False
    while True:
        now = time.monotonic()
        t = now - t0
        dt = min(0.2, now - last)
        last = now
        held = {k for k, a, b in keys if a <= t < b}
        command["throttle"] = approach(command["throttle"], 1.0 if "W" in held else 0.0,
                                       THROTTLE_RATE, dt)
        command["braking"] = approach(command["braking"], 1.0 if "S" in held else 0.0,
                                      BRAKE_RATE, dt)
        steer_target = (1.0 if "A" in held else 0.0) - (1.0 if "D" in held else 0.0)
        command["steering"] = approach(command["steering"], steer_target, STEER_RATE, dt)
        text = (f"command {command['throttle']:.3f} {command['steering']:.3f} "
                f"{command['braking']:.3f}")
        if text != sent:
            ws.send(text)
            sent = text
        if stop is not None and t >= stop and not stopped:
            ws.send("stop")
            stopped = True
        for frame in ws.poll():
            m = json.loads(frame)
            if m.get("type") == "recorded":
                return m
            if m.get("type") == "error":
                raise RuntimeError(f"vb_view refused a message: {m['message']}")
        if t > 120:
            raise RuntimeError("the drive did not end within 120 s")
        time.sleep(max(0.0, SEND_PERIOD_S - (time.monotonic() - now)))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--vb-view", required=True)
    ap.add_argument("--task", required=True)
    ap.add_argument("--vehicle", default="hmmwv")
    ap.add_argument("--pair", default="0")
    ap.add_argument("--seed", default="0")
    ap.add_argument("--operator", default="scripted")
    ap.add_argument("--out", required=True)
    ap.add_argument("drives", nargs="+")
    args = ap.parse_args()
    proc = subprocess.Popen([args.vb_view, "teleop", args.task, "--vehicle", args.vehicle,
                             "--pair", args.pair, "--seed", args.seed, "--port", "0",
                             "--operator", args.operator, "--out", args.out,
                             "--exit-after", str(len(args.drives))],
                            stdout=subprocess.PIPE, text=True)
    try:
        line = proc.stdout.readline()
        if "serving http://127.0.0.1:" not in line:
            raise RuntimeError(f"vb_view did not start: {line!r}")
        port = int(line.split("127.0.0.1:")[1].split("/")[0])
        ws = WebSocket(port)
        for d in args.drives:
            keys, stop = parse_drive(d)
            m = drive(ws, keys, stop)
            print(f"{m['result']}: {m['status']}", flush=True)
        code = proc.wait(timeout=30)
        return code
    finally:
        if proc.poll() is None:
            proc.terminate()
            proc.wait()


if __name__ == "__main__":
    sys.exit(main())
