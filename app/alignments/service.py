"""Alignment assessment (POST /v1/alignments/assess and its uploads): curves -> engine -> rows, as columns.

The curves come from a JSON list (read into columns by :mod:`app.alignments.curves`), a CSV text or a LandXML document
(:mod:`app.formats.alignment_io`); all three become one :class:`~app.formats.alignment_io.CurveTable`, so the same
curves share one cache entry whatever form they came in. The engine assesses each vehicle on arrays
(:func:`engine.road.curves.assess_alignment`: one batched solve of the distinct superelevation/grade pairs); the answer
is kept as those arrays (:class:`AlignmentAnswer`) and rendered to JSON or CSV by :mod:`app.alignments.rows` (the
renderers a job's result uses too). The answer (at most 10,000 rows) is rendered whole and cached as bytes, and served
by the fast path on a repeat; larger work goes to a job.

The assessment of a curve table is public for the routes (:mod:`app.routes.service`: a route's curves are assessed as
an alignment's) and the jobs (:mod:`app.jobs.op_alignments`): :class:`AlignmentJob`, :func:`resolved_assessment`,
:func:`solve_alignment`, :func:`check_alignment`, :func:`resolve_assessment_request`, :func:`as_fleet_error`.
"""

from __future__ import annotations

import dataclasses
import hashlib
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, TypeVar

import numpy as np
import orjson
from fastapi import Request
from fastapi.exceptions import RequestValidationError
from pydantic import BaseModel, ValidationError
from starlette.concurrency import run_in_threadpool

from app.alignments.advice import advise, curve_places
from app.alignments.answer import AlignmentAnswer, VehicleAnswer, vehicle_answer
from app.alignments.curves import curves_from_json
from app.alignments.rows import render
from app.alignments.schemas import MAX_ROWS, MAX_VEHICLES, AlignmentRequest, as_a_job
from app.compute import solvers
from app.compute.cache import ResultCache
from app.compute.resolved import CurvesDigest, ResolvedAlignment, ResolvedAssessment
from app.compute.results import Computed, cached
from app.formats.alignment_io import MAX_CURVES, AlignmentFormatError, CurveOverride, CurveTable, read_csv
from app.formats.jsonpieces import loads_in_pieces
from app.formats.road_file import ROAD_READERS, read_road_document
from app.http.negotiation import CSV_TYPE, JSON_TYPE
from app.http.problems import InvalidAlignment, request_error
from app.http.strictjson import refuse_duplicate_keys
from app.metrics import SOLVE_SECONDS
from app.settings import Settings
from app.srt.service import level_case, resolve_targets
from app.vehicles.resolve import ResolvedVehicle, VehicleRequest, resolve_request
from engine import Case, InvalidInput, LoadCase, RolloverError
from engine.models import rollover_threshold
from engine.road import (
    AlignmentColumns,
    assess_alignment,
    bank_grade_pairs,
    check_deceleration,
    superelevation_used,
)

Req = TypeVar("Req", bound=BaseModel)

_PLACEHOLDER = [{"id": "placeholder", "radius_m": 100.0}]  # stands for the curves while the rest is validated


# ------------------------------------------------------------------------------------------ reading


def parse_json_request(body: bytes) -> tuple[AlignmentRequest, CurveTable | None]:
    """The JSON request, validated: its ``curves`` (if any) read into columns by
    :func:`app.alignments.curves.curves_from_json` (fast), everything else by the request model itself. Runs in a worker
    thread: 100,000 curves are 12 MB, parsed a slice of curves at a time
    (:func:`app.formats.jsonpieces.loads_in_pieces`: the event loop is not held up meanwhile). Not the columnar reader
    of a job's curves (:mod:`app.alignments.json_curves`): at this size (10,000 curves, 1 MB) orjson and a dict per
    curve take half its time (10.6 ms against 14-20 ms, measured)."""
    try:
        data = loads_in_pieces(body, ("curves",))
    except orjson.JSONDecodeError as exc:
        raise RequestValidationError([{"type": "json_invalid", "loc": ("body",), "msg": f"JSON: {exc}"}]) from None
    refuse_duplicate_keys(body, data)
    return validate_request_data(data)


def validate_request_data(
    data: Any,
    *,
    model: type[AlignmentRequest] = AlignmentRequest,
    max_curves: int = MAX_CURVES,
    curves: CurveTable | None = None,
) -> tuple[AlignmentRequest, CurveTable | None]:
    """:func:`parse_json_request` of the parsed JSON (``model`` and ``max_curves``: a job's larger limits).
    ``curves``: the ``curves`` already read from the body's text (:mod:`app.alignments.json_curves`, valid), ``data``'s
    list then empty: the rest of the request is validated as always, with the placeholder."""
    has_curves = isinstance(data, dict) and "curves" in data
    try:
        req = model.model_validate({**data, "curves": _PLACEHOLDER} if has_curves else data)
    except ValidationError as exc:
        raise RequestValidationError(
            [{**e, "loc": ("body", *e["loc"])} for e in exc.errors(include_url=False)]
        ) from None
    if has_curves and curves is None:
        curves = curves_from_json(data["curves"], max_curves)
    return req, curves


def read_curves(
    req: AlignmentRequest, curves: CurveTable | None, source_field: str | None, max_curves: int = MAX_CURVES
) -> CurveTable:
    """The curves from whichever of ``curves`` (already read), ``csv`` or a road file (``landxml``: a field named as
    in :data:`app.formats.road_file.ROAD_READERS`) the request has.

    ``source_field`` names where a document came from for the error (``body`` for a raw upload)."""
    if curves is not None:
        return curves
    # a road file: the first of the readers' fields the request has (exactly one document is given)
    source = "csv" if req.csv is not None else next(k for k in ROAD_READERS if getattr(req, k, None) is not None)
    try:
        if source == "csv":
            return read_csv(req.csv, max_curves=max_curves)
        x = getattr(req, source)
        overrides = {
            k: CurveOverride(v.superelevation_percent, v.grade_percent, v.posted_speed_kmh)
            for k, v in (x.curve_overrides or {}).items()
        }
        return read_road_document(
            source,
            x.document,
            superelevation_percent=x.superelevation_percent,
            grade_percent=x.grade_percent,
            posted_speed_kmh=x.posted_speed_kmh,
            overrides=overrides,
            max_curves=max_curves,
            profile=x.profile,
        )
    except AlignmentFormatError as exc:
        where = source_field or ("csv" if source == "csv" else f"{source}.document")
        location, column = exc.location, exc.field
        if exc.location == "curve_overrides":
            where, location = f"{source}.curve_overrides", None
        elif exc.location == "profile":  # the query's (an upload) or the request's option
            where, location, column = ("profile" if source_field else f"{source}.profile"), None, None
        reason = str(exc).removeprefix(f"{exc.location}: ") if exc.location else str(exc)
        if max_curves == MAX_CURVES and reason.startswith("more than"):  # the synchronous request's limit
            reason = as_a_job(reason)
        raise InvalidAlignment(reason, source=where, location=location, column=column) from None


def _digest(t: CurveTable) -> str:
    """SHA-256 of the curves (ids, then the float64 columns with -0.0 and every nan made one value; a road file's
    bend columns too)."""
    h = hashlib.sha256(orjson.dumps(t.ids))
    bends = () if t.bends is None else tuple(t.bends.columns.values())
    for a in (t.radius_m, t.superelevation_percent, t.grade_percent, t.posted_speed_kmh, t.station_m, *bends):
        h.update(np.where(np.isnan(a), np.nan, a + 0.0).astype("<f8").tobytes())
    return h.hexdigest()


@dataclass(frozen=True)
class AlignmentJob:
    """A resolved alignment request: what the answer depends on (``resolved``, which holds its key: an alignment's, or
    a route's for the route's curves) and the objects to compute it from."""

    resolved: ResolvedAssessment
    vehicles: list[Any]
    curves: CurveTable
    source: str  # the request field the curves came from, for an error in a document (``csv``, ``body``, ...)
    # each curve's start station and length [m], deflection [deg] and, for a route, the part it lies on, for the
    # advice (None: a road file's, :func:`app.alignments.advice.curve_places`; a route gives its found curves')
    places: tuple[np.ndarray, ...] | None = None

    @property
    def rows(self) -> int:
        return len(self.curves) * len(self.vehicles)

    def curve_places(self) -> tuple[np.ndarray | None, ...]:
        return curve_places(self.curves) if self.places is None else self.places


def resolved_assessment(req: Any, vehicles: Sequence[ResolvedVehicle], settings: Settings) -> ResolvedAssessment:
    """What an assessment's answer depends on besides its curves (part of its cache key): the vehicles' records
    (and preset ids, saved ids), the SRT options, the design standard, e_max and the targets. ``req`` is an
    alignment or a route request (they share these fields), ``vehicles`` its resolved vehicles."""
    check_deceleration(req.deceleration_mps2)  # a truck's braking limit: a 422 naming the field
    warnings = tuple(tuple(dataclasses.asdict(w) for w in v.warnings) for v in vehicles)
    return ResolvedAssessment(
        vehicles=tuple(v.vehicle.to_dict() for v in vehicles),
        presets=tuple(v.preset for v in vehicles),
        saved_ids=tuple(v.saved_id for v in vehicles),
        model=req.model,
        stage=req.stage,
        trailer_angle_deg=req.trailer_angle_deg,
        load=req.load.model_dump(),
        rear_llt_limit=req.rear_llt_limit,
        design_standard=req.design_standard,
        side_friction_bound=req.bound,
        max_superelevation_percent=req.max_superelevation_percent,
        targets=resolve_targets(req.targets, settings),
        units=req.units,
        desired_speed_kmh=req.desired_speed_kmh,
        deceleration_mps2=req.deceleration_mps2,
        warnings=warnings if any(warnings) else None,  # None: the keys of answers without any stay as they were
    )


def resolve_alignment(
    vr: VehicleRequest[AlignmentRequest],
    curves: CurveTable | None,
    settings: Settings,
    source_field: str | None = None,
    *,
    max_curves: int = MAX_CURVES,
    max_rows: int = MAX_ROWS,
) -> AlignmentJob:
    """The fully resolved request: the vehicles' records (and preset ids), the options, and the curves (at most
    ``max_curves`` and ``max_rows`` rows: a job's limits are larger than a request's)."""
    req, refs = vr.body, vr.vehicles
    which = "vehicle" if req.vehicle is not None else "vehicles"
    table = read_curves(req, curves, source_field, max_curves)
    if len(table) * len(refs) > max_rows:
        rows = f"{len(table)} curves x {len(refs)} vehicles = {len(table) * len(refs)} rows; at most {max_rows}"
        if max_rows == MAX_ROWS:
            raise request_error(which, as_a_job(f"{rows} per request"))
        raise request_error(which, f"{rows} per job (split the alignment or the vehicles)")
    vehicles = vr.engine_vehicles
    resolved = ResolvedAlignment(
        **resolved_assessment(req, refs, settings).assessment_fields(),
        curves=CurvesDigest(len(table), _digest(table)),
        # the answer names it; the keys of curves and LandXML stay as they were (None: not in the key)
        csv_dialect=None if table.dialect is None else table.dialect.as_dict(),
        reading=table.reading,
    )
    road = next((k for k in ROAD_READERS if getattr(req, k, None) is not None), "landxml")
    source = source_field or ("curves" if curves is not None else "csv" if req.csv is not None else f"{road}.document")
    return AlignmentJob(resolved, vehicles, table, source)


# ---------------------------------------------------------------------------------------- computing


def _located(exc: InvalidInput, job: AlignmentJob, index: int) -> Exception:
    """The engine's error with its field as a request path (``curves[3].x`` -> ``curves.3.x``, with the curve's id
    in the message), at the curve's row or element for a document, and, among several vehicles, with the vehicle's
    index."""
    field, message = exc.field or "", str(exc)
    if field.startswith("curves["):
        i = int(field[len("curves[") : field.index("]")])
        column = field.split("].", 1)[1]
        reason = message.removeprefix(f"curves[{i}]").lstrip(": ").removeprefix(f"{field} ")
        t = job.curves
        if t.where is not None:  # a CSV or LandXML document: its row or element
            return InvalidAlignment(reason, source=job.source, location=t.where[i], column=column)
        return type(exc)(f"{message} (curve {t.ids[i]!r})", field=f"curves.{i}.{column}", value=exc.value)
    if len(job.vehicles) > 1 and field and "." not in field:
        return type(exc)(f"vehicles[{index}]: {message}", field=f"vehicles.{index}.{field}", value=exc.value)
    return exc


def as_fleet_error(exc: Exception, fleet: str | None, resolved: ResolvedAssessment) -> Exception:
    """An error named after a vehicle the request took from a fleet (``vehicles.1.front_track_m``) names the fleet,
    the request's own field, and says which member in the message."""
    field = getattr(exc, "field", None) or ""
    if fleet is None or not isinstance(exc, InvalidInput) or not field.startswith("vehicles."):
        return exc
    index = int(field.split(".")[1])
    member = resolved.saved_ids[index] or resolved.presets[index] or f"#{index}"
    text = str(exc).removeprefix(f"vehicles[{index}]: ")
    return type(exc)(f"fleet {fleet}, member {index} ({member}): {text}", field="fleet", value=fleet)


def assessment_case(resolved: ResolvedAssessment, vehicle: Any) -> Case:
    """The SRT case of one vehicle of a resolved assessment (its options; every curve has its own road)."""
    r = resolved
    return Case(
        vehicle,
        r.model,
        r.stage,
        trailer_angle_deg=r.trailer_angle_deg,
        load=LoadCase(**r.load),
        rear_llt_limit=r.rear_llt_limit,
    )


def assess_table(case: Case, resolved: ResolvedAssessment, t: CurveTable, solve_pairs=None) -> AlignmentColumns:
    """:func:`engine.road.assess_alignment` of the curves ``t`` with the resolved assessment's design options, its
    blocks on the solver threads (:mod:`app.compute.solvers`)."""
    return assess_alignment(
        case,
        t.radius_m,
        t.superelevation_percent,
        t.grade_percent,
        t.posted_speed_kmh,
        design_standard=resolved.design_standard,
        side_friction_bound=resolved.side_friction_bound,
        max_superelevation_percent=resolved.max_superelevation_percent,
        solve_pairs=solve_pairs,
        block_map=solvers.block_map,
    )


def _no_curves() -> AlignmentColumns:
    """The assessment of no curve: a road file whose alignments have none (a straight road) answers with no rows."""
    f, b, i = np.empty(0), np.empty(0, dtype=bool), np.empty(0, dtype=np.intp)
    return AlignmentColumns(
        radius_m=f,
        superelevation_percent=f,
        superelevation_derived=b,
        grade_percent=f,
        posted_speed_kmh=f,
        srt_g=f,
        rollover_speed_kmh=f,
        side_friction_speed_kmh=f,
        side_friction=f,
        side_friction_clamped=b,
        safe_speed_kmh=f,
        governed_by=i,
        margin_kmh=f,
        flagged=b,
        standard_min_radius_m=f,
        meets_standard_min_radius=i,
        error=i,
        errors=[],
        distinct_cases=0,
    )


def _vehicle_answer(job: AlignmentJob, index: int, solve_pairs=None, places=None) -> VehicleAnswer:
    """``places``: :meth:`AlignmentJob.curve_places` (None: found here), the same for every vehicle."""
    r = job.resolved
    case = assessment_case(r, job.vehicles[index])
    try:
        cols = assess_table(case, r, job.curves, solve_pairs) if len(job.curves) else _no_curves()
    except InvalidInput as exc:
        raise _located(exc, job, index) from None
    places = job.curve_places() if places is None else places
    return vehicle_answer(r, index, cols, level_road_srt(case), advise(r, cols, *places))


def level_road_srt(case: Case) -> float:
    """The vehicle's level-road SRT, the one its rows' targets are judged on (:func:`app.srt.service.level_case`):
    one more solve per vehicle [g]; nan when the level case is refused."""
    try:
        return rollover_threshold(level_case(case)).srt
    except RolloverError:
        return math.nan


def solve_alignment(job: AlignmentJob, solve_pairs=None) -> AlignmentAnswer:
    """Every curve for every vehicle (blocking: called in a worker thread); ``solve_pairs``: see
    :func:`engine.road.curves.assess_alignment` (a job's parts remember the pairs they solved); the blocks of the
    pairs' solve and of the side-friction speeds run on the solver threads (:mod:`app.compute.solvers`)."""
    started = time.perf_counter()
    places = job.curve_places() if job.vehicles else None  # the road's, once for every vehicle
    vehicles = [_vehicle_answer(job, k, solve_pairs, places) for k in range(len(job.vehicles))]
    answer = AlignmentAnswer(job.resolved, job.curves, vehicles)
    SOLVE_SECONDS.labels("alignments", job.resolved.model or "default").observe(time.perf_counter() - started)
    return answer


@dataclass(frozen=True)
class AlignmentPairs:
    """The superelevation each curve uses [%], the distinct (superelevation, grade) pairs of the curves (n, 2) and
    each curve's index into them (:func:`engine.road.bank_grade_pairs`)."""

    superelevation_percent: np.ndarray
    pairs: np.ndarray
    inverse: np.ndarray

    @property
    def distinct(self) -> int:
        """The number of distinct pairs (the summary's ``distinct_srt_solves``)."""
        return len(self.pairs)


def check_alignment(job: AlignmentJob) -> AlignmentPairs:
    """What :func:`solve_alignment` refuses for the request as a whole, found without solving every curve (a job
    refuses it at submission): a vehicle the model cannot use, a superelevation that cannot be derived. Raises the
    same errors, located the same way. Returns the curves' superelevation/grade pairs, which a job solves next (on a
    million curves finding them takes about 0.4 s: once)."""
    r, t = job.resolved, job.curves
    try:
        e = superelevation_used(
            t.radius_m,
            t.superelevation_percent,
            t.posted_speed_kmh,
            design_standard=r.design_standard,
            side_friction_bound=r.side_friction_bound,
            max_superelevation_percent=r.max_superelevation_percent,
        )
    except InvalidInput as exc:
        raise _located(exc, job, 0) from None
    first = AlignmentJob(r, job.vehicles, t.sliced(0, 1), job.source)
    for k in range(len(job.vehicles)):
        _vehicle_answer(first, k)  # the refusals of the vehicle and the options, on one curve
    return AlignmentPairs(e, *bank_grade_pairs(e, t.grade_percent))


# ---------------------------------------------------------------------------------------- the flow


async def resolve_assessment_request(
    request: Request, req: Req, settings: Settings, what: str = "an assessment"
) -> VehicleRequest[Req]:
    """``req`` (an alignment or a route request) and its vehicles resolved, a fleet's members among them
    (:func:`app.vehicles.resolve.resolve_request`); a fleet larger than ``what`` takes (:data:`MAX_VEHICLES`) is
    a 422 naming ``fleet``."""
    vr = await resolve_request(request, req, settings)
    fleet = req.fleet  # type: ignore[attr-defined]
    if fleet is not None and len(vr.vehicles) > MAX_VEHICLES:
        raise request_error(
            "fleet", f"fleet {fleet} has {len(vr.vehicles)} vehicles; {what} takes at most {MAX_VEHICLES}"
        )
    return vr


async def compute_alignment(
    cache: ResultCache,
    vr: VehicleRequest[AlignmentRequest],
    curves: CurveTable | None,
    settings: Settings,
    *,
    csv: bool,
    source_field: str | None = None,
) -> Computed:
    """The assessment as a cached body (at most :data:`~app.alignments.schemas.MAX_ROWS` rows: built whole)."""
    fleet = vr.body.fleet
    job = await run_in_threadpool(resolve_alignment, vr, curves, settings, source_field)
    operation = "alignments-csv" if csv else "alignments"

    async def produce() -> bytes:
        try:  # solved and rendered in one worker thread
            return await run_in_threadpool(lambda: b"".join(render(solve_alignment(job), csv)))
        except InvalidInput as exc:
            raise as_fleet_error(exc, fleet, job.resolved) from None

    return await cached(cache, operation, job.resolved, produce, CSV_TYPE if csv else JSON_TYPE)
