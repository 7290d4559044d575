"""Curve and alignment assessment: the safe speed on every horizontal curve (Eq. 9.1 against side friction)."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, fields

import numpy as np

from engine.case import Case
from engine.domain import BOUNDS, check
from engine.errors import InvalidInput, InvalidRoad
from engine.models.threshold import BlockMap, evaluate_arrays, map_blocks
from engine.road import standards
from engine.road.formulas import max_curve_speed_kmh
from engine.road.min_radius import min_radius_array
from engine.road.superelevation import distribution_min_radius_m, superelevation_table

# ----------------------------------------------------------------------------- curve assessment


@dataclass(frozen=True)
class Curve:
    """One horizontal curve. grade_percent is signed along the direction of travel (+ uphill); a superelevation of
    None is derived from the design standard's distribution (see :func:`assess_alignment`)."""

    id: str
    radius_m: float
    superelevation_percent: float | None
    grade_percent: float = 0.0
    posted_speed_kmh: float | None = None


@dataclass(frozen=True)
class CurveAssessment:
    id: str
    srt_g: float | None
    rollover_speed_kmh: float | None  # Eq. 9.1 with the SRT on this bank and grade
    side_friction_speed_kmh: float  # sqrt(127 R (0.01 e + f)), f from the design standard
    safe_speed_kmh: float | None  # the smaller of the two
    governed_by: str | None  # "rollover" or "side-friction"
    posted_speed_kmh: float | None
    margin_kmh: float | None  # safe - posted
    flagged: bool  # margin < 0, or no SRT could be computed for the curve (``error`` says why)
    error: str | None = None
    superelevation_percent: float | None = None  # as used (given or derived)
    superelevation_derived: bool = False
    standard_min_radius_m: float | None = None
    meets_standard_min_radius: bool | None = None


@dataclass
class AlignmentAssessment:
    curves: list[CurveAssessment]
    distinct_cases: int  # SRT solves needed (distinct bank/grade pairs)
    notes: list[str] = field(default_factory=list)


GOVERNED_BY = (None, "rollover", "side-friction")  # codes 0, 1, 2 of AlignmentColumns.governed_by


@dataclass(frozen=True)
class AlignmentColumns:
    """The assessment of every curve of an alignment for one vehicle, as arrays (one entry per curve).

    nan marks a missing value (no posted speed, no SRT); ``governed_by`` is a code into :data:`GOVERNED_BY`;
    ``meets_standard_min_radius`` is 1, 0 or -1 (unknown: no posted speed, or one outside the standard's range);
    ``error[i]`` indexes ``errors`` (the reason the curve's bank/grade pair has no SRT) or is -1.
    """

    radius_m: np.ndarray
    superelevation_percent: np.ndarray
    superelevation_derived: np.ndarray
    grade_percent: np.ndarray
    posted_speed_kmh: np.ndarray
    srt_g: np.ndarray
    rollover_speed_kmh: np.ndarray
    side_friction_speed_kmh: np.ndarray
    side_friction: np.ndarray
    side_friction_clamped: np.ndarray
    safe_speed_kmh: np.ndarray
    governed_by: np.ndarray
    margin_kmh: np.ndarray
    flagged: np.ndarray
    standard_min_radius_m: np.ndarray
    meets_standard_min_radius: np.ndarray
    error: np.ndarray
    errors: list[str]
    distinct_cases: int

    def __len__(self) -> int:
        return len(self.radius_m)


def check_curve(c: Curve, index: int) -> None:
    """Refuse a curve that no formula can use, naming the row and the field (the bounds of
    :data:`engine.domain.BOUNDS`, the same as the JSON request's)."""
    where = f"curves[{index}]"
    check("radius_m", c.radius_m, f"{where}.radius_m")
    if c.superelevation_percent is not None:
        check("bank_percent", c.superelevation_percent, f"{where}.superelevation_percent")
    check("slope_percent", c.grade_percent, f"{where}.grade_percent")
    if c.posted_speed_kmh is not None:
        check("speed_kmh", c.posted_speed_kmh, f"{where}.posted_speed_kmh")


def check_columns(radius, e, grade, posted) -> None:
    """The bounds of :func:`check_curve` on arrays (nan: a superelevation or posted speed not given)."""
    for name, values, allow_nan, field_ in (
        ("radius_m", radius, False, "radius_m"),
        ("bank_percent", e, True, "superelevation_percent"),
        ("slope_percent", grade, False, "grade_percent"),
        ("speed_kmh", posted, True, "posted_speed_kmh"),
    ):
        b = BOUNDS[name]
        low = values > b.minimum if b.exclusive_minimum else values >= b.minimum
        ok = np.isfinite(values) & low & (values <= b.maximum)
        if allow_nan:
            ok |= np.isnan(values)
        if not np.all(ok):
            i = int(np.flatnonzero(~ok)[0])
            check(name, float(values[i]), f"curves[{i}].{field_}")


def _derive_superelevation(std, radius, e, posted, e_max) -> np.ndarray:
    """The curves' superelevation with the missing ones (nan) from the standard's distribution at their posted
    speed and ``e_max`` (the design speed of a curve is taken to be its posted speed)."""
    missing = np.isnan(e)
    if not np.any(missing):
        return e
    first = int(np.flatnonzero(missing)[0])
    if e_max is None:
        raise InvalidRoad(
            f"curves[{first}] has no superelevation_percent: give it, or max_superelevation_percent to derive it from "
            f"the {std.id} distribution",
            field=f"curves[{first}].superelevation_percent",
        )
    no_speed = missing & np.isnan(posted)
    if np.any(no_speed):
        i = int(np.flatnonzero(no_speed)[0])
        raise InvalidRoad(
            f"curves[{i}] has neither superelevation_percent nor posted_speed_kmh: the distribution needs the speed",
            field=f"curves[{i}].posted_speed_kmh",
        )
    out = e.copy()
    for v in np.unique(posted[missing]):
        sel = missing & (posted == v)
        try:
            # a curve sharper than the distribution's R_min at its posted speed has no design superelevation: it is
            # assessed on e_max, the most a road built to this e_max has (its meets_standard_min_radius is false)
            sharp = sel & (radius < distribution_min_radius_m(std, float(v), e_max) * (1.0 - 1e-12))
            out[sharp] = e_max
            rest = sel & ~sharp
            if np.any(rest):
                out[rest] = superelevation_table(std, float(v), e_max, radius[rest]).superelevation_percent
        except InvalidRoad as exc:  # name the curve: the first of this speed outside the standard's range
            i = int(np.flatnonzero(sel)[0])
            raise InvalidRoad(f"curves[{i}]: {exc}", field=f"curves[{i}].{exc.field}", value=exc.value) from None
    return out


def _standard_min_radius(std, posted, e, e_max) -> np.ndarray:
    """The standard's R_min at each curve's posted speed (nan where unknown: no posted speed, a speed outside the
    standard's range, a negative superelevation without ``e_max``) [m]."""
    out = np.full(len(posted), np.nan)
    emax = np.full(len(posted), e_max) if e_max is not None else e
    lo, hi = std.speed_range_kmh
    known = np.isfinite(posted) & (posted >= lo) & (posted <= hi) & np.isfinite(emax) & (emax >= 0)
    known &= emax <= standards.E_MAX_LIMIT_PERCENT
    if not np.any(known):
        return out
    out[known] = min_radius_array(std, posted[known], emax[known])
    return out


def superelevation_used(
    radius_m,
    superelevation_percent,
    posted_speed_kmh,
    *,
    design_standard: str = "aashto-2018",
    side_friction_bound: str | None = None,
    max_superelevation_percent: float | None = None,
) -> np.ndarray:
    """The superelevation each curve is assessed on by :func:`assess_alignment`: its own, or (nan) the design
    standard's at its posted speed and ``max_superelevation_percent``, without solving any SRT.

    Parameters
    ----------
    radius_m : curve radii [m]
    superelevation_percent : superelevations, nan = derive [%]
    posted_speed_kmh : posted speeds, nan = none [km/h]
    design_standard : id of :data:`engine.road.standards.STANDARDS` [-]
    side_friction_bound : Table 21 bound, ``thesis-table21`` only [-]
    max_superelevation_percent : the road's e_max [%]

    Raises
    ------
    InvalidRoad : the refusal :func:`assess_alignment` would raise for the same curves (``field`` names
        ``curves[i].<field>``).
    """
    radius = np.asarray(radius_m, dtype=float).reshape(-1)
    e = np.broadcast_to(np.asarray(superelevation_percent, dtype=float), radius.shape)
    posted = np.broadcast_to(np.asarray(posted_speed_kmh, dtype=float), radius.shape)
    std = standards.get_standard(design_standard, side_friction_bound)
    return _derive_superelevation(std, radius, e, posted, max_superelevation_percent)


def bank_grade_pairs(superelevation_percent: np.ndarray, grade_percent: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The distinct (superelevation, grade) pairs of some curves, shape (n, 2), and each curve's index into them:
    one SRT solve per pair (the SRT does not depend on the radius).

    Parameters
    ----------
    superelevation_percent : superelevations as used [%]
    grade_percent : grades [%]
    """
    # a complex number sorts by its real, then imaginary part (faster than np.unique(..., axis=0))
    keys, inverse = np.unique(superelevation_percent + 1j * grade_percent, return_inverse=True)
    return np.stack((keys.real, keys.imag), axis=1), inverse.reshape(-1)


def solve_bank_grade_pairs(
    case: Case, pairs: np.ndarray, *, block_map: BlockMap = map
) -> tuple[np.ndarray, dict[int, str]]:
    """The SRT of ``case`` on each (superelevation, grade) pair (rows of ``pairs``) in one batch, and why a pair has
    none (:func:`engine.models.evaluate_arrays`); a pair's SRT does not depend on the others in the batch.

    Parameters
    ----------
    case : the vehicle and SRT options (its road is replaced by each pair)
    pairs : (n, 2) superelevation and grade [%]
    block_map : runs the batch's blocks (a thread pool's ``map`` runs them in parallel; the same bits either way) [-]
    """
    srt, _, errors = evaluate_arrays(
        case, {"bank_percent": pairs[:, 0], "slope_percent": pairs[:, 1]}, block_map=block_map
    )
    return srt, errors


def _side_friction_in_blocks(std, radius: np.ndarray, e: np.ndarray, block_map: BlockMap):
    """:func:`engine.road.standards.side_friction_speed` of the curves, in blocks run by ``block_map``
    (:func:`engine.models.map_blocks`)."""

    def block(rows: range) -> standards.SideFrictionSpeed:
        return standards.side_friction_speed(std, radius[rows.start : rows.stop], e[rows.start : rows.stop])

    parts = map_blocks(block, radius.size, block_map)
    if len(parts) == 1:
        return parts[0]
    return standards.SideFrictionSpeed(
        *(np.concatenate([getattr(p, f.name) for p in parts]) for f in fields(standards.SideFrictionSpeed))
    )


def assess_alignment(
    case: Case,
    radius_m,
    superelevation_percent,
    grade_percent,
    posted_speed_kmh,
    *,
    design_standard: str = standards.DEFAULT_DESIGN_STANDARD,
    side_friction_bound: str | None = None,
    max_superelevation_percent: float | None = None,
    solve_pairs: Callable[[Case, np.ndarray], tuple[np.ndarray, dict[int, str]]] | None = None,
    block_map: BlockMap = map,
) -> AlignmentColumns:
    """Safe speed on every curve of an alignment, on arrays (one entry per curve).

    For each curve: the SRT on its superelevation and grade (``case`` gives the vehicle and the other SRT inputs;
    curves sharing bank and grade share one solve, and every distinct pair is solved in one batch), the rollover
    speed sqrt(127 SRT R) (Eq. 9.1), the side-friction speed sqrt(127 R (0.01 e + f(V))) with the design standard's
    f_max (:func:`engine.road.standards.side_friction_speed`), the safe (smaller) speed, what governs it, the margin
    against the posted speed (flagged when negative, or when no SRT exists for the curve), and the standard's
    minimum radius at the posted speed (with ``max_superelevation_percent`` as e_max, else the curve's own e).

    Parameters
    ----------
    case : the vehicle and SRT options (its road is replaced by each curve's)
    radius_m : curve radii [m]
    superelevation_percent : superelevations [%]; nan = derive from the standard's distribution (needs
        ``max_superelevation_percent`` and the curve's posted speed)
    grade_percent : grades in the direction of travel, + uphill [%]
    posted_speed_kmh : posted speeds [km/h]; nan = none
    design_standard : id of :data:`engine.road.standards.STANDARDS` [-]
    side_friction_bound : Table 21 bound, ``thesis-table21`` only [-]
    max_superelevation_percent : the road's e_max [%]
    solve_pairs : replaces :func:`solve_bank_grade_pairs` (e.g. one that remembers the pairs it solved for a
        batch assessed in slices) [-]
    block_map : runs the blocks of :data:`~engine.models.BATCH_ROWS` rows of the pairs' solve (unless
        ``solve_pairs`` replaces it) and of the side-friction speeds (a thread pool's ``map`` runs them in parallel;
        the same bits either way) [-]

    Raises
    ------
    InvalidRoad : a curve outside the bounds (``field`` names ``curves[i].<field>``), or a superelevation that
        cannot be derived.
    """
    radius = np.asarray(radius_m, dtype=float).reshape(-1)
    if not radius.size:
        raise InvalidInput("no curves to assess", field="curves")
    e_given = np.broadcast_to(np.asarray(superelevation_percent, dtype=float), radius.shape)
    grade = np.broadcast_to(np.asarray(grade_percent, dtype=float), radius.shape)
    posted = np.broadcast_to(np.asarray(posted_speed_kmh, dtype=float), radius.shape)
    check_columns(radius, e_given, grade, posted)
    std = standards.get_standard(design_standard, side_friction_bound)
    e = _derive_superelevation(std, radius, e_given, posted, max_superelevation_percent)
    pairs, inverse = bank_grade_pairs(e, grade)
    if solve_pairs is None:
        srt_pairs, pair_errors = solve_bank_grade_pairs(case, pairs, block_map=block_map)
    else:
        srt_pairs, pair_errors = solve_pairs(case, pairs)
    srt = srt_pairs[inverse]
    friction = _side_friction_in_blocks(std, radius, e, block_map)
    fric_speed = friction.speed_kmh
    with np.errstate(invalid="ignore"):
        roll = np.where(np.isfinite(srt), max_curve_speed_kmh(np.where(np.isfinite(srt), srt, 0.0), radius), np.nan)
    has = np.isfinite(srt)
    safe = np.where(has, np.minimum(roll, fric_speed), np.nan)
    governed = np.where(has, np.where(roll < fric_speed, 1, 2), 0)
    margin = safe - posted  # nan without an SRT or a posted speed
    errors = sorted(set(pair_errors.values()))
    code = {msg: k for k, msg in enumerate(errors)}
    pair_code = np.array([code.get(pair_errors.get(k), -1) for k in range(len(pairs))], dtype=int)
    error = pair_code[inverse]
    r_min = _standard_min_radius(std, posted, e, max_superelevation_percent)
    meets = np.where(np.isnan(r_min), -1, (radius >= r_min).astype(int))
    return AlignmentColumns(
        radius_m=radius,
        superelevation_percent=e,
        superelevation_derived=np.isnan(e_given),
        grade_percent=np.array(grade),
        posted_speed_kmh=np.array(posted),
        srt_g=srt,
        rollover_speed_kmh=roll,
        side_friction_speed_kmh=fric_speed,
        side_friction=friction.side_friction,
        side_friction_clamped=friction.clamped,
        safe_speed_kmh=safe,
        governed_by=governed,
        margin_kmh=margin,
        flagged=(error >= 0) | (margin < 0),
        standard_min_radius_m=r_min,
        meets_standard_min_radius=meets,
        error=error,
        errors=errors,
        distinct_cases=len(pairs),
    )


def _opt(x: float) -> float | None:
    return None if math.isnan(x) else float(x)


def assess_curves(
    case: Case,
    curves: Sequence[Curve],
    *,
    design_standard: str = standards.DEFAULT_DESIGN_STANDARD,
    side_friction_bound: str | None = None,
    max_superelevation_percent: float | None = None,
) -> AlignmentAssessment:
    """:func:`assess_alignment` for a list of :class:`Curve` (one :class:`CurveAssessment` each).

    ``side_friction_bound`` is the Table 21 bound (``thesis-table21`` only; ``low`` when not given).
    """
    if not curves:
        raise InvalidInput("no curves to assess", field="curves")
    nan = math.nan
    cols = assess_alignment(
        case,
        [c.radius_m for c in curves],
        [nan if c.superelevation_percent is None else c.superelevation_percent for c in curves],
        [c.grade_percent for c in curves],
        [nan if c.posted_speed_kmh is None else c.posted_speed_kmh for c in curves],
        design_standard=design_standard,
        side_friction_bound=side_friction_bound,
        max_superelevation_percent=max_superelevation_percent,
    )
    out = []
    for i, c in enumerate(curves):
        err = cols.errors[cols.error[i]] if cols.error[i] >= 0 else None
        meets = int(cols.meets_standard_min_radius[i])
        out.append(
            CurveAssessment(
                c.id,
                _opt(cols.srt_g[i]),
                _opt(cols.rollover_speed_kmh[i]),
                float(cols.side_friction_speed_kmh[i]),
                _opt(cols.safe_speed_kmh[i]),
                GOVERNED_BY[int(cols.governed_by[i])],
                c.posted_speed_kmh,
                _opt(cols.margin_kmh[i]),
                bool(cols.flagged[i]),
                err,
                float(cols.superelevation_percent[i]),
                bool(cols.superelevation_derived[i]),
                _opt(cols.standard_min_radius_m[i]),
                None if meets < 0 else bool(meets),
            )
        )
    return AlignmentAssessment(out, cols.distinct_cases)
