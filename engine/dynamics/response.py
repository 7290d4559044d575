"""Responses of the state space: exact discretisation, frequency response, eigenvalues, steady state.

* **Time response** (:func:`simulate`): the input held linear over each step (first-order hold), the step's
  transition by one matrix exponential of the augmented matrix, so the discrete response is exact for a
  piecewise-linear input (Franklin, Powell and Workman, *Digital Control of Dynamic Systems*, 3rd ed., Sec. 6.3);
  :func:`follow` prescribes one output instead (the steer axle's lateral acceleration) through the inverse
  system ``delta = (a - c x) / d``, possible because that output has a direct feedthrough ``d``.
* **The reduced state** (:func:`reduced`): the lateral position and heading of the first body do not act on
  anything (a straight path in any direction is an equilibrium); replacing ``(y_0, psi_0, y_0')`` by the body's
  lateral velocity ``v = y_0' - u psi_0`` leaves ``2n - 2`` states whose eigenvalues are the vehicle's modes, and
  whose equilibrium is the steady turn.
* **Frequency response** (:func:`frequency_response`): ``C (j w I - A_r)^-1 B_r + D`` on the reduced state.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg

from engine.dynamics.model import StateSpace


@dataclass(frozen=True)
class Reduced:
    """``z = E x``, ``x = L z`` (up to the free position and heading); ``z' = A z + B delta``."""

    A: np.ndarray
    B: np.ndarray
    E: np.ndarray
    L: np.ndarray


def reduced(ss: StateSpace) -> Reduced:
    """The reduced state ``z = (q[2:], v, r, q'[2:])`` with ``v = y_0' - u psi_0``, ``r = psi_0'``."""
    n = ss.model.n
    u = ss.speed_mps
    keep = [*range(2, n), n, n + 1, *range(n + 2, 2 * n)]
    E = np.zeros((2 * n - 2, 2 * n))
    L = np.zeros((2 * n, 2 * n - 2))
    for k, idx in enumerate(keep):
        E[k, idx] = 1.0
        L[idx, k] = 1.0
    kv = keep.index(n)
    E[kv, 1] = -u  # v = y0' - u psi0
    # invariance: A (e_psi0 + u e_y0') = 0 and A e_y0 = 0, so x' = A L z whatever psi_0 and y_0 are
    return Reduced(E @ ss.A @ L, E @ ss.B, E, L)


def eigen(ss: StateSpace) -> tuple[np.ndarray, np.ndarray, Reduced]:
    """Eigenvalues [1/s] and eigenvectors of the reduced state (the vehicle's modes)."""
    r = reduced(ss)
    w, v = np.linalg.eig(r.A)
    return w, v, r


def damping_ratio(lam: complex) -> float:
    """``-Re / |lambda|`` [-]."""
    return float(-lam.real / abs(lam)) if abs(lam) > 0 else 1.0


def least_damped_oscillatory(w: np.ndarray, min_imag: float = 1e-6) -> int | None:
    """Index of the oscillatory eigenvalue (positive imaginary part) with the smallest damping ratio."""
    idx = [k for k in range(len(w)) if w[k].imag > min_imag]
    if not idx:
        return None
    return min(idx, key=lambda k: damping_ratio(w[k]))


def steady_state(ss: StateSpace) -> tuple[np.ndarray, Reduced]:
    """The reduced equilibrium per unit road-wheel steer ``A_r z + B_r = 0`` [per rad]."""
    r = reduced(ss)
    z = np.linalg.solve(r.A, -r.B)
    return z, r


def frequency_response(ss: StateSpace, outputs: list[tuple[np.ndarray, float]], freqs_hz: np.ndarray) -> np.ndarray:
    """Complex gains of each output (C on x, D) per unit steer at each frequency: shape (outputs, freqs)."""
    r = reduced(ss)
    C = np.array([c for c, _ in outputs]) @ r.L
    D = np.array([d for _, d in outputs])
    n = r.A.shape[0]
    out = np.empty((len(outputs), len(freqs_hz)), dtype=complex)
    eye = np.eye(n)
    for k, f in enumerate(freqs_hz):
        x = np.linalg.solve(2j * np.pi * f * eye - r.A, r.B)
        out[:, k] = C @ x + D
    return out


def _foh(A: np.ndarray, B: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    n = A.shape[0]
    big = np.zeros((n + 2, n + 2))
    big[:n, :n] = A * dt
    big[:n, n] = B * dt
    big[n, n + 1] = 1.0
    e = scipy.linalg.expm(big)
    phi, g1, g2 = e[:n, :n], e[:n, n], e[:n, n + 1]
    return phi, g1 - g2, g2


def simulate(A: np.ndarray, B: np.ndarray, u: np.ndarray, dt: float, x0: np.ndarray | None = None) -> np.ndarray:
    """States at every sample of ``u`` (first-order hold, exact for an input linear between samples).

    The recursion ``x_k+1 = Phi x_k + w_k`` is summed as a prefix scan (Hillis and Steele 1986): at each of the
    ``log2(N)`` levels every partial sum takes the one ``2^j`` steps earlier through ``Phi^(2^j)``, one matrix
    product over all steps at once instead of ``N`` small ones.
    """
    phi, g0, g1 = _foh(A, B, dt)
    n_steps = len(u)
    s = np.zeros((n_steps, A.shape[0]))
    s[1:] = np.outer(u[:-1], g0) + np.outer(u[1:], g1)
    if x0 is not None:
        s[0] = x0
    power, shift = phi, 1
    while shift < n_steps:
        s[shift:] = s[shift:] + s[:-shift] @ power.T
        power = power @ power
        shift *= 2
    return s


def follow(ss: StateSpace, output: tuple[np.ndarray, float], target: np.ndarray, dt: float
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # fmt: skip
    """Steer so that ``output`` follows ``target`` exactly: (states, steer [rad], the inverse system's poles)."""
    c, d = output
    if abs(d) < 1e-12:
        raise ArithmeticError("the prescribed output has no direct feedthrough from the steer")
    Ai = ss.A - np.outer(ss.B, c) / d
    Bi = ss.B / d
    x = simulate(Ai, Bi, target, dt)
    delta = (target - x @ c) / d
    return x, delta, np.linalg.eigvals(Ai)
