"""Inverse limits: the largest (smallest) value of one parameter at which the SRT still meets a target."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

from engine.bracket import bracketed_limit
from engine.case import Case
from engine.domain import BOUNDS, MAX_OVERWEIGHT_PERCENT, check
from engine.errors import InvalidInput, RolloverError
from engine.models.registry import get_model, record_view
from engine.models.threshold import rollover_threshold
from engine.vehicle.combination import Combination
from engine.vehicle.record import group_stiffness, static_axle_loads

# -------------------------------------------------------------------------------- inverse limits

LIMIT_PARAMETERS = {
    # name: (direction, description). "max": the SRT falls as the parameter grows; "min": it rises.
    "cg_height_above_chassis_m": ("max", "largest CG height above the chassis l12 [m]"),
    "overweight_percent": ("max", "largest overweight [%]"),
    "lateral_offset_m": ("max", "largest lateral CG offset toward the outside of the turn d1 [m]"),
    "spring_separation_m": ("min", "smallest lateral separation between the springs b [m]"),
    "vertical_offset_m": ("max", "largest vertical CG offset d3 (the load raised) [m]"),
}
#: the parameters that change a vehicle record's fields: a combination takes the load-case ones only
RECORD_PARAMETERS = ("cg_height_above_chassis_m", "spring_separation_m")


@dataclass(frozen=True)
class Limit:
    parameter: str
    kind: str  # "max" or "min"
    value: float | None  # the limit; None when no value in the range meets the target
    status: str  # "found", "always-met" (the whole range meets it), "never-met"
    range: tuple[float, float]  # the physically admissible range searched
    srt_at_limit: float | None
    evaluations: int


def with_parameter(case: Case, parameter: str, value: float) -> Case:
    """The case with one :data:`LIMIT_PARAMETERS` entry set to ``value`` (a vehicle field or a load input)."""
    if parameter in RECORD_PARAMETERS:
        return case.replace(vehicle=case.vehicle.replace(**{parameter: value}))
    return case.replace(load=replace(case.load, **{parameter: value}))


def parameter_range(case: Case, parameter: str) -> tuple[float, float]:
    """Admissible range of the parameter: inside the bounds :func:`engine.vehicle.validate_vehicle` enforces.

    For l12 and b that is Rill's condition k_theta > W_group l12 (Eq. 2.17) for every group the model uses
    (both groups in 3D), with the groups' nominal static loads, as the validation applies it.
    """
    vehicle, load = case.vehicle, case.load
    if parameter == "overweight_percent":
        return -50.0, MAX_OVERWEIGHT_PERCENT
    if parameter == "vertical_offset_m":
        b = BOUNDS["vertical_offset_m"]
        return max(b.minimum, _lowest_d3(case) + 0.01), b.maximum
    if isinstance(vehicle, Combination):  # lateral offset: inside the narrowest track of the load-carrying units
        half = min(g.track_m for u in vehicle.units if u.carries_load for g in u.groups) / 2
        return -0.9 * half, 0.9 * half
    front_load, rear_load = static_axle_loads(vehicle)
    groups = [("rear", rear_load)]
    if get_model(case.model).front_group and vehicle.front_axles is not None and front_load > 0:
        groups.append(("front", front_load))
    if parameter == "cg_height_above_chassis_m":
        lo = max(0.05, -load.vertical_offset_m + 0.05)
        bound = min(group_stiffness(vehicle, g).roll_stiffness(vehicle.spring_separation_m) / w for g, w in groups)
        return lo, 0.98 * bound - load.vertical_offset_m
    if parameter == "lateral_offset_m":
        half = vehicle.rear_track_m / 2
        return -0.9 * half, 0.9 * half
    # spring separation: from Rill's bound up to the narrowest axle
    width = min(vehicle.rear_axle_width_m, (vehicle.front_axle_width_m or math.inf) if len(groups) > 1 else math.inf)
    l12 = vehicle.cg_height_above_chassis_m
    b_min = 1.02 * max(math.sqrt(2 * w * l12 / group_stiffness(vehicle, g).suspension_side_kn_per_m) for g, w in groups)
    return b_min, width * (1 - 1e-6) - 1e-6


def _lowest_d3(case: Case) -> float:
    """The lowest d3 that keeps the CG above the chassis (a record) or above the roll centres (a combination) [m]."""
    v = case.vehicle
    if isinstance(v, Combination):
        return max(max(g.roll_centre_height_m for g in u.groups) - u.cg_height_m for u in v.units if u.carries_load)
    return -v.cg_height_above_chassis_m


def _margin(case: Case, parameter: str, target: float):
    """SRT minus the target as a function of the parameter; None where the value makes the case unsolvable."""

    def g(x: float) -> float | None:
        try:
            return rollover_threshold(with_parameter(case, parameter, x)).srt - target
        except RolloverError:  # collapse, tipping at rest, SRT outside the mechanism's range
            return None

    return g


def parameter_limit(case: Case, target_srt_g: float, parameter: str, *, xtol: float = 1e-6) -> Limit:
    """The limit of one parameter at which the SRT of ``case`` equals ``target_srt_g`` (Brent's method, bracketed).

    The SRT is monotonic in each parameter over its admissible range (decreasing in l12, overweight and
    outward d1; increasing in b), so the bracket holds one root. ``status`` says when the whole range
    meets the target ("always-met": the limit is the range's end, or the last solvable value where the
    vehicle would collapse before missing the target) or none of it does ("never-met").
    """
    if parameter not in LIMIT_PARAMETERS:
        raise InvalidInput(
            f"parameter must be one of {', '.join(LIMIT_PARAMETERS)}", field="parameter", value=parameter
        )
    check("target_srt_g", target_srt_g)
    # errors that do not depend on the searched value (a model that needs a missing field, a road outside the
    # domain...) are the caller's: let them through as they are, before searching
    case, _note = record_view(case)  # a record model sees a combination's last unit
    if isinstance(case.vehicle, Combination) and parameter in RECORD_PARAMETERS:
        raise InvalidInput(
            f"{parameter} is a field of a vehicle record; for a combination search overweight_percent, "
            "lateral_offset_m or vertical_offset_m (they apply to its load-carrying units)",
            field="parameter",
            value=parameter,
        )
    get_model(case.model).check(case)
    kind = LIMIT_PARAMETERS[parameter][0]
    lo, hi = parameter_range(case, parameter)
    good, bad = (lo, hi) if kind == "max" else (hi, lo)
    try:
        r = bracketed_limit(_margin(case, parameter, target_srt_g), good, bad, xtol=xtol, field=parameter)
    except InvalidInput as e:
        raise InvalidInput(
            f"no value of {parameter} in [{lo:.4g}, {hi:.4g}] can be solved for this case", field=parameter
        ) from e
    srt = None if r.margin is None else target_srt_g + r.margin
    return Limit(parameter, kind, r.value, r.status, (lo, hi), srt, r.evaluations)


@dataclass(frozen=True)
class LimitTableRow:
    overweight_percent: float
    limit: Limit


def limit_table(case: Case, target_srt_g: float, parameter: str, overweights: Sequence[float]) -> list[LimitTableRow]:
    """The limit of ``parameter`` for each overweight (TERNZ's table of acceptable mass / load-height pairs)."""
    if parameter == "overweight_percent":
        raise InvalidInput("the table runs over overweights; pick another parameter", field="parameter")
    return [
        LimitTableRow(
            float(ow),
            parameter_limit(
                case.replace(load=replace(case.load, overweight_percent=float(ow))), target_srt_g, parameter
            ),
        )
        for ow in overweights
    ]
