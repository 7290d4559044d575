"""The reference solution of the whole-combination roll model: the equilibrium of every roll degree of freedom as a
general nonlinear system, solved with scipy.

:mod:`engine.models.combination` follows the piecewise-linear equilibrium path event by event. This module knows
nothing of events or regimes: it writes the moment balance of every sprung mass and every axle with the laws as
plain functions (tyre moments clipped at lift-off, dead zones for lash), fixes the outward roll of the sprung
masses ``p = sum(W_u phi_u) / sum(W_u)`` and solves for the other roll angles and ay with
:func:`scipy.optimize.root`, scans ``p`` and refines the largest ay with :func:`scipy.optimize.minimize_scalar`.
It is slow (hundreds of root solves) and meant for tests and for checking the stepped solution.

References
----------
The equations of :mod:`engine.models.combination` (its docstring); Virtanen et al. (2020), SciPy 1.0,
Nature Methods 17: 261-272 (MINPACK's hybrid Powell method behind ``root``; Brent's bounded minimisation).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import minimize_scalar, root

from engine.errors import ConvergenceError
from engine.vehicle.combination import Combination, UnitLoad, loaded_units, roll_coupled_units, static_loads


def _dead_zone(x: float, half_width: float) -> float:
    if x > half_width:
        return x - half_width
    if x < -half_width:
        return x + half_width
    return 0.0


class _Equations:
    """The balance of the sprung masses and axles of one roll-coupled unit, written out unit by unit."""

    def __init__(self, c: Combination, members: tuple[int, ...], bank_percent: float, slope_percent: float,
                 load: UnitLoad, *, lash: bool = True):  # fmt: skip
        self.c, self.members, self.lash = c, members, lash
        b, s = math.atan(bank_percent / 100.0), math.atan(slope_percent / 100.0)
        self.cb, self.sb, self.cs, self.ss = math.cos(b), math.sin(b), math.cos(s), math.sin(s)
        self.lu = loaded_units(c, load)
        self.st = static_loads(c, self.lu)
        self.groups = [(u, j) for u in members for j in range(len(c.units[u].groups))]
        self.nb = len(members)

    def factors(self, ay: float) -> tuple[float, float]:
        normal = self.cb * self.cs + ay * self.sb
        lateral = ay * self.cb - self.sb * self.cs
        return normal, lateral

    def all_lifted(self, x: np.ndarray) -> bool:
        """Whether every group's inner tyres are off the road in the state ``x`` (the unit is on its outer wheels)."""
        normal, _lateral = self.factors(x[-1])
        for k, (u, j) in enumerate(self.groups):
            g = self.c.units[u].groups[j]
            cap = (normal * self.st.normal_kn[(u, j)] + self.ss * self.st.grade_kn[(u, j)]) * g.track_m / 2.0
            if g.tyre_roll_stiffness_knm_per_rad * x[self.nb + k] < cap:
                return False
        return True

    def residual(self, phi_body: np.ndarray, phi_axle: np.ndarray, ay: float) -> np.ndarray:
        c, st = self.c, self.st
        normal, lateral = self.factors(ay)
        n_static = normal  # the P-Delta terms at this ay's normal factor
        body = dict(zip(self.members, phi_body, strict=True))
        axle = dict(zip(self.groups, phi_axle, strict=True))
        r_body = {u: 0.0 for u in self.members}
        r_axle = {}
        for u in self.members:
            unit, lu = c.units[u], self.lu[u]
            # the sprung mass's own weight and inertia (overturning)
            r_body[u] -= lateral * lu.weight_kn * lu.cg_height_m
            r_body[u] -= n_static * lu.weight_kn * lu.cg_height_m * body[u]
            r_body[u] -= normal * lu.weight_kn * lu.lateral_offset_m
            for j, g in enumerate(unit.groups):
                wa = g.unsprung_weight_kn
                n0 = st.normal_kn[(u, j)]
                s0 = n0 - wa
                s_static = n_static * s0 + self.ss * st.grade_kn[(u, j)]
                m_susp = g.suspension_roll_stiffness_knm_per_rad * _dead_zone(
                    body[u] - axle[(u, j)], math.radians(g.lash_deg) * self.lash
                )
                # the tyres: linear until a side's load reaches zero, then the whole load on the other side
                cap = (normal * n0 + self.ss * st.grade_kn[(u, j)]) * g.track_m / 2.0
                m_tyre = max(-cap, min(cap, g.tyre_roll_stiffness_knm_per_rad * axle[(u, j)]))
                r_axle[(u, j)] = (
                    m_tyre
                    - m_susp
                    - lateral * (s0 * g.roll_centre_height_m + wa * g.unsprung_cg_height_m)
                    - axle[(u, j)] * (s_static * g.roll_centre_height_m + n_static * wa * g.unsprung_cg_height_m)
                )
                r_body[u] += (
                    m_susp + lateral * s0 * g.roll_centre_height_m + body[u] * s_static * g.roll_centre_height_m
                )
        for i, cp in enumerate(c.couplings):
            v0 = st.coupling_kn[i]
            v_static = n_static * v0 + self.ss * st.coupling_grade_kn[i]
            towing, towed = i, i + 1
            if towing in r_body:
                r_body[towing] -= lateral * v0 * cp.height_m + body[towing] * v_static * cp.height_m
            if towed in r_body:
                r_body[towed] += lateral * v0 * cp.height_m + body[towed] * v_static * cp.height_m
            if cp.transmits_roll and towing in r_body and towed in r_body:
                m = cp.roll_stiffness_knm_per_rad * _dead_zone(
                    body[towed] - body[towing], math.radians(cp.lash_deg) * self.lash
                )
                r_body[towed] += m
                r_body[towing] -= m
        return np.array([*r_body.values(), *(r_axle[g] for g in self.groups)])


def _solve_on(eq: _Equations, guess: np.ndarray, origin: np.ndarray, direction: np.ndarray, offset: float):
    """(phi_body, phi_axle, ay) on the equilibrium path where it crosses the hyperplane ``(X - origin) . direction =
    offset`` (pseudo-arclength continuation: the hyperplane is across the path, so folds in any one variable are
    passed)."""
    nb = eq.nb

    def f(x):
        res = eq.residual(x[:nb], x[nb:-1], x[-1])
        return np.append(res, float((x - origin) @ direction) - offset)

    for method, options in (("hybr", {"xtol": 1e-14, "maxfev": 20000}), ("lm", {"xtol": 1e-15, "maxiter": 20000})):
        sol = root(f, guess, method=method, options=options)
        if np.max(np.abs(f(sol.x))) <= 1e-9:
            return sol.x
    raise ConvergenceError(f"the reference equilibrium did not converge (offset {offset:g})")


def _around(eq: _Equations, a: np.ndarray, b: np.ndarray, radius: float) -> np.ndarray | None:
    """A state on the path at ``radius`` from ``b`` (the sphere meets every branch through ``b``), away from ``a``."""
    nb = eq.nb

    def f(x):
        res = eq.residual(x[:nb], x[nb:-1], x[-1])
        return np.append(res, float((x - b) @ (x - b)) / radius - radius)

    best = None
    for k in range(len(b)):
        for sign in (1.0, -1.0):
            guess = b.copy()
            guess[k] += sign * radius
            sol = root(f, guess, method="hybr", options={"xtol": 1e-14, "maxfev": 5000})
            if np.max(np.abs(f(sol.x))) > 1e-9:
                continue
            gain = float(np.linalg.norm(sol.x - a))
            if gain > np.linalg.norm(b - a) + 0.5 * radius and (best is None or gain > best[0]):
                best = (gain, sol.x)
    return None if best is None else best[1]


def _path_max(eq: _Equations, xs: list[np.ndarray], w: np.ndarray, step: float, max_steps: int) -> float:
    """Follow the equilibrium path from the two states ``xs`` and return its largest ay.

    Each step fixes the weighted roll of the sprung masses (``w . X``, which grows along the loading path); where no
    state is found there (a fold in that roll, a kink) the step is retried shorter, and across the path's secant
    (pseudo-arclength) when even a short one fails."""
    h = step
    best = max(xs[0][-1], xs[1][-1])
    for _ in range(max_steps):
        a, b = xs[-2], xs[-1]
        t = (b - a) / np.linalg.norm(b - a)
        new = None
        while new is None:
            guess = b + h * t
            for origin, direction, offset in ((b, w, float(w @ (guess - b))), (b, t, h)):
                try:
                    new = _solve_on(eq, guess, origin, direction, offset)
                    break
                except ConvergenceError:
                    continue
            if new is None and h < 1e-6:  # a corner of the path: look all round the last point
                new = _around(eq, a, b, 10 * h)
            if new is None:
                if h < 1e-10:
                    raise ConvergenceError("the reference path could not be followed")
                h /= 4.0
        xs.append(new)
        h = min(step, 2.0 * h)
        best = max(best, new[-1])
        if new[-1] < best - 0.05 and eq.all_lifted(new):
            break
    k = int(np.argmax([x[-1] for x in xs]))
    lo, hi = xs[max(k - 1, 0)], xs[min(k + 1, len(xs) - 1)]
    top = xs[k]
    for _ in range(4):  # the largest ay between the neighbours, then again on a shorter chord around it
        span = float(np.linalg.norm(hi - lo))
        if span < 1e-13:
            break
        t = (hi - lo) / span

        def state(s, lo=lo, hi=hi, t=t, span=span):
            return _solve_on(eq, lo + (hi - lo) * s / span, lo, t, s)

        try:
            r = minimize_scalar(lambda s, state=state: -state(s)[-1], bounds=(0.0, span), method="bounded",
                                options={"xatol": 1e-14 * max(1.0, span)})  # fmt: skip
            best = state(r.x)
            if best[-1] > top[-1]:
                top = best
            delta = 0.05 * span
            lo, hi = state(max(r.x - delta, 0.0)), state(min(r.x + delta, span))
        except ConvergenceError:  # the chord left the path (a corner): keep the best state so far
            break
    return float(top[-1])


def reference_srt(
    c: Combination,
    *,
    bank_percent: float = 0.0,
    slope_percent: float = 0.0,
    load: UnitLoad | None = None,
    step: float = 0.002,
    max_steps: int = 4000,
) -> list[float]:
    """The largest ay of each roll-coupled unit, from the nonlinear equilibrium (see the module docstring) [g].

    The path starts leaning outward past every lash (the weighted roll of the sprung masses at rest without lash, plus
    1.5 times the largest lash and 0.005 rad), where every lash the loading takes up is taken up, so the snaps through
    the lashes near rest are behind it; it is found first without lash, where the equations are smooth, and followed
    with steps of ``step`` in that roll."""
    load = load or UnitLoad()
    out = []
    for members in roll_coupled_units(c):
        eq = _Equations(c, members, bank_percent, slope_percent, load)
        smooth = _Equations(c, members, bank_percent, slope_percent, load, lash=False)
        n = eq.nb + len(eq.groups)
        weights = np.array([eq.lu[u].weight_kn for u in eq.members])
        w = np.concatenate([weights / weights.sum(), np.zeros(n - eq.nb + 1)])
        e_ay = np.eye(n + 1)[-1]
        x0 = np.zeros(n + 1)
        x0[-1] = eq.sb * eq.cs / eq.cb  # ay at which the road plane feels no lateral force: at rest
        origin = np.zeros(n + 1)
        rest = _solve_on(smooth, x0, origin, e_ay, x0[-1])
        lash = max([math.radians(g.lash_deg) for u in members for g in c.units[u].groups]
                   + [math.radians(cp.lash_deg) for cp in c.couplings])  # fmt: skip
        p0 = float(w @ rest) + 1.5 * lash + 0.005
        start = _solve_on(eq, _solve_on(smooth, rest, origin, w, p0), origin, w, p0)
        first = _solve_on(eq, start + step * w / float(w @ w), origin, w, p0 + step)
        out.append(_path_max(eq, [start, first], w, step, max_steps))
    return out
