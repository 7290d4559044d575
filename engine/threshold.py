"""Quasi-static load stepping to the rollover limit, and the public SRT entry points.

The lateral acceleration is raised from rest until the rear inner tire lifts off (Fz19 = 0) or the rear
lateral load transfer reaches ``rear_llt_limit``. Because the model is elastic (path independent), the
state at any ay is the consistent geometry/force solution at that ay: :func:`engine.trailer3d.solve` finds
the limit directly (the limit condition is one more linear equation at frozen geometry), and the curves of
Figs. 92-97 are the same solution at intermediate ay, each started from the previous one.

References
----------
Thesis Secs. 1.3, 6.2 (Eqs. 6.17-6.18, 6.39), 7.2, 9.1-9.2.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace

import numpy as np

from . import trailer2d, trailer3d
from .classic import CLASSIC_MODELS, classic_threshold
from .errors import InvalidInput, InvalidLoad, RolloverError
from .groups import ARRAY
from .loads import LoadCase, Road, check_case, kingpin_uplift_note
from .results import Curves, RolloverResult, TireLoads
from .vehicles import Vehicle, validate_vehicle

MODEL_IDS = ("3d", "2d", *CLASSIC_MODELS)
STAGES = trailer3d.STAGES
METHODS = ("reduced", "davies")
CLOSURES = trailer3d.CLOSURES
MAX_CURVE_POINTS = 401

#: grid axes accepted by :func:`sweep`, with the road/load field each one sets
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


def _check_options(model, stage, rear_llt_limit, curve_points, method, chassis_closure):
    if model not in MODEL_IDS:
        raise InvalidInput(f"model must be one of {', '.join(MODEL_IDS)}, got {model!r}", field="model", value=model)
    if stage not in STAGES:
        raise InvalidInput(f"stage must be one of {', '.join(STAGES)}, got {stage!r}", field="stage", value=stage)
    if stage != "full" and model != "3d":
        raise InvalidInput("stage applies to the 3d model only", field="stage", value=stage)
    if not (isinstance(rear_llt_limit, int | float) and math.isfinite(rear_llt_limit) and 0 < rear_llt_limit <= 1):
        raise InvalidLoad(
            f"rear_llt_limit must be in (0, 1], got {rear_llt_limit!r}", field="rear_llt_limit", value=rear_llt_limit
        )
    if not (isinstance(curve_points, int) and 2 <= curve_points <= MAX_CURVE_POINTS):
        raise InvalidInput(
            f"curve_points must be an integer in [2, {MAX_CURVE_POINTS}]", field="curve_points", value=curve_points
        )
    if method not in METHODS:
        raise InvalidInput(f"method must be one of {METHODS}", field="method", value=method)
    if chassis_closure not in CLOSURES:
        raise InvalidInput(f"chassis_closure must be one of {CLOSURES}", field="chassis_closure", value=chassis_closure)


def _check_case(vehicle: Vehicle, model: str, road: Road, trailer_angle_deg: float, load: LoadCase) -> None:
    check_case(vehicle, road, trailer_angle_deg, load)
    if model == "2d":
        for name, value in (("road.slope_percent", road.slope_percent), ("trailer_angle_deg", trailer_angle_deg)):
            if value != 0:
                raise InvalidInput(
                    f"the 2d model (one axle group in its transverse plane) has no {name}; use the 3d model",
                    field=name,
                    value=value,
                )


def _positive_srt(srt: float, road: Road, load: LoadCase) -> None:
    if not srt > 0:
        raise InvalidInput(
            f"the rear lateral load transfer reaches its limit with no lateral acceleration (SRT = {srt:.3f} g): "
            f"the vehicle would tip at rest on a {road.bank_percent} % bank with a "
            f"{load.lateral_offset_m} m lateral offset",
            field="load.lateral_offset_m",
            value=load.lateral_offset_m,
        )


# ------------------------------------------------------------------------------------------ 3D


def stage_model(
    vehicle: Vehicle, stage: str, chassis_closure: str = "chassis-constant", method: str = "reduced"
) -> trailer3d.TrailerModel:
    """The 3D model of one stage, with the chassis constant calibrated when that closure is chosen."""
    m = trailer3d.build_model(vehicle, stage, chassis_closure)
    if chassis_closure == "chassis-constant":
        forces = trailer3d.davies_forces_at if method == "davies" else None
        m = trailer3d.calibrate_chassis_constant(m, forces)
    return m


def _case3d(vehicle: Vehicle, road: Road, angle_deg: float, load: LoadCase, limit: float) -> trailer3d.Case:
    return trailer3d.Case(
        weight=load.weight_kn(vehicle.weight_kn),
        bank=road.bank_rad,
        slope=road.slope_rad,
        psi=math.radians(angle_deg),
        d1=load.lateral_offset_m,
        d2=load.longitudinal_offset_m,
        d3=load.vertical_offset_m,
        llt_limit=limit,
    )


def _clean(scale: float, *loads) -> list[float]:
    """Loads as floats, with round-off around an exact zero (the lifted tire, ~1e-13 kN) set to 0."""
    return [0.0 if abs(x) <= 1e-9 * abs(scale) else float(x) for x in loads]


def _llt(outer, inner):
    return (outer - inner) / (outer + inner)


def _curves_3d(m, case, limit_sol, points, forces) -> Curves:
    ays = np.linspace(0.0, limit_sol.ay, points)
    rows = []
    state = None
    for a in ays[:-1]:
        s = trailer3d.solve(m, case, float(a), start=state, forces=forces)
        state = s.state
        rows.append(s)
    rows.append(limit_sol)
    f = [_clean(case.weight, r.front.fz_outer, r.front.fz_inner, r.rear.fz_outer, r.rear.fz_inner) for r in rows]
    return Curves(
        ay_g=[float(a) for a in ays],
        fz_front_outer_kn=[float(x[0]) for x in f],
        fz_front_inner_kn=[float(x[1]) for x in f],
        fz_rear_outer_kn=[float(x[2]) for x in f],
        fz_rear_inner_kn=[float(x[3]) for x in f],
        llt_front=[float(_llt(x[0], x[1])) for x in f],
        llt_rear=[float(_llt(x[2], x[3])) for x in f],
        roll_angle_deg=[math.degrees(float(r.geometry.roll)) for r in rows],
        cg_lateral_m=[float(r.geometry.cg[1]) for r in rows],
        cg_height_m=[float(r.geometry.cg[2]) for r in rows],
    )


def _result_3d(stage, sol, limit, stage_values, curves, m) -> RolloverResult:
    fo, fi, ro, ri = sol.front.fz_outer, sol.front.fz_inner, sol.rear.fz_outer, sol.rear.fz_inner
    return RolloverResult(
        model="3d",
        stage=stage,
        srt=float(sol.ay),
        roll_angle_deg=math.degrees(float(sol.geometry.roll)),
        limit="rear-inner-lift-off" if limit == 1.0 else "rear-llt-limit",
        rear_llt_limit=limit,
        llt_front=float(_llt(fo, fi)),
        llt_rear=float(_llt(ro, ri)),
        tire_loads=TireLoads(*_clean(float(sol.loads.pz), fo, fi, ro, ri)),
        cg_lateral_m=float(sol.geometry.cg[1]),
        cg_height_m=float(sol.geometry.cg[2]),
        stage_values=stage_values,
        iterations=sol.iterations,
        parameters={
            **({"chassis_constant_x": float(m.torque_split_x)} if m.closure == "torque-split" else {}),
            "rear_load_kn": float(sol.loads.fr),
            "front_load_kn": float(sol.loads.pz - sol.loads.fr),
            "theta27_deg": math.degrees(float(sol.geometry.theta27)),
        },
        curves=curves,
    )


# ------------------------------------------------------------------------------------------ 2D


def _case2d(vehicle: Vehicle, m: trailer2d.PlanarModel, road: Road, load: LoadCase, limit) -> trailer2d.Case2D:
    return trailer2d.Case2D(
        weight=load.weight_kn(vehicle.weight_kn) * m.load_share,
        bank=road.bank_rad,
        d1=load.lateral_offset_m,
        d3=load.vertical_offset_m,
        llt_limit=limit,
    )


def _curves_2d(m, case, limit_sol, points, forces) -> Curves:
    ays = np.linspace(0.0, limit_sol.ay, points)
    rows, state = [], None
    for a in ays[:-1]:
        s = trailer2d.solve(m, case, float(a), start=state, forces=forces)
        state = s.state
        rows.append(s)
    rows.append(limit_sol)
    return Curves(
        ay_g=[float(a) for a in ays],
        fz_front_outer_kn=None,
        fz_front_inner_kn=None,
        fz_rear_outer_kn=[_clean(case.weight, r.forces.fz_outer)[0] for r in rows],
        fz_rear_inner_kn=[_clean(case.weight, r.forces.fz_inner)[0] for r in rows],
        llt_front=None,
        llt_rear=[float(_llt(r.forces.fz_outer, r.forces.fz_inner)) for r in rows],
        roll_angle_deg=[math.degrees(float(r.geometry.top_angle)) for r in rows],
        cg_lateral_m=[float(r.cg[0]) for r in rows],
        cg_height_m=[float(r.cg[1]) for r in rows],
    )


# ------------------------------------------------------------------------------------ public API


def rollover_threshold(
    vehicle: Vehicle,
    model: str = "3d",
    *,
    stage: str = "full",
    road: Road = Road(),
    trailer_angle_deg: float = 0.0,
    load: LoadCase = LoadCase(),
    rear_llt_limit: float = 1.0,
    include_curves: bool = False,
    curve_points: int = 41,
    method: str = "reduced",
    chassis_closure: str = "chassis-constant",
) -> RolloverResult:
    """Static rollover threshold of ``vehicle`` with one model.

    Parameters
    ----------
    vehicle : the vehicle record (:mod:`engine.vehicles`)
    model : ``"3d"`` (Ch. 6), ``"2d"`` (Ch. 5) or a closed form of Ch. 2 (:data:`engine.classic.MODELS`)
    stage : 3D only: ``"full"`` (tires, suspension, fifth wheel, chassis) or ``"tires-suspension"``
    road : bank [%] and slope [%, + uphill]
    trailer_angle_deg : psi, the angle between the last two units [deg] (3D only)
    load : CG offsets d1 d2 d3 [m] and overweight [%]
    rear_llt_limit : the rear LLT at which the ramp stops; 1 = rear inner tire lift-off [-]
    include_curves, curve_points : return the quantities against ay/g from rest to the limit
    method : ``"reduced"`` (hand-reduced statics, fast) or ``"davies"`` (full Davies solve per iteration)
    chassis_closure : the roll-moment closure of the 3D model (:data:`engine.trailer3d.CLOSURES`)

    Raises
    ------
    InvalidVehicle, InvalidRoad, InvalidLoad, InvalidInput : refused before solving.
    ConvergenceError : the geometry/force iteration did not converge.
    MechanismSingular : (davies method) the statics did not determine a reported quantity.
    """
    _check_options(model, stage, rear_llt_limit, curve_points, method, chassis_closure)
    if model in CLASSIC_MODELS:
        r = classic_threshold(vehicle, model, road, load, trailer_angle_deg, rear_llt_limit)
        if include_curves:
            raise InvalidInput(
                f"the {model} model is a closed form; it has no curves against ay/g", field="include_curves", value=True
            )
        return RolloverResult(
            model=model,
            stage=None,
            srt=r.srt,
            roll_angle_deg=r.roll_angle_deg,
            limit="closed-form",
            rear_llt_limit=1.0,
            parameters=r.parameters,
        )
    validate_vehicle(vehicle, model=model)
    _check_case(vehicle, model, road, trailer_angle_deg, load)

    if model == "2d":
        forces = trailer2d.davies_forces_at if method == "davies" else None
        m = trailer2d.build_model(vehicle, load.longitudinal_offset_m)
        case = _case2d(vehicle, m, road, load, rear_llt_limit)
        sol = trailer2d.solve(m, case, forces=forces)
        _positive_srt(sol.ay, road, load)
        curves = _curves_2d(m, case, sol, curve_points, forces) if include_curves else None
        f = sol.forces
        return RolloverResult(
            model="2d",
            stage=None,
            srt=float(sol.ay),
            roll_angle_deg=math.degrees(float(sol.geometry.top_angle)),
            limit="rear-inner-lift-off" if rear_llt_limit == 1.0 else "rear-llt-limit",
            rear_llt_limit=rear_llt_limit,
            llt_rear=float(_llt(f.fz_outer, f.fz_inner)),
            tire_loads=TireLoads(None, None, *_clean(float(case.weight), f.fz_outer, f.fz_inner)),
            cg_lateral_m=float(sol.cg[0]),
            cg_height_m=float(sol.cg[1]),
            iterations=sol.iterations,
            parameters={
                "group_load_kn": float(case.weight),
                "srt_eq_5_22": float(trailer2d.srt_eq_5_22(sol.cg[0], sol.cg[1], math.tan(road.bank_rad))),
            },
            curves=curves,
        )

    forces = trailer3d.davies_forces_at if method == "davies" else None
    case = _case3d(vehicle, road, trailer_angle_deg, load, rear_llt_limit)
    stages = ("tires-suspension", "full") if stage == "full" else ("tires-suspension",)
    sols = {}
    for st in stages:
        m = stage_model(vehicle, st, chassis_closure, method)
        sols[st] = (m, trailer3d.solve(m, case, forces=forces))
    m, sol = sols[stage]
    _positive_srt(sol.ay, road, load)
    stage_values = {"srt_ts": float(sols["tires-suspension"][1].ay)}
    if "full" in sols:
        stage_values["srt_3d"] = float(sols["full"][1].ay)
    curves = _curves_3d(m, case, sol, curve_points, forces) if include_curves else None
    result = _result_3d(stage, sol, rear_llt_limit, stage_values, curves, m)
    note = kingpin_uplift_note(vehicle.front_axle_to_cg_m - load.longitudinal_offset_m, vehicle.wheelbase_m)
    return replace(result, notes=[note]) if note else result


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


def _apply(axis: str, value: float, road: Road, angle: float, load: LoadCase, limit: float):
    where = SWEEP_AXES[axis]
    if where == "road":
        road = replace(road, **{axis: value})
    elif where == "load":
        load = replace(load, **{axis: value})
    elif where == "angle":
        angle = value
    else:
        limit = value
    return road, angle, load, limit


def sweep(
    vehicle: Vehicle,
    grid: Mapping[str, Sequence[float]],
    *,
    model: str = "3d",
    stage: str = "full",
    road: Road = Road(),
    trailer_angle_deg: float = 0.0,
    load: LoadCase = LoadCase(),
    rear_llt_limit: float = 1.0,
    chassis_closure: str = "chassis-constant",
) -> SweepResult:
    """SRT over the Cartesian product of ``grid`` (axes of :data:`SWEEP_AXES`), e.g. Tables 17 and 19.

    The 3D and 2D models solve all cases at once (numpy arrays through the same fast path); a case the
    engine refuses or cannot solve gets an entry in ``errors`` instead of a number, and the others are kept.
    """
    _check_options(model, stage, rear_llt_limit, 2, "reduced", chassis_closure)
    if not grid:
        raise InvalidInput("the grid needs at least one axis", field="grid")
    for axis, vals in grid.items():
        if axis not in SWEEP_AXES:
            raise InvalidInput(f"unknown sweep axis {axis!r}; use {', '.join(SWEEP_AXES)}", field=f"grid.{axis}")
        if len(vals) == 0:
            raise InvalidInput(f"grid.{axis} is empty", field=f"grid.{axis}")
    axes = tuple(grid)
    combos = list(itertools.product(*(list(map(float, grid[a])) for a in axes)))
    cases = []
    for combo in combos:
        r, ang, ld, lim = road, trailer_angle_deg, load, rear_llt_limit
        for axis, val in zip(axes, combo, strict=True):
            r, ang, ld, lim = _apply(axis, val, r, ang, ld, lim)
        cases.append((r, ang, ld, lim))
    srt, roll, errors = evaluate_cases(vehicle, cases, model=model, stage=stage, chassis_closure=chassis_closure)
    n = len(combos)
    return SweepResult(
        model, stage if model == "3d" else None, axes, np.array(combos, dtype=float).reshape(n, -1), srt, roll, errors
    )


def evaluate_cases(
    vehicle: Vehicle,
    cases: Sequence[tuple[Road, float, LoadCase, float]],
    *,
    model: str = "3d",
    stage: str = "full",
    chassis_closure: str = "chassis-constant",
) -> tuple[np.ndarray, np.ndarray, dict[int, str]]:
    """SRT [g] and roll [deg] of a list of (road, trailer angle, load, rear LLT limit) cases at once.

    Returns ``(srt, roll, errors)``: arrays with nan where ``errors`` (case index -> message) explains why.
    """
    n = len(cases)
    errors: dict[int, str] = {}
    for i, (r, ang, ld, lim) in enumerate(cases):
        try:
            _check_options(model, stage, lim, 2, "reduced", chassis_closure)
            if model not in CLASSIC_MODELS:
                _check_case(vehicle, model, r, ang, ld)
        except RolloverError as exc:
            errors[i] = str(exc)
    srt = np.full(n, np.nan)
    roll = np.full(n, np.nan)
    ok = [i for i in range(n) if i not in errors]
    if model in CLASSIC_MODELS:
        for i in ok:
            r, ang, ld, lim = cases[i]
            try:
                res = rollover_threshold(vehicle, model, road=r, trailer_angle_deg=ang, load=ld, rear_llt_limit=lim)
                srt[i] = res.srt
                roll[i] = np.nan if res.roll_angle_deg is None else res.roll_angle_deg
            except RolloverError as exc:
                errors[i] = str(exc)
    elif ok:
        validate_vehicle(vehicle, model=model)
        _batch(vehicle, model, stage, chassis_closure, [cases[i] for i in ok], ok, srt, roll, errors)
    return srt, roll, errors


def _batch(vehicle, model, stage, closure, cases, index, srt, roll, errors) -> None:
    """Solve many cases at once with numpy arrays; fall back to one by one if the batch fails."""
    arr = lambda f: np.array([f(c) for c in cases], dtype=float)  # noqa: E731
    weight = arr(lambda c: c[2].weight_kn(vehicle.weight_kn))
    bank = arr(lambda c: c[0].bank_rad)
    limit = arr(lambda c: c[3])
    d1, d3 = arr(lambda c: c[2].lateral_offset_m), arr(lambda c: c[2].vertical_offset_m)
    try:
        with np.errstate(invalid="raise", divide="raise"):
            if model == "3d":
                m = stage_model(vehicle, stage, closure)
                case = trailer3d.Case(
                    weight=weight,
                    bank=bank,
                    slope=arr(lambda c: c[0].slope_rad),
                    psi=np.radians(arr(lambda c: c[1])),
                    d1=d1,
                    d2=arr(lambda c: c[2].longitudinal_offset_m),
                    d3=d3,
                    llt_limit=limit,
                )
                sol = trailer3d.solve(m, case, xp=ARRAY)
                ay, rl = sol.ay, np.degrees(sol.geometry.roll)
            else:  # 2d: the load share depends on d2, so group by it
                ay = np.empty(len(cases))
                rl = np.empty(len(cases))
                d2 = arr(lambda c: c[2].longitudinal_offset_m)
                for val in np.unique(d2):
                    sel = d2 == val
                    m = trailer2d.build_model(vehicle, float(val))
                    case = trailer2d.Case2D(
                        weight=weight[sel] * m.load_share, bank=bank[sel], d1=d1[sel], d3=d3[sel], llt_limit=limit[sel]
                    )
                    s = trailer2d.solve(m, case, xp=ARRAY)
                    ay[sel], rl[sel] = s.ay, np.degrees(s.geometry.top_angle)
        for k, i in enumerate(index):
            if ay[k] > 0:
                srt[i], roll[i] = ay[k], rl[k]
            else:
                errors[i] = f"the rear LLT limit is reached at rest (SRT = {ay[k]:.3f} g)"
    except (RolloverError, FloatingPointError, ValueError):
        for k, i in enumerate(index):
            r, ang, ld, lim = cases[k]
            try:
                res = rollover_threshold(
                    vehicle,
                    model,
                    stage=stage,
                    road=r,
                    trailer_angle_deg=ang,
                    load=ld,
                    rear_llt_limit=lim,
                    chassis_closure=closure,
                )
                srt[i], roll[i] = res.srt, res.roll_angle_deg
            except RolloverError as exc:
                errors[i] = str(exc)
