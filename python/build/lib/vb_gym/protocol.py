"""Client side of the vb_gym frame protocol (docs/gym_protocol.md), version 1.

A frame is an 8-byte prefix (header length, payload length: uint32 little-endian), a UTF-8 JSON
header and a payload of raw little-endian arrays described by the header's ``arrays`` list.
:class:`ServerProcess` owns one ``vb_gym`` process: every request gets exactly one reply, every
wait has a deadline, and a dead server raises :class:`ServerCrashed` with its exit code and the
tail of its stderr (never a bare ``EOFError``, never a hang).
"""

from __future__ import annotations

import json
import os
import select
import shutil
import struct
import subprocess
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

PROTOCOL_VERSION = 1
_PREFIX = struct.Struct("<II")
_DTYPES = {"<f4": np.dtype("<f4"), "<f8": np.dtype("<f8")}


class VbGymError(RuntimeError):
    """The server answered a request with an error frame (the server stays usable)."""

    def __init__(self, op: str, kind: str, message: str):
        super().__init__(message)
        self.op = op
        self.kind = kind


class ServerCrashed(RuntimeError):
    """The vb_gym process died or stopped answering; carries its exit code and stderr tail."""

    def __init__(self, message: str, exit_code: int | None, stderr_tail: str):
        detail = f"{message} (exit code {exit_code})"
        if stderr_tail:
            detail += "; its stderr ends with:\n" + stderr_tail
        super().__init__(detail)
        self.exit_code = exit_code
        self.stderr_tail = stderr_tail


def encode_frame(header: dict[str, Any], payload: bytes = b"") -> bytes:
    """One frame: prefix, JSON header (no NaN: the protocol's JSON is strict), payload."""
    text = json.dumps(header, allow_nan=False, separators=(",", ":")).encode("utf-8")
    return _PREFIX.pack(len(text), len(payload)) + text + payload


def decode_arrays(header: dict[str, Any], payload: bytes) -> dict[str, np.ndarray]:
    """The payload's arrays by name, as described by ``header['arrays']`` (copies, writable)."""
    arrays: dict[str, np.ndarray] = {}
    offset = 0
    for spec in header.get("arrays", []):
        dtype = _DTYPES[spec["dtype"]]
        shape = tuple(spec["shape"])
        count = 1
        for n in shape:
            count *= n
        nbytes = count * dtype.itemsize
        if offset + nbytes > len(payload):
            raise ValueError(f"payload too short for array {spec['name']!r}")
        arrays[spec["name"]] = np.frombuffer(payload, dtype, count, offset).reshape(shape).copy()
        offset += nbytes
    return arrays


def find_server_binary() -> str:
    """$VB_GYM_BIN, else the repository's build/tools/vb_gym, else vb_gym on PATH."""
    env = os.environ.get("VB_GYM_BIN")
    if env:
        if not os.access(env, os.X_OK):
            raise FileNotFoundError(f"VB_GYM_BIN={env!r} is not an executable file")
        return env
    repo_build = Path(__file__).resolve().parents[2] / "build" / "tools" / "vb_gym"
    if os.access(repo_build, os.X_OK):
        return str(repo_build)
    on_path = shutil.which("vb_gym")
    if on_path:
        return on_path
    raise FileNotFoundError(
        "vb_gym not found: build it (scripts/build.sh), or set VB_GYM_BIN to its path"
    )


class ServerProcess:
    """One vb_gym process and its pipes. ``close()`` is idempotent; ``with`` closes it."""

    def __init__(self, binary: str | None = None, timeout_s: float = 600.0):
        # Attributes first, so close() (also from __del__) works even if start-up fails.
        self._proc: subprocess.Popen | None = None
        self._stderr_file = None
        self._buffer = bytearray()
        self.timeout_s = float(timeout_s)
        binary = binary or find_server_binary()
        # stderr to a file, never a pipe nobody reads (a full pipe would block the server).
        self._stderr_file = tempfile.TemporaryFile()
        self._proc = subprocess.Popen(
            [binary],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=self._stderr_file,
            bufsize=0,
        )
        self.hello = self.request({"op": "hello", "protocol": PROTOCOL_VERSION})[0]

    @property
    def pid(self) -> int | None:
        return self._proc.pid if self._proc is not None else None

    @property
    def closed(self) -> bool:
        return self._proc is None

    def stderr_tail(self, max_bytes: int = 2000) -> str:
        if self._stderr_file is None:
            return ""
        self._stderr_file.flush()
        self._stderr_file.seek(0, os.SEEK_END)
        size = self._stderr_file.tell()
        self._stderr_file.seek(max(0, size - max_bytes))
        return self._stderr_file.read().decode("utf-8", "replace").strip()

    def _crashed(self, what: str) -> ServerCrashed:
        code = None
        if self._proc is not None:
            try:
                code = self._proc.wait(timeout=5.0)
            except subprocess.TimeoutExpired:
                self._proc.kill()
                code = self._proc.wait()
        tail = self.stderr_tail()
        self._release()
        return ServerCrashed(f"vb_gym {what}", code, tail)

    def send(self, header: dict[str, Any], payload: bytes = b"") -> None:
        if self._proc is None:
            raise RuntimeError("the vb_gym server is closed")
        try:
            self._proc.stdin.write(encode_frame(header, payload))
        except (BrokenPipeError, OSError):
            raise self._crashed("went away before the request could be sent") from None

    def _fill(self, n: int, deadline: float) -> None:
        """Reads until the buffer holds at least n bytes (one read usually brings a whole frame)."""
        fd = self._proc.stdout.fileno()
        while len(self._buffer) < n:
            left = deadline - time.monotonic()
            if left <= 0:
                self._proc.kill()
                raise self._crashed(f"did not answer within {self.timeout_s:g} s (killed)")
            ready, _, _ = select.select([fd], [], [], left)
            if not ready:
                continue
            chunk = os.read(fd, max(65536, n - len(self._buffer)))
            if not chunk:
                raise self._crashed("closed its output (it exited or crashed)")
            self._buffer += chunk

    def receive(self) -> tuple[dict[str, Any], bytes]:
        """The next reply frame (header, payload); raises VbGymError for an error frame."""
        if self._proc is None:
            raise RuntimeError("the vb_gym server is closed")
        deadline = time.monotonic() + self.timeout_s
        self._fill(_PREFIX.size, deadline)
        header_len, payload_len = _PREFIX.unpack_from(self._buffer)
        end = _PREFIX.size + header_len + payload_len
        self._fill(end, deadline)
        buf = self._buffer
        header = json.loads(bytes(buf[_PREFIX.size:_PREFIX.size + header_len]))
        payload = bytes(buf[_PREFIX.size + header_len:end])
        del buf[:end]
        if header.get("type") == "error":
            raise VbGymError(header.get("op", "?"), header.get("kind", "?"), header["message"])
        return header, payload

    def request(self, header: dict[str, Any]) -> tuple[dict[str, Any], dict[str, np.ndarray]]:
        self.send(header)
        reply, payload = self.receive()
        return reply, decode_arrays(reply, payload)

    def _release(self) -> None:
        proc, self._proc = self._proc, None
        if proc is not None:
            for stream in (proc.stdin, proc.stdout):
                try:
                    stream.close()
                except OSError:
                    pass
            if proc.poll() is None:
                try:
                    proc.wait(timeout=5.0)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait()
        if self._stderr_file is not None:
            self._stderr_file.close()
            self._stderr_file = None

    def close(self) -> None:
        """Asks the server to exit (closing stdin also ends it); safe to call twice."""
        if self._proc is not None and self._proc.poll() is None:
            try:
                self.send({"op": "close"})
                self.receive()
            except (ServerCrashed, VbGymError, RuntimeError, OSError):
                pass
        self._release()

    def __enter__(self) -> "ServerProcess":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __del__(self) -> None:
        try:
            self.close()
        except Exception:  # noqa: BLE001 - interpreter shutdown: nothing left to report to
            pass
