"""``POST /v1/plots/*``: the thesis's figures for one case, as SVG."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Request, Response

from app.alignments.service import resolve_assessment_request
from app.deps import CacheDep, SettingsDep
from app.http.fastpath import replayable
from app.http.problems import VEHICLE_REF_CODES, error_responses
from app.http.responses import CACHE_HEADERS, computed_response
from app.plots.schemas import MinRadiusPlotRequest, PlotRequest, SpeedProfilePlotRequest
from app.plots.service import SVG_MEDIA_TYPE, plot_curves, plot_min_radius, plot_speed_profile
from app.vehicles.resolve import resolve_request

router = APIRouter(prefix="/v1/plots", tags=["plots"])


def svg_responses(what: str) -> dict[int | str, dict[str, Any]]:
    return {
        200: {
            "description": f'SVG image: {what}. Every series is a `<g class="series" data-name=...>` whose '
            "`<polyline>` lists the plotted values in `data-x` / `data-y`.",
            "content": {SVG_MEDIA_TYPE: {"schema": {"type": "string"}}},
            "headers": CACHE_HEADERS,
        },
        **error_responses(400, 404, 422, 500, *VEHICLE_REF_CODES),
    }


@router.post("/tire-loads", name="tire_loads", response_class=Response,
             responses=svg_responses("Fz1, Fz3, Fz17, Fz19 against ay/g"))  # fmt: skip
@replayable("plot-tire-loads")
async def tire_loads(body: PlotRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """Tire normal loads against ay/g (thesis Figs. 85-87, 92): Fz1, Fz3 (front outer/inner; 3d only), Fz17,
    Fz19 (rear outer/inner), with markers at SRT_ts and SRT_3D (3d full stage) or the SRT."""
    return computed_response(
        await plot_curves(cache, await resolve_request(request, body, settings), settings, "tire-loads")
    )


@router.post("/llt", name="llt", response_class=Response, responses=svg_responses("LLTf, LLTr against ay/g"))
@replayable("plot-llt")
async def llt(body: PlotRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """Front and rear lateral load transfer against ay/g (thesis Fig. 93); LLTf for the 3d model only."""
    return computed_response(await plot_curves(cache, await resolve_request(request, body, settings), settings, "llt"))


@router.post("/roll", name="roll", response_class=Response, responses=svg_responses("theta against ay/g"))
@replayable("plot-roll")
async def roll(body: PlotRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """Total body roll angle theta_3D (2D: theta1 + theta6 + theta8) against ay/g (thesis Fig. 94)."""
    return computed_response(await plot_curves(cache, await resolve_request(request, body, settings), settings, "roll"))


@router.post("/cg-path", name="cg_path", response_class=Response,
             responses=svg_responses("h1 and h2 against ay/g, two panels"))  # fmt: skip
@replayable("plot-cg-path")
async def cg_path(body: PlotRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """The CG's path: its lateral position h1 and height h2 against ay/g, two panels (thesis Figs. 96-97)."""
    return computed_response(
        await plot_curves(cache, await resolve_request(request, body, settings), settings, "cg-path")
    )


@router.post("/min-radius", name="min_radius", response_class=Response,
             responses=svg_responses("Rmin of Eqs. 9.2 and 9.3 against the design speed"))  # fmt: skip
@replayable("plot-min-radius")
async def min_radius(body: MinRadiusPlotRequest, request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """Minimum radius against design speed for one superelevation (thesis Figs. 108-114): Eq. 9.2 with the design
    standard's f_max (AASHTO 2018 by default; `thesis-table21` draws the thesis's figures) against rollover Eq. 9.3
    with the vehicle's SRT on that bank and slope, with a marker where they cross (below or above it rollover
    governs). The speeds must lie in the standard's range, and `speed_max_kmh` must be above `speed_min_kmh` (rules
    JSON Schema cannot state: a request breaking one is a 422 naming the field and the range)."""
    return computed_response(await plot_min_radius(cache, await resolve_request(request, body, settings), settings))


@router.post("/speed-profile", name="speed_profile", response_class=Response,
             responses=svg_responses("the truck's speed against station, with each curve's safe, advisory and "
                                     "posted speed"))  # fmt: skip
@replayable("plot-speed-profile")
async def speed_profile(
    body: SpeedProfilePlotRequest, request: Request, cache: CacheDep, settings: SettingsDep
) -> Response:
    """The speed profile of `POST /v1/alignments/assess` (the same body: curves as JSON, CSV or LandXML) as a plot:
    per vehicle, its speed against station (engine/road/profile.py), each curve's safe and advisory speed over the
    curve, and the posted speed (docs/advisory.md). Curves without stations (a JSON or CSV list) have no profile: a
    422 naming the curves' field and the reason."""
    resolved = await resolve_assessment_request(request, body, settings)
    return computed_response(await plot_speed_profile(cache, resolved, settings))
