"""The job worker of the Redis backend: ``python -m app.jobs.worker``, on any machine that reaches the Redis.

It reads the same ``ROLLOVER_`` settings as the API (``ROLLOVER_REDIS_URL``, ``ROLLOVER_CACHE_SECRET`` -- the same
secret: every stored value is sealed with it --, ``ROLLOVER_JOBS_QUEUE``, ``ROLLOVER_JOBS_LEASE_S``, ...) and runs
an RQ ``SimpleWorker`` on the jobs queue: one part at a time, in this process (run one worker per core). A reaper
thread queues again the parts whose worker stopped reporting for ``ROLLOVER_JOBS_LEASE_S`` (see
:meth:`app.jobs.store.JobStore.reap`).

    python -m app.jobs.worker [--burst] [--name NAME] [--metrics-port PORT]

``--burst`` stops when the queue is empty; ``--metrics-port`` serves this worker's Prometheus metrics
(``rollover_job_part_seconds``, ``rollover_jobs_total``, ``rollover_solve_seconds``...) on that port.
"""

from __future__ import annotations

import argparse
import logging

from app.compute import solvers
from app.jobs.backends import RedisBackend
from app.jobs.runner import run_part
from app.logs import configure_logging, get_logger
from app.settings import Settings, get_settings

#: this process's backend: the worker's (with its reaper), or one made from the environment on first use
_BACKEND: RedisBackend | None = None


def perform_part(job_id: str, part: int, attempt: int) -> None:
    """The RQ job of one part of one job (RQ imports it by name and calls it with the job's arguments)."""
    global _BACKEND
    if _BACKEND is None:
        _BACKEND = RedisBackend(get_settings())
        solvers.configure(_BACKEND.settings.solve_threads)
    backend = _BACKEND
    run_part(backend.store, job_id, part, attempt, timeout_s=backend.settings.jobs_part_timeout_s)


def main(argv: list[str] | None = None, settings: Settings | None = None) -> None:
    parser = argparse.ArgumentParser(prog="python -m app.jobs.worker", description=__doc__.split("\n\n")[0])
    parser.add_argument("--burst", action="store_true", help="stop when the queue is empty")
    parser.add_argument("--name", default=None, help="the worker's name in RQ (default: host and pid)")
    parser.add_argument("--metrics-port", type=int, default=None, help="serve Prometheus metrics on this port")
    parser.add_argument("--metrics-addr", default="127.0.0.1", help="address of the metrics server")
    args = parser.parse_args(argv)
    settings = settings or get_settings()
    configure_logging(settings.log_level)
    solvers.configure(settings.solve_threads)
    from rq import SimpleWorker
    from rq.serializers import JSONSerializer

    import engine.road  # noqa: F401  (warm: the first part should not pay the imports)

    global _BACKEND
    backend = _BACKEND = RedisBackend(settings, reaper=True)
    if args.metrics_port is not None:
        from prometheus_client import start_http_server

        start_http_server(args.metrics_port, addr=args.metrics_addr)
    log = get_logger("rollover.jobs")
    log.info("job_worker_start", queue=settings.jobs_queue, lease_s=settings.jobs_lease_s, burst=args.burst)
    worker = SimpleWorker([backend.queue], connection=backend.kv.redis, serializer=JSONSerializer, name=args.name)
    try:
        worker.work(burst=args.burst, logging_level=logging.getLevelName(settings.log_level.upper()))
    finally:
        backend.close()


if __name__ == "__main__":
    main()
