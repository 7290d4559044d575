"""Alignment assessment (POST /v1/alignments/assess and its uploads): curves -> engine -> rows, as columns.

The curves come from a JSON list (read into columns by :mod:`app.curves`), a CSV text or a LandXML document
(:mod:`app.formats.alignment_io`); all three become one :class:`~app.formats.alignment_io.CurveTable`, so the same
curves share one cache entry whatever form they came in. The engine assesses each vehicle on arrays
(:func:`engine.assessment.assess_alignment`: one batched solve of the distinct superelevation/grade pairs); the answer
is kept as those arrays (:class:`AlignmentAnswer`) and rendered to JSON or CSV in chunks. A small answer is rendered
whole and cached as bytes (and served by the fast path on a repeat); a large one is streamed, never built as one
document, and cached by reference, as its arrays. Streamed or whole, the bytes are the same.
"""

from __future__ import annotations

import hashlib
import math
import time
from collections.abc import Iterator
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
import orjson
from fastapi import Request
from fastapi.exceptions import RequestValidationError
from pydantic import ValidationError
from starlette.concurrency import run_in_threadpool

from app.compute import solvers
from app.compute.cache import ResultCache, cache_key
from app.compute.results import Computed, Streamed
from app.curves import curves_from_json
from app.formats.alignment_io import MAX_CURVES, AlignmentFormatError, CurveOverride, CurveTable, read_csv, read_landxml
from app.formats.json_rows import RawJson, json_objects
from app.formats.jsonpieces import loads_in_pieces
from app.formats.tables import Text, csv_line, csv_lines_of_columns, target_columns, target_columns_of
from app.http.negotiation import CSV_TYPE, JSON_TYPE
from app.http.problems import InvalidAlignment, request_error
from app.metrics import CACHE_LOOKUPS, SOLVE_SECONDS
from app.schemas.alignments import MAX_ROWS, MAX_VEHICLES, AlignmentRequest
from app.settings import Settings
from app.srt.service import resolve_targets, target_checks_json_many, target_checks_many
from app.vehicles.refs import SavedRef, resolve_vehicle, resolve_vehicle_refs
from engine import ENGINE_VERSION
from engine.case import Case, LoadCase
from engine.errors import InvalidInput
from engine.road import (
    GOVERNED_BY,
    AlignmentColumns,
    assess_alignment,
    bank_grade_pairs,
    superelevation_used,
    tilt_table_angle_deg,
)
from engine.vehicle import Vehicle

#: answers with more rows than this are streamed (and cached by reference), never built whole
STREAM_ROWS = 5_000
ROWS_PER_CHUNK = 1_000
ROW_COLUMNS = (
    "id",
    "station_m",
    "radius_m",
    "superelevation_percent",
    "superelevation_source",
    "grade_percent",
    "srt_g",
    "tilt_table_angle_deg",
)
SPEED_COLUMNS = (
    "rollover_speed_kmh",
    "side_friction_speed_kmh",
    "side_friction",
    "side_friction_clamped",
    "safe_speed_kmh",
    "governed_by",
    "posted_speed_kmh",
    "margin_kmh",
    "flagged",
    "standard_min_radius_m",
    "meets_standard_min_radius",
    "error",
)
_PLACEHOLDER = [{"id": "placeholder", "radius_m": 100.0}]  # stands for the curves while the rest is validated


# ------------------------------------------------------------------------------------------ reading


def parse_json_request(body: bytes) -> tuple[AlignmentRequest, CurveTable | None]:
    """The JSON request, validated: its ``curves`` (if any) read into columns by :func:`app.curves.curves_from_json`
    (fast), everything else by the request model itself. Runs in a worker thread: 100,000 curves are 12 MB, parsed a
    slice of curves at a time (:func:`app.formats.jsonpieces.loads_in_pieces`: the event loop is not held up
    meanwhile)."""
    try:
        data = loads_in_pieces(body, ("curves",))
    except orjson.JSONDecodeError as exc:
        raise RequestValidationError([{"type": "json_invalid", "loc": ("body",), "msg": f"JSON: {exc}"}]) from None
    return validate_request_data(data)


def validate_request_data(
    data: Any, *, model: type[AlignmentRequest] = AlignmentRequest, max_curves: int = MAX_CURVES
) -> tuple[AlignmentRequest, CurveTable | None]:
    """:func:`parse_json_request` of the parsed JSON (``model`` and ``max_curves``: a job's larger limits)."""
    curves = None
    has_curves = isinstance(data, dict) and "curves" in data
    try:
        req = model.model_validate({**data, "curves": _PLACEHOLDER} if has_curves else data)
    except ValidationError as exc:
        raise RequestValidationError(
            [{**e, "loc": ("body", *e["loc"])} for e in exc.errors(include_url=False)]
        ) from None
    if has_curves:
        curves = curves_from_json(data["curves"], max_curves)
    return req, curves


def read_curves(
    req: AlignmentRequest, curves: CurveTable | None, source_field: str | None, max_curves: int = MAX_CURVES
) -> CurveTable:
    """The curves from whichever of ``curves`` (already read), ``csv``, ``landxml`` the request has.

    ``source_field`` names where a document came from for the error (``body`` for a raw upload)."""
    if curves is not None:
        return curves
    source = "csv" if req.csv is not None else "landxml"
    try:
        if source == "csv":
            return read_csv(req.csv, max_curves=max_curves)
        x = req.landxml
        overrides = {
            k: CurveOverride(v.superelevation_percent, v.grade_percent, v.posted_speed_kmh)
            for k, v in (x.curve_overrides or {}).items()
        }
        return read_landxml(
            x.document,
            superelevation_percent=x.superelevation_percent,
            grade_percent=x.grade_percent,
            posted_speed_kmh=x.posted_speed_kmh,
            overrides=overrides,
            max_curves=max_curves,
        )
    except AlignmentFormatError as exc:
        where = source_field or ("csv" if source == "csv" else "landxml.document")
        location = exc.location
        if exc.location == "curve_overrides":
            where, location = "landxml.curve_overrides", None
        reason = str(exc).removeprefix(f"{exc.location}: ") if exc.location else str(exc)
        raise InvalidAlignment(reason, source=where, location=location, column=exc.field) from None


def _digest(t: CurveTable) -> str:
    """SHA-256 of the curves (ids, then the float64 columns with -0.0 and every nan made one value)."""
    h = hashlib.sha256(orjson.dumps(t.ids))
    for a in (t.radius_m, t.superelevation_percent, t.grade_percent, t.posted_speed_kmh, t.station_m):
        h.update(np.where(np.isnan(a), np.nan, a + 0.0).astype("<f8").tobytes())
    return h.hexdigest()


@dataclass(frozen=True)
class AlignmentJob:
    """A resolved alignment request: what the answer depends on (``resolved``, hashed into the key) and the
    objects to compute it from."""

    resolved: dict[str, Any]
    vehicles: list[Any]
    curves: CurveTable
    source: str  # the request field the curves came from, for an error in a document (``csv``, ``body``, ...)

    @property
    def rows(self) -> int:
        return len(self.curves) * len(self.vehicles)


def resolved_assessment(req: Any, refs: list[Any], vehicles: list[Vehicle], settings: Settings) -> dict[str, Any]:
    """What an assessment's answer depends on besides its curves (part of its cache key): the vehicles' records
    (and preset ids, saved ids), the SRT options, the design standard, e_max and the targets. ``req`` is an
    alignment or a route request (they share these fields)."""
    return {
        "vehicles": [v.to_dict() for v in vehicles],
        "presets": [r if isinstance(r, str) else None for r in refs],
        "saved_ids": [r.id if isinstance(r, SavedRef) else None for r in refs],
        "model": req.model,
        "stage": req.stage,
        "trailer_angle_deg": req.trailer_angle_deg,
        "load": req.load.model_dump(),
        "rear_llt_limit": req.rear_llt_limit,
        "design_standard": req.design_standard,
        "side_friction_bound": req.bound,
        "max_superelevation_percent": req.max_superelevation_percent,
        "targets": resolve_targets(req.targets, settings),
    }


def resolve_alignment(
    req: AlignmentRequest,
    curves: CurveTable | None,
    settings: Settings,
    source_field: str | None = None,
    *,
    max_curves: int = MAX_CURVES,
    max_rows: int = MAX_ROWS,
) -> AlignmentJob:
    """The fully resolved request: the vehicles' records (and preset ids), the options, and the curves (at most
    ``max_curves`` and ``max_rows`` rows: a job's limits are larger than a request's)."""
    which = "vehicle" if req.vehicle is not None else "vehicles"
    refs = [req.vehicle] if which == "vehicle" else list(req.vehicles)
    table = read_curves(req, curves, source_field, max_curves)
    if len(table) * len(refs) > max_rows:
        raise request_error(
            which,
            f"{len(table)} curves x {len(refs)} vehicles = {len(table) * len(refs)} rows; at most {max_rows} per "
            "request (split the alignment or the vehicles)",
        )
    vehicles = [resolve_vehicle(r) for r in refs]
    resolved = {
        **resolved_assessment(req, refs, vehicles, settings),
        "curves": {"count": len(table), "sha256": _digest(table)},
    }
    source = source_field or ("curves" if curves is not None else "csv" if req.csv is not None else "landxml.document")
    return AlignmentJob(resolved, vehicles, table, source)


# ---------------------------------------------------------------------------------------- computing


@dataclass(frozen=True)
class VehicleAnswer:
    """One vehicle's rows as arrays; what is shared by the curves of one SRT is kept once per distinct SRT."""

    index: int
    preset: str | None
    saved_id: str | None
    columns: AlignmentColumns
    pair_of_row: np.ndarray  # distinct-SRT index of each row, for the shared tilt angle and target checks
    srts: np.ndarray  # the distinct SRTs [g]; -1 for the rows without one
    tilt_deg: np.ndarray  # per distinct SRT [deg]; nan without an SRT
    targets: dict[str, float]

    @cached_property
    def tilt(self) -> list[float | None]:  # per distinct SRT
        return [None if math.isnan(a) else a for a in self.tilt_deg.tolist()]

    @cached_property
    def checks(self) -> list[list[dict[str, Any]]]:  # per distinct SRT: its target checks as dicts
        solved = (self.srts >= 0).tolist()
        return [c if ok else [] for c, ok in zip(target_checks_many(self.srts, self.targets), solved, strict=True)]

    @cached_property
    def checks_json(self) -> np.ndarray:  # per distinct SRT: the JSON of its ``checks`` (an object array, to index)
        out = np.array(target_checks_json_many(self.srts, self.targets), dtype=object)
        out[self.srts < 0] = b"[]"
        return out


@dataclass(frozen=True)
class AlignmentAnswer:
    """Every curve for every vehicle, as arrays: rendered to JSON or CSV in chunks."""

    resolved: dict[str, Any]
    curves: CurveTable
    vehicles: list[VehicleAnswer]

    @property
    def nbytes(self) -> int:  # what keeping it costs (the cache bounds answers kept by reference by it)
        per_row = 20 * 8
        return 2_000 + len(self.curves) * (per_row * len(self.vehicles) + 48)


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


def as_fleet_error(exc: Exception, fleet: str | None, resolved: dict[str, Any]) -> Exception:
    """An error named after a vehicle the request took from a fleet (``vehicles.1.front_track_m``) names the fleet,
    the request's own field, and says which member in the message."""
    field = getattr(exc, "field", None) or ""
    if fleet is None or not isinstance(exc, InvalidInput) or not field.startswith("vehicles."):
        return exc
    index = int(field.split(".")[1])
    member = resolved["saved_ids"][index] or resolved["presets"][index] or f"#{index}"
    text = str(exc).removeprefix(f"vehicles[{index}]: ")
    return type(exc)(f"fleet {fleet}, member {index} ({member}): {text}", field="fleet", value=fleet)


def _vehicle_answer(job: AlignmentJob, index: int, solve_pairs=None) -> VehicleAnswer:
    r = job.resolved
    case = Case(
        job.vehicles[index],
        r["model"],
        r["stage"],
        trailer_angle_deg=r["trailer_angle_deg"],
        load=LoadCase(**r["load"]),
        rear_llt_limit=r["rear_llt_limit"],
    )
    t = job.curves
    try:
        cols = assess_alignment(
            case,
            t.radius_m,
            t.superelevation_percent,
            t.grade_percent,
            t.posted_speed_kmh,
            design_standard=r["design_standard"],
            side_friction_bound=r["side_friction_bound"],
            max_superelevation_percent=r["max_superelevation_percent"],
            solve_pairs=solve_pairs,
            block_map=solvers.block_map,
        )
    except InvalidInput as exc:
        raise _located(exc, job, index) from None
    srts, pair_of_row = np.unique(np.where(np.isnan(cols.srt_g), -1.0, cols.srt_g), return_inverse=True)
    # per distinct SRT (-1: none), on arrays: 100,000 distinct SRTs one by one took a second
    tilt = np.where(srts >= 0, tilt_table_angle_deg(srts), np.nan)
    preset, saved = r["presets"][index], r["saved_ids"][index]
    return VehicleAnswer(index, preset, saved, cols, pair_of_row.reshape(-1), srts, tilt, r["targets"])


def solve_alignment(job: AlignmentJob, solve_pairs=None) -> AlignmentAnswer:
    """Every curve for every vehicle (blocking: called in a worker thread); ``solve_pairs``: see
    :func:`engine.assessment.assess_alignment` (a job's parts remember the pairs they solved); the blocks of the
    pairs' solve and of the side-friction speeds run on the solver threads (:mod:`app.compute.solvers`)."""
    started = time.perf_counter()
    vehicles = [_vehicle_answer(job, k, solve_pairs) for k in range(len(job.vehicles))]
    answer = AlignmentAnswer(job.resolved, job.curves, vehicles)
    SOLVE_SECONDS.labels("alignments", job.resolved["model"]).observe(time.perf_counter() - started)
    return answer


def check_alignment(job: AlignmentJob) -> int:
    """What :func:`solve_alignment` refuses for the request as a whole, found without solving every curve (a job
    refuses it at submission): a vehicle the model cannot use, a superelevation that cannot be derived. Raises the
    same errors, located the same way. Returns the number of distinct superelevation/grade pairs (the summary's
    ``distinct_srt_solves``)."""
    r, t = job.resolved, job.curves
    try:
        e = superelevation_used(
            t.radius_m,
            t.superelevation_percent,
            t.posted_speed_kmh,
            design_standard=r["design_standard"],
            side_friction_bound=r["side_friction_bound"],
            max_superelevation_percent=r["max_superelevation_percent"],
        )
    except InvalidInput as exc:
        raise _located(exc, job, 0) from None
    first = AlignmentJob(r, job.vehicles, t.sliced(0, 1), job.source)
    for k in range(len(job.vehicles)):
        _vehicle_answer(first, k)  # the refusals of the vehicle and the options, on one curve
    return len(bank_grade_pairs(e, t.grade_percent)[0])


# ---------------------------------------------------------------------------------------- rendering


def _opt(values: np.ndarray) -> list[float | None]:
    return [None if math.isnan(x) else x for x in values.tolist()]


def _rows(answer: AlignmentAnswer, v: VehicleAnswer, start: int, stop: int) -> list[dict[str, Any]]:
    """Rows [start, stop) of one vehicle, as CurveRow dicts in the schema's field order."""
    columns = _row_columns(answer, v, start, stop)
    names = list(columns)
    return [dict(zip(names, values, strict=True)) for values in zip(*columns.values(), strict=True)]


def _row_columns(answer: AlignmentAnswer, v: VehicleAnswer, start: int, stop: int) -> dict[str, list[Any]]:
    """Rows [start, stop) of one vehicle, column by column (CurveRow's fields in the schema's order)."""
    c, t, sl = v.columns, answer.curves, slice(start, stop)
    return {
        "id": t.ids[sl],
        "station_m": _opt(t.station_m[sl]),
        "radius_m": c.radius_m[sl].tolist(),
        "superelevation_percent": c.superelevation_percent[sl].tolist(),
        "superelevation_source": ["derived" if d else "given" for d in c.superelevation_derived[sl].tolist()],
        "grade_percent": c.grade_percent[sl].tolist(),
        "srt_g": _opt(c.srt_g[sl]),
        "tilt_table_angle_deg": [v.tilt[p] for p in v.pair_of_row[sl].tolist()],
        "targets": [v.checks[p] for p in v.pair_of_row[sl].tolist()],
        "rollover_speed_kmh": _opt(c.rollover_speed_kmh[sl]),
        "side_friction_speed_kmh": c.side_friction_speed_kmh[sl].tolist(),
        "side_friction": c.side_friction[sl].tolist(),
        "side_friction_clamped": c.side_friction_clamped[sl].tolist(),
        "safe_speed_kmh": _opt(c.safe_speed_kmh[sl]),
        "governed_by": [GOVERNED_BY[g] for g in c.governed_by[sl].tolist()],
        "posted_speed_kmh": _opt(c.posted_speed_kmh[sl]),
        "margin_kmh": _opt(c.margin_kmh[sl]),
        "flagged": c.flagged[sl].tolist(),
        "standard_min_radius_m": _opt(c.standard_min_radius_m[sl]),
        "meets_standard_min_radius": [None if m < 0 else bool(m) for m in c.meets_standard_min_radius[sl].tolist()],
        "error": [None if k < 0 else c.errors[k] for k in c.error[sl].tolist()],
    }


def _summary(c: AlignmentColumns) -> dict[str, Any]:
    margins, safe = c.margin_kmh[~np.isnan(c.margin_kmh)], c.safe_speed_kmh[~np.isnan(c.safe_speed_kmh)]
    return {
        "curves": len(c),
        "flagged": int(c.flagged.sum()),
        "below_standard_min_radius": int((c.meets_standard_min_radius == 0).sum()),
        "refused": int((c.error >= 0).sum()),
        "distinct_srt_solves": c.distinct_cases,
        "governed_by_rollover": int((c.governed_by == 1).sum()),
        "governed_by_side_friction": int((c.governed_by == 2).sum()),
        "min_margin_kmh": float(margins.min()) if margins.size else None,
        "min_safe_speed_kmh": float(safe.min()) if safe.size else None,
    }


def summary(c: AlignmentColumns) -> dict[str, Any]:
    """A vehicle's summary over the curves of ``c`` (the ``summary`` of the answer)."""
    return _summary(c)


def merge_summaries(parts: list[dict[str, Any]], distinct_srt_solves: int) -> dict[str, Any]:
    """The summary of a vehicle over all the curves from the summaries of consecutive slices of them (a job's parts):
    counts add up, minimums are the smallest (None where a slice has none); the distinct SRT solves are those of the
    whole alignment (``distinct_srt_solves``, from :func:`check_alignment`), not the sum of the slices'."""
    out = dict(parts[0])
    for p in parts[1:]:
        for name, value in p.items():
            if name.startswith("min_"):
                known = [x for x in (out[name], value) if x is not None]
                out[name] = min(known) if known else None
            else:
                out[name] += value
    out["distinct_srt_solves"] = distinct_srt_solves
    return out


def json_head(resolved: dict[str, Any], curves: int) -> bytes:
    """The AlignmentResult document up to its ``vehicles`` list (opened)."""
    r = resolved
    head = {
        "model": r["model"],
        "stage": r["stage"] if r["model"] == "3d" else None,
        "design_standard": r["design_standard"],
        "side_friction_bound": r["side_friction_bound"],
        "max_superelevation_percent": r["max_superelevation_percent"],
        "curves": curves,
    }
    return orjson.dumps(head)[:-1] + b',"vehicles":['


def json_vehicle_head(
    index: int, preset: str | None, saved_id: str | None, summary: dict[str, Any], *, first: bool
) -> bytes:
    """One vehicle's entry up to its ``rows`` list (opened); closed by :data:`JSON_VEHICLE_END`."""
    vehicle = {"index": index, "preset": preset, "saved_vehicle_id": saved_id, "summary": summary}
    return (b"" if first else b",") + orjson.dumps(vehicle)[:-1] + b',"rows":['


JSON_VEHICLE_END = b"]}"


_SOURCE_JSON = np.array([b'"given"', b'"derived"'], dtype=object)
_GOVERNED_JSON = np.array([orjson.dumps(g) for g in GOVERNED_BY], dtype=object)
_MEETS_JSON = np.array([b"null", b"false", b"true"], dtype=object)  # by meets_standard_min_radius + 1


def _json_row_columns(answer: AlignmentAnswer, v: VehicleAnswer, start: int, stop: int) -> dict[str, Any]:
    """:func:`_row_columns` as :func:`app.formats.json_rows.json_objects` writes them to the same JSON: a nan float is
    written null as ``None`` is; the texts and the target checks already as JSON
    (:class:`~app.formats.json_rows.RawJson`)."""
    c, t, sl = v.columns, answer.curves, slice(start, stop)
    pairs = v.pair_of_row[sl]
    errors = np.array([b"null", *map(orjson.dumps, c.errors)], dtype=object)
    return {
        "id": t.ids[sl],
        "station_m": t.station_m[sl].tolist(),
        "radius_m": c.radius_m[sl].tolist(),
        "superelevation_percent": c.superelevation_percent[sl].tolist(),
        "superelevation_source": RawJson(_SOURCE_JSON[c.superelevation_derived[sl].astype(np.intp)].tolist()),
        "grade_percent": c.grade_percent[sl].tolist(),
        "srt_g": c.srt_g[sl].tolist(),
        "tilt_table_angle_deg": v.tilt_deg[pairs].tolist(),
        "targets": RawJson(v.checks_json[pairs].tolist()),
        "rollover_speed_kmh": c.rollover_speed_kmh[sl].tolist(),
        "side_friction_speed_kmh": c.side_friction_speed_kmh[sl].tolist(),
        "side_friction": c.side_friction[sl].tolist(),
        "side_friction_clamped": c.side_friction_clamped[sl].tolist(),
        "safe_speed_kmh": c.safe_speed_kmh[sl].tolist(),
        "governed_by": RawJson(_GOVERNED_JSON[c.governed_by[sl]].tolist()),
        "posted_speed_kmh": c.posted_speed_kmh[sl].tolist(),
        "margin_kmh": c.margin_kmh[sl].tolist(),
        "flagged": c.flagged[sl].tolist(),
        "standard_min_radius_m": c.standard_min_radius_m[sl].tolist(),
        "meets_standard_min_radius": RawJson(_MEETS_JSON[c.meets_standard_min_radius[sl] + 1].tolist()),
        "error": RawJson(errors[c.error[sl] + 1].tolist()),
    }


def json_rows(answer: AlignmentAnswer, v: VehicleAnswer, start: int, stop: int) -> bytes:
    """Rows [start, stop) of one vehicle as JSON objects separated by commas (no brackets): ``orjson.dumps`` of
    :func:`_rows`, byte for byte, written column by column (:func:`app.formats.json_rows.json_objects`)."""
    return json_objects(_json_row_columns(answer, v, start, stop))


def json_tail() -> bytes:
    return b'],"engine_version":' + orjson.dumps(ENGINE_VERSION) + b"}"


def json_chunks(answer: AlignmentAnswer) -> Iterator[bytes]:
    """The AlignmentResult JSON document, in chunks of rows (byte for byte the document pydantic would write)."""
    yield json_head(answer.resolved, len(answer.curves))
    n = len(answer.curves)
    for k, v in enumerate(answer.vehicles):
        yield json_vehicle_head(v.index, v.preset, v.saved_id, _summary(v.columns), first=k == 0)
        for start in range(0, n, ROWS_PER_CHUNK):
            yield (b"," if start else b"") + json_rows(answer, v, start, min(start + ROWS_PER_CHUNK, n))
        yield JSON_VEHICLE_END
    yield json_tail()


def csv_columns(resolved: dict[str, Any]) -> list[str]:
    names = [n for n, _ in sorted(resolved["targets"].items(), key=lambda kv: (kv[1], kv[0]))]
    return ["vehicle_index", "vehicle_preset", "vehicle_saved_id", *ROW_COLUMNS, *target_columns(names), *SPEED_COLUMNS]


def csv_header(resolved: dict[str, Any]) -> bytes:
    """The CSV answer's header row."""
    return csv_line(csv_columns(resolved))


def csv_rows(answer: AlignmentAnswer, v: VehicleAnswer, start: int, stop: int, columns: list[str]) -> bytes:
    """CSV lines of rows [start, stop) of one vehicle (``columns``: :func:`csv_columns`)."""
    rows = _row_columns(answer, v, start, stop)
    n = stop - start
    rows["vehicle_index"] = [v.index] * n
    rows["vehicle_preset"] = [None if v.preset is None else Text(v.preset)] * n
    rows["vehicle_saved_id"] = [None if v.saved_id is None else Text(v.saved_id)] * n
    rows.update(target_columns_of(rows.pop("targets")))
    return csv_lines_of_columns([rows.get(name, [None] * n) for name in columns])


def csv_chunks(answer: AlignmentAnswer) -> Iterator[bytes]:
    """One CSV table in chunks: a row per vehicle and curve, the vehicle's index and preset first."""
    columns = csv_columns(answer.resolved)
    yield csv_line(columns)
    n = len(answer.curves)
    for v in answer.vehicles:
        for start in range(0, n, ROWS_PER_CHUNK):
            yield csv_rows(answer, v, start, min(start + ROWS_PER_CHUNK, n), columns)


def render(answer: AlignmentAnswer, csv: bool) -> Iterator[bytes]:
    return csv_chunks(answer) if csv else json_chunks(answer)


# ---------------------------------------------------------------------------------------- the flow


async def resolve_alignment_refs(request: Request, req: Any, settings: Settings, what: str = "an assessment") -> Any:
    """``req`` (an alignment or a route request) with its saved vehicles, specs and fleet resolved
    (:func:`~app.vehicles.refs.resolve_vehicle_refs`); a fleet larger than ``what`` takes (:data:`MAX_VEHICLES`) is
    a 422 naming ``fleet``."""
    fleet = req.fleet
    req = await resolve_vehicle_refs(request, req, settings)
    if fleet is not None and len(req.vehicles) > MAX_VEHICLES:
        raise request_error(
            "fleet", f"fleet {fleet} has {len(req.vehicles)} vehicles; {what} takes at most {MAX_VEHICLES}"
        )
    return req


async def compute_alignment(
    cache: ResultCache,
    request: Request,
    req: AlignmentRequest,
    curves: CurveTable | None,
    settings: Settings,
    *,
    csv: bool,
    source_field: str | None = None,
) -> Computed | Streamed:
    """The assessment as a cached body (small answers) or a stream (large ones); the same bytes either way."""
    fleet = req.fleet
    req = await resolve_alignment_refs(request, req, settings)
    job = await run_in_threadpool(resolve_alignment, req, curves, settings, source_field)
    operation = "alignments-csv" if csv else "alignments"
    media_type = CSV_TYPE if csv else JSON_TYPE
    key = cache_key(operation, job.resolved)
    body = (await cache.get(key, media_type)).value if job.rows <= STREAM_ROWS else None
    if body is not None:
        CACHE_LOOKUPS.labels(operation, "hit").inc()
        return Computed(body, key, True, media_type)
    answer_key = cache_key("alignment-answer", job.resolved)
    answer = cache.answers.get(answer_key)
    hit = answer is not None
    CACHE_LOOKUPS.labels(operation, "answer" if hit else "miss").inc()
    if answer is None:
        try:
            answer = await run_in_threadpool(solve_alignment, job)
        except InvalidInput as exc:
            raise as_fleet_error(exc, fleet, job.resolved) from None
        cache.answers[answer_key] = answer
    if job.rows <= STREAM_ROWS:
        body = await run_in_threadpool(lambda: b"".join(render(answer, csv)))
        await cache.set(key, body, media_type)
        return Computed(body, key, hit, media_type)
    request.state.raw_reusable = False  # not kept as bytes: the fast path has nothing to serve it from
    return Streamed(render(answer, csv), key, hit, media_type)
