"""The advisory speed of one curve over HTTP: the request resolved (the vehicles' SRT requests on this curve's bank and
grade), each method's speed from :mod:`engine.road.advisory`, the vehicles' rollover speeds (Eq. 9.1) through the
memoised SRT solve of :mod:`app.srt.service`, and the answer cached under its resolved request's key."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from pydantic import ConfigDict

from app.advisory.schemas import (
    AdvisorySpeedRequest,
    AdvisorySpeedResult,
    MethodOut,
    RolloverWarningOut,
    TreatmentOut,
    VehicleCheckOut,
)
from app.compute.cache import ResultCache
from app.compute.resolved import Resolved, ResolvedSrt
from app.compute.results import Computed, cached
from app.srt.service import resolve_case, resolve_srt, solve
from app.vehicles.resolve import VehicleRequest
from engine import ENGINE_VERSION, InvalidInput, Road
from engine import road as adv
from engine.road import check_deceleration, max_curve_speed_kmh, side_friction_speed
from engine.vehicle import FIELD_DOCS

OPERATION = "advisory-speed"


@dataclass(frozen=True, kw_only=True)
class ResolvedAdvisory(Resolved):
    """An advisory speed: the curve, the speeds, the options and the vehicles' SRT requests on the curve's bank and
    grade (empty without vehicles); the tangent speed with its default filled."""

    __pydantic_config__ = ConfigDict(extra="forbid", strict=True)

    radius_m: float
    superelevation_percent: float
    grade_percent: float
    deflection_deg: float | None
    posted_speed_kmh: float
    tangent_speed_kmh: float
    measured_car_speed_kmh: float | None
    units: str
    deceleration_mps2: float
    reaction_time_s: float
    rollover_margin_kmh: float
    body_roll_deg_per_g: float
    design_standard: str
    side_friction_bound: str | None
    srt_requests: tuple[ResolvedSrt, ...]


def _method(mid: str, speed: float | None, vehicle: int | None = None) -> MethodOut:
    source, legacy, verified = adv.method_source(mid)
    return MethodOut(id=mid, speed_kmh=speed, source=source, legacy=legacy, verified=verified, vehicle=vehicle)


def _finite(x: float) -> float | None:
    return x if x == x else None  # nan -> None


async def compute_advisory_speed(cache: ResultCache, vr: VehicleRequest[AdvisorySpeedRequest]) -> Computed:
    req = vr.body
    # refusals the schema cannot state: the sign's increment, a truck's braking limit
    if req.increment is not None:
        adv.check_increment(req.units, req.increment)
    check_deceleration(req.deceleration_mps2)
    road = Road(bank_percent=req.superelevation_percent, slope_percent=req.grade_percent)
    cases = [resolve_case(req, v.vehicle, road=road) for v in vr.vehicles]  # type: ignore[arg-type]
    tangent = req.tangent_speed_kmh if req.tangent_speed_kmh is not None else req.posted_speed_kmh
    resolved = ResolvedAdvisory.of(
        req,
        tangent_speed_kmh=tangent,
        side_friction_bound=req.side_friction_bound,
        # each vehicle's input warnings beside its SRT request: the answer carries them, so the key holds them
        srt_requests=tuple(
            resolve_srt(c, {}, warnings=tuple(dataclasses.asdict(w) for w in v.warnings))
            for c, v in zip(cases, vr.vehicles, strict=True)
        ),
    )

    async def produce() -> bytes:
        r, e = req.radius_m, req.superelevation_percent
        srts = []
        for i, c in enumerate(cases):
            try:
                srts.append((await solve(cache, c)).srt)
            except InvalidInput as exc:  # a record field of vehicles[i]: point at that vehicle, not at `vehicle`
                if req.vehicles is not None and exc.field in FIELD_DOCS:
                    exc.field = f"vehicles[{i}].{exc.field}"
                raise
        v_roll = [float(max_curve_speed_kmh(s, r)) for s in srts]  # Eq. 9.1: the SRT on this bank and grade
        cols = adv.advise_curves(
            [r],
            [e],
            [req.posted_speed_kmh],
            [min(v_roll)] if v_roll else None,
            deflection_deg=None if req.deflection_deg is None else [req.deflection_deg],
            measured_car_speed_kmh=None if req.measured_car_speed_kmh is None else [req.measured_car_speed_kmh],
            units=req.units,
            rollover_margin_kmh=req.rollover_margin_kmh,
            body_roll_deg_per_g=req.body_roll_deg_per_g,
        )
        shown = float(cols.advisory_speed_kmh[0])
        methods = [_method("design-method", None)]
        for mid, speeds in cols.methods.items():
            if mid == "txdot-direct" and req.measured_car_speed_kmh is None:
                continue
            methods.append(_method(mid, _finite(float(speeds[0]))))
        sf = side_friction_speed(req.design_standard, r, e, req.side_friction_bound)
        methods.append(
            MethodOut(
                id="side-friction",
                speed_kmh=float(sf.speed_kmh[0]),
                source=f"this service's check: sqrt(127 R (0.01 e + f)) with {req.design_standard}'s f_max at that "
                "speed (thesis Eq. 9.2 inverted)",
                legacy=False,
                verified=True,
                vehicle=None,
            )
        )
        warnings = adv.rollover_warning(v_roll, [shown] * len(v_roll), req.rollover_margin_kmh) if v_roll else []
        checks = []
        for i, (s, v) in enumerate(zip(srts, v_roll, strict=True)):
            methods.append(
                MethodOut(
                    id="rollover",
                    speed_kmh=v,
                    source="this service's check: sqrt(127 SRT R) (thesis Eq. 9.1), the vehicle's SRT on this bank "
                    "and grade",
                    legacy=False,
                    verified=True,
                    vehicle=i,
                )
            )
            checks.append(VehicleCheckOut(vehicle=i, srt=s, rollover_speed_kmh=v, recommended=bool(warnings[i])))
        code = int(cols.treatment[0])
        v1 = tangent / 3.6
        v2 = min(shown / 3.6, v1)
        sign_m = v1 * req.reaction_time_s + (v1**2 - v2**2) / (2.0 * req.deceleration_mps2)
        notes = [adv.DESIGN_METHOD_NOTE]
        if req.measured_car_speed_kmh is None:
            notes.append(
                f"the advisory speed is the legacy {adv.BALL_BANK_2009.id} criterion's: no measured car speed was "
                "given for the Direct Method and the Design Method is unverified"
            )
        if bool(cols.small_deflection[0]):
            notes.append(
                f"deflection below {adv.MIN_DEFLECTION_DEG:g} deg: TxDOT, 'a curve with a smaller deflection angle "
                "will rarely justify curve warning signs or an advisory speed plaque'"
            )
        notes.append("curves separated by a tangent of 600 ft or less share one sign (TxDOT): applies to alignments")
        out = AdvisorySpeedResult(
            advisory_speed_kmh=shown,
            advisory_speed_mph=float(adv.displayed_in_units(shown, "us")) if req.units == "us" else None,
            units=req.units,
            increment=adv.SIGN_INCREMENTS[req.units],
            governed_by=adv.ADVICE_GOVERNED_BY[int(cols.governed_by[0])],
            methods=methods,
            treatment=TreatmentOut(
                devices=list(adv.TREATMENTS[code]) if code >= 0 else [],
                speed_difference_mph=float(adv.kmh_to_mph(req.posted_speed_kmh - shown)),
                advance_sign_distance_m=sign_m,
                source=adv.TREATMENT_SOURCE,
            ),
            truck_rollover_warning=RolloverWarningOut(
                recommended=bool(cols.truck_rollover_warning[0]),
                rule=adv.W1_13_RULE.format(margin=req.rollover_margin_kmh),
                vehicles=checks,
            ),
            notes=notes,
            warnings=list(vr.warnings),
            engine_version=ENGINE_VERSION,
        )
        return out.model_dump_json().encode()

    return await cached(cache, OPERATION, resolved, produce)
