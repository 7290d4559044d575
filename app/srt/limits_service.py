"""Inverse limits (POST /v1/srt/limits): for a target SRT, the largest CG height, overweight or lateral offset (or
the smallest spring separation) that still meets it, and the same limit over a range of overweights.

Same flow as :mod:`app.srt.service`: the fully resolved request (preset expanded, defaults and targets filled) is the
cache key; the engine runs in a worker thread; the answer is JSON bytes.
"""

from __future__ import annotations

import time
from typing import Any

from starlette.concurrency import run_in_threadpool

from app.compute.cache import ResultCache
from app.compute.resolved import ResolvedLimits
from app.compute.results import Computed, cached
from app.metrics import SOLVE_SECONDS
from app.settings import Settings
from app.srt.limits_schemas import DEFAULT_OVERWEIGHTS, PARAMETER_INFO, LimitsRequest, LimitsResult
from app.srt.service import level_case, resolve_base_case, target_checks
from app.vehicles.resolve import VehicleRequest
from engine import ENGINE_VERSION, Case, InvalidInput, RolloverError
from engine.models import rollover_threshold
from engine.road import LIMIT_PARAMETERS, Limit, limit_table, parameter_limit, tilt_table_angle_deg, with_parameter


def resolve_limits(vr: VehicleRequest[LimitsRequest], settings: Settings) -> ResolvedLimits:
    req = vr.body
    table = None
    if req.parameter != "overweight_percent":
        table = tuple(req.overweights_percent) if req.overweights_percent is not None else tuple(DEFAULT_OVERWEIGHTS)
    target = req.target_srt_g if req.target_srt_g is not None else settings.srt_target_general_g
    return ResolvedLimits(
        case=resolve_base_case(req, vr.vehicles[0].vehicle, settings),
        parameter=req.parameter,
        target_srt_g=target,
        overweights_percent=table,
        limit_on=req.limit_on,
        warnings=vr.warnings or None,
    )


def srt_at(case: Case, searched: Case, limit: Limit) -> float | None:
    """The SRT of ``case`` with the parameter at the limit: the search's own ``srt_at_limit`` when ``case`` is the
    case searched on; None without a limit value or when the engine refuses the case."""
    if limit.value is None or limit.srt_at_limit is None:
        return None
    if case is searched:
        return limit.srt_at_limit
    try:
        return rollover_threshold(with_parameter(case, limit.parameter, limit.value)).srt
    except RolloverError:
        return None


def searched_case(base: Case, limit_on: str) -> Case:
    """The case the target is applied to: the level road's (:func:`app.srt.service.level_case`: the targets' basis,
    ``base`` itself when level) or the request's own."""
    return level_case(base) if limit_on == "level_road" else base


def _limit_out(limit: Limit, targets: dict[str, float], level: float | None, road: float | None) -> dict[str, Any]:
    srt = limit.srt_at_limit
    return {
        "value": limit.value,
        "status": limit.status,
        "range_min": limit.range[0],
        "range_max": limit.range[1],
        "srt_at_limit": srt,
        "level_road_srt": level,
        "road_srt": road,
        "evaluations": limit.evaluations,
        "tilt_table_angle_deg": None if srt is None else float(tilt_table_angle_deg(srt)),
        "targets": [] if level is None else target_checks(level, targets),
    }


def _current_value(case: Case, parameter: str) -> float:
    holder, name = PARAMETER_INFO[parameter][2].split(".")
    return float(getattr(case.vehicle if holder == "vehicle" else case.load, name))


def solve_limits(resolved: ResolvedLimits) -> bytes:
    """The limit and its table (blocking: called in a worker thread) -> LimitsResult JSON bytes."""
    started = time.perf_counter()
    base, targets = resolved.case.case, resolved.case.targets
    parameter, target = resolved.parameter, resolved.target_srt_g
    searched = searched_case(base, resolved.limit_on)
    try:
        limit = parameter_limit(searched, target, parameter)
    except InvalidInput as exc:
        if exc.field != parameter:
            raise
        cause = exc.__cause__
        if isinstance(cause, InvalidInput) and cause.field is not None:
            raise cause from None  # e.g. a MissingParameter: its own field says more than the searched one
        # the base case cannot be solved at the range's good end: point at the request's field
        raise type(exc)(str(exc), field="parameter", value=parameter) from exc
    table = None
    if resolved.overweights_percent is not None:
        table = []
        for ow in resolved.overweights_percent:
            try:
                (row,) = limit_table(searched, target, parameter, [ow])
            except RolloverError as exc:  # one row the engine cannot solve is reported, not dropped
                table.append(
                    {
                        "overweight_percent": ow,
                        "value": None,
                        "status": "refused",
                        "srt_at_limit": None,
                        "evaluations": 0,
                        "error": str(exc),
                    }
                )
                continue
            table.append(
                {
                    "overweight_percent": row.overweight_percent,
                    "value": row.limit.value,
                    "status": row.limit.status,
                    "srt_at_limit": row.limit.srt_at_limit,
                    "evaluations": row.limit.evaluations,
                    "error": None,
                }
            )
    SOLVE_SECONDS.labels("srt-limits", base.model).observe(time.perf_counter() - started)
    unit, symbol, _ = PARAMETER_INFO[parameter]
    return (
        LimitsResult.model_validate(
            {
                "parameter": parameter,
                "kind": limit.kind,
                "unit": unit,
                "symbol": symbol,
                "description": LIMIT_PARAMETERS[parameter][1],
                "target_srt_g": target,
                "limit_on": resolved.limit_on,
                "current_value": _current_value(base, parameter),
                "limit": _limit_out(
                    limit, targets, srt_at(level_case(base), searched, limit), srt_at(base, searched, limit)
                ),
                "table": table,
                "model": base.model,
                "stage": base.stage if base.model == "3d" else None,
                "warnings": list(resolved.warnings or ()),
                "engine_version": ENGINE_VERSION,
            }
        )
        .model_dump_json()
        .encode()
    )


async def compute_limits(cache: ResultCache, vr: VehicleRequest[LimitsRequest], settings: Settings) -> Computed:
    resolved = resolve_limits(vr, settings)

    async def produce() -> bytes:
        return await run_in_threadpool(solve_limits, resolved)

    return await cached(cache, "srt-limits", resolved, produce)
