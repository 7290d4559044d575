"""POST /v1/advisory-speed: the advisory speed of one curve, each method's speed, the treatment and the W1-13 rule."""

from __future__ import annotations

from fastapi import APIRouter, Request, Response

from app.advisory.schemas import AdvisorySpeedRequest, AdvisorySpeedResult
from app.advisory.service import OPERATION, compute_advisory_speed
from app.deps import CacheDep, SettingsDep
from app.http.fastpath import replayable
from app.http.problems import VEHICLE_REF_CODES
from app.http.responses import computed_responses, json_response
from app.vehicles.resolve import resolve_request

router = APIRouter(prefix="/v1", tags=["road"])


@router.post(
    "/advisory-speed",
    name="advisory_speed",
    response_model=AdvisorySpeedResult,
    responses=computed_responses(400, 404, 422, 500, *VEHICLE_REF_CODES),
)
@replayable(OPERATION)
async def advisory_speed(
    body: AdvisorySpeedRequest, request: Request, cache: CacheDep, settings: SettingsDep
) -> Response:
    """The advisory speed of one curve in the plaque's increment (5 mph, or 10 km/h with `units` `metric`), each
    method's speed with its source (the Design Method reported unverified; TxDOT's Direct Method from a measured car
    speed; the legacy ball-bank and calculated-speed criteria, labelled), the sign treatment by the posted-advisory
    difference (MUTCD 11e Table 2C-4 as transcribed, unverified) and the truck rollover warning (W1-13, this
    service's rule: a vehicle's rollover speed, Eq. 9.1, less a margin below the advisory speed). 422 for a posted or
    tangent speed outside 10-130 km/h, a deceleration a loaded truck cannot brake at, an increment that is not the
    sign's."""
    return json_response(await compute_advisory_speed(cache, await resolve_request(request, body, settings)))
