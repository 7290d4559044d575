"""Fixtures of the job tests: app clients, a real redis-server (tests/api/conftest.py's), job helpers."""

from __future__ import annotations

import time

import numpy as np

from app.settings import Settings
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


def submit(client, operation: str, request: dict, headers=None):
    return client.post("/v1/jobs", json={"operation": operation, "request": request}, headers=headers)


def run(client, operation: str, request: dict, headers=None) -> tuple[str, dict]:
    r = submit(client, operation, request, headers)
    assert r.status_code == 202, r.text
    location = r.headers["location"]
    assert location == f"/v1/jobs/{r.json()['id']}"
    return location, wait_for(client, location, headers=headers)


def job_and_sync(req: dict, accept: str | None, part_size: int, parts: int | None = None):
    """(the job's status, its result, the synchronous answer) of an alignment request run as a job in parts of
    ``part_size`` rows (``parts`` of them, checked; None: more than one) and sent to POST /v1/alignments/assess,
    both with ``accept``."""
    headers = {"accept": accept} if accept else None
    with make_client(Settings(jobs_part_size=part_size)) as c:
        location, status = run(c, "alignments.assess", req)
        assert status["status"] == "done"
        if parts is None:
            assert status["parts"]["total"] > 1
        else:
            assert status["parts"]["total"] == parts
        job = c.get(location + "/result", headers=headers)
        sync = c.post("/v1/alignments/assess", json=req, headers=headers)
    assert job.status_code == sync.status_code == 200
    return status, job, sync
