"""Noise model of a surveyed polyline: curvature and heading noise of Gaussian-smoothed GPS vertices
(Eq. 1 of :mod:`engine.route.detect`), and the position noise estimated from the vertices themselves.

The noise model
---------------
A GPS receiver's error drifts rather than jumping fix to fix: consecutive fixes share much of their error. The
lateral error e_i of vertex i (the component normal to the road, the only one that moves a fitted curve to first
order) is modelled as a stationary Gauss-Markov (first-order autoregressive) sequence along the track:

    Var e_i = sigma^2,   Corr(e_i, e_j) = exp(-|s_i - s_j| / L)                                         (Eq. 3)

s the chainage, L the correlation length; at a vertex spacing h the lag-one correlation is rho = exp(-h / L), and
L = 0 (rho = 0) is white noise. Each axis of a receiver's error is such a sequence (tests/synthetic_routes.
gauss_markov), and so is its projection on any fixed direction.

Estimating sigma and L
----------------------
*From the tangents* (:func:`residual_noise`, what :func:`engine.route.detect.find_curves` uses once a first pass
has found the curves): the normal offsets of the vertices of every straight stretch the curves leave, each with its
own line (offset and slope) as fixed effects, by restricted maximum likelihood under Eq. 3. The line absorbs the
low-frequency part of correlated noise, which a plain variance of the residuals would miss; the restricted
likelihood counts it. The Ornstein-Uhlenbeck sequence is Markov, so its innovations
z_i = (y_i - phi_i y_{i-1}) / sqrt(1 - phi_i^2), phi_i = exp(-(s_i - s_{i-1}) / L), whiten it exactly (P^-1/2, with
log|P| = sum log(1 - phi_i^2)) and the likelihood costs O(n). On the tangents the geometry is known at every lag up
to their length, so sigma and L are both identified once they are a few L long. White noise is kept unless the
correlation lowers the deviance by more than :data:`CORRELATION_SIGNIFICANCE` squared (a likelihood-ratio test of one
parameter at 3 standard deviations).

*From the differences* (:func:`estimate_noise`: the first pass, and the fallback when no tangent is long enough).
The Menger curvature of a vertex triple (i - m, i, i + m) is exactly 1/R for noise-free vertices on a circle or a
line, at any spacing m; the change of that curvature between the triples at i and i + m, times a b / 2 (a, b the
triple's sides), is therefore pure noise away from tangent points and spirals: to first order it is half the
third difference of the lateral errors at lag m, (-e_{i-m} + 3 e_i - 3 e_{i+m} + e_{i+2m}) / 2. Under Eq. 3 its
variance is

    V_m = sigma^2 g(rho^m) / 4,   g(r) = 20 - 30 r + 12 r^2 - 2 r^3                                      (Eq. 4)

(sum_jk c_j c_k r^|j - k| for c = (-1, 3, -3, 1)): 5 sigma^2 for white noise at every lag, while correlated errors
cancel in the differences at short lags (g(0.82) = 2.4: a lag-one estimate that assumes whiteness reads 0.35 sigma
when L is five vertex spacings). The variances at lags m = 1 .. :data:`NOISE_LAGS` are measured (mean of squares of
the differences, after dropping every window that touches a difference the lag-:data:`NOISE_LAGS` median absolute
deviation marks as an outlier at 3 standard deviations: a tangent point or a spiral, whose curvature change is
geometry, not noise), and (sigma^2, rho) are fitted to Eq. 4 by weighted least squares on log V_m, the weights the
inverse sampling variances of log V_m under white noise, 4.62 / N_m (2 sum_k c_k^2 / N_m for a Gaussian sequence,
sum_k c_k^2 = 2.31 the autocorrelation of the differences, N_m the number of differences). Correlation is accepted
only when the fit lowers the weighted sum of squares of white noise (rho = 0) by more than
:data:`CORRELATION_SIGNIFICANCE` squared (it ignores the positive correlation between lags, which makes it conservative
toward whiteness); otherwise the noise is white and sigma is the lag-one median absolute deviation, robust to
tangent points (:func:`vertex_noise_m`, the estimate the method always used).

What the differences cannot tell: at lags much shorter than L the errors are a random walk, V_m = 3 sigma^2 m h / L
to third order in m h / L, which fixes sigma^2 / L but neither alone. The fit's rho is therefore bounded at a
correlation length of 3 :data:`NOISE_LAGS` vertex spacings, the span of the longest difference, and on a short
track the estimate scatters widely along that ridge (measured: a 1.1 km track with 3 m noise correlated over 50 m
gives L anywhere from 20 to the bound); this is why the tangents' likelihood decides.

Using the model
---------------
* *Smoothed curvature and heading* (Eq. 1 and its first-derivative counterpart) scale by the ratio of the AR(1)
  spectrum to white noise's, weighted by the Gaussian derivative's squared transfer function
  (:func:`correlation_ratio`): S(w) / (sigma^2 h) = (1 - rho^2) / (1 - 2 rho cos(w h) + rho^2).
* *Least-squares fits* (the tangents' lines, the circle, the tangent-curve path): the estimate stays the ordinary
  least-squares one, and its variance is the sandwich a^T Sigma a, a the estimate's influence on each vertex's
  normal displacement (row of (J^T J)^-1 J^T) and Sigma_ij = sigma^2 exp(-|s_i - s_j| / L) n_i . n_j (n_i the
  unit normal at vertex i: the lateral errors of vertices whose normals differ are the projections of one 2-D
  error on different directions). Written as sigma^2 |a|^2 times the variance inflation
  a^T P a / a^T a (:func:`variance_inflation`): for the mean of n vertices under AR(1) that is
  (1 + rho) / (1 - rho) when n >> 1 / (1 - rho), the familiar n_eff = n (1 - rho) / (1 + rho); for a line's slope or
  an arc's radius the influence changes sign along the fit and the factor is computed from it, not assumed.
  The residual variance of a fit of p parameters has expectation sigma^2 (n - tr(H P)) / n, H the hat matrix: the
  fit absorbs more of correlated noise than the p of white noise, and the divisor is corrected by that excess.
  For white noise (L = 0) every factor is exactly 1.

References
----------
.. [4] G. E. P. Box, G. M. Jenkins, G. C. Reinsel (2008), Time Series Analysis, 4th ed., Wiley: the AR(1) process,
   its spectrum and the variance of a mean under autocorrelation.
.. [5] H. White (1980), A heteroskedasticity-consistent covariance matrix estimator, Econometrica 48; the sandwich
   covariance (J^T J)^-1 J^T Sigma J (J^T J)^-1 of least squares under a known error covariance.
.. [6] N. Cressie (1993), Statistics for Spatial Data, Wiley, ch. 2: variograms of increments and their fit.
.. [7] H. D. Patterson, R. Thompson (1971), Recovery of inter-block information when block sizes are unequal,
   Biometrika 58: restricted (residual) maximum likelihood.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: Eq. 1 constant: integral of the squared second derivative of a unit Gaussian, 3 / (8 sqrt(pi))
G2 = 3.0 / (8.0 * math.sqrt(math.pi))
#: and of the squared first derivative, 1 / (4 sqrt(pi)) (heading noise)
G1 = 1.0 / (4.0 * math.sqrt(math.pi))
#: heading noise allowed after the light smoothing that precedes the heading (step 3) [rad]
HEADING_NOISE_RAD = 0.03
#: the lags (in vertices) at which the variance of the noise's third differences is measured (Eq. 4)
NOISE_LAGS = 6
#: correlation is accepted when its fit beats white noise by this many standard deviations (likelihood ratio)
CORRELATION_SIGNIFICANCE = 3.0


@dataclass(frozen=True)
class NoiseModel:
    """Position noise of a track's vertices (Eq. 3): sigma [m], correlation length L [m] (0: white)."""

    sigma_m: float
    corr_m: float = 0.0
    spacing_m: float = 1.0  # median vertex spacing h [m]

    @property
    def rho(self) -> float:
        """Correlation of neighbouring vertices, exp(-h / L) [-]."""
        return math.exp(-self.spacing_m / self.corr_m) if self.corr_m > 0 else 0.0


# ------------------------------------------------------------------------------------ noise model


def correlation_ratio(spacing_m: float, scale_m: float, corr_m: float, order: int) -> float:
    """Variance of the Gaussian-smoothed ``order``-th derivative of AR(1) noise (Eq. 3) over that of white noise of
    the same sigma [-]: the AR(1) spectrum relative to white noise's, (1 - rho^2) / (1 - 2 rho cos(w h) + rho^2),
    averaged with the weight w^(2 order) exp(-w^2 tau^2) of the derivative filter's squared transfer function
    (Parseval; the white integrals are those of Eq. 1). 1 for white noise; (1 + rho) / (1 - rho) when tau >> L.

    Parameters
    ----------
    spacing_m : float
        Vertex spacing h [m].
    scale_m : float
        Smoothing scale tau [m].
    corr_m : float
        Correlation length L [m]; 0 for white noise.
    order : int
        1 for the heading, 2 for the curvature.
    """
    if corr_m <= 0 or scale_m <= 0:
        return 1.0
    rho = math.exp(-spacing_m / corr_m)
    u = np.linspace(0.0, 7.0, 701)  # w tau; the weight is below 1e-17 beyond 7
    weight = u ** (2 * order) * np.exp(-u * u)
    wh = u * (spacing_m / scale_m)
    spectrum = (1.0 - rho * rho) / (1.0 - 2.0 * rho * np.cos(wh) + rho * rho)
    return float(np.sum(weight * spectrum) / np.sum(weight))


def curvature_noise_per_m(noise_m: float, spacing_m: float, scale_m, corr_m: float = 0.0):
    """Standard deviation of the Gaussian-smoothed curvature from position noise [1/m] (Eq. 1).

    sd = sigma sqrt(h int G''^2) = sigma sqrt(3 h / (8 sqrt(pi))) tau^-2.5 for white lateral noise sigma at vertex
    spacing h and a Gaussian of standard deviation tau (valid for tau several times h); noise correlated over
    ``corr_m`` (Eq. 3) multiplies the variance by :func:`correlation_ratio`.

    Parameters
    ----------
    noise_m : float
        Position noise sigma of the vertices [m].
    spacing_m : float
        Vertex spacing h [m].
    scale_m : float or array_like
        Smoothing scale tau [m].
    corr_m : float, default 0
        Correlation length of the noise [m]; 0 for white noise.
    """
    sd = noise_m * np.sqrt(G2 * spacing_m) * np.asarray(scale_m, dtype=float) ** -2.5  # Eq. 1
    if corr_m > 0:
        ratio = np.vectorize(lambda t: correlation_ratio(spacing_m, float(t), corr_m, 2))(scale_m)
        sd = sd * np.sqrt(ratio)
    return sd


def heading_noise_rad(noise_m: float, spacing_m: float, scale_m, corr_m: float = 0.0):
    """Standard deviation of the Gaussian-smoothed heading from position noise [rad].

    sd = sigma sqrt(h / (4 sqrt(pi))) tau^-1.5 (the first-derivative counterpart of Eq. 1), times the square root of
    :func:`correlation_ratio` for correlated noise.

    Parameters
    ----------
    noise_m : float
        Position noise sigma [m].
    spacing_m : float
        Vertex spacing h [m].
    scale_m : float or array_like
        Smoothing scale tau [m].
    corr_m : float, default 0
        Correlation length of the noise [m]; 0 for white noise.
    """
    sd = noise_m * np.sqrt(G1 * spacing_m) * np.asarray(scale_m, dtype=float) ** -1.5
    if corr_m > 0:
        ratio = np.vectorize(lambda t: correlation_ratio(spacing_m, float(t), corr_m, 1))(scale_m)
        sd = sd * np.sqrt(ratio)
    return sd


def _third_differences(x: np.ndarray, y: np.ndarray, m: int) -> np.ndarray:
    """Changes of the Menger curvature between the vertex triples (i - m, i, i + m) and (i, i + m, i + 2m), times
    the mean of a b / 2: half the lateral errors' third difference at lag m (Eq. 4); element j spans vertices
    j .. j + 3m."""
    dx, dy = x[m:] - x[:-m], y[m:] - y[:-m]
    seg = np.hypot(dx, dy)
    a, b = seg[:-m], seg[m:]
    c = np.hypot(x[2 * m :] - x[: -2 * m], y[2 * m :] - y[: -2 * m])
    cross = dx[:-m] * dy[m:] - dy[:-m] * dx[m:]
    with np.errstate(divide="ignore", invalid="ignore"):
        k = np.where(c > 0, 2.0 * cross / (a * b * c), 0.0)  # Menger curvature
    w = a * b / 2.0
    return (k[m:] - k[:-m]) * 0.5 * (w[m:] + w[:-m])


def third_difference_factor(r):
    """g(r) / 4 of Eq. 4: the variance of :func:`_third_differences` over sigma^2, r = rho^m [-]."""
    r = np.asarray(r, dtype=float)
    return (20.0 - 30.0 * r + 12.0 * r * r - 2.0 * r**3) / 4.0


def _mad_sigma(r: np.ndarray) -> float:
    return float(1.4826 * np.median(np.abs(r - np.median(r))))


def vertex_noise_m(x_m, y_m) -> float:
    """Robust estimate of the position noise sigma of polyline vertices as white noise [m] (step 1 of the method).

    The Menger curvature k of each vertex triple is 1/R for noise-free points on a circle at any spacing;
    the differences of k between neighbouring triples, times the mean of a b / 2 (a, b the triple's two
    segment lengths), have variance 5 sigma^2 under white lateral noise sigma (Eq. 4 at rho = 0).
    sigma = 1.4826 MAD / sqrt(5). Returns 0 for fewer than 8 vertices. Correlated noise cancels in these
    differences (Eq. 4): :func:`residual_noise` and :func:`estimate_noise` allow for it.

    Parameters
    ----------
    x_m, y_m : array_like
        Vertices, consecutive vertices distinct [m].
    """
    x, y = np.asarray(x_m, dtype=float), np.asarray(y_m, dtype=float)
    if x.size < 8:
        return 0.0
    return _white_sigma(_third_differences(x, y, 1))


def _white_sigma(r1: np.ndarray) -> float:
    """Lag-one estimate under white noise: the differences have variance 5 sigma^2; sigma = 1.4826 MAD / sqrt(5)."""
    return _mad_sigma(r1) / math.sqrt(5.0)


def estimate_noise(x_m, y_m) -> NoiseModel:
    """Position noise of polyline vertices: sigma and the correlation length of Eq. 3 (see the module docstring).

    Returns sigma 0 for fewer than 8 vertices (and for exact vertices, a surveyed centreline).

    Parameters
    ----------
    x_m, y_m : array_like
        Vertices, consecutive vertices distinct [m].
    """
    x, y = np.asarray(x_m, dtype=float), np.asarray(y_m, dtype=float)
    if x.size < 8:
        return NoiseModel(0.0)
    h = float(np.median(np.hypot(np.diff(x), np.diff(y))))
    r1 = _third_differences(x, y, 1)
    white = NoiseModel(_white_sigma(r1), 0.0, h)
    lags = min(NOISE_LAGS, (x.size - 1) // 6)  # at least twice as many differences as the span of one
    if lags < 3 or white.sigma_m <= 0:
        return white
    diffs = [r1] + [_third_differences(x, y, m) for m in range(2, lags + 1)]
    top = diffs[-1]
    bad = np.zeros(x.size + 1, dtype=int)
    scale = _mad_sigma(top)
    for j in np.flatnonzero(np.abs(top - np.median(top)) > 3.0 * scale):  # geometry: drop its windows at every lag
        bad[j] += 1
        bad[j + 3 * lags + 1] -= 1
    covered = np.concatenate(([0], np.cumsum(np.cumsum(bad)[:-1] > 0)))  # vertices flagged before index i
    var, count = [], []
    for m, r in enumerate(diffs, start=1):
        j = np.arange(r.size)
        r = r[covered[j + 3 * m + 1] - covered[j] == 0]
        if r.size < 3 * m + 2:
            return white
        r = r[np.abs(r) <= 4.0 * _mad_sigma(r)]  # the tails beyond 4 sd: outliers (a Gaussian loses 6e-5 of them)
        var.append(float(np.mean(r * r)) / 0.99893)  # E[r^2 | |r| <= 4 sd] = 0.99893 sd^2
        count.append(r.size)
    v, n = np.array(var), np.array(count, dtype=float)
    if not np.all(v > 0):
        return white
    ms = np.arange(1, lags + 1)
    weight = n / 4.62  # inverse sampling variance of log V_m under white noise
    logv = np.log(v)
    rho_max = math.exp(-1.0 / (3.0 * lags))  # L at most the span of the longest difference, 3 lags h

    def fit(rho: float) -> tuple[float, float]:
        lg = np.log(third_difference_factor(rho**ms))
        log_s2 = float(np.sum(weight * (logv - lg)) / np.sum(weight))
        return float(np.sum(weight * (logv - lg - log_s2) ** 2)), log_s2

    rhos = np.linspace(0.0, rho_max, 200)
    q = np.array([fit(r)[0] for r in rhos])
    i = int(np.argmin(q))
    if q[0] - q[i] <= CORRELATION_SIGNIFICANCE**2:
        return white
    lo, hi = rhos[max(i - 1, 0)], rhos[min(i + 1, rhos.size - 1)]
    for _ in range(30):  # golden-section refinement inside the grid's bracket
        a, b = lo + 0.382 * (hi - lo), lo + 0.618 * (hi - lo)
        if fit(a)[0] < fit(b)[0]:
            hi = b
        else:
            lo = a
    rho = 0.5 * (lo + hi)
    return NoiseModel(math.exp(0.5 * fit(rho)[1]), -h / math.log(rho), h)


# ---------------------------------------------------------------------------- correlated least squares


def correlated_product(s_m, v, corr_m: float) -> np.ndarray:
    """P v with P_ij = exp(-|s_i - s_j| / L) (Eq. 3), s sorted, in O(n): a forward and a backward first-order
    recursion (each term's weight decays by exp(-ds / L) per step), the diagonal counted once."""
    v = np.asarray(v, dtype=float)
    if corr_m <= 0 or v.size < 2:
        return v.copy()
    decay = np.exp(-np.diff(np.asarray(s_m, dtype=float)) / corr_m).tolist()
    vals = v.tolist()
    fwd = [0.0] * len(vals)
    bwd = [0.0] * len(vals)
    acc = 0.0
    for i, val in enumerate(vals):
        acc = val + (decay[i - 1] * acc if i else 0.0)
        fwd[i] = acc
    acc = 0.0
    for i in range(len(vals) - 1, -1, -1):
        acc = vals[i] + (decay[i] * acc if i < len(vals) - 1 else 0.0)
        bwd[i] = acc
    return np.array(fwd) + np.array(bwd) - v


def variance_inflation(s_m, a, corr_m: float, normals=None) -> float:
    """a^T P a / a^T a for an estimate with influence ``a`` on the vertices' normal displacements [-] (module
    docstring: the sandwich's factor over the white variance sigma^2 |a|^2). ``normals`` (n x 2, unit) are the
    directions of those displacements (P_ij times n_i . n_j: each axis of the 2-D error correlates on its own);
    None for one direction (a line's vertices). 1 for white noise.

    Parameters
    ----------
    s_m : array_like
        Chainage of the vertices, sorted [m].
    a : array_like
        Influence of each vertex on the estimate.
    corr_m : float
        Correlation length L [m]; 0 for white noise.
    normals : array_like or None
        Unit normal of each vertex.
    """
    a = np.asarray(a, dtype=float)
    white = float(a @ a)
    if corr_m <= 0 or white <= 0:
        return 1.0
    if normals is None:
        return float(a @ correlated_product(s_m, a, corr_m)) / white
    nrm = np.asarray(normals, dtype=float)
    total = 0.0
    for axis in (0, 1):
        w = a * nrm[:, axis]
        total += float(w @ correlated_product(s_m, w, corr_m))
    return total / white


def absorbed_excess(s_m, jac, corr_m: float, normals=None) -> float:
    """tr(H P) - p for a least-squares fit with Jacobian ``jac`` (n x p) of the vertices' normal residuals, H its
    hat matrix: how many more noise degrees of freedom the fit absorbs when the noise is correlated (module
    docstring; the residual sum's expectation is sigma^2 (n - tr(H P))). 0 for white noise."""
    jac = np.asarray(jac, dtype=float)
    if corr_m <= 0:
        return 0.0
    try:
        inv = np.linalg.inv(jac.T @ jac)
    except np.linalg.LinAlgError:
        return 0.0
    p = jac.shape[1]
    pj = np.zeros_like(jac)
    for k in range(p):
        if normals is None:
            pj[:, k] = correlated_product(s_m, jac[:, k], corr_m)
        else:
            nrm = np.asarray(normals, dtype=float)
            for axis in (0, 1):
                pj[:, k] += nrm[:, axis] * correlated_product(s_m, jac[:, k] * nrm[:, axis], corr_m)
    return max(float(np.trace(inv @ (jac.T @ pj))) - p, 0.0)


# ------------------------------------------------------------------------- restricted likelihood of tangents


def _reml_terms(t: np.ndarray, y: np.ndarray, corr_m: float) -> tuple[float, float, float, int]:
    """(RSS, log|P|, log|X~^T X~|, n) of one tangent's offsets ``y`` at chainages ``t`` under Eq. 3 with a line
    (offset and slope) as the fixed effects: the innovations form of the Ornstein-Uhlenbeck sequence,
    z_0 = y_0, z_i = (y_i - phi_i y_{i-1}) / sqrt(1 - phi_i^2), phi_i = exp(-(t_i - t_{i-1}) / L), whitens it
    (P^-1/2; log|P| = sum log(1 - phi_i^2)), and the generalised least squares of the line is the ordinary one of
    the transformed columns."""
    tc = t - t.mean()
    x = np.column_stack((np.ones_like(tc), tc / max(float(np.ptp(tc)), 1e-9)))
    if corr_m > 0:
        phi = np.exp(-np.diff(t) / corr_m)
        scale = 1.0 / np.sqrt(np.maximum(1.0 - phi * phi, 1e-12))
        z = np.concatenate(([y[0]], (y[1:] - phi * y[:-1]) * scale))
        xt = np.vstack((x[:1], (x[1:] - phi[:, None] * x[:-1]) * scale[:, None]))
        logdet = float(np.sum(np.log(np.maximum(1.0 - phi * phi, 1e-12))))
    else:
        z, xt, logdet = y, x, 0.0
    gram = xt.T @ xt
    beta = np.linalg.solve(gram, xt.T @ z)
    rss = float(np.sum((z - xt @ beta) ** 2))
    return rss, logdet, float(np.linalg.slogdet(gram)[1]), int(y.size)


def _reml_deviance(stretches, corr_m: float, sigma_m: float | None) -> tuple[float, float]:
    """(-2 log restricted likelihood up to a constant, sigma^2 at its maximum) of the pooled tangents at ``corr_m``
    (sigma^2 profiled out unless given)."""
    rss = logdet = loggram = 0.0
    dof = 0
    for t, y in stretches:
        r, ld, lg, n = _reml_terms(t, y, corr_m)
        rss, logdet, loggram, dof = rss + r, logdet + ld, loggram + lg, dof + n - 2
    s2 = rss / dof if sigma_m is None else sigma_m * sigma_m
    return dof * math.log(s2) + rss / s2 + logdet + loggram, s2


def rejects(stretches, model: NoiseModel, significance: float = 4.0) -> bool:
    """Whether the tangents' offsets reject ``model`` (sigma and L both fixed) against their own restricted
    likelihood maximum (:func:`residual_noise`), by more than :data:`CORRELATION_SIGNIFICANCE` squared in deviance: a
    likelihood-ratio test of two parameters' worth at 3 standard deviations (conservative: the test of one
    parameter's threshold). Used to keep a first estimate that the tangents cannot contradict (too few of them)
    rather than fall back to white noise. Stretches as in :func:`residual_noise` (the same outlier rule)."""
    kept = _straight(stretches, significance)
    if not kept:
        return False
    longest = max(float(t[-1] - t[0]) for t, _ in kept)
    grid = np.geomspace(0.2 * model.spacing_m, max(longest, model.spacing_m), 40)
    best = min(_reml_deviance(kept, float(c), None)[0] for c in (0.0, *grid))  # the unrestricted maximum
    return _reml_deviance(kept, model.corr_m, model.sigma_m)[0] - best > CORRELATION_SIGNIFICANCE**2


def _straight(stretches, significance: float):
    """The stretches of at least 8 vertices whose residual variance about their own line is at most
    ``significance`` squared times the median stretch's (:func:`residual_noise`)."""
    stretches = [(np.asarray(t, dtype=float), np.asarray(y, dtype=float)) for t, y in stretches if len(t) >= 8]
    if not stretches:
        return []
    spread = np.array([_reml_terms(t, y, 0.0)[0] / (y.size - 2) for t, y in stretches])
    return [st for st, v in zip(stretches, spread, strict=True) if v <= significance**2 * float(np.median(spread))]


def residual_noise(
    stretches, spacing_m: float, sigma_m: float | None = None, significance: float = 4.0
) -> NoiseModel | None:
    """sigma and the correlation length L of Eq. 3 from the normal offsets of tangent vertices (restricted maximum
    likelihood, Patterson and Thompson 1971 [7]).

    ``stretches`` are (chainage, offset) of the vertices of straight stretches of the track (at least 8 each); a
    line (offset and slope) is each one's fixed effect, which the restricted likelihood accounts for (the line
    absorbs the low-frequency part of correlated noise, and a plain variance of the residuals would understate
    sigma). The likelihood is O(n) per evaluation (the innovations form, :func:`_reml_terms`), maximised over L
    on a logarithmic grid from a fifth of the spacing to the longest stretch, then by golden sections. White noise
    (L = 0) is kept unless L lowers the deviance by more than :data:`CORRELATION_SIGNIFICANCE` squared (a
    likelihood-ratio test of one parameter at 3 standard deviations). Unlike the differences of :func:`estimate_noise`,
    the tangents see the noise at every lag up to their length, where the geometry is known (a line): sigma and L are
    both identified once the tangents are a few L long. ``sigma_m`` fixes sigma (given by the user); None when no
    stretch was given.

    A stretch that is not straight (a curve the first pass missed, or a phantom's remnant) would carry its geometry
    into sigma and L: a stretch whose residual standard deviation (about its own line) exceeds ``significance``
    times the median stretch's is no tangent and is left out (with the method's 4 standard deviations, a sampling
    excursion of a true tangent's variance by a factor 16 is out of reach even for a few effective samples).

    References
    ----------
    [7] H. D. Patterson, R. Thompson (1971), Recovery of inter-block information when block sizes are unequal,
        Biometrika 58: restricted (residual) maximum likelihood.
    """
    stretches = _straight(stretches, significance)
    if not stretches:
        return None
    white, s2_white = _reml_deviance(stretches, 0.0, sigma_m)
    longest = max(float(t[-1] - t[0]) for t, _ in stretches)
    grid = np.geomspace(0.2 * spacing_m, max(longest, spacing_m), 40)
    dev = np.array([_reml_deviance(stretches, float(c), sigma_m)[0] for c in grid])
    i = int(np.argmin(dev))
    if not white - dev[i] > CORRELATION_SIGNIFICANCE**2:
        return NoiseModel(math.sqrt(s2_white), 0.0, spacing_m)
    lo, hi = math.log(grid[max(i - 1, 0)]), math.log(grid[min(i + 1, grid.size - 1)])
    for _ in range(25):
        a, b = lo + 0.382 * (hi - lo), lo + 0.618 * (hi - lo)
        if _reml_deviance(stretches, math.exp(a), sigma_m)[0] < _reml_deviance(stretches, math.exp(b), sigma_m)[0]:
            hi = b
        else:
            lo = a
    corr = math.exp(0.5 * (lo + hi))
    return NoiseModel(math.sqrt(_reml_deviance(stretches, corr, sigma_m)[1]), corr, spacing_m)
