"""Mapping between the HTTP schemas and the engine, and the cached computations.

Data flows one way: validated request -> fully resolved request (preset expanded, defaults filled) ->
cache key -> engine (in a worker thread) -> response body (JSON bytes, stored as is in the cache).
"""

from __future__ import annotations

import math
import time
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import Any

import orjson
from fastapi.exceptions import RequestValidationError
from starlette.concurrency import run_in_threadpool

from engine import ENGINE_VERSION
from engine.assessment import check_targets, tilt_table_angle_deg
from engine.loads import LoadCase, Road
from engine.road import check_speed, max_curve_speed_kmh, min_radius, side_friction_factor
from engine.threshold import rollover_threshold
from engine.vehicles import Vehicle, get_preset

from .cache import ResultCache, cache_key
from .metrics import CACHE_LOOKUPS, SOLVE_SECONDS
from .schemas.road import SRT_FIELDS, CurveSpeedRequest, CurveSpeedResult, MinRadiusRequest, MinRadiusResult
from .schemas.srt import SrtInputs, SrtRequest, SrtResult
from .settings import Settings

DEFAULT_CURVE_POINTS = SrtRequest.model_fields["curve_points"].default


@dataclass(frozen=True)
class Computed:
    """A response body with its cache key, whether it came from the cache, and its media type."""

    body: bytes
    key: str
    hit: bool
    media_type: str = "application/json"

    @property
    def etag(self) -> str:
        return f'"{self.key}"'


# ------------------------------------------------------------------------------------- resolution


def resolve_vehicle(ref: Any) -> Vehicle:
    """A preset id -> the preset's record (UnknownPreset -> 404); a record -> the engine record."""
    if isinstance(ref, str):
        return get_preset(ref)
    return Vehicle.from_dict(ref.record())


def resolve_targets(targets: dict[str, float] | None, settings: Settings) -> dict[str, float]:
    """The SRT targets of a request: its own, else the configured defaults (name -> minimum SRT [g])."""
    return dict(targets) if targets is not None else settings.default_targets()


def target_checks(srt_g: float, targets: dict[str, float]) -> list[dict[str, Any]]:
    """``TargetCheckOut`` dicts for an SRT, in order of increasing target (then name): the order is fixed by
    the targets themselves, so equal targets given in any order give the same body and the same cache key."""
    checks = sorted(check_targets(srt_g, targets), key=lambda c: (c.target_g, c.name))
    return [{"name": c.name, "target_g": c.target_g, "meets": c.meets, "margin_g": c.margin_g} for c in checks]


def resolve_srt(
    req: SrtInputs,
    *,
    targets: dict[str, float],
    include_curves: bool = False,
    curve_points: int | None = None,
) -> dict[str, Any]:
    """The fully resolved SRT request: every field explicit, the vehicle as its full record, the targets the
    result is checked against (they are in the body, so they are in the key)."""
    return {
        "vehicle": resolve_vehicle(req.vehicle).to_dict(),
        "model": req.model,
        "stage": req.stage,
        "road": req.road.model_dump(),
        "trailer_angle_deg": req.trailer_angle_deg,
        "load": req.load.model_dump(),
        "rear_llt_limit": req.rear_llt_limit,
        "include_curves": include_curves,
        # without curves the number of points changes nothing: keep it out of the key
        "curve_points": (curve_points or DEFAULT_CURVE_POINTS) if include_curves else None,
        "targets": dict(targets),
    }


def refuse(field: str, message: str, value: Any = None) -> RequestValidationError:
    return RequestValidationError(
        [{"type": "value_error", "loc": ("body", *field.split(".")), "msg": message, "input": value}]
    )


def _srt_source(req: CurveSpeedRequest | MinRadiusRequest) -> None:
    """Either ``srt`` or the SRT request fields, never both (the given SRT already holds the bank)."""
    if req.srt is None and req.vehicle is None:
        raise refuse("srt", "give either srt (g) or vehicle (with the other SRT request fields)")
    if req.srt is not None:
        extra = [f for f in SRT_FIELDS if f in req.model_fields_set]
        if extra == ["targets"]:
            raise refuse(
                "targets",
                "targets are checked against a computed SRT (the embedded srt_result); with a given srt there is "
                "none: leave targets out, or give the SRT request fields instead of srt",
            )
        if extra:
            raise refuse(
                extra[0],
                f"{extra[0]} cannot be combined with srt: a given SRT already is the SRT on this curve's bank and "
                "slope (give either srt or the SRT request fields)",
            )


# -------------------------------------------------------------------------------------- computing


def _finite_or_none(x: Any) -> Any:
    return x if not isinstance(x, float) or math.isfinite(x) else None


def solve_srt(resolved: dict[str, Any]) -> bytes:
    """Run the engine on a resolved request (blocking: called in a worker thread) -> SrtResult JSON bytes."""
    started = time.perf_counter()
    result = rollover_threshold(
        Vehicle.from_dict(resolved["vehicle"]),
        resolved["model"],
        stage=resolved["stage"],
        road=Road(**resolved["road"]),
        trailer_angle_deg=resolved["trailer_angle_deg"],
        load=LoadCase(**resolved["load"]),
        rear_llt_limit=resolved["rear_llt_limit"],
        include_curves=resolved["include_curves"],
        curve_points=resolved["curve_points"] or DEFAULT_CURVE_POINTS,
    )
    SOLVE_SECONDS.labels("srt", resolved["model"]).observe(time.perf_counter() - started)
    data = result.to_dict()
    data["parameters"] = {k: _finite_or_none(v) for k, v in data["parameters"].items()}
    data["notes"] = list(data.get("notes") or [])
    data["tilt_table_angle_deg"] = float(tilt_table_angle_deg(result.srt))
    data["targets"] = target_checks(result.srt, resolved["targets"])
    data["engine_version"] = ENGINE_VERSION
    # validating the engine's output against the published schema turns a contract break into a loud error
    return SrtResult.model_validate(data).model_dump_json().encode()


async def _cached(cache: ResultCache, operation: str, key: str) -> bytes | None:
    lookup = await cache.get(key)
    CACHE_LOOKUPS.labels(operation, lookup.tier or "miss").inc()
    return lookup.value


async def cached(
    cache: ResultCache,
    operation: str,
    resolved: dict[str, Any],
    produce: Callable[[], Awaitable[bytes]],
    media_type: str = "application/json",
) -> Computed:
    """The body for ``resolved`` from the cache, or from ``produce()`` (then stored under the same key)."""
    key = cache_key(operation, resolved)
    body = await _cached(cache, operation, key)
    if body is not None:
        return Computed(body, key, True, media_type)
    body = await produce()
    await cache.set(key, body)
    return Computed(body, key, False, media_type)


async def cached_csv(
    cache: ResultCache,
    operation: str,
    resolved: dict[str, Any],
    json_body: Callable[[], Awaitable[Computed]],
    render: Callable[[bytes], bytes],
) -> Computed:
    """The CSV form of a JSON answer, cached under its own key (``<operation>-csv``: its own ETag), rendered from
    the JSON body (itself from the cache or computed) on a miss."""

    async def produce() -> bytes:
        body = (await json_body()).body
        return await run_in_threadpool(render, body)  # 100,000 rows take a while: not on the event loop

    return await cached(cache, f"{operation}-csv", resolved, produce, "text/csv; charset=utf-8")


async def compute_srt(cache: ResultCache, resolved: dict[str, Any]) -> Computed:
    return await cached(cache, "srt", resolved, lambda: run_in_threadpool(solve_srt, resolved))


async def _srt_for(cache: ResultCache, req: CurveSpeedRequest | MinRadiusRequest, resolved_srt: dict | None):
    """(srt, source, SrtResult dict or None) for a curve-speed/min-radius request."""
    if resolved_srt is None:
        return req.srt, "given", None
    inner = await compute_srt(cache, resolved_srt)
    data = orjson.loads(inner.body)
    return data["srt"], "computed", data


async def compute_curve_speed(cache: ResultCache, req: CurveSpeedRequest, settings: Settings) -> Computed:
    _srt_source(req)
    targets = resolve_targets(req.targets, settings)
    resolved_srt = resolve_srt(req, targets=targets) if req.srt is None else None
    resolved = {"radius_m": req.radius_m, "srt": req.srt, "srt_request": resolved_srt}

    async def produce() -> bytes:
        srt, source, srt_result = await _srt_for(cache, req, resolved_srt)
        speed = float(max_curve_speed_kmh(srt, req.radius_m))  # Eq. 9.1; the SRT already contains the bank
        return (
            CurveSpeedResult(
                max_speed_kmh=speed,
                radius_m=req.radius_m,
                srt=srt,
                srt_source=source,
                srt_result=srt_result,
                engine_version=ENGINE_VERSION,
            )
            .model_dump_json()
            .encode()
        )

    return await cached(cache, "curve-speed", resolved, produce)


async def compute_min_radius(cache: ResultCache, req: MinRadiusRequest, settings: Settings) -> Computed:
    _srt_source(req)
    resolved_srt = None
    if req.srt is None:
        # Eq. 9.3 needs the SRT on this curve's bank: the bank is the superelevation
        if "bank_percent" in req.road.model_fields_set and req.road.bank_percent != req.superelevation_percent:
            raise refuse(
                "road.bank_percent",
                f"road.bank_percent ({req.road.bank_percent}) differs from superelevation_percent "
                f"({req.superelevation_percent}); the SRT is computed on the curve's superelevation (leave "
                "road.bank_percent out, or equal to it)",
                req.road.bank_percent,
            )
        with_bank = req.model_copy(
            update={"road": req.road.model_copy(update={"bank_percent": req.superelevation_percent})}
        )
        resolved_srt = resolve_srt(with_bank, targets=resolve_targets(req.targets, settings))
    resolved = {
        "design_speed_kmh": req.design_speed_kmh,
        "superelevation_percent": req.superelevation_percent,
        "side_friction": req.side_friction,
        "side_friction_bound": None if req.side_friction is not None else req.side_friction_bound,
        "srt": req.srt,
        "srt_request": resolved_srt,
    }

    async def produce() -> bytes:
        check_speed(req.design_speed_kmh)  # refuse a speed Table 21 does not cover before solving for the SRT
        if req.side_friction is None:
            side_friction_factor(req.design_speed_kmh, req.side_friction_bound)
        srt, source, srt_result = await _srt_for(cache, req, resolved_srt)
        r = min_radius(
            req.design_speed_kmh,
            req.superelevation_percent,
            srt,
            side_friction=req.side_friction,
            bound=req.side_friction_bound,
        )
        return (
            MinRadiusResult(
                aashto_min_radius_m=r.aashto_min_radius_m,
                rollover_min_radius_m=r.rollover_min_radius_m,
                governing_min_radius_m=r.governing_min_radius_m,
                governed_by=r.governed_by,
                side_friction=r.side_friction,
                side_friction_source="given" if req.side_friction is not None else f"table21-{req.side_friction_bound}",
                design_speed_kmh=req.design_speed_kmh,
                superelevation_percent=req.superelevation_percent,
                srt=srt,
                srt_source=source,
                srt_result=srt_result,
                engine_version=ENGINE_VERSION,
            )
            .model_dump_json()
            .encode()
        )

    return await cached(cache, "min-radius", resolved, produce)
