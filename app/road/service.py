"""Curve design over HTTP: the maximum speed on a curve (POST /v1/curve-speed, Eq. 9.1) and the minimum radius for a
design speed (POST /v1/min-radius, Eqs. 9.2-9.3: side friction with the design standard's f_max against rollover).

The SRT either comes with the request or is solved from its SRT fields (:func:`app.srt.service.solve`, memoised per
process: the same case as ``POST /v1/srt`` is one solve); its key is part of the answer's key.
"""

from __future__ import annotations

from typing import Any

from app.compute.cache import ResultCache
from app.compute.resolved import ResolvedCurveSpeed, ResolvedMinRadius
from app.compute.results import Computed, cached
from app.road.schemas import CurveSpeedRequest, CurveSpeedResult, MinRadiusRequest, MinRadiusResult
from app.settings import Settings
from app.srt.schemas import SrtResult
from app.srt.service import (
    resolve_case,
    resolve_srt,
    resolve_targets,
    solve_with_level,
    srt_result,
)
from app.vehicles.resolve import VehicleRequest
from engine import ENGINE_VERSION, Case, Road
from engine.road import max_curve_speed_kmh, min_radius, side_friction_factor


async def _srt_for(
    cache: ResultCache, vr: VehicleRequest[Any], case: Case | None, targets: dict[str, float]
) -> tuple[float, str, SrtResult | None]:
    """(srt, source, the SRT result or None) for a curve-speed/min-radius request; the SRT result carries the
    request's input warnings (a record's weight plausible in kN and in tonnes)."""
    if case is None or vr.vehicle is None:
        return vr.body.srt, "given", None
    engine_result, level = await solve_with_level(cache, case)
    result = srt_result(engine_result, targets, level, list(vr.vehicle.warnings))
    return result.srt, "computed", result


async def compute_curve_speed(
    cache: ResultCache, vr: VehicleRequest[CurveSpeedRequest], settings: Settings
) -> Computed:
    req = vr.body
    targets = resolve_targets(req.targets, settings)
    case = resolve_case(req, vr.vehicle.vehicle) if req.srt is None and vr.vehicle is not None else None
    srt_request = None if case is None else resolve_srt(case, targets, warnings=vr.warnings)
    resolved = ResolvedCurveSpeed.of(req, srt_request=srt_request)

    async def produce() -> bytes:
        srt, source, inner = await _srt_for(cache, vr, case, targets)
        speed = float(max_curve_speed_kmh(srt, req.radius_m))  # Eq. 9.1; the SRT already contains the bank
        out = CurveSpeedResult(
            max_speed_kmh=speed,
            radius_m=req.radius_m,
            srt=srt,
            level_road_srt=None if inner is None else inner.level_road_srt,
            srt_source=source,
            srt_result=inner,
            engine_version=ENGINE_VERSION,
        )
        return out.model_dump_json().encode()

    return await cached(cache, "curve-speed", resolved, produce)


async def compute_min_radius(cache: ResultCache, vr: VehicleRequest[MinRadiusRequest], settings: Settings) -> Computed:
    # Eq. 9.3 needs the SRT on this curve's bank: the bank is the superelevation
    req = vr.body
    targets = resolve_targets(req.targets, settings)
    road = Road(bank_percent=req.superelevation_percent, slope_percent=req.road.slope_percent)
    case = resolve_case(req, vr.vehicle.vehicle, road=road) if req.srt is None and vr.vehicle is not None else None
    if req.side_friction is None:  # refuse a speed outside the standard's range before solving for the SRT
        side_friction_factor(req.design_standard, req.design_speed_kmh, req.bound)
    resolved = ResolvedMinRadius.of(  # the bound in force (Table 21's default filled), not the one typed
        req,
        side_friction_bound=req.bound,
        srt_request=None if case is None else resolve_srt(case, targets, warnings=vr.warnings),
    )

    async def produce() -> bytes:
        srt, source, inner = await _srt_for(cache, vr, case, targets)
        r = min_radius(
            req.design_speed_kmh,
            req.superelevation_percent,
            srt,
            side_friction=req.side_friction,
            design_standard=req.design_standard,
            bound=req.bound,
        )
        out = MinRadiusResult(
            side_friction_min_radius_m=r.side_friction_min_radius_m,
            aashto_min_radius_m=r.side_friction_min_radius_m,
            rollover_min_radius_m=r.rollover_min_radius_m,
            governing_min_radius_m=r.governing_min_radius_m,
            governed_by=r.governed_by,
            side_friction=r.side_friction,
            side_friction_source=r.side_friction_source,
            design_standard=r.design_standard,
            design_speed_kmh=req.design_speed_kmh,
            superelevation_percent=req.superelevation_percent,
            srt=srt,
            level_road_srt=None if inner is None else inner.level_road_srt,
            srt_source=source,
            srt_result=inner,
            engine_version=ENGINE_VERSION,
        )
        return out.model_dump_json().encode()

    return await cached(cache, "min-radius", resolved, produce)
