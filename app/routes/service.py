"""Route assessment (POST /v1/routes/assess): geometry -> horizontal curves -> the alignment assessment.

The document is read by :mod:`app.formats.route_io` (GeoJSON or GPX: parts of WGS84 lon/lat/elevation, errors naming the
feature and the vertex), each part is developed into a plane frame that keeps its lengths and turning angles
(:func:`engine.route.geodesy.local_frame`), and :func:`engine.route.detect.find_curves` finds its tangents and curves.
The curves then go through the same assessment as an alignment's (:func:`app.alignments.service.solve_alignment`:
superelevation given, from a feature property, or derived from the standard; grade from the elevations) with the curve's
conservative radius ``radius_lower_m`` (the one-sided 95 % lower bound of the fitted ``radius_m``), so a curve gets the
same answer as a table row of that radius. The answer is a GeoJSON FeatureCollection of the curves (a GIS reads it as it
is), or CSV: one row per curve and vehicle.

Real tracks hold what no road has: a curve outside the model's domain (a radius of a few metres: a car park's or a
junction's manoeuvre) is a row with its ``error`` and no speeds (:func:`assess_route_curves`), never a refusal of the
document; a grade from the elevations beyond the domain is clipped with ``grade_clipped`` (:func:`curve_grade`); a road
without a curve is an answer without curves. Every answer carries the ``reading`` of its file (:func:`reading`): format,
writer, parts read, and what was skipped and why.
"""

from __future__ import annotations

import dataclasses
import hashlib
import math
import re
from dataclasses import dataclass
from typing import Any

import numpy as np
import orjson
from fastapi import Request
from starlette.concurrency import run_in_threadpool

from app.alignments import rows as alignment_rows
from app.alignments.advice import advise, advisory_head
from app.alignments.answer import AlignmentAnswer, vehicle_answer
from app.alignments.schemas import MAX_ROWS
from app.alignments.service import (
    AlignmentJob,
    as_fleet_error,
    resolve_assessment_request,
    resolved_assessment,
    solve_alignment,
)
from app.compute.cache import ResultCache
from app.compute.resolved import ResolvedRoute, RouteDocument
from app.compute.results import Computed, cached
from app.formats.alignment_io import CurveTable
from app.formats.route_io import (
    MAX_VERTICES,
    RouteFormatError,
    RoutePart,
    RouteRead,
    RouteTooLarge,
    read_geojson_document,
    read_gpx_document,
)
from app.formats.tables import Text, flatten_targets, to_csv
from app.http.negotiation import GEOJSON_MEDIA_TYPE
from app.http.problems import InvalidRoute, as_a_job, request_error
from app.routes.schemas import (
    MAX_GRADE_PERCENT,
    MAX_SYNC_VERTICES,
    RouteCurves,
    RouteRequest,
    RouteResult,
)
from app.settings import Settings
from app.vehicles.resolve import VehicleRequest, vehicle_of_resolved
from engine import BOUNDS, ENGINE_VERSION, InvalidInput
from engine.road import AlignmentColumns
from engine.route import HorizontalCurve, find_curves, local_frame
from engine.vehicle import Combination, Vehicle

#: a ``routes.assess`` job's rows (curves x vehicles): a route job reads one document (the synchronous request's
#: body limit, up to :data:`~app.formats.route_io.MAX_VERTICES` vertices), so a job takes what such documents hold,
#: not an alignment job's million
MAX_JOB_ROWS = 100_000

#: the route's own columns in front of the alignment's in the CSV answer
GEOMETRY_COLUMNS = (
    "part",
    "direction",
    "start_m",
    "end_m",
    "length_m",
    "deflection_deg",
    "spiral_in_m",
    "spiral_out_m",
    "radius_lower_m",
    "radius_std_m",
    "compound",
    "sparse",
    "truncated",
    "grade_source",
    "grade_clipped",
)

#: the radius a curve outside the model's domain is solved with (its results are then discarded: the row carries its
#: ``error``), any radius inside the domain [m]
_STAND_IN_RADIUS_M = 1000.0


@dataclass(frozen=True)
class FoundCurve:
    """A curve found on one part, with where it lies in the document."""

    part: RoutePart
    curve: HorizontalCurve
    id: str


@dataclass(frozen=True)
class Geometry:
    """What was read and found: the document's reading, its parts, their curves and each part's noise estimate."""

    read: RouteRead
    parts: list[RoutePart]
    curves: list[FoundCurve]
    noise_m: list[float]
    noise_corr_m: list[float]  # each part's correlation length of the noise along the track (0: white) [m]
    found_per_part: list[int]
    length_m: list[float]  # along the road (the detection's chainage: vertex noise taken out)


# ------------------------------------------------------------------------------------------ reading


def _source(req: RouteRequest, source_field: str | None) -> str:
    """The request field an error in the document names: ``geojson`` / ``gpx``, or the upload's (``body``,
    ``file``)."""
    return source_field or ("geojson" if req.geojson is not None else "gpx")


def _to_a_job(message: str, limits: str) -> str:
    """A synchronous route's size limit ``message``, with how to send it as a ``routes.assess`` job instead."""
    return as_a_job(message, "routes.assess", 'the file as its "gpx" text or "geojson" object', limits)


def read_route(req: RouteRequest, source_field: str | None = None, *, synchronous: bool = True) -> RouteRead:
    """The request's document read (its parts, and what was skipped), at most
    :data:`~app.routes.schemas.MAX_SYNC_VERTICES` vertices for the synchronous request and
    :data:`~app.formats.route_io.MAX_VERTICES` for a job; :class:`InvalidRoute` naming the part and vertex otherwise
    (and the request field, ``source_field`` for an upload); a GPX without the ``parts`` asked for: a 422 naming
    ``parts``."""
    source = _source(req, source_field)
    limit = MAX_SYNC_VERTICES if synchronous else MAX_VERTICES
    try:
        if req.geojson is not None:
            return read_geojson_document(req.geojson, max_vertices=limit)
        return read_gpx_document(req.gpx, parts=req.parts, max_vertices=limit)
    except RouteFormatError as exc:
        reason = str(exc).removeprefix(f"{exc.location}: ") if exc.location else str(exc)
        if exc.field == "parts":
            raise request_error("parts", reason) from None
        if synchronous and isinstance(exc, RouteTooLarge):
            reason = _to_a_job(reason, f"{MAX_VERTICES:,} vertices")
        raise InvalidRoute(reason, source=source, location=exc.location, column=exc.field) from None


def find_route_curves(req: RouteRequest, read: RouteRead, source_field: str | None = None) -> Geometry:
    """Every part in its plane frame, through the curve detection (without its elevations when ``use_elevation`` is
    false)."""
    d = req.detection
    parts = read.parts
    curves: list[FoundCurve] = []
    noise, corr, found, length = [], [], [], []
    for p in parts:
        frame = local_frame(p.lon_deg, p.lat_deg, p.ele_m if req.use_elevation else None)
        try:
            rc = find_curves(
                frame.x_m,
                frame.y_m,
                frame.z_m,
                noise_m=d.noise_m,
                max_radius_m=d.max_radius_m,
                min_deflection_deg=d.min_deflection_deg,
            )
        except InvalidInput as exc:
            raise InvalidRoute(str(exc), source=_source(req, source_field), location=p.location, column=None) from None
        noise.append(rc.noise_m)
        corr.append(rc.noise_corr_m)
        found.append(len(rc.curves))
        length.append(rc.length_m)
        curves += [FoundCurve(p, c, f"{p.source}-C{k + 1}") for k, c in enumerate(rc.curves)]
    return Geometry(read, parts, curves, noise, corr, found, length)


def _from_file(c: FoundCurve, name: str) -> float | None:
    """A curve's ``name`` property: its feature's; on a road joined from OSM ways, the ways' it lies on (the largest
    posted speed, against which the margin is the smallest; the smallest superelevation, the lower SRT)."""
    p = c.part
    if p.spans is None:
        return p.properties.get(name)
    lo, hi = c.curve.start_index, c.curve.end_index
    values = [props[name] for a, b, props in p.spans if a <= hi and b >= lo and props.get(name) is not None]
    if not values:
        return None
    return max(values) if name == "posted_speed_kmh" else min(values)


def _property(c: FoundCurve, name: str, default: float | None) -> float:
    value = _from_file(c, name)
    value = default if value is None else value
    return math.nan if value is None else float(value)


@dataclass(frozen=True)
class CurveGrade:
    """The grade a curve is assessed on [%], where it came from, and whether the elevations' grade was clipped."""

    percent: float
    source: str  # "elevations" or "request"
    clipped: bool


def curve_grade(req: RouteRequest, h: HorizontalCurve) -> CurveGrade:
    """The grade of a curve: the least-squares grade of its elevations (:mod:`engine.route.detect`, step 10) clipped
    to the model's domain (+/- :data:`~app.routes.schemas.MAX_GRADE_PERCENT`: GPS and DEM elevations make grades no
    road has between close fixes), else the request's ``grade_percent`` (0 by default)."""
    raw = h.grade_percent if req.use_elevation else None
    if raw is None:
        return CurveGrade(0.0 if req.grade_percent is None else req.grade_percent, "request", False)
    clipped = min(max(raw, -MAX_GRADE_PERCENT), MAX_GRADE_PERCENT)
    return CurveGrade(clipped, "elevations", clipped != raw)


def outside_domain(h: HorizontalCurve) -> str | None:
    """Why a curve is outside the model's domain (:data:`engine.domain.BOUNDS` ``radius_m``), or None: a radius below
    the smallest a heavy vehicle turns on is a manoeuvre (a car park, a junction), not a road curve."""
    b = BOUNDS["radius_m"]
    r = h.radius_lower_m
    if not b.contains(r):
        return (
            f"radius {r:.3g} m (radius_lower_m) is outside the model's domain [{b.minimum:g}, {b.maximum:g}] m "
            f"({b.why}): a manoeuvre such as a car park's or a junction's, not a road curve; no speed is given for it"
        )
    return None


def curve_table(req: RouteRequest, geo: Geometry) -> CurveTable:
    """The found curves as the alignment assessment's columns (superelevation and posted speed from the feature's
    properties, else the request's defaults; nan: derive / none; the grade of :func:`curve_grade`)."""
    cs = geo.curves
    e = np.array([_property(c, "superelevation_percent", req.superelevation_percent) for c in cs], dtype=float)
    if np.any(np.isnan(e)) and req.max_superelevation_percent is None:
        first = next(c for c, x in zip(cs, e, strict=True) if math.isnan(x))
        raise request_error(
            "superelevation_percent",
            f"curve {first.id} has no superelevation: give superelevation_percent (for every curve), the feature "
            "property superelevation_percent, or max_superelevation_percent (to derive it from the standard)",
        )
    return CurveTable(
        ids=[c.id for c in cs],
        radius_m=np.array([c.curve.radius_lower_m for c in cs], dtype=float),  # conservative: the safe speed's
        superelevation_percent=e,
        grade_percent=np.array([curve_grade(req, c.curve).percent for c in cs], dtype=float),
        posted_speed_kmh=np.array([_property(c, "posted_speed_kmh", req.posted_speed_kmh) for c in cs], dtype=float),
        station_m=np.array([c.curve.start_m for c in cs], dtype=float),
    )


def curve_places(geo: Geometry) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Each found curve's start station [m], length [m] and deflection [deg] along its line part, and its part (the
    advice's profile: one per part, the parts being unconnected and each one's stations restarting)."""
    cs = [c.curve for c in geo.curves]
    start = np.array([h.start_m for h in cs], dtype=float)
    part = np.array([c.part.source for c in geo.curves], dtype=object)
    lengths = np.array([h.end_m - h.start_m for h in cs], dtype=float)
    return start, lengths, np.array([h.deflection_deg for h in cs]), part


def _document_digest(req: RouteRequest) -> str:
    doc = orjson.dumps(req.geojson, option=orjson.OPT_SORT_KEYS) if req.geojson is not None else req.gpx.encode()
    return hashlib.sha256(doc).hexdigest()


def resolved_route(vr: VehicleRequest[RouteRequest], settings: Settings) -> ResolvedRoute:
    """What the route's answer depends on (its key): the assessment's options and vehicles, and the document."""
    req = vr.body
    return ResolvedRoute(
        **resolved_assessment(req, vr.vehicles, settings).assessment_fields(),
        route=RouteDocument(
            format="geojson" if req.geojson is not None else "gpx",
            sha256=_document_digest(req),
            superelevation_percent=req.superelevation_percent,
            posted_speed_kmh=req.posted_speed_kmh,
            detection=req.detection.model_dump(),
            parts=req.parts,
            use_elevation=req.use_elevation,
            grade_percent=req.grade_percent,
        ),
    )


# ---------------------------------------------------------------------------------------- rendering


def _coordinates(c: FoundCurve) -> list[list[float]]:
    p = c.part
    sl = slice(c.curve.start_index, c.curve.end_index + 1)
    lon, lat = p.lon_deg[sl].tolist(), p.lat_deg[sl].tolist()
    if p.ele_m is None:
        return [[a, b] for a, b in zip(lon, lat, strict=True)]
    ele = p.ele_m[sl].tolist()
    return [[a, b] if math.isnan(z) else [a, b, z] for a, b, z in zip(lon, lat, ele, strict=True)]


def _geometry_fields(req: RouteRequest, c: FoundCurve) -> dict[str, Any]:
    h = c.curve
    grade = curve_grade(req, h)
    vi = c.part.vertex_index
    return {
        "part": c.part.source,
        "name": c.part.properties.get("name"),
        "direction": h.direction,
        "radius_m": h.radius_m,
        "radius_lower_m": h.radius_lower_m,
        "radius_std_m": h.radius_std_m,
        "start_m": h.start_m,
        "end_m": h.end_m,
        "arc_start_m": h.arc_start_m,
        "arc_end_m": h.arc_end_m,
        "length_m": h.length_m,
        "deflection_deg": h.deflection_deg,
        "spiral_in_m": h.spiral_in_m,
        "spiral_out_m": h.spiral_out_m,
        "grade_percent": h.grade_percent if req.use_elevation else None,
        "grade_source": grade.source,
        "grade_clipped": grade.clipped,
        "compound": h.compound,
        "sparse": h.sparse,
        "truncated": h.truncated,
        "vertices": [int(vi[h.start_index]), int(vi[h.end_index])],
    }


def _governing(rows: list[dict[str, Any]]) -> int:
    """The vehicle with the lowest safe speed on a curve (a refused case first: it has no safe speed)."""
    speeds = [math.inf if r["safe_speed_kmh"] is None else r["safe_speed_kmh"] for r in rows]
    refused = [k for k, r in enumerate(rows) if r["error"] is not None]
    return refused[0] if refused else int(np.argmin(speeds))


#: the computed values a row outside the model's domain has none of (nan in its columns: null in the answer)
_NONE_OUTSIDE = ("superelevation_percent", "side_friction_speed_kmh", "side_friction", "side_friction_clamped")


def _rows(answer: AlignmentAnswer, v, n: int, outside: np.ndarray) -> list[dict[str, Any]]:
    """A vehicle's rows; a row outside the model's domain without the values it has none of."""
    rows = alignment_rows.rows(answer, v, 0, n)
    for i in np.flatnonzero(outside).tolist():
        row = rows[i]
        for name in _NONE_OUTSIDE:
            value = row[name]
            if name != "superelevation_percent" or (isinstance(value, float) and math.isnan(value)):
                row[name] = None
    return rows


def _curves(req: RouteRequest, geo: Geometry, answer: AlignmentAnswer) -> list[dict[str, Any]]:
    """Each curve's geometry and its assessment (the governing vehicle's row, and every row with several)."""
    n = len(geo.curves)
    outside = _outside_mask(geo)
    per_vehicle = [_rows(answer, v, n, outside) for v in answer.vehicles]
    out = []
    for i, c in enumerate(geo.curves):
        rows = [pv[i] for pv in per_vehicle]
        g = _governing(rows)
        shown = [r["advisory_speed_kmh"] for r in rows]
        lowest = min(range(len(rows)), key=lambda k: math.inf if shown[k] is None else shown[k])
        out.append(
            {
                "id": c.id,
                **_geometry_fields(req, c),
                "governing_vehicle": g,
                "assessment": rows[g],
                "vehicles": rows if len(rows) > 1 else None,
                "advisory_speed_kmh": shown[lowest],
                "treatment_devices": ";".join(rows[lowest]["treatment"]["devices"]) or None,
                "truck_rollover_warning": any(r["truck_rollover_warning"]["recommended"] for r in rows),
            }
        )
    return out


def _outside_mask(geo: Geometry) -> np.ndarray:
    return np.array([outside_domain(c.curve) is not None for c in geo.curves], dtype=bool)


def _superelevation_from(req: RouteRequest, geo: Geometry) -> str | None:
    """Where the curves' superelevation came from (the reading's ``superelevation_from``)."""
    if not geo.curves:
        return None
    if any(_from_file(c, "superelevation_percent") is not None for c in geo.curves):
        return "file"
    return "request" if req.superelevation_percent is not None else "standard"


def reading(req: RouteRequest, geo: Geometry) -> dict[str, Any]:
    """The answer's ``reading``: what was read from the file and what was not."""
    read = geo.read
    elevations = req.use_elevation and any(p.ele_m is not None for p in read.parts)
    return {
        "format": read.format,
        "writer": read.writer,
        "linear_unit": "meter",
        "alignments": [p.source for p in read.parts],
        "elements": read.elements,
        "profile": "elevations" if elevations else None,
        "superelevation_from": _superelevation_from(req, geo),
        "skipped": [{"what": what, "why": why} for what, why in read.skipped],
    }


def _profile_points(geo: Geometry, advice: Any) -> list[dict[str, Any]]:
    """A vehicle's speed profile as the answer's points, each with the part it lies on (its stations along that
    part: each part has its own profile)."""
    station, speed = advice.station_m.tolist(), advice.speed_kmh.tolist()
    if advice.point_part is not None:
        part = advice.point_part.tolist()
    else:  # the curves on one part
        part = [geo.curves[0].part.source if geo.curves else None] * len(station)
    return [{"station_m": x, "speed_kmh": y, "part": p} for x, y, p in zip(station, speed, part, strict=True)]


def route_json(req: RouteRequest, geo: Geometry, answer: AlignmentAnswer) -> bytes:
    r = answer.resolved
    found = zip(_curves(req, geo, answer), geo.curves, strict=True)
    curves = [{**props, "coordinates": _coordinates(c)} for props, c in found]
    out = {
        "model": r.model or alignment_rows.default_model(r.vehicles),
        "stage": r.stage if (r.model or alignment_rows.default_model(r.vehicles)) == "3d" else None,
        "design_standard": r.design_standard,
        "length_m": float(sum(geo.length_m)),
        "parts": [
            {
                "part": p.source,
                "name": p.properties.get("name"),
                "vertices": int(p.lon_deg.size),
                "length_m": length,
                "curves": k,
                "noise_m": s,
                "noise_corr_m": corr,
                "has_elevation": p.ele_m is not None,
                "ways": None if p.ways is None else list(p.ways),
            }
            for p, k, s, corr, length in zip(
                geo.parts, geo.found_per_part, geo.noise_m, geo.noise_corr_m, geo.length_m, strict=True
            )
        ],
        "vehicles": [
            {
                "index": v.index,
                "preset": v.preset,
                "saved_vehicle_id": v.saved_id,
                "warnings": list(v.warnings),
                "summary": alignment_rows.summary(v.columns),
                "rows": [],
                "speed_profile": _profile_points(geo, v.advice),
                "speed_profile_notes": v.advice.notes,
            }
            for v in answer.vehicles
        ],
        "curves": curves,
        "reading": reading(req, geo),
        "advisory": advisory_head(r),
        "engine_version": ENGINE_VERSION,
    }
    return RouteResult.model_validate(out).model_dump_json().encode()  # the contract checked on the way out


def route_geojson(req: RouteRequest, geo: Geometry, answer: AlignmentAnswer) -> bytes:
    """The curves as a GeoJSON FeatureCollection (RFC 7946): a LineString of its vertices per curve, the curve and
    its assessment as the feature's properties; the reading as a foreign member."""
    features = [
        {"type": "Feature", "geometry": {"type": "LineString", "coordinates": _coordinates(c)}, "properties": props}
        for props, c in zip(_curves(req, geo, answer), geo.curves, strict=True)
    ]
    doc = {
        "type": "FeatureCollection",
        "features": features,
        "reading": reading(req, geo),
        "advisory": advisory_head(answer.resolved),
        "warnings": [w for v in answer.vehicles for w in v.warnings],
    }
    return RouteCurves.model_validate(doc).model_dump_json().encode()


def route_csv(req: RouteRequest, geo: Geometry, answer: AlignmentAnswer) -> bytes:
    """One row per vehicle and curve: the vehicle, the curve's geometry, then the alignment's columns; as in the JSON
    answer's curves, ``radius_m`` is the fitted radius and ``radius_lower_m`` the one the row was assessed with."""
    n = len(geo.curves)
    # the route's geometry states the bend's facts a road file's row carries (direction, deflection, spirals...)
    base = [c for c in alignment_rows.csv_columns(answer.resolved) if c not in GEOMETRY_COLUMNS]
    columns = [*base[:3], *GEOMETRY_COLUMNS, *base[3:]]
    rows = []
    outside = _outside_mask(geo)
    for v in answer.vehicles:
        preset = None if v.preset is None else Text(v.preset)
        saved = None if v.saved_id is None else Text(v.saved_id)
        for c, row in zip(geo.curves, _rows(answer, v, n, outside), strict=True):
            geometry = _geometry_fields(req, c)
            fields = {k: x for k, x in geometry.items() if k in GEOMETRY_COLUMNS}
            fields["part"] = Text(fields["part"])
            fields["grade_source"] = Text(fields["grade_source"])
            rows.append({"vehicle_index": v.index, "vehicle_preset": preset, "vehicle_saved_id": saved,
                         **flatten_targets(alignment_rows.flatten_advice(row)), **fields,
                         "radius_m": geometry["radius_m"]})  # fmt: skip
    return to_csv(columns, rows)


# ---------------------------------------------------------------------------------------- computing


#: the answer's forms: (cache operation, media type)
FORMS = {
    "json": ("route", "application/json"),
    "csv": ("route-csv", "text/csv; charset=utf-8"),
    "geojson": ("route-geojson", GEOJSON_MEDIA_TYPE),
}


_CURVE_FIELD = re.compile(r"^curves[\[.](\d+)\]?\.(\w+)$")


def _named_after_the_route(exc: InvalidInput, table: CurveTable) -> InvalidInput:
    """An error the assessment names after a row of its curve table (``curves[3].posted_speed_kmh``) is about a
    curve the route request does not list: name the request's own field and say which curve in the message."""
    m = _CURVE_FIELD.match(exc.field or "")
    if m is None:
        return exc
    curve = table.ids[int(m.group(1))]
    text = str(exc)
    lead = re.match(r"^curves\[\d+\]", text)
    message = f"the route's curve {curve}{text[lead.end() :]}" if lead else f"the route's curve {curve}: {text}"
    return type(exc)(message, field=m.group(2), value=exc.value)


def _no_curves(job: AlignmentJob) -> AlignmentAnswer:
    """The answer of a road without a curve: every vehicle with no rows (nothing is solved)."""
    empty = {f.name: np.empty(0) for f in dataclasses.fields(AlignmentColumns)}
    cols = AlignmentColumns(**{**empty, "errors": [], "distinct_cases": 0})
    none = advise(job.resolved, cols, np.empty(0), np.empty(0), None)
    vehicles = [vehicle_answer(job.resolved, k, cols, math.nan, none) for k in range(len(job.vehicles))]
    return AlignmentAnswer(job.resolved, job.curves, vehicles)


def _with_domain_errors(answer: AlignmentAnswer, job: AlignmentJob, reasons: list[str | None]) -> AlignmentAnswer:
    """The answer with the curves outside the model's domain as refused rows: their ``error``, ``flagged``, their own
    radius, and no SRT, speeds, side friction or derived superelevation (they were solved at a stand-in radius so that
    the rest of the document is assessed; those numbers are dropped here, and the advice is made again without
    them). Whether they meet the standard's minimum radius is judged on their own radius."""
    table = job.curves
    outside = np.array([r is not None for r in reasons], dtype=bool)
    vehicles = []
    for v in answer.vehicles:
        c = v.columns
        errors = sorted(set(c.errors) | {r for r in reasons if r is not None})
        code = {m: k for k, m in enumerate(errors)}
        remap = np.array([code[m] for m in c.errors] + [-1], dtype=int)
        error = remap[c.error]  # -1 stays -1 (the last entry)
        error[outside] = [code[r] for r in reasons if r is not None]

        def drop(a: np.ndarray, fill: Any = math.nan) -> np.ndarray:
            return np.where(outside, fill, a)

        radius = table.radius_m
        meets = np.where(np.isnan(c.standard_min_radius_m), -1, (radius >= c.standard_min_radius_m).astype(int))
        cols = dataclasses.replace(
            c,
            radius_m=radius,
            superelevation_percent=np.where(outside & c.superelevation_derived, math.nan, c.superelevation_percent),
            srt_g=drop(c.srt_g),
            rollover_speed_kmh=drop(c.rollover_speed_kmh),
            side_friction_speed_kmh=drop(c.side_friction_speed_kmh),
            side_friction=drop(c.side_friction),
            safe_speed_kmh=drop(c.safe_speed_kmh),
            governed_by=drop(c.governed_by, 0),
            margin_kmh=drop(c.margin_kmh),
            flagged=c.flagged | outside,
            meets_standard_min_radius=meets,
            error=error,
            errors=errors,
        )
        advice = advise(answer.resolved, cols, *job.curve_places())
        vehicles.append(vehicle_answer(answer.resolved, v.index, cols, v.level_srt, advice))
    return AlignmentAnswer(answer.resolved, table, vehicles)


def assess_route_curves(job: AlignmentJob, geo: Geometry) -> AlignmentAnswer:
    """The alignment assessment of a route's curves (blocking): a curve outside the model's domain
    (:func:`outside_domain`) is a row with its ``error``, never a refusal of the document; a road without a curve is
    an answer without rows."""
    table = job.curves
    if not len(table):
        return _no_curves(job)
    reasons = [outside_domain(c.curve) for c in geo.curves]
    solved = job
    if any(r is not None for r in reasons):
        stand_in = np.where([r is not None for r in reasons], _STAND_IN_RADIUS_M, table.radius_m)
        solved = dataclasses.replace(job, curves=dataclasses.replace(table, radius_m=stand_in))
    try:
        answer = solve_alignment(solved)
    except InvalidInput as exc:
        raise _named_after_the_route(exc, table) from None
    return _with_domain_errors(answer, job, reasons) if solved is not job else answer


def render_route(
    req: RouteRequest,
    resolved: ResolvedRoute,
    forms: tuple[str, ...],
    source_field: str | None = None,
    *,
    max_rows: int | None = None,
    vehicles: list[Vehicle | Combination] | None = None,
) -> dict[str, bytes]:
    """Read, find, assess and render the route in each of ``forms`` (blocking: a worker thread, or a job's worker):
    ``resolved`` is :func:`resolved_route` of the request (its vehicles' records, options and targets);
    ``source_field`` names an upload's document in errors (``body``, ``file``); ``max_rows`` bounds curves x
    vehicles (None: the synchronous request's :data:`~app.alignments.schemas.MAX_ROWS`; a job passes
    :data:`MAX_JOB_ROWS`); ``vehicles``: the engine records of ``resolved.vehicles`` when the caller has them (the
    synchronous request: :mod:`app.vehicles.resolve`), else rebuilt from the stored records (a job's worker)."""
    synchronous = max_rows is None
    read = read_route(req, source_field, synchronous=synchronous)
    geo = find_route_curves(req, read, source_field)
    if vehicles is None:
        vehicles = [vehicle_of_resolved(v) for v in resolved.vehicles]
    rows = len(geo.curves) * len(vehicles)
    max_rows = MAX_ROWS if max_rows is None else max_rows
    if rows > max_rows:
        message = f"{len(geo.curves)} curves x {len(vehicles)} vehicles = {rows:,} rows; at most {max_rows:,} rows"
        if synchronous:
            message = _to_a_job(message, f"{MAX_JOB_ROWS:,} rows")
        raise request_error("vehicles", message)
    table = curve_table(req, geo)
    job = AlignmentJob(resolved, vehicles, table, _source(req, source_field), places=curve_places(geo))
    answer = assess_route_curves(job, geo)
    renderers = {
        "json": lambda: route_json(req, geo, answer),
        "csv": lambda: route_csv(req, geo, answer),
        "geojson": lambda: route_geojson(req, geo, answer),
    }
    return {form: renderers[form]() for form in forms}


async def resolve_route_request(
    request: Request, req: RouteRequest, settings: Settings
) -> VehicleRequest[RouteRequest]:
    """``req`` and its vehicles resolved (a fleet's members among them, at most :data:`MAX_VEHICLES`): the
    alignment's resolution, worded for a route."""
    return await resolve_assessment_request(request, req, settings, what="a route")


async def assess_route(
    cache: ResultCache,
    vr: VehicleRequest[RouteRequest],
    settings: Settings,
    *,
    form: str = "json",
    source_field: str | None = None,
) -> Computed:
    """The route's answer in ``form`` (cached); ``source_field`` names an upload's document in errors."""
    req, fleet = vr.body, vr.body.fleet
    resolved = await run_in_threadpool(resolved_route, vr, settings)  # the key: resolved
    operation, media = FORMS[form]

    async def produce() -> bytes:
        try:
            bodies = await run_in_threadpool(
                lambda: render_route(req, resolved, (form,), source_field, vehicles=vr.engine_vehicles)
            )
        except InvalidInput as exc:
            raise as_fleet_error(exc, fleet, resolved) from None
        return bodies[form]

    return await cached(cache, operation, resolved, produce, media)
