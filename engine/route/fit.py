"""Least-squares circle (Chernov 2010: Kasa's fit, then Gauss-Newton) and line fits of route vertices."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import ndtri

from engine.errors import InvalidInput
from engine.route.noise import absorbed_excess, variance_inflation

#: one-sided confidence of the conservative radius of a route's curve (:func:`radius_lower_bound_m`)
RADIUS_CONFIDENCE = 0.95

# ----------------------------------------------------------------------------------- circle fit


@dataclass(frozen=True)
class CircleFit:
    xc_m: float
    yc_m: float
    radius_m: float
    rms_m: float  # root-mean-square distance of the points from the circle
    radius_std_m: float | None  # standard error of the radius (None with 3 points and no known noise)
    n_points: int = 0
    radius_lower_m: float | None = None  # a lower confidence bound of the radius when the fit gives its own


def fit_circle(
    x_m, y_m, *, iterations: int = 10, noise_m: float | None = None, chain_m=None, corr_m: float = 0.0
) -> CircleFit:
    """Geometric least-squares circle through points (Gauss-Newton from Kasa's algebraic fit) [1].

    Minimises sum (|p_i - c| - R)^2. The points are centred first, so routes far from the origin keep their
    precision. The radius's standard error is sqrt(s^2 [(J^T J)^-1]_RR), J the Jacobian of the distances in
    (xc, yc, R) [1]: s^2 is the residual variance sum r^2 / (n - 3), or, when the points' noise sigma is known
    from elsewhere (``noise_m``: the whole track's estimate, from hundreds of vertices), the larger of sigma^2 and
    that variance. A handful of vertices leaves the residual variance with a few degrees of freedom: with 4 points
    (1 degree) it is below a tenth of sigma^2 one time in four, and such a fit would claim a precision it does not
    have; the larger of the two keeps a misfit of the model (residuals above the noise) counted.

    Noise correlated along the track over ``corr_m`` (Eq. 3 of :mod:`engine.route.noise`; ``chain_m`` the points'
    chainages) leaves the estimate the least-squares one and makes its variance the sandwich: [(J^T J)^-1]_RR times
    the variance inflation of R's influence on the points' radial displacements
    (:func:`engine.route.noise.variance_inflation`); the residual variance's divisor n - 3 loses what the fit absorbs
    of correlated noise beyond 3 degrees of freedom (:func:`engine.route.noise.absorbed_excess`). A few correlated
    points on a short arc then count as the few independent ones they are.

    Parameters
    ----------
    x_m, y_m : array_like
        At least 3 points [m].
    iterations : int
        Gauss-Newton iterations at most.
    noise_m : float or None
        Known position noise of the points, if any [m].
    chain_m : array_like or None
        Chainage of the points along the track, sorted [m] (needed with ``corr_m``).
    corr_m : float, default 0
        Correlation length of the points' noise along the track [m]; 0 for white noise.
    """
    x, y = np.asarray(x_m, dtype=float), np.asarray(y_m, dtype=float)
    if x.size < 3:
        raise InvalidInput(f"a circle needs at least 3 points, got {x.size}", field="points", value=int(x.size))
    x0, y0 = x.mean(), y.mean()
    u, v = x - x0, y - y0
    scale = max(float(np.sqrt(np.mean(u * u + v * v))), 1e-12)
    u, v = u / scale, v / scale
    # Kasa: u^2 + v^2 + D u + E v + F = 0 in the least-squares sense
    a = np.column_stack((u, v, np.ones_like(u)))
    sol, *_ = np.linalg.lstsq(a, -(u * u + v * v), rcond=None)
    a_c, b_c = -sol[0] / 2, -sol[1] / 2
    r = math.sqrt(max(a_c * a_c + b_c * b_c - sol[2], 1e-12))
    p = np.array([a_c, b_c, r])
    for _ in range(iterations):
        du, dv = u - p[0], v - p[1]
        d = np.maximum(np.hypot(du, dv), 1e-15)
        res = d - p[2]
        jac = np.column_stack((-du / d, -dv / d, -np.ones_like(d)))
        try:
            step = np.linalg.solve(jac.T @ jac, -(jac.T @ res))
        except np.linalg.LinAlgError:
            break
        p = p + step
        if np.all(np.abs(step) <= 1e-10 * (1.0 + np.abs(p))):
            break
    du, dv = u - p[0], v - p[1]
    d = np.hypot(du, dv)
    res = d - p[2]
    rms = float(np.sqrt(np.mean(res * res))) * scale
    std = None
    if x.size > 3 or noise_m is not None:
        jac = np.column_stack((-du / d, -dv / d, -np.ones_like(d)))
        factor, excess = 1.0, 0.0
        if corr_m > 0 and chain_m is not None:
            chain = np.asarray(chain_m, dtype=float)
            normals = np.column_stack((du / d, dv / d))
            try:
                a = (np.linalg.inv(jac.T @ jac) @ jac.T)[2]
                factor = variance_inflation(chain, a, corr_m, normals)
                excess = absorbed_excess(chain, jac, corr_m, normals)
            except np.linalg.LinAlgError:
                pass
        s2 = float(res @ res) / max(x.size - 3 - excess, 1.0) if x.size > 3 else 0.0
        if noise_m is not None:
            s2 = max(s2, (float(noise_m) / scale) ** 2)  # res is in units of scale
        try:
            cov = np.linalg.inv(jac.T @ jac) * s2
            std = float(math.sqrt(max(cov[2, 2] * factor, 0.0))) * scale
        except np.linalg.LinAlgError:
            std = None
    return CircleFit(x0 + p[0] * scale, y0 + p[1] * scale, abs(p[2]) * scale, rms, std, int(x.size))


def fit_line(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Total least-squares line: a point on it and its unit direction, oriented from the first point."""
    cx, cy = float(x.mean()), float(y.mean())
    dx, dy = x - cx, y - cy
    angle = 0.5 * math.atan2(2.0 * float(dx @ dy), float(dx @ dx) - float(dy @ dy))  # principal axis
    u = np.array([math.cos(angle), math.sin(angle)])
    if u[0] * (x[-1] - x[0]) + u[1] * (y[-1] - y[0]) < 0:
        u = -u
    return np.array([cx, cy]), u


def radius_lower_bound_m(radius_m: float, radius_std_m: float | None, confidence: float = RADIUS_CONFIDENCE) -> float:
    """One-sided lower confidence bound of a fitted radius: the true radius is at least this with ``confidence``.

    The bound is taken on the curvature kappa = 1 / R, the quantity a fit through noisy vertices measures with a
    nearly normal error (the offsets of the vertices from a tangent are linear in kappa: the middle ordinate is
    L^2 kappa / 8 to first order, whereas R's error is skewed toward flat arcs and unbounded as kappa -> 0 [1]).
    With sigma_kappa = sigma_R / R^2 (delta method) and z the normal quantile of ``confidence`` (1.645 for 95 %),

        kappa_upper = 1 / R + z sigma_R / R^2,   R_lower = 1 / kappa_upper = R / (1 + z sigma_R / R),

    which is R - z sigma_R to first order, positive, and never above R. Without a standard error (no noise: the
    radius is exact) the bound is the radius itself.

    Parameters
    ----------
    radius_m : float
        Fitted radius R [m].
    radius_std_m : float or None
        Its standard error sigma_R; None or 0 when exact [m].
    confidence : float, default 0.95
        One-sided confidence level, in (0.5, 1) [-].

    Returns
    -------
    float
        R_lower [m].

    References
    ----------
    [1] N. Chernov (2010), Circular and Linear Regression, CRC Press, ch. 6-7 (the radius estimate's heavy tail
        for small arcs; curvature-based parametrisation).
    """
    if not 0.5 < confidence < 1.0:
        raise InvalidInput(f"confidence must be in (0.5, 1), got {confidence}", field="confidence", value=confidence)
    if radius_std_m is None or not math.isfinite(radius_std_m) or radius_std_m <= 0.0:
        return float(radius_m)
    z = float(ndtri(confidence))
    return float(radius_m / (1.0 + z * radius_std_m / radius_m))
