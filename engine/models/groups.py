"""Axle-group sub-mechanisms: tires (Sec. 4.1), leaf-spring suspension (Sec. 4.2), fifth wheel (Sec. 4.3).

An *axle group* is the planar chain, in the group's transverse (y-z) plane, of Figs. 26, 31 and 37:

    road -(R 1 / Sd 3)- tire columns -(P 2, P 4: tire springs)- axle -(R+torsion 5, R 8)- leaf-spring legs
    -(P 6, P 9: leaf springs)- (R 7, R 10) bolster [-(R+torsion 11, R 14)- fifth-wheel legs -(P 12, P 15)-
    (R 13, R 16) fifth-wheel plate]

(numbers of the front group, Table 8; the rear group is 17-26 without a fifth wheel). The outer tire
contact is the origin, y points to the inner tire, z up. The group is described by five (eight with a
fifth wheel) independent joint variables, its *state*::

    (l_out, l_in, l_a, l_b, theta_a[, lf_a, lf_b, thetaf_a])

the two tire lengths (Eq. 4.1), the two spring lengths (Eq. 4.7), the base rotation of the first spring
leg (torsion spring, Eq. 4.6) and the same three for the fifth wheel (Eqs. 4.13-4.14). All other joint
variables follow from the closed-form kinematics below, and the positions from successive screw
displacements about parallel x axes (Tables 4-5, 9-10), which in the group's plane are planar rotations.

The in-plane statics of a group is statically determinate once the load on its top platform is known
(Sec. 5.1.4: 27 equations for 27 unknowns in 2D), and is written here by hand: this is the reduced form of
the Davies solution used by the fast path; ``tests/engine/test_fastpath.py`` checks it against
:func:`engine.mechanics.solve_statics` to 1e-9.

Every function works elementwise on floats (``xp=SCALAR``, the ``math`` module, fast for one case) or on
numpy arrays (``xp=numpy``, for grids of cases).
"""

from __future__ import annotations

import math
import operator
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from engine.errors import ConvergenceError
from engine.models.springs import (
    fifth_wheel_height,
    leaf_spring_height,
    shear_torsion_coefficient,
    tire_radius,
    torsion_angle,
)

HALF_PI = 0.5 * math.pi

#: the fixed-point iteration stops when no state variable (lengths [m], angles [rad]) moves more than this in a step.
#: The iteration contracts 20-50 times a step near the answer, so the state is then within about this of its fixed
#: point and the SRT within 1e-9 g of the exact one (tested against a 1e-14 solve; 1.4e-10 g at most seen): six
#: orders below the thesis' four digits. A tighter value costs a step a decade (1e-13 took 9 steps a solve, this 7).
FIXED_POINT_TOL = 1e-10


class _ScalarMath:
    """The subset of numpy's ufunc names used here, bound to the ``math`` module (fast on floats)."""

    sin = staticmethod(math.sin)
    cos = staticmethod(math.cos)
    sqrt = staticmethod(math.sqrt)
    arcsin = staticmethod(math.asin)
    arccos = staticmethod(math.acos)
    arctan2 = staticmethod(math.atan2)
    hypot = staticmethod(math.hypot)


SCALAR = _ScalarMath()
ARRAY = np


# ------------------------------------------------------------------------------------- parameters


@dataclass(frozen=True)
class FifthWheelParams:
    """Fifth-wheel mechanism on top of the front bolster (Fig. 37)."""

    width: float  # b1 [m]
    height: float  # lf [m]
    k_spring: float  # per side [kN/m] (math.inf: rigid)
    k_torsion: float  # base torsion coefficient [kN m/rad] (math.inf: rigid)
    f_start: float  # static load per side at which the height is lf [kN]


@dataclass(frozen=True)
class GroupParams:
    """One axle group: per-side equivalent stiffnesses (see :mod:`engine.vehicle`) and geometry."""

    axle_width: float  # t2 / t4 [m]
    spring_separation: float  # b [m]
    rolling_radius: float  # lr [m]
    suspension_height: float  # ls [m]
    k_tire: float  # per side [kN/m]
    k_spring: float  # per side [kN/m]
    k_shear: float  # leaf-spring torsion coefficient kst at the first leg's base [kN m/rad]
    f_start: float  # static load per side at which the lengths are lr and ls [kN]
    fifth_wheel: FifthWheelParams | None = None

    def rest_state(self) -> tuple[float, ...]:
        """Lengths at their initial values and no rotation (the reference configuration)."""
        st = (self.rolling_radius, self.rolling_radius, self.suspension_height, self.suspension_height, 0.0)
        if self.fifth_wheel is not None:
            st += (self.fifth_wheel.height, self.fifth_wheel.height, 0.0)
        return st


def group_params(
    vehicle, which: str, static_load_kn: float, fifth_wheel: FifthWheelParams | None = None
) -> GroupParams:
    """The ``"front"`` or ``"rear"`` group of a vehicle record (per-side sums of :mod:`engine.vehicle`).

    ``static_load_kn`` is the group's nominal static load: the lengths lr and ls hold at half of it per side.
    """
    from engine.vehicle.record import group_stiffness

    v = vehicle
    k = group_stiffness(v, which)
    return GroupParams(
        axle_width=v.rear_axle_width_m if which == "rear" else v.front_axle_width_m,
        spring_separation=v.spring_separation_m,
        rolling_radius=v.rolling_radius_m,
        suspension_height=v.suspension_height_m,
        k_tire=k.tire_side_kn_per_m,
        k_spring=k.suspension_side_kn_per_m,
        k_shear=shear_torsion_coefficient(k.suspension_side_kn_per_m, v.suspension_height_m),
        f_start=0.5 * static_load_kn,
        fifth_wheel=fifth_wheel,
    )


# ------------------------------------------------------------------------------------- kinematics


def tire_system(l_out, l_in, axle_width, xp=SCALAR):
    """Roll angle of the axle and instantaneous track of the tire system (Eqs. 4.2-4.5).

    Both tires stay perpendicular to the axle; the outer contact is a revolute, the inner one slides.
    Returns ``(theta, track)``: theta = theta_i = theta_j, positive when the inner side rises [rad]; track
    t_i [m].
    """
    diag = xp.sqrt(axle_width * axle_width + l_in * l_in)
    beta = HALF_PI - xp.arcsin(l_in / diag)  # Eq. 4.2
    track = xp.sqrt(diag * diag + l_out * l_out - 2.0 * diag * l_out * xp.cos(beta))  # Eq. 4.3
    delta = xp.arcsin(l_out * xp.sin(beta) / track)  # Eq. 4.4
    return HALF_PI - delta - beta, track  # Eq. 4.5


def four_bar(l_a, l_b, theta_a, separation, xp=SCALAR):
    """Joint angles of a sprung four-bar (suspension Eqs. 4.8-4.12; fifth wheel Eqs. 4.15-4.19).

    Legs a (base rotation ``theta_a``, the torsion-spring joint n) and b, of lengths l_a and l_b, stand
    ``separation`` apart on the lower link. Returns ``(theta_top_a, theta_base_b, theta_top_b)``: the
    rotations at the top of leg a (joint n+1), at the base of leg b (n+2) and at the top of leg b (n+3),
    each relative to the previous link of its successive-screw chain. Eq. 4.12 gives theta_n+3 as the
    rotation from the upper link to leg b; the chain A_{n+2} A_{n+3} uses the opposite sense, so the third
    value is -theta_n+3 (so that theta_n + theta_n+1 = theta_n+2 + theta_n+3, the loop closure).
    """
    ct = xp.cos(theta_a)
    r = xp.sqrt(l_a * l_a + separation * separation + 2.0 * l_a * separation * xp.sin(theta_a))  # Eq. 4.8
    beta = xp.arccos((separation * separation + r * r - l_b * l_b) / (2.0 * separation * r))  # Eq. 4.9
    g = xp.arcsin(separation / r * ct)
    h = xp.arcsin(separation / l_b * xp.sin(beta))
    top_a = beta + g - HALF_PI  # Eq. 4.10
    base_b = theta_a + g - h  # Eq. 4.11
    top_b = -(HALF_PI - beta - h)  # Eq. 4.12, chain sense
    return top_a, base_b, top_b


class FourBarGeometry(NamedTuple):
    pa: tuple  # base of leg a (y, z)
    ta: tuple  # top of leg a
    pb: tuple
    tb: tuple
    la: object
    angle_a: object  # direction angle of leg a (from the road's z axis)
    angle_b: object
    top_a: object  # joint angles (chain sense)
    base_b: object
    top_b: object
    platform_angle: object  # roll of the upper link
    origin: tuple  # point of the upper link at its local y = 0 (the group's reference line)
    platform_cos_sin: tuple  # (cos, sin) of platform_angle


def _four_bar_geometry(origin, angle, cos_sin, width, separation, l_a, l_b, theta_a, xp) -> FourBarGeometry:
    """Place a four-bar whose lower link has its local y = 0 at ``origin`` and roll ``angle`` (whose cosine and sine
    are ``cos_sin``: the caller has them already, and on arrays each costs as much as twenty products)."""
    c, s = cos_sin
    ya = 0.5 * (width - separation)
    pa = (origin[0] + ya * c, origin[1] + ya * s)
    pb = (pa[0] + separation * c, pa[1] + separation * s)
    top_a, base_b, top_b = four_bar(l_a, l_b, theta_a, separation, xp)
    ang_a = angle + theta_a
    ang_b = angle + base_b
    ta = (pa[0] - l_a * xp.sin(ang_a), pa[1] + l_a * xp.cos(ang_a))
    tb = (pb[0] - l_b * xp.sin(ang_b), pb[1] + l_b * xp.cos(ang_b))
    phi = ang_a + top_a
    cp, sp = xp.cos(phi), xp.sin(phi)
    up_origin = (ta[0] - ya * cp, ta[1] - ya * sp)
    return FourBarGeometry(pa, ta, pb, tb, l_a, ang_a, ang_b, top_a, base_b, top_b, phi, up_origin, (cp, sp))


class GroupGeometry(NamedTuple):
    theta_tire: object  # axle roll theta_1 / theta_17 [rad]
    track: object  # instantaneous track [m]
    l_out: object
    l_in: object
    suspension: FourBarGeometry
    fifth_wheel: FourBarGeometry | None
    top: tuple  # the group's load point: midpoint of its top link (joint 27 / 28) (y, z)
    top_angle: object  # roll of the top link [rad]
    tire_cos_sin: tuple  # (cos, sin) of theta_tire


def group_geometry(p: GroupParams, state, xp=SCALAR) -> GroupGeometry:
    """Positions and joint angles of a group in its plane from its state (Eqs. 4.2-4.19, Tables 4-5)."""
    l_out, l_in, l_a, l_b, th_a = state[:5]
    th_t, track = tire_system(l_out, l_in, p.axle_width, xp)
    tire_cs = ct, st = xp.cos(th_t), xp.sin(th_t)
    axle_origin = (-l_out * st, l_out * ct)  # top of the outer tire column
    susp = _four_bar_geometry(axle_origin, th_t, tire_cs, p.axle_width, p.spring_separation, l_a, l_b, th_a, xp)
    fw = None
    origin, angle, (c, s) = susp.origin, susp.platform_angle, susp.platform_cos_sin
    if p.fifth_wheel is not None:
        lf_a, lf_b, thf_a = state[5:8]
        fw = _four_bar_geometry(origin, angle, (c, s), p.axle_width, p.fifth_wheel.width, lf_a, lf_b, thf_a, xp)
        origin, angle, (c, s) = fw.origin, fw.platform_angle, fw.platform_cos_sin
    half = 0.5 * p.axle_width
    top = (origin[0] + half * c, origin[1] + half * s)
    return GroupGeometry(th_t, track, l_out, l_in, susp, fw, top, angle, tire_cs)


# ------------------------------------------------------------------------------ reduced statics


class FourBarForces(NamedTuple):
    compression_a: object  # spring force in leg a, FLS6 / FLS22 / FFW12 [kN] (positive = compressed)
    compression_b: object  # spring force in leg b, FLS9 / FLS25 / FFW15 [kN]
    torsion_a: object  # Davies magnitude Tx5 / Tx21 / Tx11: moment of the lower link on leg a [kN m]


def four_bar_statics(fb: FourBarGeometry, fy, fz, qy, qz, mx) -> FourBarForces:
    """Leg forces of a four-bar whose upper link carries force (fy, fz) at (qy, qz) and moment mx.

    Leg b is pin-ended (a two-force member along its axis); leg a takes the rest through its base joint.
    Moments about the top of leg a give the force in leg b; the force balance the force in leg a.
    """
    (pay, paz), (tay, taz), (pby, pbz), (tby, tbz) = fb.pa, fb.ta, fb.pb, fb.tb
    uby, ubz = tby - pby, tbz - pbz
    lb = (uby * uby + ubz * ubz) ** 0.5
    uby, ubz = uby / lb, ubz / lb
    m_load = (qy - tay) * fz - (qz - taz) * fy + mx
    arm = (tby - tay) * ubz - (tbz - taz) * uby
    n_b = -m_load / arm
    fay, faz = -fy - n_b * uby, -fz - n_b * ubz  # force of leg a on the upper link
    ray, raz = tay - pay, taz - paz
    comp_a = (fay * ray + faz * raz) / fb.la
    torsion = ray * faz - raz * fay  # moment about the base that leg a must receive from below
    return FourBarForces(comp_a, n_b, torsion)


class GroupForces(NamedTuple):
    fz_outer: object  # ground normal load, outer tire (Fz1 / Fz17) [kN]
    fz_inner: object  # ground normal load, inner tire (Fz3 / Fz19) [kN]
    fy_outer: object  # ground lateral force at the outer tire (Fy1 / Fy17) [kN]
    tire_outer: object  # tire spring force FT2 / FT18 [kN]
    tire_inner: object  # FT4 / FT20 [kN]
    suspension: FourBarForces
    fifth_wheel: FourBarForces | None


def ground_reactions(g: GroupGeometry, fy, fz, mx):
    """(Fz_outer, Fz_inner, Fy_outer) for a load (fy, fz) at the group's top point plus moment mx.

    Moments about the outer contact (the origin): the inner contact at y = track carries no lateral force
    (Sec. 5.1.2: the lateral friction at the sliding tire is neglected).
    """
    qy, qz = g.top
    fz_in = -(qy * fz - qz * fy + mx) / g.track
    return -fz - fz_in, fz_in, -fy


def group_statics(p: GroupParams, g: GroupGeometry, fy, fz, mx, xp=SCALAR) -> GroupForces:
    """All in-plane forces of a group whose top link carries force (fy, fz) at ``g.top`` and moment mx.

    The four-bars above the axle pass the same resultant down, so each is solved with the top load; the
    tire springs carry the axial components of the ground reactions (Eqs. 5.16-5.17 in 2D).
    """
    qy, qz = g.top
    fw = None
    if g.fifth_wheel is not None:
        fw = four_bar_statics(g.fifth_wheel, fy, fz, qy, qz, mx)
    susp = four_bar_statics(g.suspension, fy, fz, qy, qz, mx)
    fz_out, fz_in, fy_out = ground_reactions(g, fy, fz, mx)
    c, s = g.tire_cos_sin
    return GroupForces(fz_out, fz_in, fy_out, -fy_out * s + fz_out * c, fz_in * c, susp, fw)


def group_next_state(p: GroupParams, f: GroupForces):
    """New state from the forces through the compliance laws (Eqs. 4.1, 4.6-4.7, 4.13-4.14)."""
    susp = f.suspension
    st = (
        tire_radius(f.tire_outer, p.f_start, p.k_tire, p.rolling_radius),  # Eq. 4.1
        tire_radius(f.tire_inner, p.f_start, p.k_tire, p.rolling_radius),
        leaf_spring_height(susp.compression_a, p.f_start, p.k_spring, p.suspension_height),  # Eq. 4.7
        leaf_spring_height(susp.compression_b, p.f_start, p.k_spring, p.suspension_height),
        torsion_angle(susp.torsion_a, p.k_shear),  # Eq. 4.6
    )
    fwp = p.fifth_wheel
    if fwp is not None:  # a rigid fifth wheel (first stage) has infinite rates: its lengths stay at lf
        fw = f.fifth_wheel
        st += (
            fifth_wheel_height(fw.compression_a, fwp.f_start, fwp.k_spring, fwp.height),  # Eq. 4.14
            fifth_wheel_height(fw.compression_b, fwp.f_start, fwp.k_spring, fwp.height),
            torsion_angle(fw.torsion_a, fwp.k_torsion),  # Eq. 4.13
        )
    return st


# ------------------------------------------------------------------------------------ iteration


def fixed_point(step, x0, *, vector: bool, tol: float, max_iter: int):
    """Solve x = g(x) by fixed-point iteration with an Anderson(1) (secant) step.

    ``step(x, it)`` returns ``(payload, g(x))``; x is a tuple of floats (one problem), or of equal-shape arrays when
    ``vector`` (one independent problem per array element, see :func:`fixed_point_batch`). Returns
    ``(x, iterations, payload)`` at convergence; :class:`ConvergenceError` otherwise (for a batch: when every
    problem failed).
    """
    if vector:
        x, it, payload, failed, _ = fixed_point_batch(step, x0, tol=tol, max_iter=max_iter)
        if failed.size and bool(np.all(failed)):
            raise ConvergenceError("every case of the batch left the valid geometry or did not converge", iterations=it)
        return x, it, payload
    x = [float(v) for v in x0]
    g_prev = f_prev = None
    err = math.inf
    for it in range(1, max_iter + 1):
        payload, gx = step(tuple(x), it)
        g = list(gx)
        if len(g) != len(x):
            raise ValueError(f"the step returned {len(g)} values for a state of {len(x)}")
        f = list(map(operator.sub, g, x))  # map over operator: the same sums, a third of the interpreter's work
        err = max(map(abs, f))
        if not math.isfinite(err):
            raise ConvergenceError(
                "non-finite geometry: the vehicle is beyond its static stability limit", iterations=it
            )
        if err < tol:
            return x, it, payload
        if f_prev is None:
            x_new = g
        else:
            df = list(map(operator.sub, f, f_prev))
            den = sum(map(operator.mul, df, df))
            gamma = sum(map(operator.mul, f, df)) / den if den > 0 else 0.0
            x_new = [a - gamma * (a - b) for a, b in zip(g, g_prev, strict=True)]
        g_prev, f_prev, x = g, f, x_new
    raise ConvergenceError(
        f"the geometry/force iteration did not converge in {max_iter} iterations (last change {err:.2e})",
        iterations=max_iter,
        residual=err,
    )


def fixed_point_batch(step, x0, *, tol: float, max_iter: int):
    """:func:`fixed_point` for many independent problems at once (x a tuple of equal-shape arrays).

    A problem whose geometry becomes non-finite (it left the mechanism's valid geometry: the vehicle is at or
    beyond its static stability limit in that case) is frozen and marked failed; the others go on. Returns
    ``(x, iterations, payload, failed, steps)``, ``failed`` a boolean array (also set for problems that did not
    converge in ``max_iter`` iterations), ``steps`` each problem's own iteration count (the step at which it
    converged, as :func:`fixed_point` alone would report it); the payload's entries of failed problems are
    meaningless.
    """
    x = np.stack(np.broadcast_arrays(*x0)).astype(float)
    failed = np.zeros(x.shape[1:], dtype=bool)
    steps = np.zeros(failed.shape, dtype=int)
    g_prev = f_prev = None
    payload = None
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for it in range(1, max_iter + 1):
            payload, gx = step(tuple(x), it)
            g = np.stack(np.broadcast_arrays(*gx)).astype(float)
            failed |= ~np.all(np.isfinite(g), axis=0)
            g = np.where(failed, x, g)  # a failed problem stays where it was
            f = g - x
            err = np.max(np.abs(f), axis=0) if f.size else np.zeros(failed.shape)
            converged = ~(err >= tol)
            steps = np.where((steps == 0) & converged, it, steps)
            if np.all(converged):
                return x, it, payload, failed, steps
            if f_prev is None:
                x_new = g
            else:  # Anderson(1) per problem
                df = f - f_prev
                den = np.sum(df * df, axis=0)
                gamma = np.where(den > 0, np.sum(f * df, axis=0) / np.where(den > 0, den, 1.0), 0.0)
                x_new = g - gamma * (g - g_prev)
            # a converged problem stays at the x it converged at (as it would alone): its answer does not depend on
            # the other problems of the batch; its payload is recomputed at that same x
            g_prev, f_prev, x = g, f, np.where(converged, x, x_new)
    failed |= err >= tol
    return x, max_iter, payload, failed, np.where(steps == 0, max_iter, steps)
