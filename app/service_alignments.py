"""Alignment assessment (POST /v1/alignments/assess): curves from JSON, CSV or LandXML -> engine -> rows.

The resolved request holds the curves themselves (id, radius, superelevation, grade, posted speed, station),
not the document they came from, so the same curves sent as JSON, CSV or LandXML share one cache entry. The
engine solves one SRT per distinct (superelevation, grade) pair and per vehicle
(:func:`engine.assessment.assess_curves`); rows sharing a pair share the target checks too.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np
import orjson
from starlette.concurrency import run_in_threadpool

from engine import ENGINE_VERSION
from engine.assessment import Curve, assess_curves, tilt_table_angle_deg
from engine.case import Case
from engine.errors import InvalidInput
from engine.loads import LoadCase
from engine.road import TABLE21_SPEEDS_KMH, side_friction_factor
from engine.vehicles import Vehicle

from .alignment_io import AlignmentFormatError, CurveOverride, read_csv, read_landxml
from .cache import ResultCache
from .metrics import SOLVE_SECONDS
from .problems import InvalidAlignment, request_error
from .schemas.alignments import MAX_ROWS, AlignmentRequest, AlignmentResult
from .service import Computed, cached, cached_csv, resolve_targets, resolve_vehicle, target_checks
from .settings import Settings
from .tables import flatten_targets, target_columns, to_csv

ROW_COLUMNS = (
    "id",
    "station_m",
    "radius_m",
    "superelevation_percent",
    "grade_percent",
    "srt_g",
    "tilt_table_angle_deg",
)
SPEED_COLUMNS = (
    "rollover_speed_kmh",
    "side_friction_speed_kmh",
    "side_friction",
    "safe_speed_kmh",
    "governed_by",
    "posted_speed_kmh",
    "margin_kmh",
    "flagged",
    "error",
)


def read_curves(req: AlignmentRequest, source_field: str | None = None) -> list[tuple[Curve, float | None]]:
    """The curves (with their station, or None) from whichever of ``curves``, ``csv``, ``landxml`` is given.

    ``source_field`` names where a document came from for the error (``body`` for a raw upload)."""
    if req.curves is not None:
        return [
            (Curve(c.id, c.radius_m, c.superelevation_percent, c.grade_percent, c.posted_speed_kmh), None)
            for c in req.curves
        ]
    source = "csv" if req.csv is not None else "landxml"
    try:
        if source == "csv":
            return [(c, None) for c in read_csv(req.csv)]
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
        )
    except AlignmentFormatError as exc:
        where = source_field or ("csv" if source == "csv" else "landxml.document")
        if exc.location == "curve_overrides":
            where, location = "landxml.curve_overrides", None
        else:
            location = exc.location
        reason = str(exc)
        if exc.location and reason.startswith(f"{exc.location}: "):
            reason = reason[len(exc.location) + 2 :]
        raise InvalidAlignment(reason, source=where, location=location, column=exc.field) from None


def resolve_alignment(req: AlignmentRequest, settings: Settings, source_field: str | None = None) -> dict[str, Any]:
    """The fully resolved request: the vehicles' records (and preset ids), the options, and the curves."""
    which = "vehicle" if req.vehicle is not None else "vehicles"
    refs = [req.vehicle] if which == "vehicle" else list(req.vehicles)
    curves = read_curves(req, source_field)
    if len(curves) * len(refs) > MAX_ROWS:
        raise request_error(
            which,
            f"{len(curves)} curves x {len(refs)} vehicles = {len(curves) * len(refs)} rows; at most {MAX_ROWS} per "
            "request (split the alignment or the vehicles)",
        )
    return {
        "vehicles": [resolve_vehicle(r).to_dict() for r in refs],
        "presets": [r if isinstance(r, str) else None for r in refs],
        "model": req.model,
        "stage": req.stage,
        "trailer_angle_deg": req.trailer_angle_deg,
        "load": req.load.model_dump(),
        "rear_llt_limit": req.rear_llt_limit,
        "side_friction_bound": req.side_friction_bound,
        "targets": resolve_targets(req.targets, settings),
        "curves": [
            [c.id, c.radius_m, c.superelevation_percent, c.grade_percent, c.posted_speed_kmh, station]
            for c, station in curves
        ],
    }


def _side_friction(speeds: np.ndarray, bound: str) -> np.ndarray:
    """f at each side-friction speed, as the engine used it (Table 21, clamped to its 30-120 km/h)."""
    clamped = np.clip(speeds, TABLE21_SPEEDS_KMH[0], TABLE21_SPEEDS_KMH[-1])
    return np.asarray(side_friction_factor(clamped, bound), dtype=float)


def _assess_vehicle(index: int, vehicle: Vehicle, curves: list[Curve], stations, resolved) -> dict[str, Any]:
    case = Case(
        vehicle,
        resolved["model"],
        resolved["stage"],
        trailer_angle_deg=resolved["trailer_angle_deg"],
        load=LoadCase(**resolved["load"]),
        rear_llt_limit=resolved["rear_llt_limit"],
    )
    try:
        result = assess_curves(case, curves, friction_bound=resolved["side_friction_bound"])
    except InvalidInput as exc:  # with several vehicles, say which one the engine refused
        if len(resolved["vehicles"]) > 1 and exc.field is not None and "." not in exc.field:
            raise type(exc)(
                f"vehicles[{index}]: {exc}", field=f"vehicles.{index}.{exc.field}", value=exc.value
            ) from exc
        raise
    f = _side_friction(np.array([a.side_friction_speed_kmh for a in result.curves]), resolved["side_friction_bound"])
    shared: dict[float, tuple[float, list[dict[str, Any]]]] = {}  # SRT -> (tilt angle, target checks)
    rows = []
    for a, c, station, fi in zip(result.curves, curves, stations, f, strict=True):
        if a.srt_g is not None and a.srt_g not in shared:
            shared[a.srt_g] = (float(tilt_table_angle_deg(a.srt_g)), target_checks(a.srt_g, resolved["targets"]))
        tilt, checks = shared[a.srt_g] if a.srt_g is not None else (None, [])
        rows.append(
            {
                "id": c.id,
                "station_m": station,
                "radius_m": c.radius_m,
                "superelevation_percent": c.superelevation_percent,
                "grade_percent": c.grade_percent,
                "srt_g": a.srt_g,
                "tilt_table_angle_deg": tilt,
                "targets": checks,
                "rollover_speed_kmh": a.rollover_speed_kmh,
                "side_friction_speed_kmh": a.side_friction_speed_kmh,
                "side_friction": float(fi),
                "safe_speed_kmh": a.safe_speed_kmh,
                "governed_by": a.governed_by,
                "posted_speed_kmh": a.posted_speed_kmh,
                "margin_kmh": a.margin_kmh,
                "flagged": a.flagged,
                "error": a.error,
            }
        )
    margins = [r["margin_kmh"] for r in rows if r["margin_kmh"] is not None]
    safe = [r["safe_speed_kmh"] for r in rows if r["safe_speed_kmh"] is not None]
    summary = {
        "curves": len(rows),
        "flagged": sum(r["flagged"] for r in rows),
        "refused": sum(r["error"] is not None for r in rows),
        "distinct_srt_solves": result.distinct_cases,
        "governed_by_rollover": sum(r["governed_by"] == "rollover" for r in rows),
        "governed_by_side_friction": sum(r["governed_by"] == "side-friction" for r in rows),
        "min_margin_kmh": min(margins) if margins else None,
        "min_safe_speed_kmh": min(safe) if safe else None,
    }
    return {"index": index, "preset": resolved["presets"][index], "summary": summary, "rows": rows}


def solve_alignment(resolved: dict[str, Any]) -> bytes:
    """Every curve for every vehicle (blocking: called in a worker thread) -> AlignmentResult JSON bytes."""
    started = time.perf_counter()
    curves = [Curve(i, r, e, g, v) for i, r, e, g, v, _ in resolved["curves"]]
    stations = [c[5] for c in resolved["curves"]]
    vehicles = [
        _assess_vehicle(k, Vehicle.from_dict(record), curves, stations, resolved)
        for k, record in enumerate(resolved["vehicles"])
    ]
    SOLVE_SECONDS.labels("alignments", resolved["model"]).observe(time.perf_counter() - started)
    return (
        AlignmentResult.model_validate(
            {
                "model": resolved["model"],
                "stage": resolved["stage"] if resolved["model"] == "3d" else None,
                "side_friction_bound": resolved["side_friction_bound"],
                "curves": len(curves),
                "vehicles": vehicles,
                "engine_version": ENGINE_VERSION,
            }
        )
        .model_dump_json()
        .encode()
    )


def alignment_csv(resolved: dict[str, Any], body: bytes) -> bytes:
    """One CSV table: a row per vehicle and curve, the vehicle's index and preset first."""
    names = [n for n, _ in sorted(resolved["targets"].items(), key=lambda kv: (kv[1], kv[0]))]
    columns = ["vehicle_index", "vehicle_preset", *ROW_COLUMNS, *target_columns(names), *SPEED_COLUMNS]
    data = orjson.loads(body)
    rows = (
        {"vehicle_index": v["index"], "vehicle_preset": v["preset"], **flatten_targets(r)}
        for v in data["vehicles"]
        for r in v["rows"]
    )
    return to_csv(columns, rows)


async def compute_alignment(
    cache: ResultCache, req: AlignmentRequest, settings: Settings, *, csv: bool, source_field: str | None = None
) -> Computed:
    # reading a large CSV or LandXML document takes a while: not on the event loop
    resolved = await run_in_threadpool(resolve_alignment, req, settings, source_field)

    async def produce() -> bytes:
        return await run_in_threadpool(solve_alignment, resolved)

    async def as_json() -> Computed:
        return await cached(cache, "alignments", resolved, produce)

    if not csv:
        return await as_json()
    return await cached_csv(cache, "alignments", resolved, as_json, lambda body: alignment_csv(resolved, body))
