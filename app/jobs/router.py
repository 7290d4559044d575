"""``/v1/jobs``: submit a long batch as a job, follow its progress, fetch its result, cancel it.

Who sees a job: without ``ROLLOVER_API_KEYS`` no key is needed and a job is anyone's who holds its id (128 random
bits, unguessable). With keys configured, every jobs request needs a valid bearer key (401 otherwise), a job belongs
to the key that created it, and any other key gets 404 for it. A job created while no key was configured stays
ownerless: once keys are configured nobody sees it (a job is visible only to the owner it was created with).
"""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import AsyncIterator, Iterator
from typing import Annotated, Any

from fastapi import APIRouter, Depends, Request, Response
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse, StreamingResponse
from fastapi.security import HTTPAuthorizationCredentials
from fastapi.security.utils import get_authorization_scheme_param
from starlette.concurrency import run_in_threadpool

from app.catalog.auth import authenticate
from app.deps import SettingsDep
from app.http.bodies import json_body
from app.http.bodylimit import body_limit
from app.http.negotiation import CSV_TYPE, JSON_TYPE, wants_csv
from app.http.problems import InvalidAlignment, Problem, error_responses, problem_response
from app.jobs.backends import Backend
from app.jobs.base import Operation, ResolveContext
from app.jobs.kv import StorageFull
from app.jobs.operations import OPERATIONS
from app.jobs.schemas import JobStatus, JobSubmission
from app.jobs.service import parse_submission, prepare, status_body, under_request, visible_job
from app.jobs.store import JobView, problem
from app.logs import get_logger
from app.routes.service import MAX_JOB_ROWS as ROUTE_JOB_ROWS
from engine import InvalidInput

#: a job's request body: 1,000,000 curves as JSON are about 100 MB; a LandXML document of 200 M characters [bytes]
JOBS_BODY_LIMIT = 256 * 2**20
#: a streamed result is sent in pieces of about this size [bytes]
SEND_PIECE = 256 * 2**10

router = APIRouter(prefix="/v1/jobs", tags=["jobs"])
_log = get_logger("rollover.jobs")


# ------------------------------------------------------------------------------------- dependencies


async def job_owner(request: Request, settings: SettingsDep) -> str | None:
    """The caller's owner id; None when no key is configured (then no key is needed). With keys, a valid one is
    required (401 problem otherwise). The header is read here, not through the bearer scheme's dependency, so the
    spec can say the key is optional (``security: [{}, {bearerAuth: []}]``)."""
    if not settings.api_key_list():
        return None
    scheme, token = get_authorization_scheme_param(request.headers.get("authorization"))
    credentials = None
    if scheme.lower() == "bearer" and token:
        credentials = HTTPAuthorizationCredentials(scheme=scheme, credentials=token)
    return authenticate(credentials, settings)


OwnerDep = Annotated[str | None, Depends(job_owner)]


async def get_jobs(request: Request) -> Backend:
    return request.app.state.jobs


JobsDep = Annotated[Backend, Depends(get_jobs)]


def _storage_full(request: Request, exc: StorageFull) -> Response:
    return problem_response(
        request, 503, "jobs-storage-full", "The job store is full", str(exc), headers={"Retry-After": "60"}
    )


def _not_found(request: Request, job_id: str) -> Response:
    return problem_response(
        request,
        404,
        "job-not-found",
        "No such job",
        f"no job {job_id!r} for this caller (it does not exist, has expired or was deleted, or belongs to another key)",
    )


# ------------------------------------------------------------------------------------------ routes

_PROBLEM = {"model": Problem}
#: the bearer key is optional: needed only when keys are configured (OpenAPI: `{}` = no credentials)
_SECURITY = {"security": [{}, {"bearerAuth": []}]}
_STATUS_HEADERS = {"Location": {"description": "The job's status URL.", "schema": {"type": "string"}}}
_RESPONSES: dict[int | str, dict[str, Any]] = {
    401: {**_PROBLEM, "description": "Keys are configured (ROLLOVER_API_KEYS) and the request has no valid one."},
    404: {**_PROBLEM, "description": "No such job for this caller (or, at submission, an unknown vehicle preset)."},
    422: {**_PROBLEM, "description": "Validation error."},
    500: {**_PROBLEM, "description": "Internal error (a bug; logged, never a stack trace)."},
}
_SUBMIT_DESCRIPTION = (
    "Submit a long batch: `operation` and its `request`, the synchronous endpoint's request at a job's size. The "
    "request is validated now, exactly as the synchronous endpoint validates it (the same problems, their fields "
    "under `request.`): a bad job is refused here, never a failed job later. 202 with the job's status and "
    "`Location: /v1/jobs/{id}`.\n\n"
    + "\n".join(f"* `{op.name}`: {op.description}" for op in OPERATIONS.values())
    + "\n\nLimits (beyond the JSON schema's): `alignments.assess` at most 1,000,000 rows (curves x vehicles); "
    "`srt.sweep` at most 1,000,000 cases (the product of the axes' lengths); `routes.assess` the synchronous "
    f"request's document (body and vertices) and at most {ROUTE_JOB_ROWS:,} rows (curves x vehicles)."
)


@router.post(
    "",
    name="submit",
    status_code=202,
    response_model=JobStatus,
    responses={
        202: {"headers": _STATUS_HEADERS, "description": "Accepted: the job's status."},
        **_RESPONSES,
        400: {**_PROBLEM, "description": "Malformed request body (not JSON)."},
        403: error_responses(403)[403],
        409: error_responses(409)[409],
        422: {**_PROBLEM, "description": "The job or its request is invalid (fields under `request.`)."},
        503: {
            **_PROBLEM,
            "description": "The embedded job store is full (ROLLOVER_JOBS_MAX_BYTES), or the database of saved "
            "vehicles is unavailable: retry later.",
        },
    },
    openapi_extra={**body_limit(JOBS_BODY_LIMIT), **json_body(JobSubmission), **_SECURITY},
    description=_SUBMIT_DESCRIPTION,
)
async def submit(request: Request, owner: OwnerDep, settings: SettingsDep, jobs: JobsDep) -> Response:
    op, parsed = await run_in_threadpool(parse_submission, await request.body())
    if op.refs is not None:
        try:
            parsed = await op.refs(request, parsed, settings)
        except (RequestValidationError, InvalidAlignment, InvalidInput) as exc:
            raise under_request(exc) from None
    prepared = await run_in_threadpool(prepare, op, parsed, ResolveContext(settings, owner))
    try:
        record = await run_in_threadpool(
            jobs.store.create,
            operation=op.name,
            owner=owner,
            unit=op.unit,
            shared=prepared.shared,
            parts=prepared.parts,
            formats=op.formats,
            etag=prepared.etag,
            ttl_s=settings.jobs_result_ttl_s,
            stored=None if op.stored is None else [op.stored],
        )
    except StorageFull as exc:
        return _storage_full(request, exc)
    await run_in_threadpool(jobs.dispatch, record.id, [(k, 1) for k in range(len(prepared.parts))])
    _log.info("job_submitted", job=record.id, operation=op.name, parts=len(prepared.parts), units=record.total_units)
    view = await run_in_threadpool(jobs.store.view, record.id)
    return JSONResponse(status_body(view), status_code=202, headers={"Location": f"/v1/jobs/{record.id}"})


@router.get(
    "/{job_id}",
    name="status",
    openapi_extra=_SECURITY,
    response_model=JobStatus,
    responses=_RESPONSES,
    description="The job's status, progress (updated while it runs), timestamps and, when failed, the problem.",
)
async def status(request: Request, job_id: str, owner: OwnerDep, jobs: JobsDep) -> Response:
    view = await run_in_threadpool(visible_job, jobs, job_id, owner)
    if view is None:
        return _not_found(request, job_id)
    return JSONResponse(status_body(view))


def _coalesce(chunks: Iterator[bytes], size: int = SEND_PIECE) -> Iterator[bytes]:
    """Small chunks joined into pieces of about ``size`` bytes; a chunk of that size or more sent as it is (no copy)."""
    buf: list[bytes] = []
    n = 0
    for c in chunks:
        if len(c) >= size:
            if buf:
                yield b"".join(buf)
                buf, n = [], 0
            yield c
            continue
        buf.append(c)
        n += len(c)
        if n >= size:
            yield b"".join(buf)
            buf, n = [], 0
    if buf:
        yield b"".join(buf)


async def prefetched(chunks: Iterator[bytes]) -> AsyncIterator[bytes]:
    """``chunks`` (a blocking iterator: the result rendered from its stored parts) with its next piece rendered in a
    worker thread while this one is written to the socket (``iterate_in_threadpool`` renders a piece only once the
    last is sent, so rendering and sending took turns). A thread is held only while a piece renders, never while a
    slow client reads. An error in the rendering is raised here, after the pieces before it; a client that goes away
    leaves the piece in progress to finish (a generator cannot be stopped from another thread) and nothing after."""
    end = object()
    it = iter(chunks)

    def piece() -> Any:
        return next(it, end)  # end, not StopIteration: that cannot cross a future

    pending = asyncio.ensure_future(run_in_threadpool(piece))
    try:
        while (current := await pending) is not end:
            pending = asyncio.ensure_future(run_in_threadpool(piece))
            yield current
    finally:
        if not pending.done():
            with contextlib.suppress(Exception):
                await asyncio.shield(pending)


class _Reading:
    """The stored fragment last asked for while a result is checked or assembled: the part a failure belongs to."""

    def __init__(self, jobs: Backend, view: JobView, op: Operation, fmt: str) -> None:
        self.store, self.compressed = jobs.store, op.stored is None
        self.keys = self.store.fragment_keys(view, op.stored or fmt)
        self.job_id = view.id
        self.part: int | None = None
        self.key: str | None = None

    def _at(self, k: int, s: int) -> str:
        self.part, self.key = k, self.keys[k][s]
        return self.key

    def fragment(self, k: int, s: int) -> Iterator[bytes]:
        """(part, section) -> the stored fragment's pieces, for ``assemble`` (the op's stored format, if it has
        one)."""
        return self.store.read_fragment(self.job_id, self._at(k, s), compressed=self.compressed)

    def head(self, k: int, s: int, length: int) -> bytes:
        """(part, section, length) -> the first bytes of the stored fragment (its layout, unverified), for
        ``check``."""
        return self.store.fragment_head(self._at(k, s), length)


class _PartRefused(Exception):
    """A stored part failed its integrity checks while the answer was streamed (handled: logged and the job failed
    by :func:`_invalid`); the response ends without its end."""


def _invalid(jobs: Backend, view: JobView, exc: Exception, reading: _Reading) -> None:
    """A stored part that does not verify (its seal) or read (its layout): a handled integrity failure, logged with
    the job and the part, never a traceback; the job is failed with the reason."""
    reason = f"{type(exc).__name__}: {exc}"
    _log.warning("job_part_integrity_failure", job=view.id, part=reading.part, key=reading.key, reason=reason)
    detail = reason if reading.part is None else f"part {reading.part}: {reason}"
    jobs.store.fail(
        view.id, view.record, problem("job-state-invalid", "The job's stored result cannot be used", detail)
    )


def _check_result(jobs: Backend, view: JobView, op: Operation, fmt: str) -> bool:
    """The op's check of every stored fragment before the answer starts (True: usable; False: the job is failed)."""
    if op.check is None:
        return True
    reading = _Reading(jobs, view, op, fmt)
    try:
        metas = [p.meta or {} for p in view.parts]
        op.check(view.record.shared, metas, reading.fragment, reading.head)
    except (ValueError, KeyError, TypeError, IndexError) as exc:
        _invalid(jobs, view, exc, reading)
        return False
    return True


def _result_chunks(jobs: Backend, view: JobView, op: Operation, fmt: str) -> Iterator[bytes]:
    reading = _Reading(jobs, view, op, fmt)
    try:
        metas = [p.meta or {} for p in view.parts]
        yield from op.assemble(view.record.shared, metas, fmt, reading.fragment)
    except (ValueError, KeyError, TypeError, IndexError) as exc:  # a stored fragment or metadata that cannot be used
        _invalid(jobs, view, exc, reading)
        raise _PartRefused from None


class _StoredResult(StreamingResponse):
    """A result streamed from its stored parts. A part refused on the way (:class:`_PartRefused`, already logged)
    ends the answer without the chunked body's end: the server closes the connection, so no client takes the rows
    before it for the whole answer, and nothing propagates as an unhandled error with a traceback (uvicorn says
    once that the response was not completed)."""

    async def stream_response(self, send) -> None:
        await send({"type": "http.response.start", "status": self.status_code, "headers": self.raw_headers})
        try:
            async for chunk in self.body_iterator:
                await send({"type": "http.response.body", "body": chunk, "more_body": True})
        except _PartRefused:
            return
        await send({"type": "http.response.body", "body": b"", "more_body": False})


@router.get(
    "/{job_id}/result",
    name="result",
    openapi_extra=_SECURITY,
    responses={
        200: {
            "description": "The synchronous endpoint's answer, byte for byte: JSON, or CSV when `Accept` prefers "
            "`text/csv` and the operation offers it. Streamed.",
            "content": {"text/csv": {"schema": {"type": "string"}}},
            "headers": {
                "ETag": {"description": "The synchronous answer's cache key.", "schema": {"type": "string"}},
                "Vary": {"description": "`Accept`.", "schema": {"type": "string"}},
            },
        },
        **_RESPONSES,
        409: {**_PROBLEM, "description": "The job is not done (the problem's `status` says where it is)."},
    },
    description="The job's result once it is done: the same bytes the synchronous endpoint answers for the same "
    "request, streamed from the stored parts. The parts are checked before the answer starts (a part missing or "
    "of another layout: 409, the job failed) and each again as it is streamed: a part altered since ends the "
    "answer early (the connection closes before the chunked body's end, which HTTP clients report as an error) "
    "and fails the job.",
)
async def result(request: Request, job_id: str, owner: OwnerDep, jobs: JobsDep) -> Response:
    view = await run_in_threadpool(visible_job, jobs, job_id, owner)
    if view is None:
        return _not_found(request, job_id)
    op = OPERATIONS.get(view.record.operation) if view.record is not None else None
    fmt = "csv" if wants_csv(request.headers.get("accept")) and op is not None and op.csv else "json"
    if view.status == "done" and op is not None:
        missing = await run_in_threadpool(jobs.store.missing_fragments, view, op.stored or fmt)
        if missing:
            detail = f"{missing} stored result fragment(s) are missing (expired?)"
            await run_in_threadpool(
                jobs.store.fail, job_id, view.record, problem("job-state-invalid", "Invalid job state", detail)
            )
            view = await run_in_threadpool(jobs.store.view, job_id)
        elif not await run_in_threadpool(_check_result, jobs, view, op, fmt):
            view = await run_in_threadpool(jobs.store.view, job_id)
    if view.status != "done" or op is None:
        return problem_response(
            request,
            409,
            "job-not-done",
            "The job is not done",
            f"the job is {view.status}; its result exists once it is done",
            job_status=view.status,
        )
    headers = {"ETag": f'"{view.record.etag[fmt]}"', "Vary": "Accept"}
    chunks = _coalesce(_result_chunks(jobs, view, op, fmt))
    media_type = CSV_TYPE if fmt == "csv" else JSON_TYPE
    return _StoredResult(prefetched(chunks), media_type=media_type, headers=headers)


@router.delete(
    "/{job_id}",
    name="cancel",
    openapi_extra=_SECURITY,
    status_code=202,
    response_model=JobStatus,
    responses={
        202: {"description": "Cancelled: the job's status (`cancelled`)."},
        204: {"description": "The job had finished: it and its result are deleted."},
        **_RESPONSES,
    },
    description="Cancel a queued or running job (a queued part never starts; a running one stops at its next chunk) "
    "-> 202 with its status; delete a finished one and its result -> 204.",
)
async def cancel(request: Request, job_id: str, owner: OwnerDep, jobs: JobsDep) -> Response:
    view = await run_in_threadpool(visible_job, jobs, job_id, owner)
    if view is None:
        return _not_found(request, job_id)
    if view.status in ("queued", "running"):
        await run_in_threadpool(jobs.store.cancel, view)
        view = await run_in_threadpool(jobs.store.view, job_id)
        return JSONResponse(status_body(view), status_code=202)
    await run_in_threadpool(jobs.store.discard, view)
    return Response(status_code=204)
