"""POST /v1/curve-speed (Eq. 9.1) and POST /v1/min-radius (Eqs. 9.2-9.3, f from a design standard)."""

from __future__ import annotations

from fastapi import APIRouter, Request, Response

from app.deps import CacheDep, SettingsDep
from app.http.fastpath import replayable
from app.http.problems import VEHICLE_REF_CODES
from app.http.responses import computed_responses, json_response
from app.road.schemas import CurveSpeedRequest, CurveSpeedResult, MinRadiusRequest, MinRadiusResult
from app.road.service import compute_curve_speed, compute_min_radius
from app.vehicles.resolve import resolve_request

router = APIRouter(prefix="/v1", tags=["road"])


@router.post(
    "/curve-speed",
    name="curve_speed",
    response_model=CurveSpeedResult,
    responses=computed_responses(400, 404, 422, 500, *VEHICLE_REF_CODES),
)
@replayable("curve-speed")
async def curve_speed(body: CurveSpeedRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """Maximum speed on a curve of radius R before rollover, V = sqrt(127 SRT R) [km/h] (Eq. 9.1).

    The SRT is either given or computed from the SRT request fields for `road`'s bank and slope; it already
    contains the bank, so no superelevation term is added."""
    return json_response(await compute_curve_speed(cache, await resolve_request(request, body, settings), settings))


@router.post(
    "/min-radius",
    name="min_radius",
    response_model=MinRadiusResult,
    responses=computed_responses(400, 404, 422, 500, *VEHICLE_REF_CODES),
)
@replayable("min-radius")
async def min_radius(body: MinRadiusRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """Minimum curve radius for a design speed and superelevation: Eq. 9.2 (side friction: the design standard's
    f_max, AASHTO 2018 by default, unless `side_friction` is given), Eq. 9.3 (rollover, the SRT on that bank and
    slope) and the governing one. The design speed must lie in the standard's range (422 naming it)."""
    return json_response(await compute_min_radius(cache, await resolve_request(request, body, settings), settings))
