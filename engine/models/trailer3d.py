"""The three-dimensional trailer model of Ch. 6 (Tables 8-11, Eqs. 6.1-6.2, 6.15-6.19).

Mechanism (Fig. 43, Table 8)
----------------------------
Frame: x forward, origin below the kingpin (fifth wheel), y toward the inside of the turn with the outer
tires at y = 0, z normal to the road. Twenty-three links:

* the road (ground);
* the **front group** (front tires at x = -l13, fifth wheel at x = 0), yawed by the trailer/trailer angle
  psi about the vertical through the kingpin (point 29, Table 8): outer and inner tire columns, axle, two
  leaf-spring legs of two links each, bolster, two fifth-wheel legs of two links each, fifth-wheel plate
  (joints 1-16, :mod:`engine.models.groups`);
* the **rear group** at x = -L: tire columns, axle, two leaf-spring legs, bolster (joints 17-26);
* the **chassis** carrying the CG at (-a + d2, h1, h2), joined to the rear bolster by joint 27 and to the
  fifth-wheel plate by joint 28.

The CG hangs from the rear chain, p_CG = A17 A18 A21 A22 A23 A27 A_CG p_CG (Table 9); its lateral
distance h1 and height h2 are Eqs. 6.1-6.2.

Joints and constraints follow Table 11 (revolute: Fx Fy Fz My Mz; prismatic: Fx Fp Mx My Mz and the
spring FT/FLS/FFW; spherical slider at the inner contacts: Fx My Fz; torsion-spring revolutes 5, 11, 21:
+Tx), with two deliberate readings at the chassis joints, written down in ``docs/model.md``:

* **joint 28** (kingpin on the fifth-wheel plate) transmits the three forces and one moment *about the
  front unit's longitudinal axis x'*: a fifth wheel is free in yaw (kingpin) and in pitch about the lead
  unit's transverse axis (the plate oscillates on its mounting pins, Figs. 34-36), and roll-coupled about
  x'. At psi = 0 this is Table 11's spherical joint with Tx. For psi != 0 the moment the trailer feels about
  its own x axis is Tf cos psi and Tf sin psi goes into pitch: Eqs. 4.22-4.23.
* **joint 27** (rear bolster on the chassis) transmits, besides Fx Fy Fz Tx, the pitch moment My: the
  chassis is built into the rear suspension hangers, and a multi-axle group takes pitch moments by load
  shift between its axles. Without it Eq. 4.27 contradicts the chassis' own pitch equilibrium on a grade
  (with two pin-ended supports the rear load is fixed by statics) or is met only through a spurious axial
  chassis force of several hundred kN.

Closure equations (Eq. 6.19)
----------------------------
The cut-set equations leave the mechanism statically indeterminate (22 cuts x 6 = 132 equations, 148
unknowns here). The in-plane statics of each group is determinate; what is not:

1. the **front/rear load split**, closed by Eq. 4.27: Fz17 + Fz19 = (Pz (a - d2) - Px h2) / L;
2. the **front/rear split of the roll moment** (the four-legged table, Fig. 60), closed by the chassis
   torsion relation Eq. 4.21, ``Tf + Tr (a - L)/(a x) = 0`` with Tf = T28 (the coupling moment about the
   front unit's axis, whose trailer-x component is Tf cos psi, Eq. 4.22) and Tr = Tx27. The constant
   x = Jr/Jf is a property of the chassis. Ch. 9 fixes it through Kamnik et al.'s observation that the
   front lateral load transfer is 70 % of the rear one at the rollover limit: ``"chassis-constant"``
   (default) chooses x once per vehicle and stage so that LLTf = rho LLTr at the limit on a flat road with
   the nominal centred load (where Kamnik et al. measured it), and keeps that x for every other road and
   load case. Alternatives, for comparison: ``"llt-ratio"`` imposes LLTf = rho LLTr in every case and at
   every load step, Fr (Fz1 - Fz3) = rho Ff (Fz17 - Fz19) (identical at the calibration case, and on banks;
   it leaves grades and the trailer angle almost without effect); ``"inverse-ratio"`` reads x = 1/rho
   literally, which gives LLTf = 0.82 LLTr and SRT_3D = 0.355 for the B-train, not the 0.7 and 0.3364
   that Ch. 9 reports;
3. the **longitudinal force path**: the thesis neglects accelerating and braking forces, so the trailer's
   own (rear) tires are free-rolling, Fx17 = Fx19 = 0, and Px reaches the road through the kingpin and
   the front unit.

The remaining null space (out-of-plane force and moment distributions inside the groups, e.g. the pitch
moment shared by the front tires) touches none of the quantities reported; the Davies reference path
checks that with the null-space test of :func:`engine.mechanics.solve_statics`.

The rollover limit is the rear inner tire lifting off (Fz19 = 0, Eq. 6.18) or, more generally, the rear
lateral load transfer reaching ``llt_limit`` (Table 17 uses 0.6).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np

from engine.errors import ConvergenceError, InvalidInput
from engine.models.groups import (
    FIXED_POINT_TOL,
    SCALAR,
    FifthWheelParams,
    GroupGeometry,
    GroupParams,
    fixed_point,
    fixed_point_batch,
    ground_reactions,
    group_geometry,
    group_next_state,
    group_params,
    group_statics,
)
from engine.models.springs import (
    chassis_torque_components,
    chassis_torque_split,
    chassis_twist,
    shear_torsion_coefficient,
)
from engine.vehicle.record import Vehicle

#: the stages of Ch. 9 (see :func:`build_model`)
STAGES = ("full", "tires-suspension")


@dataclass(frozen=True)
class ChassisClosure:
    """One way of closing the front/rear split of the roll moment (see the module docstring).

    ``mode`` is the equation the solver imposes: ``"torque-split"`` (Eq. 4.21 with a chassis constant x) or
    ``"llt-ratio"`` (LLTf = rho LLTr imposed at every load step); ``x`` says how x is chosen for the torque split:
    ``"calibrated"`` (once per vehicle and stage, on the reference case) or ``"inverse-ratio"`` (x = 1/rho).
    """

    id: str
    mode: str
    x: str | None
    description: str


CLOSURES: dict[str, ChassisClosure] = {
    c.id: c
    for c in (
        ChassisClosure(
            "chassis-constant",
            "torque-split",
            "calibrated",
            "Eq. 4.21 with x = Jr/Jf calibrated once so that LLTf = rho LLTr at the flat-road limit (default)",
        ),
        ChassisClosure("llt-ratio", "llt-ratio", None, "LLTf = rho LLTr imposed in every case and at every step"),
        ChassisClosure("inverse-ratio", "torque-split", "inverse-ratio", "Eq. 4.21 with x = 1/rho read literally"),
    )
}


def get_closure(closure_id: str) -> ChassisClosure:
    """The chassis closure with this id; :class:`InvalidInput` listing the known ids otherwise."""
    try:
        return CLOSURES[closure_id]
    except KeyError:
        raise InvalidInput(
            f"chassis_closure must be one of {', '.join(CLOSURES)}, got {closure_id!r}",
            field="chassis_closure",
            value=closure_id,
        ) from None


# ---------------------------------------------------------------------------------------- model


@dataclass(frozen=True)
class TrailerModel:
    """Everything the 3D mechanism needs, derived from a vehicle record and a stage."""

    rear: GroupParams
    front: GroupParams
    wheelbase: float  # L [m]
    kingpin_to_cg: float  # a [m]
    kingpin_to_front_axle: float  # l13 [m]
    cg_above_chassis: float  # l12 [m]
    llt_ratio: float  # rho = LLTf / LLTr
    closure: str  # the solver's mode: "llt-ratio" or "torque-split" (Eq. 4.21 with torque_split_x)
    chassis_rigidity: float | None  # G Jr [kN m^2/rad]
    weight_nominal: float  # W [kN]
    torque_split_x: float = 1.0  # x = Jr/Jf of Eq. 4.21, used by the "torque-split" mode

    @property
    def yaw_pivot_y(self) -> float:
        """Lateral position of the kingpin (point 29 of Table 8): t2 / 2."""
        return 0.5 * self.front.axle_width


@functools.lru_cache(maxsize=256)
def build_model(vehicle: Vehicle, stage: str = "full", closure: str = "chassis-constant", forces=None) -> TrailerModel:
    """Map a (validated) vehicle record onto the 3D mechanism (see :mod:`engine.vehicle` for the sums).

    Memoised (bounded LRU): the model of a vehicle and stage, with its calibrated chassis constant (two solves), is
    a pure function of frozen inputs and is immutable, so a vehicle solved again (another road, load or curve of an
    alignment) reuses it. The memo changes no result, only how often the calibration runs.

    Parameters
    ----------
    vehicle : the vehicle record
    stage : ``"tires-suspension"`` is the first stage of Ch. 9 (tires and suspensions compliant, the fifth wheel
        rigid, the lateral load transfer equal front and rear, rho = 1); ``"full"`` adds the fifth wheel's
        compliance and the chassis' torsional flexibility (rho from the record, twist from G Jr) [-]
    closure : id of :data:`CLOSURES`; ``"chassis-constant"`` calibrates x on :func:`reference_case` [-]
    forces : the statics solver used by the calibration (default the fast path; the Davies reference path
        :func:`engine.models.trailer3d_davies.davies_forces_at` for cross-checks)
    """
    c = get_closure(closure)
    v = vehicle
    w = v.weight_kn
    front_load = w * (v.wheelbase_m - v.front_axle_to_cg_m) / v.wheelbase_m  # Eq. 4.27 at rest
    rear_load = w - front_load
    full = stage == "full"

    fw = None
    if v.has_fifth_wheel:
        kf = v.fifth_wheel_stiffness_kn_per_m
        fw = FifthWheelParams(
            width=v.fifth_wheel_width_m,
            height=v.fifth_wheel_height_m,
            k_spring=kf if full else math.inf,
            k_torsion=shear_torsion_coefficient(kf, v.fifth_wheel_height_m) if full else math.inf,
            f_start=0.5 * front_load,
        )
    m = TrailerModel(
        rear=group_params(v, "rear", rear_load),
        front=group_params(v, "front", front_load, fw),
        wheelbase=v.wheelbase_m,
        kingpin_to_cg=v.front_axle_to_cg_m,
        kingpin_to_front_axle=v.fifth_wheel_to_front_axle_m or 0.0,
        cg_above_chassis=v.cg_height_above_chassis_m,
        llt_ratio=v.front_llt_ratio if full else 1.0,
        closure=c.mode,
        torque_split_x=1.0 / v.front_llt_ratio if full else 1.0,
        chassis_rigidity=v.chassis_torsional_stiffness_knm2_per_rad if full else None,
        weight_nominal=w,
    )
    return calibrate_chassis_constant(m, forces) if c.x == "calibrated" else m


@dataclass(frozen=True)
class SolverCase:
    """One road/load case; every field may be a float or (for grids) a numpy array of one shape."""

    weight: object  # W with overweight [kN]
    bank: object  # bank angle [rad]
    slope: object  # slope angle, positive uphill [rad]
    psi: object  # trailer/trailer angle [rad]
    d1: object  # lateral CG offset, + toward the outer tires [m]
    d2: object  # longitudinal CG offset, + toward the front [m]
    d3: object  # vertical CG offset, + up [m]
    llt_limit: object  # rear LLT at the limit [-]


# ------------------------------------------------------------------------------ the fast path


def _road_angles(case: SolverCase, xp) -> tuple:
    """(cos, sin) of the bank, then of the slope (:func:`_kept`)."""
    if xp is not np:
        return xp.cos(case.bank), xp.sin(case.bank), xp.cos(case.slope), xp.sin(case.slope)
    return _kept(
        case, "_road_angles", lambda: (np.cos(case.bank), np.sin(case.bank), np.cos(case.slope), np.sin(case.slope))
    )


def _psi_angles(case: SolverCase, xp) -> tuple:
    """(cos, sin) of the trailer angle psi (:func:`_kept`)."""
    if xp is not np:
        return xp.cos(case.psi), xp.sin(case.psi)
    return _kept(case, "_psi_angles", lambda: (np.cos(case.psi), np.sin(case.psi)))


def _kept(case: SolverCase, name: str, compute):
    """A batch's values derived from its case alone (the cos/sin of its angles), computed once and kept on it: a
    solve evaluates them 70-odd times, each an array operation (a block of 16,384 cases: 15-20 % of its time). A single
    case computes them each time (math's cos/sin cost less than the lookup); the values are the same either way."""
    value = case.__dict__.get(name)
    if value is None:
        value = compute()
        object.__setattr__(case, name, value)  # a frozen dataclass: derived values only, never a field
    return value


class Geometry(NamedTuple):
    rear: GroupGeometry
    front: GroupGeometry
    p27: tuple  # (x, y, z) trailer frame
    p28: tuple
    cg: tuple
    roll: object  # theta_3D = theta17 + theta21 + theta23 + theta27 [rad]
    theta27: object


def geometry(m: TrailerModel, case: SolverCase, rear_state, front_state, theta27, xp=SCALAR) -> Geometry:
    """Positions of joints 27, 28 and of the CG (Table 10, Eqs. 6.1-6.2) from the group states."""
    gr = group_geometry(m.rear, rear_state, xp)
    gf = group_geometry(m.front, front_state, xp)
    p27 = (-m.wheelbase, gr.top[0], gr.top[1])
    roll = gr.top_angle + theta27
    c, s = xp.cos(roll), xp.sin(roll)
    l12 = m.cg_above_chassis + case.d3
    cg = (-m.kingpin_to_cg + case.d2, p27[1] - case.d1 * c - l12 * s, p27[2] - case.d1 * s + l12 * c)
    dy = gf.top[0] - m.yaw_pivot_y  # the kingpin point in the front frame sits at x' = 0
    cp, sp = _psi_angles(case, xp)
    p28 = (-dy * sp, m.yaw_pivot_y + dy * cp, gf.top[1])
    return Geometry(gr, gf, p27, p28, cg, roll, theta27)


def cg_actions(case: SolverCase, ay, xp=SCALAR):
    """(Px, Py, Pz) [kN] at the CG (Eqs. 4.24-4.26; Px forward, slope positive uphill)."""
    cb, sb, cs, ss = _road_angles(case, xp)
    w = case.weight
    return -w * ss, -w * sb * cs + w * ay * cb, w * cb * cs + w * ay * sb


class ChassisLoads(NamedTuple):
    px: object
    py: object
    pz: object
    fr: object  # rear normal load Fz17 + Fz19 (Eq. 4.27) [kN]
    f27: tuple  # force of the rear bolster on the chassis (Fx27, Fy27, Fz27)
    tx27: object  # moment of the rear bolster on the chassis about x
    my27: object
    f28: tuple  # force of the plate on the chassis (trailer frame)
    t28: object  # moment of the plate on the chassis about x' (the front torque Tf)
    rear_load: tuple  # (fy, fz, mx) on the rear bolster, in the rear group's plane
    front_load: tuple  # (fy', fz', mx') on the plate, in the front group's plane


def chassis_loads(m: TrailerModel, case: SolverCase, geo: Geometry, ay, t28, xp=SCALAR) -> ChassisLoads:
    """Equilibrium of the chassis link with the closures Eq. 4.27 and Fx17 = Fx19 = 0.

    Unknowns at joint 27: Fy27, Tx27, My27 (Fz27 = Fr from Eq. 4.27, Fx27 = 0: free-rolling rear tires);
    at joint 28: the force F28 and the moment t28 about x' (given here: it is fixed by the roll-moment
    closure). Moments about joint 27: z gives Fy28, x gives Tx27, y gives My27.
    """
    px, py, pz = cg_actions(case, ay, xp)
    fx, fy, fz = px, -py, -pz  # the action on the chassis (Table 11 directions)
    a_eff = m.kingpin_to_cg - case.d2
    fr = (pz * a_eff - px * geo.cg[2]) / m.wheelbase  # Eq. 4.27
    p27, p28, cg = geo.p27, geo.p28, geo.cg
    rx, ry, rz = p28[0] - p27[0], p28[1] - p27[1], p28[2] - p27[2]
    cx, cy, cz = cg[0] - p27[0], cg[1] - p27[1], cg[2] - p27[2]
    mcx, mcy, mcz = cy * fz - cz * fy, cz * fx - cx * fz, cx * fy - cy * fx
    f28x = -fx
    f28z = -fz - fr
    f28y = (ry * f28x - mcz) / rx
    fy27 = -fy - f28y
    cp, sp = _psi_angles(case, xp)
    tf_x, tf_y = chassis_torque_components(t28, cp, sp)  # Eqs. 4.22-4.23
    tx27 = -(ry * f28z - rz * f28y + mcx) - tf_x
    my27 = -(rz * f28x - rx * f28z + mcy) - tf_y
    # loads on the groups: minus what they apply to the chassis; the front one in the front frame
    rear = (-fy27, -fr, -tx27)
    front = (-(-f28x * sp + f28y * cp), -f28z, -t28)
    return ChassisLoads(px, py, pz, fr, (0.0 * fr, fy27, fr), tx27, my27, (f28x, f28y, f28z), t28, rear, front)


def _closure_residual(m: TrailerModel, case: SolverCase, geo: Geometry, ay, t28, xp, at_limit: bool):
    """Residuals of (roll-moment closure, limit condition), both affine in (ay, t28)."""
    cl = chassis_loads(m, case, geo, ay, t28, xp)
    f17, f19, _ = ground_reactions(geo.rear, *cl.rear_load)
    lam = case.llt_limit
    limit = (f17 - f19) - lam * (f17 + f19)
    if m.closure == "torque-split":  # the front tire loads are not needed
        a_eff = m.kingpin_to_cg - case.d2
        split = t28 - chassis_torque_split(cl.tx27, a_eff, m.wheelbase, m.torque_split_x)  # Eq. 4.21
        return split, limit
    f1, f3, _ = ground_reactions(geo.front, *cl.front_load)
    if at_limit:  # LLTr = lam and LLTf = rho lam: both linear
        split = (f1 - f3) - m.llt_ratio * lam * (f1 + f3)
    else:  # Fr (Fz1 - Fz3) = rho Ff (Fz17 - Fz19) with Fr, Ff fixed by ay
        split = (f17 + f19) * (f1 - f3) - m.llt_ratio * (f1 + f3) * (f17 - f19)
    return split, limit


def solve_loads(m: TrailerModel, case: SolverCase, geo: Geometry, ay=None, xp=SCALAR):
    """(ay, t28) at the limit (``ay=None``) or t28 at a given ay, exactly, at frozen geometry.

    Every force is affine in (ay, t28) at frozen geometry, so three evaluations give the coefficients and a
    2x2 (or 1x1) linear solve the answer.
    """
    if ay is None:
        s0, l0 = _closure_residual(m, case, geo, 0.0, 0.0, xp, True)
        sa, la = _closure_residual(m, case, geo, 1.0, 0.0, xp, True)
        st, lt = _closure_residual(m, case, geo, 0.0, 1.0, xp, True)
        a11, a12, a21, a22 = sa - s0, st - s0, la - l0, lt - l0
        det = a11 * a22 - a12 * a21
        ay_sol = (-s0 * a22 + a12 * l0) / det
        t_sol = (-a11 * l0 + a21 * s0) / det
        return ay_sol, t_sol
    s0, _ = _closure_residual(m, case, geo, ay, 0.0, xp, False)
    s1, _ = _closure_residual(m, case, geo, ay, 1.0, xp, False)
    return ay, -s0 / (s1 - s0)


class State(NamedTuple):
    rear: tuple
    front: tuple
    theta27: object


def rest_state(m: TrailerModel, like=0.0) -> State:
    z = 0.0 * like
    return State(tuple(v + z for v in m.rear.rest_state()), tuple(v + z for v in m.front.rest_state()), z)


class Solution(NamedTuple):
    ay: object
    state: State
    geometry: Geometry
    loads: ChassisLoads
    rear: object  # GroupForces
    front: object  # GroupForces
    iterations: object  # int; for a batch, each case's own count (an int array)


def forces_at(m: TrailerModel, case: SolverCase, state: State, ay=None, xp=SCALAR):
    """One pass of the fast path: geometry -> closures (and limit) -> all forces, at a frozen state."""
    geo = geometry(m, case, state.rear, state.front, state.theta27, xp)
    ay, t28 = solve_loads(m, case, geo, ay, xp)
    cl = chassis_loads(m, case, geo, ay, t28, xp)
    rf = group_statics(m.rear, geo.rear, *cl.rear_load, xp=xp)
    ff = group_statics(m.front, geo.front, *cl.front_load, xp=xp)
    return ay, geo, cl, rf, ff


def next_state(m: TrailerModel, case: SolverCase, cl: ChassisLoads, rf, ff) -> State:
    a_eff = m.kingpin_to_cg - case.d2
    th27 = chassis_twist(cl.tx27, m.wheelbase - a_eff, m.chassis_rigidity)  # Eq. 4.20
    return State(group_next_state(m.rear, rf), group_next_state(m.front, ff), th27)


def _flat(state: State):
    return (*state.rear, *state.front, state.theta27)


def solve(
    m: TrailerModel,
    case: SolverCase,
    ay=None,
    *,
    start: State | None = None,
    xp=SCALAR,
    tol: float = FIXED_POINT_TOL,
    max_iter: int = 200,
    forces=None,
) -> Solution:
    """Geometry and forces consistent with each other, at the limit (``ay=None``) or at a given ay.

    Fixed-point iteration (geometry -> forces by the statics -> geometry by the compliance laws) with a
    secant (Anderson, depth 1) acceleration; ``forces`` swaps in another statics solver with the same
    signature as :func:`forces_at` (the Davies reference path). Raises :class:`ConvergenceError`.
    """
    forces = forces or forces_at
    state = start or rest_state(m, case.weight)
    shape = (len(state.rear), len(state.front))

    def step(x, it):
        try:
            out = forces(m, case, _unflat(x, shape), ay, xp)
        except (ValueError, ZeroDivisionError, FloatingPointError) as exc:
            raise ConvergenceError(
                f"the mechanism left its valid geometry at iteration {it} ({exc}); the vehicle is at or beyond "
                "its static stability limit for this case",
                iterations=it,
            ) from None
        return out, _flat(next_state(m, case, *out[2:]))

    if xp is SCALAR:
        x, it, out = fixed_point(step, _flat(state), vector=False, tol=tol, max_iter=max_iter)
        ay_k, geo, cl, rf, ff = out
        return Solution(ay_k, _unflat(x, shape), geo, cl, rf, ff, it)
    # a batch: a case that leaves the valid geometry (or does not converge) gets ay = nan, the others their value
    # (``iterations`` is then each case's own count, an array)
    x, _, out, failed, steps = fixed_point_batch(step, _flat(state), tol=tol, max_iter=max_iter)
    ay_k, geo, cl, rf, ff = out
    return Solution(np.where(failed, np.nan, ay_k), _unflat(x, shape), geo, cl, rf, ff, steps)


def _unflat(x, shape) -> State:
    nr, nf = shape
    vals = list(x)
    return State(tuple(vals[:nr]), tuple(vals[nr : nr + nf]), vals[nr + nf])


def reference_case(m: TrailerModel) -> SolverCase:
    """Flat road, psi = 0, nominal centred load, rear inner tire lifting: where Kamnik et al.'s ratio holds."""
    return SolverCase(weight=m.weight_nominal, bank=0.0, slope=0.0, psi=0.0, d1=0.0, d2=0.0, d3=0.0, llt_limit=1.0)


def calibrate_chassis_constant(m: TrailerModel, forces=None) -> TrailerModel:
    """The model with the torque-split closure (Eq. 4.21) and x = Jr/Jf chosen so LLTf = rho LLTr.

    Solves the reference case (:func:`reference_case`) with the ratio imposed and reads x off Eq. 4.21,
    x = Tr (L - a) / (a Tf). At the reference case both closures give the same answer.
    """
    sol = solve(replace(m, closure="llt-ratio"), reference_case(m), forces=forces)
    a, big_l = m.kingpin_to_cg, m.wheelbase
    x = sol.loads.tx27 * (big_l - a) / (a * sol.loads.t28)
    return replace(m, closure="torque-split", torque_split_x=float(x))
