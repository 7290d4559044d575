r"""Yaw-plane equations derived by hand: the independent check of the assembly (:func:`chain_matrices`).

For a tractor-semitrailer the equations read as below (:func:`chain_matrices` writes them for any chain of
single-body units). Newton-Euler for each unit as one rigid body (mass ``m_i``, CG ``x_i`` behind its reference
point, yaw inertia ``I_i`` about the CG), the hitch force ``H = sum_2 F - m_2 a_2`` (on the tractor, + left)
eliminated; coordinates ``q = (y_1, psi_1, psi_2)``, the steer axle's lateral position and the two yaw angles; the
kingpin at ``x_c`` behind the steer axle::

    a_1 = y_1'' - x_1 psi_1'',   a_2 = y_1'' - x_c psi_1'' - x_2 psi_2''
    m_1 a_1 + m_2 a_2                 = sum_1 F + sum_2 F
    I_1 psi_1'' - (x_c - x_1) m_2 a_2 = -sum_1 (x_k - x_1) F_k - (x_c - x_1) sum_2 F
    I_2 psi_2'' - x_2 m_2 a_2         = -sum_2 x_k F_k

with ``F_k = C_k (psi_i + delta_k - Y_k' / u)`` at every axle (Gillespie 1992, ch. 6, for the tyre law; the
articulated-vehicle equations as in Vlk, F. (1982), Lateral dynamics of commercial vehicle combinations - a
literature survey, Vehicle System Dynamics 11(6)). Their eigenvalues must equal the assembly's without roll
(:func:`engine.dynamics.model.build` with ``roll=False``), which reaches them by another route: virtual work on the
kinetic energy of every mass, the couplings as constraints eliminated by a null-space map.
"""

from __future__ import annotations

import numpy as np

from engine.dynamics.parameters import ResolvedParameters, unit_total_mass_kg
from engine.vehicle.combination import Combination


def unit_rigid_body(c: Combination, p: ResolvedParameters, i: int) -> tuple[float, float, float]:
    """Mass [kg], CG behind the reference [m] and yaw inertia about the CG [kg m^2] of unit ``i`` as one body."""
    u = c.units[i]
    pts = [(u.sprung_mass_kg, u.cg_position_m)]
    for j, g in enumerate(u.groups):
        pts += [(g.unsprung_mass_kg, x) for x in p.groups[(i, j)].axle_positions_m]
    m = unit_total_mass_kg(c, i)
    xc = sum(mm * x for mm, x in pts) / m
    iz = p.units[i].yaw_inertia_kgm2.value + sum(mm * (x - xc) ** 2 for mm, x in pts)
    return m, xc, iz


def chain_matrices(c: Combination, p: ResolvedParameters, speed_mps: float):
    """``(M, C, K, B)`` of the hand-derived equations of a chain of single-body units (any combination without a
    full trailer's turntable): Newton-Euler per unit with the hitch forces eliminated from the rear forward.

    Coordinates ``q = (y_1, psi_1, ..., psi_n)``: the steer axle's lateral position and every unit's yaw. The
    reference point of unit ``i`` is at ``y_1 - sum_{k<i} x_c,k psi_k``; the hitch force ``H_i`` (on unit ``i`` at
    its reference point, from the unit ahead) follows from unit ``i``'s lateral balance,
    ``H_i = m_i a_i - sum_i F + H_i+1`` (``H_n+1 = 0``); the equations are the first unit's lateral balance
    (``H_1 = 0``) and every unit's yaw balance about its CG,
    ``I_i psi_i'' = -sum_i (x_k - x_i) F_k + x_i H_i + (x_c,i - x_i) H_i+1``.
    """
    if any(u.kind == "full-trailer" for u in c.units):
        raise ValueError("the hand-derived chain has one yaw body per unit (no full trailer's turntable)")
    n = len(c.units)
    nq = n + 1
    u = speed_mps

    def e(k: int) -> np.ndarray:
        v = np.zeros(nq)
        v[k] = 1.0
        return v

    ref = [e(0)]
    for i in range(1, n):
        ref.append(ref[i - 1] - c.couplings[i - 1].position_m * e(i))
    zero = (np.zeros(nq), np.zeros(nq), np.zeros(nq), 0.0)

    def add(a, b, scale=1.0):  # linear forms (on q'', q', q, delta)
        return (a[0] + scale * b[0], a[1] + scale * b[1], a[2] + scale * b[2], a[3] + scale * b[3])

    bodies = [unit_rigid_body(c, p, i) for i in range(n)]
    inertial = [(m * (ref[i] - x * e(i + 1)), np.zeros(nq), np.zeros(nq), 0.0) for i, (m, x, _) in enumerate(bodies)]
    forces: list[list[tuple[float, tuple]]] = [[] for _ in range(n)]  # per unit: (x_k, F_k as a linear form)
    for (i, j), gp in p.groups.items():
        steer = c.units[i].groups[j].steer
        for x, ck in zip(gp.axle_positions_m, gp.cornering_stiffness_kn_per_rad, strict=True):
            cn = ck * 1000.0
            J = ref[i] - x * e(i + 1)  # F = C (psi_i + delta - J q' / u)
            forces[i].append((x, (np.zeros(nq), -cn * J / u, cn * e(i + 1), cn if steer else 0.0)))
    total = [zero] * n
    for i in range(n):
        for _, fk in forces[i]:
            total[i] = add(total[i], fk)
    hitch = [zero] * (n + 1)  # H_i for i = 0..n (H_0 unused, H_n = 0 past the last unit)
    for i in range(n - 1, 0, -1):
        hitch[i] = add(add(inertial[i], total[i], -1.0), hitch[i + 1])
    rows = [add(add(inertial[0], total[0], -1.0), hitch[1])]  # the first unit's lateral balance
    for i, (_, xi, iz) in enumerate(bodies):
        r = (iz * e(i + 1), np.zeros(nq), np.zeros(nq), 0.0)
        for x, fk in forces[i]:
            r = add(r, fk, (x - xi))  # + (x_k - x_i) F_k on the left
        if i > 0:
            r = add(r, hitch[i], -xi)
        if i + 1 < n:
            r = add(r, hitch[i + 1], -(c.couplings[i].position_m - xi))
        rows.append(r)
    M = np.array([r[0] for r in rows])
    C = np.array([r[1] for r in rows])
    K = np.array([r[2] for r in rows])
    B = -np.array([r[3] for r in rows])
    return M, C, K, B


def state_matrix(M: np.ndarray, C: np.ndarray, K: np.ndarray) -> np.ndarray:
    n = M.shape[0]
    Minv = np.linalg.inv(M)
    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    A[n:, :n] = -Minv @ K
    A[n:, n:] = -Minv @ C
    return A
