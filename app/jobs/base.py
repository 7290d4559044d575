"""What a job operation is (:class:`Operation`) and what it is given; the registry is :mod:`app.jobs.operations`.

An operation says how to

* **parse** the job's ``request`` exactly as its synchronous endpoint does (the same pydantic model, made job-sized:
  only the size limits differ), raising the same :class:`~fastapi.exceptions.RequestValidationError` located under
  ``("body", ...)`` (the API puts ``request`` in front);
* **refs**: resolve its vehicles (presets, records, specs, saved vehicles and fleets of the caller's key) as the
  synchronous endpoint does (:func:`app.vehicles.resolve.resolve_request`, with the submitting request: its bearer
  key), into what **resolve** takes, so a stored job holds records only;
* **resolve** it with what only the API process has (presets, the caller's saved vehicles and fleets, the configured
  SRT targets): :class:`ResolveContext` carries the settings and the caller's owner id;
* **split** the resolved request into parts: a :class:`Prepared` with the inputs every part shares and each part's
  own inputs, all self-contained (engine inputs only: a worker on another machine needs nothing but Redis). Whatever
  the synchronous endpoint would refuse for the request as a whole is refused here, before the job exists;
* **run a part** (in a worker) with a :class:`PartContext`: ``write`` the part's result fragments (per format and
  section), report ``progress`` at each chunk (it raises :class:`~app.jobs.store.Stopped` when the job was cancelled);
  it returns the part's metadata (e.g. the partial summaries), kept in the part's state;
* **assemble** the result in order from the parts' metadata and fragments, byte for byte the synchronous answer.

An operation whose parts keep their result as typed columns (``stored="columns"``: :mod:`app.jobs.columns`, one
blob per section, kept raw) renders JSON or CSV from them only when the result is asked for, in ``assemble``; its
``check`` reads every fragment first, so a stored result that cannot be rendered fails the job (``job-state-invalid``)
before the first byte of the answer is sent.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Iterator
from dataclasses import dataclass
from typing import Any, Protocol

from pydantic import BaseModel
from starlette.requests import Request

from app.settings import Settings


@dataclass(frozen=True)
class ResolveContext:
    """What resolution may use besides the request: the settings and the caller's owner id (None without keys)."""

    settings: Settings
    owner: str | None


@dataclass(frozen=True)
class Prepared:
    """A split job: inputs shared by every part (JSON), each part's (units of work, packed inputs), and the cache
    key the synchronous answer would have per format (the result's ETag)."""

    shared: dict[str, Any]
    parts: list[tuple[int, bytes]]
    etag: dict[str, str]


class PartContext(Protocol):
    def write(self, fmt: str, section: int, data: bytes) -> None: ...
    def progress(self, done_units: int) -> None: ...


#: (part, section) -> the fragment's bytes, in pieces
Fragments = Callable[[int, int], Iterator[bytes]]
#: (part, section, length) -> the first ``length`` bytes of a raw fragment, not verified (a look at its layout)
FragmentHeads = Callable[[int, int, int], bytes]


@dataclass(frozen=True)
class Operation:
    name: str
    description: str  # what it does and its limits (the OpenAPI description lists them)
    request_model: type[BaseModel]  # the job-sized request model (published)
    unit: str  # what progress counts ("rows", "cases")
    part_units: int  # default units of work per part
    csv: bool  # whether the result is also offered as CSV
    parse: Callable[..., Any]  # (the request's JSON, *what read_body read besides it) -> the parsed request
    resolve: Callable[[Any, ResolveContext], Any]
    split: Callable[[Any, int], Prepared]
    run_part: Callable[[dict[str, Any], bytes, PartContext], dict[str, Any]]
    assemble: Callable[[dict[str, Any], list[dict[str, Any]], str, Fragments], Iterator[bytes]]
    #: resolves the parsed request's vehicles (:func:`app.vehicles.resolve.resolve_request`: saved ``veh_`` ids and
    #: ``flt_`` fleets with the submitting request's bearer key) in the API process; :attr:`resolve` takes what it
    #: returns (None: nothing to resolve, :attr:`resolve` takes the parsed request)
    refs: Callable[[Request, Any, Settings], Awaitable[Any]] | None = None
    #: the one format the parts write their fragments in (kept raw, rendered by ``assemble``); None: the parts write
    #: each of :attr:`formats`, rendered (zlib-compressed)
    stored: str | None = None
    #: looks at the fragments of a done job before its result is answered and raises ValueError when they cannot
    #: be rendered (None: no check); ``assemble`` checks each again as it reads it
    check: Callable[[dict[str, Any], list[dict[str, Any]], Fragments, FragmentHeads], None] | None = None
    #: reads a submission's body whose bulk it can read better than ``orjson`` into a Python object per item (an
    #: alignment's plain JSON curves, straight into columns): (the document with that bulk taken out, what it read),
    #: the second handed to :attr:`parse` after the request; None when the body is not its operation's or not of
    #: that form (the body is then parsed whole). Never decides an error: whatever it refuses is parsed as always.
    read_body: Callable[[bytes], tuple[dict[str, Any], Any] | None] | None = None

    @property
    def formats(self) -> list[str]:
        return ["json", "csv"] if self.csv else ["json"]
