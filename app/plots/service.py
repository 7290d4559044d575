"""The plot endpoints: the thesis's figures as SVG (app.formats.svg), from the cached SRT computation.

The curves against ay/g are the engine's :class:`~engine.results.Curves` of the memoised result of the case (so
the four figures of one case cost one solve); the SVG is cached under its own key, which holds the resolved SRT
request, the figure, the label shown in it and :data:`SVG_VERSION` (bump it when the drawing changes: the engine
version does not cover the renderer).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from starlette.concurrency import run_in_threadpool

from app.alignments.answer import AlignmentAnswer
from app.alignments.curves import curves_from_json
from app.alignments.schemas import MAX_CURVES, AlignmentRequest
from app.alignments.service import resolve_alignment, solve_alignment
from app.compute.cache import ResultCache
from app.compute.resolved import ResolvedCurvesPlot, ResolvedMinRadiusPlot
from app.compute.results import Computed, cached
from app.formats.svg import Marker, Panel, Series, line_chart
from app.http.problems import request_error
from app.plots.schemas import MinRadiusPlotRequest, PlotRequest
from app.settings import Settings
from app.srt.service import resolve_case, resolve_srt, solve
from app.vehicles.resolve import ResolvedVehicle, VehicleRequest
from engine import Case, InvalidRoad, Road, RolloverResult
from engine.road import (
    SIGN_INCREMENTS,
    DesignStandard,
    check_design_speeds,
    get_standard,
    rollover_min_radius_m,
    side_friction_factor,
    side_friction_min_radius_m,
)

SVG_MEDIA_TYPE = "image/svg+xml"
SVG_VERSION = 2  # 2: the caption names the design standard
AY = "lateral acceleration ay/g [-]"
SERIES_92 = "Eq. 9.2 (side friction)"
SERIES_93 = "Eq. 9.3 (rollover)"


def _label(v: ResolvedVehicle) -> str:
    """The vehicle as a figure's caption names it (part of the figure's key)."""
    if v.preset is not None:
        return v.preset
    if v.saved_id is not None:
        return f"saved vehicle {v.saved_id}"
    return "built vehicle" if v.kind == "spec" else "vehicle record"


def _conditions(r: RolloverResult, case: Case) -> str:
    stage = f", {r.stage} stage" if r.stage else ""
    return (
        f"{r.model} model{stage}; bank {case.road.bank_percent:g} %, slope {case.road.slope_percent:g} %, "
        f"rear LLT limit {r.rear_llt_limit:g}"
    )


def _markers(r: RolloverResult) -> list[Marker]:
    """SRT_ts and SRT_3D (3d full stage), SRT_ts (tires-suspension stage) or SRT (2d)."""
    values = r.stage_values
    if r.model == "3d":
        names = {"srt_ts": "SRT_ts", "srt_3d": "SRT_3D"}
        return [Marker(values[k], f"{names[k]} = {values[k]:.3f}") for k in ("srt_ts", "srt_3d") if k in values]
    return [Marker(r.srt, f"SRT = {r.srt:.3f}")]


def _marker_caption(r: RolloverResult) -> str:
    if r.model != "3d":
        return "SRT: the threshold (the end of the load ramp)"
    if "srt_3d" in r.stage_values:
        return "SRT_ts, SRT_3D: thresholds of the tires-and-suspension stage and of the full system"
    return "SRT_ts: threshold of the tires-and-suspension stage"


def _tire_loads(r: RolloverResult) -> tuple[str, list[Panel], str]:
    c = r.curves
    series = []
    if c.fz_front_outer_kn is not None:
        series += [
            Series("Fz1 front outer", c.ay_g, c.fz_front_outer_kn),
            Series("Fz3 front inner", c.ay_g, c.fz_front_inner_kn, dashed=True),
        ]
    series += [
        Series("Fz17 rear outer", c.ay_g, c.fz_rear_outer_kn),
        Series("Fz19 rear inner", c.ay_g, c.fz_rear_inner_kn, dashed=True),
    ]
    front = "Fz1, Fz3: front outer/inner tire normal loads; " if c.fz_front_outer_kn is not None else ""
    two_d = " (the 2D model's one axle group, Fz1/Fz3 in Ch. 5)" if r.model == "2d" else ""
    caption = (
        f"{front}Fz17, Fz19: rear outer/inner tire normal loads{two_d}, per side of each axle group; "
        f"{_marker_caption(r)} (thesis Figs. 85-87, 92)."
    )
    return "Tire normal loads", [Panel("normal load Fz [kN]", series, _markers(r))], caption


def _llt(r: RolloverResult) -> tuple[str, list[Panel], str]:
    c = r.curves
    series = [Series("LLTf front", c.ay_g, c.llt_front)] if c.llt_front is not None else []
    series.append(Series("LLTr rear", c.ay_g, c.llt_rear))
    caption = (
        "LLT = (Fz outer - Fz inner) / (Fz outer + Fz inner) of an axle group (Eq. 2.5); LLTf, LLTr: front and "
        f"rear groups; the ramp stops when LLTr reaches the rear LLT limit; {_marker_caption(r)} (thesis Fig. 93)."
    )
    return "Lateral load transfer", [Panel("lateral load transfer LLT [-]", series, _markers(r))], caption


def _roll(r: RolloverResult) -> tuple[str, list[Panel], str]:
    c = r.curves
    if r.model == "2d":
        name, text = "theta_2D", "theta_2D = theta1 + theta6 + theta8: body roll of the 2D mechanism (Ch. 5)"
    else:
        name, text = "theta_3D", "theta_3D = theta17 + theta21 + theta23 + theta27: total body roll (Ch. 6)"
    caption = f"{text}; {_marker_caption(r)} (thesis Fig. 94)."
    panel = Panel("roll angle theta [deg]", [Series(name, c.ay_g, c.roll_angle_deg)], _markers(r))
    return "Roll angle", [panel], caption


def _cg_path(r: RolloverResult) -> tuple[str, list[Panel], str]:
    c = r.curves
    markers = _markers(r)
    panels = [
        Panel("h1, lateral CG position [m]", [Series("h1", c.ay_g, c.cg_lateral_m)], markers),
        Panel("h2, CG height [m]", [Series("h2", c.ay_g, c.cg_height_m)], markers),
    ]
    eqs = "Eqs. 5.1-5.2" if r.model == "2d" else "Eqs. 6.1-6.2"
    caption = (
        f"h1: lateral distance of the CG from the outer tire contact; h2: CG height above the road ({eqs}); "
        f"the CG moves outward and down as the body rolls; {_marker_caption(r)} (thesis Figs. 96-97)."
    )
    return "CG path", panels, caption


FIGURES: dict[str, Callable[[RolloverResult], tuple[str, list[Panel], str]]] = {
    "tire-loads": _tire_loads,
    "llt": _llt,
    "roll": _roll,
    "cg-path": _cg_path,
}


def render_curves(kind: str, r: RolloverResult, label: str, case: Case) -> str:
    title, panels, caption = FIGURES[kind](r)
    return line_chart(
        f"{title} against ay/g: {label}",
        AY,
        panels,
        caption=f"{caption} Case: {label}, {_conditions(r, case)}.",
    )


async def plot_curves(cache: ResultCache, vr: VehicleRequest[PlotRequest], settings: Settings, kind: str) -> Computed:
    """One of the figures against ay/g (``FIGURES``) as SVG."""
    req, vehicle = vr.body, vr.vehicles[0]
    case = resolve_case(req, vehicle.vehicle)
    label = _label(vehicle)
    resolved = ResolvedCurvesPlot(
        srt_request=resolve_srt(case, settings.default_targets(), include_curves=True, curve_points=req.curve_points),
        figure=kind,
        label=label,
        svg_version=SVG_VERSION,
    )

    async def produce() -> bytes:
        result = await solve(cache, case, curve_points=req.curve_points)
        return render_curves(kind, result, label, case).encode()

    return await cached(cache, f"plot-{kind}", resolved, produce, SVG_MEDIA_TYPE)


# ------------------------------------------------------------------------------------ min radius


def crossing_speed(speeds: np.ndarray, e: float, srt: float, std: DesignStandard) -> float | None:
    """The design speed where Eq. 9.2 and Eq. 9.3 give the same radius, 0.01 e + f(V) = SRT, if it lies in the
    plotted range. f is linear between the standard's tabulated speeds, so the root is found exactly on those
    segments."""
    lo, hi = float(speeds[0]), float(speeds[-1])
    inner = [v for v in std.speeds_kmh if lo < v < hi]
    nodes = np.array([lo, *inner, hi])
    g = 0.01 * e + np.asarray(side_friction_factor(std, nodes)) - srt
    for a, b, ga, gb in zip(nodes[:-1], nodes[1:], g[:-1], g[1:], strict=True):
        if ga == 0:
            return float(a)
        if ga * gb < 0:
            return float(a + (b - a) * ga / (ga - gb))
    return float(nodes[-1]) if g[-1] == 0 else None


def _friction_text(std: DesignStandard) -> str:
    if std.bound:
        return f"f from the thesis's Table 21 ({std.bound} bound)"
    return f"f = the maximum side friction of {std.title}, {std.table}"


def render_min_radius(req: MinRadiusPlotRequest, r: RolloverResult, case: Case, label: str) -> str:
    std = get_standard(req.design_standard, req.bound)
    v = np.linspace(*req.speeds)
    f = np.asarray(side_friction_factor(std, v), dtype=float)
    e, s = req.superelevation_percent, r.srt
    r92 = side_friction_min_radius_m(v, e, f)  # Eq. 9.2
    r93 = rollover_min_radius_m(v, s)  # Eq. 9.3
    markers = []
    cross = crossing_speed(v, e, s, std)
    if cross is not None:
        side = "above" if r93[-1] > r92[-1] else "below"
        markers.append(Marker(cross, f"Eq. 9.3 governs {side} {cross:.1f} km/h"))
    panel = Panel(
        "minimum radius Rmin [m]",
        [
            Series(SERIES_92, list(v), list(r92)),
            Series(SERIES_93, list(v), list(r93), dashed=True),
        ],
        markers,
    )
    caption = (
        f"Eq. 9.2 (side friction): Rmin = V^2 / (127 (0.01 e + f)), {_friction_text(std)}; Eq. 9.3 (rollover): "
        f"Rmin = V^2 / (127 SRT) with SRT = {s:.3f} g, the SRT of {label} on that bank and slope "
        f"({_conditions(r, case)}); the larger radius governs (thesis Figs. 108-114)."
    )
    return line_chart(
        f"Minimum radius against design speed, e = {e:g} %: {label}", "design speed V [km/h]", [panel], caption
    )


async def plot_min_radius(cache: ResultCache, vr: VehicleRequest[MinRadiusPlotRequest], settings: Settings) -> Computed:
    req, vehicle = vr.body, vr.vehicles[0]
    std = get_standard(req.design_standard, req.bound)
    for name in ("speed_min_kmh", "speed_max_kmh"):  # in the standard's range (422 naming it), before any solve
        if getattr(req, name) is not None:
            check_design_speeds(std, getattr(req, name), field=name)
    v0, v1, _ = req.speeds
    if v1 <= v0:  # one end given at the other end of the range
        name = "speed_min_kmh" if req.speed_min_kmh is not None else "speed_max_kmh"
        raise InvalidRoad(
            f"{name} {getattr(req, name):g} km/h leaves nothing to plot: the design speeds of {std.id} are "
            f"{std.speed_range_kmh[0]:g}-{std.speed_range_kmh[1]:g} km/h",
            field=name,
            value=getattr(req, name),
        )
    # the SRT of Eq. 9.3 is the one on the curve's bank (the superelevation) and slope
    road = Road(bank_percent=req.superelevation_percent, slope_percent=req.slope_percent)
    case = resolve_case(req, vehicle.vehicle, road=road)
    label = _label(vehicle)
    resolved = ResolvedMinRadiusPlot(
        srt_request=resolve_srt(case, settings.default_targets()),
        speeds_kmh=tuple(req.speeds),
        design_standard=req.design_standard,
        side_friction_bound=req.bound,
        label=label,
        svg_version=SVG_VERSION,
    )

    async def produce() -> bytes:
        return render_min_radius(req, await solve(cache, case), case, label).encode()

    return await cached(cache, "plot-min-radius", resolved, produce, SVG_MEDIA_TYPE)


# ------------------------------------------------------------------------------------------ the speed profile

SERIES_PROFILE = "truck's speed profile"
SERIES_SAFE = "safe speed (Eq. 9.1 / side friction)"
SERIES_ADVISORY = "advisory speed shown"
SERIES_POSTED = "posted speed"


def _spans(start: np.ndarray, end: np.ndarray, values: np.ndarray) -> tuple[list[float], list[float]]:
    """Each curve's value over its span, the spans separated by a gap (nan): a step per curve, no line across the
    tangents between them."""
    x = np.column_stack((start, end, end)).ravel()
    y = np.column_stack((values, values, np.full(len(values), np.nan))).ravel()
    return x.tolist(), y.tolist()


def render_speed_profile(answer: AlignmentAnswer, starts: np.ndarray, lengths: np.ndarray, source: str) -> str:
    """Speed against station, a panel per vehicle: its profile (engine/road/profile.py), each curve's safe and
    advisory speed over the curve's span, and the posted speed. A vehicle without a profile is a 422 naming the
    curves' field with the first row's reason."""
    ends = starts + lengths
    panels = []
    for v in answer.vehicles:
        a = v.advice
        if not len(a.station_m):
            why = next((a.reasons[k] for k in a.reason.tolist() if k >= 0), None) or "; ".join(a.notes)
            raise request_error(source, f"no speed profile to plot (vehicle {v.index}): {why}")
        c = v.columns
        label = v.preset or v.saved_id or f"vehicle {v.index}"
        panels.append(
            Panel(
                f"speed [km/h]: {label}",
                [
                    Series(SERIES_PROFILE, a.station_m.tolist(), a.speed_kmh.tolist()),
                    Series(SERIES_SAFE, *_spans(starts, ends, c.safe_speed_kmh), gaps=True),
                    Series(SERIES_ADVISORY, *_spans(starts, ends, a.advisory_speed_kmh), dashed=True, gaps=True),
                    Series(SERIES_POSTED, *_spans(starts, ends, c.posted_speed_kmh), gaps=True),
                ],
            )
        )
    r = answer.resolved
    increment = f"{SIGN_INCREMENTS[r.units]:g} {'mph' if r.units == 'us' else 'km/h'}"
    caption = (
        "The truck's speed along the road: the desired (posted) speed on the tangents, braking into each curve at "
        f"{r.deceleration_mps2:g} m/s^2 and accelerating out of it within its power on the grade, never above a "
        "curve's safe speed (the lower of rollover, thesis Eq. 9.1, and side friction) or its advisory speed "
        f"(shown in {increment} steps; FHWA-SA-11-22 / TxDOT Design Method). docs/advisory.md."
    )
    return line_chart("Truck speed profile against station", "station [m]", panels, caption)


async def plot_speed_profile(cache: ResultCache, vr: VehicleRequest[AlignmentRequest], settings: Settings) -> Computed:
    """The speed-profile plot of an alignment request (the body of ``POST /v1/alignments/assess``), cached under the
    alignment's resolved key (which holds the engine version, not :data:`SVG_VERSION`: a change of this drawing
    alone needs the operation renamed)."""
    req = vr.body
    curves = None if req.curves is None else curves_from_json([c.model_dump() for c in req.curves], MAX_CURVES)
    job = await run_in_threadpool(resolve_alignment, vr, curves, settings)

    async def produce() -> bytes:
        def draw() -> bytes:
            starts, lengths, _ = job.curve_places()
            return render_speed_profile(solve_alignment(job), starts, lengths, job.source).encode()

        return await run_in_threadpool(draw)

    return await cached(cache, "plot-speed-profile", job.resolved, produce, SVG_MEDIA_TYPE)
