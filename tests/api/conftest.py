"""Fixtures of the API tests: app instances with their own settings, a TestClient, a real redis-server."""

from __future__ import annotations

import copy
import os
import shutil
import socket
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from app.main import create_app
from app.settings import Settings

ROOT = Path(__file__).resolve().parents[2]


def free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def make_client(settings: Settings | None = None):
    """A TestClient of a fresh app (its own in-process cache); use it as a context manager (runs the lifespan)."""
    from fastapi.testclient import TestClient

    return TestClient(create_app(settings or Settings(cache_backend="memory")), raise_server_exceptions=False)


@pytest.fixture
def client():
    with make_client() as c:
        yield c


@pytest.fixture(scope="module")
def shared_client():
    """One app for a module's read-mostly tests (saves repeated 3D solves)."""
    with make_client() as c:
        yield c


class RedisServer:
    def __init__(self, binary: str, port: int) -> None:
        self.port = port
        self.url = f"redis://127.0.0.1:{port}/0"
        self.proc = subprocess.Popen(
            [binary, "--port", str(port), "--bind", "127.0.0.1", "--save", "", "--appendonly", "no"],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline:
            try:
                with socket.create_connection(("127.0.0.1", port), timeout=0.2) as s:
                    s.sendall(b"PING\r\n")
                    if s.recv(16).startswith(b"+PONG"):
                        return
            except OSError:
                time.sleep(0.05)
        self.stop()
        raise RuntimeError(f"redis-server did not answer on port {port}")

    def client(self):
        import redis

        return redis.Redis.from_url(self.url)

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=5)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()


def _redis_binary() -> str:
    binary = shutil.which("redis-server")
    if binary is None:
        if os.environ.get("CI"):
            pytest.fail("redis-server is missing in CI: .ci/run must install it (apt-get install -y redis-server)")
        pytest.skip("redis-server binary not found (apt-get install redis-server); CI installs it and runs this")
    return binary


@pytest.fixture
def redis_server() -> Iterator[RedisServer]:
    """A real redis-server on a free port, for one test."""
    server = RedisServer(_redis_binary(), free_port())
    try:
        yield server
    finally:
        server.stop()


def a_spec(tag: object = None, payloads: int = 1) -> dict:
    """A valid builder spec ``{"spec": ...}`` (the schema's example semi-trailer), told apart by its title, with
    ``payloads`` equal deck loads (more payloads make a larger body). A deep copy throughout: a test may change any
    part of it without changing the schema's example, another test's spec or another payload of its own."""
    from app.vehicle_forms.builder_schemas import EXAMPLE_SPEC

    spec = copy.deepcopy(EXAMPLE_SPEC)
    load = spec["payloads"][0]
    spec["payloads"] = [{**load, "mass_kg": load["mass_kg"] / payloads} for _ in range(payloads)]
    if tag is not None:
        spec["title"] = str(tag)
    return {"spec": spec}
