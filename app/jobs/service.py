"""What the jobs routes do: validate a submission as its synchronous endpoint would (every refusal located under
``request``), resolve and split it, find a job the caller may see, and describe a job's status."""

from __future__ import annotations

import time
from datetime import UTC, datetime
from typing import Any

import orjson
from fastapi.exceptions import RequestValidationError
from pydantic import ValidationError

from app.formats.jsonpieces import loads_in_pieces
from app.http.problems import InvalidAlignment, engine_field
from app.http.strictjson import refuse_duplicate_keys
from app.jobs.backends import Backend
from app.jobs.base import Operation, ResolveContext
from app.jobs.operations import OPERATIONS
from app.jobs.store import JobNotFound, JobView, problem
from app.settings import Settings
from engine import InvalidInput


def _rfc3339(t: float | None) -> str | None:
    if t is None:
        return None
    return datetime.fromtimestamp(t, UTC).isoformat(timespec="milliseconds").replace("+00:00", "Z")


def status_body(view: JobView) -> dict[str, Any]:
    record, status = view.record, view.status
    total = view.total_units
    done = total if status == "done" else min(view.done_units, total)
    finished = view.finished_at
    if view.invalid is not None:
        error = problem("job-state-invalid", "The job's stored state cannot be used", view.invalid, 500)
    else:
        error = view.stop.error if view.stop is not None and view.stop.status == "failed" else None
    return {
        "id": view.id,
        "operation": record.operation if record else None,
        "status": status,
        "progress": 1.0 if status == "done" else (done / total if total else 0.0),
        "unit": record.unit if record else None,
        "done": done,
        "total": total,
        "parts": {
            "total": len(view.parts),
            **{s: view.count(s) for s in ("queued", "running", "done", "failed")},
        },
        "retries": view.retries,
        "created_at": _rfc3339(record.created_at if record else None),
        "started_at": _rfc3339(view.started_at),
        "finished_at": _rfc3339(finished),
        "expires_at": _rfc3339(finished + record.ttl_s if finished is not None and record else None),
        "formats": record.formats if record else [],
        "result": f"/v1/jobs/{view.id}/result" if status == "done" else None,
        "error": error,
    }


def under_request(exc: Exception) -> Exception:
    """An error of the inner request, located under ``request`` (``curves.3.radius_m`` -> ``request.curves.3...``)."""
    if isinstance(exc, RequestValidationError):
        errors = []
        for e in exc.errors():
            loc = tuple(e.get("loc", ()))
            errors.append({**e, "loc": ("body", "request", *(loc[1:] if loc[:1] == ("body",) else loc))})
        return RequestValidationError(errors)
    if isinstance(exc, InvalidAlignment):
        source = "request" if exc.source == "body" else f"request.{exc.source}"
        return type(exc)(exc.reason, source=source, location=exc.location, column=exc.column)  # InvalidRoute stays
    if isinstance(exc, InvalidInput) and exc.field is not None:
        out = type(exc)(str(exc), field=f"request.{engine_field(exc.field)}", value=exc.value)
        return out
    return exc


def parse_submission(body: bytes) -> tuple[Operation, Any]:
    """The job's operation and its validated request (blocking: a million curves take a few seconds)."""
    data, read, reader = None, (), None
    for candidate in OPERATIONS.values():  # an operation that reads its bulk better than orjson (read_body)
        found = candidate.read_body(body) if candidate.read_body is not None else None
        if found is not None:  # (the document without its bulk, what was read of it: handed to the op's parse)
            data, read, reader = found[0], found[1:], candidate
            break
    if data is None:
        try:
            data = loads_in_pieces(body, ("request", "curves"))  # an alignment job's curves a slice at a time
        except orjson.JSONDecodeError as exc:
            msg = f"JSON: {exc}"
            raise RequestValidationError([{"type": "json_invalid", "loc": ("body",), "msg": msg}]) from None
        refuse_duplicate_keys(body, data)
    if not isinstance(data, dict):
        raise RequestValidationError([{"type": "dict_type", "loc": ("body",), "msg": "Input should be an object"}])
    known = ", ".join(OPERATIONS)
    errors = []
    for name in sorted(set(data) - {"operation", "request"}):
        errors.append({"type": "extra_forbidden", "loc": ("body", name), "msg": "Extra inputs are not permitted"})
    operation = data.get("operation")
    if "operation" not in data:
        errors.append({"type": "missing", "loc": ("body", "operation"), "msg": f"Field required (one of {known})"})
    elif not isinstance(operation, str) or operation not in OPERATIONS:
        msg = f"unknown operation {operation!r}; one of {known}"
        errors.append({"type": "literal_error", "loc": ("body", "operation"), "msg": msg, "input": operation})
    if "request" not in data:
        errors.append({"type": "missing", "loc": ("body", "request"), "msg": "Field required"})
    elif not isinstance(data["request"], dict):
        errors.append({"type": "dict_type", "loc": ("body", "request"), "msg": "Input should be an object"})
    if errors:
        raise RequestValidationError(errors)
    op = OPERATIONS[operation]
    try:
        return op, op.parse(data["request"], *(read if op is reader else ()))
    except ValidationError as exc:  # the request model's own errors
        errors = [{**e, "loc": ("body", *e["loc"])} for e in exc.errors(include_url=False)]
        raise under_request(RequestValidationError(errors)) from None
    except RequestValidationError as exc:
        raise under_request(exc) from None


def prepare(op: Operation, parsed: Any, ctx: ResolveContext):
    """Resolve and split (blocking), every refusal located under ``request``."""
    try:
        resolved = op.resolve(parsed, ctx)
        return op.split(resolved, ctx.settings.jobs_part_size or op.part_units)
    except (RequestValidationError, InvalidAlignment, InvalidInput) as exc:
        raise under_request(exc) from None


def visible_job(backend: Backend, job_id: str, owner: str | None) -> JobView | None:
    """The job when the caller may see it (a lost worker's parts queued again on the way)."""
    if not job_id.startswith("job_") or len(job_id) > 64:
        return None
    try:
        view = backend.store.view(job_id)
    except JobNotFound:
        return None
    if view.record is not None and view.record.owner != owner:
        return None
    if view.status == "running":
        now, lease = time.time(), backend.store.lease_s
        if any(p is not None and p.status == "running" and (p.heartbeat_at or 0) + lease <= now for p in view.parts):
            backend.dispatch(job_id, backend.store.reap(job_id, now))
            view = backend.store.view(job_id)
    return view


def open_jobs(settings: Settings) -> Backend:
    """The app's job backend (in-process threads, or Redis + RQ workers), opened in the lifespan."""
    from app.jobs.backends import make_backend

    return make_backend(settings)
