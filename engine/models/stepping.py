"""Quasi-static load stepping to the rollover limit with the developed mechanisms (3D of Ch. 6, 2D of Ch. 5).

The lateral acceleration is raised from rest until the rear inner tire lifts off (Fz19 = 0) or the rear lateral
load transfer reaches the case's ``rear_llt_limit``. Because the model is elastic (path independent), the state
at any ay is the consistent geometry/force solution at that ay: :func:`engine.models.trailer3d.solve` finds the limit
directly (the limit condition is one more linear equation at frozen geometry), and the curves of Figs. 92-97 are
the same solution at intermediate ay, each started from the previous one.

Each model has a one-case solve (:func:`solve_3d`, :func:`solve_2d`) returning a
:class:`~engine.results.RolloverResult`, and a batch solve (:func:`batch_3d`, :func:`batch_2d`) that runs many cases
of one vehicle through the same fast path at once with numpy arrays. :mod:`engine.models` registers them.

References
----------
Thesis Secs. 1.3, 5.2, 6.2 (Eqs. 5.22, 6.17-6.18), 7.2, 9.1-9.2.
"""

from __future__ import annotations

import math
from dataclasses import fields

import numpy as np

from engine.case import Case, kingpin_uplift_note
from engine.domain import DEFAULT_CURVE_POINTS
from engine.models import trailer2d, trailer3d
from engine.models.groups import ARRAY
from engine.results import Curves, RolloverResult, TireLoads


def _davies_forces(model: str):
    """The Davies reference statics of a model (imported only when asked for: it is the slow path)."""
    if model == "2d":
        return trailer2d.davies_forces_at
    from engine.models.trailer3d_davies import davies_forces_at

    return davies_forces_at


def _clean(scale: float, *loads) -> list[float]:
    """Loads as floats, with round-off around an exact zero (the lifted tire, ~1e-13 kN) set to 0."""
    return [0.0 if abs(x) <= 1e-9 * abs(scale) else float(x) for x in loads]


def _llt(outer, inner):
    """Lateral load transfer (Fz outer - Fz inner) / (Fz outer + Fz inner) of one group (Eq. 2.5) [-]."""
    return (outer - inner) / (outer + inner)


def _limit_name(rear_llt_limit: float) -> str:
    return "rear-inner-lift-off" if rear_llt_limit == 1.0 else "rear-llt-limit"


def _ramp(solve_at, limit_sol, points: int) -> tuple[np.ndarray, list]:
    """The solutions at ``points`` values of ay from rest to the limit, each started from the previous one."""
    ays = np.linspace(0.0, limit_sol.ay, points)
    rows, state = [], None
    for a in ays[:-1]:
        s = solve_at(float(a), state)
        state = s.state
        rows.append(s)
    rows.append(limit_sol)
    return ays, rows


# ------------------------------------------------------------------------------------------ 3D


def stage_model(
    case: Case, stage: str | None = None, chassis_closure: str = "chassis-constant", method: str = "reduced"
) -> trailer3d.TrailerModel:
    """The 3D model of one stage of the case's vehicle (the case's own stage by default), calibrated."""
    forces = _davies_forces("3d") if method == "davies" else None
    return trailer3d.build_model(case.vehicle, stage or case.stage, chassis_closure, forces)


def solver_case_3d(case: Case) -> trailer3d.SolverCase:
    """The case in the solver's numbers (angles in rad, the weight with overweight)."""
    return trailer3d.SolverCase(
        weight=case.weight_kn,
        bank=case.road.bank_rad,
        slope=case.road.slope_rad,
        psi=math.radians(case.trailer_angle_deg),
        d1=case.load.lateral_offset_m,
        d2=case.load.longitudinal_offset_m,
        d3=case.load.vertical_offset_m,
        llt_limit=case.rear_llt_limit,
    )


def _curves_3d(m, case, limit_sol, points, forces) -> Curves:
    ays, rows = _ramp(lambda a, st: trailer3d.solve(m, case, a, start=st, forces=forces), limit_sol, points)
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


def _result_3d(case: Case, sol, stage_values, curves, m) -> RolloverResult:
    fo, fi, ro, ri = sol.front.fz_outer, sol.front.fz_inner, sol.rear.fz_outer, sol.rear.fz_inner
    note = kingpin_uplift_note(case.kingpin_to_cg_m, case.vehicle.wheelbase_m)
    return RolloverResult(
        model="3d",
        stage=case.stage,
        srt=float(sol.ay),
        roll_angle_deg=math.degrees(float(sol.geometry.roll)),
        limit=_limit_name(case.rear_llt_limit),
        rear_llt_limit=case.rear_llt_limit,
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
        notes=[note] if note else [],
    )


def solve_3d(
    case: Case,
    *,
    include_curves: bool = False,
    curve_points: int = DEFAULT_CURVE_POINTS,
    method: str = "reduced",
    chassis_closure: str = "chassis-constant",
) -> RolloverResult:
    """SRT of the 3D model (Ch. 6): both stages of Ch. 9 for ``stage="full"`` (SRT_ts and SRT_3D), the first
    only for ``"tires-suspension"``; the state at the limit of the case's stage, and its curves on request."""
    forces = _davies_forces("3d") if method == "davies" else None
    sc = solver_case_3d(case)
    stages = ("tires-suspension", "full") if case.stage == "full" else ("tires-suspension",)
    sols = {}
    for st in stages:
        m = stage_model(case, st, chassis_closure, method)
        sols[st] = (m, trailer3d.solve(m, sc, forces=forces))
    m, sol = sols[case.stage]
    stage_values = {"srt_ts": float(sols["tires-suspension"][1].ay)}
    if "full" in sols:
        stage_values["srt_3d"] = float(sols["full"][1].ay)
    curves = _curves_3d(m, sc, sol, curve_points, forces) if include_curves and sol.ay > 0 else None
    return _result_3d(case, sol, stage_values, curves, m)


class _Row:
    """Case ``i`` of a batch solution (nested named tuples of arrays and constants) read as a one-case solution:
    each array element read is returned as a Python number, the constants as they are; only what is read is taken."""

    __slots__ = ("_i", "_value")

    def __init__(self, value, i: int) -> None:
        self._value, self._i = value, i

    def __getattr__(self, name: str):
        return _take(getattr(self._value, name), self._i)

    def __getitem__(self, k: int):
        return _take(self._value[k], self._i)


def _take(value, i: int):
    if isinstance(value, np.ndarray):
        return value.item(i) if value.ndim else value.item()
    return _Row(value, i) if isinstance(value, tuple) else value


def solve_3d_many(cases: list[Case], chassis_closure: str = "chassis-constant") -> list[RolloverResult | None]:
    """:func:`solve_3d` of many cases of one vehicle and one stage (no curves, the reduced statics), solved together
    on arrays: each result is the one :func:`solve_3d` gives (a converged case stops where it would alone, with its
    own iteration count), or None for a case whose mechanism left its valid geometry (solve it alone for its error).
    The cases must have passed the model's checks."""
    first = cases[0]
    one = [solver_case_3d(c) for c in cases]
    sc = trailer3d.SolverCase(
        **{f.name: np.array([getattr(c, f.name) for c in one]) for f in fields(trailer3d.SolverCase)}
    )
    stages = ("tires-suspension", "full") if first.stage == "full" else ("tires-suspension",)
    sols = {st: (m := stage_model(first, st, chassis_closure), trailer3d.solve(m, sc, xp=ARRAY)) for st in stages}
    m, sol = sols[first.stage]
    ts_srt = sols["tires-suspension"][1].ay
    out: list[RolloverResult | None] = []
    for i, case in enumerate(cases):
        if not all(math.isfinite(s.ay[i]) for _, s in sols.values()):
            out.append(None)
            continue
        stage_values = {"srt_ts": float(ts_srt[i])}
        if "full" in sols:
            stage_values["srt_3d"] = float(sols["full"][1].ay[i])
        out.append(_result_3d(case, _Row(sol, i), stage_values, None, m))
    return out


def _weight(case: Case, overweight_percent: np.ndarray) -> np.ndarray:
    return case.vehicle.weight_kn * (1.0 + overweight_percent / 100.0)


def batch_3d(base: Case, col: dict[str, np.ndarray], chassis_closure: str = "chassis-constant"):
    """(SRT [g], roll [deg]) arrays of many cases of one vehicle and stage, solved at once with numpy arrays:
    ``col`` holds every case input as an array (:func:`engine.models.evaluate_arrays`). A case whose mechanism
    leaves its valid geometry gets nan, the others their value."""
    m = stage_model(base, None, chassis_closure)
    sc = trailer3d.SolverCase(
        weight=_weight(base, col["overweight_percent"]),
        bank=np.arctan(col["bank_percent"] / 100.0),
        slope=np.arctan(col["slope_percent"] / 100.0),
        psi=np.radians(col["trailer_angle_deg"]),
        d1=col["lateral_offset_m"],
        d2=col["longitudinal_offset_m"],
        d3=col["vertical_offset_m"],
        llt_limit=col["rear_llt_limit"],
    )
    sol = trailer3d.solve(m, sc, xp=ARRAY)
    return sol.ay, np.degrees(sol.geometry.roll)


# ------------------------------------------------------------------------------------------ 2D


def _case_2d(case: Case, m: trailer2d.PlanarModel) -> trailer2d.Case2D:
    return trailer2d.Case2D(
        weight=case.weight_kn * m.load_share,
        bank=case.road.bank_rad,
        d1=case.load.lateral_offset_m,
        d3=case.load.vertical_offset_m,
        llt_limit=case.rear_llt_limit,
    )


def _curves_2d(m, case, limit_sol, points, forces) -> Curves:
    ays, rows = _ramp(lambda a, st: trailer2d.solve(m, case, a, start=st, forces=forces), limit_sol, points)
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


def solve_2d(
    case: Case,
    *,
    include_curves: bool = False,
    curve_points: int = DEFAULT_CURVE_POINTS,
    method: str = "reduced",
    chassis_closure: str = "chassis-constant",
) -> RolloverResult:
    """SRT of the 2D model (Ch. 5): the rear group carrying its static share of the weight (Eq. 5.22)."""
    del chassis_closure  # one group: no roll-moment split to close
    forces = _davies_forces("2d") if method == "davies" else None
    m = trailer2d.build_model(case.vehicle, case.load.longitudinal_offset_m)
    c2 = _case_2d(case, m)
    sol = trailer2d.solve(m, c2, forces=forces)
    curves = _curves_2d(m, c2, sol, curve_points, forces) if include_curves and sol.ay > 0 else None
    f = sol.forces
    return RolloverResult(
        model="2d",
        stage=None,
        srt=float(sol.ay),
        roll_angle_deg=math.degrees(float(sol.geometry.top_angle)),
        limit=_limit_name(case.rear_llt_limit),
        rear_llt_limit=case.rear_llt_limit,
        llt_rear=float(_llt(f.fz_outer, f.fz_inner)),
        tire_loads=TireLoads(None, None, *_clean(float(c2.weight), f.fz_outer, f.fz_inner)),
        cg_lateral_m=float(sol.cg[0]),
        cg_height_m=float(sol.cg[1]),
        iterations=sol.iterations,
        parameters={
            "group_load_kn": float(c2.weight),
            "srt_eq_5_22": float(trailer2d.srt_eq_5_22(sol.cg[0], sol.cg[1], math.tan(case.road.bank_rad))),
        },
        curves=curves,
    )


def batch_2d(base: Case, col: dict[str, np.ndarray], chassis_closure: str = "chassis-constant"):
    """(SRT [g], roll [deg]) arrays of many 2D cases at once; the load share depends on d2, so grouped by it."""
    del chassis_closure  # one group: no roll-moment split to close
    weight = _weight(base, col["overweight_percent"])
    d2 = col["longitudinal_offset_m"]
    ay, roll = np.empty(len(d2)), np.empty(len(d2))
    for val in np.unique(d2):
        sel = d2 == val
        m = trailer2d.build_model(base.vehicle, float(val))
        c2 = trailer2d.Case2D(
            weight=weight[sel] * m.load_share,
            bank=np.arctan(col["bank_percent"][sel] / 100.0),
            d1=col["lateral_offset_m"][sel],
            d3=col["vertical_offset_m"][sel],
            llt_limit=col["rear_llt_limit"][sel],
        )
        s = trailer2d.solve(m, c2, xp=ARRAY)
        ay[sel], roll[sel] = s.ay, np.degrees(s.geometry.top_angle)
    return ay, roll
