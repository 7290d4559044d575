r"""The tractor-semitrailer's yaw-plane equations derived by hand: the independent check of the assembly.

Newton-Euler for each unit as one rigid body (mass ``m_i``, CG ``x_i`` behind its reference point, yaw inertia
``I_i`` about the CG), the hitch force ``H = sum_2 F - m_2 a_2`` (on the tractor, + left) eliminated; coordinates
``q = (y_1, psi_1, psi_2)``, the steer axle's lateral position and the two yaw angles; the kingpin at ``x_c``
behind the steer axle::

    a_1 = y_1'' - x_1 psi_1'',   a_2 = y_1'' - x_c psi_1'' - x_2 psi_2''
    m_1 a_1 + m_2 a_2                 = sum_1 F + sum_2 F
    I_1 psi_1'' - (x_c - x_1) m_2 a_2 = -sum_1 (x_k - x_1) F_k - (x_c - x_1) sum_2 F
    I_2 psi_2'' - x_2 m_2 a_2         = -sum_2 x_k F_k

with ``F_k = C_k (psi_i + delta_k - Y_k' / u)`` at every axle (Gillespie 1992, ch. 6, for the tyre law; the
articulated-vehicle equations as in Vlk, F. (1982), Lateral dynamics of commercial vehicle combinations - a
literature survey, Vehicle System Dynamics 11(6)). Its eigenvalues must equal the assembly's without roll.
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


def tractor_semitrailer_matrices(c: Combination, p: ResolvedParameters, speed_mps: float):
    """``(M, C, K, B)`` of the hand-derived equations (module docstring) for a two-unit combination."""
    if len(c.units) != 2 or c.units[1].kind not in ("semitrailer", "btrain-lead"):
        raise ValueError("the hand-derived equations are those of a tractor and a semitrailer")
    u = speed_mps
    m1, x1, i1 = unit_rigid_body(c, p, 0)
    m2, x2, i2 = unit_rigid_body(c, p, 1)
    xc = c.couplings[0].position_m
    a1 = np.array([1.0, -x1, 0.0])
    a2 = np.array([1.0, -xc, -x2])
    psi = [np.array([0.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0])]
    # rows of each equation: accelerations, and the force sums as (K-part, C-part, B-part) in F = kq q + cq q' + b
    M = np.zeros((3, 3))
    C = np.zeros((3, 3))
    K = np.zeros((3, 3))
    B = np.zeros(3)
    M[0] = m1 * a1 + m2 * a2
    M[1] = i1 * psi[0] - (xc - x1) * m2 * a2
    M[2] = i2 * psi[1] - x2 * m2 * a2
    for (i, j), gp in p.groups.items():
        steer = c.units[i].groups[j].steer
        for x, ck in zip(gp.axle_positions_m, gp.cornering_stiffness_kn_per_rad, strict=True):
            cn = ck * 1000.0
            J = np.array([1.0, -x, 0.0]) if i == 0 else np.array([1.0, -xc, -x])
            # F = cn (psi_i q + delta - J q' / u): on the right side; moved to the left: K -= cn psi, C += cn J/u
            coef = np.zeros(3)
            if i == 0:
                coef[0] = 1.0
                coef[1] = -(x - x1)
            else:
                coef[0] = 1.0
                coef[1] = -(xc - x1)  # through the hitch force
                coef[2] = -x
            for row in range(3):
                K[row] -= coef[row] * cn * psi[i]
                C[row] += coef[row] * cn * J / u
                if steer:
                    B[row] += coef[row] * cn
    return M, C, K, B


def state_matrix(M: np.ndarray, C: np.ndarray, K: np.ndarray) -> np.ndarray:
    n = M.shape[0]
    Minv = np.linalg.inv(M)
    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    A[n:, :n] = -Minv @ K
    A[n:, n:] = -Minv @ C
    return A
