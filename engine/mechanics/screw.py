"""Screw theory: successive screw displacements and unit wrenches (Appendix A.1, Eq. 3.4).

Conventions follow the thesis: a wrench is written moment-first, ``$ = [Mx, My, Mz, Fx, Fy, Fz]``
(Eq. A.5), all expressed in the inertial (road) frame about its origin.

References
----------
Tsai, L.-W. (1999) *Robot Analysis*, Sec. 2.6 (screw displacement); Davies (1983); thesis App. A.
"""

from __future__ import annotations

import math

import numpy as np


def screw_matrix(s, s0, theta: float = 0.0, d: float = 0.0) -> np.ndarray:
    """4x4 homogeneous matrix of a screw displacement (Eqs. A.1-A.4).

    A rotation ``theta`` [rad] about the axis of unit direction ``s`` through the point ``s0`` [m],
    followed by a translation ``d`` [m] along ``s``. ``p2 = A @ p1`` (Eq. A.1).
    """
    sx, sy, sz = (float(c) for c in s)
    s0x, s0y, s0z = (float(c) for c in s0)
    c, sn = math.cos(theta), math.sin(theta)
    v = 1.0 - c
    a11 = (sx * sx - 1.0) * v + 1.0  # Eq. A.3
    a12 = sx * sy * v - sz * sn
    a13 = sx * sz * v + sy * sn
    a21 = sy * sx * v + sz * sn
    a22 = (sy * sy - 1.0) * v + 1.0
    a23 = sy * sz * v - sx * sn
    a31 = sz * sx * v - sy * sn
    a32 = sz * sy * v + sx * sn
    a33 = (sz * sz - 1.0) * v + 1.0
    a14 = d * sx - s0x * (a11 - 1.0) - s0y * a12 - s0z * a13  # Eq. A.4
    a24 = d * sy - s0x * a21 - s0y * (a22 - 1.0) - s0z * a23
    a34 = d * sz - s0x * a31 - s0y * a32 - s0z * (a33 - 1.0)
    return np.array([[a11, a12, a13, a14], [a21, a22, a23, a24], [a31, a32, a33, a34], [0.0, 0.0, 0.0, 1.0]])


def successive(*matrices: np.ndarray) -> np.ndarray:
    """Product A_1 A_2 ... A_n of successive screw displacements (Table 4, Table 9)."""
    out = np.eye(4)
    for m in matrices:
        out = out @ m
    return out


def unit_force(direction, point) -> np.ndarray:
    """Normalized wrench of a force of unit magnitude along ``direction`` through ``point`` (Eq. A.6).

    ``$ = [s0 x s; s]``. Eq. 3.4 lists the same six columns for the three force and three moment
    constraints of a joint at (x, y, z).
    """
    s = np.asarray(direction, dtype=float)
    s = s / np.linalg.norm(s)
    return np.concatenate((np.cross(np.asarray(point, dtype=float), s), s))


def unit_couple(direction) -> np.ndarray:
    """Normalized wrench of a pure moment (couple) about ``direction`` (Eq. A.7): ``$ = [s; 0]``."""
    s = np.asarray(direction, dtype=float)
    return np.concatenate((s / np.linalg.norm(s), np.zeros(3)))


def rot_x(angle: float) -> np.ndarray:
    """3x3 rotation about x (a screw with s = (1, 0, 0), the axis of every revolute of Tables 3 and 8)."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
