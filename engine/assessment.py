"""Road-design and compliance tools built on the SRT (the thesis's Ch. 9.6 and 11 proposals).

* **Targets**: whether an SRT meets configurable minimums (defaults: 0.35 g general freight, 0.40 g
  dangerous goods, as in Australia's Performance-Based Standards and New Zealand's SRT rule) and by how
  much; the tilt-table angle ``atan(SRT)`` a tilt test would show.
* **Inverse limits**: for a target SRT, the largest CG height above the chassis, overweight or outward
  lateral offset d1 -- or the smallest spring separation -- at which the vehicle still meets it, found
  exactly by Brent's bracketed root finder on the engine; and the table of that limit over a range of
  overweights (the exact counterpart of the TERNZ calculator's table of acceptable mass/load-height pairs).
* **Curve assessment**: for each horizontal curve (radius, superelevation, grade), the SRT on that bank
  and grade, the rollover speed (Eq. 9.1), the side-friction speed sqrt(127 R (0.01 e + f)) with f from
  Table 21, the governing safe speed and the margin against the posted speed. The SRT does not depend on
  the radius, so curves sharing bank and grade share one solve (all distinct pairs in one batched solve).

References
----------
Thesis Eqs. 9.1-9.3, Table 21; NTC Australia (2008) PBS scheme; NZTA (2008) SRT calculator (TERNZ).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import brentq

from .case import Case
from .domain import MAX_OVERWEIGHT_PERCENT, check
from .errors import InvalidInput, RolloverError
from .loads import Road, check_case
from .models import get_model
from .road import max_curve_speed_kmh, side_friction_speed_kmh
from .threshold import evaluate_cases, rollover_threshold
from .vehicles import group_stiffness, static_axle_loads

#: default SRT targets [g]: PBS (Australia) / NZ rule: 0.35 g general, 0.40 g dangerous goods (tankers)
DEFAULT_TARGETS = {"general": 0.35, "dangerous_goods": 0.40}


# ------------------------------------------------------------------------------------- targets


@dataclass(frozen=True)
class TargetCheck:
    name: str
    target_g: float
    meets: bool
    margin_g: float  # srt - target


def check_targets(srt_g: float, targets: dict[str, float] | None = None) -> list[TargetCheck]:
    """Whether ``srt_g`` meets each target (SRT >= target) and the margin SRT - target [g]."""
    targets = DEFAULT_TARGETS if targets is None else targets
    out = []
    for name, t in targets.items():
        check("target_srt_g", t, f"targets.{name}")
        out.append(TargetCheck(name, float(t), srt_g >= t, srt_g - t))
    return out


def tilt_table_angle_deg(srt_g):
    """Tilt-table angle equivalent to an SRT: a rigid vehicle tips at tan(angle) = SRT [deg]."""
    return np.degrees(np.arctan(srt_g))


# -------------------------------------------------------------------------------- inverse limits

LIMIT_PARAMETERS = {
    # name: (direction, description). "max": the SRT falls as the parameter grows; "min": it rises.
    "cg_height_above_chassis_m": ("max", "largest CG height above the chassis l12 [m]"),
    "overweight_percent": ("max", "largest overweight [%]"),
    "lateral_offset_m": ("max", "largest lateral CG offset toward the outside of the turn d1 [m]"),
    "spring_separation_m": ("min", "smallest lateral separation between the springs b [m]"),
}


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
    if parameter in ("cg_height_above_chassis_m", "spring_separation_m"):
        return case.replace(vehicle=case.vehicle.replace(**{parameter: value}))
    return case.replace(load=replace(case.load, **{parameter: value}))


def parameter_range(case: Case, parameter: str) -> tuple[float, float]:
    """Admissible range of the parameter: inside the bounds :func:`engine.vehicles.validate_vehicle` enforces.

    For l12 and b that is Rill's condition k_theta > W_group l12 (Eq. 2.17) for every group the model uses
    (both groups in 3D), with the groups' nominal static loads, as the validation applies it.
    """
    vehicle, load = case.vehicle, case.load
    front_load, rear_load = static_axle_loads(vehicle)
    groups = [("rear", rear_load)]
    if get_model(case.model).front_group and vehicle.front_axles is not None and front_load > 0:
        groups.append(("front", front_load))
    if parameter == "cg_height_above_chassis_m":
        lo = max(0.05, -load.vertical_offset_m + 0.05)
        bound = min(group_stiffness(vehicle, g).roll_stiffness(vehicle.spring_separation_m) / w for g, w in groups)
        return lo, 0.98 * bound - load.vertical_offset_m
    if parameter == "overweight_percent":
        return -50.0, MAX_OVERWEIGHT_PERCENT
    if parameter == "lateral_offset_m":
        half = vehicle.rear_track_m / 2
        return -0.9 * half, 0.9 * half
    # spring separation: from Rill's bound up to the narrowest axle
    width = min(vehicle.rear_axle_width_m, (vehicle.front_axle_width_m or math.inf) if len(groups) > 1 else math.inf)
    l12 = vehicle.cg_height_above_chassis_m
    b_min = 1.02 * max(math.sqrt(2 * w * l12 / group_stiffness(vehicle, g).suspension_side_kn_per_m) for g, w in groups)
    return b_min, width * (1 - 1e-6) - 1e-6


@dataclass(frozen=True)
class _Search:
    """The SRT minus the target as a function of the parameter, counting evaluations."""

    case: Case
    parameter: str
    target: float
    count: list

    def __call__(self, x: float) -> float:
        self.count[0] += 1
        return rollover_threshold(with_parameter(self.case, self.parameter, x)).srt - self.target

    def solvable(self, x: float) -> float | None:
        """g(x), or None where this value makes the case unsolvable (collapse, tipping at rest, ...)."""
        try:
            return self(x)
        except RolloverError:
            return None


def _first_solvable(g: _Search, good: float, bad: float) -> tuple[float, float | None]:
    """The "good" end of the range, or the first solvable value stepping from it toward the bad end in growing
    steps (a CG so low that the SRT exceeds the mechanism's range, ...)."""
    g_good = g.solvable(good)
    if g_good is not None:
        return good, g_good
    for k in range(30, 0, -1):
        probe = good + (bad - good) / 2.0**k
        g_probe = g.solvable(probe)
        if g_probe is not None:
            return probe, g_probe
    return good, None


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
    get_model(case.model).validate(case.vehicle)
    check_case(case.vehicle, case.road, case.trailer_angle_deg, case.load)
    kind = LIMIT_PARAMETERS[parameter][0]
    lo, hi = parameter_range(case, parameter)
    g = _Search(case, parameter, target_srt_g, [0])
    good, bad = (lo, hi) if kind == "max" else (hi, lo)
    good, g_good = _first_solvable(g, good, bad)
    if g_good is None:
        raise InvalidInput(
            f"no value of {parameter} in [{lo:.4g}, {hi:.4g}] can be solved for this case", field=parameter
        )
    if g_good < 0:
        return Limit(parameter, kind, None, "never-met", (lo, hi), None, g.count[0])
    # near the bad end the vehicle may collapse (no solution): bisect toward the good end until a solvable
    # point that misses the target brackets the root
    unsolvable = None
    while True:
        g_bad = g.solvable(bad)
        if g_bad is None:
            unsolvable = bad
        elif g_bad < 0:
            break
        else:  # solvable and still meets the target: the root lies beyond it
            good, g_good = bad, g_bad
            if unsolvable is None:
                return Limit(parameter, kind, bad, "always-met", (lo, hi), target_srt_g + g_bad, g.count[0])
        if abs(unsolvable - good) < xtol:  # met up to where the vehicle stops being solvable
            return Limit(parameter, kind, good, "always-met", (lo, hi), target_srt_g + g_good, g.count[0])
        bad = 0.5 * (good + unsolvable)
    root = brentq(g, min(good, bad), max(good, bad), xtol=xtol, rtol=1e-10)
    return Limit(parameter, kind, float(root), "found", (lo, hi), target_srt_g, g.count[0])


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


# ----------------------------------------------------------------------------- curve assessment


@dataclass(frozen=True)
class Curve:
    """One horizontal curve. grade_percent is signed along the direction of travel (+ uphill)."""

    id: str
    radius_m: float
    superelevation_percent: float
    grade_percent: float = 0.0
    posted_speed_kmh: float | None = None


@dataclass(frozen=True)
class CurveAssessment:
    id: str
    srt_g: float | None
    rollover_speed_kmh: float | None  # Eq. 9.1 with the SRT on this bank and grade
    side_friction_speed_kmh: float  # sqrt(127 R (0.01 e + f)), f from Table 21
    safe_speed_kmh: float | None  # the smaller of the two
    governed_by: str | None  # "rollover" or "side-friction"
    posted_speed_kmh: float | None
    margin_kmh: float | None  # safe - posted
    flagged: bool  # margin < 0, or no SRT could be computed for the curve (``error`` says why)
    error: str | None = None


@dataclass
class AlignmentAssessment:
    curves: list[CurveAssessment]
    distinct_cases: int  # SRT solves needed (distinct bank/grade pairs)
    notes: list[str] = field(default_factory=list)


def check_curve(c: Curve, index: int) -> None:
    """Refuse a curve that no formula can use, naming the row and the field (the bounds of
    :data:`engine.domain.BOUNDS`, the same as the JSON request's)."""
    where = f"curves[{index}]"
    check("radius_m", c.radius_m, f"{where}.radius_m")
    check("bank_percent", c.superelevation_percent, f"{where}.superelevation_percent")
    check("slope_percent", c.grade_percent, f"{where}.grade_percent")
    if c.posted_speed_kmh is not None:
        check("speed_kmh", c.posted_speed_kmh, f"{where}.posted_speed_kmh")


def assess_curves(case: Case, curves: Sequence[Curve], *, friction_bound: str = "low") -> AlignmentAssessment:
    """Safe speed on each curve: rollover (Eq. 9.1 with that curve's SRT) against side friction (Table 21).

    ``case`` gives the vehicle and the SRT options; its road is replaced by each curve's superelevation and grade.
    """
    if not curves:
        raise InvalidInput("no curves to assess", field="curves")
    for i, c in enumerate(curves):
        check_curve(c, i)
    e = np.array([c.superelevation_percent for c in curves])
    gr = np.array([c.grade_percent for c in curves])
    r = np.array([c.radius_m for c in curves])
    pairs, inverse = np.unique(np.stack((e, gr), axis=1), axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    cases = [case.replace(road=Road(bank_percent=float(b), slope_percent=float(s))) for b, s in pairs]
    srt_pairs, _, errors = evaluate_cases(cases)
    srt = srt_pairs[inverse]
    fric = np.asarray(side_friction_speed_kmh(r, e, friction_bound), dtype=float).reshape(-1)
    roll = np.where(np.isfinite(srt), max_curve_speed_kmh(np.where(np.isfinite(srt), srt, 0.0), r), np.nan)
    out = []
    for i, c in enumerate(curves):
        k = int(inverse[i])
        err = errors.get(k)
        if err is not None:
            out.append(
                # no safe speed can be given: flagged for attention, not passed as fine (``error`` says why)
                CurveAssessment(c.id, None, None, float(fric[i]), None, None, c.posted_speed_kmh, None, True, err)
            )
            continue
        safe = min(float(roll[i]), float(fric[i]))
        gov = "rollover" if roll[i] < fric[i] else "side-friction"
        margin = None if c.posted_speed_kmh is None else safe - c.posted_speed_kmh
        out.append(
            CurveAssessment(
                c.id,
                float(srt[i]),
                float(roll[i]),
                float(fric[i]),
                safe,
                gov,
                c.posted_speed_kmh,
                margin,
                margin is not None and margin < 0,
            )
        )
    return AlignmentAssessment(out, len(pairs))
