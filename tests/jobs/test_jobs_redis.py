"""The Redis backend with real ``python -m app.jobs.worker`` processes and a real redis-server: one job across two
workers, a worker killed with SIGKILL mid-job (its part runs again on another worker), values read back from
Redis verified, the TTL on every key.

The redis-server fixture skips without the binary on a developer machine and fails under CI (``CI`` set).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import orjson
import pytest

from app.jobs import op_alignments
from app.jobs.kv import PREFIX, MemoryKV, RedisKV
from app.jobs.store import JobStore
from app.settings import Settings

from .conftest import make_client, random_curves, wait_for

pytestmark = pytest.mark.redis

ROOT = Path(__file__).resolve().parents[2]
SECRET = "a-deployment-secret-for-the-job-tests"
LEASE_S = 2.0
#: 10,000 rows, the synchronous request's limit: the job's result is compared with POST /v1/alignments/assess
REQUEST = {"vehicles": ["table16-btrain", "table23-semitrailer"], "curves": random_curves(5_000, seed=21)}
#: 60,000 rows: a job's size, compared with the synchronous renderer's answer without the request's limit
LARGE_REQUEST = {"vehicles": ["table16-btrain", "table23-semitrailer"], "curves": random_curves(30_000, seed=21)}


def api_settings(url: str, **kw) -> Settings:
    return Settings(
        jobs_backend="redis", redis_url=url, cache_secret=SECRET, jobs_lease_s=LEASE_S, jobs_part_size=500, **kw
    )


def unlimited_answer(request: dict, *, csv: bool = False) -> bytes:
    """What the synchronous endpoint would answer for a request above its size: its own parsing, resolution, solve
    and renderer (:mod:`app.alignments.service`, :mod:`app.alignments.rows`) at a job's limits, in process."""
    from app.alignments.rows import render
    from app.alignments.schemas import MAX_JOB_CURVES, MAX_JOB_ROWS
    from app.alignments.service import resolve_alignment, solve_alignment, validate_request_data
    from app.jobs.op_alignments import AlignmentJobRequest
    from app.vehicles.resolve import resolve_request_given

    req, curves = validate_request_data(request, model=AlignmentJobRequest, max_curves=MAX_JOB_CURVES)
    vr = resolve_request_given(req)
    job = resolve_alignment(vr, curves, Settings(), max_curves=MAX_JOB_CURVES, max_rows=MAX_JOB_ROWS)
    return b"".join(render(solve_alignment(job), csv))


class Worker:
    """``python -m app.jobs.worker`` in its own process group."""

    def __init__(self, url: str, name: str) -> None:
        env = {
            **os.environ,
            "ROLLOVER_JOBS_BACKEND": "redis",
            "ROLLOVER_REDIS_URL": url,
            "ROLLOVER_CACHE_SECRET": SECRET,
            "ROLLOVER_JOBS_LEASE_S": str(LEASE_S),
            "ROLLOVER_LOG_LEVEL": "WARNING",
        }
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "app.jobs.worker", "--name", name],
            cwd=ROOT,
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            start_new_session=True,
        )

    def kill(self) -> None:
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGKILL)
            self.proc.wait()

    def stop(self) -> None:
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGTERM)
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.kill()


@pytest.fixture
def workers(redis_server):
    started: list[Worker] = []

    def start(name: str) -> Worker:
        w = Worker(redis_server.url, name)
        started.append(w)
        return w

    yield start
    for w in started:
        w.stop()


def listening(url: str, n: int, timeout_s: float = 60.0) -> None:
    """Wait until ``n`` workers have registered with RQ (imported and about to take parts: a part is quick, and the
    first worker up would otherwise take them all)."""
    from redis import Redis
    from rq import Worker as RQWorker

    deadline = time.monotonic() + timeout_s
    with Redis.from_url(url) as conn:
        while RQWorker.count(connection=conn) < n:
            assert time.monotonic() < deadline, f"fewer than {n} workers registered after {timeout_s} s"
            time.sleep(0.05)


def parts_of(url: str, job_id: str):
    store = JobStore(RedisKV(url), SECRET.encode(), lease_s=LEASE_S, max_attempts=3)
    return store.view(job_id).parts


def test_head_is_the_first_bytes_of_a_value_in_redis_as_in_memory(redis_server):
    """KV.head (a fragment's layout looked at before a job's result is answered): GETRANGE on Redis, a slice in
    memory; a missing key is None, an empty value is empty."""
    for kv in (RedisKV(redis_server.url), MemoryKV(2**20)):
        kv.set(PREFIX + "test:head", b"0123456789", 60)
        kv.set(PREFIX + "test:empty", b"", 60)
        assert kv.head(PREFIX + "test:head", 4) == b"0123"
        assert kv.head(PREFIX + "test:head", 99) == b"0123456789"
        assert kv.head(PREFIX + "test:head", 0) == b""
        assert kv.head(PREFIX + "test:empty", 4) == b""
        assert kv.head(PREFIX + "test:absent", 4) is None
        kv.delete([PREFIX + "test:head", PREFIX + "test:empty"])


def test_one_job_runs_across_two_worker_processes(redis_server, workers):
    """20 parts taken by two workers; the result is the synchronous answer byte for byte (JSON and CSV)."""
    workers("w1"), workers("w2")
    listening(redis_server.url, 2)
    with make_client(api_settings(redis_server.url)) as c:
        r = c.post("/v1/jobs", json={"operation": "alignments.assess", "request": REQUEST})
        assert r.status_code == 202
        status = wait_for(c, r.headers["location"], timeout_s=240)
        assert status["status"] == "done" and status["parts"]["total"] == 20, status
        job_json = c.get(r.headers["location"] + "/result")
        job_csv = c.get(r.headers["location"] + "/result", headers={"accept": "text/csv"})
        assert job_json.content == c.post("/v1/alignments/assess", json=REQUEST).content
        sync_csv = c.post("/v1/alignments/assess", json=REQUEST, headers={"accept": "text/csv"})
        assert job_csv.content == sync_csv.content
    ran_on = {p.worker for p in parts_of(redis_server.url, status["id"])}
    assert len(ran_on) == 2  # both processes took parts


def test_a_worker_killed_mid_job_has_its_part_run_again_elsewhere(redis_server, workers, monkeypatch):
    """SIGKILL to the only worker while a part runs: its lease expires (2 s here), the second worker's reaper queues
    that part again with the next attempt, and the job ends done with the right answer."""
    monkeypatch.setattr(op_alignments, "CHUNK_ROWS", 1000)  # read at submission (the API is this process)
    first = workers("doomed")
    listening(redis_server.url, 1)
    # parts of 15,000 rows, each solved in 15 chunks of 1,000: a part reports while it runs
    with make_client(api_settings(redis_server.url).model_copy(update={"jobs_part_size": 15_000})) as c:
        body = {"operation": "alignments.assess", "request": LARGE_REQUEST}
        location = c.post("/v1/jobs", json=body).headers["location"]
        deadline = time.monotonic() + 120
        while True:  # wait until a part is being computed (and has reported) on the doomed worker
            s = c.get(location).json()
            if s["parts"]["running"] and 0 < s["progress"] < 1 and s["done"] % 15_000:
                break
            assert time.monotonic() < deadline and s["status"] in ("queued", "running"), s
            time.sleep(0.02)
        first.kill()
        killed_at = time.monotonic()
        workers("rescuer")
        status = wait_for(c, location, timeout_s=240)
        assert status["status"] == "done", status
        assert status["retries"] >= 1
        assert time.monotonic() - killed_at > LEASE_S  # not before the lease ran out
        assert c.get(location + "/result").content == unlimited_answer(LARGE_REQUEST)
    parts = parts_of(redis_server.url, status["id"])
    assert any(p.attempt >= 2 for p in parts)


def test_values_in_redis_are_sealed_verified_and_expire(redis_server, workers):
    """Every key of a finished job has the TTL; a record rewritten by someone without the secret makes the job
    read as failed with the reason (never a 500, never used), and the event is logged."""
    workers("w")
    sweep = {"vehicle": "table16-btrain", "grid": {"bank_percent": [0, 2, 4], "overweight_percent": [0, 10]}}
    with make_client(api_settings(redis_server.url, jobs_result_ttl_s=600)) as c:
        location = c.post("/v1/jobs", json={"operation": "srt.sweep", "request": sweep}).headers["location"]
        status = wait_for(c, location, timeout_s=120)
        assert status["status"] == "done"
        r = redis_server.client()
        keys = r.keys(PREFIX + status["id"] + "*")
        assert len(keys) >= 4 and all(0 < r.ttl(k) <= 600 for k in keys)
        record = r.get(PREFIX + status["id"])
        # the JSON inside the envelope (see app.compute.cache)
        body = record[len(b"ROLLOVER1") + 32 :].partition(b"\0")[2]
        forged = {**orjson.loads(body), "owner": None, "ttl_s": 1}
        r.set(PREFIX + status["id"], record[: len(record) - len(body)] + orjson.dumps(forged))
        body = c.get(location).json()
        assert body["status"] == "failed" and body["error"]["type"] == "urn:rollover:problem:job-state-invalid"
        assert "not sealed by this deployment" in body["error"]["detail"]
        assert c.get(location + "/result").status_code == 409
