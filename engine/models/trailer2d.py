"""The two-dimensional trailer model of Ch. 5 (Fig. 41, Tables 3-6, Eqs. 5.1-5.2, 5.14-5.22).

One equivalent axle group in the y-z plane: tire system (joints 1-5), leaf-spring suspension (6-11) and the
body carrying the CG at (h1, h2) (Eqs. 5.1-5.2). Ten links, eleven joints, two external actions Py and Pz
(Eqs. 4.25-4.26); 9 cuts x 3 = 27 equations for 27 secondary variables (Eq. 5.11), so the statics are
determinate and no closure is needed.

Which load the group carries: a record without wheelbase (Table 14) puts its whole weight on the group;
for a 3D record the 2D model is its rear group with the rear share W (a - d2)/L of the weight, exactly as
Ch. 7's Table 14 vehicle is the B-train's tridem with 250 kN of its 355 kN.

The limit is the inner tire lifting (Fz3 = 0, Eq. 5.22) or the LLT reaching ``llt_limit``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from engine.errors import ConvergenceError
from engine.mechanics.davies import PLANAR_YZ, solve_statics
from engine.mechanics.mechanism import Mechanism, external, joint
from engine.mechanics.screw import rot_x, screw_matrix, unit_force
from engine.models.groups import (
    FIXED_POINT_TOL,
    SCALAR,
    GroupGeometry,
    GroupParams,
    fixed_point,
    fixed_point_batch,
    group_geometry,
    group_next_state,
    group_params,
    group_statics,
)
from engine.vehicle.record import Vehicle, static_axle_loads


@dataclass(frozen=True)
class PlanarModel:
    group: GroupParams
    cg_above_chassis: float  # l12 [m]
    load_share: float  # fraction of the weight carried by the group (a - d2)/L, or 1


def build_model(vehicle: Vehicle, longitudinal_offset_m: float = 0.0) -> PlanarModel:
    """The Ch. 5 mechanism for the rear group of ``vehicle`` (per-side stiffness sums of vehicles.py)."""
    v = vehicle
    _, nominal_rear = static_axle_loads(v)
    _, rear = static_axle_loads(v, longitudinal_offset_m, weight_kn=1.0)
    group = group_params(v, "rear", nominal_rear)
    return PlanarModel(group, v.cg_height_above_chassis_m, rear)


@dataclass(frozen=True)
class Case2D:
    weight: object  # weight carried by the group (with overweight) [kN]
    bank: object  # [rad]
    d1: object  # + toward the outer tire [m]
    d3: object  # + up [m]
    llt_limit: object


class Solution2D(NamedTuple):
    ay: object
    state: tuple
    geometry: GroupGeometry
    cg: tuple  # (h1, h2) [m], Eqs. 5.1-5.2
    py: object
    pz: object
    forces: object  # GroupForces
    iterations: object  # int; for a batch, each case's own count (an int array)


def cg_position(m: PlanarModel, case: Case2D, g: GroupGeometry, xp=SCALAR):
    """(h1, h2): the CG on the body, Eqs. 5.1-5.2 with the offsets d1, d3 (Table 3: CG at (t1/2, l12))."""
    c, s = xp.cos(g.top_angle), xp.sin(g.top_angle)
    l12 = m.cg_above_chassis + case.d3
    return g.top[0] - case.d1 * c - l12 * s, g.top[1] - case.d1 * s + l12 * c


def _loads(case: Case2D, ay, xp):
    cb, sb = xp.cos(case.bank), xp.sin(case.bank)
    w = case.weight
    return -w * sb + w * ay * cb, w * cb + w * ay * sb  # Eqs. 4.25-4.26 (no slope in 2D)


def _top_load(g: GroupGeometry, cg, py, pz):
    """The CG action (0, -Py, -Pz) moved to the body's top point: force and moment about x."""
    fy, fz = -py, -pz
    return fy, fz, (cg[0] - g.top[0]) * fz - (cg[1] - g.top[1]) * fy


def forces_at(m: PlanarModel, case: Case2D, state, ay=None, xp=SCALAR):
    """Geometry and forces at a frozen state; ``ay=None`` solves the limit (LLT = llt_limit) exactly."""
    from engine.models.groups import ground_reactions

    g = group_geometry(m.group, state, xp)
    cg = cg_position(m, case, g, xp)
    if ay is None:  # the LLT condition is affine in ay at frozen geometry

        def resid(a):
            py, pz = _loads(case, a, xp)
            fo, fi, _ = ground_reactions(g, *_top_load(g, cg, py, pz))
            return (fo - fi) - case.llt_limit * (fo + fi)

        r0, r1 = resid(0.0), resid(1.0)
        ay = -r0 / (r1 - r0)
    py, pz = _loads(case, ay, xp)
    f = group_statics(m.group, g, *_top_load(g, cg, py, pz), xp=xp)
    return ay, g, cg, py, pz, f


def solve(
    m: PlanarModel,
    case: Case2D,
    ay=None,
    *,
    start=None,
    xp=SCALAR,
    tol: float = FIXED_POINT_TOL,
    max_iter: int = 200,
    forces=None,
) -> Solution2D:
    """Consistent geometry and forces at the limit (``ay=None``) or at a given ay (fixed point + Anderson(1))."""
    forces = forces or forces_at
    state = start or tuple(v + 0.0 * case.weight for v in m.group.rest_state())

    def step(x, it):
        try:
            out = forces(m, case, x, ay, xp)
        except (ValueError, ZeroDivisionError, FloatingPointError) as exc:
            raise ConvergenceError(
                f"the mechanism left its valid geometry at iteration {it} ({exc})", iterations=it
            ) from None
        return out, group_next_state(m.group, out[5])

    if xp is SCALAR:
        x, it, (ay_k, g, cg, py, pz, f) = fixed_point(step, state, vector=False, tol=tol, max_iter=max_iter)
        return Solution2D(ay_k, tuple(x), g, cg, py, pz, f, it)
    # a batch: a case that leaves the valid geometry (or does not converge) gets ay = nan
    x, _, (ay_k, g, cg, py, pz, f), failed, steps = fixed_point_batch(step, state, tol=tol, max_iter=max_iter)
    return Solution2D(np.where(failed, np.nan, ay_k), tuple(x), g, cg, py, pz, f, steps)


def srt_eq_5_22(h1, h2, e):
    """SRT = (h1 + h2 e) / (h2 - h1 e) (Eq. 5.22), the CG position at the limit and e = tan(bank)."""
    return (h1 + h2 * e) / (h2 - h1 * e)


# --------------------------------------------------------------------- Davies reference path


def build_mechanism(m: PlanarModel, case: Case2D, state) -> tuple[Mechanism, tuple]:
    """The 10-link planar mechanism of Fig. 41 (Tables 3, 4, 6) at ``state``, by successive screws."""
    p = m.group
    g = group_geometry(p, state)
    l1, l2, l3, l4, th6 = state[:5]
    t1, b = p.axle_width, p.spring_separation
    th1 = g.theta_tire
    ya, yb = 0.5 * (t1 - b), 0.5 * (t1 + b)

    def rx(y, theta):
        return screw_matrix((1, 0, 0), (0, y, 0), theta, 0.0)

    def tz(y, d):
        return screw_matrix((0, 0, 1), (0, y, 0), 0.0, d)

    def pt(a, y):
        return (a @ np.array([0.0, y, 0.0, 1.0]))[:3]

    links = [
        "A road",
        "B outer tire",
        "C slider",
        "D inner tire",
        "E axle",
        "F leg a lower",
        "G leg a upper",
        "H leg b lower",
        "I leg b upper",
        "J body",
    ]
    mech = Mechanism(links)
    eye = np.eye(3)
    a12 = rx(0.0, th1) @ tz(0.0, l1)  # A1 A2
    joint(mech, "1", 0, 1, (0, 0, 0), eye, "planar-revolute")
    joint(mech, "2", 1, 4, pt(a12, 0.0), rot_x(th1), "planar-prismatic", actuator="FT2")
    joint(mech, "3", 0, 2, (0, g.track, 0), eye, "planar-slider")
    joint(mech, "4", 2, 3, (0, g.track, 0), eye, "planar-revolute")
    a345 = screw_matrix((0, 1, 0), (0, 0, 0), 0.0, g.track) @ rx(0.0, th1) @ tz(0.0, l2)
    joint(mech, "5", 3, 4, pt(a345, 0.0), rot_x(th1), "planar-prismatic", actuator="FT5")
    joint(mech, "6", 4, 5, pt(a12, ya), eye, "planar-revolute", actuator="Tx6")
    a67 = a12 @ rx(ya, th6) @ tz(ya, l3)
    joint(mech, "7", 5, 6, pt(a67, ya), rot_x(th1 + th6), "planar-prismatic", actuator="FLS7")
    joint(mech, "8", 6, 9, pt(a67, ya), eye, "planar-revolute")
    joint(mech, "9", 4, 7, pt(a12, yb), eye, "planar-revolute")
    a910 = a12 @ rx(yb, g.suspension.base_b) @ tz(yb, l4)
    joint(mech, "10", 7, 8, pt(a910, yb), rot_x(th1 + g.suspension.base_b), "planar-prismatic", actuator="FLS10")
    joint(mech, "11", 8, 9, pt(a910, yb), eye, "planar-revolute")
    body = a67 @ rx(ya, g.suspension.top_a)  # A1 A2 A6 A7 A8 (Table 4)
    cg = (body @ np.array([0.0, 0.5 * t1 - float(case.d1), m.cg_above_chassis + float(case.d3), 1.0]))[:3]
    external(mech, "Py", 9, unit_force((0, -1, 0), cg))  # Table 6
    external(mech, "Pz", 9, unit_force((0, 0, -1), cg))
    return mech, (cg[1], cg[2])


REPORTED = ("Fz1", "Fz3", "Fy1", "FT2", "FT5", "FLS7", "FLS10", "Tx6")


def davies_forces_at(m: PlanarModel, case: Case2D, state, ay=None, xp=SCALAR):
    """Drop-in replacement of :func:`forces_at` solving the planar Davies statics (Eq. 5.14)."""
    from engine.models.groups import FourBarForces, GroupForces

    mech, cg = build_mechanism(m, case, state)
    g = group_geometry(m.group, state)

    def at(a):
        py, pz = _loads(case, a, SCALAR)
        return py, pz, solve_statics(mech, {"Py": py, "Pz": pz}, space=PLANAR_YZ, require=REPORTED)

    if ay is None:  # Fz1 - Fz3 - lam (Fz1 + Fz3) is affine in ay
        lam = float(case.llt_limit)
        r = [(s["Fz1"] - s["Fz3"]) - lam * (s["Fz1"] + s["Fz3"]) for s in (at(0.0)[2], at(1.0)[2])]
        ay = -r[0] / (r[1] - r[0])
    py, pz, s = at(ay)
    f = GroupForces(
        s["Fz1"], s["Fz3"], s["Fy1"], s["FT2"], s["FT5"], FourBarForces(s["FLS7"], s["FLS10"], s["Tx6"]), None
    )
    return ay, g, cg, py, pz, f
