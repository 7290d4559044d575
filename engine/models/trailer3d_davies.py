"""The Davies reference path of the 3D model (Ch. 6): the full 23-link mechanism and Eq. 6.39.

:func:`davies_forces_at` is a drop-in replacement of :func:`~engine.models.trailer3d.forces_at` that builds the
mechanism of Fig. 43 by successive screws (Table 9), writes the cut-set statics of Eqs. 6.10-6.14 with the closure rows
of Eq. 6.19, and solves them with :func:`engine.mechanics.solve_statics`, which refuses any reported quantity that the
equations leave undetermined. ``tests/engine/test_fastpath.py`` checks the fast path against it to 1e-9.
:func:`eq_6_37_coefficients` and :func:`srt_eq_6_39` give the thesis's closed form of the SRT from the Davies
solution.

References
----------
Thesis Secs. 6.1-6.2 (Tables 8-11, Eqs. 6.10-6.19, 6.37-6.39); Davies (1981); Appendix A.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from engine.errors import InvalidInput
from engine.mechanics.davies import Closure, solve_statics
from engine.mechanics.mechanism import Mechanism, custom_joint, external, joint
from engine.mechanics.screw import rot_x, screw_matrix, unit_couple, unit_force
from engine.models.groups import SCALAR, FourBarForces, GroupGeometry, GroupParams
from engine.models.trailer3d import (
    ChassisLoads,
    Geometry,
    SolverCase,
    State,
    TrailerModel,
    cg_actions,
    geometry,
)

FRONT_LINKS = (
    "front outer tire",
    "front inner tire",
    "front axle",
    "front leg a lower",
    "front leg a upper",
    "front bolster",
    "front leg b lower",
    "front leg b upper",
)
FW_LINKS = ("fw leg a lower", "fw leg a upper", "fw plate", "fw leg b lower", "fw leg b upper")
REAR_LINKS = (
    "rear outer tire",
    "rear inner tire",
    "rear axle",
    "rear leg a lower",
    "rear leg a upper",
    "rear bolster",
    "rear leg b lower",
    "rear leg b upper",
)

#: the quantities the model reports; the Davies path requires each of them to be determined
REPORTED = (
    "Fz1",
    "Fz3",
    "Fz17",
    "Fz19",
    "Fy1",
    "Fy17",
    "FT2",
    "FT4",
    "FT18",
    "FT20",
    "FLS6",
    "FLS9",
    "FLS22",
    "FLS25",
    "Tx5",
    "Tx21",
    "Tx27",
    "T28",
)
REPORTED_FW = ("FFW12", "FFW15", "Tx11")


class _Chain:
    """Successive screw displacements about x-parallel axes (and one about z) for one group (Table 9)."""

    def __init__(self, base: np.ndarray):
        self.base = base

    @staticmethod
    def rx(y: float, theta: float, x: float) -> np.ndarray:
        return screw_matrix((1.0, 0.0, 0.0), (x, y, 0.0), theta, 0.0)

    @staticmethod
    def tz(y: float, d: float, x: float) -> np.ndarray:
        return screw_matrix((0.0, 0.0, 1.0), (x, y, 0.0), 0.0, d)


def _point(a: np.ndarray, ref) -> np.ndarray:
    return (a @ np.array([*ref, 1.0]))[:3]


def _group_joints(
    mech: Mechanism, names: dict, p: GroupParams, g: GroupGeometry, state, x0: float, yaw: np.ndarray, numbers: dict
) -> tuple[np.ndarray, np.ndarray, float]:
    """Add one group's joints by successive screws; return (chain matrix to the top link, its rotation, top y).

    ``numbers`` maps role -> thesis joint number (e.g. {"outer": 17, ...}); ``yaw`` is A29 (identity at rear).
    """
    t = p.axle_width
    b = p.spring_separation
    susp = g.suspension
    l_out, l_in, l_a, l_b, th_a = state[:5]
    th_t = g.theta_tire
    ya, yb = 0.5 * (t - b), 0.5 * (t + b)
    rot_yaw = yaw[:3, :3]
    ex = rot_yaw @ np.array([1.0, 0.0, 0.0])
    ground_frame = rot_yaw
    n = numbers

    def rolled(angle: float) -> np.ndarray:
        return rot_yaw @ rot_x(angle)

    # tire system (Fig. 26): outer revolute, tire springs, inner spherical slider (Table 11)
    a_out = yaw @ _Chain.rx(0.0, th_t, x0)
    a_out_top = a_out @ _Chain.tz(0.0, l_out, x0)
    joint(mech, str(n["outer"]), "road", names["outer tire"], _point(yaw, (x0, 0.0, 0.0)), ground_frame, "revolute")
    joint(
        mech,
        str(n["outer_spring"]),
        names["outer tire"],
        names["axle"],
        _point(a_out_top, (x0, 0.0, 0.0)),
        rolled(th_t),
        "prismatic",
        actuator=f"FT{n['outer_spring']}",
    )
    a_in = yaw @ screw_matrix((0.0, 1.0, 0.0), (x0, 0.0, 0.0), 0.0, g.track) @ _Chain.rx(0.0, th_t, x0)
    joint(
        mech,
        str(n["inner"]),
        "road",
        names["inner tire"],
        _point(yaw, (x0, g.track, 0.0)),
        ground_frame,
        "spherical-slider",
    )
    joint(
        mech,
        str(n["inner_spring"]),
        names["inner tire"],
        names["axle"],
        _point(a_in @ _Chain.tz(0.0, l_in, x0), (x0, 0.0, 0.0)),
        rolled(th_t),
        "prismatic",
        actuator=f"FT{n['inner_spring']}",
    )

    def leg(lower, y, x, theta, length, link_from, link_lower, link_upper, link_to, nums, angle, spring, torsion=None):
        """Base revolute (with torsion spring), spring prismatic, top revolute of one leg (Figs. 31, 37)."""
        base, spr, top = nums
        top_chain = lower @ _Chain.rx(y, theta, x) @ _Chain.tz(y, length, x)
        p_top = _point(top_chain, (x, y, 0.0))
        joint(mech, base, link_from, link_lower, _point(lower, (x, y, 0.0)), ground_frame, "revolute", actuator=torsion)
        joint(mech, spr, link_lower, link_upper, p_top, rolled(angle + theta), "prismatic", actuator=spring)
        joint(mech, top, link_upper, link_to, p_top, ground_frame, "revolute")
        return top_chain

    # suspension four-bar (Fig. 31): legs a (torsion at the base) and b, on the axle
    a_a_top = leg(
        a_out_top,
        ya,
        x0,
        th_a,
        l_a,
        names["axle"],
        names["leg a lower"],
        names["leg a upper"],
        names["bolster"],
        (str(n["base_a"]), str(n["spring_a"]), str(n["top_a"])),
        th_t,
        f"FLS{n['spring_a']}",
        f"Tx{n['base_a']}",
    )
    leg(
        a_out_top,
        yb,
        x0,
        susp.base_b,
        l_b,
        names["axle"],
        names["leg b lower"],
        names["leg b upper"],
        names["bolster"],
        (str(n["base_b"]), str(n["spring_b"]), str(n["top_b"])),
        th_t,
        f"FLS{n['spring_b']}",
    )
    chain = a_a_top @ _Chain.rx(ya, susp.top_a, x0)  # to the bolster (A17 A18 A21 A22 A23)
    angle = th_t + th_a + susp.top_a
    if p.fifth_wheel is not None:  # fifth wheel (Fig. 37) at x = 0 on the bolster
        fw = g.fifth_wheel
        lf_a, lf_b, thf_a = state[5:8]
        fa, fb = 0.5 * (t - p.fifth_wheel.width), 0.5 * (t + p.fifth_wheel.width)
        f_a_top = leg(
            chain,
            fa,
            0.0,
            thf_a,
            lf_a,
            names["bolster"],
            "fw leg a lower",
            "fw leg a upper",
            "fw plate",
            ("11", "12", "13"),
            angle,
            "FFW12",
            "Tx11",
        )
        leg(
            chain,
            fb,
            0.0,
            fw.base_b,
            lf_b,
            names["bolster"],
            "fw leg b lower",
            "fw leg b upper",
            "fw plate",
            ("14", "15", "16"),
            angle,
            "FFW15",
        )
        chain = f_a_top @ _Chain.rx(fa, fw.top_a, 0.0)  # A11 A12 A13
    return chain, ex, t


def build_mechanism(m: TrailerModel, case: SolverCase, state: State) -> tuple[Mechanism, Geometry]:
    """The 23-link mechanism of Fig. 43 at the given state, positions by successive screws (Table 9)."""
    geo = geometry(m, case, state.rear, state.front, state.theta27)
    has_fw = m.front.fifth_wheel is not None
    links = ["road", *FRONT_LINKS, *(FW_LINKS if has_fw else ()), *REAR_LINKS, "chassis"]
    mech = Mechanism(links)
    front_names = {
        "outer tire": "front outer tire",
        "inner tire": "front inner tire",
        "axle": "front axle",
        "leg a lower": "front leg a lower",
        "leg a upper": "front leg a upper",
        "leg b lower": "front leg b lower",
        "leg b upper": "front leg b upper",
        "bolster": "front bolster",
    }
    rear_names = {k: v.replace("front", "rear") for k, v in front_names.items()}
    a29 = screw_matrix((0.0, 0.0, 1.0), (0.0, m.yaw_pivot_y, 0.0), float(case.psi), 0.0)  # point 29
    chain_f, ex_f, t2 = _group_joints(
        mech,
        front_names,
        m.front,
        geo.front,
        state.front,
        -m.kingpin_to_front_axle,
        a29,
        {
            "outer": 1,
            "outer_spring": 2,
            "inner": 3,
            "inner_spring": 4,
            "base_a": 5,
            "spring_a": 6,
            "top_a": 7,
            "base_b": 8,
            "spring_b": 9,
            "top_b": 10,
        },
    )
    chain_r, _, t4 = _group_joints(
        mech,
        rear_names,
        m.rear,
        geo.rear,
        state.rear,
        -m.wheelbase,
        np.eye(4),
        {
            "outer": 17,
            "outer_spring": 18,
            "inner": 19,
            "inner_spring": 20,
            "base_a": 21,
            "spring_a": 22,
            "top_a": 23,
            "base_b": 24,
            "spring_b": 25,
            "top_b": 26,
        },
    )
    # joint 27: rear bolster -> chassis; Fx Fy Fz, chassis torsion Tx, pitch My (see the module docstring)
    p27 = _point(chain_r, (-m.wheelbase, 0.5 * t4, 0.0))
    custom_joint(
        mech,
        "27",
        "rear bolster",
        "chassis",
        [
            ("Fx27", unit_force((1, 0, 0), p27)),
            ("Fy27", unit_force((0, 1, 0), p27)),
            ("Fz27", unit_force((0, 0, 1), p27)),
            ("Tx27", unit_couple((1, 0, 0))),
            ("My27", unit_couple((0, 1, 0))),
        ],
    )
    # joint 28: fifth-wheel plate (or front bolster) -> chassis; forces and the roll moment about x'
    p28 = _point(chain_f, (0.0, 0.5 * t2, 0.0))
    top = "fw plate" if has_fw else "front bolster"
    custom_joint(
        mech,
        "28",
        top,
        "chassis",
        [
            ("Fx28", unit_force((1, 0, 0), p28)),
            ("Fy28", unit_force((0, 1, 0), p28)),
            ("Fz28", unit_force((0, 0, 1), p28)),
            ("T28", unit_couple(ex_f)),
        ],
    )
    # the CG: A17 A18 A21 A22 A23 A27 A_CG (Table 9)
    a27 = chain_r @ screw_matrix((1.0, 0.0, 0.0), (-m.wheelbase, 0.5 * t4, 0.0), float(state.theta27), 0.0)
    cg = _point(
        a27, (-m.kingpin_to_cg + float(case.d2), 0.5 * t4 - float(case.d1), m.cg_above_chassis + float(case.d3))
    )
    external(mech, "Px", "chassis", unit_force((1, 0, 0), cg))  # Table 11
    external(mech, "Py", "chassis", unit_force((0, -1, 0), cg))
    external(mech, "Pz", "chassis", unit_force((0, 0, -1), cg))
    return mech, geo._replace(p27=tuple(p27), p28=tuple(p28), cg=tuple(cg))


def davies_closures(m: TrailerModel, case: SolverCase, geo: Geometry, ay=None) -> tuple[list[Closure], dict, list]:
    """Closure rows of Eq. 6.19 (see the module docstring); at the limit the loads become unknowns tied to ay."""
    w, lam, rho = float(case.weight), float(case.llt_limit), m.llt_ratio
    a_eff = m.kingpin_to_cg - float(case.d2)
    h2 = geo.cg[2]
    cls = [
        Closure({"Fz17": 1.0, "Fz19": 1.0, "Pz": -a_eff / m.wheelbase, "Px": h2 / m.wheelbase}, label="Eq. 4.27"),
        Closure({"Fx17": 1.0}, label="free-rolling rear tire 17"),
        Closure({"Fx19": 1.0}, label="free-rolling rear tire 19"),
    ]
    if m.closure == "torque-split":
        cls.append(Closure({"T28": 1.0, "Tx27": -(m.wheelbase - a_eff) / (a_eff * m.torque_split_x)}, label="Eq. 4.21"))
    bank, slope = float(case.bank), float(case.slope)
    if ay is None:
        cls.append(Closure({"Fz17": 1.0 - lam, "Fz19": -(1.0 + lam)}, label="rear LLT limit"))
        if m.closure != "torque-split":
            cls.append(Closure({"Fz1": 1.0 - rho * lam, "Fz3": -(1.0 + rho * lam)}, label="LLTf = rho LLTr"))
        cls += [
            Closure({"Px": 1.0}, constant=w * math.sin(slope), label="Eq. 4.24"),
            Closure(
                {"Py": 1.0, "ay": -w * math.cos(bank)}, constant=w * math.sin(bank) * math.cos(slope), label="Eq. 4.25"
            ),
            Closure(
                {"Pz": 1.0, "ay": -w * math.sin(bank)}, constant=-w * math.cos(bank) * math.cos(slope), label="Eq. 4.26"
            ),
        ]
        return cls, {}, ["ay"]
    px, py, pz = cg_actions(case, ay)
    if m.closure != "torque-split":
        fr = (pz * a_eff - px * h2) / m.wheelbase
        ff = pz - fr
        cls.append(Closure({"Fz1": fr, "Fz3": -fr, "Fz17": -rho * ff, "Fz19": rho * ff}, label="LLTf = rho LLTr"))
    return cls, {"Px": px, "Py": py, "Pz": pz}, []


class DaviesForces(NamedTuple):
    fz_outer: float
    fz_inner: float
    fy_outer: float
    tire_outer: float
    tire_inner: float
    suspension: object
    fifth_wheel: object


def davies_forces_at(m: TrailerModel, case: SolverCase, state: State, ay=None, xp=SCALAR):
    """Drop-in replacement of :func:`forces_at` that solves the full Davies statics (reference path)."""
    mech, geo = build_mechanism(m, case, state)
    closures, primary, extra = davies_closures(m, case, geo, ay)
    has_fw = m.front.fifth_wheel is not None
    sol = solve_statics(
        mech, primary, closures, extra_unknowns=extra, require=REPORTED + (REPORTED_FW if has_fw else ())
    )
    v = sol.values
    ay_sol = v["ay"] if ay is None else ay
    loads = ChassisLoads(
        v["Px"],
        v["Py"],
        v["Pz"],
        v["Fz17"] + v["Fz19"],
        (v["Fx27"], v["Fy27"], v["Fz27"]),
        v["Tx27"],
        v["My27"],
        (v["Fx28"], v["Fy28"], v["Fz28"]),
        v["T28"],
        (),
        (),
    )
    rear = DaviesForces(
        v["Fz17"], v["Fz19"], v["Fy17"], v["FT18"], v["FT20"], FourBarForces(v["FLS22"], v["FLS25"], v["Tx21"]), None
    )
    front = DaviesForces(
        v["Fz1"],
        v["Fz3"],
        v["Fy1"],
        v["FT2"],
        v["FT4"],
        FourBarForces(v["FLS6"], v["FLS9"], v["Tx5"]),
        FourBarForces(v["FFW12"], v["FFW15"], v["Tx11"]) if has_fw else None,
    )
    return ay_sol, geo, loads, rear, front


def eq_6_37_coefficients(m: TrailerModel, case: SolverCase, state: State) -> tuple[float, float, float]:
    """C52, C53, C54 of Fz19 = -C52 Px - C53 Py - C54 Pz (Eq. 6.37) at a frozen state.

    With linear homogeneous closures (Eq. 4.27, free-rolling rear tires, the torque split of Eq. 4.21) the
    Davies solution is linear in the primaries, so three solves with unit primaries give the coefficients
    (the thesis reads them off the Gauss-Jordan form of Eq. 6.19).
    """
    if m.closure != "torque-split":
        raise InvalidInput(
            "Eq. 6.37 needs the linear torque-split closure (Eq. 4.21): build the model with chassis_closure "
            "'chassis-constant' or 'inverse-ratio'",
            field="chassis_closure",
            value=m.closure,
        )
    mech, geo = build_mechanism(m, case, state)
    closures, _, _ = davies_closures(m, case, geo, ay=0.0)
    out = []
    for unit in (
        {"Px": 1.0, "Py": 0.0, "Pz": 0.0},
        {"Px": 0.0, "Py": 1.0, "Pz": 0.0},
        {"Px": 0.0, "Py": 0.0, "Pz": 1.0},
    ):
        out.append(-solve_statics(mech, unit, closures, require=("Fz19",))["Fz19"])
    return out[0], out[1], out[2]


def srt_eq_6_39(c52, c53, c54, bank_rad, slope_up_rad):
    """SRT at Fz19 = 0 from the coefficients of Eq. 6.37 (Eq. 6.39) [g].

    With Px the forward component and slopes positive uphill (Px = -W sin phi),
    ay/g = (C52 sin(phi)/cos(bank) + C53 e cos(phi) - C54 cos(phi)) / (C53 + C54 e), e = tan(bank). The
    thesis prints the same expression with its slope positive downhill (-C52 sin(phi)) and with -C53 e for
    the bank term, a sign that Eqs. 4.25-4.26 do not support (substitute them into Eq. 6.37 to check).
    """
    e = math.tan(bank_rad)
    cs = math.cos(slope_up_rad)
    return (c52 * math.sin(slope_up_rad) / math.cos(bank_rad) + c53 * e * cs - c54 * cs) / (c53 + c54 * e)
