"""The static rollover threshold (POST /v1/srt), and the SRT pieces every other computation uses.

Data flows one way: validated request -> engine :class:`~engine.case.Case` (preset expanded, defaults filled) ->
cache key (derived from the case) -> engine (in a worker thread) -> result object -> response body (JSON bytes,
stored as is in the cache). A computation that needs another one's result (the SRT inside a curve speed, a
minimum radius or a plot) asks :func:`solve` for the engine's result object, memoised per process: it never
parses another endpoint's cached bytes.

Public for the other features (road, plots, limits, sweep, alignments, routes): :func:`resolve_case` (an SRT
request's engine case), :func:`resolve_targets` and the target checks, :func:`resolve_srt` /
:func:`resolve_base_case` (the typed requests whose keys hold an SRT request: :mod:`app.compute.resolved`),
:func:`solve`, :func:`level_case` / :func:`solve_with_level` (the level-road case
the targets are judged on) and :func:`srt_result`.
"""

from __future__ import annotations

import asyncio
import dataclasses
import time
from typing import Any

import numpy as np
from starlette.concurrency import run_in_threadpool

from app.compute.cache import ResultCache, cache_key
from app.compute.coalescer import COALESCER
from app.compute.resolved import JUDGED_ON, ResolvedCase, ResolvedSrt
from app.compute.results import Computed, cached
from app.metrics import SOLVE_SECONDS
from app.settings import Settings
from app.srt.schemas import SrtInputs, SrtRequest, SrtResult
from app.vehicles.resolve import VehicleRequest
from engine import ENGINE_VERSION, Case, LoadCase, Road, RolloverResult
from engine.models import rollover_threshold
from engine.road import check_targets, tilt_table_angle_deg
from engine.vehicle import Combination, InputWarning, Vehicle

# ------------------------------------------------------------------------------------- resolution


def resolve_case(req: SrtInputs, vehicle: Vehicle | Combination, *, road: Road | None = None) -> Case:
    """The engine case of an SRT request with its resolved vehicle (:mod:`app.vehicles.resolve`; ``road`` replaces
    the request's, e.g. a curve's own)."""
    road = road if road is not None else Road(**req.road.model_dump())
    return Case(
        vehicle=vehicle,
        model=req.model,
        stage=req.stage,
        road=road,
        trailer_angle_deg=req.trailer_angle_deg,
        load=LoadCase(**req.load.model_dump()),
        rear_llt_limit=req.rear_llt_limit,
    )


def resolve_targets(targets: dict[str, float] | None, settings: Settings) -> dict[str, float]:
    """The SRT targets of a request: its own, else the configured defaults (name -> minimum SRT [g])."""
    return dict(targets) if targets is not None else settings.default_targets()


def level_case(case: Case) -> Case:
    """The case the targets are judged on: the same vehicle, load, model and parameters on a level road (bank and
    slope zero). ``case`` itself when it is level, so a level case's ``level_road_srt`` is its ``srt`` exactly."""
    if case.road.bank_percent == 0.0 and case.road.slope_percent == 0.0:
        return case
    return case.replace(road=Road())


def target_checks(level_srt_g: float, targets: dict[str, float]) -> list[dict[str, Any]]:
    """``TargetCheckOut`` dicts for a level-road SRT (:func:`level_case`), in order of increasing target (then
    name): the order is fixed by the targets themselves, so equal targets given in any order give the same body and
    the same cache key."""
    checks = _in_target_order(check_targets(level_srt_g, targets))
    return [
        {"name": c.name, "target_g": c.target_g, "meets": c.meets, "margin_g": c.margin_g, "judged_on": JUDGED_ON}
        for c in checks
    ]


def _in_target_order(checks: list[Any]) -> list[Any]:
    return sorted(checks, key=lambda c: (c.target_g, c.name))


def target_checks_many(srts: np.ndarray, targets: dict[str, float]) -> list[list[dict[str, Any]]]:
    """:func:`target_checks` of every level-road SRT of ``srts`` at once: the same dicts, the same order; the targets
    are checked once, the comparisons and margins done on arrays."""
    ordered = _in_target_order(check_targets(0.0, targets))  # the targets checked, in order (the SRT is unused)
    per_target = [
        [
            {"name": c.name, "target_g": c.target_g, "meets": meets, "margin_g": margin, "judged_on": JUDGED_ON}
            for meets, margin in zip((srts >= c.target_g).tolist(), (srts - c.target_g).tolist(), strict=True)
        ]
        for c in ordered
    ]
    return [list(checks) for checks in zip(*per_target, strict=True)] if per_target else [[] for _ in srts]


def resolve_srt(
    case: Case,
    targets: dict[str, float],
    *,
    include_curves: bool = False,
    curve_points: int | None = None,
    warnings: tuple[dict[str, Any], ...] = (),
) -> ResolvedSrt:
    """The resolved SRT request hashed into a key: the case, whether (and how finely) the curves are asked for, the
    targets the result is checked against (they are in the body, so they are in the key) and the vehicle's input
    warnings (:attr:`app.vehicles.resolve.VehicleRequest.warnings`: the answer carries them)."""
    return ResolvedSrt(
        base=ResolvedCase(case=case, targets=dict(targets)),
        include_curves=include_curves,
        curve_points=curve_points,
        warnings=warnings,
    )


def resolve_base_case(req: SrtInputs, vehicle: Vehicle | Combination, settings: Settings) -> ResolvedCase:
    """The base case of a limits or sweep request and its targets (no curves: those fields would only blur the key)."""
    return ResolvedCase(case=resolve_case(req, vehicle), targets=resolve_targets(req.targets, settings))


# -------------------------------------------------------------------------------------- computing


async def solve(cache: ResultCache, case: Case, *, curve_points: int | None = None) -> RolloverResult:
    """The engine's result for ``case`` (with its curves at ``curve_points`` points when given), memoised per
    process by the case's key. A single threshold is solved on the event loop (about a millisecond: cheaper than the
    hop to a worker thread); the curves, tens of solves, in a worker thread."""
    key = cache_key("engine-result", {**case.to_dict(), "curve_points": curve_points})
    result = cache.objects.get(key)
    if result is not None:
        return result
    running = cache.solving.get(key)
    if running is not None:  # the same case is being solved for another request: its answer is this one's
        return await asyncio.shield(running)
    task = asyncio.ensure_future(_solve_once(cache, key, case, curve_points))
    cache.solving[key] = task
    return await asyncio.shield(task)  # a request that leaves does not cancel the solve the others wait for


async def _solve_once(cache: ResultCache, key: str, case: Case, curve_points: int | None) -> RolloverResult:
    try:
        if curve_points is None:  # one threshold, on the event loop with the others waiting now (app.compute.coalescer)
            result = await COALESCER.threshold(case)
        else:  # the curves are tens of solves: not on the event loop
            started = time.perf_counter()
            result = await run_in_threadpool(rollover_threshold, case, include_curves=True, curve_points=curve_points)
            SOLVE_SECONDS.labels("srt", case.model).observe(time.perf_counter() - started)
        cache.objects[key] = result
        return result
    finally:
        cache.solving.pop(key, None)


async def solve_with_level(
    cache: ResultCache, case: Case, *, curve_points: int | None = None
) -> tuple[RolloverResult, RolloverResult]:
    """The engine's results for ``case`` and for its :func:`level_case` (the same object when the case is level; the
    level case without curves): both through :func:`solve`, so both are memoised."""
    result = await solve(cache, case, curve_points=curve_points)
    level = level_case(case)
    return result, (result if level is case else await solve(cache, level))


def srt_result(
    result: RolloverResult,
    targets: dict[str, float],
    level: RolloverResult | None = None,
    warnings: list[InputWarning] | None = None,
) -> SrtResult:
    """The published SRT result of an engine result and of its level-road case's (:func:`level_case`; None: the case
    is level), validated against the schema (a contract break is loud). The targets are judged on the level SRT;
    ``warnings``: the inputs that read plausibly in another unit too
    (:attr:`app.vehicles.resolve.ResolvedVehicle.warnings`)."""
    level_srt = result.srt if level is None else level.srt
    data = result.to_dict()
    detail = data.pop("combination", None)
    if detail is not None:  # the whole-combination model: every roll-coupled unit, flattened into the answer
        data["roll_coupled_units"] = detail["roll_coupled_units"]
        data["governing_unit"] = detail["governing"]
        data["last_unit_front_llt_ratio"] = detail["last_unit_front_llt_ratio"]
        lifts = [e for r in detail["roll_coupled_units"] for e in r["lift_sequence"]]
        data["lift_sequence"] = sorted(lifts, key=lambda e: e["ay_g"])
    data["tilt_table_angle_deg"] = float(tilt_table_angle_deg(result.srt))
    data["level_road_srt"] = level_srt
    data["targets"] = target_checks(level_srt, targets)
    data["engine_version"] = ENGINE_VERSION
    data["warnings"] = [dataclasses.asdict(w) for w in warnings or ()]
    return SrtResult.model_validate(data)


async def compute_srt(cache: ResultCache, vr: VehicleRequest[SrtRequest], settings: Settings) -> Computed:
    req, vehicle = vr.body, vr.vehicles[0]
    case = resolve_case(req, vehicle.vehicle)
    targets = resolve_targets(req.targets, settings)
    resolved = resolve_srt(
        case, targets, include_curves=req.include_curves, curve_points=req.curve_points, warnings=vr.warnings
    )
    points = resolved.curve_points  # None without curves (ResolvedSrt): what the key holds is what is solved

    warnings = list(vehicle.warnings)

    async def produce() -> bytes:
        result, level = await solve_with_level(cache, case, curve_points=points)
        return srt_result(result, targets, level, warnings).model_dump_json().encode()

    return await cached(cache, "srt", resolved, produce)
