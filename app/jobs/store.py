"""The job store: jobs, their parts and their results over a key-value layer (:mod:`app.jobs.kv`), the same logic for
the embedded and the Redis backends.

Keys (``rollover:job:<id>`` + suffix), each value sealed with the deployment's HMAC
(:func:`app.compute.cache.seal`, over the key, a media type and the body) and verified when read back
(:func:`app.compute.cache.unseal`), then parsed with a pydantic model: a value that does not verify or parse is never
used, the job it belongs to is reported ``failed`` with the reason, and the event is logged (``job_entry_rejected``).

==========================  ====================================================================================
suffix                      value
==========================  ====================================================================================
(none)                      :class:`JobRecord`: operation, owner, created_at, the self-contained shared inputs, the
                            parts' sizes (written once, at submission)
``:in:<k>``                 part k's own inputs (bytes the operation packed; e.g. its curves)
``:part:<k>``               :class:`PartState`: status, attempt, units done, lease (``heartbeat_at``), its metadata
                            when done (written only through :meth:`KV.update`, fenced by the attempt)
``:stop``                   :class:`Stop`: the job was cancelled, or failed (with the problem)
``:out:<k>:<a>:<fmt>:<s>``  result fragment of part k, attempt a, format, section (e.g. vehicle): zlib-compressed
                            rendered bytes, or the part's result columns (format ``columns``, kept raw)
==========================  ====================================================================================

**Leases.** A running part reports at every chunk (``heartbeat_at``, ``done_units``). :meth:`JobStore.reap` finds
running parts that have not reported for ``lease_s`` (their worker died: SIGKILL, OOM, a lost machine) and queues
them again with the next attempt number, or fails the job after ``max_attempts``. The attempt fences the old run: a
worker that was only slow finds at its next report that its attempt is no longer the part's and stops, and its
writes are never read (the fragments are keyed by attempt, the done state is set only for the current attempt).
"""

from __future__ import annotations

import os
import secrets
import socket
import time
import zlib
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from app.compute.cache import envelope_size, peek, seal, unseal
from app.jobs.kv import KV, PREFIX
from app.logs import get_logger
from app.metrics import JOB_PART_RETRIES, JOBS

JOB_ID_PREFIX = "job_"
RECORD_TYPE = "application/vnd.rollover.job+json"
STATE_TYPE = "application/vnd.rollover.job-part+json"
STOP_TYPE = "application/vnd.rollover.job-stop+json"
INPUT_TYPE = "application/vnd.rollover.job-input"
FRAGMENT_TYPE = "application/vnd.rollover.job-fragment+zlib"
#: a fragment kept as it was written (e.g. a part's result columns, :mod:`app.jobs.columns`)
RAW_FRAGMENT_TYPE = "application/vnd.rollover.job-fragment"
#: fragments are decompressed and sent in pieces of at most this size [bytes]
STREAM_PIECE = 1 << 20

_log = get_logger("rollover.jobs")
#: this process, as a part's state names its worker
WORKER = f"{socket.gethostname()}:{os.getpid()}"


def new_job_id() -> str:
    """``job_`` + 22 url-safe base64 characters (128 random bits): unguessable."""
    return JOB_ID_PREFIX + secrets.token_urlsafe(16)


class _Stored(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)


class JobRecord(_Stored):
    id: str
    operation: str
    owner: str | None
    created_at: float
    unit: str
    part_units: list[int] = Field(min_length=1)
    shared: dict[str, Any]
    formats: list[str]
    etag: dict[str, str]  # format -> the cache key the synchronous answer has (its ETag)
    ttl_s: int = Field(ge=1)
    #: the formats the parts store fragments in when not ``formats`` (``["columns"]``: rendered on GET)
    stored: list[str] | None = None

    @property
    def stored_formats(self) -> list[str]:
        return self.formats if self.stored is None else self.stored

    @property
    def total_units(self) -> int:
        return sum(self.part_units)


class PartState(_Stored):
    status: Literal["queued", "running", "done", "failed"]
    attempt: int = Field(ge=1)
    units: int = Field(ge=0)
    done_units: int = Field(0, ge=0)
    started_at: float | None = None
    heartbeat_at: float | None = None
    finished_at: float | None = None
    seconds: float | None = None
    sections: int = 0
    worker: str | None = None  # host:pid of the worker running it (or that ran it)
    meta: dict[str, Any] | None = None


class Stop(_Stored):
    status: Literal["cancelled", "failed"]
    at: float
    error: dict[str, Any] | None = None


class JobNotFound(Exception):
    """No job with that id (never created, expired, discarded, or another owner's)."""


class Stopped(Exception):
    """The part must stop: the job was cancelled or failed, or this attempt was superseded."""


@dataclass(frozen=True)
class JobView:
    """A job as read back: the record (None when it does not verify), its parts and its stop marker."""

    id: str
    record: JobRecord | None
    parts: list[PartState | None]
    stop: Stop | None
    invalid: str | None  # why the job's stored state cannot be used (it is then reported failed)

    @property
    def status(self) -> str:
        if self.invalid is not None:
            return "failed"
        if self.stop is not None:
            return self.stop.status
        if all(p.status == "done" for p in self.parts):
            return "done"
        if any(p.status != "queued" or p.attempt > 1 for p in self.parts):
            return "running"
        return "queued"

    @property
    def done_units(self) -> int:
        return sum(p.units if p.status == "done" else p.done_units for p in self.parts if p is not None)

    @property
    def total_units(self) -> int:
        return self.record.total_units if self.record is not None else 0

    @property
    def started_at(self) -> float | None:
        times = [p.started_at for p in self.parts if p is not None and p.started_at is not None]
        return min(times) if times else None

    @property
    def finished_at(self) -> float | None:
        status = self.status
        if status in ("cancelled", "failed") and self.stop is not None:
            return self.stop.at
        if status == "done":
            return max(p.finished_at or 0.0 for p in self.parts)
        return None

    @property
    def retries(self) -> int:
        return sum(p.attempt - 1 for p in self.parts if p is not None)

    def count(self, status: str) -> int:
        return sum(1 for p in self.parts if p is not None and p.status == status)


def problem(slug: str, title: str, detail: str, status: int = 422, **extra: Any) -> dict[str, Any]:
    """An RFC 9457 problem object (a failed job's ``error``)."""
    return {"type": f"urn:rollover:problem:{slug}", "title": title, "status": status, "detail": detail, **extra}


class JobStore:
    """Jobs over a :class:`~app.jobs.kv.KV`, every value sealed with ``secret``."""

    def __init__(self, kv: KV, secret: bytes, *, lease_s: float, max_attempts: int) -> None:
        self.kv = kv
        self.secret = secret
        self.lease_s = lease_s
        self.max_attempts = max_attempts

    # ------------------------------------------------------------------------------------------- keys
    @staticmethod
    def key(job_id: str, suffix: str = "") -> str:
        return PREFIX + job_id + suffix

    def _part_key(self, job_id: str, k: int) -> str:
        return self.key(job_id, f":part:{k}")

    def _fragment_key(self, job_id: str, k: int, attempt: int, fmt: str, section: int) -> str:
        return self.key(job_id, f":out:{k}:{attempt}:{fmt}:{section}")

    def _all_keys(self, record: JobRecord, parts: list[PartState | None]) -> list[str]:
        jid = record.id
        keys = [self.key(jid), self.key(jid, ":stop")]
        for k, p in enumerate(parts):
            keys += [self.key(jid, f":in:{k}"), self._part_key(jid, k)]
            if p is not None:
                keys += [
                    self._fragment_key(jid, k, p.attempt, fmt, s)
                    for fmt in record.stored_formats
                    for s in range(p.sections)
                ]
        return keys

    # ----------------------------------------------------------------------------------- sealing
    def _seal(self, key: str, media: str, body: bytes) -> bytes:
        return seal(self.secret, key, media, body)

    def _open(self, key: str, media: str, raw: bytes | None) -> bytes | None:
        """The body of a value this deployment sealed under ``key`` with ``media``; None when absent; raises
        :class:`ValueError` for anything else."""
        if raw is None:
            return None
        opened = unseal(self.secret, key, raw)
        if opened is None or opened[0] != media:
            raise ValueError(f"{key} was not sealed by this deployment (bad envelope, HMAC or media type)")
        return opened[1]

    def _model(self, cls: type[BaseModel], key: str, media: str, raw: bytes | None):
        body = self._open(key, media, raw)
        if body is None:
            return None
        try:
            return cls.model_validate_json(body)
        except ValidationError as exc:
            raise ValueError(f"{key} does not parse as a {cls.__name__}: {exc.errors()[0]['msg']}") from None

    def _reject(self, job_id: str, reason: str, part: int | None = None) -> None:
        """A stored value refused (its seal or its parse): a handled integrity failure, logged with the job and, for
        a part's value, the part; never a traceback."""
        _log.warning("job_entry_rejected", job=job_id, part=part, reason=reason)

    # ------------------------------------------------------------------------------------- submit
    def create(
        self,
        *,
        operation: str,
        owner: str | None,
        unit: str,
        shared: dict[str, Any],
        parts: list[tuple[int, bytes]],
        formats: list[str],
        etag: dict[str, str],
        ttl_s: int,
        stored: list[str] | None = None,
    ) -> JobRecord:
        """Store a new job (its record, each part's inputs and queued state); the caller dispatches the parts."""
        jid = new_job_id()
        record = JobRecord(
            id=jid,
            operation=operation,
            owner=owner,
            created_at=time.time(),
            unit=unit,
            part_units=[u for u, _ in parts],
            shared=shared,
            formats=formats,
            etag=etag,
            ttl_s=ttl_s,
            stored=stored,
        )
        items = {}
        for k, (units, data) in enumerate(parts):
            items[self.key(jid, f":in:{k}")] = self._seal(self.key(jid, f":in:{k}"), INPUT_TYPE, data)
            state = PartState(status="queued", attempt=1, units=units).model_dump_json().encode()
            items[self._part_key(jid, k)] = self._seal(self._part_key(jid, k), STATE_TYPE, state)
        items[self.key(jid)] = self._seal(self.key(jid), RECORD_TYPE, record.model_dump_json().encode())
        self.kv.set_many(items, ttl_s)
        self.kv.add_active(jid)
        JOBS.labels(operation, "queued").inc()
        return record

    # --------------------------------------------------------------------------------------- read
    def view(self, job_id: str) -> JobView:
        """The job as stored (raises :class:`JobNotFound`); a value that does not verify or parse makes the view
        ``invalid`` (reported as a failed job with the reason; logged)."""
        record_key = self.key(job_id)
        raw = self.kv.get(record_key)
        if raw is None:
            raise JobNotFound(job_id)
        try:
            record = self._model(JobRecord, record_key, RECORD_TYPE, raw)
            if record.id != job_id:
                raise ValueError(f"{record_key} holds the record of another job")
        except ValueError as exc:
            self._reject(job_id, str(exc))
            return JobView(job_id, None, [], None, f"the job's stored record cannot be used: {exc}")
        n = len(record.part_units)
        keys = [self._part_key(job_id, k) for k in range(n)] + [self.key(job_id, ":stop")]
        raws = self.kv.mget(keys)
        parts: list[PartState | None] = []
        invalid = None
        for k in range(n):
            try:
                state = self._model(PartState, keys[k], STATE_TYPE, raws[k])
                if state is None:
                    raise ValueError(f"{keys[k]} is missing")
            except ValueError as exc:
                state, invalid = None, invalid or f"part {k}'s stored state cannot be used: {exc}"
                self._reject(job_id, str(exc), k)
            parts.append(state)
        try:
            stop = self._model(Stop, keys[-1], STOP_TYPE, raws[-1])
        except ValueError as exc:
            stop, invalid = None, invalid or f"the job's stop marker cannot be used: {exc}"
            self._reject(job_id, str(exc))
        return JobView(job_id, record, parts, stop, invalid)

    # ----------------------------------------------------------------------------------- control
    def _set_stop(self, job_id: str, stop: Stop, ttl_s: int) -> bool:
        """Write the stop marker unless there is one (True when this call wrote it)."""
        key = self.key(job_id, ":stop")
        mine = self._seal(key, STOP_TYPE, stop.model_dump_json().encode())
        return self.kv.update(key, lambda old: mine if old is None else None, ttl_s) == mine

    def cancel(self, view: JobView) -> None:
        """Cancel a queued or running job: queued parts never start, running ones stop at their next chunk."""
        if view.record is None or view.status not in ("queued", "running"):
            return
        if self._set_stop(view.id, Stop(status="cancelled", at=time.time()), view.record.ttl_s):
            JOBS.labels(view.record.operation, "cancelled").inc()
            self.kv.remove_active(view.id)

    def discard(self, view: JobView) -> None:
        """Delete a finished job and its results."""
        keys = [self.key(view.id), self.key(view.id, ":stop")]
        if view.record is not None:
            keys = self._all_keys(view.record, view.parts)
        self.kv.delete(keys)
        self.kv.remove_active(view.id)

    def fail(self, job_id: str, record: JobRecord, error: dict[str, Any]) -> None:
        if self._set_stop(job_id, Stop(status="failed", at=time.time(), error=error), record.ttl_s):
            JOBS.labels(record.operation, "failed").inc()
            _log.warning("job_failed", job=job_id, operation=record.operation, detail=error.get("detail"))
        self.kv.remove_active(job_id)

    # ---------------------------------------------------------------------------------- the parts
    def _update_part(
        self, job_id: str, k: int, ttl_s: int, change: Callable[[PartState], PartState | None]
    ) -> PartState | None:
        """Apply ``change`` to part k's state atomically (None from it: no change); the state after, or None when
        it is missing or does not verify."""
        key = self._part_key(job_id, k)
        result: dict[str, PartState | None] = {"state": None}

        def fn(old: bytes | None) -> bytes | None:
            try:
                state = self._model(PartState, key, STATE_TYPE, old)
            except ValueError:
                return None
            result["state"] = state
            if state is None:
                return None
            new = change(state)
            if new is None:
                return None
            result["state"] = new
            return self._seal(key, STATE_TYPE, new.model_dump_json().encode())

        self.kv.update(key, fn, ttl_s)
        return result["state"]

    def begin_part(self, job_id: str, k: int, attempt: int) -> tuple[JobRecord, bytes] | None:
        """Claim part k for ``attempt``: its record and inputs, or None when it must not run (the job is gone,
        stopped or does not verify -- then failed --, or the part is not queued for this attempt)."""
        try:
            view = self.view(job_id)
        except JobNotFound:
            return None
        if view.record is None or view.invalid is not None:
            if view.record is not None:
                self.fail(job_id, view.record, problem("job-state-invalid", "Invalid job state", view.invalid))
            return None
        if view.stop is not None:
            return None
        record = view.record
        in_key = self.key(job_id, f":in:{k}")
        try:
            data = self._open(in_key, INPUT_TYPE, self.kv.get(in_key))
            if data is None:
                raise ValueError(f"{in_key} is missing")
        except ValueError as exc:
            self._reject(job_id, str(exc), k)
            self.fail(job_id, record, problem("job-state-invalid", "Invalid job state", f"part {k}: {exc}"))
            return None
        now = time.time()

        def claim(s: PartState) -> PartState | None:
            if s.status != "queued" or s.attempt != attempt:
                return None
            update = {"status": "running", "started_at": now, "heartbeat_at": now, "done_units": 0, "worker": WORKER}
            return s.model_copy(update=update)

        state = self._update_part(job_id, k, record.ttl_s, claim)
        if state is None or state.status != "running" or state.attempt != attempt or state.started_at != now:
            return None
        return record, data

    def heartbeat(self, job_id: str, k: int, attempt: int, done_units: int, ttl_s: int) -> None:
        """Report progress; raises :class:`Stopped` when the job was stopped or this attempt superseded."""
        try:
            stop = self._model(Stop, self.key(job_id, ":stop"), STOP_TYPE, self.kv.get(self.key(job_id, ":stop")))
        except ValueError:
            stop = None  # the readers report it; the part goes on
        if stop is not None:
            raise Stopped(stop.status)
        now = time.time()

        def report(s: PartState) -> PartState | None:
            if s.status != "running" or s.attempt != attempt:
                return None
            return s.model_copy(update={"heartbeat_at": now, "done_units": done_units})

        state = self._update_part(job_id, k, ttl_s, report)
        if state is None or state.attempt != attempt or state.heartbeat_at != now:
            raise Stopped("superseded")

    def finish_part(
        self,
        job_id: str,
        record: JobRecord,
        k: int,
        attempt: int,
        fragments: dict[tuple[str, int], bytes],
        meta: dict[str, Any],
        seconds: float,
        *,
        compressed: bool = True,
    ) -> bool:
        """Store the part's fragments (zlib-compressed, or raw with ``compressed=False``) and mark it done; True when
        the job is now complete."""
        media = FRAGMENT_TYPE if compressed else RAW_FRAGMENT_TYPE
        sections = 1 + max((s for _, s in fragments), default=-1)
        items = {}
        for (fmt, s), data in fragments.items():
            key = self._fragment_key(job_id, k, attempt, fmt, s)
            items[key] = self._seal(key, media, data)
        self.kv.set_many(items, record.ttl_s)
        now = time.time()

        def done(s: PartState) -> PartState | None:
            if s.status != "running" or s.attempt != attempt:
                return None
            return s.model_copy(
                update={
                    "status": "done",
                    "done_units": s.units,
                    "finished_at": now,
                    "seconds": seconds,
                    "sections": sections,
                    "meta": meta,
                }
            )

        state = self._update_part(job_id, k, record.ttl_s, done)
        if state is None or state.status != "done" or state.attempt != attempt or state.finished_at != now:
            self.kv.delete(items)  # superseded: nobody will read these
            return False
        view = self.view(job_id)
        if view.status != "done":
            return False
        # complete: every key of the job lives ttl_s from now on, and the reaper forgets it
        self.kv.expire(self._all_keys(record, view.parts), record.ttl_s)
        self.kv.remove_active(job_id)
        JOBS.labels(record.operation, "done").inc()
        return True

    # ---------------------------------------------------------------------------------- recovery
    def reap(self, job_id: str, now: float | None = None) -> list[tuple[int, int]]:
        """Queue again the running parts of ``job_id`` whose lease expired (their worker is gone), or fail the job
        after ``max_attempts``; the (part, attempt) pairs to dispatch."""
        try:
            view = self.view(job_id)
        except JobNotFound:
            self.kv.remove_active(job_id)
            return []
        if view.record is None or view.invalid is not None or view.stop is not None or view.status == "done":
            if view.record is not None and view.invalid is not None and view.stop is None:
                self.fail(job_id, view.record, problem("job-state-invalid", "Invalid job state", view.invalid))
            self.kv.remove_active(job_id)
            return []
        now = time.time() if now is None else now
        record = view.record
        out = []
        for k, p in enumerate(view.parts):
            if p is None or p.status != "running" or (p.heartbeat_at or 0.0) + self.lease_s > now:
                continue
            if p.attempt >= self.max_attempts:
                detail = (
                    f"part {k} ({p.units} {record.unit}) was started {p.attempt} times and its worker stopped "
                    f"reporting each time (killed, out of memory, or its machine lost) for over {self.lease_s:g} s"
                )
                self.fail(job_id, record, problem("job-worker-lost", "The job's workers were lost", detail, 500))
                return []
            stale = p.heartbeat_at

            def requeue(s: PartState, stale=stale, attempt=p.attempt) -> PartState | None:
                if s.status != "running" or s.attempt != attempt or s.heartbeat_at != stale:
                    return None
                return PartState(status="queued", attempt=attempt + 1, units=s.units)

            state = self._update_part(job_id, k, record.ttl_s, requeue)
            if state is not None and state.status == "queued" and state.attempt == p.attempt + 1:
                _log.warning("job_part_requeued", job=job_id, part=k, attempt=state.attempt, lease_s=self.lease_s)
                JOB_PART_RETRIES.labels(record.operation).inc()
                out.append((k, state.attempt))
        return out

    def queued_parts(self, view: JobView) -> list[tuple[int, int]]:
        return [(k, p.attempt) for k, p in enumerate(view.parts) if p is not None and p.status == "queued"]

    # ------------------------------------------------------------------------------------- results
    def fragment_keys(self, view: JobView, fmt: str) -> list[list[str]]:
        """[part][section] -> key of a done job's fragments in format ``fmt``."""
        return [
            [self._fragment_key(view.id, k, p.attempt, fmt, s) for s in range(p.sections)]
            for k, p in enumerate(view.parts)
        ]

    def missing_fragments(self, view: JobView, fmt: str) -> int:
        keys = [k for part in self.fragment_keys(view, fmt) for k in part]
        return len(keys) - self.kv.exists(keys)

    def fragment_head(self, key: str, length: int) -> bytes:
        """The first ``length`` bytes (fewer if it is shorter) of a raw fragment's body, NOT verified (only its
        envelope and media type are looked at; :meth:`read_fragment` verifies the body when it is used): a cheap look
        at its layout without reading it whole. Raises :class:`ValueError` when it is gone or not a raw fragment."""
        opened = peek(self.kv.head(key, envelope_size(RAW_FRAGMENT_TYPE) + length))
        if opened is None or opened[0] != RAW_FRAGMENT_TYPE:
            raise ValueError(f"{key} is missing (expired?) or not a job fragment (bad envelope or media type)")
        return opened[1][:length]

    def read_fragment(self, job_id: str, key: str, *, compressed: bool = True) -> Iterator[bytes]:
        """The fragment under ``key``, decompressed, in pieces (a raw one whole, ``compressed=False``); raises
        :class:`ValueError` when it does not verify (or is gone)."""
        data = self._open(key, FRAGMENT_TYPE if compressed else RAW_FRAGMENT_TYPE, self.kv.get(key))
        if data is None:
            raise ValueError(f"{key} is missing (expired?)")
        if not compressed:
            yield data
            return
        d = zlib.decompressobj()
        rest = data
        while rest:
            piece = d.decompress(rest, STREAM_PIECE)
            if piece:
                yield piece
            rest = d.unconsumed_tail
        tail = d.flush()
        if tail:
            yield tail
        if not d.eof:
            raise ValueError(f"{key} is truncated")
