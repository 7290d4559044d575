"""Inverse limits (POST /v1/srt/limits) and grid sweeps (POST /v1/srt/sweep): request -> engine -> body.

Same flow as :mod:`app.service`: the fully resolved request (preset expanded, defaults and targets filled) is the
cache key; the engine runs in a worker thread; the body is JSON bytes, and the sweep's CSV form is rendered from
it and cached under its own key.
"""

from __future__ import annotations

import time
from typing import Any

import orjson
from starlette.concurrency import run_in_threadpool

from engine import ENGINE_VERSION
from engine.assessment import LIMIT_PARAMETERS, Limit, limit_table, parameter_limit, tilt_table_angle_deg
from engine.case import Case
from engine.errors import InvalidInput, RolloverError
from engine.threshold import sweep

from .cache import ResultCache
from .metrics import SOLVE_SECONDS
from .schemas.limits import DEFAULT_OVERWEIGHTS, PARAMETER_INFO, LimitsRequest, LimitsResult
from .schemas.sweep import SweepRequest, SweepResult
from .service import Computed, cached, cached_csv, resolve_case, resolve_targets, srt_key, target_checks
from .settings import Settings
from .tables import flatten_targets, target_columns, to_csv


def _srt_case(req, settings: Settings) -> dict[str, Any]:
    """The resolved base case of a limits or sweep request (no curves: those fields would only blur the key)."""
    base = srt_key(resolve_case(req), resolve_targets(req.targets, settings))
    del base["include_curves"], base["curve_points"]
    return base


def _case(resolved_case: dict[str, Any]) -> Case:
    return Case.from_dict({k: v for k, v in resolved_case.items() if k != "targets"})


# ------------------------------------------------------------------------------------------ limits


def resolve_limits(req: LimitsRequest, settings: Settings) -> dict[str, Any]:
    table = None
    if req.parameter != "overweight_percent":
        table = list(req.overweights_percent) if req.overweights_percent is not None else list(DEFAULT_OVERWEIGHTS)
    target = req.target_srt_g if req.target_srt_g is not None else settings.srt_target_general_g
    return {
        "case": _srt_case(req, settings),
        "parameter": req.parameter,
        "target_srt_g": target,
        "overweights_percent": table,
    }


def _limit_out(limit: Limit, targets: dict[str, float]) -> dict[str, Any]:
    srt = limit.srt_at_limit
    return {
        "value": limit.value,
        "status": limit.status,
        "range_min": limit.range[0],
        "range_max": limit.range[1],
        "srt_at_limit": srt,
        "evaluations": limit.evaluations,
        "tilt_table_angle_deg": None if srt is None else float(tilt_table_angle_deg(srt)),
        "targets": [] if srt is None else target_checks(srt, targets),
    }


def _current_value(case: Case, parameter: str) -> float:
    holder, name = PARAMETER_INFO[parameter][2].split(".")
    return float(getattr(case.vehicle if holder == "vehicle" else case.load, name))


def solve_limits(resolved: dict[str, Any]) -> bytes:
    """The limit and its table (blocking: called in a worker thread) -> LimitsResult JSON bytes."""
    started = time.perf_counter()
    case = resolved["case"]
    base = _case(case)
    parameter, target = resolved["parameter"], resolved["target_srt_g"]
    try:
        limit = parameter_limit(base, target, parameter)
    except InvalidInput as exc:
        if exc.field != parameter:
            raise
        cause = exc.__cause__
        if isinstance(cause, InvalidInput) and cause.field is not None:
            raise cause from None  # e.g. a MissingParameter: its own field says more than the searched one
        # the base case cannot be solved at the range's good end: point at the request's field
        raise type(exc)(str(exc), field="parameter", value=parameter) from exc
    table = None
    if resolved["overweights_percent"] is not None:
        table = []
        for ow in resolved["overweights_percent"]:
            try:
                (row,) = limit_table(base, target, parameter, [ow])
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
    SOLVE_SECONDS.labels("srt-limits", case["model"]).observe(time.perf_counter() - started)
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
                "current_value": _current_value(base, parameter),
                "limit": _limit_out(limit, case["targets"]),
                "table": table,
                "model": case["model"],
                "stage": case["stage"] if case["model"] == "3d" else None,
                "engine_version": ENGINE_VERSION,
            }
        )
        .model_dump_json()
        .encode()
    )


async def compute_limits(cache: ResultCache, req: LimitsRequest, settings: Settings) -> Computed:
    resolved = resolve_limits(req, settings)

    async def produce() -> bytes:
        return await run_in_threadpool(solve_limits, resolved)

    return await cached(cache, "srt-limits", resolved, produce)


# ------------------------------------------------------------------------------------------- sweep


def resolve_sweep(req: SweepRequest, settings: Settings) -> dict[str, Any]:
    return {"case": _srt_case(req, settings), "grid": req.grid.axes()}


def solve_sweep(resolved: dict[str, Any]) -> bytes:
    """Every case of the grid (blocking: called in a worker thread) -> SweepResult JSON bytes."""
    started = time.perf_counter()
    case, grid = resolved["case"], resolved["grid"]
    result = sweep(_case(case), grid)
    targets = case["targets"]
    rows = result.rows()
    for row in rows:
        srt = row["srt"]
        row["tilt_table_angle_deg"] = None if srt is None else float(tilt_table_angle_deg(srt))
        row["targets"] = [] if srt is None else target_checks(srt, targets)
    SOLVE_SECONDS.labels("srt-sweep", case["model"]).observe(time.perf_counter() - started)
    out = SweepResult.model_validate(
        {
            "model": result.model,
            "stage": result.stage,
            "axes": list(result.axes),
            "cases": len(rows),
            "refused": len(result.errors),
            "rows": rows,
            "engine_version": ENGINE_VERSION,
        }
    )
    # exclude_unset: a row holds the swept axes only (the others are the base case's)
    return out.model_dump_json(exclude_unset=True).encode()


def sweep_csv(resolved: dict[str, Any], body: bytes) -> bytes:
    names = [n for n, _ in sorted(resolved["case"]["targets"].items(), key=lambda kv: (kv[1], kv[0]))]
    columns = [*resolved["grid"], "srt", "roll_angle_deg", "tilt_table_angle_deg", *target_columns(names), "error"]
    return to_csv(columns, (flatten_targets(r) for r in orjson.loads(body)["rows"]))


async def compute_sweep(cache: ResultCache, req: SweepRequest, settings: Settings, *, csv: bool) -> Computed:
    resolved = resolve_sweep(req, settings)

    async def produce() -> bytes:
        return await run_in_threadpool(solve_sweep, resolved)

    async def as_json() -> Computed:
        return await cached(cache, "srt-sweep", resolved, produce)

    if not csv:
        return await as_json()
    return await cached_csv(cache, "srt-sweep", resolved, as_json, lambda body: sweep_csv(resolved, body))
