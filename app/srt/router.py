"""POST /v1/srt (static rollover threshold), /v1/srt/limits (inverse limits) and /v1/srt/sweep (grids)."""

from __future__ import annotations

from fastapi import APIRouter, Request, Response

from app.deps import CacheDep, SettingsDep
from app.http.bodylimit import body_limit
from app.http.fastpath import replayable
from app.http.negotiation import TABLE_FORMS, wants_csv
from app.http.problems import VEHICLE_REF_CODES
from app.http.responses import computed_response, computed_responses, json_response, table_answer, table_responses
from app.srt.limits_schemas import LimitsRequest, LimitsResult
from app.srt.limits_service import compute_limits
from app.srt.schemas import SrtRequest, SrtResult
from app.srt.service import compute_srt
from app.srt.sweep_schemas import SWEEP_BODY_LIMIT, SweepRequest, SweepResult
from app.srt.sweep_service import compute_sweep
from app.vehicles.resolve import resolve_request

router = APIRouter(prefix="/v1", tags=["srt"])


@router.post(
    "/srt",
    name="compute_srt",
    response_model=SrtResult,
    responses=computed_responses(400, 404, 422, 500, *VEHICLE_REF_CODES),
)
@replayable("srt")
async def srt(body: SrtRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """Static rollover threshold (g) of a vehicle on a road with a load case, the roll angle, the stage values,
    the state at the limit and, with `include_curves`, the curves against ay/g; whether the SRT meets each
    target (`targets`, default 0.35 g general and 0.40 g dangerous goods) and its tilt-table angle atan(SRT)."""
    return json_response(await compute_srt(cache, await resolve_request(request, body, settings), settings))


@router.post(
    "/srt/limits",
    name="limits",
    response_model=LimitsResult,
    responses=computed_responses(400, 404, 422, 500, *VEHICLE_REF_CODES),
)
@replayable("srt-limits")
async def limits(body: LimitsRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """For a target SRT, the largest CG height above the chassis, overweight or lateral offset d1 -- or the
    smallest spring separation -- at which the vehicle still meets it (Brent's bracketed root finder on the
    engine; about 10-15 SRT solves), and the same limit over a range of overweights (TERNZ's table of acceptable
    mass / load-height pairs, solved exactly)."""
    return computed_response(await compute_limits(cache, await resolve_request(request, body, settings), settings))


@router.post(
    "/srt/sweep",
    name="sweep",
    response_model=SweepResult,
    responses=table_responses(400, 404, 422, 500, *VEHICLE_REF_CODES),
    openapi_extra=body_limit(SWEEP_BODY_LIMIT),
)
@replayable("srt-sweep", offers=TABLE_FORMS)
async def sweep(body: SweepRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """The SRT over the Cartesian product of up to eight axes (bank, slope, trailer angle, d1, d2, d3,
    overweight, rear LLT limit; at most 10,000 cases: a larger grid goes to a job), like the thesis's Tables 17 and
    19, in one call; JSON, or CSV with `Accept: text/csv`. A case the engine refuses keeps its row, with `error`."""
    resolved = await resolve_request(request, body, settings)
    csv = wants_csv(request.headers.get("accept"))
    return table_answer(await compute_sweep(cache, resolved, settings, csv=csv))
