"""The SRT entry points: one case (:func:`rollover_threshold`), a list of cases and a grid (:func:`sweep`).

Every entry point takes a :class:`~engine.case.Case`; the model registry (:mod:`engine.models`) says how each
model checks and solves it. The answer is never a silently absurd number: a case outside the model's domain is
refused before solving, an SRT at or below zero (the vehicle would tip at rest) is refused naming the input that
causes it, and an SRT above the tires' friction limit carries a note that the vehicle slides before it rolls.

References
----------
Thesis Secs. 1.3, 6.2 (Eqs. 6.17-6.18, 6.39), 7.2, 9.1-9.2, Tables 17 and 19; AASHTO (2018) Eq. 3-8.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any, TypeVar

import numpy as np

from engine.case import Case, check_stage_and_limit
from engine.domain import DEFAULT_CURVE_POINTS, MAX_CURVE_POINTS
from engine.errors import InvalidInput, RolloverError
from engine.models.registry import get_model, record_view
from engine.models.stepping import solve_3d_many
from engine.models.trailer3d import get_closure
from engine.results import RolloverResult
from engine.vehicle.combination import Combination
from engine.vehicle.record import Vehicle

METHODS = ("reduced", "davies")
T = TypeVar("T")

#: tire-road friction coefficient against which every SRT is compared [-]. Assumed: the low end of the
#: 0.8-1.0 peak lateral friction of truck tires on dry pavement; on a wet or worn road it is lower, so a
#: vehicle whose SRT is above it slides (or jackknifes) rather than rolls on any normal road.
TIRE_ROAD_FRICTION = 0.8

#: grid axes accepted by :func:`sweep`, with the part of the case each one sets
SWEEP_AXES = {
    "bank_percent": "road",
    "slope_percent": "road",
    "trailer_angle_deg": "angle",
    "lateral_offset_m": "load",
    "longitudinal_offset_m": "load",
    "vertical_offset_m": "load",
    "overweight_percent": "load",
    "rear_llt_limit": "limit",
}


def sliding_threshold_g(friction: float, bank_rad) -> float:
    """Lateral acceleration at which the tires slide on a bank, (f + e)/(1 - f e) with e = tan(bank) [g].

    The exact point-mass balance on a banked curve (AASHTO 2018, Eq. 3-8, V^2/(g R) = (0.01 e + f)/(1 - 0.01 e f)).
    """
    e = math.tan(bank_rad)
    return (friction + e) / (1.0 - friction * e) if friction * e < 1.0 else math.inf


def _check_options(curve_points: int, method: str, chassis_closure: str) -> None:
    if not (
        isinstance(curve_points, int) and not isinstance(curve_points, bool) and 2 <= curve_points <= MAX_CURVE_POINTS
    ):
        raise InvalidInput(
            f"curve_points must be an integer in [2, {MAX_CURVE_POINTS}]", field="curve_points", value=curve_points
        )
    if method not in METHODS:
        raise InvalidInput(f"method must be one of {', '.join(METHODS)}", field="method", value=method)
    get_closure(chassis_closure)


def _tips_at_rest(case: Case, srt: float) -> InvalidInput:
    """The error for an SRT at or below zero, naming the input that tips the vehicle."""
    if case.road.bank_percent < 0:
        field, value = "road.bank_percent", case.road.bank_percent
    elif case.load.lateral_offset_m != 0:
        field, value = "load.lateral_offset_m", case.load.lateral_offset_m
    else:
        field, value = "vehicle.cg_height_above_chassis_m", case.vehicle.cg_height_above_chassis_m
    return InvalidInput(
        f"the vehicle reaches its limit with no lateral acceleration (SRT = {srt:.3f} g): it would tip at rest on a "
        f"{case.road.bank_percent} % bank with a {case.load.lateral_offset_m} m lateral offset and rear LLT limit "
        f"{case.rear_llt_limit}",
        field=field,
        value=value,
    )


def _friction_note(case: Case, srt: float) -> str | None:
    slide = sliding_threshold_g(TIRE_ROAD_FRICTION, case.road.bank_rad)
    if srt <= slide:
        return None
    return (
        f"the SRT ({srt:.3f} g) is above the lateral acceleration at which the tires slide on this bank "
        f"({slide:.3f} g with a tire-road friction of {TIRE_ROAD_FRICTION}): the vehicle slides before it rolls"
    )


def rollover_threshold(
    case: Case,
    *,
    include_curves: bool = False,
    curve_points: int = DEFAULT_CURVE_POINTS,
    method: str = "reduced",
    chassis_closure: str = "chassis-constant",
) -> RolloverResult:
    """Static rollover threshold of one case.

    Parameters
    ----------
    case : the vehicle, model, stage, road, trailer angle, load and rear LLT limit (:class:`engine.case.Case`)
    include_curves : also return the quantities against ay/g from rest to the limit (2D and 3D only) [-]
    curve_points : number of points of the curves, 2-401 [-]
    method : ``"reduced"`` (the hand-reduced statics, fast) or ``"davies"`` (the full Davies statics at every
        iteration, the reference path) [-]
    chassis_closure : the 3D model's roll-moment closure, an id of :data:`engine.models.trailer3d.CLOSURES` [-]

    Returns
    -------
    RolloverResult
        ``srt`` [g] (the lateral acceleration ay/g at which the rear inner tire lifts off, Eq. 6.18, or the rear
        LLT reaches the limit), the roll angle [deg], the state at the limit, the stage values and notes.

    Raises
    ------
    InvalidVehicle, InvalidRoad, InvalidLoad, InvalidInput : refused before solving, ``field`` naming the input.
    ConvergenceError : the geometry/force iteration did not converge.
    MechanismSingular : (davies method) the statics did not determine a reported quantity.
    """
    model = get_model(case.model)
    _check_options(curve_points, method, chassis_closure)
    if include_curves and not model.curves:
        raise InvalidInput(f"the {model.id} model has no curves against ay/g", field="include_curves", value=True)
    case, note = record_view(case)
    model.check(case)
    solve = model.solve_combination if isinstance(case.vehicle, Combination) else model.solve
    result = solve(
        case, include_curves=include_curves, curve_points=curve_points, method=method, chassis_closure=chassis_closure
    )
    if note is not None:
        result = replace(result, notes=[note, *result.notes])
    return _finish(case, result)


def _finish(case: Case, result: RolloverResult) -> RolloverResult:
    """A model's result as the entry points give it: refused if the vehicle tips at rest, the friction note added."""
    if not result.srt > 0:
        raise _tips_at_rest(case, result.srt)
    note = _friction_note(case, result.srt)
    return replace(result, notes=[*result.notes, note]) if note else result


#: fewest 3D cases of one vehicle and stage that :func:`rollover_thresholds` solves together on arrays: an array
#: solve costs about as much as 15 one-case solves whatever its size up to a few hundred cases, so below this one case
#: at a time is faster (``python bench/bench_engine.py``, the "many cases" rows)
MIN_ARRAY_CASES = 16


def rollover_thresholds(cases: Sequence[Case]) -> list[RolloverResult | RolloverError]:
    """:func:`rollover_threshold` of each case with the default options (no curves, the reduced statics, the
    default chassis closure): in each case's place its result, or the error it raises.

    The 3D cases of one vehicle and stage, when there are at least :data:`MIN_ARRAY_CASES` of them, are solved
    together on arrays (:func:`~engine.models.stepping.solve_3d_many`); a converged case stops where it would alone,
    so its result is the one :func:`rollover_threshold` gives, to rounding (tests/engine/test_thresholds_many.py). The
    others, and a case whose array solve failed (for its exact error), are solved one at a time.
    """
    out: list[RolloverResult | RolloverError | None] = [None] * len(cases)
    notes: dict[int, str] = {}
    cases = list(cases)
    views: dict[tuple, tuple[Case, str | None] | RolloverError] = {}
    for i, case in enumerate(cases):  # a 3D case of a combination: its last unit's record, solved once per vehicle
        if case.model == "3d" and isinstance(case.vehicle, Combination):
            key = (case.vehicle, case.rear_llt_limit)
            if key not in views:
                try:
                    views[key] = record_view(case.replace(road=type(case.road)(), load=type(case.load)()))
                except RolloverError as exc:
                    views[key] = exc
            view = views[key]
            if isinstance(view, RolloverError):
                out[i] = view
                continue
            cases[i], notes[i] = case.replace(vehicle=view[0].vehicle), view[1]
    groups: dict[tuple, list[int]] = {}
    for i, case in enumerate(cases):
        if out[i] is not None:
            continue
        if case.model == "3d":
            groups.setdefault((case.vehicle, case.stage), []).append(i)
    model_3d = get_model("3d")
    valid: dict[int, Vehicle] = {}  # records validated in this call, by identity (kept alive here: ids stay unique)
    for rows in groups.values():
        if len(rows) < MIN_ARRAY_CASES:
            continue  # one at a time below (checked there: a small group is not checked twice)
        checked = [i for i in rows if _passes_3d_checks(model_3d, cases[i], valid)]
        if len(checked) < MIN_ARRAY_CASES:
            continue
        for i, result in zip(checked, solve_3d_many([cases[i] for i in checked]), strict=True):
            if result is not None:
                if i in notes:
                    result = replace(result, notes=[notes[i], *result.notes])
                out[i] = _finished_or_error(cases[i], result)
    for i, case in enumerate(cases):
        if out[i] is None:
            try:
                result = rollover_threshold(case)
                out[i] = replace(result, notes=[notes[i], *result.notes]) if i in notes else result
            except RolloverError as exc:
                out[i] = exc
    return out  # type: ignore[return-value]


def _passes_3d_checks(model, case: Case, valid: dict[int, Vehicle]) -> bool:
    """Whether ``case`` passes the 3D model's checks (its vehicle validated once per record in ``valid``); a case that
    does not is solved alone, for the error :func:`rollover_threshold` gives (its checks in their order)."""
    try:
        if id(case.vehicle) not in valid:
            model.validate(case.vehicle)
            valid[id(case.vehicle)] = case.vehicle
        model.check(case, vehicle=False)
    except RolloverError:
        return False
    return True


def _finished_or_error(case: Case, result: RolloverResult) -> RolloverResult | RolloverError:
    try:
        return _finish(case, result)
    except RolloverError as exc:
        return exc


# ------------------------------------------------------------------------------------- many cases

_MECHANISM_FAILED = (
    "the mechanism left its valid geometry for this case: the vehicle is at or beyond its static stability limit"
)


def _columns(case: Case, n: int, arrays: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Every case input as an array of length n: the given ones, the base case's value for the others."""
    base = {
        "bank_percent": case.road.bank_percent,
        "slope_percent": case.road.slope_percent,
        "trailer_angle_deg": case.trailer_angle_deg,
        "lateral_offset_m": case.load.lateral_offset_m,
        "longitudinal_offset_m": case.load.longitudinal_offset_m,
        "vertical_offset_m": case.load.vertical_offset_m,
        "overweight_percent": case.load.overweight_percent,
        "rear_llt_limit": case.rear_llt_limit,
    }
    return {k: np.broadcast_to(np.asarray(arrays.get(k, v), dtype=float), (n,)) for k, v in base.items()}


def case_at(case: Case, columns: Mapping[str, np.ndarray], i: int) -> Case:
    """The case of row ``i`` of a batch (for its exact error message, or a one-case solve)."""
    c = case
    for axis, values in columns.items():
        c = with_axis(c, axis, float(values[i]))
    return c


def _suspect_rows(model, case: Case, col: Mapping[str, np.ndarray]) -> np.ndarray:
    """Rows that may break a domain rule (a vectorised over-approximation of :meth:`Model.check`): they are checked
    one by one for their exact message; every other row is known to pass."""
    from engine.case import MAX_CG_BEHIND_REAR_GROUP
    from engine.domain import BOUNDS

    v = case.vehicle
    bad = np.zeros(len(col["bank_percent"]), dtype=bool)
    for axis, values in col.items():
        b = BOUNDS[axis]
        low = values > b.minimum if b.exclusive_minimum else values >= b.minimum
        bad |= ~(np.isfinite(values) & low & (values <= b.maximum))
    keys = {
        "bank_percent": "bank",
        "slope_percent": "slope",
        "trailer_angle_deg": "trailer_angle",
        "lateral_offset_m": "d1",
        "longitudinal_offset_m": "d2",
        "vertical_offset_m": "d3",
        "overweight_percent": "overweight",
    }
    for axis, key in keys.items():
        if key not in (model.combination_takes if isinstance(v, Combination) else model.takes):
            bad |= col[axis] != 0
    takes = model.combination_takes if isinstance(v, Combination) else model.takes
    if "rear_llt_limit" not in takes:
        bad |= col["rear_llt_limit"] != 1.0
    if isinstance(v, Combination):  # every row is checked by the combination model's own solve
        return bad
    bad |= np.abs(col["lateral_offset_m"]) >= v.rear_track_m / 2.0
    bad |= v.cg_height_above_chassis_m + col["vertical_offset_m"] <= 0
    if v.wheelbase_m is not None and v.front_axle_to_cg_m is not None:
        a_eff = v.front_axle_to_cg_m - col["longitudinal_offset_m"]
        bad |= (a_eff <= 0) | (a_eff > MAX_CG_BEHIND_REAR_GROUP * v.wheelbase_m)
    return bad


#: rows of one batch solve: larger batches are split into blocks of this many rows, in the rows' order (so the same
#: request always gives the same bits). A row's answer does not depend on the rows solved with it beyond the
#: fixed-point tolerance (tests/engine/test_sweep.py), and blocks whose arrays stay in the CPU's cache are faster than
#: one pass over 100,000 rows (bench/bench_engine.py: 1.6-2.05 s against 2.1-2.2 s here) and bound the temporaries
BATCH_ROWS = 16_384

#: how the blocks of a batch are run: ``map(function, blocks)`` or any function like it that yields the results in the
#: blocks' order (e.g. ``concurrent.futures.ThreadPoolExecutor.map``)
BlockMap = Callable[[Callable[[range], Any], Iterable[range]], Iterator[Any]]


def map_blocks(function: Callable[[range], T], size: int, block_map: BlockMap = map, rows: int = BATCH_ROWS) -> list[T]:
    """``function`` of each block of ``rows`` consecutive positions of ``range(size)`` (the last one shorter), in
    order, run by ``block_map``; a single block is run in the caller. The blocks depend on ``size`` and ``rows`` only,
    never on ``block_map``, so neither do the bits of an elementwise computation."""
    blocks = [range(start, min(start + rows, size)) for start in range(0, size, rows)]
    return [function(blocks[0])] if len(blocks) == 1 else list(block_map(function, blocks))


def evaluate_arrays(
    case: Case,
    arrays: Mapping[str, Sequence[float]],
    *,
    chassis_closure: str = "chassis-constant",
    batch_rows: int = BATCH_ROWS,
    block_map: BlockMap = map,
) -> tuple[np.ndarray, np.ndarray, dict[int, str]]:
    """SRT [g] and roll [deg] of many cases of one vehicle, model and stage: ``case`` with each input of ``arrays``
    (keys of :data:`SWEEP_AXES`, equal-length arrays) varied row by row.

    Returns ``(srt, roll, errors)``: arrays with nan where ``errors`` (row -> message) says why. The domain is
    checked with arrays (a row that may break a rule is checked alone, for its exact message); models with a batch
    solve run every valid row through it at once, a row whose mechanism leaves its valid geometry failing alone.

    ``block_map`` runs the blocks of ``batch_rows`` rows (:data:`BlockMap`). The blocks are the same whichever runs
    them, so the bits are too; a thread pool's ``map`` runs them in parallel, as the batch solve spends its time in
    numpy, which releases the GIL (``bench/bench_engine.py``: about half the time with two threads on two cores).
    """
    model = get_model(case.model)
    get_closure(chassis_closure)
    check_stage_and_limit(case)
    model.validate(case.vehicle)  # one vehicle for every row: a bad record is the caller's error, not a row's
    if isinstance(case.vehicle, Combination) and model.solve_combination is None:
        case, _note = record_view(case)  # a record model sees the combination's last unit, the same for every row
    n = len(next(iter(arrays.values()))) if arrays else 1
    col = _columns(case, n, arrays)
    srt, roll = np.full(n, np.nan), np.full(n, np.nan)
    errors: dict[int, str] = {}
    for i in np.flatnonzero(_suspect_rows(model, case, col)):
        try:
            model.check(case_at(case, col, int(i)))
        except RolloverError as exc:
            errors[int(i)] = str(exc)
    refused = np.zeros(n, dtype=bool)
    refused[list(errors)] = True
    ok = np.flatnonzero(~refused)
    if not ok.size:
        return srt, roll, errors
    if model.batch is None:  # closed forms: microseconds each
        for i in ok:
            try:
                res = rollover_threshold(case_at(case, col, int(i)), chassis_closure=chassis_closure)
            except RolloverError as exc:
                errors[int(i)] = str(exc)
                continue
            srt[i] = res.srt
            roll[i] = np.nan if res.roll_angle_deg is None else res.roll_angle_deg
        return srt, roll, errors

    def solve(block: range) -> tuple[np.ndarray, np.ndarray]:
        rows = ok[block.start : block.stop]
        return model.batch(case, {k: v[rows] for k, v in col.items()}, chassis_closure)

    solved = map_blocks(solve, ok.size, block_map, batch_rows)
    ay = np.concatenate([a for a, _ in solved])
    rl = np.concatenate([r for _, r in solved])
    good = np.isfinite(ay) & (ay > 0)
    srt[ok[good]], roll[ok[good]] = ay[good], rl[good]
    native = isinstance(case.vehicle, Combination) and model.solve_combination is not None
    for k in np.flatnonzero(~good):
        i = int(ok[k])
        failed = not np.isfinite(ay[k])
        if failed and native:  # the combination's batch refuses a row without saying why: its own solve says it
            try:
                alone = rollover_threshold(case_at(case, col, i), chassis_closure=chassis_closure)
            except RolloverError as exc:
                errors[i] = str(exc)
            else:
                srt[i], roll[i] = alone.srt, np.nan if alone.roll_angle_deg is None else alone.roll_angle_deg
            continue
        errors[i] = _MECHANISM_FAILED if failed else str(_tips_at_rest(case_at(case, col, i), float(ay[k])))
    return srt, roll, errors


def evaluate_cases(
    cases: Sequence[Case], *, chassis_closure: str = "chassis-constant"
) -> tuple[np.ndarray, np.ndarray, dict[int, str]]:
    """SRT [g] and roll [deg] of a list of cases of one vehicle, model and stage (:func:`evaluate_arrays`)."""
    if not cases:
        return np.full(0, np.nan), np.full(0, np.nan), {}
    base = cases[0]
    arrays = {
        "bank_percent": [c.road.bank_percent for c in cases],
        "slope_percent": [c.road.slope_percent for c in cases],
        "trailer_angle_deg": [c.trailer_angle_deg for c in cases],
        **{
            k: [getattr(c.load, k) for c in cases]
            for k in ("lateral_offset_m", "longitudinal_offset_m", "vertical_offset_m", "overweight_percent")
        },
        "rear_llt_limit": [c.rear_llt_limit for c in cases],
    }
    return evaluate_arrays(base, arrays, chassis_closure=chassis_closure)


@dataclass(frozen=True)
class SweepResult:
    """A grid of cases: ``axes`` names the varied inputs, ``values[i]`` their values in case i."""

    model: str
    stage: str | None
    axes: tuple[str, ...]
    values: np.ndarray  # (n_cases, n_axes)
    srt: np.ndarray  # (n_cases,) [g]; nan where ``errors`` has an entry
    roll_angle_deg: np.ndarray  # (n_cases,) [deg]; nan for closed forms without roll
    errors: dict[int, str]  # case index -> why it has no value

    def rows(self) -> list[dict[str, float | str | None]]:
        out = []
        for i, vals in enumerate(self.values):
            row: dict[str, float | str | None] = dict(zip(self.axes, (float(v) for v in vals), strict=True))
            row["srt"] = None if i in self.errors else float(self.srt[i])
            r = float(self.roll_angle_deg[i])
            row["roll_angle_deg"] = None if (i in self.errors or math.isnan(r)) else r
            row["error"] = self.errors.get(i)
            out.append(row)
        return out


def with_axis(case: Case, axis: str, value: float) -> Case:
    """The case with one sweep axis (:data:`SWEEP_AXES`) set to ``value``."""
    where = SWEEP_AXES[axis]
    if where == "road":
        return case.replace(road=replace(case.road, **{axis: value}))
    if where == "load":
        return case.replace(load=replace(case.load, **{axis: value}))
    if where == "angle":
        return case.replace(trailer_angle_deg=value)
    return case.replace(rear_llt_limit=value)


def sweep(
    case: Case,
    grid: Mapping[str, Sequence[float]],
    *,
    chassis_closure: str = "chassis-constant",
    block_map: BlockMap = map,
) -> SweepResult:
    """SRT over the Cartesian product of ``grid`` (axes of :data:`SWEEP_AXES`) around ``case``, e.g. Tables 17, 19.

    The 3D and 2D models solve all cases at once (numpy arrays through the same fast path); a case the engine
    refuses or cannot solve gets an entry in ``errors`` instead of a number, and the others are kept.
    ``block_map``: see :func:`evaluate_arrays`.
    """
    get_model(case.model)
    check_stage_and_limit(case)
    if not grid:
        raise InvalidInput("the grid needs at least one axis", field="grid")
    for axis, vals in grid.items():
        if axis not in SWEEP_AXES:
            raise InvalidInput(f"unknown sweep axis {axis!r}; use {', '.join(SWEEP_AXES)}", field=f"grid.{axis}")
        if len(vals) == 0:
            raise InvalidInput(f"grid.{axis} is empty", field=f"grid.{axis}")
    axes = tuple(grid)
    mesh = np.meshgrid(*(np.asarray(grid[a], dtype=float) for a in axes), indexing="ij")
    values = np.stack([m.reshape(-1) for m in mesh], axis=1)  # product order: the first axis varies slowest
    srt, roll, errors = evaluate_arrays(
        case, {a: values[:, k] for k, a in enumerate(axes)}, chassis_closure=chassis_closure, block_map=block_map
    )
    return SweepResult(case.model, case.stage if case.model == "3d" else None, axes, values, srt, roll, errors)
