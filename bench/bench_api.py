"""Request latency of the HTTP service for a cache hit and a cache miss, per endpoint (prints figures only).

Starts `uvicorn app.main:app` on a free port (one worker, the README's serve command), then for each case sends
`--misses` distinct requests (each a new cache key: a tiny CG offset or speed step, so the engine really runs)
and `--hits` repeats of one request, over one keep-alive connection, and prints median and p95 wall time as
seen by the client.

    python bench/bench_api.py [--hits 300] [--misses 100] [--redis redis://127.0.0.1:6379/0]
"""

from __future__ import annotations

import argparse
import os
import socket
import statistics
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import httpx

ROOT = Path(__file__).resolve().parents[1]


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_server(port: int, env: dict[str, str]) -> subprocess.Popen:
    proc = subprocess.Popen(
        [sys.executable, "-m", "uvicorn", "app.main:app", "--host", "127.0.0.1", "--port", str(port),
         "--log-level", "warning", "--no-access-log"],
        cwd=ROOT, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )  # fmt: skip
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        try:
            if httpx.get(f"http://127.0.0.1:{port}/healthz", timeout=1).status_code == 200:
                return proc
        except httpx.HTTPError:
            time.sleep(0.1)
    proc.kill()
    raise SystemExit("uvicorn did not start")


BTRAIN = "table16-btrain"

#: name -> (path, body for the i-th distinct request); every i gives a new cache key
CASES: dict[str, tuple[str, Callable[[int], dict[str, Any]]]] = {
    "srt 3d": ("/v1/srt", lambda i: {"vehicle": BTRAIN, "load": {"vertical_offset_m": i * 1e-6}}),
    "srt 3d, rear LLT 0.6, 8 % bank": (
        "/v1/srt",
        lambda i: {
            "vehicle": BTRAIN,
            "road": {"bank_percent": 8},
            "rear_llt_limit": 0.6,
            "load": {"vertical_offset_m": i * 1e-6},
        },
    ),
    "srt 3d with 41-point curves": (
        "/v1/srt",
        lambda i: {"vehicle": BTRAIN, "include_curves": True, "load": {"vertical_offset_m": i * 1e-6}},
    ),
    "srt 2d": ("/v1/srt", lambda i: {"vehicle": BTRAIN, "model": "2d", "load": {"vertical_offset_m": i * 1e-6}}),
    "srt rigid (closed form)": (
        "/v1/srt",
        lambda i: {"vehicle": BTRAIN, "model": "rigid", "load": {"vertical_offset_m": i * 1e-6}},
    ),
    "curve-speed from an SRT request (3d)": (
        "/v1/curve-speed",
        lambda i: {"radius_m": 80, "vehicle": BTRAIN, "load": {"vertical_offset_m": i * 1e-6}},
    ),
    "curve-speed from a given SRT": ("/v1/curve-speed", lambda i: {"radius_m": 80 + i * 1e-6, "srt": 0.3364}),
    "min-radius from an SRT request (3d)": (
        "/v1/min-radius",
        lambda i: {
            "design_speed_kmh": 60,
            "superelevation_percent": 8,
            "vehicle": BTRAIN,
            "load": {"vertical_offset_m": i * 1e-6},
        },
    ),
    "min-radius from a given SRT": (
        "/v1/min-radius",
        lambda i: {"design_speed_kmh": 60 + i * 1e-6, "superelevation_percent": 8, "srt": 0.285},
    ),
}


def timed(client: httpx.Client, path: str, body: dict[str, Any], expect: str) -> float:
    t0 = time.perf_counter()
    r = client.post(path, json=body)
    dt = time.perf_counter() - t0
    if r.status_code != 200 or r.headers.get("x-cache") != expect:
        raise SystemExit(f"{path} {body}: {r.status_code} X-Cache={r.headers.get('x-cache')} {r.text[:200]}")
    return dt


def stats(samples: list[float]) -> tuple[float, float]:
    ordered = sorted(samples)
    p95 = ordered[min(len(ordered) - 1, round(0.95 * (len(ordered) - 1)))]
    return statistics.median(ordered) * 1e3, p95 * 1e3


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--hits", type=int, default=300)
    parser.add_argument("--misses", type=int, default=100)
    parser.add_argument("--redis", help="use the redis backend at this URL (default: in-process memory cache)")
    args = parser.parse_args()

    env = {**os.environ, "ROLLOVER_CACHE_BACKEND": "memory", "ROLLOVER_CACHE_MAX_ENTRIES": "100000"}
    if args.redis:
        env.update(ROLLOVER_CACHE_BACKEND="redis", ROLLOVER_REDIS_URL=args.redis)
    port = free_port()
    proc = start_server(port, env)
    offset = 1 + time.time_ns() % 100_000  # fresh keys even against a Redis that outlives this run
    try:
        with httpx.Client(base_url=f"http://127.0.0.1:{port}", timeout=60) as client:
            print(f"rollover API latency, uvicorn 1 worker, backend={env['ROLLOVER_CACHE_BACKEND']}, "
                  f"{args.misses} misses / {args.hits} hits per case, client-side wall time [ms]")  # fmt: skip
            print(f"{'case':42s} {'miss median':>12s} {'miss p95':>9s} {'hit median':>11s} {'hit p95':>8s}")
            for k, (name, (path, make)) in enumerate(CASES.items()):
                base = offset + k * (args.misses + 2)  # keys of their own: no case reuses another's SRT
                timed(client, path, make(base), "miss")  # warm-up (imports, first solve)
                misses = [timed(client, path, make(base + 1 + i), "miss") for i in range(args.misses)]
                hits = [timed(client, path, make(base), "hit") for _ in range(args.hits)]
                (m50, m95), (h50, h95) = stats(misses), stats(hits)
                print(f"{name:42s} {m50:12.2f} {m95:9.2f} {h50:11.2f} {h95:8.2f}")
    finally:
        proc.terminate()
        proc.wait(timeout=10)


if __name__ == "__main__":
    main()
