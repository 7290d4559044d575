"""The noise model of a GPS track (engine.route.noise): sigma and the correlation length of Gauss-Markov noise from
the vertices, and the correlated least squares built on it (engine.route.detect, engine.route.fit).

Expected numbers come from the model, not from the code's output: the generating sigma and correlation length of
tests/synthetic_routes.gauss_markov, and tolerances of four standard errors of the estimate, the standard errors
from the AR(1) process's asymptotic theory (Box, Jenkins and Reinsel 2008, ch. 7: for n observations with lag-one
correlation rho, sd(rho_hat) = sqrt((1 - rho^2) / n) and sd(sigma_hat^2) / sigma^2 = sqrt(2 (1 + rho^2) /
(n (1 - rho^2)))), or, for the differences' variogram whose sampling theory is not closed, from the estimates' own
scatter over repeated draws (four standard errors of their mean). The exact sums of the sandwich are checked against
dense matrices and the closed form of the variance of an AR(1) mean.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import binom

from engine.route import find_curves
from engine.route.noise import (
    NoiseModel,
    correlated_product,
    estimate_noise,
    rejects,
    residual_noise,
    variance_inflation,
    vertex_noise_m,
)
from tests.engine.test_geometry import detect
from tests.synthetic_routes import Arc, Tangent, gauss_markov, layout

SPACING = 10.0


def ar1_errors(n_obs: int, rho: float) -> tuple[float, float]:
    """(sd of rho_hat, relative sd of sigma_hat) of n observations of a stationary AR(1) (module docstring)."""
    sd_rho = math.sqrt((1.0 - rho * rho) / n_obs)
    sd_var = math.sqrt(2.0 * (1.0 + rho * rho) / (n_obs * (1.0 - rho * rho)))
    return sd_rho, 0.5 * sd_var  # sigma = sqrt(variance): half the relative error


def stretches(rng, count: int, n: int, sigma: float, corr_m: float):
    """``count`` straight stretches of ``n`` vertices with lateral Gauss-Markov noise (white when corr_m is 0)."""
    t = np.arange(n) * SPACING
    out = []
    for _ in range(count):
        e = gauss_markov(rng, n, sigma, math.exp(-SPACING / corr_m)) if corr_m else rng.normal(0.0, sigma, n)
        out.append((t, e + 0.01 * t + 3.0))  # any line: the fixed effects absorb it
    return out


@pytest.mark.parametrize("corr_m", [20.0, 50.0, 100.0])
def test_tangent_residuals_recover_sigma_and_correlation_length(corr_m):
    rng = np.random.default_rng(11)
    sigma, count, n = 3.0, 20, 100
    model = residual_noise(stretches(rng, count, n, sigma, corr_m), SPACING)
    rho = math.exp(-SPACING / corr_m)
    sd_rho, rel_sigma = ar1_errors(count * (n - 2), rho)
    rho_hat = math.exp(-SPACING / model.corr_m)
    assert abs(rho_hat - rho) <= 4.0 * sd_rho
    assert abs(model.sigma_m / sigma - 1.0) <= 4.0 * rel_sigma


def test_a_stretch_that_is_not_straight_is_left_out():
    # a curve the first pass missed (an R 2000 m arc over 1 km: offsets up to 62 m) among 20 tangents: the estimate
    # is that of the tangents alone (the same tolerance as above)
    rng = np.random.default_rng(17)
    sigma, corr_m, count, n = 3.0, 50.0, 20, 100
    clean = stretches(rng, count, n, sigma, corr_m)
    t = np.arange(n) * SPACING
    arc = (t - t.mean()) ** 2 / (2.0 * 2000.0)
    bent = (t, arc + gauss_markov(rng, n, sigma, math.exp(-SPACING / corr_m)))
    model = residual_noise([*clean, bent], SPACING)
    sd_rho, rel_sigma = ar1_errors(count * (n - 2), math.exp(-SPACING / corr_m))
    assert abs(math.exp(-SPACING / model.corr_m) - math.exp(-SPACING / corr_m)) <= 4.0 * sd_rho
    assert abs(model.sigma_m / sigma - 1.0) <= 4.0 * rel_sigma


def test_the_tangents_reject_a_first_estimate_only_when_they_can():
    # 20 white tangents of 100 vertices reject 50 m of correlation; one tangent of 19 vertices (what a first pass
    # with a large sigma leaves of a 1 km track) cannot, and the first estimate is kept
    rng = np.random.default_rng(18)
    first = NoiseModel(3.0, 50.0, SPACING)
    assert rejects(stretches(rng, 20, 100, 3.0, 0.0), first)
    assert not rejects(stretches(rng, 1, 19, 3.0, 50.0), first)
    assert not rejects(stretches(rng, 20, 100, 3.0, 50.0), first)  # the truth is not rejected (at 3 sd)


def test_white_tangents_stay_white():
    rng = np.random.default_rng(12)
    sigma, count, n = 2.0, 20, 100
    model = residual_noise(stretches(rng, count, n, sigma, 0.0), SPACING)
    assert model.corr_m == 0.0  # the likelihood-ratio test does not accept a correlation (3 sd)
    assert abs(model.sigma_m / sigma - 1.0) <= 4.0 * ar1_errors(count * (n - 2), 0.0)[1]


def test_a_given_sigma_is_kept():
    rng = np.random.default_rng(13)
    model = residual_noise(stretches(rng, 20, 100, 3.0, 50.0), SPACING, sigma_m=3.0)
    assert model.sigma_m == 3.0 and model.corr_m > 0


def straight(rng, n: int, sigma: float, corr_m: float):
    """A straight track of n vertices every SPACING with 2-D noise (each axis its own Gauss-Markov sequence)."""
    x = np.arange(n) * SPACING
    if corr_m:
        rho = math.exp(-SPACING / corr_m)
        return x + gauss_markov(rng, n, sigma, rho), gauss_markov(rng, n, sigma, rho)
    return x + rng.normal(0.0, sigma, n), rng.normal(0.0, sigma, n)


def test_the_variogram_of_differences_recovers_correlated_noise():
    # the pass before the tangents are known: its mean over 10 draws within 4 standard errors (their own scatter)
    rng = np.random.default_rng(14)
    sigma, corr_m = 3.0, 20.0
    est = np.array(
        [(m.sigma_m, m.corr_m) for m in (estimate_noise(*straight(rng, 1000, sigma, corr_m)) for _ in range(10))]
    )
    se = est.std(axis=0, ddof=1) / math.sqrt(est.shape[0])
    assert np.all(est[:, 1] > 0)
    assert abs(est[:, 0].mean() - sigma) <= 4.0 * se[0]
    assert abs(est[:, 1].mean() - corr_m) <= 4.0 * se[1]


def test_white_noise_gives_the_white_sigma():
    rng = np.random.default_rng(15)
    x, y = straight(rng, 1000, 3.0, 0.0)
    model = estimate_noise(x, y)
    assert model.corr_m == 0.0
    assert model.sigma_m == vertex_noise_m(x, y)  # the lag-one estimate the method always used
    assert NoiseModel(3.0).rho == 0.0 and NoiseModel(3.0, 50.0, 10.0).rho == pytest.approx(math.exp(-0.2))


def test_the_correlated_sums_are_exact():
    rng = np.random.default_rng(16)
    s = np.sort(rng.uniform(0.0, 500.0, 60))
    v = rng.normal(size=60)
    dense = np.exp(-np.abs(s[:, None] - s[None, :]) / 35.0)
    assert correlated_product(s, v, 35.0) == pytest.approx(dense @ v, rel=1e-12, abs=1e-12)
    assert variance_inflation(s, v, 0.0) == 1.0
    # the mean of n AR(1) values: Var = sigma^2 / n [(1 + rho) / (1 - rho) - 2 rho (1 - rho^n) / (n (1 - rho)^2)]
    n, rho = 40, math.exp(-SPACING / 50.0)
    closed = (1 + rho) / (1 - rho) - 2 * rho * (1 - rho**n) / (n * (1 - rho) ** 2)
    t = np.arange(n) * SPACING
    assert variance_inflation(t, np.full(n, 1.0 / n), 50.0) == pytest.approx(closed, rel=1e-12)
    # with normals: two axes, each correlated on its own; perpendicular normals do not correlate
    normals = np.column_stack((np.ones(n), np.zeros(n)))
    assert variance_inflation(t, np.full(n, 1.0 / n), 50.0, normals) == pytest.approx(closed, rel=1e-12)
    alternate = np.where(np.arange(n)[:, None] % 2 == 0, [[1.0, 0.0]], [[0.0, 1.0]])
    half = variance_inflation(t[::2], np.full(n // 2, 1.0 / n), 50.0) + variance_inflation(
        t[1::2], np.full(n // 2, 1.0 / n), 50.0
    )
    assert variance_inflation(t, np.full(n, 1.0 / n), 50.0, alternate) == pytest.approx(half / 2.0, rel=1e-12)


def curvy(elements_after: int = 6):
    """A 7 km route: long tangents and a few curves, the tangents most of it."""
    route = [Tangent(1200.0)]
    for k in range(elements_after):
        route += [Arc(300.0 + 100.0 * k, 250.0, "left" if k % 2 else "right"), Tangent(900.0)]
    return route


def test_find_curves_reports_the_track_s_noise_and_correlation():
    sigma, corr_m = 3.0, 50.0
    found, _ = detect(curvy(), SPACING, 45.0, noise=sigma, seed=21, corr_m=corr_m)
    assert found.noise_corr_m > 0
    # the tangents' vertices (at least half the route's ~700) carry the estimate: four of their standard errors
    sd_rho, rel_sigma = ar1_errors(350, math.exp(-SPACING / corr_m))
    assert abs(math.exp(-SPACING / found.noise_corr_m) - math.exp(-SPACING / corr_m)) <= 4.0 * sd_rho
    assert abs(found.noise_m / sigma - 1.0) <= 4.0 * rel_sigma


def test_white_track_is_white_and_a_given_noise_is_sigma():
    found, _ = detect(curvy(), SPACING, 45.0, noise=3.0, seed=22)
    assert found.noise_corr_m == 0.0
    given, _ = detect(curvy(), SPACING, 45.0, noise=3.0, seed=21, corr_m=50.0, noise_m=3.0)
    assert given.noise_m == 3.0 and given.noise_corr_m > 0


def test_surveyed_centreline_stays_exact():
    x, y, _ = layout([Tangent(400.0), Arc(200.0, 300.0, "left"), Tangent(400.0)], SPACING)
    found = find_curves(x, y)
    assert found.noise_m < 0.01 and found.noise_corr_m == 0.0
    c = found.curves[0]
    assert c.radius_std_m is None and c.radius_lower_m == c.radius_m


#: tracks per coverage case, and the chance the test fails if the bound covered exactly 95 %
N_TRACKS, FALSE_ALARM = 40, 1e-3


@pytest.mark.slow
@pytest.mark.parametrize(("radius", "deflection"), [(200.0, 90.0), (800.0, 90.0)])
def test_the_bound_covers_on_correlated_tracks(radius, deflection):
    # 3 m of noise correlated over 50 m: radius_lower_m at most the true radius on at least the binomial bound of a
    # 95 % rate over N_TRACKS tracks (seeds apart from the bench's)
    route = [Tangent(400.0), Arc(radius, radius * math.radians(deflection), "left"), Tangent(400.0)]
    covered = 0
    for k in range(N_TRACKS):
        found, _ = detect(route, SPACING, 45.0, noise=3.0, seed=900 + k, corr_m=50.0)
        c = max(found.curves, key=lambda c: c.deflection_deg)
        covered += c.radius_lower_m <= radius
    assert covered >= int(binom.ppf(FALSE_ALARM, N_TRACKS, 0.95))
