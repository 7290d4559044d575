"""The two job backends behind one interface (:class:`Backend`): ``inprocess`` (the default) and ``redis``.

* :class:`InProcessBackend`: the store in process memory (bounded by ``ROLLOVER_JOBS_MAX_BYTES``, every key with
  the TTL), parts run by a pool of ``ROLLOVER_JOBS_WORKERS`` threads of the API process (numpy releases the GIL in its
  array work and the event loop keeps answering: ``/healthz`` stays prompt), and a reaper thread. Nothing else to
  run: the README's serve command is enough. A job does not outlive the process.
* :class:`RedisBackend`: the store in Redis and the parts on an RQ queue (:mod:`app.jobs.worker` runs the workers,
  on any machine that reaches the Redis); the API only submits, reads and streams.
"""

from __future__ import annotations

import threading
from concurrent.futures import ThreadPoolExecutor
from typing import Protocol

from app.jobs.kv import MemoryKV, RedisKV
from app.jobs.runner import run_part
from app.jobs.store import JobStore
from app.logs import get_logger
from app.settings import Settings

_log = get_logger("rollover.jobs")


class Backend(Protocol):
    name: str
    store: JobStore

    def dispatch(self, job_id: str, parts: list[tuple[int, int]]) -> None: ...
    def active_count(self) -> int: ...
    def close(self) -> None: ...


def _store(kv, settings: Settings) -> JobStore:
    return JobStore(
        kv, settings.cache_secret_bytes(), lease_s=settings.jobs_lease_s, max_attempts=settings.jobs_max_attempts
    )


class Reaper:
    """A daemon thread that queues again the parts whose worker was lost, every half lease."""

    def __init__(self, backend: Backend, interval_s: float, purge=None) -> None:
        self.backend = backend
        self.interval_s = interval_s
        self.purge = purge
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._loop, name="rollover-job-reaper", daemon=True)

    def start(self) -> None:
        self._thread.start()

    def sweep(self) -> None:
        store = self.backend.store
        for job_id in store.kv.active():
            self.backend.dispatch(job_id, store.reap(job_id))
        if self.purge is not None:
            self.purge()

    def _loop(self) -> None:
        while not self._stop.wait(self.interval_s):
            try:
                self.sweep()
            except Exception as exc:  # e.g. Redis unreachable for a moment: try again next time
                _log.warning("job_reaper_error", error=f"{type(exc).__name__}: {exc}")

    def stop(self) -> None:
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join(timeout=5)


class InProcessBackend:
    name = "inprocess"

    def __init__(self, settings: Settings) -> None:
        self.settings = settings
        self.kv = MemoryKV(settings.jobs_max_bytes)
        self.store = _store(self.kv, settings)
        self._closing = threading.Event()
        self.pool = ThreadPoolExecutor(max_workers=settings.jobs_workers, thread_name_prefix="rollover-job")
        self.reaper = Reaper(self, max(0.2, settings.jobs_lease_s / 2), purge=self.kv.purge)
        self.reaper.start()

    def dispatch(self, job_id: str, parts: list[tuple[int, int]]) -> None:
        for k, attempt in parts:
            self.pool.submit(self._run, job_id, k, attempt)

    def _run(self, job_id: str, k: int, attempt: int) -> None:
        if self._closing.is_set():
            return
        run_part(
            self.store,
            job_id,
            k,
            attempt,
            timeout_s=self.settings.jobs_part_timeout_s,
            should_stop=self._closing.is_set,
        )

    def active_count(self) -> int:
        return len(self.kv.active())

    def close(self) -> None:
        """Stop: queued parts never start, running ones stop at their next chunk (the jobs die with the process)."""
        self._closing.set()
        self.reaper.stop()
        self.pool.shutdown(wait=True, cancel_futures=True)
        self.kv.close()


class RedisBackend:
    name = "redis"

    def __init__(self, settings: Settings, *, reaper: bool = False) -> None:
        from rq import Queue
        from rq.serializers import JSONSerializer

        self.settings = settings
        self.kv = RedisKV(settings.redis_url)
        self.store = _store(self.kv, settings)
        # JSON, never pickle: a part's RQ job holds only (job id, part, attempt)
        self.queue = Queue(settings.jobs_queue, connection=self.kv.redis, serializer=JSONSerializer)
        self.reaper = Reaper(self, max(0.2, settings.jobs_lease_s / 2)) if reaper else None
        if self.reaper is not None:
            self.reaper.start()

    def dispatch(self, job_id: str, parts: list[tuple[int, int]]) -> None:
        for k, attempt in parts:
            self.queue.enqueue(
                "app.jobs.worker.perform_part",
                job_id,
                k,
                attempt,
                job_id=f"{job_id}-{k}-{attempt}",
                # RQ's own limit is a backstop: the part stops itself at ROLLOVER_JOBS_PART_TIMEOUT_S
                job_timeout=int(self.settings.jobs_part_timeout_s) + 60,
                result_ttl=0,
                failure_ttl=self.settings.jobs_result_ttl_s,
                description=f"{job_id} part {k} attempt {attempt}",
            )

    def active_count(self) -> int:
        return len(self.kv.active())

    def close(self) -> None:
        if self.reaper is not None:
            self.reaper.stop()
        self.kv.close()


def make_backend(settings: Settings) -> Backend:
    return RedisBackend(settings) if settings.jobs_backend == "redis" else InProcessBackend(settings)
