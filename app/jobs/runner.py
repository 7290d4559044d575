"""Running one part of a job, the same in every worker (a thread of the embedded backend, an RQ worker process).

:func:`run_part` claims the part for its attempt (:meth:`~app.jobs.store.JobStore.begin_part`), runs the
operation's ``run_part`` with a :class:`PartRun` (its fragments compressed as they come, its progress reported at
each chunk, which is also where a cancelled job or a superseded attempt stops), then stores the fragments and marks
the part done. An error fails the whole job with a problem object (the synchronous endpoint would have refused the
whole request): nothing is retried but a part whose worker was lost (:meth:`~app.jobs.store.JobStore.reap`).
"""

from __future__ import annotations

import time
import zlib
from collections.abc import Callable
from typing import Any

from app.jobs.columns import ColumnsError
from app.jobs.kv import StorageFull
from app.jobs.operations import OPERATIONS
from app.jobs.store import JobRecord, JobStore, Stopped, problem
from app.logs import get_logger
from app.metrics import JOB_PART_SECONDS
from engine import RolloverError

_log = get_logger("rollover.jobs")
#: zlib level of the fragments: 1 compresses the rows 5-8x at a few hundred MB/s
COMPRESSION_LEVEL = 1


class PartTimeout(Exception):
    pass


class PartRun:
    """The :class:`~app.jobs.base.PartContext` of one attempt of one part."""

    def __init__(
        self,
        store: JobStore,
        record: JobRecord,
        k: int,
        attempt: int,
        timeout_s: float,
        should_stop: Callable[[], bool] = lambda: False,
        *,
        compress: bool = True,
    ) -> None:
        self.store, self.record, self.k, self.attempt = store, record, k, attempt
        self.compress = compress
        self.deadline = time.monotonic() + timeout_s
        self.timeout_s = timeout_s
        self.should_stop = should_stop
        self._encoders: dict[tuple[str, int], Any] = {}
        self._out: dict[tuple[str, int], list[bytes]] = {}

    def write(self, fmt: str, section: int, data: bytes) -> None:
        key = (fmt, section)
        if not self.compress:
            self._out.setdefault(key, []).append(data)
            return
        if key not in self._encoders:
            self._encoders[key] = zlib.compressobj(COMPRESSION_LEVEL)
            self._out[key] = []
        self._out[key].append(self._encoders[key].compress(data))

    def progress(self, done_units: int) -> None:
        if self.should_stop():
            raise Stopped("shutdown")
        if time.monotonic() > self.deadline:
            raise PartTimeout()
        self.store.heartbeat(self.record.id, self.k, self.attempt, done_units, self.record.ttl_s)

    def fragments(self) -> dict[tuple[str, int], bytes]:
        if not self.compress:
            return {key: b"".join(pieces) for key, pieces in self._out.items()}
        return {key: b"".join([*self._out[key], enc.flush()]) for key, enc in self._encoders.items()}


def run_part(
    store: JobStore,
    job_id: str,
    k: int,
    attempt: int,
    *,
    timeout_s: float,
    should_stop: Callable[[], bool] | None = None,
) -> None:
    """Run part ``k`` of ``job_id`` for ``attempt`` (nothing when it is not queued for that attempt)."""
    claimed = store.begin_part(job_id, k, attempt)
    if claimed is None:
        return
    record, data = claimed
    op = OPERATIONS.get(record.operation)
    if op is None:
        store.fail(job_id, record, problem("unknown-operation", "Unknown operation", f"{record.operation!r}"))
        return
    compress = op.stored is None
    run = PartRun(store, record, k, attempt, timeout_s, should_stop or (lambda: False), compress=compress)
    started = time.perf_counter()
    log = _log.bind(job=job_id, part=k, attempt=attempt, operation=op.name)
    try:
        meta = op.run_part(record.shared, data, run)
        seconds = time.perf_counter() - started
        complete = store.finish_part(job_id, record, k, attempt, run.fragments(), meta, seconds, compressed=compress)
    except Stopped as exc:
        log.info("job_part_stopped", reason=str(exc))
        return
    except PartTimeout:
        detail = f"part {k} ran longer than ROLLOVER_JOBS_PART_TIMEOUT_S ({run.timeout_s:g} s)"
        store.fail(job_id, record, problem("job-part-timeout", "A part of the job took too long", detail, 500))
        return
    except StorageFull as exc:
        store.fail(job_id, record, problem("jobs-storage-full", "The job store is full", str(exc), 507))
        return
    except ColumnsError as exc:  # a stored input that verified but does not read: an integrity failure, handled
        log.warning("job_part_integrity_failure", reason=f"{type(exc).__name__}: {exc}")
        detail = f"part {k}: its stored input cannot be used: {exc}"
        store.fail(job_id, record, problem("job-state-invalid", "Invalid job state", detail))
        return
    except RolloverError as exc:  # refused for the whole request at submission: this is a part-level surprise
        detail = f"part {k}: {exc}"
        store.fail(job_id, record, problem("engine-refused", "The engine refused a part of the job", detail))
        return
    except Exception as exc:  # a bug or a stored input that does not parse: the job fails with the reason, logged
        log.exception("job_part_error")
        detail = f"part {k} failed: {type(exc).__name__}: {exc}"
        store.fail(job_id, record, problem("internal-error", "A part of the job failed", detail, 500))
        return
    JOB_PART_SECONDS.labels(op.name).observe(seconds)
    log.info("job_part_done", seconds=round(seconds, 3), complete=complete)
