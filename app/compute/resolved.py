"""Resolved requests: one frozen object per request kind of the batch features, holding everything its answer depends
on (the vehicles' records, the options, the targets, a digest of the curves or of the document...) and nothing else.

Each carries its cache key (:meth:`Resolved.key`): :func:`app.compute.cache.cache_key` of :meth:`Resolved.to_json_dict`,
which is the object's fields by name, so the key holds every input of the answer (the guarantee of
:mod:`app.compute.cache`). A job keeps the resolved request in its stored state as :meth:`~Resolved.to_json_dict` and a
worker reads it back with :meth:`~Resolved.from_json_dict`, which validates it (what comes back from the store is not
trusted: a wrong shape is a :class:`ValueError`).

* :class:`ResolvedAssessment`: an assessment of curves by vehicles (shared by alignments and routes), extended by
  :class:`ResolvedAlignment` (the curves' count and digest, the CSV dialect they came in) and :class:`ResolvedRoute`
  (the route document's digest and the options of its curves' detection);
* :class:`ResolvedSweep`: a grid sweep (the base case, the axes);
* :class:`ResolvedLimits`: an inverse limit (the base case, the parameter, the target, the overweights' table).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass
from typing import Any, Self

import orjson
from pydantic import ConfigDict, TypeAdapter, ValidationError

from app.compute.cache import cache_key

#: what :meth:`Resolved.from_json_dict` accepts: exactly the fields, of their types (ints for floats, arrays for tuples)
_STRICT = ConfigDict(extra="forbid", strict=True)


def _plain(value: Any) -> Any:
    """A field's value as JSON types: tuples as lists, a nested dataclass as its fields (a dict)."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: _plain(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, tuple | list):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    return value


@functools.cache
def _adapter(cls: type) -> TypeAdapter:
    return TypeAdapter(cls)


class Resolved:
    """What every resolved request has: its JSON form (the content of its cache key) and its key."""

    #: fields left out of the JSON form (and so of the key) when they are None: the keys of the requests that never
    #: have them stay what they were
    _omitted_when_none: tuple[str, ...] = ()

    def to_json_dict(self) -> dict[str, Any]:
        """The fields by name, as JSON types: the canonical content of the key, and the job's stored form."""
        out = {}
        for f in dataclasses.fields(self):  # type: ignore[arg-type]
            value = getattr(self, f.name)
            if value is None and f.name in self._omitted_when_none:
                continue
            out[f.name] = _plain(value)
        return out

    @classmethod
    def from_json_dict(cls, data: Any) -> Self:
        """:meth:`to_json_dict` read back (from a job's stored state), validated: a :class:`ValueError` naming the
        first wrong field for anything else."""
        try:
            return _adapter(cls).validate_json(orjson.dumps(data))
        except (ValidationError, orjson.JSONEncodeError) as exc:
            if isinstance(exc, ValidationError):
                error = exc.errors()[0]
                where = ".".join(str(p) for p in error["loc"]) or "(the whole)"
                reason = f"{where}: {error['msg']}"
            else:
                reason = str(exc)
            raise ValueError(f"the stored request is not a {cls.__name__}: {reason}") from None

    def key(self, operation: str) -> str:
        """The cache key of the answer of ``operation`` to this request (:func:`app.compute.cache.cache_key`)."""
        return cache_key(operation, self.to_json_dict())


# ------------------------------------------------------------------------------------- assessments


@dataclass(frozen=True, kw_only=True)
class ResolvedAssessment(Resolved):
    """What an assessment of curves depends on besides its curves: the vehicles' records (``to_dict()`` of a record
    or of a combination), their preset and saved ids (None where a vehicle is neither), the SRT options, the design
    options and the targets (name -> minimum SRT [g])."""

    __pydantic_config__ = _STRICT

    vehicles: tuple[dict[str, Any], ...]
    presets: tuple[str | None, ...]
    saved_ids: tuple[str | None, ...]
    model: str | None
    stage: str
    trailer_angle_deg: float
    load: dict[str, Any]
    rear_llt_limit: float
    design_standard: str
    side_friction_bound: str | None
    max_superelevation_percent: float | None
    targets: dict[str, float]

    def __post_init__(self) -> None:
        if not len(self.vehicles) == len(self.presets) == len(self.saved_ids):
            raise ValueError(
                f"{len(self.vehicles)} vehicles, {len(self.presets)} presets and {len(self.saved_ids)} saved ids"
            )

    def assessment_fields(self) -> dict[str, Any]:
        """The fields of :class:`ResolvedAssessment` (to build an alignment's or a route's from it)."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(ResolvedAssessment)}


@dataclass(frozen=True)
class CurvesDigest:
    """The curves of an alignment as the key holds them: their number and SHA-256 (ids and columns)."""

    __pydantic_config__ = _STRICT

    count: int
    sha256: str


@dataclass(frozen=True, kw_only=True)
class ResolvedAlignment(ResolvedAssessment):
    """An alignment's assessment: its curves' digest and, when they came as CSV, the dialect they were read in (the
    answer names it; None, and then absent from the key, for curves given as JSON or LandXML)."""

    _omitted_when_none = ("csv_dialect",)

    curves: CurvesDigest
    csv_dialect: dict[str, str | bool] | None = None


@dataclass(frozen=True)
class RouteDocument:
    """A route's document as the key holds it: its format and SHA-256, the defaults of its curves' superelevation and
    posted speed, and the curve detection's options."""

    __pydantic_config__ = _STRICT

    format: str
    sha256: str
    superelevation_percent: float | None
    posted_speed_kmh: float | None
    detection: dict[str, Any]


@dataclass(frozen=True, kw_only=True)
class ResolvedRoute(ResolvedAssessment):
    """A route's assessment: the assessment and the route document."""

    route: RouteDocument


# ------------------------------------------------------------------------------------- sweeps, limits


@dataclass(frozen=True, kw_only=True)
class ResolvedSweep(Resolved):
    """A grid sweep: the base case (:func:`app.srt.service.base_case_key`: the case's every input and the targets)
    and the axes with their values, in the request's order (the first varies slowest)."""

    __pydantic_config__ = _STRICT

    case: dict[str, Any]
    grid: dict[str, tuple[float, ...]]

    @property
    def cases(self) -> int:
        """The number of cases (rows): the product of the axes' lengths."""
        return math.prod(len(values) for values in self.grid.values())

    def on(self, grid: dict[str, Any]) -> ResolvedSweep:
        """The same base case over another grid (a sub-grid of a job's block)."""
        return dataclasses.replace(self, grid={a: tuple(v) for a, v in grid.items()})


@dataclass(frozen=True, kw_only=True)
class ResolvedLimits(Resolved):
    """An inverse limit: the base case (as :class:`ResolvedSweep`'s), the parameter searched, the target SRT [g] and
    the overweights of the table [%] (None: no table)."""

    __pydantic_config__ = _STRICT

    case: dict[str, Any]
    parameter: str
    target_srt_g: float
    overweights_percent: tuple[float, ...] | None
