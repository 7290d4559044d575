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
* :class:`ResolvedLimits`: an inverse limit (the base case, the parameter, the target, the overweights' table);
* the single answers: :class:`ResolvedCase` (an engine case and its targets, the base of the others),
  :class:`ResolvedSrt`, :class:`ResolvedCurveSpeed`, :class:`ResolvedMinRadius`, :class:`ResolvedCurvesPlot`,
  :class:`ResolvedMinRadiusPlot`,
  :class:`ResolvedSuperelevation`, :class:`ResolvedSuperelevationTable`, :class:`ResolvedBuild` and
  :class:`ResolvedPayloadTable`.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass
from typing import Any, Literal, Self

import orjson
from pydantic import ConfigDict, GetCoreSchemaHandler, TypeAdapter, ValidationError
from pydantic_core import core_schema

from app.compute.cache import cache_key
from engine import Case
from engine.builder import CombinationSpec, VehicleSpec

#: what :meth:`Resolved.from_json_dict` accepts: exactly the fields, of their types (ints for floats, arrays for tuples)
_STRICT = ConfigDict(extra="forbid", strict=True)


def _plain(value: Any) -> Any:
    """A field's value as JSON types: tuples as lists, a nested resolved request as its JSON form, a nested dataclass
    as its fields (a dict)."""
    if isinstance(value, Resolved):
        return value.to_json_dict()
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

    @classmethod
    def of(cls, request: Any, **given: Any) -> Self:
        """This kind from a validated HTTP request: each field ``given``, else the request's attribute of the same
        name (a list as a tuple). A field the request lacks and nobody gives is an :class:`AttributeError`: the key
        follows the request's own fields, so none is copied by hand and none can be left out unnoticed."""
        names = [f.name for f in dataclasses.fields(cls)]  # type: ignore[arg-type]
        unknown = set(given) - set(names)
        if unknown:
            raise TypeError(f"{cls.__name__} has no field(s) {sorted(unknown)}")
        values = {n: given[n] if n in given else getattr(request, n) for n in names}
        return cls(**{n: tuple(v) if isinstance(v, list) else v for n, v in values.items()})


# ------------------------------------------------------------------------------------- assessments


@dataclass(frozen=True, kw_only=True)
class ResolvedAssessment(Resolved):
    """What an assessment of curves depends on besides its curves: the vehicles' records (``to_dict()`` of a record
    or of a combination), their preset and saved ids (None where a vehicle is neither), the SRT options, the design
    options and the targets (name -> minimum SRT [g]), and the vehicles' input warnings (per vehicle, each a
    :class:`engine.vehicle.InputWarning` as a dict; None, and then absent from the key, when no vehicle has one).

    The warnings follow from the record and from how and where it was typed (a record typed as ``vehicles[1]`` warns
    of ``vehicles[1].weight_kn``; the same record built from a spec, or given as ``vehicle``, answers otherwise), so
    they are in the key: an answer cached for one is never served for the other."""

    __pydantic_config__ = _STRICT
    _omitted_when_none = ("warnings",)

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
    # the advisory speeds' and the speed profile's options (app.advisory.schemas.AdvisoryOptions)
    units: str
    desired_speed_kmh: float | None
    deceleration_mps2: float
    warnings: tuple[tuple[dict[str, Any], ...], ...] | None = None

    def __post_init__(self) -> None:
        if not len(self.vehicles) == len(self.presets) == len(self.saved_ids):
            raise ValueError(
                f"{len(self.vehicles)} vehicles, {len(self.presets)} presets and {len(self.saved_ids)} saved ids"
            )
        if self.warnings is not None and len(self.warnings) != len(self.vehicles):
            raise ValueError(f"{len(self.vehicles)} vehicles and {len(self.warnings)} lists of warnings")

    def vehicle_warnings(self, index: int) -> list[dict[str, Any]]:
        """Vehicle ``index``'s input warnings, as the answer writes them (``[]`` when none)."""
        return [] if self.warnings is None else list(self.warnings[index])

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
    answer names it; None, and then absent from the key, for curves given as JSON or LandXML), and when they came
    from a road file the reading summary (likewise)."""

    _omitted_when_none = ("warnings", "csv_dialect", "reading")

    curves: CurvesDigest
    csv_dialect: dict[str, str | bool] | None = None
    reading: dict[str, Any] | None = None  # a road file's reading summary (the answer names it)


@dataclass(frozen=True)
class RouteDocument:
    """A route's document as the key holds it: its format and SHA-256, the defaults of its curves' superelevation,
    posted speed and grade, the curve detection's options, which GPX parts are read and whether the elevations are
    used."""

    __pydantic_config__ = _STRICT

    format: str
    sha256: str
    superelevation_percent: float | None
    posted_speed_kmh: float | None
    detection: dict[str, Any]
    parts: str | None = None
    use_elevation: bool = True
    grade_percent: float | None = None


@dataclass(frozen=True, kw_only=True)
class ResolvedRoute(ResolvedAssessment):
    """A route's assessment: the assessment and the route document."""

    route: RouteDocument


# ------------------------------------------------------------------------------------- sweeps, limits


def _read_by_from_json_dict(cls: type, source: Any, handler: GetCoreSchemaHandler) -> core_schema.CoreSchema:
    """The pydantic schema of a resolved request whose JSON form is not its fields (a flat case): nested in another
    request validated by pydantic (:meth:`Resolved.from_json_dict`), it is read by its own ``from_json_dict``."""
    return core_schema.no_info_plain_validator_function(cls.from_json_dict)  # type: ignore[attr-defined]


def _refused(cls: type, reason: str) -> ValueError:
    return ValueError(f"the stored request is not a {cls.__name__}: {reason}")


#: what every target verdict is judged on (``TargetCheckOut.judged_on``); also in every key of a case
#: (:class:`ResolvedCase`), so an answer cached before the verdicts moved to the level road is never served again
JUDGED_ON = "level_road_srt"

_TARGETS = TypeAdapter(dict[str, float], config=ConfigDict(strict=True))


@dataclass(frozen=True, kw_only=True)
class ResolvedCase(Resolved):
    """One engine case (its vehicle record or combination, model, road, load and parameters, defaults filled) and the
    SRT targets it is judged against (name -> minimum SRT [g]; judged on the case's level-road SRT).

    Its JSON form is the case's :meth:`~engine.case.Case.to_dict` beside ``targets`` and ``targets_judged_on``, one
    flat object (the form the keys have always held). Nested in another request (a sweep's base case, the SRT of a
    curve speed) it is validated by :meth:`from_json_dict` too."""

    case: Case
    targets: dict[str, float]

    def to_json_dict(self) -> dict[str, Any]:
        return {**self.case.to_dict(), "targets": dict(self.targets), "targets_judged_on": JUDGED_ON}

    @classmethod
    def from_json_dict(cls, data: Any) -> Self:
        if not isinstance(data, dict):
            raise _refused(cls, "not an object")
        data = dict(data)
        try:
            targets = _TARGETS.validate_python(data.pop("targets"))
        except KeyError:
            raise _refused(cls, "targets: Field required") from None
        except ValidationError as exc:
            raise _refused(cls, f"targets: {exc.errors()[0]['msg']}") from None
        if data.pop("targets_judged_on", None) != JUDGED_ON:
            raise _refused(cls, f"targets_judged_on is not {JUDGED_ON!r}")
        try:
            case = Case.from_dict(data)
        except (KeyError, TypeError, ValueError) as exc:  # the engine's InvalidInput is a ValueError
            raise _refused(cls, f"case: {exc!r}") from None
        if case.to_dict().keys() != data.keys():  # nothing left over: the case's every field, and only those
            raise _refused(cls, f"case: the fields {sorted(data)} are not a case's")
        return cls(case=case, targets=targets)

    __get_pydantic_core_schema__ = classmethod(_read_by_from_json_dict)


@dataclass(frozen=True, kw_only=True)
class ResolvedSweep(Resolved):
    """A grid sweep: the base case and its targets, and the axes with their values, in the request's order (the first
    varies slowest)."""

    __pydantic_config__ = _STRICT

    _omitted_when_none = ("warnings",)

    case: ResolvedCase
    grid: dict[str, tuple[float, ...]]
    #: the vehicle's input warnings (InputWarning as dicts; None, and absent from the key, without any): see ResolvedSrt
    warnings: tuple[dict[str, Any], ...] | None = None

    @property
    def cases(self) -> int:
        """The number of cases (rows): the product of the axes' lengths."""
        return math.prod(len(values) for values in self.grid.values())

    def on(self, grid: dict[str, Any]) -> ResolvedSweep:
        """The same base case over another grid (a sub-grid of a job's block)."""
        return dataclasses.replace(self, grid={a: tuple(v) for a, v in grid.items()})


@dataclass(frozen=True, kw_only=True)
class ResolvedLimits(Resolved):
    """An inverse limit: the base case and its targets, the parameter searched, the target SRT [g], the
    overweights of the table [%] (None: no table) and where the target is applied (the level road or the request's
    own road)."""

    __pydantic_config__ = _STRICT

    case: ResolvedCase
    parameter: str
    target_srt_g: float
    overweights_percent: tuple[float, ...] | None
    limit_on: Literal["level_road", "road"]
    #: the vehicle's input warnings (InputWarning as dicts; None, and absent from the key, without any): see ResolvedSrt
    warnings: tuple[dict[str, Any], ...] | None = None

    _omitted_when_none = ("warnings",)


# ------------------------------------------------------------------------------------- single answers


@dataclass(frozen=True, kw_only=True)
class ResolvedSrt(Resolved):
    """An SRT (POST /v1/srt), or the SRT inside a curve speed, a minimum radius or a plot: the case and its targets,
    and whether (and at how many points) the curves are asked for. Without curves the number of points changes
    nothing and is None. Its JSON form is the case's (:class:`ResolvedCase`) with the two curve fields beside it, and
    the vehicle's input warnings (:class:`engine.vehicle.InputWarning` as dicts) when it has any: they follow from how
    and where the record was typed, not from the record alone (the same record built from a spec warns of nothing),
    so an answer with them is never served for one without, nor the other way round. Without any the key is what it
    always was."""

    base: ResolvedCase
    include_curves: bool = False
    curve_points: int | None = None
    warnings: tuple[dict[str, Any], ...] = ()

    def __post_init__(self) -> None:
        if not self.include_curves:  # without curves the points would only blur the key
            object.__setattr__(self, "curve_points", None)

    @property
    def case(self) -> Case:
        return self.base.case

    @property
    def targets(self) -> dict[str, float]:
        return self.base.targets

    def to_json_dict(self) -> dict[str, Any]:
        out = {**self.base.to_json_dict(), "include_curves": self.include_curves, "curve_points": self.curve_points}
        if self.warnings:
            out["warnings"] = [dict(w) for w in self.warnings]
        return out

    @classmethod
    def from_json_dict(cls, data: Any) -> Self:
        if not isinstance(data, dict):
            raise _refused(cls, "not an object")
        data = dict(data)
        curves, points = data.pop("include_curves", None), data.pop("curve_points", None)
        warnings = data.pop("warnings", [])
        if not (isinstance(warnings, list) and all(isinstance(w, dict) for w in warnings)):
            raise _refused(cls, "warnings: not a list of objects")
        if not isinstance(curves, bool):
            raise _refused(cls, "include_curves: not a boolean")
        if not (points is None or (isinstance(points, int) and not isinstance(points, bool))):
            raise _refused(cls, "curve_points: not an integer")
        return cls(
            base=ResolvedCase.from_json_dict(data), include_curves=curves, curve_points=points, warnings=tuple(warnings)
        )

    __get_pydantic_core_schema__ = classmethod(_read_by_from_json_dict)


@dataclass(frozen=True, kw_only=True)
class ResolvedCurveSpeed(Resolved):
    """A maximum curve speed (Eq. 9.1): the radius [m] and either a given SRT [g] or the SRT request (the other
    None)."""

    __pydantic_config__ = _STRICT

    radius_m: float
    srt: float | None
    srt_request: ResolvedSrt | None


@dataclass(frozen=True, kw_only=True)
class ResolvedMinRadius(Resolved):
    """A minimum radius (Eq. 9.3 against Eq. 9.2): the design speed [km/h], the superelevation [%], a given side
    friction or the design standard (and bound) it is read from, and either a given SRT [g] or the SRT request on the
    curve's bank."""

    __pydantic_config__ = _STRICT

    design_speed_kmh: float
    superelevation_percent: float
    side_friction: float | None
    design_standard: str
    side_friction_bound: str | None
    srt: float | None
    srt_request: ResolvedSrt | None


@dataclass(frozen=True, kw_only=True)
class ResolvedCurvesPlot(Resolved):
    """A figure against ay/g: the SRT request with its curves, the figure, the label and the drawing's version."""

    __pydantic_config__ = _STRICT

    srt_request: ResolvedSrt
    figure: str
    label: str
    svg_version: int


@dataclass(frozen=True, kw_only=True)
class ResolvedMinRadiusPlot(Resolved):
    """The minimum radius against the design speed: the SRT request on the curve's bank, the speeds plotted (lowest
    and highest [km/h], and how many), the design standard and bound, the label and the drawing's version."""

    __pydantic_config__ = _STRICT

    srt_request: ResolvedSrt
    speeds_kmh: tuple[float, float, int]
    design_standard: str
    side_friction_bound: str | None
    label: str
    svg_version: int


@dataclass(frozen=True, kw_only=True)
class ResolvedSuperelevation(Resolved):
    """A curve's superelevation by a design standard's distribution: every input of the request."""

    __pydantic_config__ = _STRICT

    design_standard: str
    side_friction_bound: str | None
    design_speed_kmh: float
    radius_m: float
    max_superelevation_percent: float


@dataclass(frozen=True, kw_only=True)
class ResolvedSuperelevationTable(Resolved):
    """A superelevation table: the standard, bound, speed and e_max, and its radii (given, or their span and
    count)."""

    __pydantic_config__ = _STRICT

    design_standard: str
    side_friction_bound: str | None
    design_speed_kmh: float
    max_superelevation_percent: float
    radii_m: tuple[float, ...] | None
    radius_max_m: float | None
    points: int


@dataclass(frozen=True, kw_only=True)
class ResolvedBuild(Resolved):
    """A vehicle or a combination built from its spec (every input, defaults filled: the component library is the
    engine's, versioned with it). Its JSON form is ``{"spec": ...}`` or ``{"combination_spec": ...}``."""

    spec: VehicleSpec | CombinationSpec

    def to_json_dict(self) -> dict[str, Any]:
        kind = "combination_spec" if isinstance(self.spec, CombinationSpec) else "spec"
        return {kind: self.spec.to_dict()}

    @classmethod
    def from_json_dict(cls, data: Any) -> Self:
        if not isinstance(data, dict) or len(data) != 1 or not data.keys() <= {"spec", "combination_spec"}:
            raise _refused(cls, "not an object of one spec or combination_spec")
        ((kind, spec),) = data.items()
        try:
            built = (CombinationSpec if kind == "combination_spec" else VehicleSpec).from_dict(spec)
        except (KeyError, TypeError, ValueError) as exc:
            raise _refused(cls, f"{kind}: {exc!r}") from None
        return cls(spec=built)

    __get_pydantic_core_schema__ = classmethod(_read_by_from_json_dict)


@dataclass(frozen=True, kw_only=True)
class ResolvedPayloadTable(Resolved):
    """A payload table (TERNZ style): the spec built from (as :class:`ResolvedBuild`), the unit, the target SRT [g],
    the payload, the heights [m] and masses [kg] asked for (None: the defaults) and the rows."""

    __pydantic_config__ = _STRICT

    build: ResolvedBuild
    unit_index: int | None
    target_srt_g: float
    payload_index: int
    load_heights_m: tuple[float, ...] | None
    payload_masses_kg: tuple[float, ...] | None
    rows: int

    def to_json_dict(self) -> dict[str, Any]:
        out = super().to_json_dict()
        return {**out.pop("build"), **out}  # the spec beside the options: one flat object, as the request's
