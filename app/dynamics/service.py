"""The dynamics and PBS computations: request -> combination and dynamic data -> cache key -> engine -> answer.

The model (the assembled equations) is built once per vehicle and dynamic data and kept in the process's object
cache under its own key; each answer is cached under the key of the fully resolved request (the combination's
record, the dynamic data, the options) like every other computed answer (:func:`app.compute.results.cached`).
"""

from __future__ import annotations

import re
from dataclasses import asdict, dataclass, replace
from typing import Any

import numpy as np
from starlette.concurrency import run_in_threadpool

from app.compute.cache import ResultCache, cache_key
from app.compute.resolved import Resolved
from app.compute.results import Computed, cached
from app.dynamics import plots
from app.dynamics import schemas as s
from app.vehicle_forms.build import typed_field
from app.vehicles.resolve import VehicleRequest
from engine import ENGINE_VERSION, InvalidVehicle
from engine.dynamics import (
    GROUP_DATA_DOCS,
    OUTER_RADIUS_M,
    SCREENING_NOTE,
    UNIT_DATA_DOCS,
    DynamicsData,
    GroupData,
    UnitData,
    Unstable,
    YawRollModel,
    as_dict,
    build,
    lane_change,
    low_speed_turn,
    pulse_steer,
    rearward_amplification_spectrum,
    screen,
    stability,
    steady_turn,
    worst_frequency,
)
from engine.models import solve_combination
from engine.vehicle import Combination, validate_combination

#: default frequencies of the RA spectrum [Hz]
DEFAULT_FREQUENCIES_HZ = tuple(np.geomspace(0.1, 3.0, 60).round(6).tolist())


@dataclass(frozen=True)
class ResolvedDynamics(Resolved):
    """A dynamics request resolved: the combination's record, the given dynamic data, the options."""

    vehicle: dict[str, Any]
    dynamics: dict[str, Any]
    options: dict[str, Any]


def combination_of_request(vr: VehicleRequest[Any]) -> Combination:
    vehicle = vr.vehicles[0].vehicle
    if not isinstance(vehicle, Combination):
        raise InvalidVehicle(
            "the dynamics need a combination (units, axle groups, couplings): a combination preset id "
            '(tractor-semitrailer-table15, btrain-table16, adouble, truck-trailer) or {"combination": {...}}',
            field="vehicle",
        )
    validate_combination(vehicle)
    return vehicle


def dynamics_data(req: s.DynamicsInputs) -> DynamicsData:
    """The engine's dynamic data of the request's ``dynamics`` field, each value named where it was typed; a unit or
    group listed twice is refused naming the entry."""
    d = req.dynamics
    if d is None:
        return DynamicsData()
    units: dict[str, UnitData] = {}
    given_at: dict[str, str] = {}
    for i, u in enumerate(d.units):
        if u.unit in units:
            raise InvalidVehicle(f"unit {u.unit!r} is listed twice", field=f"dynamics.units[{i}].unit", value=u.unit)
        units[u.unit] = UnitData(**{k: getattr(u, k) for k in UNIT_DATA_DOCS})
        given_at.update({f"units[{u.unit}].{k}": f"dynamics.units[{i}].{k}" for k in UNIT_DATA_DOCS
                         if getattr(u, k) is not None})  # fmt: skip
    groups: dict[tuple[str, str], GroupData] = {}
    for i, g in enumerate(d.groups):
        if (g.unit, g.group) in groups:
            raise InvalidVehicle(f"group {g.group!r} of unit {g.unit!r} is listed twice",
                                 field=f"dynamics.groups[{i}].group", value=g.group)  # fmt: skip
        groups[(g.unit, g.group)] = GroupData(**{k: getattr(g, k) for k in GROUP_DATA_DOCS})
        given_at.update({f"groups[{g.unit}/{g.group}].{k}": f"dynamics.groups[{i}].{k}" for k in GROUP_DATA_DOCS
                         if getattr(g, k) is not None})  # fmt: skip
    return DynamicsData(units, groups, given_at)


def _merge(carried: DynamicsData, request: DynamicsData) -> DynamicsData:
    """The vehicle's data (a combination spec's) and the request's ``dynamics`` field together, field by field. A
    field given in both is refused (422 naming both places), whatever the values: neither silently wins."""
    if not carried:
        return request
    if not request:
        return carried
    for key, place in request.given_at.items():
        if key in carried.given_at:
            raise InvalidVehicle(
                f"{place} is also given by the vehicle at {carried.given_at[key]}: give it in one place",
                field=place,
            )
    units = dict(carried.units)
    for uid, ud in request.units.items():
        units[uid] = replace(units[uid], **{k: v for k, v in asdict(ud).items() if v is not None}) if uid in units \
            else ud  # fmt: skip
    groups = dict(carried.groups)
    for key, gd in request.groups.items():
        groups[key] = replace(groups[key], **{k: v for k, v in asdict(gd).items() if v is not None}) if key in groups \
            else gd  # fmt: skip
    return DynamicsData(units, groups, {**carried.given_at, **request.given_at})


def _key_form(data: DynamicsData) -> dict[str, Any]:
    """The data as the cache key holds it: every given value and where it was typed (the answer's sources say)."""
    return {**data.as_lists(), "given_at": dict(sorted(data.given_at.items()))}


def _as_typed(exc: InvalidVehicle, req: s.DynamicsInputs, data: DynamicsData) -> InvalidVehicle:
    """The engine names a unit's data ``dynamics.units[<unit id>].field``: the field where it was typed (the request's
    list index, or the vehicle's combination spec)."""
    typed = typed_field(exc, data)
    if typed is not exc:
        return typed
    field = exc.field or ""
    d = req.dynamics
    m = re.match(r"dynamics\.units\[(.+?)\](.*)", field)
    if m and d is not None:
        i = next((k for k, u in enumerate(d.units) if u.unit == m.group(1)), None)
        if i is not None:
            return InvalidVehicle(str(exc), field=f"dynamics.units[{i}]{m.group(2) or '.unit'}", value=exc.value)
    m = re.match(r"dynamics\.groups\[(.+?)/(.+?)\](.*)", field)
    if m and d is not None:
        i = next((k for k, g in enumerate(d.groups) if (g.unit, g.group) == (m.group(1), m.group(2))), None)
        if i is not None:
            return InvalidVehicle(str(exc), field=f"dynamics.groups[{i}]{m.group(3) or '.group'}", value=exc.value)
    return exc


def resolve(vr: VehicleRequest[Any], **options: Any) -> tuple[Combination, DynamicsData, ResolvedDynamics]:
    """The combination, its dynamic data (the vehicle's and the request's ``dynamics``) and the resolved request.

    The key holds every given value with where it was typed (the answer's sources name the place); with none given
    it is the empty lists it always was, so the answers without dynamic data keep their keys."""
    req = vr.body
    c = combination_of_request(vr)
    data = _merge(vr.vehicles[0].dynamics, dynamics_data(req))
    given = _key_form(data) if data else {"units": [], "groups": []}
    return c, data, ResolvedDynamics(c.to_dict(), given, options)


def _model(cache: ResultCache, c: Combination, data: DynamicsData, resolved: ResolvedDynamics,
           req: s.DynamicsInputs) -> YawRollModel:  # fmt: skip
    key = cache_key("dynamics-model", {"vehicle": resolved.vehicle, "dynamics": resolved.dynamics})
    model = cache.objects.get(key)
    if model is None:
        try:
            model = build(c, data)
        except InvalidVehicle as exc:
            raise _as_typed(exc, req, data) from exc
        cache.objects[key] = model
    return model


def _common(model: YawRollModel, validity: list[str], *, stable: bool = True, limit: float | None = None
            ) -> dict[str, Any]:  # fmt: skip
    return {"screening": True, "note": SCREENING_NOTE, "validity": validity,
            "parameters": as_dict(model.combination, model.parameters), "stable": stable,
            "stability_limit_kmh": limit, "engine_version": ENGINE_VERSION}  # fmt: skip


def _unstable(exc: Unstable) -> list[str]:
    return [f"unstable at {exc.speed_kmh:g} km/h: {exc.kind} from {exc.limit_kmh} km/h; no measure is given (a "
            "diverging response has none)"]  # fmt: skip


def _srts(c: Combination) -> list[float]:
    return [r.srt for r in solve_combination(c).roll_coupled_units]


async def _answer(cache: ResultCache, operation: str, vr: VehicleRequest[Any], options: dict[str, Any], compute
                  ) -> Computed:  # fmt: skip
    c, data, resolved = resolve(vr, **options)
    model = _model(cache, c, data, resolved, vr.body)

    async def produce() -> bytes:
        result = await run_in_threadpool(compute, model)
        return result.model_dump_json().encode()

    return await cached(cache, operation, resolved, produce)


async def compute_lane_change(cache: ResultCache, vr: VehicleRequest[s.LaneChangeRequest]) -> Computed:
    req = vr.body
    opts = req.model_dump(exclude={"vehicle", "dynamics"})

    def compute(model: YawRollModel) -> s.LaneChangeResult:
        base = {k: opts[k] for k in ("speed_kmh", "frequency_hz", "amplitude_g", "ra_definition")}
        try:
            lc = lane_change(model, req.speed_kmh, frequency_hz=req.frequency_hz, amplitude_g=req.amplitude_g,
                             ra_definition=req.ra_definition, srt_g=_srts(model.combination),
                             history=req.include_history)  # fmt: skip
        except Unstable as exc:
            return s.LaneChangeResult(**base, **_common(model, _unstable(exc), stable=False, limit=exc.limit_kmh),
                                      rearward_amplification=None, high_speed_transient_offtracking_m=None,
                                      steer_axle_lateral_offset_m=None, roll_coupled_units=[], units=[],
                                      time_step_s=0.0)  # fmt: skip
        return s.LaneChangeResult(
            **base, **_common(model, lc.validity), rearward_amplification=lc.rearward_amplification,
            high_speed_transient_offtracking_m=lc.high_speed_transient_offtracking_m,
            steer_axle_lateral_offset_m=lc.steer_axle_lateral_offset_m, roll_coupled_units=lc.roll_coupled_units,
            max_path_deviation_m=lc.max_path_deviation_m,
            units=lc.units, time_step_s=lc.time_step_s, history=lc.history or None,
        )  # fmt: skip

    return await _answer(cache, "dynamics-lane-change", vr, opts, compute)


async def compute_frequency_response(cache: ResultCache, vr: VehicleRequest[s.FrequencyResponseRequest]) -> Computed:
    req = vr.body
    freqs = tuple(req.frequencies_hz) if req.frequencies_hz is not None else DEFAULT_FREQUENCIES_HZ
    for i, f in enumerate(freqs):
        if not 0.001 <= f <= 20.0:
            raise InvalidVehicle("a frequency must be from 0.001 to 20 Hz", field=f"frequencies_hz[{i}]", value=f)
    opts = {"speed_kmh": req.speed_kmh, "frequencies_hz": list(freqs), "ra_definition": req.ra_definition}

    def compute(model: YawRollModel) -> s.FrequencyResponseResult:
        base = {"speed_kmh": req.speed_kmh, "ra_definition": req.ra_definition, "frequencies_hz": list(freqs)}
        st = stability(model)
        limits = [v for v in (st.sway_critical_speed_kmh, st.divergence_speed_kmh) if v is not None]
        if limits and req.speed_kmh >= min(limits):
            exc = Unstable(req.speed_kmh, min(limits), "a growing mode")
            return s.FrequencyResponseResult(**base, **_common(model, _unstable(exc), stable=False,
                                             limit=min(limits)), rearward_amplification=None,
                                             worst_frequency_hz=None, worst_rearward_amplification=None)  # fmt: skip
        ra = rearward_amplification_spectrum(model, req.speed_kmh, np.array(freqs), req.ra_definition)
        wf, wra = worst_frequency(model, req.speed_kmh, req.ra_definition)
        return s.FrequencyResponseResult(**base, **_common(model, []), rearward_amplification=ra.tolist(),
                                         worst_frequency_hz=wf, worst_rearward_amplification=wra)  # fmt: skip

    return await _answer(cache, "dynamics-frequency-response", vr, opts, compute)


async def compute_pulse_steer(cache: ResultCache, vr: VehicleRequest[s.PulseSteerRequest]) -> Computed:
    req = vr.body
    opts = {"speed_kmh": req.speed_kmh}

    def compute(model: YawRollModel) -> s.PulseSteerResult:
        try:
            ps = pulse_steer(model, req.speed_kmh)
        except Unstable as exc:
            return s.PulseSteerResult(speed_kmh=req.speed_kmh, **_common(model, _unstable(exc), stable=False,
                                      limit=exc.limit_kmh), yaw_damping_ratio=None, articulation=None,
                                      least_damped_mode=None, eigenvalues=[])  # fmt: skip
        return s.PulseSteerResult(
            speed_kmh=req.speed_kmh, **_common(model, ps.validity), yaw_damping_ratio=ps.yaw_damping_ratio,
            articulation=ps.articulation, least_damped_mode=ps.least_damped_mode,
            eigenvalues=[{"real": z.real, "imag": z.imag} for z in ps.eigenvalues],
        )  # fmt: skip

    return await _answer(cache, "dynamics-pulse-steer", vr, opts, compute)


async def compute_stability(cache: ResultCache, vr: VehicleRequest[s.StabilityRequest]) -> Computed:

    def compute(model: YawRollModel) -> s.StabilityResult:
        st = stability(model)
        return s.StabilityResult(**_common(model, []), **asdict(st))

    return await _answer(cache, "dynamics-stability", vr, {}, compute)


async def compute_steady_turn(cache: ResultCache, vr: VehicleRequest[s.SteadyTurnRequest]) -> Computed:
    req = vr.body
    opts = {"radius_m": req.radius_m, "speed_kmh": req.speed_kmh}

    def compute(model: YawRollModel) -> s.SteadyTurnResult:
        try:
            st = steady_turn(model, req.radius_m, req.speed_kmh, _srts(model.combination))
        except Unstable as exc:
            return s.SteadyTurnResult(**opts, **_common(model, _unstable(exc), stable=False, limit=exc.limit_kmh),
                                      lateral_acceleration_g=None, steer_deg=None, axles=[], units=[],
                                      roll_coupled_units=[])  # fmt: skip
        return s.SteadyTurnResult(
            **opts, **_common(model, st.validity), lateral_acceleration_g=st.lateral_acceleration_g,
            steer_deg=st.steer_deg, axles=st.axles, units=st.units, roll_coupled_units=st.roll_coupled_units,
        )  # fmt: skip

    return await _answer(cache, "dynamics-steady-turn", vr, opts, compute)


async def compute_low_speed_turn(cache: ResultCache, vr: VehicleRequest[s.LowSpeedTurnRequest]) -> Computed:
    req = vr.body
    opts = {"path_step_m": req.path_step_m}

    def compute(model: YawRollModel) -> s.LowSpeedTurnResult:
        ls = low_speed_turn(model, path_every_m=req.path_step_m)
        return s.LowSpeedTurnResult(
            **_common(model, []), swept_path_width_m=ls.swept_path_width_m, tail_swing_m=ls.tail_swing_m,
            frontal_swing_m=ls.frontal_swing_m, units=ls.units, paths=ls.paths,
            steer_axle_radius_m=ls.steer_axle_radius_m, not_judged=["steer-tyre friction demand"],
        )  # fmt: skip

    return await _answer(cache, "dynamics-low-speed-turn", vr, opts, compute)


async def compute_pbs(cache: ResultCache, vr: VehicleRequest[s.PbsRequest]) -> Computed:
    req = vr.body
    opts = req.model_dump(exclude={"vehicle", "dynamics"})

    def compute(model: YawRollModel) -> s.PbsResult:
        sc = screen(model, **opts)
        stable = not any(x.note.startswith("unstable") for x in sc.standards)
        return s.PbsResult(
            **_common(model, sc.validity, stable=stable), standards=[asdict(x) for x in sc.standards],
            rules_version=sc.rules_version, not_judged=sc.not_judged, length_m=sc.length_m,
            network_level_by_length=sc.network_level_by_length, other_limits=sc.other_limits,
            conditions=sc.conditions,
        )  # fmt: skip

    return await _answer(cache, "pbs", vr, opts, compute)


# ------------------------------------------------------------------------------------------------ figures

SVG_MEDIA_TYPE = "image/svg+xml"


def _label(vr: VehicleRequest[Any]) -> str:
    """The combination as a figure names it (part of the figure's key): a preset's id, a given combination's title;
    a saved one is "the given combination" (its title may change while its id stays)."""
    v = vr.vehicles[0]
    if v.preset is not None:
        return v.preset
    if v.kind != "saved" and isinstance(v.vehicle, Combination) and v.vehicle.title:
        return v.vehicle.title
    return "the given combination"


async def _figure(cache: ResultCache, operation: str, vr: VehicleRequest[Any], options: dict[str, Any], draw
                  ) -> Computed:  # fmt: skip
    c, data, resolved = resolve(vr, **options, svg_version=plots.SVG_VERSION, label=_label(vr))
    model = _model(cache, c, data, resolved, vr.body)

    async def produce() -> bytes:
        return (await run_in_threadpool(draw, model)).encode()

    return await cached(cache, operation, resolved, produce, SVG_MEDIA_TYPE)


def _unstable_svg(exc: Unstable) -> InvalidVehicle:
    return InvalidVehicle(f"no figure: {_unstable(exc)[0]}", field="speed_kmh", value=exc.speed_kmh)


async def plot_lane_change(cache: ResultCache, vr: VehicleRequest[s.LaneChangeRequest]) -> Computed:
    req = vr.body
    opts = req.model_dump(exclude={"vehicle", "dynamics", "include_history"})

    def draw(model: YawRollModel) -> str:
        try:
            lc = lane_change(model, req.speed_kmh, frequency_hz=req.frequency_hz, amplitude_g=req.amplitude_g,
                             ra_definition=req.ra_definition, history=True)  # fmt: skip
        except Unstable as exc:
            raise _unstable_svg(exc) from exc
        return plots.lane_change_svg(_label(vr), lc.history, lc.rearward_amplification,
                                     lc.high_speed_transient_offtracking_m, req.speed_kmh, req.frequency_hz,
                                     req.amplitude_g)  # fmt: skip

    return await _figure(cache, "dynamics-plot-lane-change", vr, opts, draw)


async def plot_frequency_response(cache: ResultCache, vr: VehicleRequest[s.FrequencyResponseRequest]) -> Computed:
    req = vr.body
    freqs = tuple(req.frequencies_hz) if req.frequencies_hz is not None else DEFAULT_FREQUENCIES_HZ
    opts = {"speed_kmh": req.speed_kmh, "frequencies_hz": list(freqs), "ra_definition": req.ra_definition}

    def draw(model: YawRollModel) -> str:
        st = stability(model)
        limits = [v for v in (st.sway_critical_speed_kmh, st.divergence_speed_kmh) if v is not None]
        if limits and req.speed_kmh >= min(limits):
            raise _unstable_svg(Unstable(req.speed_kmh, min(limits), "a growing mode"))
        ra = rearward_amplification_spectrum(model, req.speed_kmh, np.array(freqs), req.ra_definition)
        wf, wra = worst_frequency(model, req.speed_kmh, req.ra_definition)
        return plots.frequency_response_svg(_label(vr), list(freqs), ra.tolist(), wf, wra, req.speed_kmh,
                                            req.ra_definition)  # fmt: skip

    return await _figure(cache, "dynamics-plot-frequency-response", vr, opts, draw)


async def plot_low_speed_turn(cache: ResultCache, vr: VehicleRequest[s.LowSpeedTurnRequest]) -> Computed:
    req = vr.body
    opts = {"path_step_m": req.path_step_m}

    def draw(model: YawRollModel) -> str:
        ls = low_speed_turn(model, path_every_m=req.path_step_m)
        return plots.low_speed_turn_svg(_label(vr), ls.paths, OUTER_RADIUS_M, ls.swept_path_width_m,
                                        ls.tail_swing_m, ls.frontal_swing_m)  # fmt: skip

    return await _figure(cache, "dynamics-plot-low-speed-turn", vr, opts, draw)
