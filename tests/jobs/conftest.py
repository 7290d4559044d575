"""Fixtures of the job tests: app clients, a real redis-server (tests/api/conftest.py's), job helpers."""

from __future__ import annotations

import time

import numpy as np

from tests.api.conftest import make_client, redis_server  # noqa: F401  (fixture)

TERMINAL = ("done", "failed", "cancelled")


def wait_for(client, location: str, statuses=TERMINAL, timeout_s: float = 120.0, headers=None) -> dict:
    """Poll a job until its status is one of ``statuses`` (fails after ``timeout_s``)."""
    deadline = time.monotonic() + timeout_s
    while True:
        body = client.get(location, headers=headers).json()
        if body["status"] in statuses:
            return body
        assert time.monotonic() < deadline, f"job still {body['status']} after {timeout_s} s: {body}"
        time.sleep(0.05)


def random_curves(n: int, seed: int = 1, pairs: int | None = None) -> list[dict]:
    """``n`` curves with random radius, superelevation, grade and posted speed (fixed seed); with ``pairs``, the
    superelevation/grade pairs are drawn from that many distinct ones (so parts share pairs)."""
    rng = np.random.default_rng(seed)
    e = np.round(rng.uniform(-2, 10, n), 1)
    g = np.round(rng.uniform(-6, 6, n), 1)
    if pairs is not None:
        pick = rng.integers(0, pairs, n)
        e, g = np.round(rng.uniform(-2, 10, pairs), 1)[pick], np.round(rng.uniform(-6, 6, pairs), 1)[pick]
    return [
        {
            "id": f"C{i}",
            "radius_m": float(np.round(rng.uniform(40, 900), 1)),
            "superelevation_percent": float(e[i]),
            "grade_percent": float(g[i]),
            "posted_speed_kmh": float(rng.choice([40, 60, 80, 100])),
        }
        for i in range(n)
    ]
