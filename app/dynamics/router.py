"""POST /v1/dynamics/{lane-change,frequency-response,pulse-steer,stability,steady-turn,low-speed-turn} and
POST /v1/pbs: the combination in motion, an indicative screening."""

from __future__ import annotations

from fastapi import APIRouter, Request, Response

from app.deps import CacheDep, SettingsDep
from app.dynamics import schemas as s
from app.dynamics import service
from app.http.fastpath import replayable
from app.http.problems import VEHICLE_REF_CODES
from app.http.responses import computed_response, computed_responses, json_response
from app.plots.router import svg_responses
from app.vehicles.resolve import resolve_request

router = APIRouter(prefix="/v1/dynamics", tags=["dynamics"])
pbs_router = APIRouter(prefix="/v1", tags=["pbs"])
CODES = computed_responses(400, 404, 422, 500, *VEHICLE_REF_CODES)


@router.post("/lane-change", name="lane_change", response_model=s.LaneChangeResult, responses=CODES)
@replayable("dynamics-lane-change")
async def lane_change(body: s.LaneChangeRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """Single lane change: one sine period of the steer axle's lateral acceleration; rearward amplification,
    high-speed transient offtracking, peak load transfer ratio per roll-coupled unit, peak lateral acceleration and
    roll per unit. Indicative screening by a linear model: lift-off ends its validity (flagged in `validity`)."""
    return json_response(await service.compute_lane_change(cache, await resolve_request(request, body, settings)))


@router.post("/frequency-response", name="frequency_response", response_model=s.FrequencyResponseResult,
             responses=CODES)  # fmt: skip
@replayable("dynamics-frequency-response")
async def frequency_response(body: s.FrequencyResponseRequest, request: Request, cache: CacheDep,
                             settings: SettingsDep) -> Response:  # fmt: skip
    """Rearward amplification against frequency (the ratio of the rear unit's to the steer axle's lateral
    acceleration amplitudes) and its worst frequency."""
    return json_response(
        await service.compute_frequency_response(cache, await resolve_request(request, body, settings))
    )


@router.post("/pulse-steer", name="pulse_steer", response_model=s.PulseSteerResult, responses=CODES)
@replayable("dynamics-pulse-steer")
async def pulse_steer(body: s.PulseSteerRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """Yaw damping of the rearmost articulation after a steer pulse (successive same-sign peaks, full-cycle
    logarithmic decrement), the least-damped mode's damping ratio, frequency and shape, and every eigenvalue."""
    return json_response(await service.compute_pulse_steer(cache, await resolve_request(request, body, settings)))


@router.post("/stability", name="stability", response_model=s.StabilityResult, responses=CODES)
@replayable("dynamics-stability")
async def stability(body: s.StabilityRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """The speed at which trailer sway reaches zero damping and the speed of any divergence (null where stable up
    to 200 km/h)."""
    return json_response(await service.compute_stability(cache, await resolve_request(request, body, settings)))


@router.post("/steady-turn", name="steady_turn", response_model=s.SteadyTurnResult, responses=CODES)
@replayable("dynamics-steady-turn")
async def steady_turn(body: s.SteadyTurnRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """Steady turn at a radius and speed: every group's path radius and offtracking, every unit's articulation and
    roll, the load transfer ratio of every roll-coupled unit."""
    return json_response(await service.compute_steady_turn(cache, await resolve_request(request, body, settings)))


@router.post("/low-speed-turn", name="low_speed_turn", response_model=s.LowSpeedTurnResult, responses=CODES)
@replayable("dynamics-low-speed-turn")
async def low_speed_turn(body: s.LowSpeedTurnRequest, request: Request, cache: CacheDep,
                         settings: SettingsDep) -> Response:  # fmt: skip
    """The low-speed 90 degree turn (12.5 m radius at the outer steer tyre, no slip): swept path width, tail swing,
    frontal swing and the path of every corner of every unit."""
    return json_response(await service.compute_low_speed_turn(cache, await resolve_request(request, body, settings)))


@pbs_router.post("/pbs", name="pbs", response_model=s.PbsResult, responses=CODES)
@replayable("pbs")
async def pbs(body: s.PbsRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """Performance-Based Standards screening: every standard this model can judge with its value, the limits per
    level with their sources (a null limit, `verified: false`, where the rules' text could not be read: no number
    is given for it), the level met by verified limits only (null without one), the rules' version, the length's
    network level and the standards not judged. The manoeuvres' default speeds and amplitude are unverified: set
    them to the rules' values (`conditions` names those left at default). Indicative screening, not a
    certification."""
    return json_response(await service.compute_pbs(cache, await resolve_request(request, body, settings)))


@router.post("/plots/lane-change", name="plot_lane_change", response_class=Response,
             responses=svg_responses("lateral acceleration of every unit against time in the lane change"))  # fmt: skip
@replayable("dynamics-plot-lane-change")
async def plot_lane_change(body: s.LaneChangeRequest, request: Request, cache: CacheDep,
                           settings: SettingsDep) -> Response:  # fmt: skip
    """The lane change's lateral acceleration of every unit against time, as SVG (the lane change's body)."""
    return computed_response(await service.plot_lane_change(cache, await resolve_request(request, body, settings)))


@router.post("/plots/frequency-response", name="plot_frequency_response", response_class=Response,
             responses=svg_responses("rearward amplification against frequency, the worst marked"))  # fmt: skip
@replayable("dynamics-plot-frequency-response")
async def plot_frequency_response(body: s.FrequencyResponseRequest, request: Request, cache: CacheDep,
                                  settings: SettingsDep) -> Response:  # fmt: skip
    """Rearward amplification against frequency, the worst frequency marked, as SVG."""
    return computed_response(
        await service.plot_frequency_response(cache, await resolve_request(request, body, settings))
    )


LOW_SPEED_SVG = svg_responses("the paths of every corner of every unit in the 90 degree turn, to scale")


@router.post("/plots/low-speed-turn", name="plot_low_speed_turn", response_class=Response, responses=LOW_SPEED_SVG)
@replayable("dynamics-plot-low-speed-turn")
async def plot_low_speed_turn(body: s.LowSpeedTurnRequest, request: Request, cache: CacheDep,
                              settings: SettingsDep) -> Response:  # fmt: skip
    """The low-speed turn's corner paths and the outer steer tyre's path, to scale, as SVG."""
    return computed_response(await service.plot_low_speed_turn(cache, await resolve_request(request, body, settings)))
